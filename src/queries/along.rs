//! Exact predicates at a point of an edge, and the exact construction of the points where an
//! edge's picture is cut.
//!
//! A piece of an edge `ab` is decided at one point `X(t) = a + t·(b - a)` inside it, with `t`
//! a double. `X(t)` is never rounded: every predicate the hidden-line pass asks about it is
//! affine in the point (the side of a face's plane, the side of a plane through the eye and a
//! face's edge), so its value at `X(t)` is `(1 - t)·O(a) + t·O(b)`. Equal signs at `a` and `b`
//! decide it at once; opposite signs go through a floating-point filter and, when that cannot
//! tell, exact expansions. A point of an edge that lies on another face is therefore on it,
//! exactly (two boxes stacked on each other draw their touching edges as visible).
//!
//! A cut is where the edge meets the zero set of such a form: `t = O(a) / (O(a) - O(b))`. Its
//! picture is built once from the input coordinates and the exact values `O(a)`, `O(b)`:
//! every picture form `L` is affine, so `L(X) = (O(a)·L(b) - O(b)·L(a)) / (O(a) - O(b))`, and
//! the numerator and the denominator (for a perspective view the depth form takes the place of
//! `O(a) - O(b)`) are exact expansions rounded once: within 1.5 units in the last place.

use crate::geometry::Point3;
use crate::geometry::exact::{estimate, expansion_product, expansion_sum, negated};
use crate::geometry::kernel::{Between, Estimate, Exponents, Polynomial, Ring, value};
use crate::geometry::predicates::{Orient3d, Orientation};
use crate::views::{Eye, Picture};
use std::cmp::Ordering;

/// An affine function of a point whose zero set is a plane, evaluated exactly.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum Form {
    /// `orient3d(p, q, r, x)`: the side of the plane through a triangle.
    Plane([Point3; 3]),
    /// `orient3d(p, q, x, eye)`: the side of the plane through `p`, `q` and the eye, that is,
    /// of the picture of the line `pq`.
    Sight(Point3, Point3),
}

impl Form {
    /// The form at `x`, as a polynomial of the input coordinates.
    #[inline]
    fn at(&self, eye: &Eye, x: &Point3) -> Orientation {
        match self {
            Form::Plane([p, q, r]) => Orientation::Point(Orient3d([*p, *q, *r, *x])),
            Form::Sight(p, q) => eye.determinant(p, q, x),
        }
    }

    /// Whether `x` is one of the points that define the form (so the form vanishes at `x`).
    #[inline]
    fn passes_through(&self, x: &Point3) -> bool {
        match self {
            Form::Plane(t) => t.contains(x),
            Form::Sight(p, q) => p == x || q == x,
        }
    }

    /// The exact sign at `X(t) = a + t·(b - a)`, for `0 < t < 1`: equal signs at `a` and `b`
    /// decide at once, opposite ones through the kernel's [`Between`].
    pub(crate) fn sign_along(&self, eye: &Eye, a: &Point3, b: &Point3, t: f64) -> Ordering {
        let at = |x| FormAt { form: self, eye, x };
        Between(at(a), at(b), t).sign()
    }

    /// The exact sign at `x`.
    pub(crate) fn sign_at(&self, eye: &Eye, x: &Point3) -> Ordering {
        FormAt { form: self, eye, x }.sign()
    }

    /// The parameter `t` of the zero of the form on the edge `ab`, approximately (for ordering
    /// cuts; [`cut_point`] builds the point itself exactly). `None` when the form has the same
    /// strict sign at both ends or vanishes on the whole edge.
    pub(crate) fn zero_along(&self, eye: &Eye, a: &Point3, b: &Point3) -> Option<f64> {
        let (fa, fb) = (
            FormAt {
                form: self,
                eye,
                x: a,
            },
            FormAt {
                form: self,
                eye,
                x: b,
            },
        );
        let (sa, sb) = (fa.sign(), fb.sign());
        match (sa, sb) {
            (Ordering::Equal, Ordering::Equal) => None,
            (Ordering::Equal, _) => Some(0.0),
            (_, Ordering::Equal) => Some(1.0),
            _ if sa == sb => None,
            _ => {
                let (va, vb) = (value(&fa), value(&fb));
                Some((va / (va - vb)).clamp(0.0, 1.0))
            }
        }
    }
}

/// A [`Form`] at a point: a polynomial whose sign is answered at once when the form passes
/// through the point (the exact determinant would take its slowest path to say zero).
struct FormAt<'a> {
    form: &'a Form,
    eye: &'a Eye,
    x: &'a Point3,
}

impl Polynomial for FormAt<'_> {
    #[inline]
    fn estimate(&self) -> Estimate {
        self.form.at(self.eye, self.x).estimate()
    }

    fn expansion(&self) -> Vec<f64> {
        self.form.at(self.eye, self.x).expansion()
    }

    fn evaluate<R: Ring>(&self) -> R {
        self.form.at(self.eye, self.x).evaluate()
    }

    fn degree(&self) -> u32 {
        3
    }

    fn exponents(&self) -> Exponents {
        self.form.at(self.eye, self.x).exponents()
    }

    #[inline]
    fn sign(&self) -> Ordering {
        if self.form.passes_through(self.x) {
            return Ordering::Equal;
        }
        self.form.at(self.eye, self.x).sign()
    }
}

/// Whether the triangle `tri` hides `X(t)` on the edge `ab` from the eye: `X(t)` lies strictly
/// behind the triangle's plane and the line of sight through it meets the closed triangle.
/// An edge-on triangle hides nothing; a point on the plane is not hidden by it.
pub(crate) fn hides_along(eye: &Eye, tri: &[Point3; 3], a: &Point3, b: &Point3, t: f64) -> bool {
    let eye_side = eye.orient3d(&tri[0], &tri[1], &tri[2]);
    if eye_side == Ordering::Equal
        || Form::Plane(*tri).sign_along(eye, a, b, t) != eye_side.reverse()
    {
        return false;
    }
    let (mut above, mut below) = (false, false);
    for i in 0..3 {
        match Form::Sight(tri[i], tri[(i + 1) % 3]).sign_along(eye, a, b, t) {
            Ordering::Greater => above = true,
            Ordering::Less => below = true,
            Ordering::Equal => {}
        }
        if above && below {
            return false;
        }
    }
    true
}

/// The picture of the point where `form` vanishes on the edge `ab` (its signs at `a` and `b`
/// must differ), built once from the input coordinates (see the module documentation).
pub(crate) fn cut_point(
    picture: &Picture,
    eye: &Eye,
    form: &Form,
    a: &Point3,
    b: &Point3,
) -> [f64; 2] {
    let (oa, ob) = (form.at(eye, a).expansion(), form.at(eye, b).expansion());
    let combine = |la: &[f64], lb: &[f64]| {
        estimate(&expansion_sum(
            &expansion_product(&oa, lb),
            &negated(&expansion_product(&ob, la)),
        ))
    };
    let depth = combine(&picture.form(2, a), &picture.form(2, b));
    [0, 1].map(|k| combine(&picture.form(k, a), &picture.form(k, b)) / depth)
}

/// The picture of the point where the segment `ab` crosses the plane of the triangle `plane`
/// (its ends strictly on either side), built once from the input coordinates: within 1.5 units
/// in the last place (see the module documentation).
pub(crate) fn cut_point_on_plane(
    picture: &Picture,
    eye: &Eye,
    plane: &[Point3; 3],
    a: &Point3,
    b: &Point3,
) -> [f64; 2] {
    cut_point(picture, eye, &Form::Plane(*plane), a, b)
}
