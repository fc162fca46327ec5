//! The corner formulas as forms: each case test and each vertex coordinate of the canonical
//! corner is a small integer combination of its six local bounds, simplified at compile time
//! for each set of clamped chamfers (a clamped chamfer is the exact sum of its two principal
//! bounds), and evaluated with exact signs and correctly rounded values.

use std::cmp::Ordering;

use super::cases::{A, AB, AC, B, BC, C, ROTATION, ROTATION2};
use crate::geometry::exact::{accurate_sum_array, sum_sign_array};

/// A linear form in the six local bounds `[α_A, α_B, α_C, α_AB, α_AC, α_BC]` of a corner, with
/// integer coefficients in −2..=2 (so that every term `coef · α` is an exact double).
pub(super) type LocalForm = [i8; 6];

/// A signed combination of local bounds: up to four (local plane, coefficient) pairs, unused
/// pairs with coefficient 0.
pub(super) type Combination = [(usize, i8); 4];

/// A combination of one local bound.
pub(super) const fn one(k: usize) -> Combination {
    [(k, 1), (0, 0), (0, 0), (0, 0)]
}

/// The combination `α_k − α_l`.
pub(super) const fn minus(k: usize, l: usize) -> Combination {
    [(k, 1), (l, -1), (0, 0), (0, 0)]
}

/// The combination `α_k + α_l + α_m` with the given signs.
pub(super) const fn three(k: (usize, i8), l: (usize, i8), m: (usize, i8)) -> Combination {
    [k, l, m, (0, 0)]
}

/// The effective local bound k of a corner whose clamped chamfers are the set bits of `mask`
/// (bit 0: AB, bit 1: AC, bit 2: BC) as a form: a clamped chamfer is the exact sum of its two
/// principal bounds.
pub(super) const fn local_form(k: usize, mask: usize) -> LocalForm {
    let mut f = [0; 6];
    if k >= AB && mask & (1 << (k - AB)) != 0 {
        let [p, q] = [[A, B], [A, C], [B, C]][k - AB];
        f[p] = 1;
        f[q] = 1;
    } else {
        f[k] = 1;
    }
    f
}

/// A combination of effective local bounds as a form, the symbolic cancellations of clamped
/// chamfers done (evaluated at compile time only).
pub(super) const fn form_of(combination: Combination, mask: usize) -> LocalForm {
    let mut f = [0i8; 6];
    let mut i = 0;
    while i < 4 {
        let (k, c) = combination[i];
        let l = local_form(k, mask);
        let mut m = 0;
        while m < 6 {
            f[m] += c * l[m];
            m += 1;
        }
        i += 1;
    }
    let mut m = 0;
    while m < 6 {
        assert!(
            f[m] >= -2 && f[m] <= 2,
            "a term would not be an exact double"
        );
        m += 1;
    }
    f
}

/// The three case tests of the canonical corner (x_p > α_A, y_p > α_B, z_p > α_C), each a
/// combination whose positivity is the test: α_AB + α_AC − α_BC − 2α_A > 0, and cyclically.
pub(super) const CASE_TESTS: [Combination; 3] = [
    [(AB, 1), (AC, 1), (BC, -1), (A, -2)],
    [(AB, 1), (AC, -1), (BC, 1), (B, -2)],
    [(AB, -1), (AC, 1), (BC, 1), (C, -2)],
];

/// Case 1 vertex slots (v1, v2, v3, p; paper eqs 2–7), each coordinate a combination; the
/// coordinates of p are half their combination.
pub(super) const CASE1_COORDS: [[Combination; 3]; 4] = [
    [minus(AC, C), minus(BC, C), one(C)],
    [one(A), minus(AB, A), minus(AC, A)],
    [minus(AB, B), one(B), minus(BC, B)],
    [
        three((AB, 1), (AC, 1), (BC, -1)),
        three((AB, 1), (AC, -1), (BC, 1)),
        three((AB, -1), (AC, 1), (BC, 1)),
    ],
];

/// Case 2 vertex slots (v1, v3, q2 = A∩AC∩BC, q3 = A∩AB∩BC; paper eqs 5, 7, 8, 9).
pub(super) const CASE2_COORDS: [[Combination; 3]; 4] = [
    [minus(AC, C), minus(BC, C), one(C)],
    [minus(AB, B), one(B), minus(BC, B)],
    [one(A), three((BC, 1), (AC, -1), (A, 1)), minus(AC, A)],
    [one(A), minus(AB, A), three((BC, 1), (AB, -1), (A, 1))],
];

/// Case 2's slots in the frame rotated by `sigma` ([`ROTATION`] or [`ROTATION2`]), with the
/// coordinates `w` put back as `[w[perm[0]], w[perm[1]], w[perm[2]]]`: cases 3 and 4.
pub(super) const fn rotated_coords(sigma: [usize; 6], perm: [usize; 3]) -> [[Combination; 3]; 4] {
    let mut t = CASE2_COORDS;
    let mut s = 0;
    while s < 4 {
        let mut i = 0;
        while i < 3 {
            let mut combination = CASE2_COORDS[s][perm[i]];
            let mut k = 0;
            while k < 4 {
                combination[k].0 = sigma[combination[k].0];
                k += 1;
            }
            t[s][i] = combination;
            i += 1;
        }
        s += 1;
    }
    t
}

/// The formulas of a corner with a given clamp mask: its case tests, and per case its four
/// vertices (slot order of [`CASES`]) in the canonical frame, as forms.
pub(super) struct CornerForms {
    pub(super) tests: [LocalForm; 3],
    /// The sign of each test when the clamping alone decides it (see [`known_sign`]).
    pub(super) known: [Option<Ordering>; 3],
    /// For each test, an earlier test of which it is the negation (its sign is then known).
    pub(super) negates: [Option<usize>; 3],
    pub(super) coords: [[[LocalForm; 3]; 4]; 4],
}

/// The sign of a test form when the clamp mask decides it: the zero form is zero, and
/// `±(α_P + α_Q − α_PQ)` for an unclamped chamfer PQ is positive (negative) since an unclamped
/// chamfer bound is strictly below the sum of its principal bounds (see [`clamped_chamfers`]).
pub(super) const fn known_sign(f: LocalForm, mask: usize) -> Option<Ordering> {
    if forms_equal(f, [0; 6], 1) {
        return Some(Ordering::Equal);
    }
    let mut k = AB;
    while k <= BC {
        if mask & (1 << (k - AB)) == 0 {
            // α_P + α_Q − α_PQ, as the clamped form of PQ minus its own bound.
            let mut g = local_form(k, 1 << (k - AB));
            g[k] = -1;
            if forms_equal(f, g, 1) {
                return Some(Ordering::Greater);
            }
            if forms_equal(f, g, -1) {
                return Some(Ordering::Less);
            }
        }
        k += 1;
    }
    None
}

/// Whether `f = sign · g`.
pub(super) const fn forms_equal(f: LocalForm, g: LocalForm, sign: i8) -> bool {
    let mut m = 0;
    while m < 6 {
        if f[m] != sign * g[m] {
            return false;
        }
        m += 1;
    }
    true
}

/// `CORNER_FORMS[mask]`: the formulas of a corner whose clamped chamfers are the set bits of
/// `mask` (see [`local_form`]).
pub(super) const CORNER_FORMS: [CornerForms; 8] = {
    let cases = [
        CASE1_COORDS,
        CASE2_COORDS,
        rotated_coords(ROTATION, [2, 0, 1]),
        rotated_coords(ROTATION2, [1, 2, 0]),
    ];
    let mut t = [const {
        CornerForms {
            tests: [[0; 6]; 3],
            known: [None; 3],
            negates: [None; 3],
            coords: [[[[0; 6]; 3]; 4]; 4],
        }
    }; 8];
    let mut mask = 0;
    while mask < 8 {
        let mut i = 0;
        while i < 3 {
            t[mask].tests[i] = form_of(CASE_TESTS[i], mask);
            // The test is case 1's doubled p coordinate minus twice the principal bound (see
            // `masked_corner`).
            let mut m = 0;
            while m < 6 {
                let twice = if m == i { 2 } else { 0 };
                assert!(t[mask].tests[i][m] == form_of(CASE1_COORDS[3][i], mask)[m] - twice);
                m += 1;
            }
            t[mask].known[i] = known_sign(t[mask].tests[i], mask);
            let mut j = 0;
            while j < i {
                if forms_equal(t[mask].tests[i], t[mask].tests[j], -1) {
                    t[mask].negates[i] = Some(j);
                }
                j += 1;
            }
            i += 1;
        }
        let mut k = 0;
        while k < 4 {
            let mut s = 0;
            while s < 4 {
                let mut i = 0;
                while i < 3 {
                    t[mask].coords[k][s][i] = form_of(cases[k][s][i], mask);
                    i += 1;
                }
                s += 1;
            }
            k += 1;
        }
        mask += 1;
    }
    t
};

/// The nonzero terms `coef_k · α_k` of a form (exact doubles) and their number.
#[inline(always)]
pub(super) fn form_terms(f: &LocalForm, al: &[f64; 6]) -> ([f64; 6], usize) {
    let mut terms = [0.0; 6];
    let mut n = 0;
    for (&c, &x) in f.iter().zip(al) {
        if c != 0 {
            terms[n] = f64::from(c) * x;
            n += 1;
        }
    }
    (terms, n)
}

/// The exact sign of a form. The sum of at most two exact terms is rounded once, which keeps
/// its sign; longer sums go through the filtered exact sign. The number of terms of a constant
/// form is a constant, so one arm remains, on a fixed-length array (kept in registers).
#[inline(always)]
pub(super) fn form_sign(f: &LocalForm, al: &[f64; 6]) -> Ordering {
    let (t, n) = form_terms(f, al);
    match n {
        0..=2 => (t[0] + t[1]).partial_cmp(&0.0).unwrap_or(Ordering::Equal),
        3 => sum_sign_array([t[0], t[1], t[2]]),
        4 => sum_sign_array([t[0], t[1], t[2], t[3]]),
        5 => sum_sign_array([t[0], t[1], t[2], t[3], t[4]]),
        _ => sum_sign_array(t),
    }
}

/// The exact value of a form, correctly rounded (one addition for at most two terms; see
/// [`form_sign`] for the arms).
#[inline(always)]
pub(super) fn form_value(f: &LocalForm, al: &[f64; 6]) -> f64 {
    let (t, n) = form_terms(f, al);
    match n {
        0..=2 => t[0] + t[1],
        3 => accurate_sum_array([t[0], t[1], t[2]]),
        4 => accurate_sum_array([t[0], t[1], t[2], t[3]]),
        5 => accurate_sum_array([t[0], t[1], t[2], t[3], t[4]]),
        _ => accurate_sum_array(t),
    }
}

/// The number of nonzero coefficients of a form.
pub(super) const fn form_len(f: &LocalForm) -> usize {
    let mut n = 0;
    let mut m = 0;
    while m < 6 {
        if f[m] != 0 {
            n += 1;
        }
        m += 1;
    }
    n
}

/// A vertex from the forms of its coordinates. Written out so that, the forms being
/// constants, every coefficient test folds away.
#[inline(always)]
pub(super) fn slot(coords: &[LocalForm; 3], al: &[f64; 6]) -> [f64; 3] {
    [
        form_value(&coords[0], al),
        form_value(&coords[1], al),
        form_value(&coords[2], al),
    ]
}

/// The four vertices of case 2, 3 or 4 from their forms.
#[inline(always)]
pub(super) fn slots(coords: &[[LocalForm; 3]; 4], al: &[f64; 6]) -> [[f64; 3]; 4] {
    [
        slot(&coords[0], al),
        slot(&coords[1], al),
        slot(&coords[2], al),
        slot(&coords[3], al),
    ]
}
