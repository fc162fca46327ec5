//! Error measures of a drawing against the exact one.
//!
//! The report draws each scene twice or more: once with the exact engine, and once with each
//! cheaper variant (plain floats, tolerances, `f32`, sampled edges, a z-buffer). To say how
//! wrong a variant is, [`compare`] lays its drawing over the exact one and measures, in
//! picture units, the length of line that the variant gets wrong and how:
//!
//! - *misclassified*: exact visible lines that the variant draws only hidden, and back;
//! - *missing*: exact lines the variant does not draw at all;
//! - *extra*: lines the variant draws where the exact drawing has none;
//! - *placement*: the Hausdorff distance between the two drawings' vertices, also in ulps of
//!   the exact drawing's largest coordinate, which tells a rounding apart from a blunder;
//! - *topology*: ends of visible or hidden runs in one drawing with no such end nearby in the
//!   other (a line that stops too early, a run split in two, a visibility change in the wrong
//!   place).
//!
//! A line of one drawing is *covered* by the other where it lies within a tolerance of one of
//! the other's segments. The measure is per segment and exact for straight segments: the part
//! of a segment within distance `r` of another segment is the part of its line inside that
//! segment's capsule (the rectangle of half-width `r` along it and the discs of radius `r` at
//! its ends), a convex set, so one parameter interval. The union of these intervals over the
//! nearby segments (found with an R-tree over their envelopes widened by `r`), split by the
//! visibility of the covering segments, gives the covered, misclassified and uncovered
//! lengths. Two segments crossing at an angle cover each other only near their crossing, over
//! a length of the order of the tolerance, as they should.
//!
//! Why not compare pictures pixel by pixel? A raster hides exactly the errors the report is
//! about: a visibility change computed a millionth of the picture away from the exact one, or
//! a sliver of hidden line drawn visible, vanish below a pixel, while the errors it shows
//! depend on line width and anti-aliasing rather than on the arithmetic. A raster measures
//! ink area, not length, and cannot tell a missing line from a misclassified one. Interval
//! coverage measures lengths at any scale, down to the tolerance, and it is exactly zero for a
//! drawing against itself (every segment covers itself on exactly `[0, 1]`), reversed or
//! reordered, so that a nonzero figure is always a difference between the drawings. This is
//! measuring code in plain `f64`, not part of the engine's exact arithmetic: the figures are
//! right to a few roundings, which is far below the tolerance.
//!
//! Classes are ignored: a silhouette drawn as a crease is not an error of visibility.
//!
//! ```
//! use kepler::hidden::{Drawing, EdgeClass, Polyline};
//! use kepler::lab::report::measure::{compare, default_tolerance};
//! let line = |visible, points: Vec<[f64; 2]>| Polyline { class: EdgeClass::Crease, visible, points };
//! let exact = Drawing { polylines: vec![line(true, vec![[0.0, 0.0], [10.0, 0.0]])], stages: Vec::new() };
//! // The variant draws the second half hidden.
//! let variant = Drawing {
//!     polylines: vec![line(true, vec![[0.0, 0.0], [5.0, 0.0]]), line(false, vec![[5.0, 0.0], [10.0, 0.0]])],
//!     stages: Vec::new(),
//! };
//! let e = compare(&exact, &variant, 0.0);
//! assert_eq!((e.visible_as_hidden, e.missing, e.extra), (5.0, 0.0, 0.0));
//! assert_eq!(e.relative(), 0.5);
//! assert!(compare(&exact, &exact, default_tolerance(&exact)).is_exact());
//! ```

use crate::hidden::Drawing;
use rstar::primitives::{GeomWithData, Rectangle};
use rstar::{AABB, RTree};
use serde::Serialize;

/// How a variant drawing differs from the exact one (see the [module documentation](self)).
/// Lengths are in picture units.
///
/// ```
/// use kepler::hidden::Drawing;
/// use kepler::lab::report::measure::compare;
/// let empty = Drawing { polylines: Vec::new(), stages: Vec::new() };
/// let e = compare(&empty, &empty, 1e-9);
/// assert!(e.is_exact());
/// assert_eq!((e.exact_length, e.relative(), e.runs), (0.0, 0.0, [0, 0]));
/// ```
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize)]
pub struct ErrorFigures {
    /// The total length of the exact drawing, visible and hidden.
    pub exact_length: f64,
    /// The length of exact visible lines that the variant draws hidden: covered by the
    /// variant's hidden lines and not by its visible ones.
    pub visible_as_hidden: f64,
    /// The length of exact hidden lines that the variant draws visible: covered by the
    /// variant's visible lines and not by its hidden ones.
    pub hidden_as_visible: f64,
    /// The length of the exact drawing covered by no line of the variant.
    pub missing: f64,
    /// The length of the variant drawing covered by no line of the exact one.
    pub extra: f64,
    /// The symmetric Hausdorff distance between the two sets of polyline vertices: 0 if both
    /// drawings are empty, infinite if only one is (or if a vertex has a non-finite
    /// coordinate). A distance between vertices, not between lines: a variant that puts a
    /// vertex where the exact drawing has none (a run split mid-segment, a sampled edge) is
    /// as far off as that vertex is from the nearest exact vertex.
    pub hausdorff: f64,
    /// [`hausdorff`](Self::hausdorff) divided by the ulp of the largest finite coordinate
    /// magnitude of the exact drawing (the spacing of `f64` just above it).
    pub hausdorff_ulps: f64,
    /// Topological errors: at each point where segments end, the difference between the
    /// drawings' numbers of visible segment ends, plus that of hidden ones, summed over the
    /// points (see `wrong_ends` in the source): a visibility change in the wrong place, a run
    /// split or merged wrongly, a line ending in the wrong place. How a drawing chains its
    /// runs into polylines does not count.
    pub wrong_ends: usize,
    /// The number of polylines of the exact and of the variant drawing.
    pub runs: [usize; 2],
}

impl ErrorFigures {
    /// The length drawn with the wrong visibility: `visible_as_hidden + hidden_as_visible`.
    ///
    /// ```
    /// use kepler::hidden::Drawing;
    /// let empty = Drawing { polylines: Vec::new(), stages: Vec::new() };
    /// assert_eq!(kepler::lab::report::measure::compare(&empty, &empty, 0.0).misclassified(), 0.0);
    /// ```
    pub fn misclassified(&self) -> f64 {
        self.visible_as_hidden + self.hidden_as_visible
    }

    /// All the length the variant gets wrong: `misclassified + missing + extra`.
    ///
    /// ```
    /// use kepler::hidden::{Drawing, EdgeClass, Polyline};
    /// let exact = Drawing { polylines: Vec::new(), stages: Vec::new() };
    /// let p = Polyline { class: EdgeClass::Boundary, visible: true, points: vec![[0.0, 0.0], [0.0, 2.0]] };
    /// let variant = Drawing { polylines: vec![p], stages: Vec::new() };
    /// assert_eq!(kepler::lab::report::measure::compare(&exact, &variant, 0.0).wrong_length(), 2.0);
    /// ```
    pub fn wrong_length(&self) -> f64 {
        self.misclassified() + self.missing + self.extra
    }

    /// [`wrong_length`](Self::wrong_length) over
    /// [`exact_length`](Self::exact_length): 0 when both are 0, infinite when only the exact
    /// drawing is empty.
    ///
    /// ```
    /// use kepler::hidden::{Drawing, EdgeClass, Polyline};
    /// let p = Polyline { class: EdgeClass::Boundary, visible: true, points: vec![[0.0, 0.0], [0.0, 2.0]] };
    /// let exact = Drawing { polylines: vec![p], stages: Vec::new() };
    /// let variant = Drawing { polylines: Vec::new(), stages: Vec::new() };
    /// assert_eq!(kepler::lab::report::measure::compare(&exact, &variant, 0.0).relative(), 1.0);
    /// ```
    pub fn relative(&self) -> f64 {
        let wrong = self.wrong_length();
        if wrong == 0.0 && self.exact_length == 0.0 {
            0.0
        } else {
            wrong / self.exact_length
        }
    }

    /// Whether every error figure is zero: misclassified, missing and extra lengths, the
    /// Hausdorff distance and the wrong ends (the exact length and the numbers of runs are not
    /// errors; runs split differently show as wrong ends).
    ///
    /// ```
    /// use kepler::hidden::{Drawing, EdgeClass, Polyline};
    /// let p = Polyline { class: EdgeClass::Smooth, visible: false, points: vec![[0.0, 0.0], [1.0, 1.0]] };
    /// let d = Drawing { polylines: vec![p], stages: Vec::new() };
    /// assert!(kepler::lab::report::measure::compare(&d, &d, 0.0).is_exact());
    /// ```
    pub fn is_exact(&self) -> bool {
        self.visible_as_hidden == 0.0
            && self.hidden_as_visible == 0.0
            && self.missing == 0.0
            && self.extra == 0.0
            && self.hausdorff == 0.0
            && self.wrong_ends == 0
    }
}

/// Measures `variant` against `exact` (see the [module documentation](self)), counting a
/// line as covered where it lies within `tolerance` of a line of the other drawing. A
/// negative or NaN tolerance is taken as 0 (covered only by a line through it).
///
/// A segment with a non-finite coordinate covers nothing, is infinitely long and uncovered
/// (so `missing` or `extra` is infinite), and makes the Hausdorff distance infinite; the
/// engine's drawings never hold one.
///
/// ```
/// use kepler::hidden::{Drawing, EdgeClass, Polyline};
/// use kepler::lab::report::measure::compare;
/// let line = |points: Vec<[f64; 2]>| Polyline { class: EdgeClass::Silhouette, visible: true, points };
/// let exact = Drawing { polylines: vec![line(vec![[0.0, 0.0], [4.0, 0.0]])], stages: Vec::new() };
/// let shifted = Drawing { polylines: vec![line(vec![[0.0, 3.0], [4.0, 3.0]])], stages: Vec::new() };
/// let e = compare(&exact, &shifted, 0.5);
/// assert_eq!((e.missing, e.extra, e.hausdorff, e.wrong_ends), (4.0, 4.0, 3.0, 4));
/// // Within the tolerance, only the Hausdorff distance tells them apart.
/// let e = compare(&exact, &shifted, 3.5);
/// assert_eq!((e.wrong_length(), e.hausdorff, e.wrong_ends), (0.0, 3.0, 0));
/// ```
pub fn compare(exact: &Drawing, variant: &Drawing, tolerance: f64) -> ErrorFigures {
    let tolerance = if tolerance >= 0.0 { tolerance } else { 0.0 };
    let exact_segments = segments(exact);
    let variant_segments = segments(variant);
    let exact_tree = segment_tree(&exact_segments, tolerance);
    let variant_tree = segment_tree(&variant_segments, tolerance);

    let mut figures = ErrorFigures {
        exact_length: 0.0,
        visible_as_hidden: 0.0,
        hidden_as_visible: 0.0,
        missing: 0.0,
        extra: 0.0,
        hausdorff: hausdorff(exact, variant),
        hausdorff_ulps: 0.0,
        wrong_ends: wrong_ends(exact, variant, tolerance),
        runs: [exact.polylines.len(), variant.polylines.len()],
    };
    figures.hausdorff_ulps = figures.hausdorff / ulp(largest_magnitude(exact));

    for s in &exact_segments {
        let length = s.length();
        figures.exact_length += length;
        let cover = Cover::of(s, &variant_segments, &variant_tree, tolerance);
        let (same, other) = if s.visible {
            (&cover.visible, &cover.hidden)
        } else {
            (&cover.hidden, &cover.visible)
        };
        let misclassified = resolved(
            scaled(
                length,
                other.iter().map(|&(lo, hi)| gaps(lo, hi, same)).sum(),
            ),
            tolerance,
        );
        if s.visible {
            figures.visible_as_hidden += misclassified;
        } else {
            figures.hidden_as_visible += misclassified;
        }
        figures.missing += resolved(scaled(length, gaps(0.0, 1.0, &cover.any())), tolerance);
    }
    for s in &variant_segments {
        let cover = Cover::of(s, &exact_segments, &exact_tree, tolerance);
        figures.extra += resolved(scaled(s.length(), gaps(0.0, 1.0, &cover.any())), tolerance);
    }
    figures
}

/// A length of one segment as the comparison resolves it: none when it is no longer than the
/// tolerance (the rounding of the covering intervals leaves such slivers where lines meet
/// exactly; a part that short is below what the comparison tells apart).
fn resolved(length: f64, tolerance: f64) -> f64 {
    if length <= tolerance { 0.0 } else { length }
}

/// The length of a part `fraction` of a segment of length `length`: 0 for no part, even of
/// an infinitely long segment.
fn scaled(length: f64, fraction: f64) -> f64 {
    if fraction > 0.0 {
        length * fraction
    } else {
        0.0
    }
}

/// The tolerance for [`compare`] fitting an exact drawing: its bounding-box diagonal times
/// `2^-40`, and at least 16 ulps of its largest coordinate magnitude (the floor that an empty
/// drawing, a drawing reduced to a point, or one far from the origin compared with its size
/// falls back on).
///
/// Why `2^-40`: the exact drawing's coordinates are correctly rounded, about `2^-52` of the
/// coordinates apart from the true picture, so a variant that gets the lines right differs by
/// a few ulps, some `2^12` times below the tolerance, and is covered; a pixel of a picture a
/// thousand pixels across is about `2^-10` of the diagonal, `2^30` times above it, so any
/// difference a user could see is far outside the tolerance and counted. What lies between is
/// placement error of the arithmetic, which [`ErrorFigures::hausdorff`] reports separately.
///
/// ```
/// use kepler::hidden::{Drawing, EdgeClass, Polyline};
/// use kepler::lab::report::measure::default_tolerance;
/// let p = Polyline { class: EdgeClass::Crease, visible: true, points: vec![[0.0, 0.0], [3.0, 4.0]] };
/// let d = Drawing { polylines: vec![p], stages: Vec::new() };
/// assert_eq!(default_tolerance(&d), 5.0 * 2f64.powi(-40));
/// assert!(default_tolerance(&Drawing { polylines: Vec::new(), stages: Vec::new() }) > 0.0);
/// ```
pub fn default_tolerance(exact: &Drawing) -> f64 {
    let mut points = finite_points(exact);
    let diagonal = points.next().map_or(0.0, |first| {
        let (lo, hi) = points.fold((first, first), |(lo, hi), p| {
            (
                [lo[0].min(p[0]), lo[1].min(p[1])],
                [hi[0].max(p[0]), hi[1].max(p[1])],
            )
        });
        (hi[0] - lo[0]).hypot(hi[1] - lo[1])
    });
    (diagonal * 2f64.powi(-40)).max(16.0 * ulp(largest_magnitude(exact)))
}

/// One segment of a drawing, from `a` to `b`: `a + t d` for `t` in `[0, 1]`, `d = b - a`.
/// Both ends are kept as drawn (not recomputed from `d`), so that a segment covers itself,
/// and its reversal, on exactly `[0, 1]`.
struct Segment {
    a: [f64; 2],
    b: [f64; 2],
    d: [f64; 2],
    visible: bool,
    /// Both ends have finite coordinates (`d` may still overflow).
    finite: bool,
}

impl Segment {
    fn length(&self) -> f64 {
        if self.finite {
            self.d[0].hypot(self.d[1])
        } else {
            f64::INFINITY
        }
    }
}

fn segments(drawing: &Drawing) -> Vec<Segment> {
    drawing
        .polylines
        .iter()
        .flat_map(|line| {
            line.points.windows(2).map(move |w| {
                let (a, b) = (w[0], w[1]);
                Segment {
                    a,
                    b,
                    d: [b[0] - a[0], b[1] - a[1]],
                    visible: line.visible,
                    finite: a.iter().chain(&b).all(|x| x.is_finite()),
                }
            })
        })
        .collect()
}

type Envelope = GeomWithData<Rectangle<[f64; 2]>, usize>;

/// The finite segments' envelopes widened by the tolerance, a little more so that rounding
/// the widened bounds never leaves out a segment within the tolerance.
fn segment_tree(segments: &[Segment], tolerance: f64) -> RTree<Envelope> {
    let widen = |x: f64, by: f64| (x + by).clamp(-f64::MAX, f64::MAX);
    RTree::bulk_load(
        segments
            .iter()
            .enumerate()
            .filter(|(_, s)| s.finite)
            .map(|(i, s)| {
                let (a, b) = (s.a, s.b);
                let lo = [0, 1].map(|k| widen(a[k].min(b[k]), -tolerance).next_down());
                let hi = [0, 1].map(|k| widen(a[k].max(b[k]), tolerance).next_up());
                GeomWithData::new(Rectangle::from_corners(lo, hi), i)
            })
            .collect(),
    )
}

/// The parameter intervals of one segment covered by the visible and by the hidden segments
/// of the other drawing, each sorted and merged.
struct Cover {
    visible: Vec<(f64, f64)>,
    hidden: Vec<(f64, f64)>,
}

impl Cover {
    fn of(s: &Segment, others: &[Segment], tree: &RTree<Envelope>, tolerance: f64) -> Cover {
        let mut cover = Cover {
            visible: Vec::new(),
            hidden: Vec::new(),
        };
        if !s.finite || s.length() == 0.0 {
            return cover;
        }
        let (a, b) = (s.a, s.b);
        let query = AABB::from_corners(
            [a[0].min(b[0]), a[1].min(b[1])],
            [a[0].max(b[0]), a[1].max(b[1])],
        );
        for near in tree.locate_in_envelope_intersecting(&query) {
            let other = &others[near.data];
            if let Some((lo, hi)) = capsule(s, other.a, other.b, tolerance) {
                let (lo, hi) = (lo.max(0.0), hi.min(1.0));
                if lo <= hi {
                    if other.visible {
                        cover.visible.push((lo, hi));
                    } else {
                        cover.hidden.push((lo, hi));
                    }
                }
            }
        }
        merge(&mut cover.visible);
        merge(&mut cover.hidden);
        cover
    }

    /// The intervals covered by any segment.
    fn any(&self) -> Vec<(f64, f64)> {
        let mut all = [self.visible.as_slice(), self.hidden.as_slice()].concat();
        merge(&mut all);
        all
    }
}

/// Sorts intervals and merges those that overlap or touch.
fn merge(intervals: &mut Vec<(f64, f64)>) {
    intervals.sort_by(|x, y| x.0.total_cmp(&y.0));
    let mut merged: Vec<(f64, f64)> = Vec::with_capacity(intervals.len());
    for &(lo, hi) in intervals.iter() {
        match merged.last_mut() {
            Some(last) if lo <= last.1 => last.1 = last.1.max(hi),
            _ => merged.push((lo, hi)),
        }
    }
    *intervals = merged;
}

/// The measure of `[lo, hi]` outside the sorted, merged intervals `covered`.
fn gaps(lo: f64, hi: f64, covered: &[(f64, f64)]) -> f64 {
    let mut reached = lo;
    let mut total = 0.0;
    for &(a, b) in covered {
        if a >= hi {
            break;
        }
        if a > reached {
            total += a - reached;
        }
        reached = reached.max(b);
    }
    if hi > reached {
        total += hi - reached;
    }
    total
}

/// The interval of parameters `t` with `s.a + t s.d` within `r` of the segment `ab`: the
/// line's intersection with the capsule of `ab`, the union of its intersections with the
/// rectangle of half-width `r` along `ab` and with the discs of radius `r` at `a` and `b`
/// (an interval, since the capsule is convex). `None` if the line misses it.
fn capsule(s: &Segment, a: [f64; 2], b: [f64; 2], r: f64) -> Option<(f64, f64)> {
    let e = [b[0] - a[0], b[1] - a[1]];
    let ee = dot(e, e);
    let mut pieces = [disc(s, a, r), disc(s, b, r), None];
    if ee > 0.0 {
        let w = [s.a[0] - a[0], s.a[1] - a[1]];
        let half_width = r * ee.sqrt();
        pieces[2] = Some((f64::NEG_INFINITY, f64::INFINITY))
            .and_then(|t| slab(t, dot(w, e), dot(s.d, e), 0.0, ee))
            .and_then(|t| slab(t, cross(e, w), cross(e, s.d), -half_width, half_width));
    }
    pieces
        .into_iter()
        .flatten()
        .reduce(|x, y| (x.0.min(y.0), x.1.max(y.1)))
}

/// The part of the interval `t` where `lo <= f0 + f1 t <= hi`.
fn slab(t: (f64, f64), f0: f64, f1: f64, lo: f64, hi: f64) -> Option<(f64, f64)> {
    let (from, to) = if f1 == 0.0 {
        if lo <= f0 && f0 <= hi {
            t
        } else {
            return None;
        }
    } else {
        let (x, y) = ((lo - f0) / f1, (hi - f0) / f1);
        (t.0.max(x.min(y)), t.1.min(x.max(y)))
    };
    // Also false for NaN (an overflow of huge coordinates): no cover.
    (from <= to).then_some((from, to))
}

/// The parameters `t` with `|s.a + t s.d - c| <= r`: the roots of
/// `|d|^2 t^2 + 2 (d.w) t + |w|^2 - r^2` for `w = a - c`, computed without cancellation.
fn disc(s: &Segment, c: [f64; 2], r: f64) -> Option<(f64, f64)> {
    let w = [s.a[0] - c[0], s.a[1] - c[1]];
    let a = dot(s.d, s.d);
    let b = dot(s.d, w);
    let c = dot(w, w) - r * r;
    let discriminant = b * b - a * c;
    if !(a > 0.0 && discriminant >= 0.0) {
        return None;
    }
    let q = -(b + discriminant.sqrt().copysign(b));
    let (x, y) = if q == 0.0 { (0.0, 0.0) } else { (q / a, c / q) };
    Some((x.min(y), x.max(y))).filter(|(x, y)| x <= y)
}

fn dot(u: [f64; 2], v: [f64; 2]) -> f64 {
    u[0] * v[0] + u[1] * v[1]
}

fn cross(u: [f64; 2], v: [f64; 2]) -> f64 {
    u[0] * v[1] - u[1] * v[0]
}

fn finite_points(drawing: &Drawing) -> impl Iterator<Item = [f64; 2]> + '_ {
    drawing
        .polylines
        .iter()
        .flat_map(|p| p.points.iter().copied())
        .filter(|p| p[0].is_finite() && p[1].is_finite())
}

fn largest_magnitude(drawing: &Drawing) -> f64 {
    finite_points(drawing).fold(0.0, |m, p| m.max(p[0].abs()).max(p[1].abs()))
}

/// The spacing of `f64` just above `x >= 0` (just below it for the largest finite `f64`).
fn ulp(x: f64) -> f64 {
    if x == f64::MAX {
        x - x.next_down()
    } else {
        x.next_up() - x
    }
}

/// The symmetric Hausdorff distance between the drawings' vertex sets.
fn hausdorff(a: &Drawing, b: &Drawing) -> f64 {
    let count = |d: &Drawing| d.polylines.iter().map(|p| p.points.len()).sum::<usize>();
    let (na, nb) = (count(a), count(b));
    if na == 0 && nb == 0 {
        return 0.0;
    }
    let (fa, fb) = (finite_points(a).count(), finite_points(b).count());
    if na == 0 || nb == 0 || fa < na || fb < nb {
        return f64::INFINITY;
    }
    directed_hausdorff(a, b).max(directed_hausdorff(b, a))
}

/// The largest distance from a vertex of `from` to the nearest vertex of `to` (both
/// nonempty, with finite coordinates).
fn directed_hausdorff(from: &Drawing, to: &Drawing) -> f64 {
    let tree = RTree::bulk_load(finite_points(to).collect());
    finite_points(from)
        .map(|p| {
            tree.nearest_neighbor(&p)
                .map_or(f64::INFINITY, |q| (p[0] - q[0]).hypot(p[1] - q[1]))
        })
        .fold(0.0, f64::max)
}

/// The ends that differ between the drawings: at each point where segments end (points
/// within the tolerance of each other are one point), the number of visible segment ends and
/// the number of hidden ones are counted in each drawing, and their differences summed. An
/// interior vertex of a polyline is two ends (of its two segments), so a drawing chained
/// into long polylines and one drawn run by run count alike; a visibility change moved, a
/// run split or merged where the other drawing does not, a line ending short, all count.
fn wrong_ends(a: &Drawing, b: &Drawing, tolerance: f64) -> usize {
    // Every segment end: (point, drawing, visible).
    let mut ends: Vec<([f64; 2], usize, bool)> = Vec::new();
    for (k, d) in [a, b].into_iter().enumerate() {
        for line in &d.polylines {
            for w in line.points.windows(2) {
                for p in [w[0], w[1]] {
                    if p[0].is_finite() && p[1].is_finite() {
                        ends.push((p, k, line.visible));
                    }
                }
            }
        }
    }
    let tree = RTree::bulk_load(
        ends.iter()
            .enumerate()
            .map(|(i, e)| GeomWithData::new(e.0, i))
            .collect::<Vec<GeomWithData<[f64; 2], usize>>>(),
    );
    // Points within the tolerance of each other, transitively, are one point.
    let mut cluster = vec![usize::MAX; ends.len()];
    let mut wrong = 0usize;
    for start in 0..ends.len() {
        if cluster[start] != usize::MAX {
            continue;
        }
        cluster[start] = start;
        let mut counts = [[0i64; 2]; 2];
        let mut stack = vec![start];
        while let Some(i) = stack.pop() {
            let (p, k, visible) = ends[i];
            counts[k][usize::from(visible)] += 1;
            for near in tree.locate_within_distance(p, tolerance * tolerance) {
                if cluster[near.data] == usize::MAX {
                    cluster[near.data] = start;
                    stack.push(near.data);
                }
            }
        }
        let [a, b] = counts;
        wrong += (a[0].abs_diff(b[0]) + a[1].abs_diff(b[1])) as usize;
    }
    wrong
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::{Point3, Vector3};
    use crate::hidden::{EdgeClass, EdgeSelection, Options, Polyline, draw};
    use crate::views::View;

    fn line(visible: bool, points: &[[f64; 2]]) -> Polyline {
        Polyline {
            class: EdgeClass::Crease,
            visible,
            points: points.to_vec(),
        }
    }

    fn drawing(polylines: Vec<Polyline>) -> Drawing {
        Drawing {
            polylines,
            stages: Vec::new(),
        }
    }

    fn all_zero(e: &ErrorFigures) {
        assert!(e.is_exact(), "{e:?}");
        assert_eq!(
            (e.misclassified(), e.wrong_length(), e.relative()),
            (0.0, 0.0, 0.0),
            "{e:?}"
        );
        assert_eq!(e.hausdorff_ulps, 0.0, "{e:?}");
    }

    #[test]
    fn half_hidden() {
        let exact = drawing(vec![line(true, &[[0.0, 0.0], [10.0, 0.0]])]);
        let variant = drawing(vec![
            line(true, &[[0.0, 0.0], [5.0, 0.0]]),
            line(false, &[[5.0, 0.0], [10.0, 0.0]]),
        ]);
        let e = compare(&exact, &variant, 0.0);
        assert_eq!(e.exact_length, 10.0);
        assert_eq!((e.visible_as_hidden, e.hidden_as_visible), (5.0, 0.0));
        assert_eq!((e.missing, e.extra), (0.0, 0.0));
        // The variant's vertex at (5, 0), where its visibility changes, is 5 from the nearest
        // exact vertex.
        assert_eq!(e.hausdorff, 5.0);
        assert_eq!(e.relative(), 0.5);
        // Unmatched: the variant's visible end at (5, 0) and its hidden ends at (5, 0) and
        // (10, 0); the exact visible end at (10, 0).
        assert_eq!((e.wrong_ends, e.runs), (4, [1, 2]));
        // With a tolerance r, the visible run's capsule reaches r past (5, 0): that much of
        // the hidden half counts as covered by both, so as not misclassified.
        let r = 0.25;
        let e = compare(&exact, &variant, r);
        assert!((e.visible_as_hidden - (5.0 - r)).abs() < 1e-12, "{e:?}");
        // Back: the hidden half of an exact hidden line drawn visible.
        let exact = drawing(vec![line(false, &[[0.0, 0.0], [10.0, 0.0]])]);
        let e = compare(&exact, &variant, 0.0);
        assert_eq!((e.visible_as_hidden, e.hidden_as_visible), (0.0, 5.0));
    }

    #[test]
    fn missing_and_extra_segments() {
        let one = drawing(vec![line(true, &[[0.0, 0.0], [10.0, 0.0]])]);
        let two = drawing(vec![
            line(true, &[[0.0, 0.0], [10.0, 0.0]]),
            line(false, &[[0.0, 5.0], [3.0, 9.0]]),
        ]);
        let e = compare(&two, &one, 0.5);
        assert_eq!((e.exact_length, e.missing, e.extra), (15.0, 5.0, 0.0));
        assert_eq!((e.misclassified(), e.wrong_ends), (0.0, 2));
        assert!((e.hausdorff - 90f64.sqrt()).abs() < 1e-12, "{e:?}");
        assert_eq!(e.relative(), 5.0 / 15.0);
        let e = compare(&one, &two, 0.5);
        assert_eq!((e.exact_length, e.missing, e.extra), (10.0, 0.0, 5.0));
        assert_eq!((e.misclassified(), e.wrong_ends), (0.0, 2));
        assert_eq!(e.relative(), 0.5);
    }

    #[test]
    fn shifted_segment() {
        let exact = drawing(vec![line(true, &[[0.0, 0.0], [10.0, 0.0]])]);
        let variant = drawing(vec![line(true, &[[0.0, 3.0], [10.0, 3.0]])]);
        let e = compare(&exact, &variant, 0.5);
        assert_eq!((e.missing, e.extra, e.misclassified()), (10.0, 10.0, 0.0));
        assert_eq!((e.hausdorff, e.wrong_ends), (3.0, 4));
        // The largest exact coordinate is 10, whose ulp is 2^-49.
        assert_eq!(e.hausdorff_ulps, 3.0 * 2f64.powi(49));
    }

    #[test]
    fn shift_below_tolerance() {
        let exact = drawing(vec![
            line(true, &[[0.0, 0.0], [10.0, 0.0], [10.0, 10.0]]),
            line(false, &[[10.0, 10.0], [0.0, 0.0]]),
        ]);
        let shift = [3e-6, -4e-6];
        let variant = drawing(
            exact
                .polylines
                .iter()
                .map(|p| Polyline {
                    points: p
                        .points
                        .iter()
                        .map(|q| [q[0] + shift[0], q[1] + shift[1]])
                        .collect(),
                    ..p.clone()
                })
                .collect(),
        );
        let e = compare(&exact, &variant, 1e-5);
        assert_eq!((e.visible_as_hidden, e.hidden_as_visible), (0.0, 0.0));
        assert_eq!((e.missing, e.extra, e.wrong_ends), (0.0, 0.0, 0));
        assert!((e.hausdorff - 5e-6).abs() < 1e-15, "{e:?}");
        assert!(e.hausdorff_ulps > 0.0 && !e.is_exact());
    }

    #[test]
    fn split_run() {
        let exact = drawing(vec![line(true, &[[0.0, 0.0], [10.0, 0.0]])]);
        let variant = drawing(vec![
            line(true, &[[0.0, 0.0], [5.0, 0.0]]),
            line(true, &[[5.0, 0.0], [10.0, 0.0]]),
        ]);
        let e = compare(&exact, &variant, default_tolerance(&exact));
        assert_eq!(e.wrong_length(), 0.0);
        assert_eq!((e.hausdorff, e.wrong_ends, e.runs), (5.0, 2, [1, 2]));
    }

    #[test]
    fn chaining_does_not_count() {
        // Two edges meeting at (5, 0), chained into one polyline or drawn apart.
        let exact = drawing(vec![line(true, &[[0.0, 0.0], [5.0, 0.0], [5.0, 4.0]])]);
        let variant = drawing(vec![
            line(true, &[[5.0, 4.0], [5.0, 0.0]]),
            line(true, &[[0.0, 0.0], [5.0, 0.0]]),
        ]);
        all_zero(&compare(&exact, &variant, default_tolerance(&exact)));
    }

    #[test]
    fn crossing_segments_do_not_cover() {
        let exact = drawing(vec![line(true, &[[0.0, 0.0], [16.0, 0.0]])]);
        let variant = drawing(vec![line(true, &[[8.0, -8.0], [8.0, 8.0]])]);
        // Each covers the other on [7.75, 8.25], within 0.25 of the crossing.
        let e = compare(&exact, &variant, 0.25);
        assert_eq!((e.missing, e.extra, e.misclassified()), (15.5, 15.5, 0.0));
        assert_eq!(e.wrong_ends, 4);
    }

    #[test]
    fn reversed_and_reordered() {
        let exact = drawing(vec![
            line(true, &[[0.1, 0.3], [10.7, 0.2], [10.0, 10.9], [0.1, 0.3]]),
            line(false, &[[0.3, 0.7], [5.1, -3.3]]),
            line(true, &[[0.3, 0.7], [-2.9, 1.0 / 3.0], [7.0, 1e-3]]),
        ]);
        let mut variant = exact.clone();
        variant.polylines.reverse();
        for p in &mut variant.polylines {
            p.points.reverse();
        }
        for tolerance in [0.0, 1e-12, default_tolerance(&exact), 0.5] {
            all_zero(&compare(&exact, &variant, tolerance));
            all_zero(&compare(&variant, &exact, tolerance));
        }
    }

    #[test]
    fn closed_runs_have_no_ends() {
        let square = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0], [0.0, 0.0]];
        let rotated = [[1.0, 1.0], [0.0, 1.0], [0.0, 0.0], [1.0, 0.0], [1.0, 1.0]];
        let e = compare(
            &drawing(vec![line(true, &square)]),
            &drawing(vec![line(true, &rotated)]),
            0.0,
        );
        all_zero(&e);
    }

    #[test]
    fn empty_and_degenerate() {
        let empty = drawing(Vec::new());
        let one = drawing(vec![line(false, &[[1.0, 2.0], [1.0, 2.0], [4.0, 6.0]])]);
        let e = compare(&empty, &one, 0.0);
        assert_eq!(
            (e.extra, e.hausdorff, e.hausdorff_ulps),
            (5.0, f64::INFINITY, f64::INFINITY)
        );
        assert_eq!(e.relative(), f64::INFINITY);
        let e = compare(&one, &empty, 0.0);
        assert_eq!(
            (e.exact_length, e.missing, e.hausdorff),
            (5.0, 5.0, f64::INFINITY)
        );
        all_zero(&compare(&one, &one, f64::NAN));
        all_zero(&compare(&one, &one, -1.0));
        let broken = drawing(vec![line(true, &[[0.0, 0.0], [f64::NAN, 1.0]])]);
        let e = compare(&one, &broken, 0.1);
        assert_eq!((e.extra, e.hausdorff), (f64::INFINITY, f64::INFINITY));
        assert_eq!((e.misclassified(), e.missing), (0.0, 5.0));
        let e = compare(&broken, &one, 0.1);
        assert_eq!((e.exact_length, e.missing), (f64::INFINITY, f64::INFINITY));
        assert_eq!((e.misclassified(), e.extra), (0.0, 5.0));
        assert_eq!(default_tolerance(&empty), 16.0 * f64::from_bits(1));
        let point = drawing(vec![line(true, &[[1.0, 1.0], [1.0, 1.0]])]);
        assert_eq!(default_tolerance(&point), 16.0 * 2f64.powi(-52));
        assert_eq!(default_tolerance(&one), 5.0 * 2f64.powi(-40));
    }

    /// A real drawing against itself and against its reversal: every figure exactly 0.
    #[test]
    fn self_comparison_of_drawings() {
        let options = Options {
            edges: EdgeSelection::All,
            ..Default::default()
        };
        let orthographic = |x, y, z| View::orthographic(Vector3::new(x, y, z), Vector3::z());
        let cases = [
            ("polyhedra", orthographic(1.0, 2.0, -3.0)),
            ("polyhedra", orthographic(-1.0, -2.0, -1.5)),
            ("polyhedra", orthographic(0.3, -0.7, 0.2)),
            (
                "polyhedra",
                View::perspective(
                    Point3::new(20.0, -15.0, 10.0),
                    Point3::new(20.0, 5.0, 0.0),
                    Vector3::z(),
                    60.0,
                ),
            ),
            ("solids", orthographic(-1.0, -2.0, -3.0)),
        ];
        for (name, view) in cases {
            let path = format!("scenes/{name}.toml");
            let scene = crate::scene::file::load(path.as_ref()).unwrap();
            let exact = draw(&scene, &view.unwrap(), &options).unwrap();
            assert!(exact.polylines.iter().any(|p| p.visible));
            assert!(exact.polylines.iter().any(|p| !p.visible));
            let tolerance = default_tolerance(&exact);
            let e = compare(&exact, &exact, tolerance);
            all_zero(&e);
            assert!(e.exact_length > 0.0);
            assert_eq!(e.runs[0], exact.polylines.len());
            let mut reversed = exact.clone();
            reversed.polylines.reverse();
            for p in &mut reversed.polylines {
                p.points.reverse();
            }
            all_zero(&compare(&exact, &reversed, tolerance));
            // Hiding one visible run shows as exactly its length drawn hidden.
            let mut one_hidden = exact.clone();
            let k = one_hidden.polylines.iter().position(|p| p.visible).unwrap();
            one_hidden.polylines[k].visible = false;
            let e = compare(&exact, &one_hidden, tolerance);
            let length = exact.polylines[k].length();
            assert!(e.visible_as_hidden <= length, "{e:?}");
            assert!(e.visible_as_hidden > 0.5 * length, "{e:?}");
            assert_eq!((e.hidden_as_visible, e.missing, e.extra), (0.0, 0.0, 0.0));
        }
    }
}
