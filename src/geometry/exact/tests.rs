//! The expansion arithmetic's inner steps against each other and at their edge cases.

use super::expansion::{grow_expansion, with_expansion};
use super::sign::{exact_sign, sign_of};
use super::sum::{exact_round, min_half_gap, round_expansion};
use super::*;
use crate::random::SplitMix64;
use std::cmp::Ordering;

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
    let mut rng = SplitMix64(0x2545_f491_4f6c_dd1d);
    let mut next = move || rng.next_u64();
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
