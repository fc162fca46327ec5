//! The exact sign of a sum of doubles: a floating-point filter, then the TwoSum cascade, then
//! the exact expansion.

use super::expansion::with_expansion;
use super::sum::cascade;
use crate::geometry::estimate::sum_error_bound;
use std::cmp::Ordering;

/// The exact sign of the real sum of `terms`.
///
/// A floating-point filter decides almost every call: the recursively rounded sum is trusted
/// when its magnitude exceeds a bound on its accumulated rounding error. Otherwise the sum is
/// rebuilt exactly as an expansion and its sign is the sign of its largest component.
///
/// ```
/// use kepler::geometry::exact::sum_sign;
/// use std::cmp::Ordering;
/// assert_eq!(sum_sign(&[1e100, 1.0, -1e100]), Ordering::Greater);
/// assert_eq!(sum_sign(&[0.5, 0.25, -0.75]), Ordering::Equal);
/// assert_eq!(sum_sign(&[]), Ordering::Equal);
/// ```
#[inline]
pub fn sum_sign(terms: &[f64]) -> Ordering {
    sum_sign_inline(terms)
}

/// [`sum_sign`] of a fixed number of terms, always inlined (the same result): for hot callers
/// of short sums, whose terms then stay in registers unless the filter fails.
///
/// ```
/// use kepler::geometry::exact::{sum_sign, sum_sign_array};
/// let terms = [0.1, 0.2, -0.3];
/// assert_eq!(sum_sign_array(terms), sum_sign(&terms));
/// ```
#[inline(always)]
pub fn sum_sign_array<const N: usize>(terms: [f64; N]) -> Ordering {
    sum_sign_inline(&terms)
}

#[inline(always)]
fn sum_sign_inline(terms: &[f64]) -> Ordering {
    match filtered_sign_inline(terms) {
        Some(sign) => sign,
        None => exact_sign(terms),
    }
}

/// The sign of the real sum of `terms` when the floating-point filter of [`sum_sign`] can
/// certify it (always correct when `Some`), `None` when only the exact expansion can decide.
///
/// ```
/// use kepler::geometry::exact::filtered_sign;
/// use std::cmp::Ordering;
/// assert_eq!(filtered_sign(&[1.0, 2.0, -2.5]), Some(Ordering::Greater));
/// assert_eq!(filtered_sign(&[0.0, 0.0]), Some(Ordering::Equal));
/// assert_eq!(filtered_sign(&[0.5, 0.25, -0.75]), None); // an exact zero needs the expansion
/// ```
#[inline]
pub fn filtered_sign(terms: &[f64]) -> Option<Ordering> {
    filtered_sign_inline(terms)
}

#[inline(always)]
fn filtered_sign_inline(terms: &[f64]) -> Option<Ordering> {
    let mut sum = 0.0;
    let mut magnitude = 0.0;
    for &t in terms {
        sum += t;
        magnitude += t.abs();
    }
    let bound = sum_error_bound(terms.len(), magnitude);
    if sum > bound {
        Some(Ordering::Greater)
    } else if sum < -bound {
        Some(Ordering::Less)
    } else if magnitude == 0.0 {
        Some(Ordering::Equal)
    } else {
        None
    }
}

/// The exact sign of the sum (the filter's fallback): by the TwoSum cascade of
/// [`accurate_sum`](super::accurate_sum) when it leaves no residual (the exact sum is then
/// `sum + err`, two doubles, whose rounded sum has its sign since a sum of doubles rounds to
/// zero only when it is zero), otherwise by the sign of the exact expansion.
#[cold]
#[inline(never)]
pub(super) fn exact_sign(terms: &[f64]) -> Ordering {
    if let [a, b, ref rest @ ..] = *terms {
        let (sum, err, residual) = cascade(a, b, rest);
        if residual == 0.0 {
            return sign_of(sum + err);
        }
    }
    with_expansion(terms, |e| sign_of(e.last().copied().unwrap_or(0.0)))
}

/// The sign of a double as an ordering (NaN counts as zero).
#[inline]
pub(super) fn sign_of(x: f64) -> Ordering {
    if x > 0.0 {
        Ordering::Greater
    } else if x < 0.0 {
        Ordering::Less
    } else {
        Ordering::Equal
    }
}
