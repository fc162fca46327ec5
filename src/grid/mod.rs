//! Franklin's uniform grid for segment intersection (KEPLER 1981, item 4c, and his later
//! uniform-grid work): every pair of segments in the plane that meet, in time linear in the
//! number of segments plus the number of intersections for segments of similar lengths.
//!
//! The grid's cell side comes from the number of segments and their mean length (about one
//! segment length, and no more cells than a few per segment). Each segment is listed in the
//! cells it passes through (a column-by-column walk, widened by a margin far above rounding so
//! that no cell it touches is missed); pairs are tested cell by cell (a compact box test
//! first), and a pair found in several cells is reported once.
//! Whether two segments meet, touching and collinear overlap included, is decided exactly
//! ([`segments_meet`]); where they meet is constructed once from the input coordinates
//! ([`meeting`]). Cells are processed in parallel (rayon).
//!
//! Written by hand because it is the paper's own algorithm; geo's sweep (`geo::algorithm::
//! sweep`) finds the same pairs 8 to 23 times slower here (`cargo bench --bench segx`) and
//! serves the tests as an oracle.
//!
//! ```
//! use geo::{Line, coord};
//! use kepler::grid::intersecting_pairs;
//! let segments = [
//!     Line::new(coord! { x: 0.0, y: 0.0 }, coord! { x: 2.0, y: 2.0 }),
//!     Line::new(coord! { x: 0.0, y: 2.0 }, coord! { x: 2.0, y: 0.0 }),
//!     Line::new(coord! { x: 2.0, y: 2.0 }, coord! { x: 3.0, y: 2.0 }), // touches the first
//!     Line::new(coord! { x: 5.0, y: 5.0 }, coord! { x: 6.0, y: 5.0 }),
//! ];
//! assert_eq!(intersecting_pairs(&segments), vec![(0, 1), (0, 2)]);
//! ```

mod candidates;
mod cells;
mod voxels;

pub use cells::{CellLists, Cells};
pub(crate) use voxels::MARGIN as CELL_MARGIN;
pub use voxels::Voxels;

use crate::geometry::exact::{accurate_sum, product_terms, two_sum};
use crate::geometry::kernel::Polynomial;
use crate::geometry::polygon::segments_meet;
use crate::geometry::predicates::{Orient2d, orient2d};
use crate::random::SplitMix64;
use geo::{Coord, Line};
use rayon::prelude::*;
use std::cmp::Ordering;

/// Where two segments meet.
///
/// ```
/// use geo::{Line, coord};
/// use kepler::grid::{Meeting, meeting};
/// let a = Line::new(coord! { x: 0.0, y: 0.0 }, coord! { x: 4.0, y: 0.0 });
/// let b = Line::new(coord! { x: 1.0, y: 0.0 }, coord! { x: 9.0, y: 0.0 });
/// assert_eq!(meeting(&a, &b), Some(Meeting::Overlap(coord! { x: 1.0, y: 0.0 }, coord! { x: 4.0, y: 0.0 })));
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Meeting {
    /// One point: a crossing (constructed once from the input coordinates, a few ulps from
    /// the exact point) or a touching endpoint (an input point, exact).
    Point(Coord<f64>),
    /// A collinear overlap between these two input points (in the first segment's direction).
    Overlap(Coord<f64>, Coord<f64>),
}

/// Where the closed segments `s` and `t` meet, or `None`; decided exactly.
///
/// ```
/// use geo::{Line, coord};
/// use kepler::grid::{Meeting, meeting};
/// let a = Line::new(coord! { x: 0.0, y: 0.0 }, coord! { x: 2.0, y: 2.0 });
/// let b = Line::new(coord! { x: 0.0, y: 2.0 }, coord! { x: 2.0, y: 0.0 });
/// assert_eq!(meeting(&a, &b), Some(Meeting::Point(coord! { x: 1.0, y: 1.0 })));
/// let c = Line::new(coord! { x: 3.0, y: 0.0 }, coord! { x: 4.0, y: 0.0 });
/// assert_eq!(meeting(&a, &c), None);
/// ```
pub fn meeting(s: &Line<f64>, t: &Line<f64>) -> Option<Meeting> {
    let (a, b, c, d) = (xy(s.start), xy(s.end), xy(t.start), xy(t.end));
    let (o1, o2) = (orient2d(a, b, c), orient2d(a, b, d));
    let (o3, o4) = (orient2d(c, d, a), orient2d(c, d, b));
    let zero = Ordering::Equal;
    if [o1, o2, o3, o4].iter().all(|&o| o != zero) {
        return (o1 != o2 && o3 != o4).then(|| Meeting::Point(crossing(a, b, c, d)));
    }
    if [o1, o2, o3, o4].iter().all(|&o| o == zero) {
        return overlap(a, b, c, d);
    }
    let between = |p: [f64; 2], q: [f64; 2], r: [f64; 2]| {
        (0..2).all(|k| p[k].min(q[k]) <= r[k] && r[k] <= p[k].max(q[k]))
    };
    [(o1, a, b, c), (o2, a, b, d), (o3, c, d, a), (o4, c, d, b)]
        .into_iter()
        .find(|&(o, p, q, r)| o == zero && between(p, q, r))
        .map(|(_, _, _, r)| Meeting::Point(coord(r)))
}

/// The crossing point of two segments that cross properly: `a + t (b - a)` with `t` the
/// ratio of two correctly rounded exact determinants.
fn crossing(a: [f64; 2], b: [f64; 2], c: [f64; 2], d: [f64; 2]) -> Coord<f64> {
    // t = (d - c) x (c - a) / (d - c) x (b - a).
    let diff = |p: [f64; 2], q: [f64; 2], k: usize| {
        let (s, e) = two_sum(p[k], -q[k]);
        [s, e]
    };
    let cross = |u: [f64; 2], v: [f64; 2], w: [f64; 2], z: [f64; 2]| {
        let mut terms = Vec::with_capacity(16);
        product_terms(&diff(u, v, 0), &diff(w, z, 1), &mut terms);
        let start = terms.len();
        product_terms(&diff(u, v, 1), &diff(w, z, 0), &mut terms);
        terms[start..].iter_mut().for_each(|x| *x = -*x);
        accurate_sum(&terms)
    };
    let t = cross(d, c, c, a) / cross(d, c, b, a);
    coord([0, 1].map(|k| a[k] + t * (b[k] - a[k])))
}

/// The overlap of two collinear segments, as input points, or `None`.
fn overlap(a: [f64; 2], b: [f64; 2], c: [f64; 2], d: [f64; 2]) -> Option<Meeting> {
    // Along the axis where the four points are not all equal.
    let k = if a[0] != b[0] || c[0] != d[0] || a[0] != c[0] {
        0
    } else {
        1
    };
    let along = |p: &[f64; 2]| p[k];
    let sort = |p: [f64; 2], q: [f64; 2]| {
        if along(&p) <= along(&q) {
            (p, q)
        } else {
            (q, p)
        }
    };
    let ((a0, a1), (c0, c1)) = (sort(a, b), sort(c, d));
    let lo = if along(&a0) >= along(&c0) { a0 } else { c0 };
    let hi = if along(&a1) <= along(&c1) { a1 } else { c1 };
    match along(&lo).partial_cmp(&along(&hi)) {
        Some(Ordering::Less) => {
            let forward = along(&a) <= along(&b);
            let (p, q) = if forward { (lo, hi) } else { (hi, lo) };
            Some(Meeting::Overlap(coord(p), coord(q)))
        }
        Some(Ordering::Equal) => Some(Meeting::Point(coord(lo))),
        _ => None,
    }
}

fn xy(c: Coord<f64>) -> [f64; 2] {
    [c.x, c.y]
}

fn coord(p: [f64; 2]) -> Coord<f64> {
    Coord { x: p[0], y: p[1] }
}

/// The relative margin by which a segment's walk is widened: 2⁻⁴⁶ of the largest coordinate,
/// 64 units in the last place of it, above the few units the walk's arithmetic (cell
/// boundaries, the segment's height at them) can be off by; small enough that data far from
/// the origin, with cells only thousands of ulps wide, still lists each segment in few cells.
const MARGIN: f64 = 1.0 / (1u64 << 46) as f64;

/// A uniform grid over a set of segments: which cells each segment passes through, and which
/// segments each cell lists.
///
/// ```
/// use geo::{Line, coord};
/// use kepler::grid::SegmentGrid;
/// // A zigzag: each segment meets the next one at a shared endpoint.
/// let segments: Vec<Line<f64>> = (0..100)
///     .map(|i| {
///         let (x, y) = (i as f64, (i % 2) as f64);
///         Line::new(coord! { x: x, y: y }, coord! { x: x + 1.0, y: 1.0 - y })
///     })
///     .collect();
/// let grid = SegmentGrid::new(&segments);
/// assert_eq!(grid.pairs().len(), 99);
/// // Parallel neighbours never meet.
/// let parallel: Vec<Line<f64>> = (0..100)
///     .map(|i| Line::new(coord! { x: i as f64, y: 0.0 }, coord! { x: i as f64 + 1.5, y: 1.0 }))
///     .collect();
/// assert!(SegmentGrid::new(&parallel).pairs().is_empty());
/// ```
#[derive(Debug, Clone)]
pub struct SegmentGrid {
    cells: Cells,
    margin: f64,
    segments: usize,
    /// Cell `c` lists `items[start[c]..start[c + 1]]`.
    start: Vec<u32>,
    items: Vec<Item>,
}

/// A segment as a cell lists it: the cell, the segment's index and its endpoints (copied, so
/// that a cell's pairs are tested without reaching back into the input), `a` the one of
/// smaller `x`. A cell lists its items by increasing `a.x`.
#[derive(Debug, Clone, Copy)]
struct Item {
    cell: u32,
    segment: u32,
    a: [f64; 2],
    b: [f64; 2],
}

impl Item {
    /// Whether the closed bounding boxes, grown by `m`, meet.
    #[inline]
    fn boxes_meet_within(&self, other: &Item, m: f64) -> bool {
        (0..2).all(|k| {
            self.a[k].min(self.b[k]) - m <= other.a[k].max(other.b[k])
                && other.a[k].min(other.b[k]) - m <= self.a[k].max(self.b[k])
        })
    }

    /// Whether the closed bounding boxes meet (exact comparisons).
    #[inline]
    fn boxes_meet(&self, other: &Item) -> bool {
        (0..2).all(|k| {
            self.a[k].min(self.b[k]) <= other.a[k].max(other.b[k])
                && other.a[k].min(other.b[k]) <= self.a[k].max(self.b[k])
        })
    }
}

impl SegmentGrid {
    /// Builds the grid for `segments`: cell side about the mean segment length (but cells no
    /// smaller than one per segment would give), capped at four cells per segment.
    ///
    /// ```
    /// use geo::{Line, coord};
    /// let s = [Line::new(coord! { x: 0.0, y: 0.0 }, coord! { x: 1.0, y: 1.0 })];
    /// assert_eq!(kepler::grid::SegmentGrid::new(&s).shape(), [1, 1]);
    /// ```
    pub fn new(segments: &[Line<f64>]) -> SegmentGrid {
        let (lo, hi, scale) = extent(segments);
        let n = segments.len().max(1) as f64;
        let size = [hi[0] - lo[0], hi[1] - lo[1]];
        let mean_length = segments
            .iter()
            .map(|s| (s.dx() * s.dx() + s.dy() * s.dy()).sqrt())
            .sum::<f64>()
            / n;
        let spread = (size[0].max(0.0) * size[1].max(0.0) / n).sqrt();
        let side = mean_length.max(spread);
        let mut cells = [0, 1].map(|k| {
            if side > 0.0 && size[k] > 0.0 {
                (size[k] / side).ceil().clamp(1.0, 1e6) as usize
            } else {
                1
            }
        });
        while (cells[0] * cells[1]) as f64 > 4.0 * n + 1.0 {
            cells = cells.map(|c| c.div_ceil(2));
        }
        let mut grid = SegmentGrid {
            cells: Cells::new(lo, size, cells),
            margin: MARGIN * scale,
            segments: segments.len(),
            start: Vec::new(),
            items: Vec::new(),
        };
        // Every (cell, segment) of the walks, gathered per thread in one pass over the input
        // (in the order of the segments), then placed by cell with a counting pass (the cells
        // are at most 4n + 1): within a cell, in the order of the segments, as a sort of the
        // (cell, segment) pairs would leave them, and in one pass instead of a sort.
        let keys: Vec<u64> = segments
            .par_iter()
            .enumerate()
            .fold(Vec::new, |mut out, (i, s)| {
                walk(&grid.cells, grid.margin, s, |cell| {
                    out.push((u64::from(cell) << 32) | i as u64)
                });
                out
            })
            .reduce(Vec::new, |mut x, mut y| {
                x.append(&mut y);
                x
            });
        let item = |&k: &u64| {
            let s = &segments[(k & 0xffff_ffff) as usize];
            let (a, b) = (xy(s.start), xy(s.end));
            let (a, b) = if a[0] <= b[0] { (a, b) } else { (b, a) };
            Item {
                cell: (k >> 32) as u32,
                segment: k as u32,
                a,
                b,
            }
        };
        let (start, mut items) =
            crate::mesh::by_bucket(grid.cells.count(), &keys, |k| (k >> 32) as usize, item);
        // Within a cell, by the left end's x: a cell's pairs are then found by a sweep.
        items
            .par_chunk_by_mut(|x, y| x.cell == y.cell)
            .for_each(|cell| cell.sort_unstable_by(|x, y| x.a[0].total_cmp(&y.a[0])));
        grid.start = start.into_iter().map(|s| s as u32).collect();
        grid.items = items;
        grid
    }

    /// The grid's shape: cells along x and y.
    ///
    /// ```
    /// use geo::{Line, coord};
    /// let s = [Line::new(coord! { x: 0.0, y: 0.0 }, coord! { x: 0.0, y: 0.0 })];
    /// assert_eq!(kepler::grid::SegmentGrid::new(&s).shape(), [1, 1]);
    /// ```
    pub fn shape(&self) -> [usize; 2] {
        self.cells.shape()
    }

    /// The mean number of cells a segment is listed in.
    ///
    /// ```
    /// use geo::{Line, coord};
    /// let s = [Line::new(coord! { x: 0.0, y: 0.0 }, coord! { x: 1.0, y: 0.0 })];
    /// assert_eq!(kepler::grid::SegmentGrid::new(&s).cells_per_segment(), 1.0);
    /// ```
    pub fn cells_per_segment(&self) -> f64 {
        self.items.len() as f64 / self.segments.max(1) as f64
    }

    /// Every pair `(i, j)`, `i < j`, of the segments the grid was built from that meet, in
    /// increasing order, each once.
    ///
    /// ```
    /// use geo::{Line, coord};
    /// use kepler::grid::SegmentGrid;
    /// // Three segments through one point, and a far one.
    /// let s = [
    ///     Line::new(coord! { x: -1.0, y: 0.0 }, coord! { x: 1.0, y: 0.0 }),
    ///     Line::new(coord! { x: 0.0, y: -1.0 }, coord! { x: 0.0, y: 1.0 }),
    ///     Line::new(coord! { x: -1.0, y: -1.0 }, coord! { x: 1.0, y: 1.0 }),
    ///     Line::new(coord! { x: 7.0, y: 7.0 }, coord! { x: 8.0, y: 7.0 }),
    /// ];
    /// assert_eq!(SegmentGrid::new(&s).pairs(), vec![(0, 1), (0, 2), (1, 2)]);
    /// ```
    pub fn pairs(&self) -> Vec<(usize, usize)> {
        self.gather(|c| self.pairs_in(c))
    }

    /// The pairs every cell yields (each `(i, j)` as the integer `i·2³² + j`), gathered in
    /// parallel; a pair listed together in several cells is found in each, so they are sorted
    /// and deduplicated.
    fn gather<'a, I>(&'a self, in_cell: impl Fn(usize) -> I + Sync + Send) -> Vec<(usize, usize)>
    where
        I: Iterator<Item = u64> + 'a,
    {
        let pairs: Vec<u64> = (0..self.cells.count())
            .into_par_iter()
            .flat_map_iter(in_cell)
            .collect();
        unpacked(pairs)
    }

    /// The pairs of cell `c` that meet.
    /// Each pair `(i, j)`, `i < j`, as the integer `i·2³² + j`.
    fn pairs_in<'a>(&'a self, c: usize) -> impl Iterator<Item = u64> + 'a {
        let here = &self.items[self.start[c] as usize..self.start[c + 1] as usize];
        here.iter().enumerate().flat_map(move |(n, a)| {
            // The items after `a` whose x-ranges can meet its own: a sweep along x.
            let right = a.b[0];
            here[n + 1..]
                .iter()
                .take_while(move |b| b.a[0] <= right)
                .filter_map(move |b| {
                    if !a.boxes_meet(b) {
                        return None;
                    }
                    if apart(a.a, a.b, b.a, b.b) || apart(b.a, b.b, a.a, a.b) {
                        return None;
                    }
                    let (i, j) = (a.segment.min(b.segment), a.segment.max(b.segment));
                    segments_meet(a.a, a.b, b.a, b.b).then_some((u64::from(i) << 32) | u64::from(j))
                })
        })
    }
}

/// The pairs `i·2³² + j` as `(i, j)`, sorted, each once (a pair listed together in several
/// cells is found in each).
fn unpacked(mut pairs: Vec<u64>) -> Vec<(usize, usize)> {
    pairs.par_sort_unstable();
    pairs.dedup();
    pairs
        .into_iter()
        .map(|p| ((p >> 32) as usize, (p & 0xffff_ffff) as usize))
        .collect()
}

/// Calls `visit` with each cell of `cells` segment `s` passes through, once: column by column,
/// the rows its part in the (widened) column spans, widened again by the margin `m`. The first
/// and last columns reach out without bound (the indices clamp to the grid there), so that in
/// a grid over part of the plane (a crowded cell split, see `candidates.rs`) a point of `s`
/// outside the grid is listed in the border cell its clamped indices name.
fn walk(cells: &Cells, m: f64, s: &Line<f64>, mut visit: impl FnMut(u32)) {
    let (a, b) = if s.start.x <= s.end.x {
        (s.start, s.end)
    } else {
        (s.end, s.start)
    };
    let [columns, _] = cells.shape();
    let (y_min, y_max) = (a.y.min(b.y) - m, a.y.max(b.y) + m);
    let (c0, c1) = (cells.index(0, a.x - m), cells.index(0, b.x + m));
    for col in c0..=c1 {
        let (mut x0, mut x1) = (a.x, b.x);
        if col > 0 {
            x0 = x0.max(cells.coordinate(0, col as f64) - m);
        }
        if col + 1 < columns {
            x1 = x1.min(cells.coordinate(0, (col + 1) as f64) + m);
        }
        if x0 > x1 {
            continue;
        }
        // The segment's heights at the column's ends; a slope too steep for a double (a
        // nearly vertical segment) spans the whole height.
        let slope = (b.y - a.y) / (b.x - a.x);
        let (lo, hi) = if b.x > a.x && slope.is_finite() {
            let (y0, y1) = (a.y + (x0 - a.x) * slope, a.y + (x1 - a.x) * slope);
            (y0.min(y1) - m, y0.max(y1) + m)
        } else {
            (y_min, y_max)
        };
        let (r0, r1) = (cells.index(1, lo.max(y_min)), cells.index(1, hi.min(y_max)));
        for row in r0..=r1 {
            visit((row * columns + col) as u32);
        }
    }
}

/// Whether `c` and `d` lie strictly on the same side of the line through `a` and `b`, as
/// certified by the kernel's floating-point filter of [`Orient2d`]; `false` when the filter
/// cannot tell, and the exact test decides. Most pairs in a cell are rejected here.
#[inline]
fn apart(a: [f64; 2], b: [f64; 2], c: [f64; 2], d: [f64; 2]) -> bool {
    let side = |p: [f64; 2]| Orient2d([a, b, p]).estimate().sign();
    matches!((side(c), side(d)), (Some(s), Some(t)) if s == t && s != Ordering::Equal)
}

/// The bounding box of all endpoints and the largest coordinate magnitude.
fn extent(segments: &[Line<f64>]) -> ([f64; 2], [f64; 2], f64) {
    let mut lo = [f64::INFINITY; 2];
    let mut hi = [f64::NEG_INFINITY; 2];
    let mut scale = 0.0f64;
    for p in segments.iter().flat_map(|s| [s.start, s.end]) {
        lo = [lo[0].min(p.x), lo[1].min(p.y)];
        hi = [hi[0].max(p.x), hi[1].max(p.y)];
        scale = scale.max(p.x.abs()).max(p.y.abs());
    }
    if segments.is_empty() {
        return ([0.0; 2], [0.0; 2], 0.0);
    }
    (lo, hi, scale)
}

/// Every pair `(i, j)`, `i < j`, of `segments` that meet (touching and collinear overlap
/// included), each once, in increasing order.
///
/// ```
/// use geo::{Line, coord};
/// let s = [
///     Line::new(coord! { x: 0.0, y: 0.0 }, coord! { x: 1.0, y: 0.0 }),
///     Line::new(coord! { x: 0.5, y: 0.0 }, coord! { x: 2.0, y: 0.0 }),
/// ];
/// assert_eq!(kepler::grid::intersecting_pairs(&s), vec![(0, 1)]);
/// ```
pub fn intersecting_pairs(segments: &[Line<f64>]) -> Vec<(usize, usize)> {
    SegmentGrid::new(segments).pairs()
}

/// Every pair of `segments` that meet, with where they meet, in increasing pair order.
///
/// ```
/// use geo::{Line, coord};
/// use kepler::grid::{Meeting, intersections};
/// let s = [
///     Line::new(coord! { x: 0.0, y: 0.0 }, coord! { x: 4.0, y: 4.0 }),
///     Line::new(coord! { x: 0.0, y: 4.0 }, coord! { x: 4.0, y: 0.0 }),
/// ];
/// assert_eq!(intersections(&s), vec![(0, 1, Meeting::Point(coord! { x: 2.0, y: 2.0 }))]);
/// ```
pub fn intersections(segments: &[Line<f64>]) -> Vec<(usize, usize, Meeting)> {
    intersecting_pairs(segments)
        .into_par_iter()
        .filter_map(|(i, j)| meeting(&segments[i], &segments[j]).map(|m| (i, j, m)))
        .collect()
}

/// Franklin's experiment: `n` segments of length `len` (at most 1) in the unit square, each
/// with a uniformly random midpoint in `[len/2, 1 - len/2]²` and a uniformly random direction,
/// from a fixed seed ([`SplitMix64`]), so runs reproduce.
///
/// ```
/// let s = kepler::grid::random_segments(1000, 0.01, 7);
/// assert_eq!(s.len(), 1000);
/// assert!(s.iter().all(|l| (l.dx().hypot(l.dy()) - 0.01).abs() < 1e-15));
/// assert!(s.iter().flat_map(|l| [l.start, l.end]).all(|p| (0.0..=1.0).contains(&p.x) && (0.0..=1.0).contains(&p.y)));
/// ```
pub fn random_segments(n: usize, len: f64, seed: u64) -> Vec<Line<f64>> {
    let mut rng = SplitMix64(seed);
    let mut unit = move || rng.unit();
    let half = len.clamp(0.0, 1.0) / 2.0;
    (0..n)
        .map(|_| {
            let centre = [0, 1].map(|_| half + (1.0 - 2.0 * half) * unit());
            let angle = std::f64::consts::TAU * unit();
            let (dy, dx) = angle.sin_cos();
            let (hx, hy) = (half * dx, half * dy);
            Line::new(
                Coord {
                    x: centre[0] - hx,
                    y: centre[1] - hy,
                },
                Coord {
                    x: centre[0] + hx,
                    y: centre[1] + hy,
                },
            )
        })
        .collect()
}
