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
//! `O(a) - O(b)`) are exact expansions rounded once: within 1.5 units in the last place. Where
//! the inputs' exponents are too far apart for exact expansions (a scene scaled by `2^±280`,
//! say), the same two values are computed as rationals and each rounded once at its own scale
//! ([`rounded_ratio`](super::ratio::rounded_ratio)): the same bits as the expansions would
//! give, scaled.
//!
//! The arithmetic for polynomials written once over any [`Ring`] lives beside it, in
//! [`formula`]: [`Filtered`] (estimates with the kernel's certified bounds) and
//! [`Expanded`](formula::Expanded) (exact expansions).

use crate::geometry::exact::{
    estimate, expansion_product, expansion_sum, ldexp, lerp, negated, scale_expansion,
};
use crate::geometry::kernel::{
    Between, Difference, Estimate, Exponents, Polynomial, Product, Ring, UNIT_ROUNDOFF,
    builds_exactly, expansion_sign, plain_ratio, rounded,
};
use crate::geometry::predicates::{Orient3d, Orientation, Side};
use crate::geometry::{Point3, Vector3};
use crate::sight::ratio::{nearest_ratio, rounded_ratio};
use crate::views::{Eye, Picture};
use num_rational::BigRational;
use num_traits::ToPrimitive;
use std::cmp::Ordering;

mod formula;

pub(crate) use formula::{Expanded, Filtered, Formula, exact_sign_rational};

/// An affine function of a point whose zero set is a plane, evaluated exactly.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum Form {
    /// `orient3d(p, q, r, x)`: the side of the plane through a triangle.
    Plane([Point3; 3]),
    /// `orient3d(p, q, x, eye)`: the side of the plane through `p`, `q` and the eye, that is,
    /// of the picture of the line `pq`.
    Sight(Point3, Point3),
    /// `n·(x − eye) − d` for a perspective eye: a plane given relative to the eye (a plane of
    /// the view's frustum), the same wherever scene and eye are moved together.
    Frustum(Vector3, f64),
}

impl Form {
    /// The form at `x`, as a polynomial of the input coordinates.
    #[inline]
    pub(crate) fn at(&self, eye: &Eye, x: &Point3) -> Orientation {
        match self {
            Form::Plane([p, q, r]) => Orientation::Point(Orient3d([*p, *q, *r, *x])),
            Form::Sight(p, q) => eye.determinant(p, q, x),
            Form::Frustum(normal, offset) => Orientation::Side(Side {
                origin: match eye {
                    Eye::Point(e) => *e,
                    Eye::Infinity(_) => Point3::origin(),
                },
                normal: *normal,
                offset: *offset,
                x: *x,
            }),
        }
    }

    /// Whether `x` is one of the points that define the form (so the form vanishes at `x`).
    #[inline]
    fn passes_through(&self, x: &Point3) -> bool {
        match self {
            Form::Plane(t) => t.contains(x),
            Form::Sight(p, q) => p == x || q == x,
            Form::Frustum(..) => false,
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

    /// Where the form vanishes strictly inside the edge `ab` (its signs at `a` and `b` strictly
    /// opposite), with its parameter approximately and a certified bound on that parameter's
    /// error (for ordering cuts; [`cut_point`] builds the point itself exactly). `None` when
    /// the form vanishes at an end or has the same sign at both.
    pub(crate) fn zero_on(&self, eye: &Eye, a: &Point3, b: &Point3) -> Option<Zero> {
        let at = |x| FormAt { form: self, eye, x };
        let (fa, fb) = (at(a), at(b));
        let (sa, sb) = (fa.sign(), fb.sign());
        if sa == Ordering::Equal || sb == Ordering::Equal || sa == sb {
            return None;
        }
        let ((va, ra), (vb, rb)) = (approximate(&fa), approximate(&fb));
        let t = va / (va - vb);
        let (t, error) = if t.is_finite() && ra.is_finite() && rb.is_finite() {
            // Opposite signs: the difference does not cancel, so `t` is within a relative
            // `ra + max(ra, rb)` and three roundings of the exact parameter.
            let relative = 2.0 * (ra + rb) + 8.0 * UNIT_ROUNDOFF;
            (t.clamp(0.0, 1.0), t.abs() * relative + f64::MIN_POSITIVE)
        } else {
            // The values do not fit a double (inputs of far apart exponents): the parameter
            // from their exact ratio, rounded once.
            let (xa, xb) = (fa.evaluate::<BigRational>(), fb.evaluate::<BigRational>());
            let denominator = &xa - xb;
            match (xa / denominator).to_f64() {
                Some(t) if t.is_finite() => (
                    t.clamp(0.0, 1.0),
                    t * 4.0 * UNIT_ROUNDOFF + f64::MIN_POSITIVE,
                ),
                _ => (0.5, f64::INFINITY),
            }
        };
        Some(Zero {
            form: *self,
            rising: sb == Ordering::Greater,
            t,
            error,
        })
    }
}

/// The value of `p` and a certified bound on its relative error: the estimate when its bound is
/// below 2⁻²⁰ of it, else the exact value rounded once (infinite error where that fails: an
/// input outside the range the engine draws in).
fn approximate<P: Polynomial>(p: &P) -> (f64, f64) {
    let e = p.estimate();
    if e.value.is_finite() && e.value != 0.0 && e.bound <= e.value.abs() * RELATIVE {
        return (e.value, e.bound / e.value.abs());
    }
    let v = rounded(p);
    if v.is_finite() && v != 0.0 && v.abs() >= f64::MIN_POSITIVE {
        (v, 2.0 * UNIT_ROUNDOFF)
    } else {
        (e.value, f64::INFINITY)
    }
}

/// The relative error under which [`approximate`] keeps an estimate.
const RELATIVE: f64 = 1.0 / (1u64 << 20) as f64;

/// The zero of a [`Form`] strictly inside an edge `ab`: a cut of the edge, defined from the
/// input (see [`Form::zero_on`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Zero {
    /// The form.
    pub form: Form,
    /// Whether the form is positive at `b` (and so negative at `a`).
    pub rising: bool,
    /// The zero's parameter `t` along the edge, approximately.
    pub t: f64,
    /// A bound on the error of `t`.
    pub error: f64,
}

impl Zero {
    /// The exact order of two zeros along the edge `ab`: with both forms rising, `t_f < t_g`
    /// exactly when `g(a)·f(b) − f(a)·g(b) < 0`; their parameters decide when their error
    /// bounds keep them apart.
    pub(crate) fn compare(&self, other: &Zero, eye: &Eye, a: &Point3, b: &Point3) -> Ordering {
        if self.apart(other) {
            return self.t.total_cmp(&other.t);
        }
        let at = |form, x| FormAt { form, eye, x };
        let (f, g) = (&self.form, &other.form);
        let s = Difference(Product(at(g, a), at(f, b)), Product(at(f, a), at(g, b))).sign();
        if self.rising == other.rising {
            s
        } else {
            s.reverse()
        }
    }

    /// Whether the two parameters' error bounds keep the zeros apart (then their parameters
    /// order them).
    fn apart(&self, other: &Zero) -> bool {
        (self.t - other.t).abs() > (self.error + other.error) * (1.0 + 4.0 * UNIT_ROUNDOFF)
    }

    /// Whether the two zeros are a near tie: their parameters' error bounds leave their order
    /// to exact signs, so the parameters themselves may be out of that order.
    pub(crate) fn near(&self, other: &Zero) -> bool {
        !self.apart(other)
    }

    /// The zero with its parameter `f(a) / (f(a) − f(b))` correctly rounded (its error bound
    /// then half a unit in the last place). Rounding to nearest is monotone, so near ties put
    /// in their exact order (see [`Zero::compare`]) get parameters in that order too, and a
    /// zero apart from them keeps its own on the right side: the pieces of an edge then have
    /// parameter ranges in order along it (by which `verify` checks them and tiles are
    /// stitched). Unchanged where the engine builds points in plain floating point.
    pub(crate) fn correctly_rounded(&self, eye: &Eye, a: &Point3, b: &Point3) -> Zero {
        if !builds_exactly() {
            return *self;
        }
        let at = |x| FormAt {
            form: &self.form,
            eye,
            x,
        };
        let t = nearest_ratio(&at(a), &Difference(at(a), at(b)));
        Zero {
            t,
            error: 2.0 * UNIT_ROUNDOFF * t.abs() + f64::MIN_POSITIVE,
            ..*self
        }
    }

    /// The exact sign of the form at a sample of the edge, as if it were rising: `Greater`
    /// past the zero.
    fn past(&self, sample: &Sample, eye: &Eye, a: &Point3, b: &Point3) -> Ordering {
        let s = sample.sign(&self.form, eye, a, b);
        if self.rising { s } else { s.reverse() }
    }

    /// The zero's parameter `f(a) / (f(a) − f(b))` rounded once (within 1.5 units in the last
    /// place).
    fn rounded(&self, eye: &Eye, a: &Point3, b: &Point3) -> f64 {
        let at = |x| FormAt {
            form: &self.form,
            eye,
            x,
        };
        rounded_ratio(&at(a), &Difference(at(a), at(b))).clamp(0.0, 1.0)
    }

    /// The zero's weight `|f(b) − f(a)|`, approximately (for [`balance`]).
    fn weight(&self, eye: &Eye, a: &Point3, b: &Point3) -> f64 {
        let at = |x| FormAt {
            form: &self.form,
            eye,
            x,
        };
        Difference(at(b), at(a)).estimate().value.abs()
    }

    /// The form `H` (given at the ends as `ha`, `hb`) at the zero, times its positive weight:
    /// `f(b)·H(a) − f(a)·H(b)` for a rising form `f`, the negation for a falling one.
    fn numerator<'a>(
        &'a self,
        eye: &'a Eye,
        ha: FormAt<'a>,
        hb: FormAt<'a>,
    ) -> Difference<Product<FormAt<'a>, FormAt<'a>>, Product<FormAt<'a>, FormAt<'a>>> {
        let at = |x| FormAt {
            form: &self.form,
            eye,
            x,
        };
        let (fa, fb) = (at(ha.x), at(hb.x));
        if self.rising {
            Difference(Product(fb, ha), Product(fa, hb))
        } else {
            Difference(Product(fa, hb), Product(fb, ha))
        }
    }
}

/// A point `X(t) = a + t·(b − a)` strictly inside a piece of an edge `ab` between two cuts,
/// where the pass decides the piece: `t` a double when one lies strictly between the cuts
/// (nearly always: the middle of their parameters, checked exactly when their error bounds do
/// not decide; else the middle of their correctly rounded parameters), else a point between
/// the two exact cut points with positive weights (see [`Sample::Midpoint`]). Either way never
/// rounded: every form is evaluated exactly at it.
#[derive(Debug, Clone, PartialEq)]
pub(crate) enum Sample {
    /// At a double parameter.
    At(f64),
    /// Where no double lies strictly between the cuts `lo` and `hi` (`None`: an end of the
    /// edge): the point `M = (c1·W1·X1 + c2·W2·X2) / (c1·W1 + c2·W2)` of the two cut points
    /// `X = (f(b)·a − f(a)·b) / W` (a zero of the form `f`, with its weight `W = f(b) − f(a)`
    /// made positive; an end has weight 1), for powers of two `c` that bring `c·W` near 1. It
    /// lies strictly between them, and every form `H` has at `M` the sign of
    /// `c1·W1·H(X1) + c2·W2·H(X2)`, a polynomial of the input (see [`Blend`]). `t` is its
    /// parameter, approximately.
    Midpoint {
        /// The cuts (`None`: the ends `a`, resp. `b`); boxed, as this variant is rare.
        ends: Box<[Option<Zero>; 2]>,
        /// The powers of two `c1`, `c2`.
        scales: [f64; 2],
        /// The parameter of the point, within two units in the last place of 1.
        t: f64,
    },
}

impl Sample {
    /// A point strictly between `lo` and `hi` (`None`: the edge's end `a`, resp. `b`), which
    /// must be in that order along `ab`, distinct.
    pub(crate) fn between(
        eye: &Eye,
        a: &Point3,
        b: &Point3,
        [lo, hi]: [Option<&Zero>; 2],
    ) -> Sample {
        let (t0, t1) = (lo.map_or(0.0, |z| z.t), hi.map_or(1.0, |z| z.t));
        let middle = t0 + (t1 - t0) / 2.0;
        if strictly_between(eye, a, b, [lo, hi], middle) {
            return Sample::At(middle);
        }
        // The parameters rounded correctly: a double strictly between the cuts, if any, is
        // found by the middle of these or next to it.
        let (r0, r1) = (
            lo.map_or(0.0, |z| z.rounded(eye, a, b)),
            hi.map_or(1.0, |z| z.rounded(eye, a, b)),
        );
        let middle = r0 + (r1 - r0) / 2.0;
        for t in [middle, middle.next_up(), middle.next_down()] {
            if strictly_between(eye, a, b, [lo, hi], t) {
                return Sample::At(t);
            }
        }
        let weight = |z: Option<&Zero>| z.map_or(1.0, |z| z.weight(eye, a, b));
        Sample::Midpoint {
            ends: Box::new([lo.copied(), hi.copied()]),
            scales: [balance(weight(lo)), balance(weight(hi))],
            t: middle.clamp(0.0, 1.0),
        }
    }

    /// The point of the edge `ab`, each coordinate rounded once, and a bound on its distance
    /// from the exact point (for finding what lies near it, never for a decision).
    pub(crate) fn point(&self, a: &Point3, b: &Point3) -> (Point3, f64) {
        let at = |t: f64| Point3::from(std::array::from_fn(|k| lerp(a[k], b[k], t)));
        // Each coordinate within a unit in the last place of the largest.
        let rounding = |x: &Point3| 4.0 * UNIT_ROUNDOFF * x.coords.amax() + f64::MIN_POSITIVE;
        match self {
            Sample::At(t) => {
                let x = at(*t);
                (x, rounding(&x))
            }
            Sample::Midpoint { t, .. } => {
                // The exact point's parameter is within a few units in the last place of 1
                // of `t` (no double lies between the cuts, each rounded within 1.5 of them).
                let x = at(*t);
                let length = (b - a).amax() * 3f64.sqrt();
                (x, rounding(&x) + 8.0 * UNIT_ROUNDOFF * length)
            }
        }
    }

    /// The exact sign of `form` at the sample of the edge `ab`.
    pub(crate) fn sign(&self, form: &Form, eye: &Eye, a: &Point3, b: &Point3) -> Ordering {
        match self {
            Sample::At(t) => form.sign_along(eye, a, b, *t),
            Sample::Midpoint { ends, scales, .. } => {
                let (ha, hb) = (FormAt { form, eye, x: a }, FormAt { form, eye, x: b });
                let [lo, hi] = ends
                    .each_ref()
                    .map(|end| end.as_ref().map(|z| AtCut::Zero(z.numerator(eye, ha, hb))));
                Blend {
                    parts: [lo.unwrap_or(AtCut::End(ha)), hi.unwrap_or(AtCut::End(hb))],
                    scales: *scales,
                }
                .sign()
            }
        }
    }
}

/// A form `H` at a bound of a piece of an edge, times the bound's positive weight: at an end,
/// `H` there; at a cut, `f(b)·H(a) − f(a)·H(b)` for its rising form `f` (see
/// [`Sample::Midpoint`]).
#[derive(Debug, Clone, Copy)]
enum AtCut<'a> {
    /// At an end of the edge.
    End(FormAt<'a>),
    /// At a cut.
    Zero(Difference<Product<FormAt<'a>, FormAt<'a>>, Product<FormAt<'a>, FormAt<'a>>>),
}

impl Polynomial for AtCut<'_> {
    fn estimate(&self) -> Estimate {
        match self {
            AtCut::End(p) => p.estimate(),
            AtCut::Zero(p) => p.estimate(),
        }
    }

    fn expansion(&self) -> Vec<f64> {
        match self {
            AtCut::End(p) => p.expansion(),
            AtCut::Zero(p) => p.expansion(),
        }
    }

    fn evaluate<R: Ring>(&self) -> R {
        match self {
            AtCut::End(p) => p.evaluate(),
            AtCut::Zero(p) => p.evaluate(),
        }
    }

    fn degree(&self) -> u32 {
        match self {
            AtCut::End(p) => p.degree(),
            AtCut::Zero(p) => p.degree(),
        }
    }

    fn exponents(&self) -> Exponents {
        match self {
            AtCut::End(p) => p.exponents(),
            AtCut::Zero(p) => p.exponents(),
        }
    }

    fn sign(&self) -> Ordering {
        match self {
            AtCut::End(p) => p.sign(),
            AtCut::Zero(p) => p.sign(),
        }
    }
}

/// `c1·N1 + c2·N2` for powers of two `c1`, `c2` and polynomials `N1`, `N2` (a form's
/// numerators at two points, each times a positive weight): the sign of the form at a point
/// between the two, with positive weights (see [`Sample::Midpoint`] and
/// `Meet::sign_between`).
#[derive(Debug, Clone)]
pub(crate) struct Blend<P> {
    /// `N1` and `N2`.
    pub parts: [P; 2],
    /// `c1` and `c2`.
    pub scales: [f64; 2],
}

impl<P: Polynomial> Blend<P> {
    /// The scaled parts' expansions, when both are exact.
    fn expansions(&self) -> Option<[Vec<f64>; 2]> {
        let mut out = [Vec::new(), Vec::new()];
        for (k, n) in self.parts.iter().enumerate() {
            if !n.exponents().exact_for(n.degree()) {
                return None;
            }
            let e = n.expansion();
            // Scaling by a power of two is exact unless a component leaves the normal range.
            let c = self.scales[k];
            if e.iter().any(|&x| !(x * c).is_normal()) {
                return None;
            }
            out[k] = scale_expansion(&e, c);
        }
        Some(out)
    }
}

impl<P: Polynomial> Polynomial for Blend<P> {
    fn estimate(&self) -> Estimate {
        let [a, b] = &self.parts;
        let scaled = |n: &P, c: f64| Filtered(n.estimate()) * Filtered::from_f64(c);
        (scaled(a, self.scales[0]) + scaled(b, self.scales[1])).0
    }

    fn expansion(&self) -> Vec<f64> {
        let [a, b] = &self.parts;
        let scaled = |n: &P, c: f64| scale_expansion(&n.expansion(), c);
        expansion_sum(&scaled(a, self.scales[0]), &scaled(b, self.scales[1]))
    }

    fn evaluate<R: Ring>(&self) -> R {
        let [a, b] = &self.parts;
        R::from_f64(self.scales[0]) * a.evaluate::<R>()
            + R::from_f64(self.scales[1]) * b.evaluate::<R>()
    }

    fn degree(&self) -> u32 {
        self.parts[0].degree().max(self.parts[1].degree()) + 1
    }

    fn exponents(&self) -> Exponents {
        let [a, b] = &self.parts;
        a.exponents()
            .union(b.exponents())
            .union(Exponents::of(&self.scales))
    }

    /// Equal signs at the two points decide; else the filter; else the exact sum (expansions
    /// of the two parts scaled, or rationals).
    fn sign(&self) -> Ordering {
        let [a, b] = &self.parts;
        let (sa, sb) = (a.sign(), b.sign());
        if sa == sb || sb == Ordering::Equal {
            return sa;
        }
        if sa == Ordering::Equal {
            return sb;
        }
        if let Some(sign) = self.estimate().sign() {
            return sign;
        }
        match self.expansions() {
            Some([x, y]) => expansion_sign(&expansion_sum(&x, &y)),
            None => exact_sign_rational(self),
        }
    }
}

/// The power of two that brings a positive weight near 1 (1 for a weight that is not a
/// positive normal double).
pub(crate) fn balance(weight: f64) -> f64 {
    if weight.is_normal() && weight > 0.0 {
        ldexp(1.0, -(weight.log2().floor() as i32))
    } else {
        1.0
    }
}

/// Whether `X(t)` lies strictly between the zeros `lo` and `hi` of the edge `ab` (`None`: its
/// ends): certified by the zeros' error bounds, else decided exactly.
fn strictly_between(
    eye: &Eye,
    a: &Point3,
    b: &Point3,
    [lo, hi]: [Option<&Zero>; 2],
    t: f64,
) -> bool {
    if !(t > 0.0 && t < 1.0) {
        return false;
    }
    let slack = 1.0 + 4.0 * UNIT_ROUNDOFF;
    let after = |z: &Zero| {
        t - z.t > z.error * slack || z.past(&Sample::At(t), eye, a, b) == Ordering::Greater
    };
    let before =
        |z: &Zero| z.t - t > z.error * slack || z.past(&Sample::At(t), eye, a, b) == Ordering::Less;
    lo.is_none_or(after) && hi.is_none_or(before)
}

/// A [`Form`] at a point: a polynomial whose sign is answered at once when the form passes
/// through the point (the exact determinant would take its slowest path to say zero).
#[derive(Debug, Clone, Copy)]
pub(crate) struct FormAt<'a> {
    pub form: &'a Form,
    pub eye: &'a Eye,
    pub x: &'a Point3,
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
        self.form.at(self.eye, self.x).degree()
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

/// Whether the triangle `tri` hides a point from the eye, given the exact sign of any form at
/// the point (`sign`): the point lies strictly behind the triangle's plane and the line of
/// sight through it meets the closed triangle. An edge-on triangle hides nothing; a point on
/// the plane is not hidden by it.
pub(crate) fn hides_at(eye: &Eye, tri: &[Point3; 3], sign: impl Fn(&Form) -> Ordering) -> bool {
    let eye_side = eye.orient3d(&tri[0], &tri[1], &tri[2]);
    if eye_side == Ordering::Equal || sign(&Form::Plane(*tri)) != eye_side.reverse() {
        return false;
    }
    let (mut above, mut below) = (false, false);
    for i in 0..3 {
        match sign(&Form::Sight(tri[i], tri[(i + 1) % 3])) {
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
    let at = |x| FormAt { form, eye, x };
    cut_point_of(picture, [at(a), at(b)], a, b)
}

/// The picture of the point of the edge `ab` where an affine function with the exact values
/// `values` at `a` and `b` (of opposite signs) vanishes: every picture form `L` gives
/// `L(X) = (O(a)·L(b) − O(b)·L(a)) / (O(a) − O(b))`, and each coordinate is the ratio of two
/// exact polynomials of the input, each rounded once ([`rounded_ratio`]).
pub(crate) fn cut_point_of<P: Polynomial + Copy>(
    picture: &Picture,
    [oa, ob]: [P; 2],
    a: &Point3,
    b: &Point3,
) -> [f64; 2] {
    let form = |k, x| PictureAt { picture, k, x };
    let combine = |k| Difference(Product(oa, form(k, b)), Product(ob, form(k, a)));
    if !builds_exactly() {
        let depth = combine(2);
        return [0, 1].map(|k| plain_ratio(&combine(k), &depth));
    }
    let exact = |k| {
        let c = combine(k);
        c.exponents().exact_for(c.degree())
    };
    if exact(0) && exact(1) && exact(2) {
        // The values at the ends expanded once for the three picture forms (the hot path of
        // every edge cut).
        let (ea, eb) = (oa.expansion(), ob.expansion());
        let value = |k| {
            estimate(&expansion_sum(
                &expansion_product(&ea, &picture.form(k, b)),
                &negated(&expansion_product(&eb, &picture.form(k, a))),
            ))
        };
        let depth = value(2);
        return [0, 1].map(|k| value(k) / depth);
    }
    let depth = combine(2);
    [0, 1].map(|k| rounded_ratio(&combine(k), &depth))
}

/// Picture form `k` of `picture` at `x`: `rows[k]·(x − origin)` (see [`Picture::rows`]), the
/// constant 1 for an orthographic view's depth (`k = 2`), as a polynomial.
#[derive(Debug, Clone, Copy)]
pub(crate) struct PictureAt<'a> {
    /// The picture map.
    pub picture: &'a Picture,
    /// The form: 0 for `x`, 1 for `y`, 2 for depth.
    pub k: usize,
    /// The point.
    pub x: &'a Point3,
}

impl PictureAt<'_> {
    /// The form in the ring `R`.
    fn value<R: Ring>(&self) -> R {
        if self.k == 2 && !self.picture.is_perspective() {
            return R::from_f64(1.0);
        }
        let (rows, origin) = self.picture.rows();
        let term = |i: usize| {
            R::from_f64(rows[self.k][i]) * (R::from_f64(self.x[i]) - R::from_f64(origin[i]))
        };
        term(0) + term(1) + term(2)
    }
}

impl Polynomial for PictureAt<'_> {
    fn estimate(&self) -> Estimate {
        self.value::<Filtered>().0
    }

    fn expansion(&self) -> Vec<f64> {
        self.picture.form(self.k, self.x)
    }

    fn evaluate<R: Ring>(&self) -> R {
        self.value()
    }

    fn degree(&self) -> u32 {
        2
    }

    fn exponents(&self) -> Exponents {
        let (rows, origin) = self.picture.rows();
        Exponents::of(rows[self.k].as_slice())
            .union(Exponents::of(origin.coords.as_slice()))
            .union(Exponents::of(self.x.coords.as_slice()))
    }
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
