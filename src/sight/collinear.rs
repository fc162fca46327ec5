//! Pictures on one line: whether the pictures of two lines of the scene lie on one line of
//! the picture, and the order of points along it, decided exactly.
//!
//! # Supports and their points
//!
//! Every piece of a drawing lies on a [`Support`]: an input edge's line, or the line where
//! the planes of two input faces meet (a [`Meet`]). Its ends are [`LinePoint`]s, each defined
//! from the input: an input vertex; the zero of a [`Form`] along an input edge (a cut); or a
//! point of a meet line ([`OnLine`]: a vertex, an edge's crossing with a plane, or a cut by a
//! third plane). Each point `X` is a ratio of polynomials of the input with a positive
//! weight `W`; its *lift* relative to an input point `o` is `(W·(X − o), W)`, written once
//! over any [`Ring`], so that every affine function of `X`, times `W`, is a polynomial of the
//! input: its sign is exact (estimated with a certified bound, else expansions, else
//! rationals; see [`crate::geometry::kernel`]).
//!
//! # Collinear pictures
//!
//! The picture of a support is a line of the picture unless the support points at the eye.
//! Every point with a picture on it lies in the support's *plane of sight*: through the
//! support and the eye (for an orthographic view, through the support along the view
//! direction). For an edge `ab` its form is `orient3d(a, b, x, eye)` ([`Form::Sight`]); for a
//! meet line of planes `A` and `B`, `oA(x)·E_B − oB(x)·E_A` with `E` each plane's form at the
//! eye (it vanishes on the line and at the eye). Two supports have collinear pictures exactly
//! when both points that define one lie in the other's plane of sight ([`Support::same_picture`]).
//!
//! # Order along a picture line
//!
//! Points `P` and `Q` of one plane of sight `S` have the same picture exactly when the turn
//! `det(P − E, Q − E, w − E)` vanishes (a perspective eye `E`; for an orthographic eye along
//! `u`, `det(P − w, Q − w, u)`), with `w` an input point off `S` ([`Support::off_point`]):
//! its sign tells on which side of the line of sight through `P` the point `Q` lies, seen from
//! `w`. All the points a drawing holds lie in front of the eye, within a half-plane of `S`, so
//! the sign orders them ([`turn`]); compared with the turn of a reference pair, it says which
//! comes first along the picture line. Each turn is a polynomial of degree at most 15 of the
//! input, through the lifts: never a rounded point.

use super::along::{Form, FormAt, Formula, Zero};
use super::meet::{
    Meet, OnLine, det, difference, dot, eye_exponents, form_exponents, gradient, point_exponents,
};
use crate::geometry::Point3;
use crate::geometry::kernel::{Exponents, Polynomial, Ring};
use crate::views::Eye;
use std::cmp::Ordering;

/// The line a piece of a drawing lies on, exactly (see the module documentation).
// A meet line's variant is large, but supports are made only for the lines of candidate
// groups and travel in tiles' tables: a box each would allocate for nothing.
#[allow(clippy::large_enum_variant)]
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum Support {
    /// An input edge's line, through its two ends.
    Edge([Point3; 2]),
    /// The line where two faces' planes meet, with two distinct points of it.
    Meet {
        /// The line.
        meet: Meet,
        /// Two distinct points of it (an intersection segment's ends).
        ends: [OnLine; 2],
    },
}

/// A point of a [`Support`], defined from the input (see the module documentation).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum LinePoint {
    /// An input vertex.
    Vertex(Point3),
    /// The zero of a form strictly inside an input edge.
    Cut {
        /// The edge.
        edge: [Point3; 2],
        /// The zero.
        zero: Zero,
    },
    /// A point of a meet line.
    Meet {
        /// The line.
        meet: Meet,
        /// The point.
        point: OnLine,
    },
}

impl LinePoint {
    /// The lift `(W·(X − origin), W)` of the point `X`, with its weight `W > 0`, in `R`.
    pub(crate) fn lift<R: Ring>(&self, eye: &Eye, origin: &Point3) -> ([R; 3], R) {
        match self {
            LinePoint::Vertex(p) => (difference(p, origin), R::from_f64(1.0)),
            LinePoint::Cut { edge: [a, b], zero } => {
                // X = (f(b)·a − f(a)·b) / (f(b) − f(a)) for a rising form f (negated for a
                // falling one, so that the weight is positive).
                let at = |x| {
                    FormAt {
                        form: &zero.form,
                        eye,
                        x,
                    }
                    .evaluate::<R>()
                };
                let (fa, fb) = (at(a), at(b));
                let (p, q) = if zero.rising { (fb, fa) } else { (-fb, -fa) };
                let (da, db) = (difference::<R>(a, origin), difference::<R>(b, origin));
                let x = [0, 1, 2].map(|k| p.clone() * da[k].clone() - q.clone() * db[k].clone());
                (x, p - q)
            }
            LinePoint::Meet { meet, point } => meet.lifted(eye, point, origin),
        }
    }

    /// The degree of the lift's coordinates.
    fn degree(&self, eye: &Eye) -> u32 {
        match self {
            LinePoint::Vertex(_) => 1,
            LinePoint::Cut { edge, zero } => {
                FormAt {
                    form: &zero.form,
                    eye,
                    x: &edge[0],
                }
                .degree()
                    + 1
            }
            LinePoint::Meet { meet, point } => meet.lifted_degree(eye, point),
        }
    }

    /// The binary exponents of the inputs that define the point (and of the eye).
    fn exponents(&self, eye: &Eye) -> Exponents {
        match self {
            LinePoint::Vertex(p) => point_exponents(p).union(eye_exponents(eye)),
            LinePoint::Cut { edge, zero } => point_exponents(&edge[0])
                .union(point_exponents(&edge[1]))
                .union(form_exponents(&zero.form))
                .union(eye_exponents(eye)),
            LinePoint::Meet { meet, point } => meet.exponents_with(eye, point),
        }
    }
}

impl Support {
    /// Two distinct points of the support: an edge's ends, a meet line's two points.
    pub(crate) fn points(&self) -> [LinePoint; 2] {
        match self {
            Support::Edge([a, b]) => [LinePoint::Vertex(*a), LinePoint::Vertex(*b)],
            Support::Meet { meet, ends } => {
                ends.map(|point| LinePoint::Meet { meet: *meet, point })
            }
        }
    }

    /// Whether the support's picture is a line (it does not point at the eye), exactly.
    pub(crate) fn is_pictured(&self, eye: &Eye) -> bool {
        match self {
            Support::Edge([a, b]) => !eye.sees_end_on(a, b),
            Support::Meet { meet, .. } => meet
                .planes
                .iter()
                .any(|p| eye.orient3d(&p[0], &p[1], &p[2]) != Ordering::Equal),
        }
    }

    /// The side of `x` of the support's plane of sight (see the module documentation); the
    /// support must be pictured.
    pub(crate) fn sight_sign(&self, eye: &Eye, x: &LinePoint) -> Ordering {
        match (self, x) {
            // The edge's own ends: the exact determinant would take its slowest path to zero.
            (Support::Edge([a, b]), LinePoint::Vertex(p)) if p == a || p == b => Ordering::Equal,
            (Support::Edge([a, b]), LinePoint::Vertex(p)) => eye.orient3d(a, b, p),
            (Support::Meet { meet, .. }, LinePoint::Vertex(p)) => meet.sight_side(eye, p),
            _ => SightAt {
                eye,
                support: self,
                point: x,
            }
            .sign(),
        }
    }

    /// Whether the pictures of the two supports (both pictured) lie on one line, exactly.
    pub(crate) fn same_picture(&self, other: &Support, eye: &Eye) -> bool {
        match (self, other) {
            _ if self == other => return true,
            // Segments of one meet line (the exact test would take its slowest path to zero).
            (Support::Meet { meet: a, .. }, Support::Meet { meet: b, .. }) if a == b => {
                return true;
            }
            _ => {}
        }
        other
            .points()
            .iter()
            .all(|p| self.sight_sign(eye, p) == Ordering::Equal)
    }

    /// An input-scale point off the support's plane of sight (the support must be pictured):
    /// one of the four [`corners`] at the scale of the points that define the support, of
    /// which at least one is off any plane.
    pub(crate) fn off_point(&self, eye: &Eye) -> Point3 {
        let top = match self {
            Support::Edge([a, b]) => a.coords.amax().max(b.coords.amax()),
            Support::Meet { meet, .. } => meet
                .planes
                .iter()
                .flatten()
                .fold(0.0f64, |m, p| m.max(p.coords.amax())),
        };
        let corners = corners(top);
        corners
            .into_iter()
            .find(|w| self.sight_sign(eye, &LinePoint::Vertex(*w)) != Ordering::Equal)
            .unwrap_or(corners[3])
    }

    /// The input point the support's plane of sight is measured from.
    fn anchor(&self) -> Point3 {
        match self {
            Support::Edge([a, _]) => *a,
            Support::Meet { meet, .. } => meet.planes[0][0],
        }
    }

    fn exponents(&self, eye: &Eye) -> Exponents {
        match self {
            Support::Edge([a, b]) => point_exponents(a).union(point_exponents(b)),
            Support::Meet { meet, .. } => meet
                .planes
                .iter()
                .flatten()
                .fold(eye_exponents(eye), |e, p| e.union(point_exponents(p))),
        }
    }
}

/// Four affinely independent points at the scale `top` (the origin and a power of two not
/// below `top` on each axis): at least one lies off any plane, and a plane spanned with one
/// of them depends only on which, never on where the scene is.
pub(crate) fn corners(top: f64) -> [Point3; 4] {
    let scale = if top.is_normal() {
        2f64.powi((top.log2().ceil() as i32).clamp(-1022, 1023))
    } else {
        1.0
    };
    [
        Point3::origin(),
        Point3::new(scale, 0.0, 0.0),
        Point3::new(0.0, scale, 0.0),
        Point3::new(0.0, 0.0, scale),
    ]
}

/// The turn from `p` to `q` seen from `off` (see the module documentation): `Equal` exactly
/// when the two points of one plane of sight have the same picture; otherwise the same sign
/// for every pair in the same order along the picture line. `off` must lie off their plane
/// of sight.
pub(crate) fn turn(eye: &Eye, off: &Point3, p: &LinePoint, q: &LinePoint) -> Ordering {
    if let (LinePoint::Vertex(a), LinePoint::Vertex(b)) = (p, q)
        && a == b
    {
        return Ordering::Equal;
    }
    Turn { eye, off, p, q }.sign()
}

/// The value of the support's plane-of-sight form at a point, times the point's weight: a
/// polynomial of the input.
struct SightAt<'a> {
    eye: &'a Eye,
    support: &'a Support,
    point: &'a LinePoint,
}

impl Formula for SightAt<'_> {
    fn value<R: Ring>(&self) -> R {
        let eye = self.eye;
        let o = self.support.anchor();
        let (x, w) = self.point.lift::<R>(eye, &o);
        match self.support {
            // orient3d(a, b, x, eye) vanishes at a: its gradient times W·(X − a).
            Support::Edge([a, b]) => dot(&gradient::<R>(eye, &Form::Sight(*a, *b)), &x),
            Support::Meet { meet, .. } => {
                // oA(x)·E_B − oB(x)·E_A, with oA(o) = 0 at o = a0.
                let [pa, pb] = meet.planes;
                let ea = eye.determinant(&pa[0], &pa[1], &pa[2]).evaluate::<R>();
                let eb = eye.determinant(&pb[0], &pb[1], &pb[2]).evaluate::<R>();
                let (ga, gb) = (
                    gradient::<R>(eye, &meet.plane(0)),
                    gradient::<R>(eye, &meet.plane(1)),
                );
                let g = [0, 1, 2].map(|k| ga[k].clone() * eb.clone() - gb[k].clone() * ea.clone());
                let b_o = FormAt {
                    form: &meet.plane(1),
                    eye,
                    x: &o,
                }
                .evaluate::<R>();
                dot(&g, &x) - w * b_o * ea
            }
        }
    }

    fn formula_degree(&self) -> u32 {
        let lift = self.point.degree(self.eye);
        match self.support {
            Support::Edge(_) => lift + 2,
            Support::Meet { .. } => lift + 5,
        }
    }

    fn formula_exponents(&self) -> Exponents {
        self.support
            .exponents(self.eye)
            .union(self.point.exponents(self.eye))
            .union(eye_exponents(self.eye))
    }
}

/// `det(P − E, Q − E, w − E)` (perspective) or `det(P − w, Q − w, u)` (orthographic), times
/// the points' weights: a polynomial of the input (see [`turn`]).
struct Turn<'a> {
    eye: &'a Eye,
    off: &'a Point3,
    p: &'a LinePoint,
    q: &'a LinePoint,
}

impl Formula for Turn<'_> {
    fn value<R: Ring>(&self) -> R {
        let (origin, v) = match self.eye {
            Eye::Point(e) => (*e, difference::<R>(self.off, e)),
            Eye::Infinity(u) => (*self.off, [0, 1, 2].map(|k| R::from_f64(u[k]))),
        };
        let (p, _) = self.p.lift::<R>(self.eye, &origin);
        let (q, _) = self.q.lift::<R>(self.eye, &origin);
        det(&p, &q, &v)
    }

    fn formula_degree(&self) -> u32 {
        self.p.degree(self.eye) + self.q.degree(self.eye) + 1
    }

    fn formula_exponents(&self) -> Exponents {
        self.p
            .exponents(self.eye)
            .union(self.q.exponents(self.eye))
            .union(point_exponents(self.off))
            .union(eye_exponents(self.eye))
    }
}
