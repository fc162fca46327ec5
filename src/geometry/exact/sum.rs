//! Sums of doubles correctly rounded: a compensated sum certified by an error bound, with
//! the exact expansion rounded from the top as its fallback; the value of an expansion.

use super::expansion::with_expansion;
use super::two_sum;

/// The value of the expansion `e` correctly rounded to the nearest double (ties to even); 0
/// for the empty expansion.
///
/// This is [`accurate_sum`], which rounds the exact sum of *any* list of doubles correctly
/// (its fast path is certified by an error bound, its fallback rounds the exact expansion
/// from the top as `math.fsum` does), so it is correct for expansions in particular, and
/// its sign is the sign of the expansion's value (the largest component's).
///
/// ```
/// use kepler::geometry::exact::{estimate, expansion};
/// assert_eq!(estimate(&expansion(&[0.1, 0.2, -0.3])), 2f64.powi(-55));
/// // 1 + 2^-53 is half-way between 1 and the next double; the lowest component breaks the tie.
/// assert_eq!(estimate(&[-(2f64.powi(-80)), 2f64.powi(-53), 1.0]), 1.0);
/// assert_eq!(estimate(&[2f64.powi(-80), 2f64.powi(-53), 1.0]), 1.0f64.next_up());
/// assert_eq!(estimate(&[]), 0.0);
/// ```
#[inline]
pub fn estimate(e: &[f64]) -> f64 {
    accurate_sum(e)
}

/// The exact sum of `terms` rounded to the nearest double (ties to even).
///
/// One or two terms are rounded correctly by a single addition. Longer sums use a compensated
/// sum (TwoSum cascade) whose rounding is certified correct by an a-posteriori error bound;
/// only when the bound cannot certify it (a near half-way case, or heavy cancellation) is the
/// sum rebuilt exactly as an expansion and rounded from the top (as `math.fsum` does).
///
/// ```
/// use kepler::geometry::exact::accurate_sum;
/// assert_eq!(accurate_sum(&[1.0, 1e-30, -1.0]), 1e-30);
/// // The doubles nearest 0.1, 0.2 and 0.3 sum exactly to 2^-55 (not to 0.1 + 0.2 - 0.3 = 2^-54).
/// assert_eq!(accurate_sum(&[0.1, 0.2, -0.3]), 2.0f64.powi(-55));
/// // 1 + 2^-53 is half-way between 1 and the next double; the last term breaks the tie.
/// assert_eq!(accurate_sum(&[1.0, 2f64.powi(-53), 2f64.powi(-300)]), 1.0f64.next_up());
/// assert_eq!(accurate_sum(&[]), 0.0);
/// ```
#[inline]
pub fn accurate_sum(terms: &[f64]) -> f64 {
    accurate_sum_inline(terms)
}

/// [`accurate_sum`] of a fixed number of terms, always inlined (the same result): for hot
/// callers of short sums, whose terms then stay in registers unless the certification fails.
///
/// ```
/// use kepler::geometry::exact::{accurate_sum, accurate_sum_array};
/// let terms = [0.1, 0.2, -0.3];
/// assert_eq!(accurate_sum_array(terms), accurate_sum(&terms));
/// ```
#[inline(always)]
pub fn accurate_sum_array<const N: usize>(terms: [f64; N]) -> f64 {
    accurate_sum_inline(&terms)
}

#[inline(always)]
fn accurate_sum_inline(terms: &[f64]) -> f64 {
    match *terms {
        [] => 0.0,
        [a] => a,
        [a, b] => a + b,
        [a, b, ref rest @ ..] => {
            let (sum, err, residual) = cascade(a, b, rest);
            // With no residual, sum + err is the exact sum and its IEEE rounding is correct
            // (ties included).
            if residual == 0.0 {
                return sum + err;
            }
            // Otherwise exact = result + k + (sum of the d_i), and `result` is the correct
            // rounding when |k| + |sum of the d_i| stays below half the gap to its nearer
            // neighbour; the factor 2n covers the rounding of `residual` and of the test.
            let (result, k) = two_sum(sum, err);
            if k.abs() + (2 * terms.len()) as f64 * residual < min_half_gap(result) {
                result
            } else {
                exact_round(terms)
            }
        }
    }
}

/// [`accurate_sum`] of three terms in each of `N` lanes, `a[i] + b[i] + c[i]`, branch-free so
/// that the lanes vectorise, with whether every lane is certified: the TwoSum cascade turns
/// each sum exactly into `sum + e1 + e2` and `e1 + e2` into `err + d`; when `d` is zero, the
/// exact sum is the two doubles `sum + err`, whose single rounding is correct (ties included),
/// and the lane is bit for bit what [`accurate_sum`] returns. When some `d` is not zero the
/// flag is false and the lanes are only approximations: call [`accurate_sum`] instead.
///
/// ```
/// use kepler::geometry::exact::{accurate_sum, accurate_sum3_lanes};
/// let (sums, certified) = accurate_sum3_lanes([0.1, 1e20], [0.2, 1.0], [-0.3, -1e20]);
/// assert!(certified);
/// assert_eq!(sums, [accurate_sum(&[0.1, 0.2, -0.3]), 1.0]);
/// // In 1 + 2^-53 + 2^-200 the two rounding errors, 2^-53 and 2^-200, do not add exactly.
/// let (_, certified) = accurate_sum3_lanes([1.0], [2f64.powi(-53)], [2f64.powi(-200)]);
/// assert!(!certified);
/// ```
#[inline(always)]
pub fn accurate_sum3_lanes<const N: usize>(
    a: [f64; N],
    b: [f64; N],
    c: [f64; N],
) -> ([f64; N], bool) {
    let mut out = [0.0; N];
    let mut residual = 0.0;
    for i in 0..N {
        let (sum, err, d) = cascade(a[i], b[i], &[c[i]]);
        out[i] = sum + err;
        residual += d;
    }
    (out, residual == 0.0)
}

/// The TwoSum cascade of `a`, `b` and `rest`: `(sum, err, residual)` with exact sum =
/// sum + (sum of the errors e_i); the errors are added with TwoSum too, so exact sum = sum +
/// err + (sum of the residuals d_i), and `residual` is the sum of their magnitudes, rounded
/// (zero exactly when every d_i is).
#[inline(always)]
pub(super) fn cascade(a: f64, b: f64, rest: &[f64]) -> (f64, f64, f64) {
    let (mut sum, mut err) = two_sum(a, b);
    let mut residual = 0.0;
    for &t in rest {
        let (s, e) = two_sum(sum, t);
        sum = s;
        let (r, d) = two_sum(err, e);
        err = r;
        residual += d.abs();
    }
    (sum, err, residual)
}

/// Half the smaller of the two gaps between `x` and its neighbouring doubles, when `x` is
/// normal and not tiny (|x| >= 2^-895); 0 otherwise, so that callers fall back to exact code.
#[inline]
pub(super) fn min_half_gap(x: f64) -> f64 {
    const MANTISSA: u64 = (1 << 52) - 1;
    let bits = x.to_bits() & !(1 << 63);
    let biased_exponent = bits >> 52;
    if !(128..0x7ff).contains(&biased_exponent) {
        return 0.0;
    }
    // 2^E for |x| in [2^E, 2^(E+1)): the gap above is 2^(E-52); below a power of two it halves.
    let power = f64::from_bits(biased_exponent << 52);
    if bits & MANTISSA == 0 {
        power * 2f64.powi(-54)
    } else {
        power * 2f64.powi(-53)
    }
}

/// The exact sum rounded to nearest via its expansion (the certification's fallback).
#[cold]
#[inline(never)]
pub(super) fn exact_round(terms: &[f64]) -> f64 {
    with_expansion(terms, round_expansion)
}

/// Rounds an expansion (nonzero, nonoverlapping, increasing magnitude) to the nearest double,
/// ties to even, by summing from the top until the sum becomes inexact, then correcting a
/// half-way case that the lower components break (the final step of CPython's `math.fsum`).
pub(super) fn round_expansion(e: &[f64]) -> f64 {
    let Some((&top, rest)) = e.split_last() else {
        return 0.0;
    };
    let mut hi = top;
    let mut lo = 0.0;
    let mut n = rest.len();
    while n > 0 {
        let x = hi;
        let y = e[n - 1];
        n -= 1;
        hi = x + y;
        let yr = hi - x;
        lo = y - yr;
        if lo != 0.0 {
            break;
        }
    }
    if n > 0 && ((lo < 0.0 && e[n - 1] < 0.0) || (lo > 0.0 && e[n - 1] > 0.0)) {
        let y = lo * 2.0;
        let x = hi + y;
        let yr = x - hi;
        if y == yr {
            hi = x;
        }
    }
    hi
}
