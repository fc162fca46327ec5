//! Collision detection between two boxtrees: does a triangle of one meet a triangle of the
//! other?
//!
//! "Starting from the root of the tree, determine whether the box collides with [...] the
//! obstacle in question. If yes, explore both children and recurse." For two hierarchies the
//! search runs on pairs of nodes: a pair whose bounds may overlap ([`NodeShape::may_overlap`],
//! conservative) is split by replacing the node with the larger surface area (an inner node)
//! by its two children; a pair of leaves whose bounds may overlap is decided exactly
//! ([`triangles_meet`]). Each bound-bound test counts as one of the paper's "collision tests
//! between hierarchy elements", the number its Table 1 reports.
//!
//! ```
//! use kepler::lab::boxtree::{BoxTree, Merge};
//! use kepler::geometry::{Aabb, Vector3};
//! let a = kepler::solids::cube(2.0).unwrap();
//! let b = a.transformed(&nalgebra::Matrix4::new_translation(&Vector3::new(1.5, 0.5, 0.5))).unwrap();
//! let c = a.transformed(&nalgebra::Matrix4::new_translation(&Vector3::new(3.0, 0.0, 0.0))).unwrap();
//! let [ta, tb, tc] = [&a, &b, &c].map(|m| BoxTree::<Aabb>::build(m, Merge::Area));
//! assert!(ta.collide(&tb).pair.is_some());
//! let apart = ta.collide(&tc);
//! assert!(apart.pair.is_none());
//! assert_eq!(apart.tests, 1); // the roots' boxes are disjoint
//! ```

use super::tree::Link;
use super::tritri::triangles_meet;
use super::{BoxTree, NodeShape};
use serde::Serialize;

/// The answer of a collision query and its work.
///
/// ```
/// use kepler::lab::boxtree::Collision;
/// let c = Collision::default();
/// assert!(c.pair.is_none() && c.tests == 0);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize)]
pub struct Collision {
    /// A meeting pair of triangles (of the first tree, of the second), if any: the first
    /// found by [`BoxTree::collide`], the last by [`BoxTree::intersecting_pairs`].
    pub pair: Option<[usize; 2]>,
    /// Bound-bound overlap tests.
    pub tests: u64,
    /// Triangle-triangle tests (pairs of leaves whose bounds may overlap).
    pub triangle_tests: u64,
}

impl<S: NodeShape> BoxTree<S> {
    /// Whether a triangle of `self` meets (shares a point with) a triangle of `other`,
    /// stopping at the first meeting pair found.
    ///
    /// ```
    /// use kepler::lab::boxtree::{BoxTree, Merge};
    /// use kepler::bounds::tribox::TriboxBounds;
    /// let a = kepler::solids::cube(2.0).unwrap();
    /// let t: BoxTree<TriboxBounds> = BoxTree::build(&a, Merge::Area);
    /// let c = t.collide(&t); // a surface meets itself
    /// assert!(c.pair.is_some() && c.triangle_tests >= 1);
    /// ```
    pub fn collide(&self, other: &BoxTree<S>) -> Collision {
        let mut answer = Collision::default();
        self.descend(
            other,
            |pair, answer: &mut Collision| {
                answer.pair = Some(pair);
                false
            },
            &mut answer,
        );
        answer
    }

    /// Every meeting pair of triangles (of `self`, of `other`), sorted, by a full traversal;
    /// its counts are those of a search that cannot stop early (two surfaces that do not
    /// meet, like the paper's concentric spheres, cost this much to clear).
    ///
    /// ```
    /// use kepler::lab::boxtree::{BoxTree, Merge};
    /// use kepler::geometry::Aabb;
    /// let a = kepler::solids::tetrahedron(1.0).unwrap();
    /// let t: BoxTree<Aabb> = BoxTree::build(&a, Merge::Area);
    /// let (pairs, work) = t.intersecting_pairs(&t);
    /// assert_eq!(pairs.len(), 16); // any two faces of a tetrahedron share a vertex or an edge
    /// assert_eq!(work.pair, pairs.last().copied());
    /// ```
    pub fn intersecting_pairs(&self, other: &BoxTree<S>) -> (Vec<[usize; 2]>, Collision) {
        let mut answer = Collision::default();
        let mut pairs = Vec::new();
        self.descend(
            other,
            |pair, _: &mut Collision| {
                pairs.push(pair);
                true
            },
            &mut answer,
        );
        pairs.sort_unstable();
        answer.pair = pairs.last().copied();
        (pairs, answer)
    }

    /// The simultaneous descent; `found` is called with each meeting pair and says whether
    /// to go on.
    fn descend(
        &self,
        other: &BoxTree<S>,
        mut found: impl FnMut([usize; 2], &mut Collision) -> bool,
        answer: &mut Collision,
    ) {
        let (Some(ra), Some(rb)) = (self.root(), other.root()) else {
            return;
        };
        let (na, nb) = (self.nodes(), other.nodes());
        let mut stack = vec![(ra, rb)];
        while let Some((a, b)) = stack.pop() {
            answer.tests += 1;
            let (x, y) = (&na[a], &nb[b]);
            if !x.bound().may_overlap(y.bound()) {
                continue;
            }
            match (x.link(), y.link()) {
                (Link::Leaf(s), Link::Leaf(t)) => {
                    answer.triangle_tests += 1;
                    if triangles_meet(&self.triangles()[s], &other.triangles()[t])
                        && !found([s, t], answer)
                    {
                        return;
                    }
                }
                (Link::Inner([a0, a1]), Link::Leaf(_)) => stack.extend([(a1, b), (a0, b)]),
                (Link::Leaf(_), Link::Inner([b0, b1])) => stack.extend([(a, b1), (a, b0)]),
                (Link::Inner([a0, a1]), Link::Inner([b0, b1])) => {
                    if x.measures().area >= y.measures().area {
                        stack.extend([(a1, b), (a0, b)]);
                    } else {
                        stack.extend([(a, b1), (a, b0)]);
                    }
                }
            }
        }
    }
}
