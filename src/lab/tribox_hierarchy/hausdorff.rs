//! The one-sided Hausdorff distance from a union of triboxes to the solid they bound, by
//! branch and bound: an interval that surely holds the exact value, not a sample.
//!
//! The distance from a point `u` to the solid `S` is 0 inside and the distance to the surface
//! outside. Over an axis-aligned box of centre `c` and half-diagonal `r` it is at most
//! `d(c, S) + r` when `c` is outside, and at most `max(0, r − d(c, ∂S))` when `c` is inside
//! (the ball of radius `d(c, ∂S)` about `c` lies in `S`). Points surely in the union (the
//! triboxes' vertices, box centres inside a tribox) give lower bounds. Boxes start as the
//! triboxes' axis-aligned boxes, are dropped when separated from their tribox along one of
//! the 9 directions, and are halved along all three axes, largest upper bound first, until
//! the bounds are within the tolerance.
//!
//! The number of boxes grows as `1/tolerance` where the distance is reached along a ridge
//! and as `1/tolerance²` on a plateau (both common on prisms) or where the union hugs the
//! object (every box across the surface keeps a positive upper bound). Past a budget of
//! 400,000 boxes the bounds are returned as they stand: still valid, wider than asked.
//!
//! Inside or outside is decided exactly (INCLUDE's ray test); distances to triangles are
//! rounded, so every bound is moved outward by 64 ulps of the largest coordinate, far more
//! than the rounding of the closest-point computation.

use crate::bounds::tribox::{Tribox, TriboxBounds};
use crate::geometry::{Aabb, Point3};
use crate::mesh::{Containment, TriangleTree, classify_point};
use serde::Serialize;
use std::cmp::Ordering;
use std::collections::BinaryHeap;

/// An interval that holds an exact distance.
///
/// ```
/// let b = kepler::lab::tribox_hierarchy::DistanceBounds { lower: 1.0, upper: 1.001 };
/// assert!(b.lower <= b.upper);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct DistanceBounds {
    /// At most the exact distance.
    pub lower: f64,
    /// At least the exact distance.
    pub upper: f64,
}

/// The most boxes looked at for one union; past it the bounds are returned as they stand
/// (still valid, maybe wider than the tolerance).
const MAX_BOXES: usize = 400_000;

/// A box waiting to be halved.
struct Candidate {
    upper: f64,
    cell: Aabb,
    tribox: usize,
}

impl PartialEq for Candidate {
    fn eq(&self, other: &Self) -> bool {
        self.upper.total_cmp(&other.upper) == Ordering::Equal
    }
}

impl Eq for Candidate {}

impl PartialOrd for Candidate {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}

impl Ord for Candidate {
    fn cmp(&self, other: &Self) -> Ordering {
        self.upper.total_cmp(&other.upper)
    }
}

/// Bounds on `max over u in ∪ triboxes of d(u, S)`, where `S` is the solid bounded by the
/// closed mesh of `tree`, to within `tolerance` (absolute) unless the box budget runs out.
/// No tribox gives 0.
///
/// ```
/// use kepler::bounds::tribox::TriboxBounds;
/// use kepler::mesh::TriangleTree;
/// use kepler::lab::tribox_hierarchy::hausdorff;
/// // A regular tetrahedron in the cube [-1, 1]³: its tribox is the cube, whose far corners
/// // are 2/√3 from the tetrahedron.
/// let tet = kepler::mesh::Mesh::from_polygons(
///     vec![[1.0, 1.0, 1.0].into(), [1.0, -1.0, -1.0].into(), [-1.0, 1.0, -1.0].into(), [-1.0, -1.0, 1.0].into()],
///     vec![vec![0, 1, 2], vec![0, 3, 1], vec![0, 2, 3], vec![1, 3, 2]],
/// ).unwrap();
/// let t = TriboxBounds::from_points(tet.vertices());
/// let d = hausdorff(&[t], &TriangleTree::new(&tet), 1e-6);
/// let exact = 2.0 / 3f64.sqrt();
/// assert!(d.lower <= exact && exact <= d.upper && d.upper - d.lower <= 1e-6);
/// ```
pub fn hausdorff(triboxes: &[TriboxBounds], tree: &TriangleTree, tolerance: f64) -> DistanceBounds {
    let scale = triboxes
        .iter()
        .flat_map(|t| t.min()[..3].iter().chain(&t.max()[..3]))
        .fold(0.0f64, |m, v| m.max(v.abs()));
    let slack = 64.0 * f64::EPSILON * scale + f64::MIN_POSITIVE;
    let mut lower = 0.0f64;
    for t in triboxes {
        for v in Tribox::new(t).cleaned().vertices() {
            lower = lower.max(signed_distance(tree, v) - slack);
        }
    }
    let mut search = Search {
        triboxes,
        tree,
        tolerance,
        slack,
        lower,
        heap: BinaryHeap::new(),
        dropped: 0.0f64,
    };
    let mut boxes = 0;
    for (i, t) in triboxes.iter().enumerate() {
        if t.is_empty() {
            continue;
        }
        // A tribox's first three slabs are its axis-aligned box.
        let cell = Aabb {
            min: [t.min()[0], t.min()[1], t.min()[2]],
            max: [t.max()[0], t.max()[1], t.max()[2]],
        };
        search.consider(cell, i);
    }
    while let Some(top) = search.heap.peek() {
        if top.upper <= search.lower + tolerance || boxes >= MAX_BOXES {
            break;
        }
        let Some(b) = search.heap.pop() else { break };
        let (lo, hi) = (b.cell.min, b.cell.max);
        let mid = [0, 1, 2].map(|k| 0.5 * lo[k] + 0.5 * hi[k]);
        for c in 0..8 {
            let octant = Aabb {
                min: [0, 1, 2].map(|k| if c >> k & 1 == 0 { lo[k] } else { mid[k] }),
                max: [0, 1, 2].map(|k| if c >> k & 1 == 0 { mid[k] } else { hi[k] }),
            };
            search.consider(octant, b.tribox);
            boxes += 1;
        }
    }
    let open = search.heap.peek().map_or(0.0, |c| c.upper);
    DistanceBounds {
        lower: search.lower,
        upper: open.max(search.dropped).max(search.lower),
    }
}

/// The signed distance from `p` to the solid of `tree`: negative inside (to the surface),
/// positive outside, 0 on it.
fn signed_distance(tree: &TriangleTree, p: &Point3) -> f64 {
    match classify_point(tree, p) {
        Containment::Outside => tree.distance(p),
        Containment::Inside => -tree.distance(p),
        Containment::Boundary => 0.0,
    }
}

/// The branch and bound of [`hausdorff`]: the lower bound so far, the boxes still open (by
/// their upper bounds), and the largest upper bound of the boxes dropped.
struct Search<'a> {
    triboxes: &'a [TriboxBounds],
    tree: &'a TriangleTree,
    tolerance: f64,
    slack: f64,
    lower: f64,
    heap: BinaryHeap<Candidate>,
    dropped: f64,
}

impl Search<'_> {
    /// Bounds the distance over the part of tribox `i` in `cell` by the distance at the
    /// cell's centre and its radius: raises the lower bound when the centre is in the tribox,
    /// drops the cell when it cannot raise the result beyond the tolerance, else keeps it
    /// open.
    fn consider(&mut self, cell: Aabb, i: usize) {
        let (lo, hi) = (cell.min, cell.max);
        if !TriboxBounds::from_points(&cell.corners()).intersects(&self.triboxes[i]) {
            return;
        }
        let c = Point3::new(
            0.5 * lo[0] + 0.5 * hi[0],
            0.5 * lo[1] + 0.5 * hi[1],
            0.5 * lo[2] + 0.5 * hi[2],
        );
        let r = (0..3)
            .map(|k| (hi[k] - c[k]).max(c[k] - lo[k]).powi(2))
            .sum::<f64>()
            .sqrt()
            * (1.0 + 8.0 * f64::EPSILON);
        let d = signed_distance(self.tree, &c);
        if d > 0.0 && self.triboxes[i].contains_point(&c) {
            self.lower = self.lower.max(d - self.slack);
        }
        let upper = (d + r).max(0.0) + self.slack;
        if upper <= self.lower + self.tolerance || r <= self.slack {
            self.dropped = self.dropped.max(upper);
        } else {
            self.heap.push(Candidate {
                upper,
                cell,
                tribox: i,
            });
        }
    }
}
