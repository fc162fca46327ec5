//! One object of a scene: its key, its name and parent, its content (subobjects or a mesh)
//! and its cached bounds.

use crate::bounds::tribox::TriboxBounds;
use crate::bounds::{Aabb, Inbox};
use crate::geometry::kernel::Exponents;
use crate::mesh::Mesh;
use std::sync::{Arc, OnceLock};

slotmap::new_key_type! {
    /// The key of an object in a [`Scene`](super::Scene).
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
    pub(super) name: String,
    pub(super) parent: Option<ObjectId>,
    pub(super) content: Content,
    pub(super) instance_of: Option<String>,
    pub(super) cbox: OnceLock<Aabb>,
    pub(super) inbox: OnceLock<Option<Inbox>>,
    pub(super) tribox: OnceLock<TriboxBounds>,
    /// The exponents of a mesh's coordinates (see [`Scene::exponents`](super::Scene::exponents)).
    pub(super) exponents: OnceLock<Exponents>,
}

impl Object {
    pub(super) fn new(name: String, parent: Option<ObjectId>, content: Content) -> Object {
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
