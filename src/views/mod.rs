//! Views: where the eye is, and the exact predicates that ask what lies between a point and it.
//!
//! Franklin's algorithms look from his standard viewpoint `(0, 0, +∞)`. Any orthographic view
//! is that one turned, and a perspective view becomes an orthographic one under the projective
//! transform of [`View::matrix`], which keeps planes planar. Rounding that transform would
//! move every vertex, so the visibility tests are not done on transformed coordinates: a
//! projective transform preserves the sign of every orientation determinant (up to one global
//! sign), so `orient3d(a, b, c, eye)` in world coordinates, with the eye a point
//! ([`Eye::Point`]) or a point at infinity ([`Eye::Infinity`]), is exactly the view-space
//! test. The transform is only for drawing.
//!
//! [`Picture`] maps world points to the 2-D coordinates of a drawing, each rounded once from
//! its exact value; [`projected_area`] gives the exact area of a box's picture (Schmalstieg
//! and Tobler 1999).
//!
//! ```
//! use kepler::views::View;
//! use kepler::geometry::{Point3, Vector3};
//! let view = View::orthographic(Vector3::new(0.0, 0.0, -1.0), Vector3::new(0.0, 1.0, 0.0)).unwrap();
//! assert_eq!(view.to_view(&Point3::new(1.0, 2.0, 3.0)), Point3::new(1.0, 2.0, 3.0));
//! ```

use crate::geometry::exact::{accurate_sum, ldexp, two_product, unit_scaled};
use crate::geometry::kernel::Exponents;
use crate::geometry::kernel::Polynomial;
use crate::geometry::predicates::{
    Orient3d, Orient3dAtInfinity, Orientation, Side, orient2d, orient2d_at_infinity, orient3d,
    orient3d_at_infinity, project,
};
use crate::geometry::{Point3, Vector3, predicates::collinear};
use crate::scene::{Camera, Projection};
use nalgebra::Matrix4;
use std::cmp::Ordering;

mod picture;
pub mod projected_area;
mod window;
pub use picture::Picture;
pub use window::Window;

/// A view that cannot be built, or a scene it cannot picture: the views layer's error.
///
/// ```
/// use kepler::views::{View, ViewError};
/// use kepler::geometry::Vector3;
/// let e = View::orthographic(Vector3::zeros(), Vector3::z()).unwrap_err();
/// assert_eq!(e, ViewError::ZeroDirection);
/// assert_eq!(e.to_string(), "invalid view: the view direction is zero");
/// ```
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ViewError {
    /// The view direction is the zero vector.
    #[error("invalid view: the view direction is zero")]
    ZeroDirection,
    /// The up vector is zero or parallel to the view direction.
    #[error("invalid view: the up vector is zero or parallel to the view direction")]
    UpParallel,
    /// The eye and the target coincide.
    #[error("invalid view: the eye and the target are the same point")]
    EyeAtTarget,
    /// The field of view is not strictly between 0 and 180 degrees.
    #[error("invalid view: the field of view must be between 0 and 180 degrees, not {0}")]
    FieldOfView(f64),
    /// A coordinate is NaN or infinite.
    #[error("invalid view: view coordinates must be finite numbers")]
    NotFinite,
    /// View options that do not go together.
    #[error("invalid view: {0}")]
    Options(&'static str),
    /// A vertex of an object is not in front of a perspective eye, so the picture would be
    /// meaningless.
    #[error(
        "object '{object}': vertex {vertex} ({point:?}) is not in front of the eye; a \
         perspective picture needs the whole scene in front of it"
    )]
    NotInFront {
        /// The object's path.
        object: String,
        /// The vertex (0-based).
        vertex: usize,
        /// Its coordinates.
        point: Point3,
    },
}

/// Where the viewer is: a point (perspective) or a point at infinity (orthographic).
///
/// ```
/// use kepler::views::Eye;
/// use kepler::geometry::{Point3, Vector3};
/// use std::cmp::Ordering;
/// // Franklin's standard viewpoint (0, 0, +∞) is above the counter-clockwise triangle.
/// let eye = Eye::Infinity(Vector3::new(0.0, 0.0, 1.0));
/// let t = [Point3::new(0.0, 0.0, 0.0), Point3::new(1.0, 0.0, 0.0), Point3::new(0.0, 1.0, 0.0)];
/// assert_eq!(eye.orient3d(&t[0], &t[1], &t[2]), Ordering::Less);
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Eye {
    /// The eye point of a perspective view.
    Point(Point3),
    /// The eye of an orthographic view: at infinity in this direction (from the scene towards
    /// the viewer, the opposite of the view direction; [`View::orthographic`] scales it by a
    /// power of two, exactly, so that its largest component lies in `[1, 2)`).
    Infinity(Vector3),
}

impl Eye {
    /// Exact sign of `orient3d(a, b, c, eye)`: the side of the plane through `a`, `b`, `c` on
    /// which the eye lies, `Equal` when the plane passes through it (the face is edge-on).
    ///
    /// ```
    /// use kepler::views::Eye;
    /// use kepler::geometry::Point3;
    /// use std::cmp::Ordering;
    /// let eye = Eye::Point(Point3::new(0.0, 0.0, 5.0));
    /// let (a, b) = (Point3::new(0.0, 0.0, 0.0), Point3::new(1.0, 0.0, 0.0));
    /// assert_eq!(eye.orient3d(&a, &b, &Point3::new(0.0, 0.0, 1.0)), Ordering::Equal);
    /// ```
    #[inline]
    pub fn orient3d(&self, a: &Point3, b: &Point3, c: &Point3) -> Ordering {
        match self {
            Eye::Point(e) => orient3d(a, b, c, e),
            Eye::Infinity(u) => orient3d_at_infinity(a, b, c, u),
        }
    }

    /// Whether the segment `ab` points at the eye (the eye lies on its line), so that its
    /// picture is a single point. Exact.
    ///
    /// ```
    /// use kepler::{geometry::{Point3, Vector3}, views::Eye};
    /// let eye = Eye::Infinity(Vector3::z());
    /// assert!(eye.sees_end_on(&Point3::new(1.0, 2.0, 0.0), &Point3::new(1.0, 2.0, 5.0)));
    /// assert!(!eye.sees_end_on(&Point3::new(1.0, 2.0, 0.0), &Point3::new(1.0, 3.0, 5.0)));
    /// ```
    pub fn sees_end_on(&self, a: &Point3, b: &Point3) -> bool {
        self.perturbation(a, b) == Ordering::Equal
    }

    /// The determinant whose sign [`Eye::orient3d`] gives, as a
    /// [`Polynomial`](crate::geometry::kernel::Polynomial) (its estimate
    /// with a certified error bound, and its exact expansion).
    ///
    /// ```
    /// use kepler::{geometry::{Point3, Vector3, kernel::Polynomial}, views::Eye};
    /// let eye = Eye::Infinity(Vector3::z());
    /// let t = [Point3::new(0.0, 0.0, 0.0), Point3::new(1.0, 0.0, 0.0), Point3::new(0.0, 1.0, 0.0)];
    /// let det = eye.determinant(&t[0], &t[1], &t[2]);
    /// assert!(det.estimate().value < -det.estimate().bound);
    /// assert_eq!(det.expansion(), vec![-1.0]);
    /// ```
    #[inline]
    pub fn determinant(&self, a: &Point3, b: &Point3, c: &Point3) -> Orientation {
        match self {
            Eye::Point(e) => Orientation::Point(Orient3d([*a, *b, *c, *e])),
            Eye::Infinity(u) => Orientation::Infinity(Orient3dAtInfinity([*a, *b, *c], *u)),
        }
    }

    /// The sign of `orient3d(p', a, b, eye)` for `p'` the point `p` moved by the symbolic
    /// perturbation `(ε, ε², ε³)`: which side of the line of sight through `p'` the edge `ab`
    /// passes. It is `Equal` only when `a`, `b` and the eye are collinear (the edge points at
    /// the eye). Antisymmetric in `a` and `b`, so a line of sight that passes exactly through
    /// an edge shared by two triangles is counted in exactly one of them.
    ///
    /// The coefficient of `ε^(k+1)` is the orientation of `a`, `b` and the eye in the
    /// projection that drops axis `k` (see [`project`]).
    ///
    /// ```
    /// use kepler::views::Eye;
    /// use kepler::geometry::{Point3, Vector3};
    /// use std::cmp::Ordering;
    /// let eye = Eye::Infinity(Vector3::new(0.0, 0.0, 1.0));
    /// let (a, b) = (Point3::new(0.0, -1.0, 0.0), Point3::new(0.0, 1.0, 0.0));
    /// // p lies exactly below the edge; moved by +ε in x it passes on one side.
    /// let p = Point3::new(0.0, 0.0, -3.0);
    /// let s = eye.perturbed_orient3d(&p, &a, &b);
    /// assert_ne!(s, Ordering::Equal);
    /// assert_eq!(eye.perturbed_orient3d(&p, &b, &a), s.reverse());
    /// ```
    #[inline]
    pub fn perturbed_orient3d(&self, p: &Point3, a: &Point3, b: &Point3) -> Ordering {
        let exact = match self {
            Eye::Point(e) => orient3d(p, a, b, e),
            Eye::Infinity(u) => orient3d_at_infinity(p, a, b, u),
        };
        if exact != Ordering::Equal {
            return exact;
        }
        self.perturbation(a, b)
    }

    /// The first nonzero coefficient of the perturbation in [`Eye::perturbed_orient3d`].
    #[cold]
    fn perturbation(&self, a: &Point3, b: &Point3) -> Ordering {
        [0, 1, 2]
            .into_iter()
            .map(|k| match self {
                Eye::Point(e) => orient2d(project(a, k), project(b, k), project(e, k)),
                Eye::Infinity(u) => orient2d_at_infinity(
                    project(a, k),
                    project(b, k),
                    project(&Point3::from(*u), k),
                ),
            })
            .find(|&o| o != Ordering::Equal)
            .unwrap_or(Ordering::Equal)
    }
}

/// A view: an eye, the direction looked along, the up direction of the picture and, for a
/// perspective view, the vertical field of view.
///
/// ```
/// use kepler::views::{Eye, View};
/// use kepler::geometry::{Point3, Vector3};
/// let v = View::perspective(Point3::new(0.0, -10.0, 0.0), Point3::origin(), Vector3::z(), 40.0).unwrap();
/// assert_eq!(*v.eye(), Eye::Point(Point3::new(0.0, -10.0, 0.0)));
/// assert!(v.is_perspective());
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct View {
    eye: Eye,
    forward: Vector3,
    right: Vector3,
    up: Vector3,
    fov: Option<f64>,
    /// A perspective view's near clipping distance is `near · 2^near_exponent` (apart, so that
    /// the default near plane of an eye at an extreme distance neither overflows nor
    /// underflows, and scales exactly with the view).
    near: f64,
    /// See `near`.
    near_exponent: i32,
    /// A perspective view's picture width over its height.
    aspect: f64,
}

impl View {
    /// Franklin's standard view from `(0, 0, +∞)`: looking along `(0, 0, -1)` with `y` up, so
    /// that view coordinates are world coordinates.
    ///
    /// ```
    /// use kepler::views::View;
    /// use kepler::geometry::Point3;
    /// let p = Point3::new(1.5, -2.0, 7.0);
    /// assert_eq!(View::standard().to_view(&p), p);
    /// ```
    pub fn standard() -> View {
        View {
            eye: Eye::Infinity(Vector3::z()),
            forward: -Vector3::z(),
            right: Vector3::x(),
            up: Vector3::y(),
            fov: None,
            near: 0.0,
            near_exponent: 0,
            aspect: 1.0,
        }
    }

    /// An orthographic view looking along `direction`, with `up` pointing up in the picture.
    ///
    /// ```
    /// use kepler::views::{View, ViewError};
    /// use kepler::geometry::Vector3;
    /// let v = View::orthographic(Vector3::new(-1.0, -1.0, -1.0), Vector3::z()).unwrap();
    /// assert!(!v.is_perspective());
    /// let parallel = View::orthographic(Vector3::new(0.0, 0.0, -2.0), Vector3::z());
    /// assert_eq!(parallel.unwrap_err(), ViewError::UpParallel);
    /// ```
    pub fn orthographic(direction: Vector3, up: Vector3) -> Result<View, ViewError> {
        if !direction.iter().chain(up.iter()).all(|c| c.is_finite()) {
            return Err(ViewError::NotFinite);
        }
        if direction == Vector3::zeros() {
            return Err(ViewError::ZeroDirection);
        }
        let (forward, right, up) = frame(&direction, &up)?;
        // Scaled by a power of two (exactly) so that the predicates' products stay in range
        // for tiny or huge directions.
        Ok(View {
            eye: Eye::Infinity(-Vector3::from(unit_scaled(direction.into()))),
            forward,
            right,
            up,
            fov: None,
            near: 0.0,
            near_exponent: 0,
            aspect: 1.0,
        })
    }

    /// A perspective view from `eye` towards `target`, with `up` pointing up in the picture
    /// and a vertical field of view of `fov` degrees.
    ///
    /// ```
    /// use kepler::views::{View, ViewError};
    /// use kepler::geometry::{Point3, Vector3};
    /// let e = View::perspective(Point3::origin(), Point3::new(1.0, 0.0, 0.0), Vector3::z(), 180.0);
    /// assert_eq!(e.unwrap_err(), ViewError::FieldOfView(180.0));
    /// ```
    pub fn perspective(
        eye: Point3,
        target: Point3,
        up: Vector3,
        fov: f64,
    ) -> Result<View, ViewError> {
        let coordinates = eye.iter().chain(target.iter()).chain(up.iter());
        if !coordinates.chain([fov].iter()).all(|c| c.is_finite()) {
            return Err(ViewError::NotFinite);
        }
        if eye == target {
            return Err(ViewError::EyeAtTarget);
        }
        if !(fov > 0.0 && fov < 180.0) {
            return Err(ViewError::FieldOfView(fov));
        }
        // Halved first where the difference would overflow; the frame is only for drawing.
        let direction = if (target - eye).iter().all(|c| c.is_finite()) {
            target - eye
        } else {
            target.coords * 0.5 - eye.coords * 0.5
        };
        let (forward, right, up) = frame(&direction, &up)?;
        // The near plane at 1/1024 of the distance to the target, kept as a number near 1 and a
        // power of two (the distance's, twice it where the direction was halved).
        let scaled = unit_scaled(direction.into());
        let magnitude = direction.amax() / scaled.iter().fold(0.0f64, |m, c| m.max(c.abs()));
        let halved = i32::from(!(target - eye).iter().all(|c| c.is_finite()));
        let near = Vector3::from(scaled).norm() / 1024.0;
        let near_exponent = magnitude.log2().round() as i32 + halved;
        Ok(View {
            eye: Eye::Point(eye),
            forward,
            right,
            up,
            fov: Some(fov),
            near,
            near_exponent,
            aspect: 1.0,
        })
    }

    /// The view a scene file's camera describes.
    ///
    /// ```
    /// use kepler::{scene::Camera, views::View};
    /// let v = View::from_camera(&Camera::default()).unwrap();
    /// assert!(!v.is_perspective());
    /// ```
    pub fn from_camera(camera: &Camera) -> Result<View, ViewError> {
        let up = Vector3::from(camera.up);
        match camera.projection {
            Projection::Orthographic { direction } => View::orthographic(direction.into(), up),
            Projection::Perspective { eye, target, fov } => {
                View::perspective(eye.into(), target.into(), up, fov)
            }
        }
    }

    /// The same view of the scene scaled by `2^exponent` (see
    /// [`Scene::scaled`](crate::scene::Scene::scaled)): a perspective eye is scaled with it,
    /// exactly, and so is its near distance; directions, the frame and the field of view stay.
    ///
    /// ```
    /// use kepler::{geometry::{Point3, Vector3}, views::{Eye, View}};
    /// let v = View::perspective(Point3::new(0.0, 0.0, 3.0), Point3::origin(), Vector3::y(), 40.0).unwrap();
    /// assert_eq!(v.scaled(4).eye(), &Eye::Point(Point3::new(0.0, 0.0, 48.0)));
    /// ```
    pub fn scaled(&self, exponent: i32) -> View {
        let eye = match self.eye {
            Eye::Point(p) => Eye::Point(p.map(|c| ldexp(c, exponent))),
            Eye::Infinity(u) => Eye::Infinity(u),
        };
        View {
            eye,
            near_exponent: self.near_exponent + exponent,
            ..*self
        }
    }

    /// The same view clipped, when the scene is not wholly in front of a perspective eye, to a
    /// frustum with its near plane at `near` in front of the eye and a picture `aspect` times
    /// as wide as high (the field of view is vertical). An error unless both are positive and
    /// finite; no effect on an orthographic view.
    ///
    /// ```
    /// use kepler::{geometry::{Point3, Vector3}, views::View};
    /// let v = View::perspective(Point3::origin(), Point3::new(0.0, 10.0, 0.0), Vector3::z(), 90.0).unwrap();
    /// let f = v.with_clipping(0.5, 2.0).unwrap().frustum().unwrap();
    /// assert!(f.contains(&Point3::new(1.9, 1.0, 0.9)));
    /// assert!(!f.contains(&Point3::new(0.0, 0.25, 0.0))); // nearer than the near plane
    /// assert!(!f.contains(&Point3::new(2.1, 1.0, 0.0))); // beyond the right side
    /// ```
    pub fn with_clipping(self, near: f64, aspect: f64) -> Result<View, ViewError> {
        if !(near > 0.0 && near.is_finite() && aspect > 0.0 && aspect.is_finite()) {
            return Err(ViewError::Options(
                "the near distance and the aspect ratio must be positive numbers",
            ));
        }
        Ok(View {
            near,
            near_exponent: 0,
            aspect,
            ..self
        })
    }

    /// The frustum a perspective view clips to when the scene is not wholly in front of the
    /// eye (see [`with_clipping`](Self::with_clipping)); `None` for an orthographic view.
    ///
    /// ```
    /// use kepler::{geometry::{Point3, Vector3}, views::View};
    /// let v = View::perspective(Point3::new(0.0, 0.0, 5.0), Point3::origin(), Vector3::y(), 40.0).unwrap();
    /// assert!(v.frustum().unwrap().contains(&Point3::origin()));
    /// assert!(kepler::views::View::standard().frustum().is_none());
    /// ```
    pub fn frustum(&self) -> Option<Frustum> {
        let Eye::Point(eye) = self.eye else {
            return None;
        };
        let (f, r, u) = (self.forward, self.right, self.up);
        let [horizontal, vertical] = self.window()?;
        Some(Frustum {
            planes: [
                (eye, f, self.near()),
                (eye, r + f * horizontal, 0.0),
                (eye, f * horizontal - r, 0.0),
                (eye, u + f * vertical, 0.0),
                (eye, f * vertical - u, 0.0),
            ],
        })
    }

    /// A perspective view's near clipping distance (see [`with_clipping`](Self::with_clipping));
    /// zero for an orthographic view.
    ///
    /// ```
    /// use kepler::{geometry::{Point3, Vector3}, views::View};
    /// let v = View::perspective(Point3::origin(), Point3::new(0.0, 1024.0, 0.0), Vector3::z(), 40.0).unwrap();
    /// assert_eq!(v.near(), 1.0);
    /// assert_eq!(v.with_clipping(0.25, 1.5).unwrap().near(), 0.25);
    /// ```
    pub fn near(&self) -> f64 {
        ldexp(self.near, self.near_exponent)
    }

    /// The same view clipped to a picture `aspect` times as wide as high, with its near
    /// distance as it is (see [`with_clipping`](Self::with_clipping)). An error unless the
    /// aspect is positive and finite.
    ///
    /// ```
    /// use kepler::{geometry::{Point3, Vector3}, views::View};
    /// let far = 2f64.powi(1020);
    /// let v = View::perspective(Point3::new(far, far, far), Point3::origin(), Vector3::z(), 40.0).unwrap();
    /// let v = v.with_aspect(1.5).unwrap();
    /// assert!(v.near().is_finite() && v.near() > 0.0);
    /// assert_eq!(v.window().unwrap()[0] / v.window().unwrap()[1], 1.5);
    /// ```
    pub fn with_aspect(self, aspect: f64) -> Result<View, ViewError> {
        if !(aspect > 0.0 && aspect.is_finite()) {
            return Err(ViewError::Options(
                "the aspect ratio must be a positive number",
            ));
        }
        Ok(View { aspect, ..self })
    }

    /// The half-width and half-height of a perspective view's picture window at unit depth
    /// (the tangents of half the field of view, across and up); `None` for an orthographic
    /// view.
    ///
    /// ```
    /// use kepler::{geometry::{Point3, Vector3}, views::View};
    /// let v = View::perspective(Point3::origin(), Point3::new(0.0, 10.0, 0.0), Vector3::z(), 90.0).unwrap();
    /// let [h, v] = v.with_clipping(0.5, 2.0).unwrap().window().unwrap();
    /// assert!((h - 2.0).abs() < 1e-15 && (v - 1.0).abs() < 1e-15);
    /// ```
    pub fn window(&self) -> Option<[f64; 2]> {
        let vertical = (self.fov?.to_radians() / 2.0).tan();
        Some([vertical * self.aspect, vertical])
    }

    /// The binary exponents of the eye's coordinates, when it is a point (none for an eye at
    /// infinity, whose direction is normalised apart).
    ///
    /// ```
    /// use kepler::{geometry::{Point3, Vector3}, views::View};
    /// let v = View::perspective(Point3::new(0.0, 0.0, 8.0), Point3::origin(), Vector3::y(), 40.0).unwrap();
    /// assert_eq!((v.exponents().min, v.exponents().max), (3, 3));
    /// ```
    pub fn exponents(&self) -> Exponents {
        match &self.eye {
            Eye::Point(p) => Exponents::of(p.coords.as_slice()),
            Eye::Infinity(_) => Exponents::NONE,
        }
    }

    /// The eye.
    ///
    /// ```
    /// use kepler::views::{Eye, View};
    /// assert_eq!(*View::standard().eye(), Eye::Infinity(kepler::geometry::Vector3::z()));
    /// ```
    pub fn eye(&self) -> &Eye {
        &self.eye
    }

    /// Every number that defines the view, as bits (for fingerprints: two views with the
    /// same bits are the same view).
    pub(crate) fn bits(&self) -> Vec<u64> {
        let (tag, eye) = match self.eye {
            Eye::Point(p) => (0, p.coords),
            Eye::Infinity(u) => (1, u),
        };
        let vectors = [eye, self.forward, self.right, self.up];
        let mut bits = vec![tag];
        bits.extend(vectors.iter().flat_map(|v| v.iter().map(|c| c.to_bits())));
        bits.extend([self.fov.map_or(u64::MAX, f64::to_bits), self.near.to_bits()]);
        bits.extend([i64::from(self.near_exponent) as u64, self.aspect.to_bits()]);
        bits
    }

    /// A perspective view's vertical field of view in degrees (`None` for an orthographic
    /// view).
    ///
    /// ```
    /// use kepler::{geometry::{Point3, Vector3}, views::View};
    /// let v = View::perspective(Point3::new(0.0, -10.0, 0.0), Point3::origin(), Vector3::z(), 40.0).unwrap();
    /// assert_eq!(v.fov(), Some(40.0));
    /// assert_eq!(View::standard().fov(), None);
    /// ```
    pub fn fov(&self) -> Option<f64> {
        self.fov
    }

    /// Whether the view is a perspective one.
    ///
    /// ```
    /// assert!(!kepler::views::View::standard().is_perspective());
    /// ```
    pub fn is_perspective(&self) -> bool {
        matches!(self.eye, Eye::Point(_))
    }

    /// The unit vector the camera looks along.
    ///
    /// ```
    /// use kepler::{geometry::Vector3, views::View};
    /// assert_eq!(View::standard().forward(), Vector3::new(0.0, 0.0, -1.0));
    /// ```
    pub fn forward(&self) -> Vector3 {
        self.forward
    }

    /// The unit vectors pointing right and up in the picture.
    ///
    /// ```
    /// use kepler::{geometry::Vector3, views::View};
    /// assert_eq!(View::standard().right_up(), (Vector3::x(), Vector3::y()));
    /// ```
    pub fn right_up(&self) -> (Vector3, Vector3) {
        (self.right, self.up)
    }

    /// The 4×4 matrix from world to view coordinates: `x` right and `y` up in the picture, `z`
    /// increasing towards the viewer (as from Franklin's `(0, 0, +∞)`). Orthographic: a
    /// rotation. Perspective: a projective transform with the eye sent to infinity, `x` and
    /// `y` scaled so that the field of view spans `y` in `[-1, 1]`, and `z = -1/depth`; planes
    /// stay planes. For drawing only; decisions use [`Eye`]'s exact predicates.
    ///
    /// ```
    /// use kepler::views::View;
    /// assert_eq!(View::standard().matrix(), nalgebra::Matrix4::identity());
    /// ```
    #[rustfmt::skip]
    pub fn matrix(&self) -> Matrix4<f64> {
        let (r, u, f) = (self.right, self.up, self.forward);
        match (self.eye, self.fov) {
            (Eye::Point(e), Some(fov)) => {
                let k = 1.0 / (fov.to_radians() / 2.0).tan();
                let e = e.coords;
                Matrix4::new(
                    k * r.x, k * r.y, k * r.z, -k * r.dot(&e),
                    k * u.x, k * u.y, k * u.z, -k * u.dot(&e),
                    0.0, 0.0, 0.0, -1.0,
                    f.x, f.y, f.z, -f.dot(&e),
                )
            }
            _ => Matrix4::new(
                r.x, r.y, r.z, 0.0,
                u.x, u.y, u.z, 0.0,
                -f.x, -f.y, -f.z, 0.0,
                0.0, 0.0, 0.0, 1.0,
            ),
        }
    }

    /// The view coordinates of `p` (see [`View::matrix`]), computed once from `p`.
    ///
    /// ```
    /// use kepler::views::View;
    /// use kepler::geometry::{Point3, Vector3};
    /// let v = View::perspective(Point3::new(0.0, 0.0, 10.0), Point3::origin(), Vector3::y(), 90.0).unwrap();
    /// let q = v.to_view(&Point3::new(1.0, 2.0, 0.0));
    /// assert!((q.x - 0.1).abs() < 1e-15 && (q.y - 0.2).abs() < 1e-15 && (q.z + 0.1).abs() < 1e-15);
    /// ```
    pub fn to_view(&self, p: &Point3) -> Point3 {
        self.matrix().transform_point(p)
    }
}

/// The view options of the command line (`--view-dir`, `--up`, `--eye`, `--target`, `--fov`),
/// resolved against a scene file's camera: options given replace the camera's, and without
/// any the camera (or the default isometric view) is used.
///
/// `--view-dir` makes an orthographic view, `--eye` with `--target` a perspective one (field
/// of view from `--fov`, else the camera's, else 40 degrees). When no `--up` is given and the
/// camera's up vector is parallel to the view direction (looking straight down with z up),
/// `y` is up instead.
///
/// ```
/// use kepler::views::{ViewOptions, ViewError};
/// use kepler::geometry::Vector3;
/// let down = ViewOptions { view_dir: Some(Vector3::new(0.0, 0.0, -1.0)), ..Default::default() };
/// assert_eq!(down.resolve(None).unwrap(), kepler::views::View::standard());
/// let both = ViewOptions { view_dir: Some(Vector3::x()), eye: Some(Default::default()), ..Default::default() };
/// assert!(matches!(both.resolve(None), Err(ViewError::Options(_))));
/// ```
#[derive(Debug, Clone, Default, PartialEq)]
pub struct ViewOptions {
    /// The direction the camera looks along (orthographic).
    pub view_dir: Option<Vector3>,
    /// The direction that appears upward.
    pub up: Option<Vector3>,
    /// The eye point (perspective, with `target`).
    pub eye: Option<Point3>,
    /// The point looked at (perspective, with `eye`).
    pub target: Option<Point3>,
    /// The vertical field of view in degrees (perspective).
    pub fov: Option<f64>,
}

impl ViewOptions {
    /// The view these options describe over `camera` (a scene file's, if it has one).
    ///
    /// ```
    /// use kepler::{scene::{Camera, Projection}, views::ViewOptions, geometry::Point3};
    /// let camera = Camera { projection: Projection::Perspective { eye: [0.0, -9.0, 2.0], target: [0.0; 3], fov: 30.0 }, up: [0.0, 0.0, 1.0] };
    /// let wider = ViewOptions { fov: Some(60.0), ..Default::default() };
    /// let view = wider.resolve(Some(&camera)).unwrap();
    /// assert_eq!(*view.eye(), kepler::views::Eye::Point(Point3::new(0.0, -9.0, 2.0)));
    /// ```
    pub fn resolve(&self, camera: Option<&Camera>) -> Result<View, ViewError> {
        if self.view_dir.is_some() && (self.eye.is_some() || self.target.is_some()) {
            return Err(ViewError::Options(
                "--view-dir (orthographic) cannot be combined with --eye/--target (perspective)",
            ));
        }
        if self.eye.is_some() != self.target.is_some() {
            return Err(ViewError::Options(
                "--eye and --target must be given together",
            ));
        }
        let base = camera.copied().unwrap_or_default();
        let base_fov = match base.projection {
            Projection::Perspective { fov, .. } => Some(fov),
            Projection::Orthographic { .. } => None,
        };
        let projection = match (self.view_dir, self.eye, self.target) {
            (Some(d), _, _) => Projection::Orthographic {
                direction: d.into(),
            },
            (None, Some(eye), Some(target)) => Projection::Perspective {
                eye: eye.into(),
                target: target.into(),
                fov: self.fov.or(base_fov).unwrap_or(40.0),
            },
            _ => match base.projection {
                Projection::Perspective { eye, target, fov } => Projection::Perspective {
                    eye,
                    target,
                    fov: self.fov.unwrap_or(fov),
                },
                orthographic => orthographic,
            },
        };
        if self.fov.is_some() && matches!(projection, Projection::Orthographic { .. }) {
            return Err(ViewError::Options(
                "--fov applies to perspective views only (give --eye and --target)",
            ));
        }
        let build = |up: [f64; 3]| View::from_camera(&Camera { projection, up });
        match self.up {
            Some(up) => build(up.into()),
            None => match build(base.up) {
                Err(ViewError::UpParallel) => build([0.0, 1.0, 0.0]),
                other => other,
            },
        }
    }
}

/// The region a perspective view draws when its scene is not wholly in front of the eye: the
/// points on the inner side of five planes, each given by the eye, an inward normal and an
/// offset from the eye along it, in doubles (exact input for the predicates): the near plane,
/// then the left, right, bottom and top planes through the eye at the field of view. Given
/// relative to the eye, they are the same planes wherever scene and eye are moved together,
/// and their normals (sums of the view's frame vectors) mirror and permute with the view.
///
/// ```
/// use kepler::{geometry::{Point3, Vector3}, views::View};
/// let v = View::perspective(Point3::new(0.0, 0.0, 5.0), Point3::origin(), Vector3::y(), 40.0).unwrap();
/// let f = v.frustum().unwrap();
/// assert_eq!(f.planes[0].1, Vector3::new(0.0, 0.0, -1.0)); // the near plane faces away from the eye
/// assert_eq!(f.planes[0].2, v.near()); // at the near distance from it
/// assert!(!f.contains(&Point3::new(0.0, 0.0, 6.0))); // behind the eye
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Frustum {
    /// Each plane as the eye, its inward normal `n` and its offset `d` (the plane is
    /// `n·(x − eye) = d`): near, left, right, bottom, top.
    pub planes: [(Point3, Vector3, f64); 5],
}

impl Frustum {
    /// The side of `p` of plane `k`, as a polynomial (positive inside).
    ///
    /// ```
    /// use kepler::{geometry::{Point3, Vector3, kernel::Polynomial}, views::View};
    /// use std::cmp::Ordering;
    /// let v = View::perspective(Point3::new(0.0, 0.0, 5.0), Point3::origin(), Vector3::y(), 40.0).unwrap();
    /// assert_eq!(v.frustum().unwrap().side(0, &Point3::origin()).sign(), Ordering::Greater);
    /// ```
    pub fn side(&self, k: usize, p: &Point3) -> Side {
        let (origin, normal, offset) = self.planes[k];
        Side {
            origin,
            normal,
            offset,
            x: *p,
        }
    }

    /// Whether `p` lies in the closed frustum, decided exactly.
    ///
    /// ```
    /// use kepler::{geometry::{Point3, Vector3}, views::View};
    /// let v = View::perspective(Point3::new(0.0, 0.0, 5.0), Point3::origin(), Vector3::y(), 40.0).unwrap();
    /// assert!(v.frustum().unwrap().contains(&Point3::new(0.0, 0.0, 1.0)));
    /// ```
    pub fn contains(&self, p: &Point3) -> bool {
        (0..5).all(|k| self.side(k, p).sign() != Ordering::Less)
    }
}

/// The unit forward, right and up vectors for looking along `direction` with `up` up; the up
/// vector must not be parallel to the direction (decided exactly).
fn frame(direction: &Vector3, up: &Vector3) -> Result<(Vector3, Vector3, Vector3), ViewError> {
    let origin = Point3::origin();
    if *up == Vector3::zeros() || collinear(&origin, &Point3::from(*direction), &Point3::from(*up))
    {
        return Err(ViewError::UpParallel);
    }
    let forward = unit(direction);
    let right = unit(&forward.cross(&unit(up)));
    let up = right.cross(&forward);
    Ok((forward, right, up))
}

/// `v` scaled to length 1, first scaled exactly by a power of two so that the sum of squares
/// neither underflows (a direction of 1e-300) nor overflows (one of 1e300); a vector whose
/// components overflowed (a difference of points near `f64::MAX`) is halved first.
fn unit(v: &Vector3) -> Vector3 {
    let v = if v.iter().all(|c| c.is_finite()) {
        *v
    } else {
        v * 0.5
    };
    let v = Vector3::from(unit_scaled(v.into()));
    // The length from the exact sum of squares rounded once, so that the frame mirrors and
    // permutes with its input bit for bit (a sum rounded in order depends on the order).
    let squares: Vec<f64> = v
        .iter()
        .flat_map(|&c| {
            let (high, low) = two_product(c, c);
            [high, low]
        })
        .collect();
    v / accurate_sum(&squares).sqrt()
}
