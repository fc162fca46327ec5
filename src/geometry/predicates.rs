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

use super::Point3;
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
