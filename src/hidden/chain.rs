//! Chaining pieces into maximal polylines.

use super::marks::{self, Mark};
use super::pass::Pass;
use super::{Drawing, EdgeClass, Options, OverlapReport, Overlaps, Polyline, overlaps};
use foldhash::fast::FixedState;
use rayon::prelude::*;
use std::collections::HashMap;
use std::time::Instant;

/// A segment's two ends.
type Segment = [[f64; 2]; 2];

/// A visible or hidden piece of an edge, in picture coordinates.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Piece {
    /// The class of its edge.
    pub class: EdgeClass,
    /// Whether it is visible.
    pub visible: bool,
    /// Its ends.
    pub ends: [[f64; 2]; 2],
    /// The index of its line in the pass, and its range of the line's parameter `t` (where
    /// `X(t) = a + t·(b - a)`): what [`super::verify`] checks it by.
    pub line: usize,
    /// See `line`.
    pub t: [f64; 2],
    /// Whether a tile's plane passes through each end (see [`super::tiles`]).
    pub border: [bool; 2],
    /// What its ends are, exactly (see [`super::marks`]).
    pub marks: [Mark; 2],
}

/// Chains the pieces of each class and visibility into polylines, joining pieces at ends
/// shared by exactly two of them (ends are equal only when built from the same input, since
/// each point is computed once). Closed chains repeat their first point. Pieces of zero length
/// are left out.
pub(crate) fn chain(pieces: &[Piece]) -> Vec<Polyline> {
    let mut groups: Vec<(EdgeClass, bool, Vec<Segment>)> = Vec::new();
    for class in EdgeClass::ALL {
        for visible in [false, true] {
            let ends: Vec<Segment> = pieces
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
pub(super) fn chain_group(segments: &[Segment]) -> Vec<Vec<[f64; 2]>> {
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

/// Stage 5 of the pass: the drawing chained from the pieces, each stretch of line once when
/// the options ask for it. The pass keeps the stages' reports.
pub(super) fn chained(pass: &mut Pass, pieces: Vec<Piece>, options: &Options) -> Drawing {
    let clock = Instant::now();
    let (pieces, report) = finished(&*pass, pieces, options);
    match report {
        Some(r) => {
            let done = format!(
                "{} groups of {} segments on one line drawn once ({:.6} of line no longer drawn \
                 twice)",
                r.groups, r.segments, r.removed_length
            );
            pass.stage("overlaps", clock, done, None);
        }
        None => {
            let skipped = "each stretch drawn once (asked to keep overlapping pieces)";
            pass.stage("overlaps", clock, String::new(), Some(skipped.to_string()));
        }
    }
    let clock = Instant::now();
    let polylines = chain(&pieces);
    pass.stage(
        "chains",
        clock,
        format!("{} polylines from {} runs", polylines.len(), pieces.len()),
        (!options.hidden).then(|| "hidden pieces (not asked for)".to_string()),
    );
    Drawing {
        polylines,
        stages: pass.stages.clone(),
    }
}

/// The pieces a drawing chains: hidden ones dropped unless the options ask for them, each
/// stretch of a picture line once when they ask for that (with what was removed).
pub(super) fn finished<P: marks::Provenance>(
    provenance: &P,
    mut pieces: Vec<Piece>,
    options: &Options,
) -> (Vec<Piece>, Option<OverlapReport>) {
    if !options.hidden {
        pieces.retain(|p| p.visible);
    }
    match options.overlaps {
        Overlaps::Once => {
            let (pieces, report) = overlaps::drawn_once(provenance, pieces);
            (pieces, Some(report))
        }
        Overlaps::Keep => (pieces, None),
    }
}
