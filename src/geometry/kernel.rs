//! The kernel: how kepler decides a sign and builds a point, and the one place that knows
//! about rounding.
//!
//! # The error model
//!
//! Every number the engine decides on is a polynomial in the input coordinates (a determinant
//! such as `orient3d`, a product or difference of two, a point of an edge `(1 − t)·O(a) +
//! t·O(b)`). Such a [`Polynomial`] is known two ways:
//!
//! - an [`Estimate`]: its value in `f64`, with a certified bound on the error, so that the
//!   real number lies in `[value − bound, value + bound]`. Each floating-point operation
//!   rounds to nearest, `fl(x ∘ y) = (x ∘ y)(1 + δ)` with `|δ| ≤ u` ([`UNIT_ROUNDOFF`],
//!   `u = 2⁻⁵³`), plus an absolute error of at most `2⁻¹⁰⁷⁵` when the result is subnormal;
//!   each bound below is derived by counting those roundings, padded for the roundings of the
//!   bound itself, and every bound adds `f64::MIN_POSITIVE` (`2⁻¹⁰²²`), far above any
//!   accumulated underflow;
//! - its exact value, an *expansion* (Shewchuk 1997; see [`super::exact`]): nonoverlapping
//!   doubles whose sum is the polynomial exactly, as long as no partial product overflows
//!   (coordinates up to [`MAX_COORDINATE`](super::predicates::MAX_COORDINATE) in magnitude)
//!   or underflows (nonzero coordinates at least about `1e-90`).
//!
//! A sign is then decided by the [`Exact`] kernel: the estimate's sign when `|value| > bound`
//! (almost always), else the sign of the expansion. A NaN or infinite estimate never decides.
//!
//! A constructed point (where an edge is cut, where a ray meets a plane) is a ratio of such
//! polynomials of the input: numerator and denominator are formed as exact expansions, each
//! rounded once to the nearest double, and divided, so each coordinate is within 1.5 units in
//! the last place of the exact one, and the same input gives the same bits whatever the order
//! of the work.
//!
//! # Swapping the arithmetic
//!
//! The [`Kernel`] trait is the seam where cheaper arithmetic can replace the exact one, for
//! measuring what exactness costs and what the shortcuts lose: a kernel decides the sign of any
//! [`Polynomial`]. [`Exact`] is the engine's; a plain-`f64` kernel would take the sign of
//! `estimate().value` alone, a tolerance kernel would call values within `ε` zero.
//!
//! ```
//! use kepler::geometry::kernel::{Estimate, Exact, Kernel, Polynomial};
//! use kepler::geometry::{Point3, predicates::Orient3d};
//! use std::cmp::Ordering;
//! // Far from the origin the rounded determinant cannot tell; the expansion can.
//! let (a, b, c) = (Point3::new(1e15, 0.0, 1e15), Point3::new(1e15 + 1.0, 0.0, 1e15), Point3::new(1e15, 1.0, 1e15));
//! let d = Point3::new(3.0, 5.0, 1e15 - 0.125);
//! let det = Orient3d([a, b, c, d]);
//! assert_eq!(Exact.sign(&det), Ordering::Greater);
//! assert_eq!(Estimate { value: 1.0, bound: 0.5 }.sign(), Some(Ordering::Greater));
//! ```

use super::exact::{estimate, expansion_product, expansion_sum, negated, scale_expansion};
use std::cmp::Ordering;

/// The unit roundoff of `f64`, `u = 2⁻⁵³`: half the gap between 1 and the next double, the
/// largest relative error of one rounding to nearest.
///
/// ```
/// assert_eq!(kepler::geometry::kernel::UNIT_ROUNDOFF, 2f64.powi(-53));
/// ```
pub const UNIT_ROUNDOFF: f64 = f64::EPSILON / 2.0;

/// A bound on the error of a sum of `n` terms added one by one in `f64`, each term exact or
/// rounded once (a product of two doubles, say), whose magnitudes sum to at most
/// `magnitude`: `|computed − exact| ≤ (u + γ_(n−1))·magnitude` with `γ_k = k·u / (1 − k·u)`;
/// `2n·u·magnitude` absorbs the denominator, a `magnitude` itself computed with a few
/// roundings, and the roundings of the bound, and `MIN_POSITIVE` a sum that underflows.
///
/// ```
/// use kepler::geometry::kernel::{UNIT_ROUNDOFF, sum_error_bound};
/// let terms: [f64; 3] = [0.1, 0.2, -0.3];
/// let magnitude: f64 = terms.iter().map(|t| t.abs()).sum();
/// let computed: f64 = terms.iter().sum();
/// // The exact sum of these doubles is 2^-55.
/// assert!((computed - 2f64.powi(-55)).abs() <= sum_error_bound(3, magnitude));
/// assert_eq!(sum_error_bound(3, 1.0), 6.0 * UNIT_ROUNDOFF + f64::MIN_POSITIVE);
/// ```
#[inline]
pub fn sum_error_bound(n: usize, magnitude: f64) -> f64 {
    (2 * n) as f64 * UNIT_ROUNDOFF * magnitude + f64::MIN_POSITIVE
}

/// A rounded value with a certified bound on its error: the exact number lies in
/// `[value − bound, value + bound]` (see the [module documentation](self) for the model).
///
/// ```
/// use kepler::geometry::kernel::Estimate;
/// use std::cmp::Ordering;
/// let x = Estimate { value: 3.0, bound: 1e-15 };
/// let y = Estimate::exact(2.0);
/// let p = x.product(&y);
/// assert_eq!(p.value, 6.0);
/// assert!(p.bound >= 2e-15);
/// assert_eq!(x.difference(&y).sign(), Some(Ordering::Greater));
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Estimate {
    /// The rounded value.
    pub value: f64,
    /// A bound on `|exact − value|`.
    pub bound: f64,
}

impl Estimate {
    /// A value known exactly.
    ///
    /// ```
    /// assert_eq!(kepler::geometry::kernel::Estimate::exact(0.5).bound, 0.0);
    /// ```
    #[inline]
    pub fn exact(value: f64) -> Estimate {
        Estimate { value, bound: 0.0 }
    }

    /// The sign of the exact number when the estimate certifies it (`|value| > bound`), else
    /// `None`; never for a NaN or infinite estimate.
    ///
    /// ```
    /// use kepler::geometry::kernel::Estimate;
    /// use std::cmp::Ordering;
    /// assert_eq!(Estimate { value: -2.0, bound: 1.0 }.sign(), Some(Ordering::Less));
    /// assert_eq!(Estimate { value: 0.5, bound: 1.0 }.sign(), None);
    /// assert_eq!(Estimate::exact(0.0).sign(), None);
    /// assert_eq!(Estimate { value: f64::NAN, bound: 0.0 }.sign(), None);
    /// ```
    #[inline]
    pub fn sign(&self) -> Option<Ordering> {
        if self.value > self.bound && self.value.is_finite() {
            Some(Ordering::Greater)
        } else if self.value < -self.bound && self.value.is_finite() {
            Some(Ordering::Less)
        } else {
            None
        }
    }

    /// The product: `|x̂ŷ − xy| ≤ |x̂|·e_y + |ŷ|·e_x + e_x·e_y`, plus the rounding of the product
    /// (`u·|x̂ŷ|`); the five roundings of the bound's own sum are covered by the factor
    /// `1 + 8u`.
    ///
    /// ```
    /// use kepler::geometry::kernel::Estimate;
    /// let p = Estimate { value: 2.0, bound: 0.25 }.product(&Estimate { value: -3.0, bound: 0.5 });
    /// assert_eq!(p.value, -6.0);
    /// assert!(p.bound >= 2.0 * 0.5 + 3.0 * 0.25 + 0.25 * 0.5);
    /// ```
    #[inline]
    pub fn product(&self, other: &Estimate) -> Estimate {
        let value = self.value * other.value;
        let bound = (self.value.abs() * other.bound
            + other.value.abs() * self.bound
            + self.bound * other.bound
            + UNIT_ROUNDOFF * value.abs())
            * (1.0 + 8.0 * UNIT_ROUNDOFF)
            + f64::MIN_POSITIVE;
        Estimate { value, bound }
    }

    /// The difference: `e_x + e_y` plus the rounding of the difference (`u·|x̂ − ŷ|`), the
    /// bound's own roundings covered by the factor `1 + 4u`.
    ///
    /// ```
    /// use kepler::geometry::kernel::Estimate;
    /// let d = Estimate { value: 1.0, bound: 0.5 }.difference(&Estimate { value: 0.25, bound: 0.25 });
    /// assert_eq!(d.value, 0.75);
    /// assert!(d.bound >= 0.75);
    /// ```
    #[inline]
    pub fn difference(&self, other: &Estimate) -> Estimate {
        let value = self.value - other.value;
        let bound = (self.bound + other.bound + UNIT_ROUNDOFF * value.abs())
            * (1.0 + 4.0 * UNIT_ROUNDOFF)
            + f64::MIN_POSITIVE;
        Estimate { value, bound }
    }

    /// The value `(1 − t)·x + t·y` at a parameter `0 < t < 1`, computed as `x̂ + t·(ŷ − x̂)`:
    /// each estimate is off by at most its bound, and the three roundings of the combination
    /// by at most `3u(|x̂| + |ŷ|)`, padded to `4u`.
    ///
    /// ```
    /// use kepler::geometry::kernel::Estimate;
    /// let m = Estimate::exact(-1.0).between(&Estimate::exact(3.0), 0.25);
    /// assert_eq!(m.value, 0.0);
    /// assert!(m.bound > 0.0 && m.bound < 1e-14);
    /// ```
    #[inline]
    pub fn between(&self, other: &Estimate, t: f64) -> Estimate {
        let value = self.value + t * (other.value - self.value);
        let bound = self.bound
            + other.bound
            + 4.0 * UNIT_ROUNDOFF * (self.value.abs() + other.value.abs())
            + f64::MIN_POSITIVE;
        Estimate { value, bound }
    }
}

/// A real number that is a polynomial in the input coordinates, known as an [`Estimate`] and
/// exactly, as an expansion.
///
/// ```
/// use kepler::geometry::kernel::{Estimate, Polynomial};
/// use std::cmp::Ordering;
/// /// The number `a − b` of two doubles.
/// struct Gap(f64, f64);
/// impl Polynomial for Gap {
///     fn estimate(&self) -> Estimate {
///         Estimate::exact(self.0).difference(&Estimate::exact(self.1))
///     }
///     fn expansion(&self) -> Vec<f64> {
///         kepler::geometry::exact::expansion(&[self.0, -self.1])
///     }
/// }
/// assert_eq!(Gap(1.0, 1.0 - f64::EPSILON / 2.0).sign(), Ordering::Greater);
/// assert_eq!(Gap(0.1, 0.1).sign(), Ordering::Equal);
/// ```
pub trait Polynomial {
    /// A rounded value and a certified bound on its error.
    fn estimate(&self) -> Estimate;

    /// The exact value, as an expansion (empty for zero).
    fn expansion(&self) -> Vec<f64>;

    /// The exact sign: the estimate's when it is certified, else the expansion's. A
    /// polynomial with a faster exact predicate (`robust`'s adaptive `orient3d`, say)
    /// overrides it.
    #[inline]
    fn sign(&self) -> Ordering {
        match self.estimate().sign() {
            Some(sign) => sign,
            None => expansion_sign(&self.expansion()),
        }
    }
}

/// The sign of an expansion: the sign of its largest (last) component.
///
/// ```
/// use kepler::geometry::kernel::expansion_sign;
/// use std::cmp::Ordering;
/// assert_eq!(expansion_sign(&[1e-30, -1.0]), Ordering::Less);
/// assert_eq!(expansion_sign(&[]), Ordering::Equal);
/// ```
#[inline]
pub fn expansion_sign(e: &[f64]) -> Ordering {
    e.last().map_or(Ordering::Equal, |top| {
        top.partial_cmp(&0.0).unwrap_or(Ordering::Equal)
    })
}

/// The product of two polynomials.
///
/// ```
/// use kepler::geometry::kernel::{Polynomial, Product};
/// use kepler::geometry::{Point3, predicates::Orient3d};
/// use std::cmp::Ordering;
/// let o = Point3::origin();
/// let (x, y) = (Point3::new(1.0, 0.0, 0.0), Point3::new(0.0, 1.0, 0.0));
/// let below = Orient3d([o, x, y, Point3::new(0.0, 0.0, -1.0)]);
/// assert_eq!(Product(below, below).sign(), Ordering::Greater);
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Product<A, B>(pub A, pub B);

impl<A: Polynomial, B: Polynomial> Polynomial for Product<A, B> {
    #[inline]
    fn estimate(&self) -> Estimate {
        self.0.estimate().product(&self.1.estimate())
    }

    fn expansion(&self) -> Vec<f64> {
        expansion_product(&self.0.expansion(), &self.1.expansion())
    }

    #[inline]
    fn sign(&self) -> Ordering {
        match self.estimate().sign() {
            Some(sign) => sign,
            // The signs of the factors are cheaper than the product's expansion.
            None => match (self.0.sign(), self.1.sign()) {
                (Ordering::Equal, _) | (_, Ordering::Equal) => Ordering::Equal,
                (a, b) if a == b => Ordering::Greater,
                _ => Ordering::Less,
            },
        }
    }
}

/// The difference of two polynomials.
///
/// ```
/// use kepler::geometry::kernel::{Difference, Polynomial};
/// use kepler::geometry::{Point3, predicates::Orient3d};
/// use std::cmp::Ordering;
/// let (a, b, c) = (Point3::new(0.0, 0.0, 0.0), Point3::new(1.0, 0.0, 0.0), Point3::new(0.0, 1.0, 0.0));
/// let d1 = Orient3d([a, b, c, Point3::new(5.0, 5.0, -1.0)]);
/// let d2 = Orient3d([a, b, c, Point3::new(-5.0, 2.0, -1.0)]);
/// assert_eq!(Difference(d1, d2).sign(), Ordering::Equal); // both are 1
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Difference<A, B>(pub A, pub B);

impl<A: Polynomial, B: Polynomial> Polynomial for Difference<A, B> {
    #[inline]
    fn estimate(&self) -> Estimate {
        self.0.estimate().difference(&self.1.estimate())
    }

    fn expansion(&self) -> Vec<f64> {
        expansion_sum(&self.0.expansion(), &negated(&self.1.expansion()))
    }
}

/// An affine polynomial at a point `X(t) = a + t·(b − a)` of a segment, `0 < t < 1`, from its
/// values at the ends: `(1 − t)·O(a) + t·O(b)`. `X(t)` itself is never rounded.
///
/// ```
/// use kepler::geometry::kernel::{Between, Polynomial};
/// use kepler::geometry::{Point3, predicates::Orient3d};
/// use std::cmp::Ordering;
/// let (p, q, r) = (Point3::new(0.0, 0.0, 0.0), Point3::new(1.0, 0.0, 0.0), Point3::new(0.0, 1.0, 0.0));
/// let (a, b) = (Point3::new(0.0, 0.0, -1.0), Point3::new(0.0, 0.0, 3.0));
/// let at = |t| Between(Orient3d([p, q, r, a]), Orient3d([p, q, r, b]), t);
/// assert_eq!(at(0.25).sign(), Ordering::Equal); // z = 0 on the plane
/// assert_eq!(at(0.125).sign(), Ordering::Greater); // below it
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Between<A>(pub A, pub A, pub f64);

impl<A: Polynomial> Polynomial for Between<A> {
    #[inline]
    fn estimate(&self) -> Estimate {
        self.0.estimate().between(&self.1.estimate(), self.2)
    }

    fn expansion(&self) -> Vec<f64> {
        let (xa, xb) = (self.0.expansion(), self.1.expansion());
        expansion_sum(
            &xa,
            &scale_expansion(&expansion_sum(&xb, &negated(&xa)), self.2),
        )
    }

    #[inline]
    fn sign(&self) -> Ordering {
        let (sa, sb) = (self.0.sign(), self.1.sign());
        // Equal signs at the ends decide every point between them.
        if sa == sb || sb == Ordering::Equal {
            return sa;
        }
        if sa == Ordering::Equal {
            return sb;
        }
        match self.estimate().sign() {
            Some(sign) => sign,
            None => expansion_sign(&self.expansion()),
        }
    }
}

/// The ratio `n / d` of two polynomials rounded once: both exact, each rounded to the nearest
/// double, then divided (within 1.5 units in the last place of the exact ratio). The rule by
/// which every constructed coordinate is built.
///
/// ```
/// use kepler::geometry::kernel::ratio;
/// assert_eq!(ratio(&[1.0, 2.0], &[3.0]), 1.0);
/// assert!(ratio(&[1.0], &[]).is_infinite());
/// ```
#[inline]
pub fn ratio(numerator: &[f64], denominator: &[f64]) -> f64 {
    estimate(numerator) / estimate(denominator)
}

/// An arithmetic that decides signs of polynomials: the seam where cheaper arithmetic can
/// replace the exact one (see the [module documentation](self)).
///
/// ```
/// use kepler::geometry::kernel::{Exact, Kernel};
/// use kepler::geometry::{Point3, predicates::Orient3d};
/// use std::cmp::Ordering;
/// let o = Point3::origin();
/// let (x, y) = (Point3::new(1.0, 0.0, 0.0), Point3::new(0.0, 1.0, 0.0));
/// assert_eq!(Exact.sign(&Orient3d([o, x, y, Point3::new(0.3, 0.3, 0.0)])), Ordering::Equal);
/// ```
pub trait Kernel {
    /// The sign of `p`, as this arithmetic decides it.
    fn sign<P: Polynomial + ?Sized>(&self, p: &P) -> Ordering;
}

/// The engine's arithmetic: every sign exact (a certified floating-point filter, then exact
/// expansions).
///
/// ```
/// use kepler::geometry::kernel::{Exact, Kernel};
/// use kepler::geometry::{Point3, predicates::Orient3d};
/// use std::cmp::Ordering;
/// let a = Point3::new(0.1, 0.2, 0.3);
/// assert_eq!(Exact.sign(&Orient3d([a, a, a, a])), Ordering::Equal);
/// ```
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Exact;

impl Kernel for Exact {
    #[inline]
    fn sign<P: Polynomial + ?Sized>(&self, p: &P) -> Ordering {
        p.sign()
    }
}
