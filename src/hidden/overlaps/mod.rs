//! Lines drawn once: a drawing without two pieces that overlap along a length, decided
//! exactly.
//!
//! The pass draws every edge of every object, so where two objects touch along an edge
//! (stacked boxes, a part standing on a plate's rim), where a face's side meets another's at a
//! T-junction, or where a line lies right behind a contour in the picture (both in one plane
//! of sight), two pieces of the drawing run along the same stretch of one picture line. A
//! screen shows them as one; a pen plotter draws the stretch twice, and a dashed hidden line
//! drawn under a visible one shows through its gaps. With [`Overlaps::Once`](super::Overlaps)
//! each stretch is drawn once:
//!
//! - of the pieces covering a stretch, the one drawn on top wins: visible over hidden, then
//!   the later class in [`EdgeClass::ALL`] (silhouette over boundary over intersection over
//!   crease over smooth), which is what the SVG shows there otherwise;
//! - pieces that touch at a point or cross are not overlaps and are left alone.
//!
//! # Every decision from what the pieces are
//!
//! A piece lies on a support (an input edge's line, or the meet line of two input planes)
//! and its ends are points defined from the input (see [`super::marks`] and
//! [`crate::sight::collinear`]); the rounded pictures are never asked whether two pieces
//! are collinear or which end comes first. So the same pieces are removed wherever the scene
//! is placed, at every power-of-two scale, mirrored, permuted or with its faces reversed.
//!
//! 1. **Supports on one picture line** ([`lines`]). Each line with pieces gets an angle and
//!    an offset of its picture from the rounded ends of its pieces, with certified error
//!    bounds; lines whose intervals overlap in both are candidates, found by two sorts (a
//!    crowd of lines through one point, a cone seen head-on, has distinct angles and meets no
//!    other). Candidates are then grouped exactly: two supports have one picture line when
//!    the points that define one lie in the other's plane of sight. Lines too short for the
//!    bounds (a picture of a few units in the last place) are compared, exactly, with the
//!    lines whose pieces pass near them.
//! 2. **A sweep along each group** ([`sweep`]). The ends of the group's pieces are sorted
//!    along the picture line exactly (the turn of their lines of sight; a certified filter on
//!    the rounded pictures decides all but near ties), equal points taken together. The line
//!    falls into runs covered by pieces without a gap; in a run covered twice somewhere, each
//!    stretch between consecutive points goes to the highest rank covering it and
//!    consecutive stretches of one rank are joined; a run never covered twice is left as it
//!    was. No point is made: where several ends are one exact point, the one named by the
//!    smallest [`MarkKey`](super::marks::MarkKey) is drawn.
//!
//! Cost: the sorts of step 1 (`n log n` in the lines, nothing quadratic in a crowded point),
//! then `m log m` exact comparisons, nearly all decided by the filter, in a group of `m`
//! pieces. The pieces left out of every group keep their order; each changed group's pieces
//! follow them, groups in the order of their first line, stretches along the line.
//!
//! ```
//! use kepler::{scene::Scene, views::View, hidden::{EdgeClass, Options, Overlaps, draw}};
//! use kepler::geometry::{Point3, Vector3};
//! let mut scene = Scene::new();
//! // Two boxes side by side, seen from the front: their shared edge is drawn by both.
//! let boxed = |x: f64| {
//!     let mesh = kepler::solids::cube(1.0).unwrap();
//!     let v = mesh.vertices().iter().map(|p| p + Vector3::new(x, 0.0, 0.0)).collect();
//!     let faces = mesh.faces().iter().map(|f| f.vertices().to_vec()).collect();
//!     kepler::mesh::Mesh::from_polygons(v, faces).unwrap()
//! };
//! scene.add_mesh(None, "left", boxed(0.0)).unwrap();
//! scene.add_mesh(None, "right", boxed(1.0)).unwrap();
//! let view = View::orthographic(Vector3::new(0.0, -1.0, 0.0), Vector3::z()).unwrap();
//! let kept = draw(&scene, &view, &Options::default()).unwrap();
//! let once = draw(&scene, &view, &Options { overlaps: Overlaps::Once, ..Options::default() }).unwrap();
//! // The outline is the same; the shared edge, a crease of each box, is drawn once.
//! let length = |d: &kepler::hidden::Drawing| d.length(EdgeClass::Silhouette, true) + d.length(EdgeClass::Crease, true);
//! assert_eq!(length(&kept) - length(&once), 1.0);
//! ```

mod lines;
mod sweep;
#[cfg(test)]
mod tests;

use super::EdgeClass;
use super::marks::Provenance;
use super::piece::Piece;
use rayon::prelude::*;
use std::ops::Range;

/// What removing overlaps found and removed.
///
/// ```
/// let r = kepler::hidden::OverlapReport::default();
/// assert_eq!((r.groups, r.segments, r.removed_length), (0, 0, 0.0));
/// ```
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct OverlapReport {
    /// Groups of pieces on one picture line of which some overlap.
    pub groups: usize,
    /// Pieces in those groups (each drawn, after the sweep, only where it wins).
    pub segments: usize,
    /// Length of line no longer drawn twice or more (view coordinates).
    pub removed_length: f64,
}

/// The drawing order of a class and visibility: hidden below visible, then
/// [`EdgeClass::ALL`]'s order.
fn rank(class: EdgeClass, visible: bool) -> usize {
    let position = EdgeClass::ALL.iter().position(|&c| c == class).unwrap_or(0);
    usize::from(visible) * EdgeClass::ALL.len() + position
}

/// The class and visibility of a rank.
fn unranked(rank: usize) -> (EdgeClass, bool) {
    let n = EdgeClass::ALL.len();
    (EdgeClass::ALL[rank % n], rank >= n)
}

/// The pieces of one line: its index in the provenance, and their range in the list.
#[derive(Debug, Clone)]
struct Span {
    line: usize,
    pieces: Range<usize>,
}

/// The pieces with each stretch of a picture line drawn once (see the module documentation),
/// and what was removed. The pieces must come grouped by line, in order along it. Pieces
/// made by the sweep lie on a line of their group (`line`) but carry no parameters.
pub(crate) fn drawn_once<P: Provenance>(
    provenance: &P,
    pieces: Vec<Piece>,
) -> (Vec<Piece>, OverlapReport) {
    let spans = spans(&pieces);
    let groups = lines::groups(provenance, &spans, &pieces);
    let found: Vec<Vec<sweep::Overlap>> = groups
        .par_iter()
        .map(|group| sweep::sweep(provenance, group, &spans, &pieces))
        .collect();
    let mut report = OverlapReport::default();
    let mut replaced = vec![false; pieces.len()];
    let mut made = Vec::new();
    for overlap in found.into_iter().flatten() {
        report.groups += 1;
        let mut length = 0.0;
        for &k in &overlap.pieces {
            replaced[k] = true;
            report.segments += 1;
            length += distance(pieces[k].ends);
        }
        report.removed_length +=
            length - overlap.drawn.iter().map(|p| distance(p.ends)).sum::<f64>();
        made.extend(overlap.drawn);
    }
    if report.groups == 0 {
        return (pieces, report);
    }
    let mut pieces = pieces;
    let mut k = 0;
    pieces.retain(|_| {
        k += 1;
        !replaced[k - 1]
    });
    pieces.extend(made);
    (pieces, report)
}

/// The pieces' lines, each with its run of pieces (the pieces come grouped by line).
fn spans(pieces: &[Piece]) -> Vec<Span> {
    let mut spans: Vec<Span> = Vec::new();
    for (k, p) in pieces.iter().enumerate() {
        match spans.last_mut() {
            Some(s) if s.line == p.line && s.pieces.end == k => s.pieces.end = k + 1,
            _ => spans.push(Span {
                line: p.line,
                pieces: k..k + 1,
            }),
        }
    }
    spans
}

/// The length of a segment.
fn distance(s: [[f64; 2]; 2]) -> f64 {
    (s[1][0] - s[0][0]).hypot(s[1][1] - s[0][1])
}

/// A bound on the distance of a rounded picture point from the exact one (within two units in
/// the last place of its larger coordinate, padded), plus the provenance's slack.
fn rounding(p: [f64; 2], slack: f64) -> f64 {
    8.0 * f64::EPSILON * p[0].abs().max(p[1].abs()) + slack + 4.0 * f64::MIN_POSITIVE
}
