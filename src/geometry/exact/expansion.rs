//! Expansions: exact sums of doubles as nonoverlapping components in increasing magnitude,
//! built from terms, added, compressed, scaled, multiplied and negated (Shewchuk's
//! algorithms with zero elimination).

use super::{two_product, two_sum};

/// Expansions of at most this many components are built on the stack.
const STACK_TERMS: usize = 32;

/// The exact sum of `terms` as an expansion: nonzero, nonoverlapping components in increasing
/// magnitude, at most `terms.len()` of them (empty for a zero sum). Feed it to
/// [`product_terms`](super::product_terms) to multiply exact sums without the number of terms
/// exploding.
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

/// Builds the exact expansion of the sum of `terms` (nonzero components, nonoverlapping,
/// increasing magnitude) in a buffer on the stack when it is short, and hands it to `f`.
pub(super) fn with_expansion<R>(terms: &[f64], f: impl FnOnce(&[f64]) -> R) -> R {
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
pub(super) fn grow_expansion(terms: &[f64], buf: &mut [f64]) -> usize {
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
