//! Stage 3 of the pass: the cuts where a line's picture crosses the picture of a contour in
//! front of it (found from Franklin's uniform grid, decided by `crossing.rs`), and the cuts
//! where a line leaves the frustum of a view that clips or the window of a tile.

use super::crossing::{crossing, crossing_line};
use super::line::{Cut, Line, MeetLine, rough_parameter};
use super::pass::Pass;
use crate::geometry::Point3;
use crate::grid::SegmentGrid;
use crate::sight::frustum::{Clip, Framed, FramedLine, TilePlanes};
use crate::views::Eye;
use geo::{Line as GeoLine, coord};
use rayon::prelude::*;
use std::cmp::Ordering;
use std::time::Instant;

/// Below this many lines, crossings are found by testing every pair: no grid.
pub(super) const FEW_LINES: usize = 64;

/// The lines stage 3 puts in the grid, when the view clips by the part of each picture
/// inside the window.
struct Gridded {
    /// The lines in the grid, by their index in the pass.
    lines: Vec<usize>,
    /// Their pictures (the parts inside the window).
    segments: Vec<GeoLine<f64>>,
    /// The lines whose picture inside the window cannot be bounded, in increasing order.
    untamed: Vec<usize>,
    /// Whether each line of the pass is gridded or untamed.
    relevant: Vec<bool>,
}

impl Pass<'_> {
    /// Stage 3: the cuts where a line's picture crosses the picture of a contour in front of
    /// it, from the uniform grid over the lines' pictures (or every pair, for few lines).
    pub(super) fn contour_cuts(&mut self) {
        let clock = Instant::now();
        let n = self.lines.len();
        let (found, method) = if n < FEW_LINES {
            let all: Vec<(usize, Cut)> = (0..n)
                .flat_map(|i| (i + 1..n).map(move |j| (i, j)))
                .filter(|&(i, j)| self.cuts_needed(i, j))
                .flat_map(|(i, j)| self.crossing_cuts(i, j))
                .collect();
            let method =
                format!("every pair of {n} lines tested (fewer than {FEW_LINES}: no grid)");
            (all, method)
        } else {
            self.grid_cuts()
        };
        let done = format!(
            "{} cuts where a picture crosses a contour's; {method}",
            found.len()
        );
        self.cuts.extend(found);
        self.stage("cuts", clock, done, None);
    }

    /// The triangles on the sides of edge `j` (none for an intersection line).
    fn sides(&self, j: usize) -> Vec<[Point3; 3]> {
        let leaves = &self.leaves;
        let leaf = leaves.get(leaves.partition_point(|leaf| leaf.lines.end <= j));
        match (self.lines[j].triangles, leaf) {
            (Some(ts), Some(leaf)) => ts.map(|t| leaf.mesh.triangle(t as usize)).to_vec(),
            _ => Vec::new(),
        }
    }

    /// Whether lines `i` and `j` may cut each other: one is a contour and the other is not
    /// hidden by its own solid.
    fn cuts_needed(&self, i: usize, j: usize) -> bool {
        let lines = &self.lines;
        (lines[j].is_contour() && !lines[i].back) || (lines[i].is_contour() && !lines[j].back)
    }

    /// The cuts that lines `i` and `j` make on each other (see [`crossing`] and
    /// [`crossing_line`]).
    fn crossing_cuts(&self, i: usize, j: usize) -> Vec<(usize, Cut)> {
        let (lines, meets, eye, clip) = (&self.lines, &self.meets, &self.eye, self.clip);
        let mut out = Vec::new();
        for (x, y) in [(i, j), (j, i)] {
            let found = || match lines[x].meet {
                Some(m) => crossing_line(eye, &meets[m], &lines[x], &lines[y]),
                None => crossing(eye, clip, &lines[x], &lines[y], || self.sides(y)),
            };
            if lines[y].is_contour()
                && !lines[x].back
                && let Some(c) = found()
            {
                out.extend(c.into_iter().map(|c| (x, c)));
            }
        }
        out
    }

    /// The lines put in the grid. Lines hidden by their own solid are neither cut nor
    /// contours: not in the grid. When the view clips, each line is gridded by the part of its
    /// picture inside the window (none: left out), or, where that cannot be bounded, tested
    /// against every other line.
    fn gridded(&self) -> Gridded {
        let lines = &self.lines;
        let (mut gridded, mut segments, mut untamed) = (Vec::new(), Vec::new(), Vec::new());
        let mut relevant = vec![false; lines.len()];
        for (i, l) in lines.iter().enumerate().filter(|(_, l)| !l.back) {
            let framed = match self.clip {
                Some(n) if l.clipped => self.framed(&n, l),
                _ => Framed::Inside(l.ends),
            };
            match framed {
                Framed::Inside([a, b]) => {
                    gridded.push(i);
                    segments.push(GeoLine::new(
                        coord! { x: a[0], y: a[1] },
                        coord! { x: b[0], y: b[1] },
                    ));
                }
                Framed::Unbounded => untamed.push(i),
                Framed::Outside => continue,
            }
            relevant[i] = true;
        }
        Gridded {
            lines: gridded,
            segments,
            untamed,
            relevant,
        }
    }

    /// The cuts of stage 3 from the uniform grid over the lines' pictures (and the pairs of
    /// an untamed line with every other), with how they were found.
    fn grid_cuts(&self) -> (Vec<(usize, Cut)>, String) {
        let lines = &self.lines;
        let Gridded {
            lines: gridded,
            segments,
            untamed,
            relevant,
        } = self.gridded();
        let grid = SegmentGrid::new(&segments);
        // Only pairs with a contour can cut (see `cuts_needed`): the grid enumerates those alone.
        let candidates = grid.candidates(
            |i| lines[gridded[i]].is_contour(),
            |i, j| self.cuts_needed(gridded[i], gridded[j]),
        );
        let is_untamed = |j: usize| untamed.binary_search(&j).is_ok();
        let (relevant, is_untamed) = (&relevant, &is_untamed);
        let with_untamed: Vec<(usize, usize)> = untamed
            .iter()
            .flat_map(|&w| {
                (0..lines.len())
                    .filter(move |&j| j != w && relevant[j] && !(is_untamed(j) && j < w))
                    .map(move |j| (w, j))
            })
            .filter(|&(i, j)| self.cuts_needed(i, j))
            .collect();
        let all: Vec<(usize, Cut)> = candidates
            .par_iter()
            .map(|&(i, j)| (gridded[i], gridded[j]))
            .chain(with_untamed.par_iter().copied())
            .flat_map_iter(|(i, j)| self.crossing_cuts(i, j))
            .collect();
        let [nx, ny] = grid.shape();
        let own = lines.iter().filter(|l| l.back).count();
        let outside = lines.len() - own - gridded.len() - untamed.len();
        let framing = match self.clip {
            Some(_) => format!(
                "; pictures clipped to the window: {outside} lines outside it left out, {} \
                 too far out to clip tested against every line",
                untamed.len()
            ),
            None => String::new(),
        };
        let method = format!(
            "uniform grid {nx}×{ny} over {} lines ({:.2} cells per line; {own} lines hidden \
             by their own solid left out{framing}), {} candidate pairs",
            gridded.len(),
            grid.cells_per_segment(),
            candidates.len() + with_untamed.len()
        );
        (all, method)
    }

    /// The part of line `l`'s picture inside the window of a view that clips (see
    /// [`Clip::framed`]): a wide intersection line is unbounded.
    pub(super) fn framed(&self, clip: &Clip, l: &Line) -> Framed {
        if !l.wide {
            return clip.framed(&self.picture, FramedLine::Segment(l.ends));
        }
        if l.meet.is_some() {
            return Framed::Unbounded;
        }
        let (front, from, other) = if clip.in_front(&l.a) {
            (&l.a, l.ends[0], &l.b)
        } else {
            (&l.b, l.ends[1], &l.a)
        };
        clip.framed(&self.picture, FramedLine::Ray { front, from, other })
    }
}

/// The cuts of line `l` (index `i`) where it crosses the planes of the frustum of a view
/// that clips, and the planes of a tile, strictly inside it. A tile's cuts have the largest
/// keys (see [`TILE_CUT`]): where one falls on another cut, the other is drawn, as in the
/// whole drawing.
pub(super) fn frustum_cuts(
    clip: Option<Clip>,
    tile: Option<&TilePlanes>,
    eye: &Eye,
    (i, l, m): (usize, &Line, Option<&MeetLine>),
) -> Vec<(usize, Cut)> {
    let frustum = clip.iter().flat_map(|c| c.forms());
    let frustum = frustum
        .enumerate()
        .map(|(k, form)| (form, [3, k as u32, 0, 0]));
    let tile = tile.into_iter().flat_map(|t| t.forms());
    let tile = tile
        .enumerate()
        .map(|(k, form)| (form, [TILE_CUT, k as u32, 0, 0]));
    frustum
        .chain(tile)
        .filter_map(|(form, key)| {
            let cut = match m {
                None => Cut::on_edge(form.zero_on(eye, &l.a, &l.b)?, None, key),
                Some(m) => {
                    // On an intersection line, strictly between its ends, as a form increasing
                    // along it.
                    let [x, y] = &m.ends;
                    let signs = [x, y].map(|e| m.meet.sign_at(eye, e, &form));
                    if signs.contains(&Ordering::Equal) || signs[0] == signs[1] {
                        return None;
                    }
                    let form = m.meet.increasing(eye, form);
                    Cut::on_line(form, rough_parameter(eye, &form, &l.a, &l.b), None, key)
                }
            };
            Some((i, cut))
        })
        .collect()
}

/// The first element of the key of a cut where a line crosses a tile's plane: larger than any
/// other cut's.
pub(super) const TILE_CUT: u32 = 4;
