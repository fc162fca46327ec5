//! Exact orientation predicates on [`Point3`](super::Point3), thin wrappers over `robust`.
//!
//! Each returns the exact sign of its determinant as an [`Ordering`]: the `robust` crate's
//! adaptive-precision arithmetic makes the sign exact for finite inputs without overflow or
//! underflow (coordinates up to 1e100 in magnitude, see [`MAX_COORDINATE`]).
//!
//! ```
//! use kepler::geometry::{Point3, predicates::orient3d};
//! use std::cmp::Ordering;
//! let (a, b, c) = (Point3::new(0.0, 0.0, 0.0), Point3::new(1.0, 0.0, 0.0), Point3::new(0.0, 1.0, 0.0));
//! assert_eq!(orient3d(&a, &b, &c, &Point3::new(0.0, 0.0, -1.0)), Ordering::Greater);
//! assert_eq!(orient3d(&a, &b, &c, &Point3::new(0.3, 0.3, 0.0)), Ordering::Equal);
//! ```

use super::exact::{product_terms, sum_sign, two_sum};
use super::{Point3, Vector3};
use robust::{Coord, Coord3D};
use std::cmp::Ordering;

/// The largest coordinate magnitude the engine accepts: beyond it the products inside the
/// predicates could overflow and signs would no longer be exact.
///
/// ```
/// assert_eq!(kepler::geometry::predicates::MAX_COORDINATE, 1e100);
/// ```
pub const MAX_COORDINATE: f64 = 1e100;

fn sign(v: f64) -> Ordering {
    v.partial_cmp(&0.0).unwrap_or(Ordering::Equal)
}

/// Exact sign of the orientation of `d` against the plane through `a`, `b`, `c`: `Greater`
/// when `d` lies below the plane, where "below" means `a`, `b`, `c` appear counter-clockwise
/// seen from above (Shewchuk's convention), `Equal` when the four points are coplanar.
///
/// ```
/// use kepler::geometry::{Point3, predicates::orient3d};
/// use std::cmp::Ordering;
/// let o = Point3::origin();
/// let (x, y) = (Point3::new(1.0, 0.0, 0.0), Point3::new(0.0, 1.0, 0.0));
/// assert_eq!(orient3d(&o, &x, &y, &Point3::new(0.0, 0.0, 1.0)), Ordering::Less);
/// ```
pub fn orient3d(a: &Point3, b: &Point3, c: &Point3, d: &Point3) -> Ordering {
    let p = |q: &Point3| Coord3D {
        x: q.x,
        y: q.y,
        z: q.z,
    };
    sign(robust::orient3d(p(a), p(b), p(c), p(d)))
}

/// Exact sign of the 2-D orientation of `(a, b, c)`, each given as `[x, y]`: `Greater` when
/// counter-clockwise, `Less` when clockwise, `Equal` when collinear.
///
/// ```
/// use kepler::geometry::predicates::orient2d;
/// use std::cmp::Ordering;
/// assert_eq!(orient2d([0.0, 0.0], [1.0, 0.0], [0.0, 1.0]), Ordering::Greater);
/// assert_eq!(orient2d([0.0, 0.0], [1.0, 1.0], [2.0, 2.0]), Ordering::Equal);
/// ```
pub fn orient2d(a: [f64; 2], b: [f64; 2], c: [f64; 2]) -> Ordering {
    let p = |q: [f64; 2]| Coord { x: q[0], y: q[1] };
    sign(robust::orient2d(p(a), p(b), p(c)))
}

/// The projection of `p` that drops coordinate `axis` (0, 1 or 2), keeping the other two in
/// cyclic order so that orientations in the projection match the sign of the dropped normal
/// component: dropping z gives (x, y), dropping x gives (y, z), dropping y gives (z, x).
///
/// ```
/// use kepler::geometry::{Point3, predicates::project};
/// assert_eq!(project(&Point3::new(1.0, 2.0, 3.0), 1), [3.0, 1.0]);
/// ```
pub fn project(p: &Point3, axis: usize) -> [f64; 2] {
    match axis {
        0 => [p.y, p.z],
        1 => [p.z, p.x],
        _ => [p.x, p.y],
    }
}

/// Exact sign of `orient3d(a, b, c, q)` for the point `q` at infinity in direction `u`: the
/// side of the plane through `a`, `b`, `c` towards which `u` points (`Greater` when `u` points
/// below it, in [`orient3d`]'s sense), `Equal` when the plane is parallel to `u`. It is the
/// sign of `-det[a - c, b - c, u]`, the limit of `orient3d(a, b, c, c + λu)` as λ grows.
///
/// Used for orthographic views, whose eye is such a point at infinity. Written by hand because
/// `robust` has no predicate with a direction: a floating-point filter decides almost every
/// call, and an exact expansion ([`sum_sign`]) the rest; a `u` along a coordinate axis reduces
/// to `robust`'s `orient2d`.
///
/// ```
/// use kepler::geometry::{Point3, Vector3, predicates::orient3d_at_infinity};
/// use std::cmp::Ordering;
/// let (a, b, c) = (Point3::new(0.0, 0.0, 0.0), Point3::new(1.0, 0.0, 0.0), Point3::new(0.0, 1.0, 0.0));
/// assert_eq!(orient3d_at_infinity(&a, &b, &c, &Vector3::new(0.1, 0.2, -1.0)), Ordering::Greater);
/// assert_eq!(orient3d_at_infinity(&a, &b, &c, &Vector3::new(1.0, 1.0, 0.0)), Ordering::Equal);
/// ```
pub fn orient3d_at_infinity(a: &Point3, b: &Point3, c: &Point3, u: &Vector3) -> Ordering {
    if let Some(k) = single_axis(&[u.x, u.y, u.z]) {
        // det[a - c, b - c, u_k e_k] = u_k (the k-th component of (a - c) x (b - c)).
        let o = orient2d(project(a, k), project(b, k), project(c, k));
        return if u[k] > 0.0 { o.reverse() } else { o };
    }
    let r1 = a - c;
    let r2 = b - c;
    let value = r1.dot(&r2.cross(u));
    let (p, q, w) = (r1.map(f64::abs), r2.map(f64::abs), u.map(f64::abs));
    let permanent = p.x * (q.y * w.z + q.z * w.y)
        + p.y * (q.x * w.z + q.z * w.x)
        + p.z * (q.x * w.y + q.y * w.x);
    let bound = 16.0 * (f64::EPSILON / 2.0) * permanent + f64::MIN_POSITIVE;
    if value > bound {
        return Ordering::Less;
    }
    if value < -bound {
        return Ordering::Greater;
    }
    exact_direction_det(a, b, c, u).reverse()
}

/// The exact sign of `det[a - c, b - c, u]` from its expansion (the filter's fallback).
#[cold]
#[inline(never)]
fn exact_direction_det(a: &Point3, b: &Point3, c: &Point3, u: &Vector3) -> Ordering {
    const PERMUTATIONS: [([usize; 3], f64); 6] = [
        ([0, 1, 2], 1.0),
        ([1, 2, 0], 1.0),
        ([2, 0, 1], 1.0),
        ([0, 2, 1], -1.0),
        ([2, 1, 0], -1.0),
        ([1, 0, 2], -1.0),
    ];
    let diff = |p: &Point3, i: usize| {
        let (s, e) = two_sum(p[i], -c[i]);
        [s, e]
    };
    let mut terms = Vec::with_capacity(96);
    let mut pair = Vec::with_capacity(8);
    for ([i, j, k], sign) in PERMUTATIONS {
        pair.clear();
        product_terms(&diff(a, i), &diff(b, j), &mut pair);
        product_terms(&pair, &[sign * u[k]], &mut terms);
    }
    sum_sign(&terms)
}

/// Exact sign of `orient2d(a, b, q)` for the point `q` at infinity in direction `u`: which
/// side of `u` the vector `a - b` lies on (`Greater` when `(a, b, q)` turn counter-clockwise),
/// the sign of `-det[a - b, u]`.
///
/// ```
/// use kepler::geometry::predicates::orient2d_at_infinity;
/// use std::cmp::Ordering;
/// // Looking from b = (0, 0) along +y, a = (1, 0) lies to the right: clockwise.
/// assert_eq!(orient2d_at_infinity([1.0, 0.0], [0.0, 0.0], [0.0, 1.0]), Ordering::Less);
/// assert_eq!(orient2d_at_infinity([0.0, 3.0], [0.0, 0.0], [0.0, 1.0]), Ordering::Equal);
/// ```
pub fn orient2d_at_infinity(a: [f64; 2], b: [f64; 2], u: [f64; 2]) -> Ordering {
    // det[a - b, u] = (a - b)_x u_y - (a - b)_y u_x.
    let cmp = |x: f64, y: f64| x.partial_cmp(&y).unwrap_or(Ordering::Equal);
    match (u[0] == 0.0, u[1] == 0.0) {
        (true, true) => return Ordering::Equal,
        (true, false) => return cmp(a[0], b[0]).reverse_if(u[1] > 0.0),
        (false, true) => return cmp(a[1], b[1]).reverse_if(u[0] < 0.0),
        (false, false) => {}
    }
    let (dx, ex) = two_sum(a[0], -b[0]);
    let (dy, ey) = two_sum(a[1], -b[1]);
    let mut terms = Vec::with_capacity(8);
    product_terms(&[dx, ex], &[u[1]], &mut terms);
    product_terms(&[dy, ey], &[-u[0]], &mut terms);
    sum_sign(&terms).reverse()
}

/// `reverse` when a condition holds: the sign of a product with a factor of known sign.
trait ReverseIf {
    fn reverse_if(self, condition: bool) -> Self;
}

impl ReverseIf for Ordering {
    #[inline]
    fn reverse_if(self, condition: bool) -> Self {
        if condition { self.reverse() } else { self }
    }
}

/// The axis `k` when `v` has exactly one nonzero component, `v[k]`.
#[inline]
fn single_axis(v: &[f64; 3]) -> Option<usize> {
    match (v[0] != 0.0, v[1] != 0.0, v[2] != 0.0) {
        (true, false, false) => Some(0),
        (false, true, false) => Some(1),
        (false, false, true) => Some(2),
        _ => None,
    }
}

/// Whether the three points are collinear, decided exactly (all three coordinate-plane
/// projections are collinear).
///
/// ```
/// use kepler::geometry::{Point3, predicates::collinear};
/// let a = Point3::new(0.0, 0.0, 0.0);
/// assert!(collinear(&a, &Point3::new(1.0, 2.0, 3.0), &Point3::new(2.0, 4.0, 6.0)));
/// assert!(!collinear(&a, &Point3::new(1.0, 2.0, 3.0), &Point3::new(2.0, 4.0, 6.5)));
/// ```
pub fn collinear(a: &Point3, b: &Point3, c: &Point3) -> bool {
    (0..3).all(|k| orient2d(project(a, k), project(b, k), project(c, k)) == Ordering::Equal)
}

/// Whether the triangle `t` meets the *open* box `b` (its interior), decided exactly.
///
/// By the separating-axis theorem, a triangle and a box have disjoint interiors exactly when
/// one of these weakly separates them: a coordinate axis, the triangle's plane, or (for the
/// nine edge-by-axis directions) a line through an edge of the triangle's projection along a
/// coordinate axis, with the projected box on its far side. Each test is a comparison,
/// an `orient3d` or an `orient2d` on input coordinates, so the answer is exact. Touching the
/// box's boundary does not count as meeting it. The box must have positive volume and the
/// triangle must not be degenerate (collinear).
///
/// ```
/// use kepler::geometry::{Aabb, Point3, predicates::triangle_meets_open_box};
/// let b = Aabb::new(Point3::new(0.0, 0.0, 0.0), Point3::new(1.0, 1.0, 1.0));
/// let touching = [Point3::new(1.0, 0.0, 0.0), Point3::new(1.0, 1.0, 0.0), Point3::new(1.0, 0.0, 1.0)];
/// assert!(!triangle_meets_open_box(&touching, &b));
/// let piercing = [Point3::new(0.5, 0.5, -1.0), Point3::new(0.5, 0.5, 2.0), Point3::new(3.0, 3.0, 0.5)];
/// assert!(triangle_meets_open_box(&piercing, &b));
/// ```
pub fn triangle_meets_open_box(t: &[Point3; 3], b: &super::Aabb) -> bool {
    // Coordinate axes.
    for k in 0..3 {
        if t.iter().all(|p| p[k] <= b.min[k]) || t.iter().all(|p| p[k] >= b.max[k]) {
            return false;
        }
    }
    let corners = b.corners();
    // The triangle's plane (skipped for a degenerate triangle, whose orient3d vanishes).
    if !collinear(&t[0], &t[1], &t[2]) {
        let signs = corners.map(|q| orient3d(&t[0], &t[1], &t[2], &q));
        if signs.iter().all(|&s| s != Ordering::Less)
            || signs.iter().all(|&s| s != Ordering::Greater)
        {
            return false;
        }
    }
    // Edge lines of the projections along each axis.
    for k in 0..3 {
        let p = t.map(|q| project(&q, k));
        let rect = [0usize, 1, 2, 3].map(|i| {
            let q = corners[match k {
                0 => [0, 2, 4, 6][i],
                1 => [0, 1, 4, 5][i],
                _ => [0, 1, 2, 3][i],
            }];
            project(&q, k)
        });
        let area = orient2d(p[0], p[1], p[2]);
        for e in 0..3 {
            let (u, v, w) = (p[e], p[(e + 1) % 3], p[(e + 2) % 3]);
            if u == v {
                continue;
            }
            let beyond = |side: Ordering| {
                rect.iter()
                    .all(|&q| matches!(orient2d(u, v, q), o if o == side || o == Ordering::Equal))
            };
            let separated = if area == Ordering::Equal {
                // The projection is a segment: either side of its line separates.
                beyond(Ordering::Less) || beyond(Ordering::Greater)
            } else {
                beyond(orient2d(u, v, w).reverse())
            };
            if separated {
                return false;
            }
        }
    }
    true
}
