//! Exact scaling by a power of two: the exponents of a scene's coordinates, and the scene, or
//! some of its subtrees, scaled into the range where the engine's arithmetic is exact.

use super::{Content, ObjectId, ObjectProblem, Result, Scene, SceneError};
use crate::geometry::kernel::Exponents;
use std::sync::{Arc, OnceLock};

impl Scene {
    /// The binary exponents of the nonzero coordinates of every mesh's vertices.
    ///
    /// ```
    /// let mut s = kepler::scene::Scene::new();
    /// s.add_mesh(None, "c", kepler::solids::cube(2.0).unwrap()).unwrap();
    /// assert_eq!((s.exponents().min, s.exponents().max), (0, 0)); // coordinates ±1
    /// ```
    pub fn exponents(&self) -> Exponents {
        self.objects
            .values()
            .filter_map(|o| {
                let mesh = o.mesh()?;
                Some(*o.exponents.get_or_init(|| {
                    mesh.vertices().iter().fold(Exponents::NONE, |e, p| {
                        e.union(Exponents::of(p.coords.as_slice()))
                    })
                }))
            })
            .fold(Exponents::NONE, Exponents::union)
    }

    /// The scene scaled by `2^exponent`, exactly (the same objects, with the same ids and
    /// names; the camera is left as it is): how the engine brings a scene of extreme
    /// coordinates into the range where its arithmetic is exact (see
    /// [`Exponents::shift`]). An error if a mesh, scaled, is not valid (coordinates that
    /// overflow).
    ///
    /// ```
    /// let mut s = kepler::scene::Scene::new();
    /// let c = s.add_mesh(None, "c", kepler::solids::cube(2.0).unwrap()).unwrap();
    /// let big = s.scaled(500).unwrap();
    /// assert_eq!(big.cbox(c).max, [2f64.powi(500); 3]);
    /// ```
    pub fn scaled(&self, exponent: i32) -> Result<Scene> {
        self.scaled_where(exponent, |_| true)
    }

    /// The scene with the meshes of the subtrees of `roots` scaled by `2^exponent` (the others
    /// as they are): how the bounds report measures each object at its own scale.
    pub(crate) fn scaled_subtrees(&self, exponent: i32, roots: &[ObjectId]) -> Result<Scene> {
        let inside: std::collections::HashSet<ObjectId> = self
            .depth_first(roots)
            .into_iter()
            .map(|(o, _)| o)
            .collect();
        self.scaled_where(exponent, |id| inside.contains(&id))
    }

    /// The scene with the meshes of the objects `chosen` scaled by `2^exponent`, exactly.
    fn scaled_where(&self, exponent: i32, chosen: impl Fn(ObjectId) -> bool) -> Result<Scene> {
        // In two steps: 2^exponent itself may not be a double.
        let half = exponent / 2;
        let steps = [half, exponent - half].map(|k| nalgebra::Matrix4::new_scaling(2f64.powi(k)));
        let mut objects = self.objects.clone();
        for (id, o) in objects.iter_mut() {
            if let Content::Mesh(mesh) = &o.content
                && chosen(id)
            {
                let scaled = match mesh.scaled_exactly(exponent) {
                    Some(m) => Ok(m),
                    None => mesh
                        .transformed(&steps[0])
                        .and_then(|m| m.transformed(&steps[1])),
                }
                .map_err(|e| SceneError::Object {
                    object: o.name.clone(),
                    problem: ObjectProblem::Mesh(e),
                })?;
                o.content = Content::Mesh(Arc::new(scaled));
            }
            o.cbox = OnceLock::new();
            o.inbox = OnceLock::new();
            o.tribox = OnceLock::new();
            o.exponents = OnceLock::new();
        }
        Ok(Scene {
            objects,
            roots: self.roots.clone(),
            camera: self.camera,
        })
    }
}
