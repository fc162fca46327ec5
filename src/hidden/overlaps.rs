//! Lines drawn once: a drawing without two segments that overlap along a length.
//!
//! The pass draws every edge of every object, so where two objects touch along an edge
//! (stacked boxes, a part standing on a plate's rim), where a face's side meets another's at a
//! T-junction, or where a line lies right behind a contour in the picture (both in one plane
//! of sight), two segments of the drawing run along the same stretch of one line. A screen
//! shows them as one; a pen plotter draws the stretch twice, and a dashed hidden line drawn
//! under a visible one shows through its gaps. [`without_overlaps`] keeps each stretch once:
//!
//! - of the segments covering a stretch, the one drawn on top wins: visible over hidden, then
//!   the later class in [`EdgeClass::ALL`] (silhouette over boundary over intersection over
//!   crease over smooth), which is what the SVG shows there today;
//! - segments that touch at a point or cross are not overlaps and are left alone.
//!
//! Every decision is exact on the drawing's points (the doubles written to the file):
//! two segments overlap when both ends of one lie exactly on the other's line
//! ([`orient2d`](crate::geometry::predicates::orient2d)) and their ranges along a coordinate in
//! which the line is not constant overlap with positive length. The stretches are cut only at
//! the segments' own ends, so the result has no new point: every point of it is a point of the
//! drawing, as the pass constructed it. Segments on one line are found through Franklin's
//! uniform grid ([`SegmentGrid`]), as the pass finds crossings; those that overlap are grouped, and each group is swept once along
//! its line, keeping for each stretch between consecutive ends the winning class and
//! visibility. Pieces of one class and visibility are then chained again into maximal
//! polylines.
//!
//! ```
//! use kepler::hidden::{Drawing, EdgeClass, Polyline, without_overlaps};
//! let line = |class, visible, points: &[[f64; 2]]| Polyline { class, visible, points: points.to_vec() };
//! // Two boxes side by side: the right one's hidden edge runs under the left one's visible one.
//! let drawing = Drawing {
//!     polylines: vec![
//!         line(EdgeClass::Silhouette, false, &[[1.0, 0.0], [1.0, 2.0]]),
//!         line(EdgeClass::Crease, true, &[[1.0, 0.0], [1.0, 1.0]]),
//!     ],
//!     stages: Vec::new(),
//! };
//! let (clean, report) = without_overlaps(&drawing);
//! assert_eq!(report.groups, 1);
//! // The visible crease keeps [0, 1]; the hidden silhouette keeps only what it alone covers.
//! assert_eq!(clean.polylines, vec![
//!     line(EdgeClass::Silhouette, false, &[[1.0, 1.0], [1.0, 2.0]]),
//!     line(EdgeClass::Crease, true, &[[1.0, 0.0], [1.0, 1.0]]),
//! ]);
//! ```

use super::chain::chain_group;
use super::{Drawing, EdgeClass, Polyline};
use crate::geometry::predicates::orient2d;
use crate::grid::SegmentGrid;
use geo::{Line as GeoLine, coord};
use std::cmp::Ordering;

/// What [`without_overlaps`] found and removed.
///
/// ```
/// let r = kepler::hidden::OverlapReport::default();
/// assert_eq!((r.groups, r.segments, r.removed_length), (0, 0, 0.0));
/// ```
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct OverlapReport {
    /// Groups of segments that overlap along one line.
    pub groups: usize,
    /// Segments in those groups (each drawn, after the sweep, only where it wins).
    pub segments: usize,
    /// Length of line no longer drawn twice or more (view coordinates).
    pub removed_length: f64,
}

/// A segment of the drawing: its ends, and its rank (what is drawn on top wins).
#[derive(Debug, Clone, Copy)]
struct Segment {
    ends: [[f64; 2]; 2],
    rank: usize,
}

/// The drawing order of a class and visibility: hidden below visible, then
/// [`EdgeClass::ALL`]'s order.
fn rank(class: EdgeClass, visible: bool) -> usize {
    let position = EdgeClass::ALL.iter().position(|&c| c == class).unwrap_or(0);
    usize::from(visible) * EdgeClass::ALL.len() + position
}

/// The coordinate along which the line through `s` is not constant: `x` unless it is vertical.
fn axis(s: &[[f64; 2]; 2]) -> usize {
    usize::from(s[0][0] == s[1][0])
}

/// Whether segments `s` and `t` (each of positive length) lie on one line and share a stretch
/// of positive length: exact.
pub(crate) fn overlap(s: &[[f64; 2]; 2], t: &[[f64; 2]; 2]) -> bool {
    if orient2d(s[0], s[1], t[0]) != Ordering::Equal
        || orient2d(s[0], s[1], t[1]) != Ordering::Equal
    {
        return false;
    }
    let k = axis(s);
    let (lo_s, hi_s) = (s[0][k].min(s[1][k]), s[0][k].max(s[1][k]));
    let (lo_t, hi_t) = (t[0][k].min(t[1][k]), t[0][k].max(t[1][k]));
    lo_s.max(lo_t) < hi_s.min(hi_t)
}

/// The drawing with each stretch of line drawn once (see the module documentation), and what
/// was removed. A drawing without overlaps comes back unchanged, polyline for polyline.
pub fn without_overlaps(drawing: &Drawing) -> (Drawing, OverlapReport) {
    let segments: Vec<Segment> = drawing
        .segments()
        .filter(|(_, _, ends)| ends[0] != ends[1])
        .map(|(class, visible, ends)| Segment {
            ends,
            rank: rank(class, visible),
        })
        .collect();
    let groups = overlapping_groups(&segments);
    let mut report = OverlapReport::default();
    if groups.is_empty() {
        return (drawing.clone(), report);
    }
    let mut in_group = vec![false; segments.len()];
    let mut kept: Vec<Segment> = Vec::new();
    for group in &groups {
        report.groups += 1;
        report.segments += group.len();
        for &i in group {
            in_group[i] = true;
        }
        let swept = sweep(&segments, group);
        let length = |s: &[Segment]| s.iter().map(|s| distance(s.ends)).sum::<f64>();
        report.removed_length += group
            .iter()
            .map(|&i| distance(segments[i].ends))
            .sum::<f64>()
            - length(&swept);
        kept.extend(swept);
    }
    kept.extend(
        segments
            .iter()
            .zip(&in_group)
            .filter(|(_, g)| !**g)
            .map(|(s, _)| *s),
    );
    // The classes and visibilities that lost or gained a segment are chained again; the
    // others keep their polylines as they were.
    let mut changed = vec![false; 2 * EdgeClass::ALL.len()];
    for group in &groups {
        for &i in group {
            changed[segments[i].rank] = true;
        }
    }
    let mut polylines = Vec::with_capacity(drawing.polylines.len());
    let mut done = vec![false; changed.len()];
    for p in &drawing.polylines {
        let r = rank(p.class, p.visible);
        if !changed[r] {
            polylines.push(p.clone());
        } else if !done[r] {
            done[r] = true;
            let ends: Vec<[[f64; 2]; 2]> = kept
                .iter()
                .filter(|s| s.rank == r)
                .map(|s| s.ends)
                .collect();
            polylines.extend(chain_group(&ends).into_iter().map(|points| Polyline {
                class: p.class,
                visible: p.visible,
                points,
            }));
        }
    }
    let clean = Drawing {
        polylines,
        stages: drawing.stages.clone(),
    };
    (clean, report)
}

/// The length of a segment.
fn distance(s: [[f64; 2]; 2]) -> f64 {
    (s[1][0] - s[0][0]).hypot(s[1][1] - s[0][1])
}

/// The groups (indices, increasing; groups by their first index) of segments joined by
/// overlaps: each group lies on one line.
fn overlapping_groups(segments: &[Segment]) -> Vec<Vec<usize>> {
    let lines: Vec<GeoLine<f64>> = segments
        .iter()
        .map(|s| {
            GeoLine::new(
                coord! { x: s.ends[0][0], y: s.ends[0][1] },
                coord! { x: s.ends[1][0], y: s.ends[1][1] },
            )
        })
        .collect();
    let pairs =
        SegmentGrid::new(&lines).candidates(|i, j| overlap(&segments[i].ends, &segments[j].ends));
    let mut parent: Vec<usize> = (0..segments.len()).collect();
    fn root(parent: &mut [usize], mut i: usize) -> usize {
        while parent[i] != i {
            parent[i] = parent[parent[i]];
            i = parent[i];
        }
        i
    }
    let any = !pairs.is_empty();
    for (i, j) in pairs {
        let (a, b) = (root(&mut parent, i), root(&mut parent, j));
        if a != b {
            parent[a.max(b)] = a.min(b);
        }
    }
    if !any {
        return Vec::new();
    }
    let mut members: Vec<Vec<usize>> = vec![Vec::new(); segments.len()];
    for i in 0..segments.len() {
        let r = root(&mut parent, i);
        members[r].push(i);
    }
    members.into_iter().filter(|m| m.len() > 1).collect()
}

/// The pieces of one group (segments on one line) that win their stretch: cut at the
/// segments' ends, each stretch given the highest rank of the segments covering it, and
/// consecutive stretches of one rank joined.
fn sweep(segments: &[Segment], group: &[usize]) -> Vec<Segment> {
    let k = axis(&segments[group[0]].ends);
    // Events along the line: (coordinate, point, rank, +1 at the start, -1 at the end). On
    // one line that is not constant in coordinate k, points with one coordinate k are equal.
    let mut events: Vec<(f64, [f64; 2], usize, i32)> = Vec::with_capacity(2 * group.len());
    for &i in group {
        let s = &segments[i];
        let [a, b] = if s.ends[0][k] < s.ends[1][k] {
            s.ends
        } else {
            [s.ends[1], s.ends[0]]
        };
        events.push((a[k], a, s.rank, 1));
        events.push((b[k], b, s.rank, -1));
    }
    events.sort_by(|x, y| x.0.total_cmp(&y.0));
    let mut count = vec![0i32; 2 * EdgeClass::ALL.len()];
    let mut out: Vec<Segment> = Vec::new();
    let mut from: Option<[f64; 2]> = None;
    let mut i = 0;
    while i < events.len() {
        let (coordinate, point) = (events[i].0, events[i].1);
        // The stretch from the last point to this one goes to the rank on top over it.
        if let (Some(start), Some(top)) = (from, count.iter().rposition(|&c| c > 0)) {
            match out.last_mut() {
                Some(last) if last.rank == top && last.ends[1] == start => last.ends[1] = point,
                _ => out.push(Segment {
                    ends: [start, point],
                    rank: top,
                }),
            }
        }
        while i < events.len() && events[i].0 == coordinate {
            count[events[i].2] += events[i].3;
            i += 1;
        }
        from = Some(point);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn drawing(lines: &[(EdgeClass, bool, &[[f64; 2]])]) -> Drawing {
        Drawing {
            polylines: lines
                .iter()
                .map(|(class, visible, points)| Polyline {
                    class: *class,
                    visible: *visible,
                    points: points.to_vec(),
                })
                .collect(),
            stages: Vec::new(),
        }
    }

    /// Whether every stretch of `s` is covered by one of `pieces` of rank `at_least` or more
    /// that overlaps it (comparing coordinates along the line: exact).
    fn covered(
        pieces: &[(EdgeClass, bool, [[f64; 2]; 2])],
        s: &[[f64; 2]; 2],
        at_least: usize,
    ) -> bool {
        let k = axis(s);
        let (lo, hi) = (s[0][k].min(s[1][k]), s[0][k].max(s[1][k]));
        let on: Vec<(f64, f64)> = pieces
            .iter()
            .filter(|(c, v, e)| rank(*c, *v) >= at_least && overlap(s, e))
            .map(|(_, _, e)| (e[0][k].min(e[1][k]), e[0][k].max(e[1][k])))
            .collect();
        let mut cuts: Vec<f64> = on
            .iter()
            .flat_map(|&(a, b)| [a, b])
            .chain([lo, hi])
            .collect();
        cuts.retain(|&c| lo <= c && c <= hi);
        cuts.sort_by(f64::total_cmp);
        cuts.dedup();
        cuts.windows(2)
            .all(|w| on.iter().any(|&(a, b)| a <= w[0] && w[1] <= b))
    }

    /// Checks `clean` against `original`: no two of its segments overlap (every pair,
    /// exactly); every segment of it lies on segments of the original of its class and
    /// visibility; every segment of the original is covered by segments of its rank or above.
    fn check(original: &Drawing, clean: &Drawing) {
        let after: Vec<_> = clean.segments().collect();
        for (i, a) in after.iter().enumerate() {
            for b in &after[i + 1..] {
                assert!(!overlap(&a.2, &b.2), "{a:?} and {b:?} overlap");
            }
        }
        let before: Vec<_> = original.segments().collect();
        for a in &after {
            let same: Vec<_> = before
                .iter()
                .filter(|b| (b.0, b.1) == (a.0, a.1))
                .copied()
                .collect();
            assert!(
                covered(&same, &a.2, 0),
                "{a:?} is not on segments of the drawing"
            );
        }
        for b in &before {
            if b.2[0] != b.2[1] {
                assert!(
                    covered(&after, &b.2, rank(b.0, b.1)),
                    "{b:?} lost a stretch"
                );
            }
        }
    }

    #[test]
    fn a_drawing_without_overlaps_is_unchanged() {
        let d = drawing(&[
            (
                EdgeClass::Silhouette,
                true,
                &[[0.0, 0.0], [1.0, 0.0], [1.0, 1.0]],
            ),
            (EdgeClass::Crease, true, &[[0.0, 0.0], [1.0, 1.0]]),
            (EdgeClass::Crease, false, &[[2.0, 0.0], [0.0, 2.0]]),
            (EdgeClass::Smooth, true, &[[1.0, 0.0], [3.0, 0.0]]),
        ]);
        let (clean, report) = without_overlaps(&d);
        assert_eq!(clean, d);
        assert_eq!(report, OverlapReport::default());
    }

    #[test]
    fn coextensive_and_partial_overlaps_are_drawn_once() {
        // The same edge twice (two touching boxes), a T-junction, and a diagonal line
        // partly under a visible one and partly alone.
        let d = drawing(&[
            (EdgeClass::Silhouette, true, &[[0.0, 0.0], [4.0, 0.0]]),
            (EdgeClass::Silhouette, true, &[[4.0, 0.0], [0.0, 0.0]]),
            (
                EdgeClass::Crease,
                true,
                &[[1.0, 0.0], [2.0, 0.0], [2.0, 5.0]],
            ),
            (EdgeClass::Boundary, false, &[[0.125, 0.375], [0.75, 2.25]]),
            (EdgeClass::Smooth, true, &[[0.375, 1.125], [1.0, 3.0]]),
        ]);
        let (clean, report) = without_overlaps(&d);
        check(&d, &clean);
        assert_eq!((report.groups, report.segments), (2, 5));
        // What is left: the silhouette once, the crease's vertical part, the diagonal in two.
        assert_eq!(clean.polylines.len(), 4);
        let length = |c, v| clean.length(c, v);
        assert_eq!(length(EdgeClass::Silhouette, true), 4.0);
        assert_eq!(length(EdgeClass::Crease, true), 5.0);
        assert_eq!(length(EdgeClass::Boundary, false), 0.25f64.hypot(0.75));
        assert_eq!(length(EdgeClass::Smooth, true), 0.625f64.hypot(1.875));
    }

    /// Random drawings on a small lattice, many segments on few lines (and some off the
    /// lattice on slanted lines), at scales from 2^-1000 to 2^1000 and 1e8 from the origin:
    /// checked pair by pair.
    #[test]
    fn random_lattice_drawings_are_drawn_once() {
        let mut state = 0x2545_f491_4f6c_dd1du64;
        let mut below = |n: u64| {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            state % n
        };
        let mut overlapping = 0;
        for round in 0..300 {
            let (scale, offset) = match round % 4 {
                0 => (1.0, 0.0),
                1 => (2f64.powi(-1000), 0.0),
                2 => (2f64.powi(1000), 0.0),
                _ => (1.0, 1e8),
            };
            let lines: Vec<(EdgeClass, bool, Vec<[f64; 2]>)> = (0..2 + below(12))
                .map(|_| {
                    let class = EdgeClass::ALL[below(5) as usize];
                    let visible = below(2) == 0;
                    let n = 2 + below(3) as usize;
                    // A vertex on a 5 × 5 lattice, then steps along one of four directions.
                    let (dx, dy) =
                        [(1.0, 0.0), (0.0, 1.0), (1.0, 1.0), (1.0, -1.0)][below(4) as usize];
                    let mut p = [below(5) as f64, below(5) as f64];
                    let points = (0..n)
                        .map(|_| {
                            let q = [p[0] * scale + offset, p[1] * scale + offset];
                            let step = 1.0 + below(2) as f64;
                            p = [p[0] + step * dx, p[1] + step * dy];
                            q
                        })
                        .collect();
                    (class, visible, points)
                })
                .collect();
            let d = drawing(
                &lines
                    .iter()
                    .map(|(c, v, p)| (*c, *v, p.as_slice()))
                    .collect::<Vec<_>>(),
            );
            let (clean, report) = without_overlaps(&d);
            check(&d, &clean);
            overlapping += report.groups;
            if report.groups == 0 {
                assert_eq!(clean, d);
            }
        }
        assert!(overlapping > 100, "only {overlapping} groups of overlaps");
    }
}
