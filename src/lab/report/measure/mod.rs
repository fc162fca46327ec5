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

mod coverage;
mod ends;
mod placement;
#[cfg(test)]
mod tests;

use crate::hidden::Drawing;
use coverage::{Cover, gaps, segment_tree, segments};
use ends::wrong_ends;
use placement::{finite_points, hausdorff, largest_magnitude, ulp};
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
