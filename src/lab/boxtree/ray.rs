//! Ray shooting through a boxtree: the first triangle a ray meets, decided exactly.
//!
//! "Given an internal node v with children (u1, u2), if it is determined that the ray hits
//! box(v), then both child boxes, box(u1) and box(u2), must be examined. However, only those
//! actually hit by the ray trigger a recursive call. It follows immediately that the number of
//! nodes traversed coincides precisely with the number of boxes hit by the ray. The maximum such
//! number, over all rays, is called the stabbing number of the boxtree."
//!
//! [`BoxTree::first_hit`] descends nearer child first and skips a node whose bound the ray
//! enters only beyond the best hit so far; it counts the bounds it tests (`visited`, the ray's
//! work) and those the ray meets (`met`). [`BoxTree::stabbing`] counts, without skipping, every
//! node whose bound the ray meets: the paper's stabbing count of that ray. Bounds are tested
//! conservatively ([`super::slab`]), so a count may include a bound the exact ray just misses.
//!
//! The triangles decide exactly, by the rule of
//! [`VisibilityIndex::first_hit`](crate::queries::visp::VisibilityIndex::first_hit): a ray
//! meets a closed triangle when it crosses the triangle's plane at some `t > 0` inside it (a
//! triangle whose plane contains the ray's origin, or that the ray runs along, is not met);
//! hits are ordered by the exact ray parameter `n·(a − o) / n·u` as a ratio of expansions, and
//! ties go to the lowest triangle index. The functions of that rule are `visp`'s
//! ([`pierces`], [`compare_hits`]).
//!
//! ```
//! use kepler::lab::boxtree::{BoxTree, Merge};
//! use kepler::bounds::tribox::TriboxBounds;
//! use kepler::geometry::{Point3, Vector3};
//! use kepler::geometry::ray::Ray;
//! let torus = kepler::solids::torus(2.0, 0.5, 48, 24).unwrap();
//! let tree: BoxTree<TriboxBounds> = BoxTree::build(&torus, Merge::Area);
//! let through_hole = Ray { origin: Point3::new(0.0, 0.0, 5.0), direction: -Vector3::z() };
//! let shot = tree.first_hit(&through_hole);
//! assert!(shot.hit.is_none());
//! let at_tube = Ray { origin: Point3::new(2.0, 0.0, 5.0), direction: -Vector3::z() };
//! let hit = tree.first_hit(&at_tube).hit.unwrap();
//! assert!((hit.point.z - 0.5).abs() < 0.01);
//! assert!(tree.stabbing(&at_tube) >= tree.first_hit(&at_tube).met);
//! ```

use super::tree::Link;
use super::{BoxTree, NodeShape, RayProbe};
use crate::geometry::exact::accurate_sum;
use crate::geometry::ray::{Ray, compare_hits, hit_point, pierces};
use crate::geometry::{Point3, Vector3};
use std::cmp::Ordering;

/// Where a ray first meets a triangle.
///
/// ```
/// use kepler::lab::boxtree::RayHit;
/// use kepler::geometry::Point3;
/// let h = RayHit { triangle: 3, point: Point3::origin() };
/// assert_eq!(h.triangle, 3);
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RayHit {
    /// The triangle's index in the mesh's triangles.
    pub triangle: usize,
    /// The point hit, computed once from the exact parameter's rounded numerator and
    /// denominator (a few ulps from the exact point).
    pub point: Point3,
}

/// The answer of a ray shot and its work.
///
/// ```
/// use kepler::lab::boxtree::RayShot;
/// let s = RayShot::default();
/// assert!(s.hit.is_none() && s.visited == 0);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct RayShot {
    /// The first triangle met, if any.
    pub hit: Option<RayHit>,
    /// Bounds tested.
    pub visited: usize,
    /// Bounds the ray (may) meet, among those tested.
    pub met: usize,
    /// Triangles tested exactly.
    pub triangle_tests: usize,
}

impl<S: NodeShape> BoxTree<S> {
    /// The first triangle the ray meets, exactly, and the work it took (see the module
    /// documentation). A zero or non-finite direction meets nothing.
    ///
    /// ```
    /// use kepler::lab::boxtree::{BoxTree, Merge, pca::PcaMin};
    /// use kepler::geometry::{Point3, Vector3};
    /// use kepler::geometry::ray::Ray;
    /// let cube = kepler::solids::cube(2.0).unwrap();
    /// let tree: BoxTree<PcaMin> = BoxTree::build(&cube, Merge::Area);
    /// // Through the corner (1, 1, 1): three faces meet there, the lowest triangle wins.
    /// let ray = Ray { origin: Point3::new(3.0, 3.0, 3.0), direction: Vector3::new(-1.0, -1.0, -1.0) };
    /// let hit = tree.first_hit(&ray).hit.unwrap();
    /// assert_eq!(hit.point, Point3::new(1.0, 1.0, 1.0));
    /// assert_eq!(Some(hit), kepler::lab::boxtree::ray::first_hit_brute_force(tree.triangles(), &ray));
    /// ```
    pub fn first_hit(&self, ray: &Ray) -> RayShot {
        let mut shot = RayShot::default();
        let (Some(probe), Some(root)) = (RayProbe::new(ray), self.root()) else {
            return shot;
        };
        let r = probe.ray();
        let nodes = self.nodes();
        let triangles = self.triangles();
        // The best hit: its triangle, an enclosure of its parameter if the filter gives one,
        // and an upper bound of its parameter.
        let mut best: Option<(usize, Option<[f64; 2]>, f64)> = None;
        let mut stack: Vec<(usize, f64)> = Vec::new();
        shot.visited += 1;
        if let Some([t0, _]) = nodes[root].bound().ray_interval(&probe) {
            shot.met += 1;
            stack.push((root, t0));
        }
        while let Some((n, t0)) = stack.pop() {
            if best.is_some_and(|(_, _, limit)| t0 > limit) {
                continue;
            }
            match nodes[n].link() {
                Link::Leaf(t) => {
                    shot.triangle_tests += 1;
                    if !pierces(r, &triangles[t]) {
                        continue;
                    }
                    let bounds = parameter_bounds(r, &triangles[t]);
                    let better = match best {
                        None => true,
                        Some((b, b_bounds, _)) => {
                            let order = match (bounds, b_bounds) {
                                (Some(c), Some(d)) if c[1] < d[0] => Ordering::Less,
                                (Some(c), Some(d)) if c[0] > d[1] => Ordering::Greater,
                                _ => compare_hits(r, &triangles[t], &triangles[b]),
                            };
                            order == Ordering::Less || (order == Ordering::Equal && t < b)
                        }
                    };
                    if better {
                        let limit = match bounds {
                            Some([_, hi]) => hi,
                            None => parameter_upper_bound(r, &triangles[t]),
                        };
                        best = Some((t, bounds, limit));
                    }
                }
                Link::Inner(children) => {
                    let mut entered = [(0, 0.0); 2];
                    let mut count = 0;
                    for c in children {
                        shot.visited += 1;
                        if let Some([c0, _]) = nodes[c].bound().ray_interval(&probe) {
                            shot.met += 1;
                            entered[count] = (c, c0);
                            count += 1;
                        }
                    }
                    // Farther first on the stack, so the nearer is explored first.
                    if count == 2 && entered[0].1 < entered[1].1 {
                        entered.swap(0, 1);
                    }
                    stack.extend_from_slice(&entered[..count]);
                }
            }
        }
        shot.hit = best.map(|(t, _, _)| RayHit {
            triangle: t,
            point: hit_point(r, &triangles[t]),
        });
        shot
    }

    /// The number of nodes whose bound the ray meets (the paper's stabbing count of this ray),
    /// found by descending into every node met.
    ///
    /// ```
    /// use kepler::lab::boxtree::{BoxTree, Merge};
    /// use kepler::geometry::{Aabb, Point3, Vector3};
    /// use kepler::geometry::ray::Ray;
    /// let cube = kepler::solids::cube(2.0).unwrap();
    /// let tree: BoxTree<Aabb> = BoxTree::build(&cube, Merge::Area);
    /// let away = Ray { origin: Point3::new(5.0, 0.0, 0.0), direction: Vector3::x() };
    /// assert_eq!(tree.stabbing(&away), 0);
    /// let through = Ray { origin: Point3::new(5.0, 0.1, 0.2), direction: -Vector3::x() };
    /// assert!(tree.stabbing(&through) >= 3); // at least the root and two leaves
    /// ```
    pub fn stabbing(&self, ray: &Ray) -> usize {
        let (Some(probe), Some(root)) = (RayProbe::new(ray), self.root()) else {
            return 0;
        };
        let nodes = self.nodes();
        let meets = |n: usize| nodes[n].bound().ray_interval(&probe).is_some();
        if !meets(root) {
            return 0;
        }
        let mut count = 1;
        let mut stack = vec![root];
        while let Some(n) = stack.pop() {
            for c in nodes[n].children().into_iter().flatten() {
                if meets(c) {
                    count += 1;
                    stack.push(c);
                }
            }
        }
        count
    }
}

/// The first triangle the ray meets among `triangles`, by testing every one (the reference
/// the hierarchy must agree with).
///
/// ```
/// use kepler::lab::boxtree::ray::first_hit_brute_force;
/// use kepler::geometry::{Point3, Vector3};
/// use kepler::geometry::ray::Ray;
/// let t = [Point3::new(0.0, 0.0, 1.0), Point3::new(4.0, 0.0, 1.0), Point3::new(0.0, 4.0, 1.0)];
/// let u = [Point3::new(0.0, 0.0, 2.0), Point3::new(4.0, 0.0, 2.0), Point3::new(0.0, 4.0, 2.0)];
/// let ray = Ray { origin: Point3::new(1.0, 1.0, 5.0), direction: -Vector3::z() };
/// assert_eq!(first_hit_brute_force(&[t, u], &ray).unwrap().triangle, 1);
/// ```
pub fn first_hit_brute_force(triangles: &[[Point3; 3]], ray: &Ray) -> Option<RayHit> {
    let r = *RayProbe::new(ray)?.ray();
    let mut best: Option<usize> = None;
    for (t, corners) in triangles.iter().enumerate() {
        if pierces(&r, corners)
            && best.is_none_or(|b| compare_hits(&r, corners, &triangles[b]) == Ordering::Less)
        {
            best = Some(t);
        }
    }
    best.map(|t| RayHit {
        triangle: t,
        point: hit_point(&r, &triangles[t]),
    })
}

/// An enclosure `[lo, hi]` of the exact parameter `t = n·(a − o) / n·u` at which the ray
/// meets the plane of a pierced triangle, in floating point (`None` when the error bound
/// cannot tell the denominator from zero): the normal's components carry at most about 4u of
/// their permanents `P_k = |e1_i e2_j| + |e1_j e2_i|` (u the unit roundoff), so numerator and
/// denominator are within about 8u of `Σ P_k |(a − o)_k|` and `Σ P_k |u_k|`; the bounds use
/// 32u, and the quotients are widened by 8u for their own rounding.
fn parameter_bounds(ray: &Ray, t: &[Point3; 3]) -> Option<[f64; 2]> {
    const U: f64 = f64::EPSILON / 2.0;
    let (e1, e2) = (t[1] - t[0], t[2] - t[0]);
    let n = e1.cross(&e2);
    let permanent = Vector3::new(
        (e1.y * e2.z).abs() + (e1.z * e2.y).abs(),
        (e1.z * e2.x).abs() + (e1.x * e2.z).abs(),
        (e1.x * e2.y).abs() + (e1.y * e2.x).abs(),
    );
    let d = t[0] - ray.origin;
    let (num, den) = (n.dot(&d), n.dot(&ray.direction));
    let en = 32.0 * U * permanent.dot(&d.abs()) + f64::MIN_POSITIVE;
    let ed = 32.0 * U * permanent.dot(&ray.direction.abs()) + f64::MIN_POSITIVE;
    let (num, den) = if den < 0.0 { (-num, -den) } else { (num, den) };
    if !(den > ed && num.is_finite() && en.is_finite() && ed.is_finite()) {
        return None;
    }
    let lo = (num - en).max(0.0) / (den + ed);
    let hi = (num + en) / (den - ed);
    Some([
        lo * (1.0 - 8.0 * U),
        hi * (1.0 + 8.0 * U) + f64::MIN_POSITIVE,
    ])
}

/// An upper bound of the (positive) exact parameter of a pierced triangle: the quotient of the
/// correctly rounded numerator and denominator is within three roundings of it.
fn parameter_upper_bound(ray: &Ray, t: &[Point3; 3]) -> f64 {
    let (n, d) = crate::geometry::ray::parameter(ray, t);
    let q = accurate_sum(&n) / accurate_sum(&d);
    q + q.abs() * 4.0 * f64::EPSILON + f64::MIN_POSITIVE
}
