//! Exact linear forms in the 18 offsets and the support of each direction over the tribox:
//! integer forms evaluated with exact signs and correct rounding, and, by linear programming
//! duality, the least nonnegative combination of other bounds that bounds a direction (how
//! clean-up tightens a bound that misses the tribox).

use std::cmp::Ordering;
use std::sync::OnceLock;

use super::directions::normal;
use crate::geometry::exact::{accurate_sum, sum_sign};

/// Integer 3×3 determinant.
pub(super) fn det3(m: [[i32; 3]; 3]) -> i32 {
    m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1])
        - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
        + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0])
}

/// Integer adjugate: `adj(m) · m = det(m) · I`.
pub(super) fn adjugate(m: [[i32; 3]; 3]) -> [[i32; 3]; 3] {
    std::array::from_fn(|i| {
        std::array::from_fn(|k| {
            // Cofactor (k, i).
            let r = [(k + 1) % 3, (k + 2) % 3];
            let c = [(i + 1) % 3, (i + 2) % 3];
            m[r[0]][c[0]] * m[r[1]][c[1]] - m[r[0]][c[1]] * m[r[1]][c[0]]
        })
    })
}

/// The normals of planes p as matrix rows.
pub(super) fn normal_rows(p: [usize; 3]) -> [[i32; 3]; 3] {
    p.map(|j| normal(j).map(i32::from))
}

/// Each bound as the exact maximum of its direction over the tribox, as a form in half-units:
/// `tight[j]` has coefficients c with `h_j = Σ_k c_k β_k / 2`. It is `2 β_j` itself when plane j
/// touches the tribox, otherwise the least combination of other bounds (an optimal dual
/// basis, whose planes all touch the tribox by complementary slackness).
pub(super) fn tight_forms(beta: &[f64; 18]) -> [[i32; 18]; 18] {
    std::array::from_fn(|j| {
        let mut own = [0; 18];
        own[j] = 2;
        match support_without(j, beta) {
            Some(basis) => {
                let halves = basis.dense();
                let coef: [i32; 18] = std::array::from_fn(|k| halves[k] - own[k]);
                if sign_of_form(&coef, beta) == Ordering::Less {
                    halves
                } else {
                    own
                }
            }
            None => own,
        }
    })
}

/// Calls `f` with the terms `c_k β_k` of an integer form, each coefficient split into signed
/// powers of two so that every term is an exact double (on the stack when there are few).
pub(super) fn with_form_terms<R>(
    coef: &[i32; 18],
    beta: &[f64; 18],
    f: impl FnOnce(&[f64]) -> R,
) -> R {
    const STACK: usize = 64;
    let fill = |terms: &mut [f64]| {
        let mut n = 0;
        for (k, &c) in coef.iter().enumerate() {
            let mut m = c.unsigned_abs();
            let mut scale = if c < 0 { -beta[k] } else { beta[k] };
            while m != 0 {
                if m & 1 == 1 {
                    terms[n] = scale;
                    n += 1;
                }
                scale *= 2.0;
                m >>= 1;
            }
        }
        n
    };
    let count: u32 = coef.iter().map(|c| c.unsigned_abs().count_ones()).sum();
    if count as usize <= STACK {
        let mut terms = [0.0; STACK];
        let n = fill(&mut terms);
        f(&terms[..n])
    } else {
        let mut terms = vec![0.0; count as usize];
        let n = fill(&mut terms);
        f(&terms[..n])
    }
}

/// The exact sign of `Σ coef_k β_k`.
pub(super) fn sign_of_form(coef: &[i32; 18], beta: &[f64; 18]) -> Ordering {
    with_form_terms(coef, beta, sum_sign)
}

/// `Σ coef_k β_k`, correctly rounded.
pub(super) fn eval_form(coef: &[i32; 18], beta: &[f64; 18]) -> f64 {
    with_form_terms(coef, beta, accurate_sum)
}

/// A nonnegative combination of three plane normals equal to another plane's normal:
/// `Σ_i halves_i n_(planes_i) = 2 n_j` with `halves ≥ 0` (a dual feasible basis of the linear
/// program "maximise n_j · x over the other 17 half-spaces"); its value `Σ halves_i β_i / 2` is
/// an upper bound of n_j · x over the tribox.
#[derive(PartialEq)]
pub(super) struct DualBasis {
    planes: [usize; 3],
    halves: [i32; 3],
}

impl DualBasis {
    /// The value, rounded (see [`support_without`] for its error).
    fn approx(&self, beta: &[f64; 18]) -> f64 {
        let [a, b, c] = self.planes;
        let [ha, hb, hc] = self.halves.map(f64::from);
        0.5 * (ha * beta[a] + hb * beta[b] + hc * beta[c])
    }

    /// The value as a dense form in half-units.
    pub(super) fn dense(&self) -> [i32; 18] {
        let mut coef = [0; 18];
        for (&p, &h) in self.planes.iter().zip(&self.halves) {
            coef[p] += h;
        }
        coef
    }
}

/// For each plane j, the distinct dual feasible bases made of three other planes with
/// independent normals (computed once; 36 to 40 per plane).
pub(super) fn dual_bases() -> &'static [Vec<DualBasis>; 18] {
    static TABLE: OnceLock<[Vec<DualBasis>; 18]> = OnceLock::new();
    TABLE.get_or_init(|| {
        std::array::from_fn(|j| {
            let d = normal(j).map(i32::from);
            let mut out: Vec<DualBasis> = Vec::new();
            for a in 0..18 {
                for b in a + 1..18 {
                    for c in b + 1..18 {
                        if a == j || b == j || c == j {
                            continue;
                        }
                        // Columns are the normals: solve M λ = d with M = rowsᵀ.
                        let rows = normal_rows([a, b, c]);
                        let m: [[i32; 3]; 3] =
                            std::array::from_fn(|r| std::array::from_fn(|k| rows[k][r]));
                        let det = det3(m);
                        if det == 0 {
                            continue;
                        }
                        let adj = adjugate(m);
                        // λ = adj · d / det; in half-units (|det| is 1 or 2 for these normals).
                        let halves: [i32; 3] = std::array::from_fn(|k| {
                            (0..3).map(|r| adj[k][r] * d[r]).sum::<i32>() * 2 / det
                        });
                        if halves.iter().any(|&l| l < 0) {
                            continue;
                        }
                        // Keep the planes with a positive coefficient, padded by a zero term.
                        let mut basis = DualBasis {
                            planes: [a, b, c],
                            halves,
                        };
                        for k in 0..3 {
                            if basis.halves[k] == 0 {
                                basis.planes[k] = j;
                            }
                        }
                        if !out.iter().any(|o| o.dense() == basis.dense()) {
                            out.push(basis);
                        }
                    }
                }
            }
            out
        })
    })
}

/// The exact maximum of n_j · x over the polytope of the 17 half-spaces other than j, as the
/// least value of a dual feasible basis (linear programming duality); `None` when there is
/// none (the maximum is unbounded; never for bounds of points).
///
/// The rounded values pick the least candidate; only candidates within the rounding error of
/// it are compared exactly.
pub(super) fn support_without(j: usize, beta: &[f64; 18]) -> Option<&'static DualBasis> {
    let candidates = &dual_bases()[j];
    let (mut best, least) = candidates
        .iter()
        .map(|c| c.approx(beta))
        .enumerate()
        .min_by(|a, b| a.1.total_cmp(&b.1))?;
    // Each value is half a sum of three rounded products of magnitude at most 4 m (halves
    // ≤ 4), so the kernel's bound of a sum of three terms over 6 m bounds its error; two
    // values within twice that of each other may be in either order.
    let m = beta.iter().fold(0.0f64, |m, b| m.max(b.abs()));
    let slack = 2.0 * (24.0 * f64::EPSILON * m + f64::MIN_POSITIVE);
    for (i, c) in candidates.iter().enumerate() {
        if i != best && c.approx(beta) <= least + slack {
            let (cd, bd) = (c.dense(), candidates[best].dense());
            let diff: [i32; 18] = std::array::from_fn(|k| cd[k] - bd[k]);
            if sign_of_form(&diff, beta) == Ordering::Less {
                best = i;
            }
        }
    }
    candidates.get(best)
}

/// The smallest double at least `Σ halves_i β_i / 2`.
pub(super) fn round_up_form(f: &DualBasis, beta: &[f64; 18]) -> f64 {
    let coef = f.dense();
    // Correctly rounded and halved: at most a step or two below the exact value.
    let mut r = eval_form(&coef, beta) * 0.5;
    while with_form_terms(&coef, beta, |terms| {
        let mut all = terms.to_vec();
        all.push(-2.0 * r);
        sum_sign(&all) == Ordering::Greater
    }) {
        r = r.next_up();
    }
    r
}
