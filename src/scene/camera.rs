//! The camera a scene file may give: a view direction or an eye and a target, an up vector,
//! and orthographic or perspective projection.

use serde::Serialize;

/// How the scene is viewed.
///
/// ```
/// use kepler::scene::Camera;
/// let c = Camera::default();
/// assert_eq!(c.up, [0.0, 0.0, 1.0]);
/// assert!(matches!(c.projection, kepler::scene::Projection::Orthographic { .. }));
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Camera {
    /// Orthographic or perspective.
    pub projection: Projection,
    /// The direction that appears upward in the picture.
    pub up: [f64; 3],
}

/// The projection of a [`Camera`].
///
/// ```
/// use kepler::scene::Projection;
/// let p = Projection::Perspective { eye: [0.0, -10.0, 0.0], target: [0.0; 3], fov: 40.0 };
/// assert!(matches!(p, Projection::Perspective { fov, .. } if fov == 40.0));
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
#[serde(tag = "kind", rename_all = "lowercase")]
pub enum Projection {
    /// Parallel projection looking along `direction` (Franklin's standard view, from
    /// `(0, 0, +∞)`, is the direction `(0, 0, -1)`).
    Orthographic {
        /// The direction the camera looks along.
        direction: [f64; 3],
    },
    /// Central projection from `eye` towards `target` with a vertical field of view in degrees.
    Perspective {
        /// The eye point.
        eye: [f64; 3],
        /// The point looked at.
        target: [f64; 3],
        /// The vertical field of view in degrees.
        fov: f64,
    },
}

impl Default for Camera {
    /// The default isometric view: looking along `(-1, -1, -1)` with z up.
    fn default() -> Self {
        Camera {
            projection: Projection::Orthographic {
                direction: [-1.0, -1.0, -1.0],
            },
            up: [0.0, 0.0, 1.0],
        }
    }
}
