//! Exact scaling by powers of two: [`ldexp`] beyond the exponent range of one double, and
//! [`unit_scaled`], a vector brought to a largest component in `[1, 2)`.

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
