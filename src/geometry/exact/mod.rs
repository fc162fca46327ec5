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

mod expansion;
mod rounding;
mod scaling;
mod sign;
mod sum;
#[cfg(test)]
mod tests;

pub use expansion::{
    compress, expansion, expansion_product, expansion_sum, negated, scale_expansion,
};
pub use rounding::{add_round_down, add_round_up, lerp};
pub use scaling::{ldexp, unit_scaled};
pub use sign::{filtered_sign, sum_sign, sum_sign_array};
pub use sum::{accurate_sum, accurate_sum_array, accurate_sum3_lanes, estimate};

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
