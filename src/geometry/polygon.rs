//! Planar polygons in 3-D: Newell normal, dominant projection, exact triangulation.
//!
//! ```
//! use kepler::geometry::{Point3, polygon};
//! let square = [
//!     Point3::new(0.0, 0.0, 0.0), Point3::new(1.0, 0.0, 0.0),
//!     Point3::new(1.0, 1.0, 0.0), Point3::new(0.0, 1.0, 0.0),
//! ];
//! let n = polygon::newell_normal(&square);
//! assert_eq!((n.x, n.y, n.z), (0.0, 0.0, 2.0));
//! assert_eq!(polygon::triangulate(&square, &n).unwrap().len(), 2);
//! ```

use super::kernel::UNIT_ROUNDOFF;
use super::predicates::{orient2d, project};
use super::{Point3, Vector3};
use std::cmp::Ordering;

/// Twice the vector area of the polygon (Newell's method): its direction is the normal given
/// by the right-hand rule on the vertex order, its length twice the area for a planar polygon.
/// Computed relative to the first vertex to limit cancellation.
///
/// ```
/// use kepler::geometry::{Point3, polygon::newell_normal};
/// let tri = [Point3::new(0.0, 0.0, 0.0), Point3::new(0.0, 2.0, 0.0), Point3::new(0.0, 0.0, 2.0)];
/// assert_eq!(newell_normal(&tri).x, 4.0);
/// ```
pub fn newell_normal(points: &[Point3]) -> Vector3 {
    let Some(origin) = points.first() else {
        return Vector3::zeros();
    };
    let mut n = Vector3::zeros();
    for (i, p) in points.iter().enumerate() {
        let q = &points[(i + 1) % points.len()];
        n += (p - origin).cross(&(q - origin));
    }
    n
}

/// The coordinate axis (0, 1, 2) along which `normal` has its largest component: dropping it
/// gives the projection of the polygon with the least distortion.
///
/// ```
/// use kepler::geometry::{Vector3, polygon::dominant_axis};
/// assert_eq!(dominant_axis(&Vector3::new(0.1, -0.9, 0.3)), 1);
/// ```
pub fn dominant_axis(normal: &Vector3) -> usize {
    let a = normal.abs();
    if a.x >= a.y && a.x >= a.z {
        0
    } else if a.y >= a.z {
        1
    } else {
        2
    }
}

/// The polygon could not be triangulated: it is not simple (it crosses or overlaps itself).
///
/// ```
/// use kepler::geometry::polygon::NotSimple;
/// assert_eq!(NotSimple.to_string(), "the polygon is not simple");
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, thiserror::Error)]
#[error("the polygon is not simple")]
pub struct NotSimple;

/// Triangulates a simple polygon (convex or not) whose vertex order turns counter-clockwise
/// around `normal`, returning index triples into `points` with the same orientation: the
/// triangulation of [`triangulate_along`] the axis of `normal`'s largest component
/// ([`dominant_axis`]).
///
/// Written by hand because geo's spade triangulation snaps vertices within an absolute radius
/// and its earcut uses inexact tests.
///
/// ```
/// use kepler::geometry::{Point3, polygon::{newell_normal, triangulate}};
/// // An L-shape: not convex, still 4 triangles for 6 vertices.
/// let l: Vec<Point3> = [(0., 0.), (2., 0.), (2., 1.), (1., 1.), (1., 2.), (0., 2.)]
///     .iter().map(|&(x, y)| Point3::new(x, y, 0.0)).collect();
/// let tris = triangulate(&l, &newell_normal(&l)).unwrap();
/// assert_eq!(tris.len(), 4);
/// ```
pub fn triangulate(points: &[Point3], normal: &Vector3) -> Result<Vec<[usize; 3]>, NotSimple> {
    triangulate_along(points, dominant_axis(normal))
}

/// Triangulates the polygon `points` in its projection that drops coordinate `axis`, when that
/// projection is a simple polygon (distinct points, no two edges meeting but neighbours at
/// their common end); the triangles turn the way the projected polygon does. Every decision is
/// an exact `orient2d` on input coordinates, so the triangles cover the projection exactly.
///
/// Strictly convex projections get a fan from the first vertex; others are cut into ears. The
/// polygon need not be planar: over a simple projection its triangles make a surface that does
/// not cross itself.
///
/// ```
/// use kepler::geometry::{Point3, polygon::triangulate_along};
/// // A quad folded along a diagonal is simple seen along z (axis 2), a segment along y.
/// let q = [
///     Point3::new(0.0, 0.0, 0.0), Point3::new(1.0, 0.0, 0.0),
///     Point3::new(1.0, 1.0, 1e-12), Point3::new(0.0, 1.0, 0.0),
/// ];
/// assert_eq!(triangulate_along(&q, 2).unwrap(), vec![[0, 1, 2], [0, 2, 3]]);
/// assert!(triangulate_along(&q, 0).is_err());
/// ```
pub fn triangulate_along(points: &[Point3], axis: usize) -> Result<Vec<[usize; 3]>, NotSimple> {
    let n = points.len();
    if n < 3 {
        return Err(NotSimple);
    }
    // Adding +0.0 turns -0.0 into +0.0, so equal points sort next to each other.
    let p: Vec<[f64; 2]> = points
        .iter()
        .map(|q| project(q, axis).map(|c| c + 0.0))
        .collect();
    let mut sorted = p.clone();
    sorted.sort_unstable_by(|a, b| a[0].total_cmp(&b[0]).then(a[1].total_cmp(&b[1])));
    if sorted.windows(2).any(|w| w[0] == w[1]) {
        return Err(NotSimple);
    }
    // The lowest vertex (then leftmost) is convex in a simple polygon, so the turn there is
    // the polygon's orientation; a straight turn there folds back (or all points are on a
    // line).
    let low = (0..n)
        .min_by(|&i, &j| {
            p[i][1]
                .total_cmp(&p[j][1])
                .then(p[i][0].total_cmp(&p[j][0]))
        })
        .ok_or(NotSimple)?;
    let want = orient2d(p[(low + n - 1) % n], p[low], p[(low + 1) % n]);
    if want == Ordering::Equal {
        return Err(NotSimple);
    }
    if n == 3 {
        return Ok(vec![[0, 1, 2]]);
    }
    let turns_convex = (0..n).all(|i| orient2d(p[(i + n - 1) % n], p[i], p[(i + 1) % n]) == want);
    let fan_positive = (1..n - 1).all(|i| orient2d(p[0], p[i], p[i + 1]) == want);
    if turns_convex && fan_positive {
        return Ok((1..n - 1).map(|i| [0, i, i + 1]).collect());
    }
    if !is_simple(&p) {
        return Err(NotSimple);
    }
    ear_clip(&p, want)
}

/// Whether the closed polyline `p` is simple: no two non-adjacent edges meet and no two
/// adjacent edges fold back onto each other (exact, `O(n²)`).
///
/// ```
/// use kepler::geometry::polygon::is_simple;
/// assert!(is_simple(&[[0.0, 0.0], [2.0, 0.0], [2.0, 1.0], [1.0, 1.0], [1.0, 2.0], [0.0, 2.0]]));
/// // A bow tie crosses itself.
/// assert!(!is_simple(&[[0.0, 0.0], [1.0, 1.0], [1.0, 0.0], [0.0, 1.0]]));
/// ```
pub fn is_simple(p: &[[f64; 2]]) -> bool {
    let n = p.len();
    let edge = |i: usize| (p[i], p[(i + 1) % n]);
    for i in 0..n {
        let (a, b) = edge(i);
        let c = p[(i + 2) % n];
        // Adjacent edges a→b→c fold back when c lies on the ray from b through a.
        if orient2d(a, b, c) == Ordering::Equal && folds_back(a, b, c) {
            return false;
        }
        for j in i + 2..n {
            if i == 0 && j == n - 1 {
                continue;
            }
            let (c, d) = edge(j);
            if segments_meet(a, b, c, d) {
                return false;
            }
        }
    }
    true
}

/// For collinear `a`, `b`, `c`: whether `c` lies on the same side of `b` as `a` (compared
/// coordinate-wise, exactly).
fn folds_back(a: [f64; 2], b: [f64; 2], c: [f64; 2]) -> bool {
    let k = if a[0] != b[0] { 0 } else { 1 };
    (a[k] - b[k]).signum() == (c[k] - b[k]).signum() && c[k] != b[k]
}

/// Whether the closed segments `ab` and `cd` share a point (exact).
///
/// ```
/// use kepler::geometry::polygon::segments_meet;
/// assert!(segments_meet([0.0, 0.0], [2.0, 2.0], [0.0, 2.0], [2.0, 0.0]));
/// assert!(segments_meet([0.0, 0.0], [1.0, 0.0], [1.0, 0.0], [2.0, 5.0]));
/// assert!(!segments_meet([0.0, 0.0], [1.0, 0.0], [2.0, 0.0], [3.0, 0.0]));
/// ```
pub fn segments_meet(a: [f64; 2], b: [f64; 2], c: [f64; 2], d: [f64; 2]) -> bool {
    let (o1, o2) = (orient2d(a, b, c), orient2d(a, b, d));
    let (o3, o4) = (orient2d(c, d, a), orient2d(c, d, b));
    let between = |p: [f64; 2], q: [f64; 2], r: [f64; 2]| {
        (0..2).all(|k| p[k].min(q[k]) <= r[k] && r[k] <= p[k].max(q[k]))
    };
    if [o1, o2, o3, o4].iter().all(|&o| o != Ordering::Equal) {
        return o1 != o2 && o3 != o4;
    }
    // An endpoint on the other segment's line: they meet only at such an endpoint.
    (o1 == Ordering::Equal && between(a, b, c))
        || (o2 == Ordering::Equal && between(a, b, d))
        || (o3 == Ordering::Equal && between(c, d, a))
        || (o4 == Ordering::Equal && between(c, d, b))
}

/// Ear clipping with exact predicates: an ear is a strictly convex vertex whose triangle holds
/// no other remaining vertex, not even on its boundary.
fn ear_clip(p: &[[f64; 2]], want: Ordering) -> Result<Vec<[usize; 3]>, NotSimple> {
    let mut ring: Vec<usize> = (0..p.len()).collect();
    let mut tris = Vec::with_capacity(p.len() - 2);
    let inside_closed = |a: [f64; 2], b: [f64; 2], c: [f64; 2], q: [f64; 2]| {
        let not_out = |o: Ordering| o == want || o == Ordering::Equal;
        not_out(orient2d(a, b, q)) && not_out(orient2d(b, c, q)) && not_out(orient2d(c, a, q))
    };
    while ring.len() > 3 {
        let m = ring.len();
        let ear = (0..m).find(|&i| {
            let (a, b, c) = (ring[(i + m - 1) % m], ring[i], ring[(i + 1) % m]);
            orient2d(p[a], p[b], p[c]) == want
                && ring
                    .iter()
                    .filter(|&&j| j != a && j != b && j != c)
                    .all(|&j| !inside_closed(p[a], p[b], p[c], p[j]))
        });
        let Some(i) = ear else {
            // Only a chain of collinear vertices can remain in a simple polygon.
            return if (0..m).all(|i| {
                orient2d(p[ring[(i + m - 1) % m]], p[ring[i]], p[ring[(i + 1) % m]])
                    == Ordering::Equal
            }) {
                Ok(tris)
            } else {
                Err(NotSimple)
            };
        };
        tris.push([ring[(i + m - 1) % m], ring[i], ring[(i + 1) % m]]);
        ring.remove(i);
    }
    if orient2d(p[ring[0]], p[ring[1]], p[ring[2]]) == want {
        tris.push([ring[0], ring[1], ring[2]]);
    }
    Ok(tris)
}

/// Twice the signed area of the triangle `(a, b, c)` as a vector (its normal times twice its
/// area).
///
/// ```
/// use kepler::geometry::{Point3, polygon::triangle_normal};
/// let n = triangle_normal(&Point3::origin(), &Point3::new(1.0, 0.0, 0.0), &Point3::new(0.0, 1.0, 0.0));
/// assert_eq!(n.z, 1.0);
/// ```
pub fn triangle_normal(a: &Point3, b: &Point3, c: &Point3) -> Vector3 {
    (b - a).cross(&(c - a))
}

/// The smallest box `[min, max]` holding the plane points (infinite and inverted for none).
///
/// ```
/// use kepler::geometry::polygon::bounding_box;
/// assert_eq!(bounding_box([[1.0, 5.0], [-2.0, 3.0]]), [[-2.0, 3.0], [1.0, 5.0]]);
/// assert!(bounding_box([]).iter().flatten().all(|c| c.is_infinite()));
/// ```
pub fn bounding_box(points: impl IntoIterator<Item = [f64; 2]>) -> [[f64; 2]; 2] {
    points.into_iter().fold(
        [[f64::INFINITY; 2], [f64::NEG_INFINITY; 2]],
        |[lo, hi], p| {
            [
                [lo[0].min(p[0]), lo[1].min(p[1])],
                [hi[0].max(p[0]), hi[1].max(p[1])],
            ]
        },
    )
}

/// Whether the plane point `p` is certainly farther than `distance` from the closed triangle
/// `tri`: a floating-point filter, `false` whenever it cannot be sure (non-finite values,
/// a triangle too flat to tell its sides), never `true` for a point within `distance`.
///
/// Two tests, each conservative. The box: `p` lies beyond the triangle's bounding box grown by
/// `distance` on some axis (a difference rounds by at most a relative `u`, covered by the
/// factor `1 + 2⁻²⁰`). An edge `ab`: the estimates of `orient2d(a, b, p)` and
/// `orient2d(a, b, c)` for the third vertex `c` have certain, opposite signs (each within
/// Shewchuk's bound `(3 + 16u)u` times its permanent, plus a term for underflow), and the
/// line `ab` is farther from `p` than `distance`: the distance is the exact `|orient2d|`
/// over `|b − a|`, at least the estimate less its bound over `√2·max(|bₓ − aₓ|, |b_y − a_y|)`;
/// comparing with `1.5` for `√2` leaves room for the few roundings of the comparison.
///
/// ```
/// use kepler::geometry::polygon::surely_farther;
/// let t = [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]];
/// assert!(surely_farther(&t, [2.0, 2.0], 0.5));
/// assert!(!surely_farther(&t, [0.6, 0.6], 0.5)); // within 0.5 of the hypotenuse
/// assert!(!surely_farther(&t, [0.25, 0.25], 0.0)); // inside
/// ```
pub fn surely_farther(tri: &[[f64; 2]; 3], p: [f64; 2], distance: f64) -> bool {
    const GROWN: f64 = 1.0 + 1.0 / (1u64 << 20) as f64;
    const BOUND: f64 = (3.0 + 16.0 * UNIT_ROUNDOFF) * UNIT_ROUNDOFF;
    const TINY: f64 = 4.0 * f64::MIN_POSITIVE;
    let reach = distance * GROWN;
    for k in 0..2 {
        let (lo, hi) = tri
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), q| {
                (lo.min(q[k]), hi.max(q[k]))
            });
        if lo - p[k] > reach || p[k] - hi > reach {
            return true;
        }
    }
    // The estimate of orient2d(a, b, q) and its error bound.
    let orient = |a: [f64; 2], e: [f64; 2], q: [f64; 2]| {
        let w = [q[0] - a[0], q[1] - a[1]];
        let (l, r) = (e[0] * w[1], e[1] * w[0]);
        (l - r, BOUND * (l.abs() + r.abs()) + TINY)
    };
    (0..3).any(|i| {
        let (a, b, c) = (tri[i], tri[(i + 1) % 3], tri[(i + 2) % 3]);
        let e = [b[0] - a[0], b[1] - a[1]];
        let (at_p, err_p) = orient(a, e, p);
        let (at_c, err_c) = orient(a, e, c);
        let opposite = (at_p > err_p && at_c < -err_c) || (at_p < -err_p && at_c > err_c);
        opposite && at_p.abs() - err_p > 1.5 * reach * e[0].abs().max(e[1].abs())
    })
}
