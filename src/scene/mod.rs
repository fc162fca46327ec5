//! Franklin's hierarchical scene graph (1981, "Definitions and data structure").
//!
//! Objects live in a [`slotmap`] arena and are addressed by [`ObjectId`]. Each object holds
//! either subobjects or a mesh (vertices and faces), never both ([`Content`]), and caches its
//! three bounds (CBOX, INBOX, TRIBOX), computed only when first asked for. Instancing places
//! a copy of a mesh or subtree under a [`Transform`]; the copy's vertices are transformed
//! once, so every later computation starts from world coordinates. [`Scene::flatten`] turns a
//! subtree into one mesh by the paper's four steps.
//!
//! ```
//! use kepler::scene::{Scene, Transform};
//! let mut scene = Scene::new();
//! let block = scene.add_group(None, "block").unwrap();
//! let a = scene.add_mesh(Some(block), "a", kepler::solids::cube(1.0).unwrap()).unwrap();
//! let moved = Transform { translate: [3.0, 0.0, 0.0], ..Transform::default() };
//! scene.instantiate(a, Some(block), "b", &moved).unwrap();
//! assert_eq!(scene.cbox(block).max, [3.5, 0.5, 0.5]);
//! assert_eq!(scene.face_count(block), 12);
//! assert_eq!(scene.flatten(block).unwrap().vertices().len(), 16);
//! ```

mod bounds;
mod camera;
mod error;
pub mod file;
mod flatten;
pub mod index;
mod measures;
mod object;
pub mod report;
mod scale;
mod transform;

pub use camera::{Camera, Projection};
pub use error::{ObjectProblem, Result, SceneError};
pub use object::{Content, Object, ObjectId};
pub use transform::Transform;

use crate::mesh::Mesh;
use slotmap::SlotMap;
use std::sync::{Arc, OnceLock};

/// A scene: an arena of objects, its top-level objects, and an optional camera.
///
/// ```
/// let mut s = kepler::scene::Scene::new();
/// s.add_mesh(None, "cube", kepler::solids::cube(1.0).unwrap()).unwrap();
/// assert_eq!(s.roots().len(), 1);
/// ```
#[derive(Debug, Default)]
pub struct Scene {
    objects: SlotMap<ObjectId, Object>,
    roots: Vec<ObjectId>,
    camera: Option<Camera>,
}

impl std::ops::Index<ObjectId> for Scene {
    type Output = Object;
    fn index(&self, id: ObjectId) -> &Object {
        &self.objects[id]
    }
}

impl Scene {
    /// An empty scene.
    ///
    /// ```
    /// assert!(kepler::scene::Scene::new().roots().is_empty());
    /// ```
    pub fn new() -> Scene {
        Scene::default()
    }

    fn insert(
        &mut self,
        parent: Option<ObjectId>,
        name: String,
        content: Content,
    ) -> Result<ObjectId> {
        if let Some(p) = parent {
            let Some(po) = self.objects.get(p) else {
                return Err(SceneError::Object {
                    object: name,
                    problem: ObjectProblem::ParentMissing,
                });
            };
            if let Content::Mesh(_) = po.content {
                return Err(SceneError::Object {
                    object: po.name.clone(),
                    problem: ObjectProblem::HasFaces,
                });
            }
        }
        let id = self.objects.insert(Object::new(name, parent, content));
        match parent {
            Some(p) => {
                if let Content::Subobjects(v) = &mut self.objects[p].content {
                    v.push(id);
                }
                self.invalidate(p);
            }
            None => self.roots.push(id),
        }
        Ok(id)
    }

    /// Forgets the cached bounds of `id` and its ancestors after a change below them.
    fn invalidate(&mut self, mut id: ObjectId) {
        loop {
            let o = &mut self.objects[id];
            o.cbox = OnceLock::new();
            o.inbox = OnceLock::new();
            o.tribox = OnceLock::new();
            o.exponents = OnceLock::new();
            match o.parent {
                Some(p) => id = p,
                None => break,
            }
        }
    }

    /// Adds an object with subobjects (initially none) under `parent`, or at the top level.
    ///
    /// ```
    /// let mut s = kepler::scene::Scene::new();
    /// let c = s.add_mesh(None, "c", kepler::solids::cube(1.0).unwrap()).unwrap();
    /// // A mesh object cannot take subobjects.
    /// assert!(s.add_group(Some(c), "x").is_err());
    /// ```
    pub fn add_group(
        &mut self,
        parent: Option<ObjectId>,
        name: impl Into<String>,
    ) -> Result<ObjectId> {
        self.insert(parent, name.into(), Content::Subobjects(Vec::new()))
    }

    /// Adds an object with a mesh under `parent`, or at the top level.
    ///
    /// ```
    /// let mut s = kepler::scene::Scene::new();
    /// let g = s.add_group(None, "g").unwrap();
    /// let c = s.add_mesh(Some(g), "c", kepler::solids::cube(1.0).unwrap()).unwrap();
    /// assert_eq!(s[g].subobjects(), &[c]);
    /// ```
    pub fn add_mesh(
        &mut self,
        parent: Option<ObjectId>,
        name: impl Into<String>,
        mesh: Mesh,
    ) -> Result<ObjectId> {
        self.insert(parent, name.into(), Content::Mesh(Arc::new(mesh)))
    }

    /// Places a copy of the subtree `source` under `parent` with `transform` applied to every
    /// vertex (faces reversed under a mirroring transform). Returns the new subtree's root.
    ///
    /// ```
    /// use kepler::scene::{Scene, Transform};
    /// let mut s = Scene::new();
    /// let a = s.add_mesh(None, "a", kepler::solids::cube(1.0).unwrap()).unwrap();
    /// let t = Transform { scale: [2.0, 2.0, 2.0], ..Transform::default() };
    /// let b = s.instantiate(a, None, "b", &t).unwrap();
    /// assert_eq!(s.volume(b), Some(8.0));
    /// ```
    pub fn instantiate(
        &mut self,
        source: ObjectId,
        parent: Option<ObjectId>,
        name: impl Into<String>,
        transform: &Transform,
    ) -> Result<ObjectId> {
        self.instantiate_matrix(source, parent, name.into(), &transform.matrix())
    }

    /// [`instantiate`](Scene::instantiate) with an affine 4×4 matrix instead of a
    /// [`Transform`].
    ///
    /// ```
    /// use kepler::scene::Scene;
    /// let mut s = Scene::new();
    /// let a = s.add_mesh(None, "a", kepler::solids::cube(1.0).unwrap()).unwrap();
    /// let m = nalgebra::Matrix4::new_scaling(3.0);
    /// let b = s.instantiate_matrix(a, None, "b".into(), &m).unwrap();
    /// assert_eq!(s.cbox(b).max, [1.5; 3]);
    /// ```
    pub fn instantiate_matrix(
        &mut self,
        source: ObjectId,
        parent: Option<ObjectId>,
        name: String,
        m: &nalgebra::Matrix4<f64>,
    ) -> Result<ObjectId> {
        let det = m.fixed_view::<3, 3>(0, 0).determinant();
        if m.iter().any(|x| !x.is_finite()) || !det.is_finite() || det == 0.0 {
            return Err(SceneError::Object {
                object: name,
                problem: ObjectProblem::SingularTransform,
            });
        }
        let mut root = None;
        let copied = self.copy_subtree(source, parent, name, m, &mut root);
        if copied.is_err() {
            // Leave the scene as it was: remove whatever part of the copy was inserted.
            if let Some(r) = root {
                self.remove_subtree(r);
            }
        }
        copied
    }

    /// Copies the subtree `source` under `parent`, transformed by `m`; `root` receives the
    /// copy's root as soon as it is inserted.
    fn copy_subtree(
        &mut self,
        source: ObjectId,
        parent: Option<ObjectId>,
        name: String,
        m: &nalgebra::Matrix4<f64>,
        root: &mut Option<ObjectId>,
    ) -> Result<ObjectId> {
        let Some(src) = self.objects.get(source) else {
            return Err(SceneError::Object {
                object: name,
                problem: ObjectProblem::SourceMissing,
            });
        };
        let source_name = src.name.clone();
        let content = match &src.content {
            Content::Mesh(mesh) => Content::Mesh(Arc::new(mesh.transformed(m).map_err(|e| {
                SceneError::Object {
                    object: name.clone(),
                    problem: ObjectProblem::Mesh(e),
                }
            })?)),
            Content::Subobjects(_) => Content::Subobjects(Vec::new()),
        };
        let children = src.subobjects().to_vec();
        let id = self.insert(parent, name, content)?;
        root.get_or_insert(id);
        self.objects[id].instance_of = Some(source_name);
        for c in children {
            let child_name = self.objects[c].name.clone();
            self.copy_subtree(c, Some(id), child_name, m, root)?;
        }
        Ok(id)
    }

    /// Removes `id` and everything below it.
    fn remove_subtree(&mut self, id: ObjectId) {
        match self.objects[id].parent {
            Some(p) => {
                if let Content::Subobjects(v) = &mut self.objects[p].content {
                    v.retain(|&c| c != id);
                }
                self.invalidate(p);
            }
            None => self.roots.retain(|&r| r != id),
        }
        let mut stack = vec![id];
        while let Some(i) = stack.pop() {
            if let Some(o) = self.objects.remove(i) {
                stack.extend(o.subobjects());
            }
        }
    }

    /// The top-level objects.
    ///
    /// ```
    /// let mut s = kepler::scene::Scene::new();
    /// let g = s.add_group(None, "g").unwrap();
    /// s.add_group(Some(g), "h").unwrap();
    /// assert_eq!(s.roots(), &[g]);
    /// ```
    pub fn roots(&self) -> &[ObjectId] {
        &self.roots
    }

    /// The object with this key, if it is in the scene.
    ///
    /// ```
    /// let mut s = kepler::scene::Scene::new();
    /// let g = s.add_group(None, "g").unwrap();
    /// assert_eq!(s.get(g).map(|o| o.name()), Some("g"));
    /// ```
    pub fn get(&self, id: ObjectId) -> Option<&Object> {
        self.objects.get(id)
    }

    /// The scene's camera, if the scene gave one.
    ///
    /// ```
    /// assert!(kepler::scene::Scene::new().camera().is_none());
    /// ```
    pub fn camera(&self) -> Option<&Camera> {
        self.camera.as_ref()
    }

    /// Sets the scene's camera.
    ///
    /// ```
    /// let mut s = kepler::scene::Scene::new();
    /// s.set_camera(kepler::scene::Camera::default());
    /// assert!(s.camera().is_some());
    /// ```
    pub fn set_camera(&mut self, camera: Camera) {
        self.camera = Some(camera);
    }

    /// Every object of the scene in depth-first order, with its depth (0 for top level).
    ///
    /// ```
    /// let mut s = kepler::scene::Scene::new();
    /// let g = s.add_group(None, "g").unwrap();
    /// let h = s.add_group(Some(g), "h").unwrap();
    /// assert_eq!(s.walk(), vec![(g, 0), (h, 1)]);
    /// ```
    pub fn walk(&self) -> Vec<(ObjectId, usize)> {
        self.depth_first(&self.roots)
    }

    /// The objects of the subtree of `id` in depth-first order, `id` first.
    ///
    /// ```
    /// let mut s = kepler::scene::Scene::new();
    /// let g = s.add_group(None, "g").unwrap();
    /// let h = s.add_group(Some(g), "h").unwrap();
    /// s.add_group(None, "other").unwrap();
    /// assert_eq!(s.subtree(g), vec![g, h]);
    /// ```
    pub fn subtree(&self, id: ObjectId) -> Vec<ObjectId> {
        self.depth_first(&[id])
            .into_iter()
            .map(|(o, _)| o)
            .collect()
    }

    /// The subtrees of `starts`, in order, depth-first, with depths counted from them.
    fn depth_first(&self, starts: &[ObjectId]) -> Vec<(ObjectId, usize)> {
        let mut out = Vec::new();
        let mut stack: Vec<(ObjectId, usize)> = starts.iter().rev().map(|&r| (r, 0)).collect();
        while let Some((id, depth)) = stack.pop() {
            out.push((id, depth));
            stack.extend(
                self.objects[id]
                    .subobjects()
                    .iter()
                    .rev()
                    .map(|&c| (c, depth + 1)),
            );
        }
        out
    }

    /// The meshes of the subtree `id`, depth-first.
    ///
    /// ```
    /// let mut s = kepler::scene::Scene::new();
    /// let g = s.add_group(None, "g").unwrap();
    /// s.add_mesh(Some(g), "c", kepler::solids::cube(1.0).unwrap()).unwrap();
    /// assert_eq!(s.meshes(g).len(), 1);
    /// ```
    pub fn meshes(&self, id: ObjectId) -> Vec<&Mesh> {
        self.subtree(id)
            .into_iter()
            .filter_map(|o| self.objects[o].mesh())
            .collect()
    }

    /// The mesh objects of the subtrees of `objects`, depth-first, with their meshes.
    ///
    /// ```
    /// let mut s = kepler::scene::Scene::new();
    /// let g = s.add_group(None, "g").unwrap();
    /// let c = s.add_mesh(Some(g), "c", kepler::solids::cube(1.0).unwrap()).unwrap();
    /// let found: Vec<_> = s.mesh_objects(&[g]).into_iter().map(|(id, _)| id).collect();
    /// assert_eq!(found, vec![c]);
    /// ```
    pub fn mesh_objects(&self, objects: &[ObjectId]) -> Vec<(ObjectId, &Mesh)> {
        objects
            .iter()
            .flat_map(|&id| self.subtree(id))
            .filter_map(|id| self.objects[id].mesh().map(|m| (id, m)))
            .collect()
    }

    /// The path of names from the top level down to `id`, joined by `/`.
    ///
    /// ```
    /// let mut s = kepler::scene::Scene::new();
    /// let g = s.add_group(None, "city").unwrap();
    /// let h = s.add_group(Some(g), "tower").unwrap();
    /// assert_eq!(s.path(h), "city/tower");
    /// ```
    pub fn path(&self, id: ObjectId) -> String {
        let mut names = vec![self.objects[id].name.as_str()];
        let mut cur = self.objects[id].parent;
        while let Some(p) = cur {
            names.push(&self.objects[p].name);
            cur = self.objects[p].parent;
        }
        names.reverse();
        names.join("/")
    }

    /// The first object (depth-first) whose [`path`](Scene::path) or name is `name`.
    ///
    /// ```
    /// let mut s = kepler::scene::Scene::new();
    /// let g = s.add_group(None, "city").unwrap();
    /// let h = s.add_group(Some(g), "tower").unwrap();
    /// assert_eq!(s.find("tower"), Some(h));
    /// assert_eq!(s.find("city/tower"), Some(h));
    /// ```
    pub fn find(&self, name: &str) -> Option<ObjectId> {
        let all = self.walk();
        all.iter()
            .find(|(id, _)| self.path(*id) == name)
            .or_else(|| all.iter().find(|(id, _)| self.objects[*id].name == name))
            .map(|(id, _)| *id)
    }
}
