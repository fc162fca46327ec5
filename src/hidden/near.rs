//! Near-plane clipping: a perspective eye inside the scene.
//!
//! When some vertex of the scene is not strictly in front of a perspective eye (the eye in a
//! room, walking down a street), the pass draws only the parts of lines beyond the near plane
//! ([`View::with_clipping`]); everything in front of the eye still hides what lies behind it,
//! as in the world. So:
//!
//! - a line wholly behind the eye (no point strictly in front of it) is left out; a line that
//!   crosses the plane of the eye is *wide*: its picture is unbounded, so it is tested against
//!   every other line rather than through the grid, and a triangle that crosses that plane is
//!   listed in every picture cell;
//! - a line not wholly beyond the near plane is cut where it crosses it, and its pieces on the
//!   eye's side are not drawn;
//! - where a line's picture crosses a wide contour's, the point of the contour behind the
//!   crossing must be in front of the eye for the contour to cut the line: decided exactly
//!   ([`contour_in_front`]).
//!
//! The near plane is the plane through three points in doubles ([`NearPlane::points`]): the
//! frustum's near point and that point moved along the picture's right and up directions
//! (scaled by a power of two to its magnitude), so that each clipped end is the intersection of
//! an input edge with a plane given exactly, constructed once like every other cut
//! ([`cut_point`](crate::queries::along::cut_point)). The rounding of the two moved points
//! tilts the plane by about 2⁻⁵³ radians from the exact near plane: immaterial for drawing,
//! and every decision is made against the same plane.

use crate::geometry::kernel::{Difference, Polynomial, Product};
use crate::geometry::predicates::{Side, orient3d};
use crate::geometry::{Point3, Vector3};
use crate::queries::along::Form;
use crate::views::{Eye, View};
use std::cmp::Ordering;

/// The near plane of a perspective view that clips, and the plane of its eye.
#[derive(Debug, Clone, Copy)]
pub(crate) struct NearPlane {
    /// Three points of the plane, in doubles.
    pub points: [Point3; 3],
    /// The sign of `orient3d(points, x)` for a point `x` beyond the plane (away from the eye).
    beyond: Ordering,
    /// The eye.
    eye: Point3,
    /// The view's forward direction: the depth of `x` is `forward·(x − eye)`.
    forward: Vector3,
}

impl NearPlane {
    /// The near plane of a perspective view; `None` for an orthographic view.
    pub(crate) fn of(view: &View) -> Option<NearPlane> {
        let Eye::Point(eye) = *view.eye() else {
            return None;
        };
        let frustum = view.frustum()?;
        let q = frustum.planes[0].0;
        let (right, up) = view.right_up();
        // Moves of about the point's own magnitude (a power of two: exact products), so the
        // rounding of the moved points tilts the plane as little as doubles allow.
        let magnitude = q
            .coords
            .amax()
            .max(eye.coords.amax())
            .max(f64::MIN_POSITIVE);
        let step = 2f64.powi(magnitude.log2().ceil() as i32);
        let points = [q, q + right * step, q + up * step];
        let behind = orient3d(&points[0], &points[1], &points[2], &eye);
        (behind != Ordering::Equal).then_some(NearPlane {
            points,
            beyond: behind.reverse(),
            eye,
            forward: view.forward(),
        })
    }

    /// The near plane as a form along lines (its zero set is the plane).
    pub(crate) fn form(&self) -> Form {
        Form::Plane(self.points)
    }

    /// Whether `x` lies strictly beyond the near plane, decided exactly.
    pub(crate) fn beyond(&self, x: &Point3) -> bool {
        let [p, q, r] = &self.points;
        orient3d(p, q, r, x) == self.beyond
    }

    /// Whether the point `X(t) = a + t·(b − a)` lies strictly beyond the near plane, exactly.
    pub(crate) fn beyond_along(&self, eye: &Eye, a: &Point3, b: &Point3, t: f64) -> bool {
        self.form().sign_along(eye, a, b, t) == self.beyond
    }

    /// The depth of `x` as a polynomial: positive in front of the eye (the same form as the
    /// picture's depth, so the same decisions).
    fn depth(&self, x: &Point3) -> Side {
        Side {
            origin: self.eye,
            normal: self.forward,
            x: *x,
        }
    }

    /// Whether `x` lies strictly in front of the eye, exactly.
    pub(crate) fn in_front(&self, x: &Point3) -> bool {
        self.depth(x).sign() == Ordering::Greater
    }
}

/// Whether the point where the segment `cd` crosses the plane through the eye and the line
/// `ab` lies strictly in front of the eye, given the sides `sc`, `sd` of `c` and `d` of that
/// plane (opposite, or one of them zero). With `O(x) = orient3d(a, b, x, eye)` and depth `S`,
/// the crossing is `X = (O(d)·c − O(c)·d) / (O(d) − O(c))`, so the sign of `S(X)` is that of
/// `S(c)·O(d) − S(d)·O(c)` times that of `O(d) − O(c)`, which is `sd` (or `−sc`).
pub(crate) fn contour_in_front(
    near: &NearPlane,
    eye: &Eye,
    [a, b]: [&Point3; 2],
    [c, d]: [&Point3; 2],
    [sc, sd]: [Ordering; 2],
) -> bool {
    match (sc, sd) {
        (Ordering::Equal, _) => near.in_front(c),
        (_, Ordering::Equal) => near.in_front(d),
        _ => {
            let numerator = Difference(
                Product(near.depth(c), eye.determinant(a, b, d)),
                Product(near.depth(d), eye.determinant(a, b, c)),
            );
            let s = numerator.sign();
            s != Ordering::Equal && s == sd
        }
    }
}
