//! Flattening: a subtree, or the whole scene, joined into one mesh by Franklin's four steps.

use super::{ObjectId, ObjectProblem, Result, Scene, SceneError};
use crate::mesh::Mesh;

impl Scene {
    /// Flattens the subtree `id` into one mesh with faces and vertices but no subobjects, by
    /// Franklin's four steps: (1) flatten any subobject that has subobjects (the depth-first
    /// walk reaches every mesh), (2) number the vertices uniquely throughout, (3) append the
    /// vertex lists and combine the face sets, (4) sort the vertices to find duplicates,
    /// combine and renumber them, updating the faces (vertices merged on exactly equal
    /// coordinates, by [`Mesh::from_polygons`]).
    ///
    /// ```
    /// use kepler::scene::{Scene, Transform};
    /// let mut s = Scene::new();
    /// let g = s.add_group(None, "pair").unwrap();
    /// let a = s.add_mesh(Some(g), "a", kepler::solids::cube(1.0).unwrap()).unwrap();
    /// let t = Transform { translate: [1.0, 0.0, 0.0], ..Transform::default() };
    /// s.instantiate(a, Some(g), "b", &t).unwrap();
    /// let flat = s.flatten(g).unwrap();
    /// // The two cubes share 4 vertices: 16 - 4 = 12.
    /// assert_eq!((flat.faces().len(), flat.vertices().len()), (12, 12));
    /// ```
    pub fn flatten(&self, id: ObjectId) -> Result<Mesh> {
        Mesh::concatenate(self.meshes(id)).map_err(|e| SceneError::Object {
            object: self.path(id),
            problem: ObjectProblem::Flatten(e),
        })
    }

    /// Flattens every object of the scene into one mesh, as [`flatten`](Self::flatten) does
    /// one subtree.
    ///
    /// ```
    /// use kepler::scene::{Scene, Transform};
    /// let mut s = Scene::new();
    /// let a = s.add_mesh(None, "a", kepler::solids::cube(1.0).unwrap()).unwrap();
    /// let t = Transform { translate: [3.0, 0.0, 0.0], ..Transform::default() };
    /// s.instantiate(a, None, "b", &t).unwrap();
    /// let flat = s.flatten_all().unwrap();
    /// assert_eq!((flat.faces().len(), flat.vertices().len()), (12, 16));
    /// ```
    pub fn flatten_all(&self) -> Result<Mesh> {
        let meshes = self.roots().iter().flat_map(|&r| self.meshes(r));
        Mesh::concatenate(meshes).map_err(|e| SceneError::Object {
            object: "(all objects)".to_string(),
            problem: ObjectProblem::Flatten(e),
        })
    }
}
