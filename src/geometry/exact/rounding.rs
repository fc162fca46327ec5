//! Operations rounded once or in a chosen direction: [`lerp`] to half an ulp, sums rounded
//! up or down.

use super::sum::accurate_sum;
use super::{two_product, two_sum};

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
