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
//! ([`rounded_ratio`]): the same bits as the expansions would give, scaled.
//!
//! The arithmetic for polynomials written once over any [`Ring`] lives here too: [`Filtered`]
//! (estimates with the kernel's certified bounds) and [`Expanded`] (exact expansions).

use crate::geometry::exact::{estimate, expansion_product, expansion_sum, lerp, negated};
use crate::geometry::kernel::{
    Between, Difference, Estimate, Exponents, Polynomial, Product, Ring, UNIT_ROUNDOFF, rounded,
};
use crate::geometry::predicates::{Orient3d, Orientation, Side};
use crate::geometry::{Point3, Vector3};
use crate::views::{Eye, Picture};
use num_bigint::{BigInt, Sign};
use num_rational::BigRational;
use num_traits::{One, Signed, ToPrimitive, Zero as _};
use std::cmp::Ordering;
use std::ops::{Add, Mul, Neg, Sub};

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

    /// The exact sign of the form at a sample of the edge, as if it were rising: `Greater`
    /// past the zero.
    fn past(&self, sample: &Sample, eye: &Eye, a: &Point3, b: &Point3) -> Ordering {
        let s = sample.sign(&self.form, eye, a, b);
        if self.rising { s } else { s.reverse() }
    }

    /// The exact parameter of the zero.
    fn parameter(&self, eye: &Eye, a: &Point3, b: &Point3) -> BigRational {
        let at = |x| {
            FormAt {
                form: &self.form,
                eye,
                x,
            }
            .evaluate::<BigRational>()
        };
        let fa = at(a);
        let denominator = &fa - at(b);
        fa / denominator
    }
}

/// A point `X(t) = a + t·(b − a)` strictly inside a piece of an edge `ab` between two cuts,
/// where the pass decides the piece: `t` a double when one lies strictly between the cuts
/// (nearly always: the middle of their parameters, checked exactly when their error bounds do
/// not decide), else the exact middle of the two zeros as a rational. Either way never rounded:
/// every form is evaluated exactly at it.
#[derive(Debug, Clone, PartialEq)]
pub(crate) enum Sample {
    /// At a double parameter.
    At(f64),
    /// At a rational parameter (no double lies strictly between the cuts).
    Exactly(BigRational),
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
        let exact = |z: Option<&Zero>, end: f64| match z {
            Some(z) => z.parameter(eye, a, b),
            None => BigRational::from_float(end).unwrap_or_else(BigRational::zero),
        };
        let half = BigRational::new(BigInt::one(), BigInt::from(2));
        let m = (exact(lo, 0.0) + exact(hi, 1.0)) * half;
        // The double nearest the middle lies between the cuts whenever any double does.
        match m.to_f64() {
            Some(t) if strictly_between(eye, a, b, [lo, hi], t) => Sample::At(t),
            _ => Sample::Exactly(m),
        }
    }

    /// The point of the edge `ab`, each coordinate rounded once, and a bound on its distance
    /// from the exact point (for finding what lies near it, never for a decision).
    pub(crate) fn point(&self, a: &Point3, b: &Point3) -> (Point3, f64) {
        let x = match self {
            Sample::At(t) => Point3::from(std::array::from_fn(|k| lerp(a[k], b[k], *t))),
            Sample::Exactly(t) => Point3::from(std::array::from_fn(|k| {
                let [ak, bk] = [a[k], b[k]].map(|v| BigRational::from_float(v).unwrap_or_default());
                (&ak + t * (bk - &ak)).to_f64().unwrap_or(a[k])
            })),
        };
        // Each coordinate within a unit in the last place of the largest.
        (x, 4.0 * UNIT_ROUNDOFF * x.coords.amax() + f64::MIN_POSITIVE)
    }

    /// The exact sign of `form` at the sample of the edge `ab`.
    pub(crate) fn sign(&self, form: &Form, eye: &Eye, a: &Point3, b: &Point3) -> Ordering {
        match self {
            Sample::At(t) => form.sign_along(eye, a, b, *t),
            Sample::Exactly(t) => {
                let at = |x| FormAt { form, eye, x }.evaluate::<BigRational>();
                let fa = at(a);
                let value = &fa + t * (at(b) - &fa);
                match value.numer().sign() {
                    Sign::Minus => Ordering::Less,
                    Sign::NoSign => Ordering::Equal,
                    Sign::Plus => Ordering::Greater,
                }
            }
        }
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

/// The ring of [`Estimate`]s: each operation's value rounded, its bound the kernel's
/// ([`Estimate::product`], [`Estimate::difference`]; a sum is the difference with the negated
/// operand, a negation is exact), so a formula evaluated here carries a certified bound.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Filtered(pub Estimate);

impl Add for Filtered {
    type Output = Filtered;
    #[inline]
    fn add(self, other: Filtered) -> Filtered {
        self - (-other)
    }
}

impl Sub for Filtered {
    type Output = Filtered;
    #[inline]
    fn sub(self, other: Filtered) -> Filtered {
        Filtered(self.0.difference(&other.0))
    }
}

impl Mul for Filtered {
    type Output = Filtered;
    #[inline]
    fn mul(self, other: Filtered) -> Filtered {
        Filtered(self.0.product(&other.0))
    }
}

impl Neg for Filtered {
    type Output = Filtered;
    #[inline]
    fn neg(self) -> Filtered {
        Filtered(Estimate {
            value: -self.0.value,
            bound: self.0.bound,
        })
    }
}

impl Ring for Filtered {
    #[inline]
    fn from_f64(x: f64) -> Filtered {
        Filtered(Estimate::exact(x))
    }
}

/// The ring of expansions: exact while no product overflows or underflows (see
/// [`Exponents::exact_for`]).
#[derive(Debug, Clone)]
pub(crate) struct Expanded(pub Vec<f64>);

impl Add for Expanded {
    type Output = Expanded;
    fn add(self, other: Expanded) -> Expanded {
        Expanded(expansion_sum(&self.0, &other.0))
    }
}

impl Sub for Expanded {
    type Output = Expanded;
    fn sub(self, other: Expanded) -> Expanded {
        Expanded(expansion_sum(&self.0, &negated(&other.0)))
    }
}

impl Mul for Expanded {
    type Output = Expanded;
    fn mul(self, other: Expanded) -> Expanded {
        Expanded(expansion_product(&self.0, &other.0))
    }
}

impl Neg for Expanded {
    type Output = Expanded;
    fn neg(self) -> Expanded {
        Expanded(negated(&self.0))
    }
}

impl Ring for Expanded {
    fn from_f64(x: f64) -> Expanded {
        Expanded(if x == 0.0 { Vec::new() } else { vec![x] })
    }
}

/// The sign of `p` from its rational value.
#[cold]
pub(crate) fn exact_sign_rational<P: Polynomial>(p: &P) -> Ordering {
    let x = p.evaluate::<BigRational>();
    if x.is_zero() {
        Ordering::Equal
    } else if x.is_positive() {
        Ordering::Greater
    } else {
        Ordering::Less
    }
}

/// `n / d` with each exact polynomial rounded once to the nearest double, then divided (the
/// rule of every constructed coordinate; see [`crate::geometry::kernel::ratio`]); where the
/// inputs' exponents do not allow exact expansions, the same rule from rationals, each value
/// rounded at its own scale so that nothing overflows on the way.
pub(crate) fn rounded_ratio<N: Polynomial, D: Polynomial>(n: &N, d: &D) -> f64 {
    if n.exponents().exact_for(n.degree()) && d.exponents().exact_for(d.degree()) {
        return estimate(&n.expansion()) / estimate(&d.expansion());
    }
    let (n, d) = (n.evaluate::<BigRational>(), d.evaluate::<BigRational>());
    let (xn, en) = split(&n);
    let (xd, ed) = split(&d);
    times_power_of_two(xn / xd, en - ed)
}

/// `x` as a double `m` rounded once and a power of two: `x ≈ m·2^e` with `m` in `[1, 2]`
/// (`m = 0` for zero). For `x` in the normal range, `m·2^e` is `x` rounded to the nearest
/// double.
fn split(x: &BigRational) -> (f64, i64) {
    if x.is_zero() {
        return (0.0, 0);
    }
    let bits = |n: &BigInt| n.bits() as i64;
    let mut e = bits(x.numer()) - bits(x.denom());
    let scaled = |e: i64| {
        let p = BigRational::from_integer(BigInt::one() << e.unsigned_abs());
        if e >= 0 { x / p } else { x * p }
    };
    let mut y = scaled(e);
    if y.abs() < BigRational::one() {
        e -= 1;
        y = scaled(e);
    }
    (y.to_f64().unwrap_or(f64::NAN), e)
}

/// `x·2^e`, exact while the result is normal.
fn times_power_of_two(mut x: f64, mut e: i64) -> f64 {
    while e > 1000 {
        x *= 2f64.powi(1000);
        e -= 1000;
    }
    while e < -1000 {
        x *= 2f64.powi(-1000);
        e += 1000;
    }
    x * 2f64.powi(e as i32)
}
