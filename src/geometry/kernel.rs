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
//! A sign is then decided exactly: the estimate's sign when `|value| > bound`
//! (almost always), else the sign of the expansion. A NaN or infinite estimate never decides.
//!
//! Expansion arithmetic is exact only while no partial product overflows or loses bits to
//! underflow, which depends on the polynomial's degree and on the binary exponents of its
//! inputs ([`Exponents::exact_for`]): for `orient3d` (degree 3), nonzero coordinates between
//! about `2^-306` and `2^330`; for a product of two such, between `2^-127` and `2^163`. The
//! engine brings a scene into that window by an exact power-of-two scaling before it works on
//! it, so the expansions serve almost every call; a polynomial whose inputs still fall outside
//! (a view direction with a component of `1e-300`, say, or a scene whose coordinates span more
//! than the window) is evaluated in exact rational arithmetic instead ([`Ring`], with
//! `num-rational`). So every sign is exact for every finite input.
//!
//! A constructed point (where an edge is cut, where a ray meets a plane) is a ratio of such
//! polynomials of the input: numerator and denominator are formed as exact expansions, each
//! rounded once to the nearest double, and divided, so each coordinate is within 1.5 units in
//! the last place of the exact one, and the same input gives the same bits whatever the order
//! of the work.
//!
//! # Swapping the arithmetic
//!
//! For measuring what exactness costs and what the shortcuts lose, the error report runs the
//! same algorithms under cheaper arithmetic (plain `f64`, a tolerance, `f32`): the filter
//! ([`Estimate::sign`]) and the constructions consult their thread's
//! [`Arithmetic`](super::arithmetic::Arithmetic), which is exact everywhere but on the threads
//! that [`with_arithmetic`](super::arithmetic::with_arithmetic) starts for the report (see
//! [`super::arithmetic`]).
//!
//! ```
//! use kepler::geometry::kernel::{Estimate, Polynomial};
//! use kepler::geometry::{Point3, predicates::Orient3d};
//! use std::cmp::Ordering;
//! // Far from the origin the rounded determinant cannot tell; the expansion can.
//! let (a, b, c) = (Point3::new(1e15, 0.0, 1e15), Point3::new(1e15 + 1.0, 0.0, 1e15), Point3::new(1e15, 1.0, 1e15));
//! let d = Point3::new(3.0, 5.0, 1e15 - 0.125);
//! let det = Orient3d([a, b, c, d]);
//! assert_eq!(det.sign(), Ordering::Greater);
//! assert_eq!(Estimate { value: 1.0, bound: 0.5 }.sign(), Some(Ordering::Greater));
//! ```

use super::arithmetic::builds_in_single;
use super::exact::{estimate, expansion_product, expansion_sum, negated, scale_expansion};
use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::{Signed, Zero};
use std::cmp::Ordering;
use std::ops::{Add, Mul, Neg, Sub};

// The filter and the arithmetic, in their own files, named here too: every predicate and
// construction reads them beside the polynomial vocabulary below.
pub use super::arithmetic::{
    Arithmetic, FilterCounts, arithmetic, builds_exactly, count_filters, plain_dot, with_arithmetic,
};
pub use super::estimate::{Estimate, UNIT_ROUNDOFF, sum_error_bound};

/// A real number that is a polynomial in the input coordinates, known as an [`Estimate`] and
/// exactly, as an expansion.
///
/// ```
/// use kepler::geometry::kernel::{Estimate, Exponents, Polynomial, Ring};
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
///     fn evaluate<R: Ring>(&self) -> R {
///         R::from_f64(self.0) - R::from_f64(self.1)
///     }
///     fn degree(&self) -> u32 {
///         1
///     }
///     fn exponents(&self) -> Exponents {
///         Exponents::of(&[self.0, self.1])
///     }
/// }
/// assert_eq!(Gap(1.0, 1.0 - f64::EPSILON / 2.0).sign(), Ordering::Greater);
/// assert_eq!(Gap(0.1, 0.1).sign(), Ordering::Equal);
/// ```
pub trait Polynomial {
    /// A rounded value and a certified bound on its error.
    fn estimate(&self) -> Estimate;

    /// The exact value, as an expansion (empty for zero): exact when
    /// [`exponents`](Self::exponents) are [`exact_for`](Exponents::exact_for) the
    /// [`degree`](Self::degree).
    fn expansion(&self) -> Vec<f64>;

    /// The polynomial computed in the ring `R` by the same formula: exactly in
    /// [`BigRational`], rounded at every step in `f64` or `f32`.
    fn evaluate<R: Ring>(&self) -> R;

    /// Its degree in the inputs (a bound on the number of inputs multiplied in a monomial).
    fn degree(&self) -> u32;

    /// The binary exponents of its nonzero inputs.
    fn exponents(&self) -> Exponents;

    /// The exact sign: the estimate's when it is certified, else the expansion's when the
    /// inputs allow exact expansions, else the rational value's. A polynomial with a faster
    /// exact predicate (`robust`'s adaptive `orient3d`, say) overrides it.
    #[inline]
    fn sign(&self) -> Ordering {
        sign_with(self, || expansion_sign(&self.expansion()))
    }
}

/// The sign of `p`: its estimate's when certified, else `exact()` (an exact predicate that
/// relies on expansion arithmetic) when the inputs allow exact expansions, else the sign of
/// its rational value.
///
/// ```
/// use kepler::geometry::kernel::{Polynomial, sign_with};
/// use kepler::geometry::predicates::Orient2d;
/// use std::cmp::Ordering;
/// let flat = Orient2d([[0.0, 0.0], [1.0, 1.0], [2.0, 2.0]]);
/// assert_eq!(sign_with(&flat, || Ordering::Equal), Ordering::Equal);
/// ```
#[inline]
pub fn sign_with<P: Polynomial + ?Sized>(p: &P, exact: impl FnOnce() -> Ordering) -> Ordering {
    match p.estimate().sign() {
        Some(sign) => sign,
        None if p.exponents().exact_for(p.degree()) => exact(),
        None => exact_sign(p),
    }
}

/// The exact sign of `p` without its filter: from its expansion when its inputs allow, else
/// from its rational value.
///
/// ```
/// use kepler::geometry::kernel::exact_sign;
/// use kepler::geometry::{Point3, predicates::Orient3d};
/// use std::cmp::Ordering;
/// let t = 1e-300; // products of three such coordinates underflow: evaluated as rationals
/// let det = Orient3d([
///     Point3::new(0.0, 0.0, 0.0), Point3::new(t, 0.0, 0.0),
///     Point3::new(0.0, t, 0.0), Point3::new(0.0, 0.0, -t),
/// ]);
/// assert_eq!(exact_sign(&det), Ordering::Greater);
/// ```
#[cold]
pub fn exact_sign<P: Polynomial + ?Sized>(p: &P) -> Ordering {
    let exponents = p.exponents();
    if exponents.max > 1023 {
        // An infinite or NaN input (the engine passes none): meaningless, but no panic.
        return Ordering::Equal;
    }
    if exponents.exact_for(p.degree()) {
        expansion_sign(&p.expansion())
    } else {
        rational_sign(&p.evaluate::<BigRational>())
    }
}

/// The value of `p` to within a relative 2⁻²⁰, enough to order and place cuts: its estimate
/// when the certified bound is below 2⁻²⁰ of it (the common case, no extra work), else its
/// exact expansion rounded correctly, else its rational value rounded. For parameters computed
/// from polynomials whose estimates cancel (a far perspective eye, say), where the plain
/// estimate may be off in every digit or even in sign.
///
/// ```
/// use kepler::geometry::kernel::{Polynomial, value};
/// use kepler::geometry::{Point3, predicates::Orient3d};
/// // Far from the origin, the filter's value cancels; the exact one does not.
/// let f = 2f64.powi(30);
/// let det = Orient3d([
///     Point3::new(f, f, f), Point3::new(f + 1.0, f, f),
///     Point3::new(f, f + 1.0, f), Point3::new(f, f, f - 0.5),
/// ]);
/// assert_eq!(value(&det), 0.5);
/// ```
pub fn value<P: Polynomial + ?Sized>(p: &P) -> f64 {
    value_within(p, RELATIVE_VALUE)
}

/// The relative bound under which [`value`] keeps an estimate: 2⁻²⁰.
const RELATIVE_VALUE: f64 = 1.0 / (1u64 << 20) as f64;

/// The value of `p` to within a relative `relative` (at least a few units in the last place):
/// its estimate when the certified bound allows, else [`rounded`] (the estimate again if that
/// does not fit a double).
///
/// ```
/// use kepler::geometry::kernel::value_within;
/// use kepler::geometry::{Point3, predicates::Orient3d};
/// let det = Orient3d([
///     Point3::new(0.0, 0.0, 0.0), Point3::new(1.0, 0.0, 0.0),
///     Point3::new(0.0, 1.0, 0.0), Point3::new(0.0, 0.0, -3.0),
/// ]);
/// assert_eq!(value_within(&det, 1e-15), 3.0);
/// ```
pub fn value_within<P: Polynomial + ?Sized>(p: &P, relative: f64) -> f64 {
    let e = p.estimate();
    if e.value.is_finite() && e.bound <= e.value.abs() * relative {
        return e.value;
    }
    if p.exponents().max > 1023 {
        return e.value;
    }
    Some(rounded(p))
        .filter(|v| v.is_finite())
        .unwrap_or(e.value)
}

/// The exact value of `p` rounded once to the nearest double: from its expansion when its
/// inputs allow exact expansions, else from its rational value (NaN where that does not fit a
/// double).
///
/// ```
/// use kepler::geometry::kernel::rounded;
/// use kepler::geometry::{Point3, predicates::Orient3d};
/// let t = 1e-300; // products underflow: rounded from the rational value
/// let det = Orient3d([
///     Point3::new(0.0, 0.0, 0.0), Point3::new(t, 0.0, 0.0),
///     Point3::new(0.0, t, 0.0), Point3::new(0.0, 0.0, -t),
/// ]);
/// assert_eq!(rounded(&det), 0.0); // 1e-900 rounds to zero
/// ```
pub fn rounded<P: Polynomial + ?Sized>(p: &P) -> f64 {
    use num_traits::ToPrimitive;
    if p.exponents().exact_for(p.degree()) {
        estimate(&p.expansion())
    } else {
        p.evaluate::<BigRational>().to_f64().unwrap_or(f64::NAN)
    }
}

/// The sign of an exact rational.
fn rational_sign(x: &BigRational) -> Ordering {
    let n: &BigInt = x.numer();
    if n.is_zero() {
        Ordering::Equal
    } else if n.is_positive() {
        Ordering::Greater
    } else {
        Ordering::Less
    }
}

/// A commutative ring in which the kernel evaluates polynomials: exact rationals for the last
/// resort of [`exact_sign`], and rounded `f64` and `f32` for measuring cheaper arithmetic.
///
/// ```
/// use kepler::geometry::kernel::{Polynomial, Ring};
/// use kepler::geometry::predicates::Orient2d;
/// use num_rational::BigRational;
/// let det = Orient2d([[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]]);
/// assert_eq!(det.evaluate::<f64>(), 1.0);
/// assert_eq!(det.evaluate::<f32>(), 1.0);
/// assert_eq!(det.evaluate::<BigRational>(), BigRational::from_f64(1.0));
/// ```
pub trait Ring:
    Sized + Clone + Add<Output = Self> + Sub<Output = Self> + Mul<Output = Self> + Neg<Output = Self>
{
    /// The ring element nearest a finite double (exact in the rationals).
    fn from_f64(x: f64) -> Self;
}

impl Ring for f64 {
    #[inline]
    fn from_f64(x: f64) -> f64 {
        x
    }
}

impl Ring for f32 {
    #[inline]
    fn from_f64(x: f64) -> f32 {
        x as f32
    }
}

impl Ring for BigRational {
    /// Exact; a non-finite `x` (never passed by the engine) gives zero.
    fn from_f64(x: f64) -> BigRational {
        BigRational::from_float(x).unwrap_or_else(BigRational::zero)
    }
}

/// The smallest and largest binary exponents of a polynomial's nonzero inputs (`x` has
/// exponent `e` when `2^e ≤ |x| < 2^(e+1)`; a subnormal counts as `-1023`, an infinity or
/// NaN as `1024`), which decide
/// whether expansion arithmetic evaluates it exactly.
///
/// ```
/// use kepler::geometry::kernel::Exponents;
/// let e = Exponents::of(&[0.0, 0.75, -12.0]);
/// assert_eq!((e.min, e.max), (-1, 3));
/// assert!(e.exact_for(3));
/// assert!(!Exponents::of(&[1e-300, 1.0]).exact_for(3));
/// assert!(Exponents::of(&[0.0]).exact_for(9)); // no nonzero input
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Exponents {
    /// The smallest exponent (`i32::MAX` when no input is nonzero).
    pub min: i32,
    /// The largest exponent (`i32::MIN` when no input is nonzero).
    pub max: i32,
}

impl Exponents {
    /// No nonzero input.
    pub const NONE: Exponents = Exponents {
        min: i32::MAX,
        max: i32::MIN,
    };

    /// The exponents of `values`' nonzero entries.
    ///
    /// ```
    /// use kepler::geometry::kernel::Exponents;
    /// assert_eq!(Exponents::of(&[1.0, 1024.0]), Exponents { min: 0, max: 10 });
    /// ```
    #[inline]
    pub fn of(values: &[f64]) -> Exponents {
        values
            .iter()
            .fold(Exponents::NONE, |e, &x| e.union(Exponents::one(x)))
    }

    /// The exponent of one value (none for zero).
    #[inline]
    fn one(x: f64) -> Exponents {
        if x == 0.0 {
            return Exponents::NONE;
        }
        let biased = ((x.to_bits() >> 52) & 0x7ff) as i32;
        let k = if biased == 0 { -1023 } else { biased - 1023 };
        Exponents { min: k, max: k }
    }

    /// The exponents of the inputs of both.
    ///
    /// ```
    /// use kepler::geometry::kernel::Exponents;
    /// let u = Exponents::of(&[1.0]).union(Exponents::of(&[8.0]));
    /// assert_eq!((u.min, u.max), (0, 3));
    /// ```
    #[inline]
    pub fn union(self, other: Exponents) -> Exponents {
        Exponents {
            min: self.min.min(other.min),
            max: self.max.max(other.max),
        }
    }

    /// The exponents within which the engine works: a scene whose nonzero coordinates lie in
    /// `[2^-60, 2^101)` has every expansion of degree up to 9 exact (see
    /// [`exact_for`](Self::exact_for)), which covers every construction of the engine.
    ///
    /// ```
    /// use kepler::geometry::kernel::Exponents;
    /// assert!(Exponents::WINDOW.exact_for(9));
    /// ```
    pub const WINDOW: Exponents = Exponents { min: -60, max: 100 };

    /// The power of two `k` by which to scale inputs with these exponents so that they lie in
    /// [`WINDOW`](Self::WINDOW): 0 when they already do (or none is nonzero); otherwise the
    /// shift that brings the largest exponent to the window's top, so that nothing overflows
    /// and as little as possible falls below the window; but never so far down that a normal
    /// input becomes subnormal (or a subnormal one loses more bits), nor so far up that one
    /// overflows. So scaling by `2^k` is always exact, and every sign and every rounded
    /// construction of the scaled inputs is that of the inputs, scaled. (Inputs spanning more
    /// than the window keep values above it; the kernel decides their signs in rationals.)
    ///
    /// ```
    /// use kepler::geometry::kernel::Exponents;
    /// assert_eq!(Exponents::of(&[1e-3, 1e6]).shift(), 0);
    /// assert_eq!(Exponents::of(&[1e-300]).shift(), 100 - (-997));
    /// assert_eq!(Exponents::of(&[1e300, 1.0]).shift(), 100 - 996);
    /// // 4e-50 (2^-165 and a bit) must stay normal: scaled by 2^-857, not 2^-896.
    /// assert_eq!(Exponents::of(&[1e300, 4e-50]).shift(), -1022 + 165);
    /// ```
    pub fn shift(self) -> i32 {
        if self.min > self.max
            || (self.min >= Exponents::WINDOW.min && self.max <= Exponents::WINDOW.max)
        {
            return 0;
        }
        let lowest = if self.min < -1022 {
            0
        } else {
            -1022 - self.min
        };
        let highest = 1023 - self.max;
        (Exponents::WINDOW.max - self.max).clamp(lowest.min(highest), highest)
    }

    /// Whether Shewchuk's expansion arithmetic evaluates a polynomial of `degree` in inputs
    /// with these exponents exactly. A monomial multiplies at most `degree` inputs (or their
    /// differences, whose components are multiples of the smaller input's unit in the last
    /// place); its exact products stay multiples of `2^-1074` when every input's last place is
    /// at least `2^(-1074/degree)`, that is its exponent at least `52 − 1074/degree`, and stay
    /// below `2^1000` with room for the sums when every exponent is at most
    /// `1000/degree − 3`.
    ///
    /// ```
    /// use kepler::geometry::kernel::Exponents;
    /// assert!(Exponents { min: -306, max: 330 }.exact_for(3));
    /// assert!(!Exponents { min: -307, max: 0 }.exact_for(3));
    /// assert!(!Exponents { min: 0, max: 331 }.exact_for(3));
    /// ```
    #[inline]
    pub fn exact_for(self, degree: u32) -> bool {
        let d = degree.max(1) as i32;
        self.min > self.max || (self.min >= 52 - 1074 / d && self.max <= 1000 / d - 3)
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

    fn evaluate<R: Ring>(&self) -> R {
        self.0.evaluate::<R>() * self.1.evaluate::<R>()
    }

    fn degree(&self) -> u32 {
        self.0.degree() + self.1.degree()
    }

    fn exponents(&self) -> Exponents {
        self.0.exponents().union(self.1.exponents())
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

    fn evaluate<R: Ring>(&self) -> R {
        self.0.evaluate::<R>() - self.1.evaluate::<R>()
    }

    fn degree(&self) -> u32 {
        self.0.degree().max(self.1.degree())
    }

    fn exponents(&self) -> Exponents {
        self.0.exponents().union(self.1.exponents())
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

    fn evaluate<R: Ring>(&self) -> R {
        let xa = self.0.evaluate::<R>();
        xa.clone() + R::from_f64(self.2) * (self.1.evaluate::<R>() - xa)
    }

    fn degree(&self) -> u32 {
        self.0.degree().max(self.1.degree()) + 1
    }

    fn exponents(&self) -> Exponents {
        self.0
            .exponents()
            .union(self.1.exponents())
            .union(Exponents::of(&[self.2]))
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
            None => exact_sign(self),
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

/// `n / d` as this thread's cheaper [`Arithmetic`] builds it: both evaluated by the same formula
/// in `f64` (in `f32` for [`Arithmetic::Single`]) and divided. The engine calls it only when
/// [`builds_exactly`] is false.
///
/// ```
/// use kepler::geometry::kernel::{Arithmetic, plain_ratio, with_arithmetic};
/// use kepler::geometry::predicates::Orient2d;
/// let n = Orient2d([[0.0, 0.0], [1.0, 0.0], [0.0, 0.1]]);
/// let d = Orient2d([[0.0, 0.0], [1.0, 0.0], [0.0, 0.3]]);
/// assert_eq!(with_arithmetic(Arithmetic::Float, || plain_ratio(&n, &d)), 0.1 / 0.3);
/// assert_eq!(with_arithmetic(Arithmetic::Single, || plain_ratio(&n, &d)), (0.1f32 / 0.3f32) as f64);
/// ```
pub fn plain_ratio<N: Polynomial + ?Sized, D: Polynomial + ?Sized>(n: &N, d: &D) -> f64 {
    if builds_in_single() {
        f64::from(n.evaluate::<f32>() / d.evaluate::<f32>())
    } else {
        n.evaluate::<f64>() / d.evaluate::<f64>()
    }
}
