//! Step 1 of overlap removal: the lines whose pictures lie on one line, grouped exactly.
//!
//! A filter finds candidates, an exact predicate decides. Each line's picture is known
//! roughly from the rounded ends of its pieces (the first piece's start and the last one's
//! end, each within [`rounding`] of an exact point of the line's picture): its angle
//! `θ ∈ [0, π)` and offset `ρ` (the signed distance of the line from the picture's origin)
//! with bounds on their errors. Two lines with one picture line have intervals that overlap
//! in both, so the lines are sorted by angle and cut into runs of overlapping intervals,
//! each run sorted by offset and cut again, and again by the lines' extents along the run's
//! direction (lines on one picture line that do not reach each other, floors of a tower or
//! buildings along a street, share no stretch: they need not be grouped). Within a run
//! (the runs in parallel), each line is compared exactly ([`Support::same_picture`]) with
//! the first line of each class found so far. A line near `θ = 0`
//! or `π` enters twice, once on each side (its offset negated). A line too short for useful
//! bounds is compared exactly with every line that has a piece passing near it (an R-tree of
//! the pieces' boxes, built only when there is such a line).

use super::{Span, rounding};
use crate::hidden::marks::Provenance;
use crate::hidden::piece::Piece;
use crate::sight::collinear::Support;
use crate::union_find::UnionFind;
use rayon::prelude::*;
use rstar::primitives::{GeomWithData, Rectangle};
use rstar::{AABB, RTree};
use std::collections::HashMap;
use std::f64::consts::PI;

/// A line's picture, roughly: its angle and offset, each with a bound on its error.
#[derive(Debug, Clone, Copy)]
struct Entry {
    span: u32,
    theta: f64,
    theta_error: f64,
    rho: f64,
    rho_error: f64,
}

/// The groups (span indices, increasing; groups by their first) of two or more lines whose
/// pictures lie on one line and may share a stretch.
pub(super) fn groups<P: Provenance>(
    provenance: &P,
    spans: &[Span],
    pieces: &[Piece],
) -> Vec<Vec<usize>> {
    let slack = provenance.slack();
    let mut entries = Vec::with_capacity(spans.len());
    let mut short = Vec::new();
    for (s, span) in spans.iter().enumerate() {
        let p = pieces[span.pieces.start].ends[0];
        let q = pieces[span.pieces.end - 1].ends[1];
        match entry(s, p, q, slack) {
            Some(e) => {
                entries.push(e);
                // Near θ = 0 or π the line enters again on the other side, its normal reversed.
                if e.theta - e.theta_error < 0.0 {
                    entries.push(Entry {
                        theta: e.theta + PI,
                        rho: -e.rho,
                        ..e
                    });
                }
                if e.theta + e.theta_error >= PI {
                    entries.push(Entry {
                        theta: e.theta - PI,
                        rho: -e.rho,
                        ..e
                    });
                }
            }
            None => short.push(s),
        }
    }
    let candidates: Vec<Vec<Entry>> = runs(entries, |e| (e.theta, e.theta_error))
        .into_iter()
        .flat_map(|run| runs(run, |e| (e.rho, e.rho_error)))
        .flat_map(|run| along(run, spans, pieces, slack))
        .collect();
    let found: Vec<Vec<Vec<usize>>> = candidates
        .par_iter()
        .map(|run| classes(provenance, spans, run))
        .collect();
    let mut exact = Grouping::new(provenance, spans);
    for class in found.iter().flatten() {
        for &s in &class[1..] {
            exact.join(class[0], s);
        }
    }
    if !short.is_empty() {
        exact.short(&short, pieces);
    }
    exact.groups()
}

/// A run of lines with one picture line, roughly, cut into runs whose extents along it
/// overlap: lines whose pieces share a stretch are in one. Along a direction within a small
/// angle of the exact picture line, projections keep the order of its points, and each end's
/// projection is within its rounding bound of the exact end's.
fn along(run: Vec<Entry>, spans: &[Span], pieces: &[Piece], slack: f64) -> Vec<Vec<Entry>> {
    let (sin, cos) = run[0].theta.sin_cos();
    runs(run, move |e| {
        let span = &spans[e.span as usize];
        let ends = [
            pieces[span.pieces.start].ends[0],
            pieces[span.pieces.end - 1].ends[1],
        ];
        let [lo, hi] = {
            let [a, b] = ends.map(|p| cos * p[0] + sin * p[1]);
            [a.min(b), a.max(b)]
        };
        let margin = rounding(ends[0], slack) + rounding(ends[1], slack);
        let rounding = 4.0 * f64::EPSILON * (lo.abs() + hi.abs());
        ((lo + hi) / 2.0, (hi - lo) / 2.0 + margin + rounding)
    })
}

/// The lines of one run of candidates grouped exactly: each compared with the first line of
/// each class found so far; classes of two or more (span indices, the first first).
fn classes<P: Provenance>(provenance: &P, spans: &[Span], run: &[Entry]) -> Vec<Vec<usize>> {
    let eye = provenance.eye();
    let mut classes: Vec<(Support, Vec<usize>)> = Vec::new();
    for e in run {
        let span = e.span as usize;
        let support = provenance.support(spans[span].line);
        if !support.is_pictured(eye) {
            continue;
        }
        match classes
            .iter_mut()
            .find(|(first, _)| first.same_picture(&support, eye))
        {
            Some((_, members)) => members.push(span),
            None => classes.push((support, vec![span])),
        }
    }
    classes
        .into_iter()
        .filter(|(_, m)| m.len() > 1)
        .map(|(_, m)| m)
        .collect()
}

/// The entry of a line whose pieces run from `p` to `q`, or `None` when its picture is too
/// short (or too far out) for the bounds.
fn entry(span: usize, p: [f64; 2], q: [f64; 2], slack: f64) -> Option<Entry> {
    let error = 2.0 * (rounding(p, slack) + rounding(q, slack));
    let (dx, dy) = (q[0] - p[0], q[1] - p[1]);
    let length = dx.hypot(dy);
    if !(length.is_finite() && length > 16.0 * error) {
        return None;
    }
    let mut theta = dy.atan2(dx);
    if theta < 0.0 {
        theta += PI;
    }
    if theta >= PI {
        theta -= PI;
    }
    // Each end moved by at most `error / 2` turns the line by at most `error / length`
    // (doubled for the roundings of the angle).
    let theta_error = 2.0 * error / length + 16.0 * f64::EPSILON;
    let middle = [p[0] / 2.0 + q[0] / 2.0, p[1] / 2.0 + q[1] / 2.0];
    let (sin, cos) = theta.sin_cos();
    let rho = cos * middle[1] - sin * middle[0];
    let far = middle[0].abs().max(middle[1].abs()) * 2f64.sqrt();
    let rho_error = 2.0 * (far * theta_error + error) + 16.0 * f64::EPSILON * far;
    Some(Entry {
        span: span as u32,
        theta,
        theta_error,
        rho,
        rho_error,
    })
}

/// The entries cut into maximal runs of two or more whose intervals `(value ± error)` chain
/// into one (an entry whose interval meets no other's is left out).
fn runs(
    mut entries: Vec<Entry>,
    interval: impl Fn(&Entry) -> (f64, f64) + Sync,
) -> Vec<Vec<Entry>> {
    let low = |e: &Entry| {
        let (v, r) = interval(e);
        v - r
    };
    entries.par_sort_unstable_by(|x, y| low(x).total_cmp(&low(y)).then(x.span.cmp(&y.span)));
    let mut out: Vec<Vec<Entry>> = Vec::new();
    let mut run: Vec<Entry> = Vec::new();
    let mut high = f64::NEG_INFINITY;
    for e in entries {
        let (v, r) = interval(&e);
        if v - r > high {
            if run.len() > 1 {
                out.push(std::mem::take(&mut run));
            }
            run.clear();
            high = f64::NEG_INFINITY;
        }
        high = high.max(v + r);
        run.push(e);
    }
    if run.len() > 1 {
        out.push(run);
    }
    out
}

/// Lines grouped exactly: a union-find over the spans.
struct Grouping<'a, P> {
    provenance: &'a P,
    spans: &'a [Span],
    sets: UnionFind,
    /// The supports of the spans compared so far, and whether their pictures are lines (few
    /// spans are: a map, not a slot for each).
    supports: HashMap<usize, (Support, bool)>,
}

impl<'a, P: Provenance> Grouping<'a, P> {
    fn new(provenance: &'a P, spans: &'a [Span]) -> Self {
        Grouping {
            provenance,
            spans,
            sets: UnionFind::new(spans.len()),
            supports: HashMap::new(),
        }
    }

    /// Span `s`'s support when its picture is a line.
    fn support(&mut self, s: usize) -> Option<Support> {
        let (provenance, span) = (self.provenance, &self.spans[s]);
        let (support, pictured) = *self.supports.entry(s).or_insert_with(|| {
            let support = provenance.support(span.line);
            (support, support.is_pictured(provenance.eye()))
        });
        pictured.then_some(support)
    }

    /// Whether spans `s` and `t` lie on one picture line (exactly); joins them if so.
    fn join_if_same(&mut self, s: usize, t: usize) -> bool {
        if self.sets.find(s) == self.sets.find(t) {
            return true;
        }
        let (Some(x), Some(y)) = (self.support(s), self.support(t)) else {
            return false;
        };
        if !x.same_picture(&y, self.provenance.eye()) {
            return false;
        }
        self.sets.union_least(s, t);
        true
    }

    /// Joins the groups of spans `s` and `t`.
    fn join(&mut self, s: usize, t: usize) {
        self.sets.union_least(s, t);
    }

    /// Compares each short line with the lines that have a piece whose box, grown by the
    /// rounding, meets the short line's.
    fn short(&mut self, short: &[usize], pieces: &[Piece]) {
        let slack = self.provenance.slack();
        let boxed = |s: &Span| {
            let mut lo = [f64::INFINITY; 2];
            let mut hi = [f64::NEG_INFINITY; 2];
            for p in &pieces[s.pieces.clone()] {
                for e in p.ends {
                    let r = 2.0 * rounding(e, slack);
                    for k in 0..2 {
                        lo[k] = lo[k].min(e[k] - r);
                        hi[k] = hi[k].max(e[k] + r);
                    }
                }
            }
            (lo, hi)
        };
        let boxes: Vec<GeomWithData<Rectangle<[f64; 2]>, usize>> = self
            .spans
            .iter()
            .enumerate()
            .filter_map(|(s, span)| {
                let (lo, hi) = boxed(span);
                let finite = lo.iter().chain(&hi).all(|x| x.is_finite());
                finite.then(|| GeomWithData::new(Rectangle::from_corners(lo, hi), s))
            })
            .collect();
        let tree = RTree::bulk_load(boxes);
        for &s in short {
            let (lo, hi) = boxed(&self.spans[s]);
            if !lo.iter().chain(&hi).all(|x| x.is_finite()) {
                continue;
            }
            let mut near: Vec<usize> = tree
                .locate_in_envelope_intersecting(&AABB::from_corners(lo, hi))
                .map(|g| g.data)
                .filter(|&t| t != s)
                .collect();
            near.sort_unstable();
            for t in near {
                self.join_if_same(s, t);
            }
        }
    }

    /// The groups of two or more spans.
    fn groups(mut self) -> Vec<Vec<usize>> {
        let n = self.sets.len();
        let mut members: Vec<Vec<usize>> = vec![Vec::new(); n];
        for s in 0..n {
            let r = self.sets.find(s);
            members[r].push(s);
        }
        let mut out: Vec<Vec<usize>> = members.into_iter().filter(|m| m.len() > 1).collect();
        out.sort_unstable_by_key(|m| m[0]);
        out
    }
}
