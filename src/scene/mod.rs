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

mod camera;
pub mod file;
pub mod report;
mod transform;

pub use camera::{Camera, Projection};
pub use transform::Transform;

use crate::bounds::tribox::TriboxBounds;
use crate::bounds::{Aabb, Inbox, InboxMethod, inbox};
use crate::geometry::kernel::Exponents;
use crate::io::FileError;
use crate::mesh::{Mesh, MeshError};
use crate::solids::SolidError;
use slotmap::SlotMap;
use std::sync::{Arc, OnceLock};

/// What went wrong building or reading a scene: the scene layer's error.
///
/// ```
/// use kepler::scene::{ObjectProblem, Scene, SceneError};
/// let mut scene = Scene::new();
/// let cube = scene.add_mesh(None, "cube", kepler::solids::cube(1.0).unwrap()).unwrap();
/// let e = scene.add_group(Some(cube), "inner").unwrap_err();
/// assert!(matches!(e, SceneError::Object { problem: ObjectProblem::HasFaces, .. }));
/// assert_eq!(e.to_string(), "object 'cube': it has faces, so it cannot also have subobjects");
/// ```
#[derive(Debug, thiserror::Error)]
pub enum SceneError {
    /// The scene file, or a mesh file, could not be read or holds bad input.
    #[error(transparent)]
    File(#[from] FileError),
    /// An error caused at a line of a scene file: by a mesh file or a solid it names, or by an
    /// object it places.
    #[error("{path}:{line}: {source}")]
    AtLine {
        /// The scene file.
        path: String,
        /// The 1-based line.
        line: usize,
        /// What went wrong there.
        #[source]
        source: Box<SceneError>,
    },
    /// A built-in solid with bad parameters.
    #[error(transparent)]
    Solid(#[from] SolidError),
    /// A problem with a named object.
    #[error("object '{object}': {problem}")]
    Object {
        /// The object's name (or path).
        object: String,
        /// What is wrong with it.
        problem: ObjectProblem,
    },
}

/// What is wrong with an object of a scene (see [`SceneError::Object`]).
///
/// ```
/// assert_eq!(
///     kepler::scene::ObjectProblem::SingularTransform.to_string(),
///     "the transform is singular or not finite"
/// );
/// ```
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ObjectProblem {
    /// Its parent is not in the scene.
    #[error("its parent is not in this scene")]
    ParentMissing,
    /// It is a mesh object, which cannot have subobjects.
    #[error("it has faces, so it cannot also have subobjects")]
    HasFaces,
    /// Its transform is singular or not finite.
    #[error("the transform is singular or not finite")]
    SingularTransform,
    /// The object to instance is not in the scene.
    #[error("the object to instance is not in this scene")]
    SourceMissing,
    /// Its mesh, transformed, is not a valid mesh.
    #[error(transparent)]
    Mesh(MeshError),
    /// Its meshes, joined into one, are not a valid mesh.
    #[error("flattening: {0}")]
    Flatten(MeshError),
}

/// `Result` with the scene layer's [`SceneError`].
pub type Result<T, E = SceneError> = std::result::Result<T, E>;

slotmap::new_key_type! {
    /// The key of an object in a [`Scene`].
    pub struct ObjectId;
}

/// What an object holds: subobjects or a mesh, never both (Franklin: "If an object has
/// subobjects, then it cannot also have vertices or faces").
///
/// ```
/// use kepler::scene::{Content, Scene};
/// let mut s = Scene::new();
/// let g = s.add_group(None, "g").unwrap();
/// assert!(matches!(s[g].content(), Content::Subobjects(v) if v.is_empty()));
/// ```
#[derive(Debug, Clone)]
pub enum Content {
    /// Subobjects, in order.
    Subobjects(Vec<ObjectId>),
    /// Vertices and faces (shared: copying a scene, to scale it, say, does not copy its
    /// meshes).
    Mesh(Arc<Mesh>),
}

/// One object of the scene: a name, its content, and its cached bounds.
///
/// ```
/// use kepler::scene::Scene;
/// let mut s = Scene::new();
/// let c = s.add_mesh(None, "cube", kepler::solids::cube(1.0).unwrap()).unwrap();
/// assert_eq!(s[c].name(), "cube");
/// assert!(s[c].mesh().is_some());
/// ```
#[derive(Debug, Clone)]
pub struct Object {
    name: String,
    parent: Option<ObjectId>,
    content: Content,
    instance_of: Option<String>,
    cbox: OnceLock<Aabb>,
    inbox: OnceLock<Option<Inbox>>,
    tribox: OnceLock<TriboxBounds>,
    /// The exponents of a mesh's coordinates (see [`Scene::exponents`]).
    exponents: OnceLock<Exponents>,
}

impl Object {
    fn new(name: String, parent: Option<ObjectId>, content: Content) -> Object {
        Object {
            name,
            parent,
            content,
            instance_of: None,
            cbox: OnceLock::new(),
            inbox: OnceLock::new(),
            tribox: OnceLock::new(),
            exponents: OnceLock::new(),
        }
    }

    /// The object's name.
    ///
    /// ```
    /// let mut s = kepler::scene::Scene::new();
    /// let g = s.add_group(None, "street").unwrap();
    /// assert_eq!(s[g].name(), "street");
    /// ```
    pub fn name(&self) -> &str {
        &self.name
    }

    /// The parent object, if any.
    ///
    /// ```
    /// let mut s = kepler::scene::Scene::new();
    /// let g = s.add_group(None, "g").unwrap();
    /// let h = s.add_group(Some(g), "h").unwrap();
    /// assert_eq!(s[h].parent(), Some(g));
    /// ```
    pub fn parent(&self) -> Option<ObjectId> {
        self.parent
    }

    /// Subobjects or mesh.
    ///
    /// ```
    /// let mut s = kepler::scene::Scene::new();
    /// let g = s.add_group(None, "g").unwrap();
    /// assert!(matches!(s[g].content(), kepler::scene::Content::Subobjects(_)));
    /// ```
    pub fn content(&self) -> &Content {
        &self.content
    }

    /// The mesh of a leaf object.
    ///
    /// ```
    /// let mut s = kepler::scene::Scene::new();
    /// let g = s.add_group(None, "g").unwrap();
    /// assert!(s[g].mesh().is_none());
    /// ```
    pub fn mesh(&self) -> Option<&Mesh> {
        match &self.content {
            Content::Mesh(m) => Some(m),
            Content::Subobjects(_) => None,
        }
    }

    /// The subobjects (empty for a leaf).
    ///
    /// ```
    /// let mut s = kepler::scene::Scene::new();
    /// let g = s.add_group(None, "g").unwrap();
    /// let h = s.add_group(Some(g), "h").unwrap();
    /// assert_eq!(s[g].subobjects(), &[h]);
    /// ```
    pub fn subobjects(&self) -> &[ObjectId] {
        match &self.content {
            Content::Subobjects(v) => v,
            Content::Mesh(_) => &[],
        }
    }

    /// The name of the object this one is an instance of, if it was placed as an instance.
    ///
    /// ```
    /// use kepler::scene::{Scene, Transform};
    /// let mut s = Scene::new();
    /// let a = s.add_mesh(None, "a", kepler::solids::cube(1.0).unwrap()).unwrap();
    /// let b = s.instantiate(a, None, "b", &Transform::default()).unwrap();
    /// assert_eq!(s[b].instance_of(), Some("a"));
    /// ```
    pub fn instance_of(&self) -> Option<&str> {
        self.instance_of.as_deref()
    }
}

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

    /// The CBOX: the smallest box around the object's vertices; for an object with
    /// subobjects, the union of theirs. Computed once, then cached.
    ///
    /// ```
    /// let mut s = kepler::scene::Scene::new();
    /// let c = s.add_mesh(None, "c", kepler::solids::cube(2.0).unwrap()).unwrap();
    /// assert_eq!(s.cbox(c).min, [-1.0; 3]);
    /// ```
    pub fn cbox(&self, id: ObjectId) -> Aabb {
        let o = &self.objects[id];
        *o.cbox.get_or_init(|| match &o.content {
            Content::Mesh(m) => crate::bounds::cbox(m),
            Content::Subobjects(v) => v.iter().fold(Aabb::EMPTY, |b, &c| b.union(&self.cbox(c))),
        })
    }

    /// The INBOX, or `None` for an object without interior (open, inconsistently oriented or
    /// flat). For an object with subobjects, the largest inbox among them. Cached.
    ///
    /// ```
    /// let mut s = kepler::scene::Scene::new();
    /// let c = s.add_mesh(None, "c", kepler::solids::cube(2.0).unwrap()).unwrap();
    /// assert_eq!(s.inbox(c).unwrap().aabb, s.cbox(c));
    /// ```
    pub fn inbox(&self, id: ObjectId) -> Option<Inbox> {
        let o = &self.objects[id];
        *o.inbox.get_or_init(|| match &o.content {
            Content::Mesh(m) => inbox(m),
            Content::Subobjects(v) => v
                .iter()
                .filter_map(|&c| self.inbox(c))
                .max_by(|a, b| a.aabb.volume().total_cmp(&b.aabb.volume()))
                .map(|i| Inbox {
                    aabb: i.aabb,
                    method: InboxMethod::Subobject,
                }),
        })
    }

    /// The tribox bounds (18 projection bounds); for an object with subobjects, the union of
    /// theirs, which is the tribox of all their vertices. Cached.
    ///
    /// ```
    /// let mut s = kepler::scene::Scene::new();
    /// let c = s.add_mesh(None, "c", kepler::solids::cube(2.0).unwrap()).unwrap();
    /// assert!(s.tribox(c).contains_point(&kepler::geometry::Point3::new(1.0, 1.0, 1.0)));
    /// ```
    pub fn tribox(&self, id: ObjectId) -> TriboxBounds {
        let o = &self.objects[id];
        *o.tribox.get_or_init(|| match &o.content {
            Content::Mesh(m) => TriboxBounds::from_points(m.vertices()),
            Content::Subobjects(v) => v
                .iter()
                .fold(TriboxBounds::empty(), |b, &c| b.union(&self.tribox(c))),
        })
    }

    /// Computes (and caches) the CBOX, INBOX and tribox bounds of every object: the mesh
    /// objects in parallel, then the objects with subobjects from their cached results.
    ///
    /// ```
    /// let mut s = kepler::scene::Scene::new();
    /// let c = s.add_mesh(None, "c", kepler::solids::cube(1.0).unwrap()).unwrap();
    /// s.compute_bounds();
    /// assert!(s.inbox(c).is_some());
    /// ```
    pub fn compute_bounds(&self) {
        self.compute_bounds_of(&self.roots);
    }

    /// Computes (and caches) the bounds of the subtrees of `objects` only, as
    /// [`Scene::compute_bounds`] does for the whole scene.
    ///
    /// ```
    /// let mut s = kepler::scene::Scene::new();
    /// let g = s.add_group(None, "g").unwrap();
    /// let c = s.add_mesh(Some(g), "c", kepler::solids::cube(1.0).unwrap()).unwrap();
    /// s.compute_bounds_of(&[g]);
    /// assert_eq!(s.inbox(g).unwrap().aabb, s.cbox(c));
    /// ```
    pub fn compute_bounds_of(&self, objects: &[ObjectId]) {
        use rayon::prelude::*;
        let walk = self.depth_first(objects);
        walk.par_iter()
            .filter(|(id, _)| self.objects[*id].mesh().is_some())
            .for_each(|&(id, _)| {
                self.cbox(id);
                self.inbox(id);
                self.tribox(id);
            });
        for (id, _) in walk {
            self.cbox(id);
            self.inbox(id);
            self.tribox(id);
        }
    }

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
