//! Placement: the Hausdorff distance between two drawings' vertices, and the ulps of a
//! drawing's largest coordinate that tell a rounding apart from a blunder.

use crate::hidden::Drawing;
use rstar::RTree;

pub(super) fn finite_points(drawing: &Drawing) -> impl Iterator<Item = [f64; 2]> + '_ {
    drawing
        .polylines
        .iter()
        .flat_map(|p| p.points.iter().copied())
        .filter(|p| p[0].is_finite() && p[1].is_finite())
}

pub(super) fn largest_magnitude(drawing: &Drawing) -> f64 {
    finite_points(drawing).fold(0.0, |m, p| m.max(p[0].abs()).max(p[1].abs()))
}

/// The spacing of `f64` just above `x >= 0` (just below it for the largest finite `f64`).
pub(super) fn ulp(x: f64) -> f64 {
    if x == f64::MAX {
        x - x.next_down()
    } else {
        x.next_up() - x
    }
}

/// The symmetric Hausdorff distance between the drawings' vertex sets.
pub(super) fn hausdorff(a: &Drawing, b: &Drawing) -> f64 {
    let count = |d: &Drawing| d.polylines.iter().map(|p| p.points.len()).sum::<usize>();
    let (na, nb) = (count(a), count(b));
    if na == 0 && nb == 0 {
        return 0.0;
    }
    let (fa, fb) = (finite_points(a).count(), finite_points(b).count());
    if na == 0 || nb == 0 || fa < na || fb < nb {
        return f64::INFINITY;
    }
    directed_hausdorff(a, b).max(directed_hausdorff(b, a))
}

/// The largest distance from a vertex of `from` to the nearest vertex of `to` (both
/// nonempty, with finite coordinates).
pub(super) fn directed_hausdorff(from: &Drawing, to: &Drawing) -> f64 {
    let tree = RTree::bulk_load(finite_points(to).collect());
    finite_points(from)
        .map(|p| {
            tree.nearest_neighbor(&p)
                .map_or(f64::INFINITY, |q| (p[0] - q[0]).hypot(p[1] - q[1]))
        })
        .fold(0.0, f64::max)
}
