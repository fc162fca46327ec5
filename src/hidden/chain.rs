//! Chaining pieces into maximal polylines.

use super::piece::Piece;
use super::{EdgeClass, Polyline};
use foldhash::fast::FixedState;
use rayon::prelude::*;
use std::collections::HashMap;

/// A segment's two ends.
type Ends = [[f64; 2]; 2];

/// Chains the pieces of each class and visibility into polylines, joining pieces at ends
/// shared by exactly two of them (ends are equal only when built from the same input, since
/// each point is computed once). Closed chains repeat their first point. Pieces of zero length
/// are left out.
pub(crate) fn chain(pieces: &[Piece]) -> Vec<Polyline> {
    let mut groups: Vec<(EdgeClass, bool, Vec<Ends>)> = Vec::new();
    for class in EdgeClass::ALL {
        for visible in [false, true] {
            let ends: Vec<Ends> = pieces
                .iter()
                .filter(|p| p.class == class && p.visible == visible && p.ends[0] != p.ends[1])
                .map(|p| p.ends)
                .collect();
            if !ends.is_empty() {
                groups.push((class, visible, ends));
            }
        }
    }
    let chained: Vec<Vec<Polyline>> = groups
        .par_iter()
        .map(|(class, visible, segments)| {
            chain_group(segments)
                .into_iter()
                .map(|points| Polyline {
                    class: *class,
                    visible: *visible,
                    points,
                })
                .collect()
        })
        .collect();
    chained.into_iter().flatten().collect()
}

/// The bit pattern of a point, for hashing (`-0.0` and `0.0` made equal).
fn key(p: [f64; 2]) -> [u64; 2] {
    p.map(|x| (x + 0.0).to_bits())
}

/// Chains one group's segments.
pub(super) fn chain_group(segments: &[Ends]) -> Vec<Vec<[f64; 2]>> {
    // At each point, how many segment ends lie there and the first two segments: only a point
    // with exactly two is chained through.
    let mut at: HashMap<[u64; 2], (usize, [usize; 2]), FixedState> =
        HashMap::with_capacity_and_hasher(segments.len() * 2, FixedState::default());
    for (i, s) in segments.iter().enumerate() {
        for p in s {
            let (count, first) = at.entry(key(*p)).or_insert((0, [i, i]));
            if *count < 2 {
                first[*count] = i;
            }
            *count += 1;
        }
    }
    let mut used = vec![false; segments.len()];
    // The one other unused segment at point p, when exactly two segments end there.
    let next = |p: [f64; 2], from: usize, used: &[bool]| -> Option<usize> {
        match at.get(&key(p)) {
            Some(&(2, [x, y])) => {
                let other = if x == from { y } else { x };
                (other != from && !used[other]).then_some(other)
            }
            _ => None,
        }
    };
    let other_end = |s: usize, p: [f64; 2]| {
        let [a, b] = segments[s];
        if key(a) == key(p) { b } else { a }
    };
    let mut out = Vec::new();
    for start in 0..segments.len() {
        if used[start] {
            continue;
        }
        used[start] = true;
        let [a, b] = segments[start];
        // Forwards from b, then backwards from a.
        let mut forward = vec![a, b];
        let (mut s, mut p) = (start, b);
        while let Some(n) = next(p, s, &used) {
            used[n] = true;
            p = other_end(n, p);
            forward.push(p);
            s = n;
        }
        let mut backward = Vec::new();
        let (mut s, mut p) = (start, a);
        while let Some(n) = next(p, s, &used) {
            used[n] = true;
            p = other_end(n, p);
            backward.push(p);
            s = n;
        }
        if backward.is_empty() {
            out.push(forward);
        } else {
            backward.reverse();
            backward.extend(forward);
            out.push(backward);
        }
    }
    out
}
