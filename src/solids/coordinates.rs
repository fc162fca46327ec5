//! Vertex coordinates of the Platonic and Archimedean solids: permutations and sign changes of
//! the standard coordinate triples (at whatever edge length they come; the hull scales them),
//! and the constants they need.

use crate::geometry::Point3;

/// Which permutations of a coordinate triple to take.
#[derive(Clone, Copy)]
pub(super) enum Perms {
    /// All 6.
    All,
    /// The 3 cyclic (even) ones.
    Even,
    /// The 3 odd ones.
    Odd,
}

/// Which sign changes of a coordinate triple to take (each `±` flips one entry).
#[derive(Clone, Copy)]
pub(super) enum Signs {
    /// All of them.
    All,
    /// Those flipping an even number of entries.
    EvenFlips,
    /// Those flipping an odd number of entries.
    OddFlips,
}

/// One family of vertices: the chosen permutations and sign changes of `base`.
pub(super) struct Family {
    pub base: [f64; 3],
    pub perms: Perms,
    pub signs: Signs,
}

impl Family {
    /// Every permutation and sign change of `base`.
    pub fn all(base: [f64; 3]) -> Family {
        Family {
            base,
            perms: Perms::All,
            signs: Signs::All,
        }
    }

    /// Even permutations with every sign change.
    pub fn even(base: [f64; 3]) -> Family {
        Family {
            base,
            perms: Perms::Even,
            signs: Signs::All,
        }
    }
}

/// The points of the families, without duplicates (a zero flipped, or a permutation of
/// equal entries, gives a point already there).
pub(super) fn expand(families: &[Family]) -> Vec<Point3> {
    // The even permutations, then the odd ones.
    const PERMS: [[usize; 3]; 6] = [
        [0, 1, 2],
        [1, 2, 0],
        [2, 0, 1],
        [0, 2, 1],
        [2, 1, 0],
        [1, 0, 2],
    ];
    let mut out: Vec<Point3> = Vec::new();
    for f in families {
        let perms = match f.perms {
            Perms::All => &PERMS[..],
            Perms::Even => &PERMS[..3],
            Perms::Odd => &PERMS[3..],
        };
        for flips in 0u32..8 {
            let keep = match f.signs {
                Signs::All => true,
                Signs::EvenFlips => flips.count_ones() % 2 == 0,
                Signs::OddFlips => flips.count_ones() % 2 == 1,
            };
            if !keep {
                continue;
            }
            let signed: [f64; 3] = std::array::from_fn(|k| {
                // Adding 0.0 turns -0.0 into 0.0 so that duplicates compare equal.
                (if flips & (1 << k) != 0 {
                    -f.base[k]
                } else {
                    f.base[k]
                }) + 0.0
            });
            for p in perms {
                let q = Point3::new(signed[p[0]], signed[p[1]], signed[p[2]]);
                if !out.contains(&q) {
                    out.push(q);
                }
            }
        }
    }
    out
}

/// The golden ratio φ = (1 + √5)/2.
pub(super) fn phi() -> f64 {
    (1.0 + 5f64.sqrt()) / 2.0
}

/// The tribonacci constant: the real root of t³ = t² + t + 1 (≈ 1.839286755), from Cardano's
/// formula, polished by a Newton step.
pub(super) fn tribonacci() -> f64 {
    let s = 3.0 * 33f64.sqrt();
    let t = (1.0 + (19.0 + s).cbrt() + (19.0 - s).cbrt()) / 3.0;
    newton(
        t,
        |t| t * t * t - t * t - t - 1.0,
        |t| 3.0 * t * t - 2.0 * t - 1.0,
    )
}

/// The snub dodecahedron's ξ: the real root of ξ³ − 2ξ = φ (≈ 1.7155615), from Cardano's
/// formula, polished by a Newton step.
pub(super) fn snub_xi() -> f64 {
    let phi = phi();
    let r = (phi - 5.0 / 27.0).sqrt() / 2.0;
    let x = (phi / 2.0 + r).cbrt() + (phi / 2.0 - r).cbrt();
    newton(x, |x| x * x * x - 2.0 * x - phi, |x| 3.0 * x * x - 2.0)
}

/// One Newton step for the root of `f` near `x`.
fn newton(x: f64, f: impl Fn(f64) -> f64, df: impl Fn(f64) -> f64) -> f64 {
    x - f(x) / df(x)
}
