//! Randomised checks that the compile-time simplified forms give, bit for bit, the boundary
//! the generic corner formulas give on exact forms.

use std::cmp::Ordering;

use super::cases::CORNER_PLANES;
use super::cleanup::OffsetForm;
use super::corners::{clamped_chamfers, corner, reflected};
use super::directions::CHAMFER_PARENTS;
use super::forms::CASE_TESTS;
use super::{Tribox, TriboxBounds};
use crate::geometry::Point3;
use crate::geometry::exact::{accurate_sum, sum_sign};
use crate::random::SplitMix64;

/// The boundary by the generic corner formulas on exact forms (every clamped chamfer the
/// form of its two principal bounds): each sign exact, each coordinate correctly rounded.
fn reference(bounds: &TriboxBounds) -> Tribox {
    let beta = bounds.offsets();
    let clamped = clamped_chamfers(&beta);
    let forms: [[i32; 18]; 18] = std::array::from_fn(|j| {
        let mut f = [0; 18];
        if clamped[j] {
            for p in CHAMFER_PARENTS[j] {
                f[usize::from(p)] = 2;
            }
        } else {
            f[j] = 2;
        }
        f
    });
    Tribox::from_corners(bounds, |c| {
        let planes = CORNER_PLANES[c];
        let (case, v) = corner(std::array::from_fn(|k| OffsetForm {
            coef: forms[usize::from(planes[k])],
            beta: &beta,
        }));
        (case, reflected(c, &v))
    })
}

/// Bit-for-bit equality of two boundaries (a zero's sign included).
fn assert_same(t: &Tribox, r: &Tribox, b: &TriboxBounds) {
    assert_eq!(t.corner_cases(), r.corner_cases(), "{b:?}");
    let bits = |t: &Tribox| -> Vec<u64> {
        t.vertices()
            .iter()
            .flat_map(|p| [p.x, p.y, p.z].map(f64::to_bits))
            .collect()
    };
    assert_eq!(bits(t), bits(r), "{b:?}");
    assert_eq!(t.vertex_planes(), r.vertex_planes(), "{b:?}");
    for j in 0..18 {
        assert_eq!(t.face(j), r.face(j), "{b:?}");
    }
}

/// A random cloud of a few points: generic, on a coarse grid (many exact ties and clamped
/// chamfers whose sums cancel exactly), or of wildly different magnitudes; scaled by a
/// power of ten from 1e-310 to 1e300, mixed signs (and no sum of bounds overflows).
fn cloud(rng: &mut SplitMix64) -> Vec<Point3> {
    const SCALES: [f64; 8] = [1.0, 1e-300, 1e300, 1e-160, 3e150, 1e-310, 0.1, -7.0];
    let scale = SCALES[rng.below(8)];
    let kind = rng.below(6);
    let n = 1 + rng.below(9);
    (0..n)
        .map(|_| {
            let mut c = [0.0; 3];
            for x in &mut c {
                *x = scale
                    * match kind {
                        0 => 2.0 * rng.unit() - 1.0,
                        1 => (rng.below(5) as f64 - 2.0) * 0.5,
                        2 => rng.below(3) as f64,
                        3 => (rng.unit() - 0.5) * 2f64.powi(rng.below(120) as i32 - 100),
                        4 => rng.below(4) as f64 * 0.1 + [0.0, 1e-17][rng.below(2)],
                        _ => rng.unit(),
                    };
            }
            Point3::new(c[0], c[1], c[2])
        })
        .collect()
}

#[test]
fn simplified_forms_match_the_exact_formulas() {
    let mut rng = SplitMix64(0x1234_5678_9abc_def1);
    let mut masks = [0usize; 8];
    let mut cases = [0usize; 5];
    for it in 0..100_000 {
        let mut b = TriboxBounds::from_points(&cloud(&mut rng));
        if it % 3 == 2 {
            // Bounds of no point set: random cuts across random directions.
            for _ in 0..1 + rng.below(4) {
                let d = rng.below(9);
                let (lo, hi) = (b.min()[d], b.max()[d]);
                let pick = b.split(d, lo + (hi - lo) * rng.unit())[rng.below(2)];
                if !pick.is_empty() {
                    b = pick;
                }
            }
        }
        let t = Tribox::new(&b);
        assert_same(&t, &reference(&b), &b);
        let clamped = clamped_chamfers(&b.offsets());
        for (c, planes) in CORNER_PLANES.iter().enumerate() {
            let mask = (3..6).fold(0, |m, k| {
                m | usize::from(clamped[usize::from(planes[k])]) << (k - 3)
            });
            masks[mask] += 1;
            cases[usize::from(t.corner_cases()[c])] += 1;
        }
    }
    // Every clamp mask and every case is exercised.
    assert!(masks.iter().all(|&m| m > 100), "{masks:?}");
    assert!(cases[1..].iter().all(|&m| m > 100), "{cases:?}");
}

/// Bounds on the edge of every filter: small integers times a power of two (so that
/// chamfers equal the sum of their principal bounds, and p lies on a principal plane,
/// exactly and often), with chamfers set to the rounded sum of their principal bounds and
/// bounds moved by an ulp either way; from subnormal scales to near overflow.
fn edge_bounds(rng: &mut SplitMix64) -> TriboxBounds {
    const SCALES: [i32; 8] = [-1074, -1060, -1000, -500, 0, 30, 500, 1000];
    let scale = 2f64.powi(SCALES[rng.below(8)]);
    // An odd factor makes sums inexact (and their errors ties of a half ulp) at times.
    let factor = [1.0, 3.0, 0.1, 1.0 + f64::EPSILON][rng.below(4)];
    let mut beta: [f64; 18] = std::array::from_fn(|j| {
        let range = if j < 6 { 5 } else { 9 };
        (rng.below(range) as f64 - 1.0) * factor * scale
    });
    for j in 6..18 {
        if rng.below(2) == 0 {
            let [p, q] = CHAMFER_PARENTS[j].map(usize::from);
            beta[j] = beta[p] + beta[q];
        }
    }
    for _ in 0..rng.below(4) {
        let j = rng.below(18);
        beta[j] = if rng.below(2) == 0 {
            beta[j].next_up()
        } else {
            beta[j].next_down()
        };
    }
    TriboxBounds::from_offsets(&beta)
}

#[test]
fn ties_and_near_ties_match_the_exact_formulas() {
    let mut rng = SplitMix64(0x0bad_cafe_f00d_d00d);
    // Corner tests (x_p > α_A and cyclically) that are exactly zero, and that the rounded
    // doubled p cannot decide (equal to 2α but not exactly), on unclamped corners.
    let (mut zero, mut undecided, mut clamp_ties) = (0, 0, 0);
    for _ in 0..200_000 {
        let b = edge_bounds(&mut rng);
        if b.is_empty() {
            continue;
        }
        let t = Tribox::new(&b);
        assert_same(&t, &reference(&b), &b);
        let beta = b.offsets();
        for j in 6..18 {
            let [p, q] = CHAMFER_PARENTS[j].map(usize::from);
            clamp_ties += usize::from(beta[j] == beta[p] + beta[q]);
        }
        let clamped = clamped_chamfers(&beta);
        for planes in CORNER_PLANES {
            let al = planes.map(|j| beta[usize::from(j)]);
            if (3..6).any(|k| clamped[usize::from(planes[k])]) {
                continue;
            }
            for (i, test) in CASE_TESTS.iter().enumerate() {
                let terms = test.map(|(k, c)| f64::from(c) * al[k]);
                let twice_p = accurate_sum(&terms[..3]);
                if sum_sign(&terms) == Ordering::Equal {
                    zero += 1;
                } else if twice_p == 2.0 * al[i] {
                    undecided += 1;
                }
            }
        }
    }
    assert!(zero > 2_000 && undecided > 1_000, "{zero} {undecided}");
    assert!(clamp_ties > 10_000, "{clamp_ties}");
}
