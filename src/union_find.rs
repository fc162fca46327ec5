//! Disjoint sets of indices (union-find), the one used wherever the engine groups things
//! that turn out to be one: equal points and connected cells of visible polygons
//! (`surfaces::vtp`), pieces on one picture line (`hidden::overlaps`), pieces of an edge cut
//! at T-junctions (`hidden::edges`, `hidden::verify`).
//!
//! Written here rather than taken from a crate because which index ends up the root of a set
//! is part of what its callers decide (the piece a joined run keeps, the order of groups),
//! and the two rules they use ([`UnionFind::union`], [`UnionFind::union_least`]) are each a
//! line; finding halves paths.

/// Disjoint sets of the indices `0..n`, each named by its root.
#[derive(Clone, Debug)]
pub(crate) struct UnionFind(Vec<usize>);

impl UnionFind {
    /// `n` sets of one index each.
    pub(crate) fn new(n: usize) -> UnionFind {
        UnionFind((0..n).collect())
    }

    /// How many indices there are.
    pub(crate) fn len(&self) -> usize {
        self.0.len()
    }

    /// The root of `i`'s set (halving the path on the way).
    pub(crate) fn find(&mut self, mut i: usize) -> usize {
        while self.0[i] != i {
            self.0[i] = self.0[self.0[i]];
            i = self.0[i];
        }
        i
    }

    /// Joins the sets of `a` and `b`; the root of `a`'s set stays the root.
    pub(crate) fn union(&mut self, a: usize, b: usize) {
        let (a, b) = (self.find(a), self.find(b));
        self.0[b] = a;
    }

    /// Joins the sets of `a` and `b`; the lesser root stays the root, so that (when every
    /// join is made this way) each set's root is its least index.
    pub(crate) fn union_least(&mut self, a: usize, b: usize) {
        let (a, b) = (self.find(a), self.find(b));
        if a != b {
            self.0[a.max(b)] = a.min(b);
        }
    }
}

#[cfg(test)]
mod tests {
    use crate::random::SplitMix64;
    use crate::union_find::UnionFind;

    /// Against a brute-force labelling: after random joins (both rules), two indices have
    /// one root exactly when a chain of joins links them, and `union_least` roots are least.
    #[test]
    fn roots_agree_with_brute_force_labels() {
        let mut rng = SplitMix64(0x2545_f491_4f6c_dd1d);
        let mut next = |n: usize| rng.below(n);
        for round in 0..200 {
            let n = 1 + next(40);
            let mut sets = UnionFind::new(n);
            let mut label: Vec<usize> = (0..n).collect();
            for _ in 0..next(2 * n) {
                let (a, b) = (next(n), next(n));
                if round % 2 == 0 {
                    sets.union(a, b);
                } else {
                    sets.union_least(a, b);
                }
                let (la, lb) = (label[a], label[b]);
                for l in &mut label {
                    if *l == lb {
                        *l = la;
                    }
                }
            }
            assert_eq!(sets.len(), n);
            for i in 0..n {
                for j in 0..n {
                    assert_eq!(sets.find(i) == sets.find(j), label[i] == label[j]);
                }
                if round % 2 == 1 {
                    let least = (0..n).find(|&j| label[j] == label[i]).unwrap();
                    assert_eq!(sets.find(i), least);
                }
            }
        }
    }
}
