//! Exact values of the orientation determinants and the expansion arithmetic under them,
//! against exact arithmetic: results equal the exact values and are valid expansions,
//! `estimate` rounds correctly, signs agree with the predicates, and the floating-point
//! estimates' error bounds hold.
//!
//! Every double is an integer multiple of `2^-1074`, so a polynomial of degree `k` in doubles
//! is an integer multiple of `2^(-1074 k)`: the references are computed exactly on such
//! scaled `BigInt`s (fast: no gcd), and cross-checked against `BigRational` on a sample.

use kepler::geometry::exact::{
    estimate, expansion, expansion_product, expansion_sum, negated, scale_expansion,
};
use kepler::geometry::kernel::Polynomial;
use kepler::geometry::predicates::{Orient3d, Orient3dAtInfinity, orient3d, orient3d_at_infinity};
use kepler::geometry::{Point3, Vector3};
use num_bigint::BigInt;
use num_traits::{Signed, Zero};

/// The kernel's exact value of `orient3d(a, b, c, d)`, as an expansion.
fn orient3d_value(a: &Point3, b: &Point3, c: &Point3, d: &Point3) -> Vec<f64> {
    Orient3d([*a, *b, *c, *d]).expansion()
}

/// The kernel's estimate of `orient3d(a, b, c, d)`: value and error bound.
fn orient3d_estimate(a: &Point3, b: &Point3, c: &Point3, d: &Point3) -> (f64, f64) {
    let e = Orient3d([*a, *b, *c, *d]).estimate();
    (e.value, e.bound)
}

/// The kernel's exact value of `orient3d_at_infinity(a, b, c, u)`, as an expansion.
fn orient3d_at_infinity_value(a: &Point3, b: &Point3, c: &Point3, u: &Vector3) -> Vec<f64> {
    Orient3dAtInfinity([*a, *b, *c], *u).expansion()
}

/// The kernel's estimate of `orient3d_at_infinity(a, b, c, u)`: value and error bound.
fn orient3d_at_infinity_estimate(a: &Point3, b: &Point3, c: &Point3, u: &Vector3) -> (f64, f64) {
    let e = Orient3dAtInfinity([*a, *b, *c], *u).estimate();
    (e.value, e.bound)
}

use crate::common::{Q, SplitMix64, q, qcross, qdot, qsign, qsub, qv};

/// The exact value of `x · 2^(1074 degree)`, an integer for `degree >= 1`.
fn z(x: f64, degree: u32) -> BigInt {
    assert!(x.is_finite() && degree >= 1);
    let bits = x.to_bits();
    let biased = ((bits >> 52) & 0x7ff) as i64;
    let fraction = bits & ((1 << 52) - 1);
    // |x| = mantissa · 2^exp with exp >= -1074.
    let (mantissa, exp) = if biased == 0 {
        (fraction, -1074)
    } else {
        (fraction | (1 << 52), biased - 1075)
    };
    let m = BigInt::from(mantissa) << ((exp + 1074 * i64::from(degree)) as usize);
    if x < 0.0 { -m } else { m }
}

/// The exact value of a list of doubles, scaled by `2^(1074 degree)`.
fn value(e: &[f64], degree: u32) -> BigInt {
    e.iter().map(|&c| z(c, degree)).sum()
}

/// The sign of an exact value.
fn zsign(x: &BigInt) -> Option<std::cmp::Ordering> {
    Some(x.sign().cmp(&num_bigint::Sign::NoSign))
}

/// The positions of the lowest and highest set bits of a nonzero finite double
/// (`x = m 2^lsb` with `m` odd, `2^msb <= |x| < 2^(msb + 1)`).
fn bit_range(x: f64) -> (i32, i32) {
    let bits = x.abs().to_bits();
    let biased = (bits >> 52) as i32;
    let fraction = bits & ((1 << 52) - 1);
    let (mantissa, shift) = if biased == 0 {
        (fraction, -1074)
    } else {
        (fraction | (1 << 52), biased - 1075)
    };
    let lsb = shift + mantissa.trailing_zeros() as i32;
    let msb = shift + 63 - mantissa.leading_zeros() as i32;
    (lsb, msb)
}

/// Asserts that `e` is an expansion: finite nonzero components, each one's bits entirely
/// below the next one's lowest set bit (nonoverlapping, increasing magnitude).
fn assert_expansion(e: &[f64]) {
    assert!(
        e.iter().all(|c| c.is_finite() && *c != 0.0),
        "zero or non-finite component in {e:?}"
    );
    for w in e.windows(2) {
        let (_, msb_low) = bit_range(w[0]);
        let (lsb_high, _) = bit_range(w[1]);
        assert!(msb_low < lsb_high, "overlapping components in {e:?}");
    }
}

/// Asserts that `x` is the exact value `exact · 2^(-1074 degree)` rounded to the nearest
/// double, ties to even.
fn assert_rounded(x: f64, exact: &BigInt, degree: u32) {
    let distance = |y: f64| (z(y, degree) - exact).abs();
    let d = distance(x);
    let (up, down) = (distance(x.next_up()), distance(x.next_down()));
    assert!(d <= up && d <= down, "{x:e} is not the nearest double");
    if d == up || d == down {
        assert_eq!(x.to_bits() & 1, 0, "tie not rounded to even: {x:e}");
    }
}

/// A random double with a random sign, magnitude `2^exp` times [1, 2) for a random `exp` in
/// `lo..=hi`; sometimes a power of two or a small integer times `2^exp`.
fn wild(rng: &mut SplitMix64, lo: i32, hi: i32) -> f64 {
    let exp = lo + rng.below((hi - lo + 1) as usize) as i32;
    let mantissa = match rng.below(4) {
        0 => 1.0,
        1 => rng.int(1, 15),
        _ => rng.range(1.0, 2.0),
    };
    let sign = if rng.below(2) == 0 { 1.0 } else { -1.0 };
    sign * mantissa * 2f64.powi(exp)
}

/// A random expansion from up to 8 wild doubles, with exact cancellations among them.
fn random_expansion(rng: &mut SplitMix64, lo: i32, hi: i32) -> Vec<f64> {
    let mut terms = Vec::new();
    for _ in 0..rng.below(9) {
        if !terms.is_empty() && rng.below(4) == 0 {
            let t: f64 = rng.pick(&terms);
            terms.push(-t);
        } else {
            terms.push(wild(rng, lo, hi));
        }
    }
    let e = expansion(&terms);
    assert_expansion(&e);
    assert_eq!(value(&e, 1), value(&terms, 1));
    e
}

/// A second expansion related to `e`: its negation, a near-negation (exact cancellation of
/// the top components), or an unrelated one.
fn partner(rng: &mut SplitMix64, e: &[f64], lo: i32, hi: i32) -> Vec<f64> {
    match rng.below(4) {
        0 => negated(e),
        1 => {
            let mut terms = negated(e);
            terms.push(wild(rng, lo, hi));
            expansion(&terms)
        }
        _ => random_expansion(rng, lo, hi),
    }
}

#[test]
fn expansion_sums_are_exact_expansions() {
    let mut rng = SplitMix64(1);
    for _ in 0..3000 {
        let e = random_expansion(&mut rng, -600, 600);
        let f = partner(&mut rng, &e, -600, 600);
        let s = expansion_sum(&e, &f);
        assert_expansion(&s);
        assert!(s.len() <= e.len() + f.len());
        assert_eq!(value(&s, 1), value(&e, 1) + value(&f, 1));
        assert_rounded(estimate(&s), &value(&s, 1), 1);
        // Results feed back in.
        let t = expansion_sum(&s, &negated(&e));
        assert_expansion(&t);
        assert_eq!(value(&t, 1), value(&f, 1));
    }
}

#[test]
fn scaled_and_multiplied_expansions_are_exact_expansions() {
    let mut rng = SplitMix64(2);
    for _ in 0..1500 {
        let e = random_expansion(&mut rng, -150, 150);
        let b = if rng.below(10) == 0 {
            0.0
        } else {
            wild(&mut rng, -150, 150)
        };
        let s = scale_expansion(&e, b);
        assert_expansion(&s);
        assert!(s.len() <= 2 * e.len());
        assert_eq!(value(&s, 2), value(&e, 1) * z(b, 1));

        let f = partner(&mut rng, &e, -150, 150);
        let p = expansion_product(&e, &f);
        assert_expansion(&p);
        assert_eq!(value(&p, 2), value(&e, 1) * value(&f, 1));
        assert_rounded(estimate(&p), &value(&p, 2), 2);
        // Results feed back in: (e f) s - (e f) s = 0 and (e f) + (e s) = e (f + s).
        let ps = expansion_product(&p, &s);
        assert_expansion(&ps);
        assert!(expansion_sum(&ps, &negated(&ps)).is_empty());
        let lhs = expansion_sum(&p, &expansion_product(&e, &s));
        let rhs = expansion_product(&e, &expansion_sum(&f, &s));
        assert_expansion(&lhs);
        assert_expansion(&rhs);
        assert_eq!(value(&lhs, 2), value(&rhs, 2));
    }
}

#[test]
fn estimate_rounds_to_nearest_with_ties_to_even() {
    let mut rng = SplitMix64(3);
    for _ in 0..3000 {
        let e = random_expansion(&mut rng, -900, 900);
        assert_rounded(estimate(&e), &value(&e, 1), 1);
    }
    // Half-way cases: top ± half an ulp, with or without a tie-breaking lower component.
    for _ in 0..2000 {
        let top = wild(&mut rng, -500, 500);
        let (lsb, _) = bit_range(top);
        let (_, msb) = bit_range(top);
        let half = if rng.below(2) == 0 { 1.0 } else { -1.0 } * 2f64.powi(msb - 53);
        assert!(msb - 53 < lsb);
        let mut e = vec![half, top];
        if rng.below(3) > 0 {
            let tail = if rng.below(2) == 0 { 1.0 } else { -1.0 } * 2f64.powi(msb - 60 - 3);
            e.insert(0, tail);
        }
        assert_expansion(&e);
        assert_rounded(estimate(&e), &value(&e, 1), 1);
    }
    assert_eq!(estimate(&[]), 0.0);
}

/// det[r; s; t] with the three vectors as rows.
fn det3(r: &[BigInt; 3], s: &[BigInt; 3], t: &[BigInt; 3]) -> BigInt {
    &r[0] * (&s[1] * &t[2] - &s[2] * &t[1])
        + &r[1] * (&s[2] * &t[0] - &s[0] * &t[2])
        + &r[2] * (&s[0] * &t[1] - &s[1] * &t[0])
}

/// The coordinates of `p` scaled by `2^1074` (exact integers).
fn zv(p: [f64; 3]) -> [BigInt; 3] {
    p.map(|x| z(x, 1))
}

fn zsub(a: &[BigInt; 3], b: &[BigInt; 3]) -> [BigInt; 3] {
    [&a[0] - &b[0], &a[1] - &b[1], &a[2] - &b[2]]
}

/// `det[a - d, b - d, c - d]` scaled by `2^3222`: the determinant of `orient3d`.
fn orient3d_exact(a: &Point3, b: &Point3, c: &Point3, d: &Point3) -> BigInt {
    let [a, b, c, d] = [a, b, c, d].map(|p| zv(arr(p)));
    det3(&zsub(&a, &d), &zsub(&b, &d), &zsub(&c, &d))
}

/// `-det[a - c, b - c, u]` scaled by `2^3222`: the determinant of `orient3d_at_infinity`.
fn at_infinity_exact(a: &Point3, b: &Point3, c: &Point3, u: &Vector3) -> BigInt {
    let [a, b, c] = [a, b, c].map(|p| zv(arr(p)));
    -det3(&zsub(&a, &c), &zsub(&b, &c), &zv([u.x, u.y, u.z]))
}

fn arr(p: &Point3) -> [f64; 3] {
    [p.x, p.y, p.z]
}

/// Tallies of the determinants checked, to make sure the hard cases occur.
#[derive(Default, Debug)]
struct Tally {
    zero: usize,
    nonzero: usize,
    /// Nonzero determinants whose estimate could not certify the sign.
    uncertified: usize,
    /// Nonzero determinants whose floating-point value has the wrong sign.
    wrong_float_sign: usize,
}

impl Tally {
    fn record(&mut self, exact: &BigInt, value: f64, bound: f64) {
        // The certified bound.
        let error = (z(value, 3) - exact).abs();
        assert!(error <= z(bound, 3), "error above bound {bound:e}");
        if exact.is_zero() {
            self.zero += 1;
        } else {
            self.nonzero += 1;
            if value.abs() <= bound {
                self.uncertified += 1;
            }
            if value.partial_cmp(&0.0) != zsign(exact) {
                self.wrong_float_sign += 1;
            }
        }
    }
}

fn check_orient3d(a: &Point3, b: &Point3, c: &Point3, d: &Point3, tally: &mut Tally) {
    let exact = orient3d_exact(a, b, c, d);
    let v = orient3d_value(a, b, c, d);
    assert_expansion(&v);
    assert_eq!(value(&v, 3), exact, "orient3d_value({a}, {b}, {c}, {d})");
    let rounded = estimate(&v);
    assert_rounded(rounded, &exact, 3);
    let sign = orient3d(a, b, c, d);
    assert_eq!(rounded.partial_cmp(&0.0), Some(sign));
    assert_eq!(zsign(&exact), Some(sign));
    let (value, bound) = orient3d_estimate(a, b, c, d);
    tally.record(&exact, value, bound);
}

fn check_at_infinity(a: &Point3, b: &Point3, c: &Point3, u: &Vector3, tally: &mut Tally) {
    let exact = at_infinity_exact(a, b, c, u);
    let v = orient3d_at_infinity_value(a, b, c, u);
    assert_expansion(&v);
    assert_eq!(
        value(&v, 3),
        exact,
        "orient3d_at_infinity_value({a}, {b}, {c}, {u})"
    );
    let rounded = estimate(&v);
    assert_rounded(rounded, &exact, 3);
    let sign = orient3d_at_infinity(a, b, c, u);
    assert_eq!(rounded.partial_cmp(&0.0), Some(sign));
    assert_eq!(zsign(&exact), Some(sign));
    let (value, bound) = orient3d_at_infinity_estimate(a, b, c, u);
    tally.record(&exact, value, bound);
}

/// `x` moved by `k` ulps.
fn nudge(x: f64, k: i32) -> f64 {
    let mut y = x;
    for _ in 0..k.abs() {
        y = if k > 0 { y.next_up() } else { y.next_down() };
    }
    y
}

/// A point on (or, after rounding, next to) the plane through `a`, `b`, `c`, moved by a few
/// ulps in one coordinate.
fn near_plane(rng: &mut SplitMix64, a: &Point3, b: &Point3, c: &Point3) -> Point3 {
    let (s, t) = (rng.range(-2.0, 2.0), rng.range(-2.0, 2.0));
    let mut p = a + (b - a) * s + (c - a) * t;
    let k = rng.below(3);
    p[k] = nudge(p[k], rng.below(5) as i32 - 2);
    p
}

/// Four points (or three and a direction) in one of several regimes, by `kind`.
fn points(rng: &mut SplitMix64, kind: usize) -> [Point3; 4] {
    let lattice = |rng: &mut SplitMix64, base: f64, r: i32| {
        Point3::new(
            base + rng.int(-r, r),
            base + rng.int(-r, r),
            base + rng.int(-r, r),
        )
    };
    match kind {
        // Uniform in a cube.
        0 => [(); 4].map(|_| Point3::from(rng.vector(1.0))),
        // Coordinates of wildly different magnitudes.
        1 => {
            [(); 4].map(|_| Point3::new(wild(rng, -40, 40), wild(rng, -40, 40), wild(rng, -40, 40)))
        }
        // Nearly coplanar.
        2 => {
            let [a, b, c] = [(); 3].map(|_| Point3::from(rng.vector(10.0)));
            let d = near_plane(rng, &a, &b, &c);
            [a, b, c, d]
        }
        // Far from the origin, nearly coplanar.
        3 => {
            let base = rng.pick(&[1e15, 2f64.powi(52), 1e17, -3e16]);
            let offset = |rng: &mut SplitMix64| {
                Point3::new(
                    base + rng.range(-50.0, 50.0),
                    base + rng.range(-50.0, 50.0),
                    base + rng.range(-50.0, 50.0),
                )
            };
            let [a, b, c] = [(); 3].map(|_| offset(rng));
            let d = if rng.below(2) == 0 {
                near_plane(rng, &a, &b, &c)
            } else {
                offset(rng)
            };
            [a, b, c, d]
        }
        // Exactly degenerate: coplanar lattice points (z an integer combination of x and y),
        // repeated or collinear points, far from the origin or not.
        4 => {
            let base = rng.pick(&[0.0, 1e15, -2f64.powi(50)]);
            let (p, r) = (rng.int(-3, 3), rng.int(-3, 3));
            let mut pts = [(); 4].map(|_| lattice(rng, 0.0, 1000));
            for pt in &mut pts {
                pt.z = p * pt.x + r * pt.y + base;
                pt.x += base;
                pt.y += base;
            }
            match rng.below(4) {
                0 => pts[3] = pts[rng.below(3)],
                1 => pts[2] = pts[0] + (pts[1] - pts[0]) * 2.0,
                2 => pts[3].z += rng.pick(&[1.0, -1.0, 2.0]),
                _ => {}
            }
            pts
        }
        // Tiny coordinates (still exact: nonzero magnitudes above 1e-90).
        _ => {
            let [a, b, c] = [(); 3].map(|_| Point3::from(rng.vector(1e-75)));
            let d = near_plane(rng, &a, &b, &c);
            [a, b, c, d]
        }
    }
}

const KINDS: usize = 6;

#[test]
fn orient3d_value_is_the_exact_determinant() {
    let mut rng = SplitMix64(4);
    let mut tally = Tally::default();
    for i in 0..3000 {
        let [a, b, c, d] = points(&mut rng, i % KINDS);
        check_orient3d(&a, &b, &c, &d, &mut tally);
        // An odd permutation negates the determinant.
        check_orient3d(&b, &a, &c, &d, &mut tally);
    }
    let o = Point3::origin();
    let (x, y) = (Point3::new(1.0, 0.0, 0.0), Point3::new(0.0, 1.0, 0.0));
    assert_eq!(
        orient3d_value(&o, &x, &y, &Point3::new(0.0, 0.0, -3.0)),
        vec![3.0]
    );
    assert!(orient3d_value(&o, &x, &y, &Point3::new(5.0, -7.0, 0.0)).is_empty());
    // The hard cases occur: exact zeros, and nonzero determinants the filter cannot decide.
    assert!(tally.zero > 300, "{tally:?}");
    assert!(tally.uncertified > 100, "{tally:?}");
    assert!(tally.wrong_float_sign > 10, "{tally:?}");
}

#[test]
fn orient3d_at_infinity_value_is_the_exact_determinant() {
    let mut rng = SplitMix64(5);
    let mut tally = Tally::default();
    for i in 0..3000 {
        let [a, b, c, d] = points(&mut rng, i % KINDS);
        let u = match rng.below(5) {
            // A direction in (or, after rounding, next to) the plane.
            0 => (d - c) * rng.pick(&[1.0, -0.5, 3.0]),
            // Along an axis (`orient3d_at_infinity` reduces it to orient2d).
            1 => {
                let mut u = Vector3::zeros();
                u[rng.below(3)] = rng.pick(&[1.0, -1.0, 0.1, -1e-20]);
                u
            }
            // Wild magnitudes.
            2 => Vector3::new(
                wild(&mut rng, -30, 30),
                wild(&mut rng, -30, 30),
                wild(&mut rng, -30, 30),
            ),
            // Nearly parallel to the plane.
            3 => {
                let mut u = (b - a) + (c - a) * rng.range(-1.0, 1.0);
                let k = rng.below(3);
                u[k] = nudge(u[k], rng.below(3) as i32 - 1);
                u
            }
            _ => rng.vector(1.0),
        };
        check_at_infinity(&a, &b, &c, &u, &mut tally);
        check_at_infinity(&a, &b, &c, &-u, &mut tally);
    }
    let (a, b, c) = (
        Point3::origin(),
        Point3::new(1.0, 0.0, 0.0),
        Point3::new(0.0, 1.0, 0.0),
    );
    assert_eq!(
        orient3d_at_infinity_value(&a, &b, &c, &Vector3::new(0.0, 0.0, -2.0)),
        vec![2.0]
    );
    assert!(tally.zero > 300, "{tally:?}");
    assert!(tally.uncertified > 100, "{tally:?}");
    assert!(tally.wrong_float_sign > 10, "{tally:?}");
}

/// With coordinates so small that products underflow, the values are no longer exact, but
/// the estimates' bounds still hold.
#[test]
fn estimate_bounds_hold_under_underflow() {
    let mut rng = SplitMix64(6);
    let mut tally = Tally::default();
    for _ in 0..500 {
        let scale = rng.pick(&[1e-110, 1e-150, 1e-200, 1e-305]);
        let [a, b, c, d] = [(); 4].map(|_| Point3::from(rng.vector(scale)));
        let exact = orient3d_exact(&a, &b, &c, &d);
        let (value, bound) = orient3d_estimate(&a, &b, &c, &d);
        tally.record(&exact, value, bound);
        let u = Vector3::new(wild(&mut rng, -300, 300), rng.range(-1.0, 1.0), 1e-300);
        let exact = at_infinity_exact(&a, &b, &c, &u);
        let (value, bound) = orient3d_at_infinity_estimate(&a, &b, &c, &u);
        tally.record(&exact, value, bound);
    }
}

/// The scaled-integer references and the values agree with `BigRational` arithmetic on the
/// doubles themselves (the helpers of `common`).
#[test]
fn references_agree_with_rationals() {
    let mut rng = SplitMix64(7);
    let scale = Q::from_integer(BigInt::from(1) << 3222usize);
    let rational_value = |e: &[f64]| e.iter().fold(Q::zero(), |acc, &c| acc + q(c));
    for i in 0..120 {
        let [a, b, c, d] = points(&mut rng, i % KINDS);
        let [qa, qb, qc, qd] = [a, b, c, d].map(|p| qv(arr(&p)));
        let det = qdot(&qsub(&qa, &qd), &qcross(&qsub(&qb, &qd), &qsub(&qc, &qd)));
        assert_eq!(
            Q::from_integer(orient3d_exact(&a, &b, &c, &d)) / &scale,
            det
        );
        assert_eq!(rational_value(&orient3d_value(&a, &b, &c, &d)), det);
        assert_eq!(qsign(&det), orient3d(&a, &b, &c, &d));
        let u = d - a;
        let qu = qv([u.x, u.y, u.z]);
        let det = -qdot(&qsub(&qa, &qc), &qcross(&qsub(&qb, &qc), &qu));
        assert_eq!(
            Q::from_integer(at_infinity_exact(&a, &b, &c, &u)) / &scale,
            det
        );
        assert_eq!(
            rational_value(&orient3d_at_infinity_value(&a, &b, &c, &u)),
            det
        );
        assert_eq!(qsign(&det), orient3d_at_infinity(&a, &b, &c, &u));
    }
}
