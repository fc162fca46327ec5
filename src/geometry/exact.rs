//! Exact arithmetic on doubles: error-free transformations and expansion sums.
//!
//! These are Shewchuk's (1997) building blocks, written by hand because the `robust` crate
//! exposes only its four predicates (orient2d/3d, incircle, insphere), not the expansion
//! arithmetic under them. A sum of doubles is represented exactly as an *expansion*: a list of
//! doubles whose magnitudes increase and whose bits do not overlap, so that its sign is the sign
//! of its largest component and its value rounds from the top.
//!
//! Every function assumes finite inputs whose partial sums do not overflow (magnitudes well
//! below `f64::MAX`); with infinities or NaN the results are meaningless but nothing panics.
//!
//! ```
//! use kepler::geometry::exact::{accurate_sum, sum_sign, two_sum};
//! use std::cmp::Ordering;
//! assert_eq!(two_sum(1.0, 1e-20), (1.0, 1e-20));
//! // 0.1 + 0.2 - 0.3 is not zero in doubles, and the exact sum of these doubles is positive.
//! assert_eq!(sum_sign(&[0.1, 0.2, -0.3]), Ordering::Greater);
//! assert_eq!(accurate_sum(&[1e20, 1.0, -1e20]), 1.0);
//! ```

use super::estimate::sum_error_bound;
use std::cmp::Ordering;

/// Expansions of at most this many components are built on the stack.
const STACK_TERMS: usize = 32;

/// The rounded sum `s = fl(a + b)` and its exact error `e`, so that `a + b = s + e` exactly
/// (Knuth's branch-free TwoSum).
///
/// ```
/// use kepler::geometry::exact::two_sum;
/// let (s, e) = two_sum(0.1, 0.2);
/// assert_eq!(s, 0.1 + 0.2);
/// assert!(e != 0.0 && e.abs() <= f64::EPSILON * s.abs());
/// ```
#[inline]
pub fn two_sum(a: f64, b: f64) -> (f64, f64) {
    let s = a + b;
    let bb = s - a;
    let e = (a - (s - bb)) + (b - bb);
    (s, e)
}

/// The rounded product `p = fl(a * b)` and its exact error `e`, so that `a * b = p + e`
/// exactly when the product neither overflows nor underflows (one fused multiply-add).
///
/// ```
/// use kepler::geometry::exact::two_product;
/// let (p, e) = two_product(0.1, 0.1);
/// assert_eq!(p, 0.1 * 0.1);
/// assert!(e != 0.0 && e.abs() <= f64::EPSILON * p);
/// ```
#[inline]
pub fn two_product(a: f64, b: f64) -> (f64, f64) {
    let p = a * b;
    (p, a.mul_add(b, -p))
}

/// Appends to `out` the exact terms of the product of the sums `a` and `b` (each pair's
/// [`two_product`]), so that the sum of what is appended equals `(Σa)·(Σb)` exactly.
///
/// ```
/// use kepler::geometry::exact::{product_terms, accurate_sum};
/// let mut out = Vec::new();
/// product_terms(&[0.1, 1e-20], &[3.0], &mut out);
/// assert_eq!(out.len(), 4);
/// assert_eq!(accurate_sum(&out), 0.30000000000000004);
/// ```
pub fn product_terms(a: &[f64], b: &[f64], out: &mut Vec<f64>) {
    for &x in a {
        for &y in b {
            let (p, e) = two_product(x, y);
            out.push(p);
            if e != 0.0 {
                out.push(e);
            }
        }
    }
}

/// The exact sum of `terms` as an expansion: nonzero, nonoverlapping components in increasing
/// magnitude, at most `terms.len()` of them (empty for a zero sum). Feed it to
/// [`product_terms`] to multiply exact sums without the number of terms exploding.
///
/// ```
/// use kepler::geometry::exact::expansion;
/// assert_eq!(expansion(&[1e100, 1.0, -1e100]), vec![1.0]);
/// assert!(expansion(&[0.5, -0.5]).is_empty());
/// ```
pub fn expansion(terms: &[f64]) -> Vec<f64> {
    let mut buf = vec![0.0; terms.len()];
    let n = grow_expansion(terms, &mut buf);
    buf.truncate(n);
    buf
}

/// The exact sum of the expansions `e` and `f`, as an expansion.
///
/// Shewchuk's Linear-Expansion-Sum with zero elimination: the components of both inputs are
/// merged by increasing magnitude and accumulated with a chain of [`two_sum`]s, in time linear
/// in `e.len() + f.len()`. The sum of the result equals the sum of the inputs exactly whatever
/// the inputs (barring overflow); when both are expansions (nonzero, nonoverlapping components
/// in increasing magnitude; empty for zero), so is the result, of at most `e.len() + f.len()`
/// components, so it can be fed back into this module's expansion arithmetic.
///
/// ```
/// use kepler::geometry::exact::{expansion, expansion_sum};
/// let e = expansion(&[1e100, 1.0]);
/// let f = expansion(&[-1e100, 2f64.powi(-80)]);
/// assert_eq!(expansion_sum(&e, &f), vec![2f64.powi(-80), 1.0]);
/// assert!(expansion_sum(&[0.5], &[-0.5]).is_empty());
/// assert_eq!(expansion_sum(&[], &[3.0]), vec![3.0]);
/// ```
pub fn expansion_sum(e: &[f64], f: &[f64]) -> Vec<f64> {
    let mut h = Vec::with_capacity(e.len() + f.len());
    let mut merged = merge_by_magnitude(e, f);
    let (Some(g0), Some(g1)) = (merged.next(), merged.next()) else {
        // At most one component in all.
        h.extend(e.iter().chain(f).copied().filter(|&c| c != 0.0));
        return h;
    };
    // Invariant: big + small + (the components emitted so far) is the exact sum of the
    // components merged so far, and `small` is below the bits of `big`.
    let (mut big, mut small) = two_sum(g1, g0);
    for g in merged {
        // Shewchuk uses Fast-Two-Sum here; TwoSum gives the same result when its
        // precondition holds and stays exact when it does not.
        let (r, low) = two_sum(g, small);
        push_nonzero(&mut h, low);
        (big, small) = two_sum(big, r);
    }
    push_nonzero(&mut h, small);
    push_nonzero(&mut h, big);
    h
}

/// The expansion `e` with the same value in as few components as the value needs (Shewchuk's
/// Compress, with [`two_sum`]): sums of many expansions stay short when compressed now and
/// then, since nonoverlapping components of a compressed expansion differ in magnitude by
/// at least `2^53`.
///
/// ```
/// use kepler::geometry::exact::{compress, expansion_sum};
/// let mut sum: Vec<f64> = Vec::new();
/// for _ in 0..100 {
///     sum = expansion_sum(&sum, &[0.1, 1.0]);
/// }
/// let short = compress(&sum);
/// assert!(short.len() <= 2);
/// assert_eq!(short.iter().sum::<f64>(), sum.iter().sum::<f64>());
/// assert!(compress(&[]).is_empty());
/// ```
pub fn compress(e: &[f64]) -> Vec<f64> {
    let Some(&top) = e.last() else {
        return Vec::new();
    };
    // From the top down: gather the bits into components that do not overlap.
    let mut g = Vec::with_capacity(e.len());
    let mut q = top;
    for &c in e[..e.len() - 1].iter().rev() {
        let (sum, low) = two_sum(q, c);
        if low != 0.0 {
            g.push(sum);
            q = low;
        } else {
            q = sum;
        }
    }
    g.push(q);
    // From the bottom up (g holds the components from the largest down): join neighbours.
    let mut h = Vec::with_capacity(g.len());
    let mut q = g[g.len() - 1];
    for &c in g[..g.len() - 1].iter().rev() {
        let (sum, low) = two_sum(c, q);
        push_nonzero(&mut h, low);
        q = sum;
    }
    push_nonzero(&mut h, q);
    h
}

/// The components of `e` and `f` merged by nondecreasing magnitude (each is assumed sorted).
fn merge_by_magnitude<'a>(e: &'a [f64], f: &'a [f64]) -> impl Iterator<Item = f64> + 'a {
    let (mut i, mut j) = (0, 0);
    std::iter::from_fn(move || {
        let take_e = match (e.get(i), f.get(j)) {
            (Some(x), Some(y)) => x.abs() <= y.abs(),
            (Some(_), None) => true,
            (None, Some(_)) => false,
            (None, None) => return None,
        };
        if take_e {
            i += 1;
            Some(e[i - 1])
        } else {
            j += 1;
            Some(f[j - 1])
        }
    })
}

#[inline]
fn push_nonzero(h: &mut Vec<f64>, x: f64) {
    if x != 0.0 {
        h.push(x);
    }
}

/// The exact product of the expansion `e` and the double `b`, as an expansion of at most
/// `2 * e.len()` components (empty when the product is zero).
///
/// Shewchuk's Scale-Expansion with zero elimination, with [`two_product`]. The result is
/// exact, and an expansion when `e` is one, as long as no product of a component with `b`
/// underflows (its rounding error must be representable: true when every such product is
/// zero or a multiple of `2^-1074`, e.g. all of magnitude above about `2^-969`) and none
/// overflows.
///
/// ```
/// use kepler::geometry::exact::{expansion, scale_expansion};
/// // 0.1 * 3 is not a double: the product needs two components.
/// let p = scale_expansion(&[0.1], 3.0);
/// assert_eq!(p.len(), 2);
/// assert_eq!(p[1], 0.1 * 3.0);
/// assert_eq!(scale_expansion(&expansion(&[1e100, 1.0]), 0.5), vec![0.5, 5e99]);
/// assert!(scale_expansion(&[1.0, 1e20], 0.0).is_empty());
/// ```
pub fn scale_expansion(e: &[f64], b: f64) -> Vec<f64> {
    let mut h = Vec::with_capacity(2 * e.len());
    let Some((&first, rest)) = e.split_first() else {
        return h;
    };
    let (mut big, low) = two_product(first, b);
    push_nonzero(&mut h, low);
    for &c in rest {
        let (p_high, p_low) = two_product(c, b);
        let (sum, low) = two_sum(big, p_low);
        push_nonzero(&mut h, low);
        // Shewchuk's Fast-Two-Sum (|p_high| >= |sum|); TwoSum is exact regardless.
        let (s, low) = two_sum(p_high, sum);
        push_nonzero(&mut h, low);
        big = s;
    }
    push_nonzero(&mut h, big);
    h
}

/// The exact product of the expansions `e` and `f`, as an expansion: the sum, by
/// [`expansion_sum`], of [`scale_expansion`] of the longer one by each component of the
/// shorter one. Exact under the same condition as [`scale_expansion`] (no product of two
/// components underflows or overflows).
///
/// ```
/// use kepler::geometry::exact::{estimate, expansion, expansion_product};
/// // (1 + 2^-60)^2 = 1 + 2^-59 + 2^-120 exactly.
/// let e = expansion(&[1.0, 2f64.powi(-60)]);
/// let p = expansion_product(&e, &e);
/// assert_eq!(p, vec![2f64.powi(-120), 2f64.powi(-59), 1.0]);
/// assert_eq!(estimate(&p), 1.0);
/// assert!(expansion_product(&e, &[]).is_empty());
/// ```
pub fn expansion_product(e: &[f64], f: &[f64]) -> Vec<f64> {
    let (short, long) = if e.len() <= f.len() { (e, f) } else { (f, e) };
    let mut product = Vec::new();
    for &b in short {
        let scaled = scale_expansion(long, b);
        product = if product.is_empty() {
            scaled
        } else {
            expansion_sum(&product, &scaled)
        };
    }
    product
}

/// The expansion of `-e` (each component negated; an expansion stays one).
///
/// ```
/// use kepler::geometry::exact::negated;
/// assert_eq!(negated(&[1e-20, -3.0]), vec![-1e-20, 3.0]);
/// ```
pub fn negated(e: &[f64]) -> Vec<f64> {
    e.iter().map(|&c| -c).collect()
}

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

/// `v` scaled by the power of two `2^-e` with `2^e <= max |v_k| < 2^(e+1)`, so that its largest
/// component lies in `[1, 2)`: exact (barring components more than `2^1022` times smaller than
/// the largest, which underflow), so a direction is rescaled without changing it, even from a
/// subnormal or huge one. The zero vector (or one with an infinite or NaN component) is
/// returned as it is.
///
/// ```
/// use kepler::geometry::exact::unit_scaled;
/// assert_eq!(unit_scaled([12.0, -3.0, 0.0]), [1.5, -0.375, 0.0]);
/// assert_eq!(unit_scaled([0.0, 0.0, 5e-324]), [0.0, 0.0, 1.0]);
/// assert_eq!(unit_scaled([1e300, 0.0, 0.0])[0], 1e300 / 2f64.powi(996));
/// ```
pub fn unit_scaled(v: [f64; 3]) -> [f64; 3] {
    let top = v.iter().fold(0.0f64, |m, c| m.max(c.abs()));
    if top == 0.0 || !top.is_finite() {
        return v;
    }
    let scaled = v.map(|c| ldexp(c, -(top.log2().floor() as i32)));
    // The rounded logarithm may be one off next to a power of two.
    let top = scaled.iter().fold(0.0f64, |m, c| m.max(c.abs()));
    if top >= 2.0 {
        scaled.map(|c| c * 0.5)
    } else if top < 1.0 {
        scaled.map(|c| c * 2.0)
    } else {
        scaled
    }
}

/// `x · 2^k`, exactly unless the result overflows or falls below the normal range; `k` may
/// exceed the exponent range of one double (`2^k` itself need not be representable).
///
/// ```
/// use kepler::geometry::exact::ldexp;
/// assert_eq!(ldexp(3.0, 4), 48.0);
/// assert_eq!(ldexp(2f64.powi(-1000), 1100), 2f64.powi(100));
/// assert_eq!(ldexp(2f64.powi(1000), -1100), 2f64.powi(-100));
/// ```
pub fn ldexp(x: f64, k: i32) -> f64 {
    let half = k / 2;
    x * 2f64.powi(half) * 2f64.powi(k - half)
}

/// `a + t·(b − a)` rounded once to the nearest double (the difference and the product are
/// kept exact as expansions): a point of a segment within half a unit in the last place of
/// its own coordinate, however long the segment (`a + t·(b − a)` in floating point is off by
/// units in the last place of `a` and `b`).
///
/// ```
/// use kepler::geometry::exact::lerp;
/// let far = 2f64.powi(60);
/// // 1 − 2⁻⁶⁰·(2⁶⁰ + 1) = −2⁻⁶⁰; in floating point, 1 + 2⁻⁶⁰·(−2⁶⁰) = 0.
/// assert_eq!(lerp(1.0, -far, 1.0 / far), -1.0 / far);
/// assert_eq!(1.0 + (-far - 1.0) * (1.0 / far), 0.0);
/// assert_eq!(lerp(2.0, 6.0, 0.25), 3.0);
/// ```
#[inline]
pub fn lerp(a: f64, b: f64, t: f64) -> f64 {
    let (hi, lo) = two_sum(b, -a);
    let (p1, p0) = two_product(hi, t);
    let (q1, q0) = two_product(lo, t);
    accurate_sum(&[a, p1, p0, q1, q0])
}

/// The smallest double that is at least the exact sum `a + b`.
///
/// ```
/// use kepler::geometry::exact::add_round_up;
/// assert_eq!(add_round_up(1.0, 2.0), 3.0);
/// assert_eq!(add_round_up(1.0, 1e-30), 1.0f64.next_up());
/// assert_eq!(add_round_up(1.0, -1e-30), 1.0);
/// ```
#[inline]
pub fn add_round_up(a: f64, b: f64) -> f64 {
    let (s, e) = two_sum(a, b);
    if e > 0.0 { s.next_up() } else { s }
}

/// The largest double that is at most the exact sum `a + b`.
///
/// ```
/// use kepler::geometry::exact::add_round_down;
/// assert_eq!(add_round_down(1.0, 2.0), 3.0);
/// assert_eq!(add_round_down(1.0, -1e-30), 1.0f64.next_down());
/// assert_eq!(add_round_down(1.0, 1e-30), 1.0);
/// ```
#[inline]
pub fn add_round_down(a: f64, b: f64) -> f64 {
    let (s, e) = two_sum(a, b);
    if e < 0.0 { s.next_down() } else { s }
}

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
/// [`accurate_sum`] when it leaves no residual (the exact sum is then `sum + err`, two doubles,
/// whose rounded sum has its sign since a sum of doubles rounds to zero only when it is zero),
/// otherwise by the sign of the exact expansion.
#[cold]
#[inline(never)]
fn exact_sign(terms: &[f64]) -> Ordering {
    if let [a, b, ref rest @ ..] = *terms {
        let (sum, err, residual) = cascade(a, b, rest);
        if residual == 0.0 {
            return sign_of(sum + err);
        }
    }
    with_expansion(terms, |e| sign_of(e.last().copied().unwrap_or(0.0)))
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
fn cascade(a: f64, b: f64, rest: &[f64]) -> (f64, f64, f64) {
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
fn min_half_gap(x: f64) -> f64 {
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
fn exact_round(terms: &[f64]) -> f64 {
    with_expansion(terms, round_expansion)
}

/// The sign of a double as an ordering (NaN counts as zero).
#[inline]
fn sign_of(x: f64) -> Ordering {
    if x > 0.0 {
        Ordering::Greater
    } else if x < 0.0 {
        Ordering::Less
    } else {
        Ordering::Equal
    }
}

/// Builds the exact expansion of the sum of `terms` (nonzero components, nonoverlapping,
/// increasing magnitude) in a buffer on the stack when it is short, and hands it to `f`.
fn with_expansion<R>(terms: &[f64], f: impl FnOnce(&[f64]) -> R) -> R {
    if terms.len() <= STACK_TERMS {
        let mut buf = [0.0; STACK_TERMS];
        let n = grow_expansion(terms, &mut buf);
        f(&buf[..n])
    } else {
        let mut buf = vec![0.0; terms.len()];
        let n = grow_expansion(terms, &mut buf);
        f(&buf[..n])
    }
}

/// Shewchuk's Grow-Expansion with zero elimination, term by term (the `msum` loop of Python's
/// `math.fsum`). `buf` must hold `terms.len()` doubles; returns the number of components.
fn grow_expansion(terms: &[f64], buf: &mut [f64]) -> usize {
    let mut len = 0;
    for &t in terms {
        let mut x = t;
        let mut kept = 0;
        for i in 0..len {
            let mut y = buf[i];
            if x.abs() < y.abs() {
                std::mem::swap(&mut x, &mut y);
            }
            // Fast TwoSum, valid since |x| >= |y|.
            let hi = x + y;
            let lo = y - (hi - x);
            if lo != 0.0 {
                buf[kept] = lo;
                kept += 1;
            }
            x = hi;
        }
        if x != 0.0 {
            buf[kept] = x;
            kept += 1;
        }
        len = kept;
    }
    len
}

/// Rounds an expansion (nonzero, nonoverlapping, increasing magnitude) to the nearest double,
/// ties to even, by summing from the top until the sum becomes inexact, then correcting a
/// half-way case that the lower components break (the final step of CPython's `math.fsum`).
fn round_expansion(e: &[f64]) -> f64 {
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn expansion_is_nonoverlapping_and_increasing() {
        let terms = [1e300, 1.0, -1e300, 1e-300, 3.0, 2f64.powi(-60)];
        let mut buf = [0.0; 6];
        let n = grow_expansion(&terms, &mut buf);
        let e = &buf[..n];
        assert!(e.windows(2).all(|w| w[0].abs() < w[1].abs()));
        assert!(e.iter().all(|&c| c != 0.0));
        assert_eq!(round_expansion(e), 4.0);
    }

    #[test]
    fn min_half_gap_is_half_the_smaller_gap() {
        for x in [1.0, 1.5, 3.0, 1e300, -7.25e-200, 2f64.powi(-800)] {
            let h = min_half_gap(x);
            let a = x.abs();
            assert_eq!(h, (a.next_up() - a).min(a - a.next_down()) / 2.0);
        }
        assert_eq!(min_half_gap(0.0), 0.0);
        assert_eq!(min_half_gap(1e-300), 0.0);
        assert_eq!(min_half_gap(f64::INFINITY), 0.0);
        assert_eq!(min_half_gap(f64::NAN), 0.0);
    }

    #[test]
    fn fsum_half_way_correction() {
        // 1 + 2^-53 is half-way between 1 and 1 + 2^-52; the tiny term breaks the tie upward.
        assert_eq!(
            accurate_sum(&[1.0, 2f64.powi(-53), 2f64.powi(-200), 0.0, 0.0]),
            1.0f64.next_up()
        );
        assert_eq!(
            accurate_sum(&[1.0, 2f64.powi(-53), -(2f64.powi(-200)), 0.0]),
            1.0
        );
    }

    /// The sign of the exact expansion, without the cascade of `exact_sign`.
    fn expansion_sign(terms: &[f64]) -> Ordering {
        with_expansion(terms, |e| sign_of(e.last().copied().unwrap_or(0.0)))
    }

    #[test]
    fn cascade_signs_and_fixed_arrays_agree_with_the_expansion() {
        let mut state = 0x2545_f491_4f6c_dd1du64;
        let mut next = move || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            state
        };
        // Terms that cancel exactly or nearly: shared magnitudes, halves, tiny tails, zeros,
        // from 1e-300 to 1e300 and mixed signs.
        let pool = [
            0.0,
            1.0,
            0.1,
            0.2,
            0.3,
            0.5,
            0.75,
            1e-17,
            2f64.powi(-53),
            2f64.powi(-60),
            1e300,
            1e-300,
            3e299,
            5e-324,
            1e16,
            1.5,
        ];
        let mut uncertified = 0;
        for _ in 0..200_000 {
            let mut t = [0.0; 5];
            for x in &mut t {
                let v = pool[(next() % pool.len() as u64) as usize];
                *x = if next() % 2 == 0 { v } else { -v };
            }
            // Often make the sum cancel: the last term undoes the first ones' rounded sum.
            if next() % 2 == 0 {
                t[4] = -(t[0] + t[1] + t[2] + t[3]);
            }
            assert_eq!(exact_sign(&t), expansion_sign(&t), "{t:?}");
            assert_eq!(exact_sign(&t[..3]), expansion_sign(&t[..3]), "{t:?}");
            assert_eq!(sum_sign_array(t), sum_sign(&t), "{t:?}");
            assert_eq!(sum_sign_array([t[0], t[1], t[2]]), sum_sign(&t[..3]));
            assert_eq!(accurate_sum_array(t).to_bits(), accurate_sum(&t).to_bits());
            let (lanes, certified) = accurate_sum3_lanes([t[0], t[3]], [t[1], t[4]], [t[2], t[0]]);
            for (sum, terms) in lanes.iter().zip([[t[0], t[1], t[2]], [t[3], t[4], t[0]]]) {
                uncertified += usize::from(!certified);
                if certified {
                    assert_eq!(sum.to_bits(), accurate_sum(&terms).to_bits(), "{t:?}");
                }
            }
            assert_eq!(
                accurate_sum(&t).to_bits(),
                exact_round(&t).to_bits(),
                "{t:?}"
            );
        }
        // The lanes' fallback is exercised too.
        assert!(uncertified > 1_000, "{uncertified}");
    }

    #[test]
    fn long_slices_use_the_heap_buffer() {
        let mut terms: Vec<f64> = (0..40).map(|i| 2f64.powi(i * 30 - 600)).collect();
        let negated: Vec<f64> = terms.iter().map(|t| -t).collect();
        terms.extend(negated);
        terms.push(-(2f64.powi(-700)));
        assert_eq!(sum_sign(&terms), Ordering::Less);
        assert_eq!(accurate_sum(&terms), -(2f64.powi(-700)));
    }
}
