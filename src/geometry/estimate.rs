//! Rounded values with certified error bounds: the filter in front of every exact sign.
//!
//! An [`Estimate`] is a polynomial's value computed in `f64` together with a bound on its
//! error, derived by counting roundings (the error model is written out in
//! [`kernel`](super::kernel)). Its [`sign`](Estimate::sign) is certified when the value is
//! farther from zero than the bound; otherwise the caller's exact path decides.
//!
//! ```
//! use kepler::geometry::estimate::Estimate;
//! use std::cmp::Ordering;
//! assert_eq!(Estimate { value: 1.0, bound: 0.5 }.sign(), Some(Ordering::Greater));
//! assert_eq!(Estimate { value: 1.0, bound: 2.0 }.sign(), None);
//! ```

use super::arithmetic::{Mode, count_filter, mode, others_running};
use std::cmp::Ordering;

/// The unit roundoff of `f64`, `u = 2⁻⁵³`: half the gap between 1 and the next double, the
/// largest relative error of one rounding to nearest.
///
/// ```
/// assert_eq!(kepler::geometry::estimate::UNIT_ROUNDOFF, 2f64.powi(-53));
/// ```
pub const UNIT_ROUNDOFF: f64 = f64::EPSILON / 2.0;

/// A bound on the error of a sum of `n` terms added one by one in `f64`, each term exact or
/// rounded once (a product of two doubles, say), whose magnitudes sum to at most
/// `magnitude`: `|computed − exact| ≤ (u + γ_(n−1))·magnitude` with `γ_k = k·u / (1 − k·u)`;
/// `2n·u·magnitude` absorbs the denominator, a `magnitude` itself computed with a few
/// roundings, and the roundings of the bound, and `MIN_POSITIVE` a sum that underflows.
///
/// ```
/// use kepler::geometry::estimate::{UNIT_ROUNDOFF, sum_error_bound};
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
/// `[value − bound, value + bound]` (see the [kernel documentation](super::kernel) for the model).
///
/// ```
/// use kepler::geometry::estimate::Estimate;
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
    /// assert_eq!(kepler::geometry::estimate::Estimate::exact(0.5).bound, 0.0);
    /// ```
    #[inline]
    pub fn exact(value: f64) -> Estimate {
        Estimate { value, bound: 0.0 }
    }

    /// The sign of the exact number when the estimate certifies it (`|value| > bound`), else
    /// `None`; never for a NaN or infinite estimate.
    ///
    /// ```
    /// use kepler::geometry::estimate::Estimate;
    /// use std::cmp::Ordering;
    /// assert_eq!(Estimate { value: -2.0, bound: 1.0 }.sign(), Some(Ordering::Less));
    /// assert_eq!(Estimate { value: 0.5, bound: 1.0 }.sign(), None);
    /// assert_eq!(Estimate::exact(0.0).sign(), None);
    /// assert_eq!(Estimate { value: f64::NAN, bound: 0.0 }.sign(), None);
    /// ```
    ///
    /// On a thread that runs under an [`Arithmetic`](super::arithmetic::Arithmetic) other than [`Arithmetic::Exact`](super::arithmetic::Arithmetic::Exact) (a
    /// worker of [`with_arithmetic`](super::arithmetic::with_arithmetic), for the error report), the rounded value decides
    /// instead: see there.
    #[inline]
    pub fn sign(&self) -> Option<Ordering> {
        if others_running() {
            return self.sign_in_mode();
        }
        self.certified_sign()
    }

    /// [`sign`](Self::sign) in the exact arithmetic: the certified sign or `None`.
    #[inline]
    fn certified_sign(&self) -> Option<Ordering> {
        if self.value > self.bound && self.value.is_finite() {
            Some(Ordering::Greater)
        } else if self.value < -self.bound && self.value.is_finite() {
            Some(Ordering::Less)
        } else {
            None
        }
    }

    /// [`sign`](Self::sign) under this thread's arithmetic when some thread runs another than
    /// the plain exact one: certified (and counted, when counting), or decided by the rounded
    /// value alone. A NaN or infinite value decides nothing (the caller's exact path does).
    #[cold]
    #[inline(never)]
    fn sign_in_mode(&self) -> Option<Ordering> {
        let mode = mode();
        match mode {
            Mode::Exact => return self.certified_sign(),
            Mode::Counted => {
                let sign = self.certified_sign();
                count_filter(sign.is_none());
                return sign;
            }
            _ => {}
        }
        if !self.value.is_finite() {
            return None;
        }
        if let Mode::Tolerance(tolerance) = mode {
            // The bound is a few units of roundoff times the magnitude of the terms.
            let magnitude = self.bound / UNIT_ROUNDOFF;
            if self.value.abs() <= tolerance * magnitude {
                return Some(Ordering::Equal);
            }
        }
        self.value.partial_cmp(&0.0)
    }

    /// The product: `|x̂ŷ − xy| ≤ |x̂|·e_y + |ŷ|·e_x + e_x·e_y`, plus the rounding of the product
    /// (`u·|x̂ŷ|`); the five roundings of the bound's own sum are covered by the factor
    /// `1 + 8u`.
    ///
    /// ```
    /// use kepler::geometry::estimate::Estimate;
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
    /// use kepler::geometry::estimate::Estimate;
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
    /// use kepler::geometry::estimate::Estimate;
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
