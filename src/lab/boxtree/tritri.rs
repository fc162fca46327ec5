//! Whether two closed triangles in space share a point, decided exactly with `orient3d` (and
//! `orient2d` when they are coplanar), degenerate (collinear) triangles included.
//!
//! For two proper triangles A and B not in one plane, every common point lies on both planes,
//! so A ∩ B = (A ∩ plane B) ∩ (B ∩ plane A): two intervals of the planes' common line L. Name
//! `p` a vertex of A strictly on one side of plane B with the other two, `e` and `e'`, on the
//! other side or on it (if A only touches plane B at a vertex, `e = e'` is that vertex and `p`
//! either other one): A ∩ plane B is the segment between the crossings of the edges `pe` and
//! `pe'`. Likewise `q`, `f`, `f'` for B. For X on edge `pe` and Y on edge `qf`, both on L,
//!
//!   det(e − p, f − q, q − p) = μ · det(e − p, f − q, d) = −μ (n_B·(e − p)) (n_A·(f − q)),
//!
//! where `Y − X = μ d` with `d = n_A × n_B` (the components of `q − p` along the two edges
//! drop out, and `e − p` is orthogonal to `n_A`). The last two factors have the signs of `p`
//! against plane B and of `q` against plane A, the same for all four pairs; the left side is
//! `orient3d(e, f, q, p)`. So the intervals are disjoint (every Y strictly after every X, or
//! before) exactly when the four signs of `orient3d(e|e', f|f', q, p)` are all positive or all
//! negative: four more `orient3d`s after the six that place the vertices.
//!
//! Coplanar triangles, and a segment (a collinear triangle) in the other's plane, are compared
//! in projections: two sets in one plane meet exactly when their projections along all three
//! coordinate axes meet (one axis is not parallel to the plane, and projecting along it is
//! one-to-one there). A segment against a proper triangle crossing its plane, and two
//! segments, are the usual `orient3d` tests.
//!
//! ```
//! use kepler::lab::boxtree::tritri::triangles_meet;
//! use kepler::geometry::Point3;
//! let p = |x, y, z| Point3::new(x, y, z);
//! let floor = [p(0.0, 0.0, 0.0), p(4.0, 0.0, 0.0), p(0.0, 4.0, 0.0)];
//! let piercing = [p(1.0, 1.0, -1.0), p(1.0, 1.0, 1.0), p(3.0, 3.0, 1.0)];
//! let touching = [p(4.0, 0.0, 0.0), p(5.0, 0.0, 1.0), p(5.0, 1.0, 1.0)]; // at a vertex
//! let above = [p(1.0, 1.0, 1e-300), p(2.0, 1.0, 1.0), p(1.0, 2.0, 1.0)];
//! assert!(triangles_meet(&floor, &piercing));
//! assert!(triangles_meet(&floor, &touching));
//! assert!(!triangles_meet(&floor, &above));
//! ```

use crate::geometry::Point3;
use crate::geometry::polygon::segments_meet;
use crate::geometry::predicates::{collinear, orient2d, orient3d, project};
use std::cmp::Ordering;

/// Whether the closed triangles `a` and `b` share a point, exactly.
///
/// ```
/// use kepler::lab::boxtree::tritri::triangles_meet;
/// use kepler::geometry::Point3;
/// let p = |x, y, z| Point3::new(x, y, z);
/// let t = [p(0.0, 0.0, 0.0), p(2.0, 0.0, 0.0), p(0.0, 2.0, 0.0)];
/// // Coplanar: overlapping, touching along an edge, apart.
/// assert!(triangles_meet(&t, &[p(1.0, 0.0, 0.0), p(3.0, 0.0, 0.0), p(1.0, 0.5, 0.0)]));
/// assert!(triangles_meet(&t, &[p(2.0, 0.0, 0.0), p(0.0, 2.0, 0.0), p(2.0, 2.0, 0.0)]));
/// assert!(!triangles_meet(&t, &[p(2.0, 0.1, 0.0), p(0.1, 2.0, 0.0), p(2.0, 2.0, 0.0)]));
/// // A degenerate triangle (a segment) through t, and one beside it.
/// assert!(triangles_meet(&t, &[p(0.5, 0.5, -1.0), p(0.5, 0.5, 0.0), p(0.5, 0.5, 1.0)]));
/// assert!(!triangles_meet(&t, &[p(1.5, 1.5, -1.0), p(1.5, 1.5, 0.0), p(1.5, 1.5, 1.0)]));
/// ```
pub fn triangles_meet(a: &[Point3; 3], b: &[Point3; 3]) -> bool {
    match (
        collinear(&a[0], &a[1], &a[2]),
        collinear(&b[0], &b[1], &b[2]),
    ) {
        (false, false) => proper(a, b),
        (true, false) => segment_meets_triangle(&extremes(a), b),
        (false, true) => segment_meets_triangle(&extremes(b), a),
        (true, true) => segments_meet_3d(&extremes(a), &extremes(b)),
    }
}

/// Two triangles with positive area (see the module documentation).
fn proper(a: &[Point3; 3], b: &[Point3; 3]) -> bool {
    let against_a = b.map(|q| orient3d(&a[0], &a[1], &a[2], &q));
    if one_strict_side(&against_a) {
        return false;
    }
    if against_a.iter().all(|&s| s == Ordering::Equal) {
        return coplanar(a, b);
    }
    let against_b = a.map(|q| orient3d(&b[0], &b[1], &b[2], &q));
    if one_strict_side(&against_b) {
        return false;
    }
    let (p, ends_a) = lone_vertex(&against_b);
    let (q, ends_b) = lone_vertex(&against_a);
    let mut signs = ends_a
        .iter()
        .flat_map(|&e| ends_b.map(|f| orient3d(&a[e], &b[f], &b[q], &a[p])));
    let first = signs.next().unwrap_or(Ordering::Equal);
    !(first != Ordering::Equal && signs.all(|s| s == first))
}

/// Whether all three signs are positive, or all negative.
fn one_strict_side(signs: &[Ordering; 3]) -> bool {
    signs[0] != Ordering::Equal && signs.iter().all(|&s| s == signs[0])
}

/// For a triangle's vertex signs against a plane it meets (not all on one strict side, not
/// all on the plane): a vertex strictly on one side with the others on the other side or on
/// the plane, and those two; or, when the triangle touches the plane at a single vertex, a
/// vertex off the plane and that vertex twice.
fn lone_vertex(signs: &[Ordering; 3]) -> (usize, [usize; 2]) {
    for i in 0..3 {
        let (j, k) = ((i + 1) % 3, (i + 2) % 3);
        if signs[i] != Ordering::Equal && signs[j] != signs[i] && signs[k] != signs[i] {
            return (i, [j, k]);
        }
    }
    let z = signs
        .iter()
        .position(|&s| s == Ordering::Equal)
        .unwrap_or(0);
    ((z + 1) % 3, [z, z])
}

/// Two coplanar triangles (either possibly degenerate): their projections along all three
/// axes meet.
fn coplanar(a: &[Point3; 3], b: &[Point3; 3]) -> bool {
    (0..3).all(|k| triangles_meet_2d(&a.map(|p| project(&p, k)), &b.map(|p| project(&p, k))))
}

/// Whether two closed plane triangles (possibly degenerate) meet: an edge of one meets an edge
/// of the other, or one holds a vertex of the other.
fn triangles_meet_2d(a: &[[f64; 2]; 3], b: &[[f64; 2]; 3]) -> bool {
    let edges_meet =
        (0..3).any(|i| (0..3).any(|j| segments_meet(a[i], a[(i + 1) % 3], b[j], b[(j + 1) % 3])));
    edges_meet || holds(a, b[0]) || holds(b, a[0])
}

/// Whether the plane triangle `t` has positive area and holds `p` (closed).
fn holds(t: &[[f64; 2]; 3], p: [f64; 2]) -> bool {
    let turn = orient2d(t[0], t[1], t[2]);
    turn != Ordering::Equal
        && (0..3).all(|i| {
            let s = orient2d(t[i], t[(i + 1) % 3], p);
            s == turn || s == Ordering::Equal
        })
}

/// The two extreme points of three collinear points (their hull): along a coordinate in which
/// they differ, the order on the line is the order of that coordinate.
fn extremes(t: &[Point3; 3]) -> [Point3; 2] {
    let k = (0..3)
        .find(|&k| t[0][k] != t[1][k] || t[0][k] != t[2][k])
        .unwrap_or(0);
    let lo = t
        .iter()
        .min_by(|p, q| p[k].total_cmp(&q[k]))
        .unwrap_or(&t[0]);
    let hi = t
        .iter()
        .max_by(|p, q| p[k].total_cmp(&q[k]))
        .unwrap_or(&t[0]);
    [*lo, *hi]
}

/// A closed segment (possibly a point) against a proper triangle.
fn segment_meets_triangle(s: &[Point3; 2], t: &[Point3; 3]) -> bool {
    let [p, q] = s;
    let (sp, sq) = (
        orient3d(&t[0], &t[1], &t[2], p),
        orient3d(&t[0], &t[1], &t[2], q),
    );
    if sp == sq && sp != Ordering::Equal {
        return false;
    }
    if sp == Ordering::Equal && sq == Ordering::Equal {
        return coplanar(&[*p, *q, *q], t);
    }
    // The segment crosses the plane (p ≠ q): through the triangle when the line's sides of
    // its three edges are not mixed.
    let sides = [0, 1, 2].map(|i| orient3d(p, q, &t[i], &t[(i + 1) % 3]));
    !(sides.contains(&Ordering::Greater) && sides.contains(&Ordering::Less))
}

/// Two closed segments (possibly points) in space: coplanar, and meeting in all three
/// projections.
fn segments_meet_3d(s: &[Point3; 2], t: &[Point3; 2]) -> bool {
    orient3d(&s[0], &s[1], &t[0], &t[1]) == Ordering::Equal
        && (0..3).all(|k| {
            segments_meet(
                project(&s[0], k),
                project(&s[1], k),
                project(&t[0], k),
                project(&t[1], k),
            )
        })
}
