//! The bounds of an object (CBOX, INBOX and tribox), each computed once and then cached, for
//! one object or every object of a subtree in parallel.

use super::{Content, ObjectId, Scene};
use crate::bounds::tribox::TriboxBounds;
use crate::bounds::{Aabb, Inbox, InboxMethod, inbox};

impl Scene {
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
}
