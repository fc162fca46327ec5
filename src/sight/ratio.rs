//! Ratios of exact polynomials as doubles: each polynomial rounded once, then divided (the
//! rule of every constructed coordinate), or the ratio itself correctly rounded; from
//! expansions where they are exact, else from rationals.

use crate::geometry::exact::{estimate, expansion_sum, negated, scale_expansion};
use crate::geometry::kernel::{Polynomial, builds_exactly, expansion_sign, plain_ratio};
use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::{One, Signed, ToPrimitive, Zero as _};
use std::cmp::Ordering;

/// `n / d` with each exact polynomial rounded once to the nearest double, then divided (the
/// rule of every constructed coordinate; see [`crate::geometry::kernel::ratio`]); where the
/// inputs' exponents do not allow exact expansions, the same rule from rationals, each value
/// rounded at its own scale so that nothing overflows on the way.
pub(crate) fn rounded_ratio<N: Polynomial, D: Polynomial>(n: &N, d: &D) -> f64 {
    if !builds_exactly() {
        return plain_ratio(n, d);
    }
    if n.exponents().exact_for(n.degree()) && d.exponents().exact_for(d.degree()) {
        return estimate(&n.expansion()) / estimate(&d.expansion());
    }
    let (n, d) = (n.evaluate::<BigRational>(), d.evaluate::<BigRational>());
    let (xn, en) = split(&n);
    let (xd, ed) = split(&d);
    times_power_of_two(xn / xd, en - ed)
}

/// `n / d` (`d` not zero) correctly rounded to the nearest double, ties to even: a first guess
/// from the two values each rounded once, moved to the neighbour past each midpoint `m`
/// between neighbouring doubles that the exact ratio lies beyond (the sign of `2n − 2m·d`, an
/// expansion, exact). From rationals where the expansions or their scaled copies could
/// overflow or underflow.
pub(crate) fn nearest_ratio<N: Polynomial, D: Polynomial>(n: &N, d: &D) -> f64 {
    let rational = || {
        let x = n.evaluate::<BigRational>() / d.evaluate::<BigRational>();
        x.to_f64().unwrap_or(f64::NAN)
    };
    if !(n.exponents().exact_for(n.degree()) && d.exponents().exact_for(d.degree())) {
        return rational();
    }
    let (mut en, mut ed) = (n.expansion(), d.expansion());
    if expansion_sign(&ed) == Ordering::Less {
        (en, ed) = (negated(&en), negated(&ed));
    }
    let twice: Vec<f64> = en.iter().map(|&c| 2.0 * c).collect();
    // Whether the ratio lies past the midpoint of the neighbours `lo < hi` (`Greater`), before
    // it, or on it; `None` where a product may not be exact.
    let past = |lo: f64, hi: f64| -> Option<Ordering> {
        let exact = |c: f64| {
            ed.iter()
                .all(|&x| x == 0.0 || ((x * c).abs() >= TINY && (x * c).abs() <= HUGE))
        };
        if !(exact(lo) && exact(hi) && lo.is_finite() && hi.is_finite()) {
            return None;
        }
        let across = expansion_sum(&scale_expansion(&ed, lo), &scale_expansion(&ed, hi));
        Some(expansion_sign(&expansion_sum(&twice, &negated(&across))))
    };
    let even = |x: f64, y: f64| if x.to_bits() & 1 == 0 { x } else { y };
    let mut c = estimate(&en) / estimate(&ed);
    // The guess is within a few units in the last place: a few steps at most.
    for _ in 0..64 {
        let up = c.next_up();
        match past(c, up) {
            Some(Ordering::Greater) => {
                c = up;
                continue;
            }
            Some(Ordering::Equal) => return even(c, up),
            Some(Ordering::Less) => {}
            None => return rational(),
        }
        let down = c.next_down();
        match past(down, c) {
            Some(Ordering::Less) => c = down,
            Some(Ordering::Equal) => return even(down, c),
            Some(Ordering::Greater) => return c,
            None => return rational(),
        }
    }
    rational()
}

/// `2⁻⁹⁶⁹`: a product of doubles at least this large has an exact low part (no underflow).
const TINY: f64 = f64::from_bits(54 << 52);

/// `2¹⁰⁰⁰`: products of doubles at most this large do not overflow when summed in an
/// expansion.
const HUGE: f64 = f64::from_bits(2023 << 52);

/// `x` as a double `m` rounded once and a power of two: `x ≈ m·2^e` with `m` in `[1, 2]`
/// (`m = 0` for zero). For `x` in the normal range, `m·2^e` is `x` rounded to the nearest
/// double.
fn split(x: &BigRational) -> (f64, i64) {
    if x.is_zero() {
        return (0.0, 0);
    }
    let bits = |n: &BigInt| n.bits() as i64;
    let mut e = bits(x.numer()) - bits(x.denom());
    let scaled = |e: i64| {
        let p = BigRational::from_integer(BigInt::one() << e.unsigned_abs());
        if e >= 0 { x / p } else { x * p }
    };
    let mut y = scaled(e);
    if y.abs() < BigRational::one() {
        e -= 1;
        y = scaled(e);
    }
    (y.to_f64().unwrap_or(f64::NAN), e)
}

/// `x·2^e`, exact while the result is normal.
fn times_power_of_two(mut x: f64, mut e: i64) -> f64 {
    while e > 1000 {
        x *= 2f64.powi(1000);
        e -= 1000;
    }
    while e < -1000 {
        x *= 2f64.powi(-1000);
        e += 1000;
    }
    x * 2f64.powi(e as i32)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::kernel::Product;
    use crate::geometry::predicates::Side;
    use crate::geometry::{Point3, Vector3};

    /// The product `p·q` as a polynomial of degree 2.
    fn product(p: f64, q: f64) -> Side {
        Side {
            origin: Point3::origin(),
            normal: Vector3::new(p, 0.0, 0.0),
            offset: 0.0,
            x: Point3::new(q, 0.0, 0.0),
        }
    }

    /// Against the rational ratio correctly rounded, on products whose ratios fall on and next
    /// to midpoints between doubles, and on random ones.
    #[test]
    fn nearest_ratio_is_correctly_rounded() {
        let mut seed = 0x27u64;
        let mut next = || {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            seed
        };
        let big = (1u64 << 27) as f64;
        // (2^27 + 1)(2^27 − 1) = 2^54 − 1, halfway between 2^54 − 2 and 2^54: ties to even.
        let mut cases = vec![
            (product(big + 1.0, big - 1.0), product(1.0, 1.0)),
            (product(big + 1.0, big + 1.0), product(1.0, 2.0)),
            (product(3.0, 1.0), product(10.0, 1.0)),
        ];
        for _ in 0..2000 {
            let mut x = || (next() >> 11) as f64 / (1u64 << 20) as f64 - 2f64.powi(32);
            cases.push((product(x(), x()), product(x(), 1.0 + x().abs())));
        }
        for (n, d) in cases {
            if d.sign() == Ordering::Equal {
                continue;
            }
            let exact = n.evaluate::<BigRational>() / d.evaluate::<BigRational>();
            let want = exact.to_f64().unwrap();
            assert_eq!(
                nearest_ratio(&n, &d).to_bits(),
                want.to_bits(),
                "{n:?} / {d:?}"
            );
            // The same ratio as a product over a product.
            let twice = Product(n, product(2.0, 1.0));
            assert_eq!(nearest_ratio(&twice, &Product(d, product(1.0, 2.0))), want);
        }
    }
}
