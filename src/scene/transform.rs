//! Placement of an instance: scale, then rotate about x, y, z, then translate.

use nalgebra::{Matrix4, Vector3};
use serde::Serialize;

/// An instance's placement: non-uniform `scale`, then rotations by `rotate` degrees about the
/// x, then y, then z axis, then `translate`. Quarter turns are exact (cosines and sines of
/// multiples of 90° are taken as exactly 0 and ±1), so a box turned by 90° stays axis-aligned.
///
/// ```
/// use kepler::scene::Transform;
/// let t = Transform { rotate: [0.0, 0.0, 90.0], ..Transform::default() };
/// let p = t.matrix().transform_point(&nalgebra::Point3::new(1.0, 0.0, 0.0));
/// assert_eq!((p.x, p.y, p.z), (0.0, 1.0, 0.0));
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Transform {
    /// Scale factors along x, y, z (negative mirrors).
    pub scale: [f64; 3],
    /// Rotation angles in degrees about x, y, z, applied in that order.
    pub rotate: [f64; 3],
    /// Translation.
    pub translate: [f64; 3],
}

impl Default for Transform {
    fn default() -> Self {
        Transform {
            scale: [1.0; 3],
            rotate: [0.0; 3],
            translate: [0.0; 3],
        }
    }
}

impl Transform {
    /// The 4×4 affine matrix `T · Rz · Ry · Rx · S`.
    ///
    /// ```
    /// use kepler::scene::Transform;
    /// let t = Transform { scale: [2.0, 1.0, 1.0], translate: [0.0, 0.0, 5.0], ..Transform::default() };
    /// assert_eq!(t.matrix()[(0, 0)], 2.0);
    /// assert_eq!(t.matrix()[(2, 3)], 5.0);
    /// ```
    pub fn matrix(&self) -> Matrix4<f64> {
        let axes = [Vector3::x_axis(), Vector3::y_axis(), Vector3::z_axis()];
        let mut m = Matrix4::new_nonuniform_scaling(&Vector3::from(self.scale));
        for (axis, &deg) in axes.iter().zip(&self.rotate) {
            m = rotation(axis, deg) * m;
        }
        Matrix4::new_translation(&Vector3::from(self.translate)) * m
    }

    /// Whether this is the identity.
    ///
    /// ```
    /// assert!(kepler::scene::Transform::default().is_identity());
    /// ```
    pub fn is_identity(&self) -> bool {
        *self == Transform::default()
    }
}

/// Rotation by `deg` degrees about a coordinate axis, exact for multiples of 90°.
fn rotation(axis: &nalgebra::Unit<Vector3<f64>>, deg: f64) -> Matrix4<f64> {
    let quarter = deg / 90.0;
    let (s, c) = if quarter == quarter.round() && quarter.abs() < 1e15 {
        match (quarter as i64).rem_euclid(4) {
            0 => (0.0, 1.0),
            1 => (1.0, 0.0),
            2 => (0.0, -1.0),
            _ => (-1.0, 0.0),
        }
    } else {
        deg.to_radians().sin_cos()
    };
    let (i, j) = if axis.x == 1.0 {
        (1, 2)
    } else if axis.y == 1.0 {
        (2, 0)
    } else {
        (0, 1)
    };
    let mut m = Matrix4::identity();
    m[(i, i)] = c;
    m[(j, j)] = c;
    m[(i, j)] = -s;
    m[(j, i)] = s;
    m
}
