//! Exact classification of a point against a closed mesh: inside, outside or on the boundary.
//!
//! The leaf test of Franklin's INCLUDE. A vertical ray from the point counts the triangles it
//! crosses; the point is perturbed symbolically by `(ε, ε²)` in x and y, so the ray never
//! passes through an edge or a vertex and every crossing is counted exactly once, with no
//! second ray and no epsilon. A point lying on a triangle (decided exactly) is on the
//! boundary.

use super::{Mesh, TriangleTree};
use crate::geometry::Point3;
use crate::geometry::predicates::{orient2d, orient3d, project};
use std::cmp::Ordering;

/// Where a point lies with respect to a closed mesh.
///
/// ```
/// use kepler::{mesh::{Containment, TriangleTree, classify_point}, geometry::Point3};
/// let cube = kepler::solids::cube(2.0).unwrap();
/// let tree = TriangleTree::new(&cube);
/// assert_eq!(classify_point(&tree, &Point3::new(0.0, 0.0, 0.0)), Containment::Inside);
/// assert_eq!(classify_point(&tree, &Point3::new(1.0, 1.0, 0.0)), Containment::Boundary);
/// assert_eq!(classify_point(&tree, &Point3::new(1.0, 1.0, 1.5)), Containment::Outside);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
pub enum Containment {
    /// Strictly inside.
    Inside,
    /// Strictly outside.
    Outside,
    /// On a face, edge or vertex.
    Boundary,
}

/// Classifies `p` against the closed mesh whose triangles are in `tree`, exactly. The mesh
/// must be closed (see [`Mesh::topology`]); its orientation does not matter.
///
/// ```
/// use kepler::{mesh::{Containment, TriangleTree, classify_point}, geometry::Point3};
/// // Points exactly above a vertex and an edge of the cube: the perturbation decides.
/// let tree = TriangleTree::new(&kepler::solids::cube(2.0).unwrap());
/// assert_eq!(classify_point(&tree, &Point3::new(1.0, 0.0, -5.0)), Containment::Outside);
/// assert_eq!(classify_point(&tree, &Point3::new(0.0, 0.0, 0.999)), Containment::Inside);
/// ```
pub fn classify_point(tree: &TriangleTree, p: &Point3) -> Containment {
    classify_among(tree.above(p).map(|(_, t)| t), p)
}

/// Classifies `p` against `mesh` by testing every triangle (no tree): the brute-force form,
/// for one-off queries and as a reference.
///
/// ```
/// use kepler::{mesh::{Containment, classify_point_brute_force}, geometry::Point3};
/// let cube = kepler::solids::cube(2.0).unwrap();
/// assert_eq!(classify_point_brute_force(&cube, &Point3::new(0.5, 0.5, 0.5)), Containment::Inside);
/// ```
pub fn classify_point_brute_force(mesh: &Mesh, p: &Point3) -> Containment {
    classify_among((0..mesh.triangles().len()).map(|i| mesh.triangle(i)), p)
}

/// Classifies `p` from the triangles of a closed mesh that the upward vertical ray from `p`
/// can meet: the parity of the perturbed ray's crossings, or `Boundary` as soon as `p` lies on
/// one. `triangles` must include every triangle whose closed bounding box contains `p` or lies
/// above it in its column (more do no harm); a spatial index picks them, as
/// [`classify_point`] does with an R-tree and INCLUDE's projection grid with a 2-D grid.
///
/// ```
/// use kepler::{mesh::{Containment, classify_among}, geometry::Point3};
/// let cube = kepler::solids::cube(2.0).unwrap();
/// let all = (0..cube.triangles().len()).map(|t| cube.triangle(t));
/// assert_eq!(classify_among(all, &Point3::new(0.0, 1.0, 0.0)), Containment::Boundary);
/// ```
pub fn classify_among(triangles: impl Iterator<Item = [Point3; 3]>, p: &Point3) -> Containment {
    let mut crossings = 0usize;
    for t in triangles {
        if on_triangle(&t, p) {
            return Containment::Boundary;
        }
        if crosses_above(&t, p) {
            crossings += 1;
        }
    }
    if crossings % 2 == 1 {
        Containment::Inside
    } else {
        Containment::Outside
    }
}

/// Whether `p` lies on the closed triangle `t`, exactly.
fn on_triangle(t: &[Point3; 3], p: &Point3) -> bool {
    let inside_box = (0..3).all(|k| {
        let lo = t[0][k].min(t[1][k]).min(t[2][k]);
        let hi = t[0][k].max(t[1][k]).max(t[2][k]);
        lo <= p[k] && p[k] <= hi
    });
    if !inside_box || orient3d(&t[0], &t[1], &t[2], p) != Ordering::Equal {
        return false;
    }
    // Coplanar: test in a coordinate projection where the triangle is not degenerate.
    (0..3).any(|k| {
        let q = t.map(|v| project(&v, k));
        let s = orient2d(q[0], q[1], q[2]);
        if s == Ordering::Equal {
            return false;
        }
        let pp = project(p, k);
        (0..3).all(|e| orient2d(q[e], q[(e + 1) % 3], pp) != s.reverse())
    })
}

/// Whether the vertical line through `p`, moved by the symbolic perturbation `(ε, ε²)` in x
/// and y, passes through triangle `t` (through its interior: the perturbation keeps it off
/// edges and vertices; a vertical triangle is never crossed). The parity of these crossings
/// above a point is what [`classify_among`] counts.
///
/// ```
/// use kepler::{mesh::crosses_column, geometry::Point3};
/// let t = [Point3::new(0.0, 0.0, 0.0), Point3::new(2.0, 0.0, 1.0), Point3::new(0.0, 2.0, 5.0)];
/// assert!(crosses_column(&t, 0.5, 0.5));
/// assert!(!crosses_column(&t, 1.5, 1.5));
/// // On the edge from (0,0) to (2,0): the perturbation moves the line to +y, inside.
/// assert!(crosses_column(&t, 1.0, 0.0));
/// ```
pub fn crosses_column(t: &[Point3; 3], x: f64, y: f64) -> bool {
    column_side(t, &Point3::new(x, y, 0.0)).is_some()
}

/// The turning sign of `t`'s projection when the perturbed vertical line through `p` passes
/// through it, `None` when it does not.
#[inline]
fn column_side(t: &[Point3; 3], p: &Point3) -> Option<Ordering> {
    let s0 = perturbed_side(&t[0], &t[1], p);
    if s0 == Ordering::Equal
        || perturbed_side(&t[1], &t[2], p) != s0
        || perturbed_side(&t[2], &t[0], p) != s0
    {
        return None;
    }
    Some(s0)
}

/// The sign of `orient2d(a, b, p')` in the xy-plane for `p' = p + (ε, ε²)`.
fn perturbed_side(a: &Point3, b: &Point3, p: &Point3) -> Ordering {
    match orient2d([a.x, a.y], [b.x, b.y], [p.x, p.y]) {
        Ordering::Equal => a.y.total_cmp(&b.y).then(b.x.total_cmp(&a.x)),
        o => o,
    }
}

/// Whether the upward vertical ray from the perturbed point crosses triangle `t` strictly
/// above `p` (`p` is known not to lie on `t`).
fn crosses_above(t: &[Point3; 3], p: &Point3) -> bool {
    let Some(s0) = column_side(t, p) else {
        return false;
    };
    // The projection contains p' and turns with sign s0; p is below the plane when orient3d
    // (positive below a counter-clockwise-from-above triangle) has the same sign.
    orient3d(&t[0], &t[1], &t[2], p) == s0
}
