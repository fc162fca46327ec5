//! The sizes of an object's subtree: its faces and vertices, whether it bounds a solid, its
//! volume and surface area.

use super::{ObjectId, Scene};

impl Scene {
    /// Number of faces in the subtree.
    ///
    /// ```
    /// let mut s = kepler::scene::Scene::new();
    /// let c = s.add_mesh(None, "c", kepler::solids::cube(1.0).unwrap()).unwrap();
    /// assert_eq!(s.face_count(c), 6);
    /// ```
    pub fn face_count(&self, id: ObjectId) -> usize {
        self.meshes(id).iter().map(|m| m.faces().len()).sum()
    }

    /// Number of vertices in the subtree (a vertex shared by two subobjects counts twice,
    /// as the paper allows).
    ///
    /// ```
    /// let mut s = kepler::scene::Scene::new();
    /// let c = s.add_mesh(None, "c", kepler::solids::cube(1.0).unwrap()).unwrap();
    /// assert_eq!(s.vertex_count(c), 8);
    /// ```
    pub fn vertex_count(&self, id: ObjectId) -> usize {
        self.meshes(id).iter().map(|m| m.vertices().len()).sum()
    }

    /// Whether every mesh of the subtree bounds a solid (closed, consistently oriented).
    ///
    /// ```
    /// let mut s = kepler::scene::Scene::new();
    /// let c = s.add_mesh(None, "c", kepler::solids::cube(1.0).unwrap()).unwrap();
    /// assert!(s.is_solid(c));
    /// ```
    pub fn is_solid(&self, id: ObjectId) -> bool {
        let leaves = self.meshes(id);
        !leaves.is_empty() && leaves.iter().all(|m| m.is_solid())
    }

    /// The enclosed volume, summed over the meshes of the subtree (subobjects may abut but
    /// not overlap), or `None` unless every mesh bounds a solid. An inside-out mesh counts
    /// with its absolute volume.
    ///
    /// ```
    /// let mut s = kepler::scene::Scene::new();
    /// let c = s.add_mesh(None, "c", kepler::solids::cube(2.0).unwrap()).unwrap();
    /// assert_eq!(s.volume(c), Some(8.0));
    /// ```
    pub fn volume(&self, id: ObjectId) -> Option<f64> {
        self.is_solid(id)
            .then(|| self.meshes(id).iter().map(|m| m.volume().abs()).sum())
    }

    /// The total face area of the subtree.
    ///
    /// ```
    /// let mut s = kepler::scene::Scene::new();
    /// let c = s.add_mesh(None, "c", kepler::solids::cube(2.0).unwrap()).unwrap();
    /// assert_eq!(s.surface_area(c), 24.0);
    /// ```
    pub fn surface_area(&self, id: ObjectId) -> f64 {
        self.meshes(id).iter().map(|m| m.surface_area()).sum()
    }
}
