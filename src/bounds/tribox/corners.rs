//! The corners of the block (paper section 3): each corner is reflected to the canonical one,
//! classified into case 1 to 4 and given its four vertices, either from the compile-time forms
//! ([`masked_corner`]), for all eight corners at once in the generic case
//! ([`generic_vertices`]), or from the generic formulas over any [`LocalBound`] ([`corner`]).

use std::cmp::Ordering;

use super::cases::{CORNER_PLANES, CORNER_SIGNS};
use super::directions::CHAMFER_PARENTS;
use super::forms::{CORNER_FORMS, CornerForms, form_len, form_sign, form_value, slot, slots};
use crate::geometry::Point3;
use crate::geometry::exact::{accurate_sum3_lanes, two_sum};

/// A local bound of a corner, as the generic corner formulas ([`corner`]) need it: the
/// tightened bounds of [`Tribox::cleaned`] ([`OffsetForm`]). [`Tribox::new`] evaluates the same
/// formulas from tables of simplified forms instead ([`masked_corner`]).
pub(super) trait LocalBound: Copy {
    /// The negated bound.
    fn neg(self) -> Self;
    /// The value, for a principal bound (a single double).
    fn value(self) -> f64;
    /// a + b, correctly rounded.
    fn sum2(a: Self, b: Self) -> f64;
    /// a + b + c, correctly rounded.
    fn sum3(a: Self, b: Self, c: Self) -> f64;
    /// Whether a + b + c + d + e > 0, exactly.
    fn positive5(a: Self, b: Self, c: Self, d: Self, e: Self) -> bool;
    /// The case (1..4) of the canonical corner with local bounds `[α_A, α_B, α_C, α_AB, α_AC,
    /// α_BC]`: x_p > α_A ⇔ α_AB + α_AC − α_BC − 2α_A > 0, and cyclically; at most one holds once
    /// the chamfers are clamped, so the paper's order of the tests is immaterial.
    #[inline]
    fn case_of(al: [Self; 6]) -> usize {
        let [a, b, c, ab, ac, bc] = al;
        if Self::positive5(ab, ac, bc.neg(), a.neg(), a.neg()) {
            2
        } else if Self::positive5(ab, ac.neg(), bc, b.neg(), b.neg()) {
            3
        } else if Self::positive5(ab.neg(), ac, bc, c.neg(), c.neg()) {
            4
        } else {
            1
        }
    }
}
/// The canonical corner with local bounds `al = [α_A, α_B, α_C, α_AB, α_AC, α_BC]` whose
/// clamped chamfers are the set bits of `MASK`: its case (1..4) and its four vertices in the
/// slot order of [`CASES`], each coordinate the correctly rounded exact value of its formula
/// (halved for p). The formulas are the symbolically simplified forms of [`CORNER_FORMS`], so
/// that exact cancellations of clamped chamfers cost no arithmetic, and tests whose sign the
/// clamping decides ([`CornerForms::known`]) none either. The tests are taken in the paper's
/// order, as [`LocalBound::case_of`] does.
///
/// Test i (x_p > α_A, y_p > α_B, z_p > α_C) is the sign of `2p_i − 2α_i`, and `2p_i` is the
/// form case 1 rounds for its last slot anyway (halving it): since rounding to nearest is
/// monotone and `2α_i` is a double, the rounded `2p_i` above (below) `2α_i` proves the exact one
/// above (below) it, so one comparison decides the test, and the exact sign of the test's form
/// is needed only when they are equal.
#[inline(always)]
pub(super) fn masked_corner<const MASK: usize>(al: [f64; 6]) -> (usize, [[f64; 3]; 4]) {
    let forms = const { &CORNER_FORMS[MASK] };
    let p2 = &forms.coords[0][3];
    // The doubled p, correctly rounded (computed where a test or case 1 needs it).
    let twice_p = [
        form_value(&p2[0], &al),
        form_value(&p2[1], &al),
        form_value(&p2[2], &al),
    ];
    // Written out (no loop, no closure) so that the constant tables fold.
    #[inline(always)]
    fn sign(
        forms: &CornerForms,
        i: usize,
        earlier: &[Ordering],
        twice_p: f64,
        al: &[f64; 6],
    ) -> Ordering {
        match (forms.known[i], forms.negates[i]) {
            (Some(known), _) => known,
            (None, Some(j)) => earlier[j].reverse(),
            // One rounded addition keeps the sign of a sum of two exact terms.
            (None, None) if form_len(&forms.tests[i]) <= 2 => form_sign(&forms.tests[i], al),
            (None, None) => {
                let bound = 2.0 * al[i];
                if twice_p > bound {
                    Ordering::Greater
                } else if twice_p < bound {
                    Ordering::Less
                } else {
                    form_sign(&forms.tests[i], al)
                }
            }
        }
    }
    let s0 = sign(forms, 0, &[], twice_p[0], &al);
    if s0 == Ordering::Greater {
        return (2, slots(&forms.coords[1], &al));
    }
    let s1 = sign(forms, 1, &[s0], twice_p[1], &al);
    if s1 == Ordering::Greater {
        return (3, slots(&forms.coords[2], &al));
    }
    if sign(forms, 2, &[s0, s1], twice_p[2], &al) == Ordering::Greater {
        return (4, slots(&forms.coords[3], &al));
    }
    // Halving is exact but for subnormal results.
    let c = &forms.coords[0];
    (
        1,
        [
            slot(&c[0], &al),
            slot(&c[1], &al),
            slot(&c[2], &al),
            twice_p.map(|x| 0.5 * x),
        ],
    )
}

/// Classifies the canonical corner with local bounds `[α_A, α_B, α_C, α_AB, α_AC, α_BC]`
/// (chamfers already clamped) and computes its four vertices in the canonical frame.
/// Returns the case (1..4) and the vertices in the slot order of [`CASES`].
#[inline]
pub(super) fn corner<T: LocalBound>(al: [T; 6]) -> (usize, [[f64; 3]; 4]) {
    let [a, b, c, ab, ac, bc] = al;
    match T::case_of(al) {
        2 => return (2, case2(al)),
        3 => {
            let v = case2([b, c, a, bc, ab, ac]);
            return (3, v.map(|w| [w[2], w[0], w[1]]));
        }
        4 => {
            let v = case2([c, a, b, ac, bc, ab]);
            return (4, v.map(|w| [w[1], w[2], w[0]]));
        }
        _ => {}
    }
    // Case 1: p inside the block. Paper eqs (2)-(7); halving is exact.
    let v1 = [T::sum2(ac, c.neg()), T::sum2(bc, c.neg()), c.value()];
    let v2 = [a.value(), T::sum2(ab, a.neg()), T::sum2(ac, a.neg())];
    let v3 = [T::sum2(ab, b.neg()), b.value(), T::sum2(bc, b.neg())];
    let p = [
        0.5 * T::sum3(ab, ac, bc.neg()),
        0.5 * T::sum3(ab, ac.neg(), bc),
        0.5 * T::sum3(ab.neg(), ac, bc),
    ];
    (1, [v1, v2, v3, p])
}

/// Case 2 (p beyond h_A): vertices v1, v3 (eqs 5, 7), q2 = A∩AC∩BC and q3 = A∩AB∩BC
/// (eqs 8, 9), in the canonical frame.
#[inline]
pub(super) fn case2<T: LocalBound>(al: [T; 6]) -> [[f64; 3]; 4] {
    let [a, b, c, ab, ac, bc] = al;
    let v1 = [T::sum2(ac, c.neg()), T::sum2(bc, c.neg()), c.value()];
    let v3 = [T::sum2(ab, b.neg()), b.value(), T::sum2(bc, b.neg())];
    let q2 = [a.value(), T::sum3(bc, ac.neg(), a), T::sum2(ac, a.neg())];
    let q3 = [a.value(), T::sum2(ab, a.neg()), T::sum3(bc, ab.neg(), a)];
    [v1, v3, q2, q3]
}

/// The vertices `v` of corner `c`, computed in its canonical frame, in world coordinates (each
/// coordinate times the corner's sign; adding +0 turns the −0 of a reflected zero into +0).
#[inline(always)]
pub(super) fn reflected(c: usize, v: &[[f64; 3]; 4]) -> [Point3; 4] {
    let s = CORNER_SIGNS[c];
    let r = |v: &[f64; 3]| Point3::new(s[0] * v[0] + 0.0, s[1] * v[1] + 0.0, s[2] * v[2] + 0.0);
    [r(&v[0]), r(&v[1]), r(&v[2]), r(&v[3])]
}

/// The vertices of the generic boundary, no chamfer clamped and every corner in case 1,
/// evaluated for the 8 corners at once (lane c is corner c, so that the arithmetic
/// vectorises); `None` when some corner is in another case or needs exact arithmetic (a
/// doubled p coordinate equal to twice its principal bound, or a sum [`accurate_sum3_lanes`]
/// does not certify), left to [`masked_corner`]. The same operations as
/// [`masked_corner::<0>`](masked_corner) in case 1, hence the same doubles.
#[inline(always)]
pub(super) fn generic_vertices(beta: &[f64; 18]) -> Option<[[Point3; 4]; 8]> {
    // Plain loops over fixed arrays (array::from_fn and map were left as calls).
    let mut al = [[0.0; 8]; 6];
    for (k, lanes) in al.iter_mut().enumerate() {
        for (c, x) in lanes.iter_mut().enumerate() {
            *x = beta[usize::from(CORNER_PLANES[c][k])];
        }
    }
    let [a, b, c, ab, ac, bc] = al;
    let neg = |mut x: [f64; 8]| {
        for v in &mut x {
            *v = -*v;
        }
        x
    };
    // The doubled p (CASE1_COORDS's last slot), terms in the order of the local planes.
    let (px, cx) = accurate_sum3_lanes(ab, ac, neg(bc));
    let (py, cy) = accurate_sum3_lanes(ab, neg(ac), bc);
    let (pz, cz) = accurate_sum3_lanes(neg(ab), ac, bc);
    // Case 1 everywhere: every test x_p > α_A (and cyclically) decided negative.
    let mut below = cx && cy && cz;
    for k in 0..8 {
        below &= (px[k] < 2.0 * a[k]) & (py[k] < 2.0 * b[k]) & (pz[k] < 2.0 * c[k]);
    }
    if !below {
        return None;
    }
    let mut out = [[const { Point3::new(0.0, 0.0, 0.0) }; 4]; 8];
    for (k, o) in out.iter_mut().enumerate() {
        let (aa, bb, cc, ab, ac, bc) = (a[k], b[k], c[k], ab[k], ac[k], bc[k]);
        *o = reflected(
            k,
            &[
                [ac - cc, bc - cc, cc + 0.0],
                [aa + 0.0, ab - aa, ac - aa],
                [ab - bb, bb + 0.0, bc - bb],
                [0.5 * px[k], 0.5 * py[k], 0.5 * pz[k]],
            ],
        );
    }
    Some(out)
}

/// Which chamfer bounds are clamped: β_j ≥ β_p1 + β_p2 for its parent principal planes.
#[inline]
pub(super) fn clamped_chamfers(beta: &[f64; 18]) -> [bool; 18] {
    let mut clamped = [false; 18];
    for j in 6..18 {
        let [p1, p2] = CHAMFER_PARENTS[j];
        // β_p1 + β_p2 = s + e exactly, and rounding to nearest puts s + e strictly between
        // the neighbours of s: so β_j ≥ s + e ⇔ β_j > s, or β_j = s and e ≤ 0.
        // The error e is needed only in a tie.
        let (x, y) = (beta[usize::from(p1)], beta[usize::from(p2)]);
        let s = x + y;
        clamped[j] = beta[j] > s || (beta[j] == s && two_sum(x, y).1 <= 0.0);
    }
    clamped
}
