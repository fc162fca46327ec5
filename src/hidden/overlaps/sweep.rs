//! Step 2 of overlap removal: the sweep along one group's picture line.
//!
//! The group's points are ordered by the turn of their lines of sight
//! ([`collinear::turn`](crate::sight::collinear::turn)) against the turn of the first
//! line's own two points, which gives the direction of the sweep. A certified filter decides
//! first: with `g` the first line's rounded picture direction, two points whose rounded
//! pictures differ along `g` by more than their rounding bounds are in that order.

use super::{Span, rank, rounding, unranked};
use crate::hidden::EdgeClass;
use crate::hidden::marks::{Mark, MarkKey, Provenance};
use crate::hidden::piece::Piece;
use crate::sight::collinear::turn;
use std::cmp::Ordering;

/// A piece's end in the sweep: the piece, its line and mark, the point's name and rounded
/// picture, and whether a piece of rank `rank` begins (`+1`) or ends (`−1`) there.
#[derive(Debug, Clone, Copy)]
struct Event {
    piece: usize,
    line: usize,
    mark: Mark,
    key: MarkKey,
    picture: [f64; 2],
    rank: usize,
    delta: i32,
}

/// The order of points along the group's picture line.
struct Order<'a, P> {
    provenance: &'a P,
    /// A point off the plane of sight, to turn about.
    off: crate::geometry::Point3,
    /// The turn of the first line's two points: the sweep's direction.
    forward: Ordering,
    /// The rounded direction of the picture line, when certified to within a small angle.
    direction: Option<[f64; 2]>,
}

impl<P: Provenance> Order<'_, P> {
    /// The exact order of `x` and `y` along the sweep.
    fn compare(&self, x: &Event, y: &Event) -> Ordering {
        if (x.line, x.mark) == (y.line, y.mark) {
            return Ordering::Equal;
        }
        if let Some(g) = self.direction {
            let slack = self.provenance.slack();
            let d = [y.picture[0] - x.picture[0], y.picture[1] - x.picture[1]];
            let along = g[0] * d[0] + g[1] * d[1];
            let bound = 2.0 * (rounding(x.picture, slack) + rounding(y.picture, slack))
                + 8.0 * f64::EPSILON * (d[0].abs() + d[1].abs());
            if along > bound {
                return Ordering::Less;
            }
            if along < -bound {
                return Ordering::Greater;
            }
        }
        let point = |e: &Event| self.provenance.point(e.line, e.mark);
        match turn(self.provenance.eye(), &self.off, &point(x), &point(y)) {
            Ordering::Equal => Ordering::Equal,
            t if t == self.forward => Ordering::Less,
            _ => Ordering::Greater,
        }
    }
}

/// A stretch of the group's picture line covered twice or more, drawn once: the pieces that
/// cover it (indices into the pieces) and what replaces them.
pub(super) struct Overlap {
    pub pieces: Vec<usize>,
    pub drawn: Vec<Piece>,
}

/// The group's stretches covered twice or more (each a maximal run of the line covered by
/// pieces without a gap), each drawn once, in the sweep's direction; the group's other
/// pieces are left as they are.
pub(super) fn sweep<P: Provenance>(
    provenance: &P,
    group: &[usize],
    spans: &[Span],
    pieces: &[Piece],
) -> Vec<Overlap> {
    let eye = provenance.eye();
    let first = &spans[group[0]];
    let support = provenance.support(first.line);
    let off = support.off_point(eye);
    let [p0, p1] = support.points();
    let forward = turn(eye, &off, &p0, &p1);
    if forward == Ordering::Equal {
        return Vec::new();
    }
    let order = Order {
        provenance,
        off,
        forward,
        direction: direction(
            pieces[first.pieces.start].ends[0],
            pieces[first.pieces.end - 1].ends[1],
            provenance.slack(),
        ),
    };
    let mut events = Vec::new();
    for &s in group {
        let span = &spans[s];
        let [q0, q1] = provenance.support(span.line).points();
        let along = s == group[0] || turn(eye, &off, &q0, &q1) == forward;
        let (lo, hi) = if along { (0, 1) } else { (1, 0) };
        for k in span.pieces.clone() {
            let p = &pieces[k];
            for (end, delta) in [(lo, 1), (hi, -1)] {
                events.push(Event {
                    piece: k,
                    line: span.line,
                    mark: p.marks[end],
                    key: provenance.key(span.line, p.marks[end]),
                    picture: p.ends[end],
                    rank: rank(p.class, p.visible),
                    delta,
                });
            }
        }
    }
    events.sort_by(|x, y| order.compare(x, y));
    overlaps(&events, &order)
        .into_iter()
        .map(|(covering, stretches)| Overlap {
            pieces: covering,
            drawn: stretches
                .into_iter()
                .map(|(rank, ends)| {
                    let (class, visible) = unranked(rank);
                    Piece {
                        class,
                        visible,
                        ends,
                        line: first.line,
                        t: [0.0, 0.0],
                        border: [false; 2],
                        marks: [Mark::First, Mark::Last],
                    }
                })
                .collect(),
        })
        .collect()
}

/// The rounded direction from `p` to `q` as a unit vector, when the line is long enough for
/// it to be within a small angle of the exact one.
fn direction(p: [f64; 2], q: [f64; 2], slack: f64) -> Option<[f64; 2]> {
    let error = 2.0 * (rounding(p, slack) + rounding(q, slack));
    let d = [q[0] - p[0], q[1] - p[1]];
    let length = d[0].hypot(d[1]);
    (length.is_finite() && length > 64.0 * error).then(|| [d[0] / length, d[1] / length])
}

/// A run's stretches: each rank with its ends.
type Stretches = Vec<(usize, [[f64; 2]; 2])>;

/// The runs of the line covered without a gap (in the sorted events) that are covered twice
/// somewhere, each with its pieces and its stretches between consecutive points, each
/// stretch given the highest rank covering it and consecutive ones of one rank joined. Where
/// several ends are one point, the one with the smallest key is drawn.
fn overlaps<P: Provenance>(events: &[Event], order: &Order<P>) -> Vec<(Vec<usize>, Stretches)> {
    let mut count = vec![0i32; 2 * EdgeClass::ALL.len()];
    let mut covering = 0i32;
    let mut out = Vec::new();
    // The current run: its pieces, whether it is covered twice, its stretches (each with
    // its rank, ends and the index of its last point).
    let mut pieces: Vec<usize> = Vec::new();
    let mut twice = false;
    let mut stretches: Vec<(usize, [[f64; 2]; 2], usize)> = Vec::new();
    let mut from: Option<[f64; 2]> = None;
    let (mut i, mut position) = (0, 0);
    while i < events.len() {
        let mut j = i + 1;
        while j < events.len() && order.compare(&events[i], &events[j]) == Ordering::Equal {
            j += 1;
        }
        let here = events[i..j]
            .iter()
            .min_by_key(|e| e.key)
            .map_or(events[i].picture, |e| e.picture);
        if let (Some(start), Some(top)) = (from, count.iter().rposition(|&c| c > 0)) {
            twice |= covering >= 2;
            match stretches.last_mut() {
                Some(last) if last.0 == top && last.2 + 1 == position => {
                    last.1[1] = here;
                    last.2 = position;
                }
                _ => stretches.push((top, [start, here], position)),
            }
        }
        for e in &events[i..j] {
            count[e.rank] += e.delta;
            covering += e.delta;
            if e.delta > 0 {
                pieces.push(e.piece);
            }
        }
        if covering == 0 {
            // A gap: the run ends here.
            let run = std::mem::take(&mut stretches);
            if std::mem::take(&mut twice) {
                let ends = run
                    .into_iter()
                    .map(|(rank, ends, _)| (rank, ends))
                    .collect();
                out.push((std::mem::take(&mut pieces), ends));
            }
            pieces.clear();
        }
        from = Some(here);
        position += 1;
        i = j;
    }
    out
}
