//! The cameras of the stiff scenes: generic orthographic views, exact ones for the edge-on
//! family, and perspective views.

use super::choices::Choices;
use crate::scene::{Camera, Projection};

/// View directions for the generic orthographic views: from the front (`+y`), above and to a
/// side; not dyadic, so that no difference of two of the scenes' (dyadic) vertices is
/// parallel to one, and no edge is seen end-on by chance.
pub(super) const GENERIC_DIRECTIONS: [[f64; 3]; 5] = [
    [-0.3, 1.0, -0.45],
    [0.35, 1.0, -0.55],
    [-0.6, 1.0, -0.35],
    [0.55, 1.0, -0.7],
    [-0.15, 1.0, -0.8],
];

/// Exact (dyadic) view directions for the edge-on family.
pub(super) const EXACT_DIRECTIONS: [[f64; 3]; 4] = [
    [-1.0, 2.0, -0.5],
    [0.5, 2.0, -0.75],
    [-0.75, 2.0, -1.0],
    [1.0, 2.0, -0.5],
];

/// An orthographic camera along one of [`GENERIC_DIRECTIONS`], `z` up.
pub(super) fn generic_view(rng: &mut Choices) -> Camera {
    Camera {
        projection: Projection::Orthographic {
            direction: rng.pick(&GENERIC_DIRECTIONS),
        },
        up: [0.0, 0.0, 1.0],
    }
}

/// A perspective camera from `eye` at `target`, `z` up, with a field of view of 40 degrees.
pub(super) fn perspective(eye: [f64; 3], target: [f64; 3]) -> Camera {
    Camera {
        projection: Projection::Perspective {
            eye,
            target,
            fov: 40.0,
        },
        up: [0.0, 0.0, 1.0],
    }
}
