//! Certified boxes of the cells: a filter in front of the signs of an occluder piece's lines.
//!
//! Most occluder pieces miss most cells of VTP(F): on the bundled metropolis 98 % of the
//! (cell, piece) pairs tested leave the cell whole. Telling so by the signs of the cell's
//! vertices costs an estimate per vertex and line (an exact sign when the estimate cannot
//! tell) and a few allocations. Here each vertex `X = O + N / W` gets a box certified to hold
//! it, from the estimates of `N` and `W` and their error bounds; a cell, convex, lies in the
//! box of its vertices' boxes; and a line's form, affine, is bounded above on that box from
//! its estimated coefficients, every rounding accounted for. When the form is certified
//! strictly negative on the piece's side on the whole box, every vertex of the cell is
//! strictly outside that line, which is exactly when `Vtp::without` answers that the piece
//! misses the cell: the filter gives that answer first and decides nothing else. A vertex
//! whose `W` is not certified nonzero (nearly parallel lines) has no box, nor has its cell;
//! the signs decide for it as before.
//!
//! Written by hand: the bounds follow the error model of [`Estimate`], which no interval crate
//! shares.

use crate::geometry::estimate::{Estimate, UNIT_ROUNDOFF, sum_error_bound};
use std::cmp::Ordering;

/// A box certified to hold a point or a cell of F's plane: for each axis, a lower and an
/// upper bound on the coordinate relative to F's first vertex `O`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(in crate::surfaces) struct Extent(pub(in crate::surfaces) [[f64; 2]; 3]);

impl Extent {
    /// The box of the point `O + N / W` from estimates of `N`'s components and of `W`; `None`
    /// when `W` is not certified nonzero or a bound is not finite.
    pub(in crate::surfaces) fn of_quotient(n: [Estimate; 3], w: Estimate) -> Option<Extent> {
        if !(w.value.is_finite() && w.value.abs() > w.bound) {
            return None;
        }
        // `W` has the sign `s` of its estimate; `N / W = sN / |W|`, with `|W|` between
        // `low` and `high`, both positive.
        let s = w.value.signum();
        let (low, high) = (w.value.abs() - w.bound, w.value.abs() + w.bound);
        if low.partial_cmp(&0.0) != Some(Ordering::Greater) {
            return None;
        }
        let mut extent = [[0.0; 2]; 3];
        for (k, nk) in n.iter().enumerate() {
            let (n_low, n_high) = (s * nk.value - nk.bound, s * nk.value + nk.bound);
            // Over the denominators in [low, high] the quotient is least at an end of the
            // numerator's lower bound and greatest at one of its upper bound.
            let least = (n_low / low).min(n_low / high);
            let most = (n_high / low).max(n_high / high);
            // Each end above was rounded once, and each quotient once: within 3.01u of the
            // exact ones. The pad of 8u covers that and its own rounding; `MIN_POSITIVE` an
            // underflow.
            let pad = |x: f64| 8.0 * UNIT_ROUNDOFF * x.abs() + f64::MIN_POSITIVE;
            extent[k] = [least - pad(least), most + pad(most)];
        }
        extent
            .iter()
            .flatten()
            .all(|x| x.is_finite())
            .then_some(Extent(extent))
    }

    /// The box holding both boxes.
    pub(in crate::surfaces) fn union(&self, other: &Extent) -> Extent {
        Extent([0, 1, 2].map(|k| {
            [
                self.0[k][0].min(other.0[k][0]),
                self.0[k][1].max(other.0[k][1]),
            ]
        }))
    }

    /// Whether the affine `form` is certified strictly negative at every point of the box.
    #[inline]
    pub(in crate::surfaces) fn surely_negative(&self, form: &SignedForm) -> bool {
        // The greatest value of each term on the box, the estimates taken as exact, then what
        // their errors add: `|c − ĉ| ≤ e_c` and `|(g − ĝ)·d| ≤ e_g·max|d|`.
        let term = |k: usize| {
            let [low, high] = self.0[k];
            let a = form.g[k].value;
            let most = if a >= 0.0 { a * high } else { a * low };
            (most, form.g[k].bound * low.abs().max(high.abs()))
        };
        let (t0, t1, t2) = (term(0), term(1), term(2));
        let terms = [
            form.c.value,
            form.c.bound,
            t0.0,
            t0.1,
            t1.0,
            t1.1,
            t2.0,
            t2.1,
        ];
        // Summed pairwise (the bound of a sum of `n` terms holds in any order).
        let sum = |t: [f64; 8]| ((t[0] + t[1]) + (t[2] + t[3])) + ((t[4] + t[5]) + (t[6] + t[7]));
        let value = sum(terms);
        let magnitude = sum(terms.map(f64::abs));
        // Each term exact or rounded once: the sum is within the bound of the exact sum; a
        // computed `value + bound` below zero has an exact one below zero.
        value + sum_error_bound(terms.len(), magnitude) < 0.0
    }
}

/// An affine form `c + g·(x − O)` of F's plane, from estimates of its coefficients, times a
/// sign (negation is exact).
#[derive(Debug, Clone, Copy)]
pub(in crate::surfaces) struct SignedForm {
    c: Estimate,
    g: [Estimate; 3],
}

impl SignedForm {
    /// The form with coefficients estimated by `c` and `g`, times the sign `side` (`None` for
    /// `Equal`).
    pub(in crate::surfaces) fn new(c: Estimate, g: [Estimate; 3], side: Ordering) -> Option<Self> {
        let sigma = match side {
            Ordering::Greater => 1.0,
            Ordering::Less => -1.0,
            Ordering::Equal => return None,
        };
        let times = |e: Estimate| Estimate {
            value: sigma * e.value,
            bound: e.bound,
        };
        Some(SignedForm {
            c: times(c),
            g: g.map(times),
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::random::SplitMix64 as Rng;
    use num_rational::BigRational;
    use num_traits::{FromPrimitive, Signed};

    fn rational(x: f64) -> BigRational {
        BigRational::from_f64(x).unwrap()
    }

    /// An estimate of `x`, off by up to its bound either way.
    fn estimate(rng: &mut Rng, x: f64, relative: f64) -> (BigRational, Estimate) {
        let bound = x.abs() * relative * rng.unit();
        let value = x + bound * (2.0 * rng.unit() - 1.0);
        (rational(x), Estimate { value, bound })
    }

    /// The box holds the exact quotient `N / W` for numbers anywhere in their estimates'
    /// ranges, at every scale, and is `None` exactly when `W`'s sign is uncertain.
    #[test]
    fn boxes_hold_the_exact_point() {
        let mut rng = Rng(7);
        for round in 0..20_000 {
            let scale = 2f64.powi((round % 61) * 20 - 600);
            let relative = [0.0, 1e-16, 1e-8, 0.5][round as usize % 4];
            let mut value = || (2.0 * rng.unit() - 1.0) * scale;
            let (n, w): ([f64; 3], f64) = ([value(), value(), value()], value());
            let mut rng2 = Rng(round as u64);
            let (w_exact, w_est) = estimate(&mut rng2, w, relative);
            let ns = n.map(|x| estimate(&mut rng2, x, relative));
            let extent = Extent::of_quotient(ns.clone().map(|n| n.1), w_est);
            if w_est.value.abs() <= w_est.bound {
                assert!(extent.is_none());
                continue;
            }
            let Some(Extent(e)) = extent else {
                assert!(!(w / scale).is_finite() || w == 0.0, "{w}");
                continue;
            };
            for k in 0..3 {
                let q = &ns[k].0 / &w_exact;
                assert!(
                    rational(e[k][0]) <= q && q <= rational(e[k][1]),
                    "{round} {k}"
                );
            }
        }
    }

    /// The form is surely negative on a box only when every form within the estimates'
    /// bounds is negative at every corner of the box, checked exactly at the ends of each
    /// coefficient's range; and it is found surely negative when it clearly is.
    #[test]
    fn forms_surely_negative_only_when_negative() {
        let mut rng = Rng(11);
        let mut found = 0;
        for round in 0..4_000 {
            let scale = 2f64.powi((round % 41) * 30 - 600);
            let mut v = || (2.0 * rng.unit() - 1.0) * scale;
            let extent = Extent([0, 1, 2].map(|_| {
                let (a, b) = (v(), v());
                [a.min(b), a.max(b)]
            }));
            let (c, g) = (v() * scale, [v(), v(), v()]);
            let side = if round % 2 == 0 {
                Ordering::Greater
            } else {
                Ordering::Less
            };
            let relative = [0.0, 1e-12, 1e-3, 0.3][round as usize % 4];
            let e = |x: f64| Estimate {
                value: x,
                bound: x.abs() * relative,
            };
            let form = SignedForm::new(e(c), g.map(e), side).unwrap();
            if !extent.surely_negative(&form) {
                continue;
            }
            found += 1;
            let ends = |x: f64| {
                [
                    rational(x) - rational(e(x).bound),
                    rational(x) + rational(e(x).bound),
                ]
            };
            let (cs, gs) = (ends(c), g.map(ends));
            for choice in 0..16 {
                for corner in 0..8 {
                    let mut s = cs[choice & 1].clone();
                    for k in 0..3 {
                        let d = rational(extent.0[k][(corner >> k) & 1]);
                        s += gs[k][(choice >> (k + 1)) & 1].clone() * d;
                    }
                    let s = if side == Ordering::Less { -s } else { s };
                    assert!(s.is_negative(), "{round} {choice} {corner}");
                }
            }
        }
        assert!(found > 400, "{found}");
    }
}
