//! Boolean operations on polygons (intersection, difference, union), exact to a fraction of an
//! ulp of the largest input coordinate.
//!
//! The only module that knows the clipping engine: everything else sees geo's
//! [`MultiPolygon<f64>`], so the engine can be swapped here alone.
//!
//! # Engine
//!
//! [i_overlay](https://docs.rs/i_overlay) 9, used directly with its `i64` integer engine
//! (`FloatOverlay::<[f64; 2], i64>`, with the float-to-integer adapter chosen here). Not geo's
//! `BooleanOps`: geo 0.33 runs i_overlay 4.5 on its `i32` engine, about 2³⁰ grid steps across
//! the inputs, and moves vertices by up to about 1e-8 of the inputs' size (measured in
//! `tests/clip.rs`); the `i64` grid is finer than `f64` itself.
//!
//! # Coordinates and exactness
//!
//! Let `M` be the largest coordinate magnitude of both operands, and `ulp(M)` the spacing of
//! `f64` values at `M`. Every coordinate `x` becomes the integer `round(x · 2ᵏ)`, where `2ᵏ`
//! is the largest power of two with `M · 2ᵏ ≤ 2⁶¹` (the engine keeps 3 of the 64 bits for
//! differences and products; there is no translation). The grid step `h = 2⁻ᵏ` is at most
//! `ulp(M) / 256`, so:
//! - an input vertex comes back bit-identical, unless a coordinate is below `M / 256` in
//!   magnitude and finer than the grid: then it moves by at most `h / 2 ≤ ulp(M) / 512`;
//! - a vertex where two edges cross is the exact crossing rounded to the grid (the engine
//!   divides in 128-bit integers), then to the nearest `f64`: off by at most `ulp(M) / 2`,
//!   plus a few `h` where the engine snaps a crossing onto a nearby vertex to keep the
//!   rounded edges from crossing again.
//!
//! The bound is in ulps of `M`, not of the vertex: a vertex much closer to the origin than `M`
//! is only as exact as `ulp(M)`. Full precision needs `M > 2⁻⁹⁶³` (about 1.3e-290): below, `2ᵏ` stops at 2¹⁰²³ and
//! the grid step at 2⁻¹⁰²³.
//!
//! # Polygons
//!
//! Each operand is filled by the even-odd rule: a point is inside if it is enclosed by an odd
//! number of rings of that operand. Ring orientation and the closing vertex do not matter; a
//! valid geo polygon (holes inside its exterior, members with disjoint interiors) means what
//! it says, a self-crossing ring alternates inside and outside, and two overlapping members
//! of one operand cancel where they overlap (unite them first with [`union`]).
//!
//! The result follows geo's convention: exteriors counter-clockwise, holes clockwise, rings
//! closed, no repeated vertices and no vertex between two collinear edges. Two result pieces
//! may touch at a vertex; pieces of zero area (a shared edge, a touching vertex) are dropped.
//!
//! ```
//! use geo::{Area, MultiPolygon, polygon};
//! use kepler::clip;
//! let square: MultiPolygon<f64> =
//!     polygon![(x: 0.0, y: 0.0), (x: 1.0, y: 0.0), (x: 1.0, y: 1.0), (x: 0.0, y: 1.0)].into();
//! let wedge: MultiPolygon<f64> = polygon![(x: -1.0, y: 0.0), (x: 2.0, y: 1.0), (x: -1.0, y: 1.0)].into();
//! let top = clip::intersection(&square, &wedge)?;
//! // The wedge's lower edge crosses the square's sides at y = 1/3 and y = 2/3: both come out
//! // as the nearest f64.
//! let ring = top.0[0].exterior();
//! assert!(ring.coords().any(|c| (c.x, c.y) == (0.0, 1.0 / 3.0)));
//! assert!(ring.coords().any(|c| (c.x, c.y) == (1.0, 2.0 / 3.0)));
//! assert!((top.unsigned_area() - 0.5).abs() < 1e-15);
//! let bottom = clip::difference(&square, &wedge)?;
//! assert!((bottom.unsigned_area() - 0.5).abs() < 1e-15);
//! assert!((clip::union(&square, &wedge)?.unsigned_area() - 2.0).abs() < 1e-15);
//! # Ok::<(), clip::ClipError>(())
//! ```

use crate::geometry::exact::{product_terms, sum_sign};
use crate::geometry::predicates::orient2d;
use geo::{Coord, LineString, MultiPolygon, Polygon};
use i_overlay::core::fill_rule::FillRule;
use i_overlay::core::overlay::ShapeType;
use i_overlay::core::overlay_rule::OverlayRule;
use i_overlay::float::overlay::FloatOverlay;
use i_overlay::i_float::adapter::FloatPointAdapter;
use i_overlay::i_float::float::rect::FloatRect;
use std::cmp::Ordering;

/// Coordinates the engine cannot take; nothing is computed.
///
/// ```
/// use geo::{MultiPolygon, polygon};
/// use kepler::clip::{self, ClipError};
/// let bad: MultiPolygon<f64> =
///     polygon![(x: 0.0, y: 0.0), (x: f64::NAN, y: 0.0), (x: 0.0, y: 1.0)].into();
/// assert_eq!(clip::union(&bad, &MultiPolygon::new(vec![])), Err(ClipError::NotFinite));
/// assert_eq!(ClipError::TooLarge.to_string(), "polygon coordinates must be at most 2^500 in magnitude");
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, thiserror::Error)]
pub enum ClipError {
    /// A coordinate is NaN or infinite.
    #[error("polygon coordinates must be finite numbers")]
    NotFinite,
    /// A coordinate exceeds 2⁵⁰⁰ (about 3.3e150) in magnitude, i_overlay's limit.
    #[error("polygon coordinates must be at most 2^500 in magnitude")]
    TooLarge,
}

/// The points in both `a` and `b` (even-odd fill of each; see the [module](self) for the
/// conventions and the error bound).
///
/// ```
/// use geo::{Area, MultiPolygon, polygon};
/// use kepler::clip;
/// let a: MultiPolygon<f64> = polygon![(x: 0.0, y: 0.0), (x: 4.0, y: 0.0), (x: 0.0, y: 4.0)].into();
/// let b: MultiPolygon<f64> = polygon![(x: 1.0, y: 1.0), (x: 5.0, y: 1.0), (x: 1.0, y: 5.0)].into();
/// let ab = clip::intersection(&a, &b)?;
/// assert_eq!(ab.unsigned_area(), 2.0);
/// assert!(clip::intersection(&a, &MultiPolygon::new(vec![]))?.0.is_empty());
/// # Ok::<(), clip::ClipError>(())
/// ```
pub fn intersection(
    a: &MultiPolygon<f64>,
    b: &MultiPolygon<f64>,
) -> Result<MultiPolygon<f64>, ClipError> {
    overlay(a, b, OverlayRule::Intersect)
}

/// The points in `a` but not in `b` (even-odd fill of each; see the [module](self) for the
/// conventions and the error bound).
///
/// ```
/// use geo::{MultiPolygon, polygon};
/// use kepler::clip;
/// let outer: MultiPolygon<f64> =
///     polygon![(x: 0.0, y: 0.0), (x: 3.0, y: 0.0), (x: 3.0, y: 3.0), (x: 0.0, y: 3.0)].into();
/// let inner: MultiPolygon<f64> =
///     polygon![(x: 1.0, y: 1.0), (x: 2.0, y: 1.0), (x: 2.0, y: 2.0), (x: 1.0, y: 2.0)].into();
/// let ring = clip::difference(&outer, &inner)?;
/// assert_eq!(ring.0.len(), 1);
/// assert_eq!(ring.0[0].interiors().len(), 1);
/// assert!(clip::difference(&inner, &outer)?.0.is_empty());
/// # Ok::<(), clip::ClipError>(())
/// ```
pub fn difference(
    a: &MultiPolygon<f64>,
    b: &MultiPolygon<f64>,
) -> Result<MultiPolygon<f64>, ClipError> {
    overlay(a, b, OverlayRule::Difference)
}

/// The points in `a` or in `b` (even-odd fill of each; see the [module](self) for the
/// conventions and the error bound).
///
/// ```
/// use geo::{MultiPolygon, polygon};
/// use kepler::clip;
/// let left: MultiPolygon<f64> =
///     polygon![(x: 0.0, y: 0.0), (x: 1.0, y: 0.0), (x: 1.0, y: 1.0), (x: 0.0, y: 1.0)].into();
/// let right: MultiPolygon<f64> =
///     polygon![(x: 1.0, y: 0.0), (x: 2.0, y: 0.0), (x: 2.0, y: 1.0), (x: 1.0, y: 1.0)].into();
/// let both = clip::union(&left, &right)?;
/// // One rectangle: the shared edge and its collinear vertices are gone.
/// assert_eq!(both.0.len(), 1);
/// assert_eq!(both.0[0].exterior().0.len(), 5);
/// # Ok::<(), clip::ClipError>(())
/// ```
pub fn union(a: &MultiPolygon<f64>, b: &MultiPolygon<f64>) -> Result<MultiPolygon<f64>, ClipError> {
    overlay(a, b, OverlayRule::Union)
}

/// The points in `a` but in none of `pieces`, in one operation: `a` (one simple ring or a
/// valid polygon) minus the union of the pieces, where each piece is a simple ring (no holes)
/// in either orientation and pieces may overlap. One operation means one rounding: where
/// pieces share edges with each other or with `a` (equal coordinates), nothing of them is
/// left between them, however many there are. Pieces of zero area are ignored.
///
/// ```
/// use geo::{MultiPolygon, polygon};
/// use kepler::clip;
/// let square: MultiPolygon<f64> =
///     polygon![(x: 0.0, y: 0.0), (x: 3.0, y: 0.0), (x: 3.0, y: 3.0), (x: 0.0, y: 3.0)].into();
/// // Three strips, one clockwise, covering the square between them: nothing is left.
/// let strip = |x0: f64, x1: f64| -> MultiPolygon<f64> {
///     polygon![(x: x0, y: -1.0), (x: x1, y: -1.0), (x: x1, y: 4.0), (x: x0, y: 4.0)].into()
/// };
/// let cw: MultiPolygon<f64> =
///     polygon![(x: 2.0, y: -1.0), (x: 2.0, y: 4.0), (x: 4.0, y: 4.0), (x: 4.0, y: -1.0)].into();
/// let pieces = [strip(-1.0, 1.0), strip(1.0, 2.0), cw];
/// assert!(clip::difference_of_union(&square, &pieces)?.0.is_empty());
/// assert_eq!(clip::difference_of_union(&square, &pieces[..2])?.0.len(), 1);
/// # Ok::<(), clip::ClipError>(())
/// ```
pub fn difference_of_union(
    a: &MultiPolygon<f64>,
    pieces: &[MultiPolygon<f64>],
) -> Result<MultiPolygon<f64>, ClipError> {
    let subject = rings(a);
    // Every piece counter-clockwise, so that the non-zero rule fills their union.
    let clip: Vec<Vec<[f64; 2]>> = pieces
        .iter()
        .flat_map(rings)
        .filter_map(|mut ring| {
            // The exact sign of twice the signed area (the shoelace sum, as exact products).
            let mut terms = Vec::with_capacity(4 * ring.len());
            for i in 0..ring.len() {
                let (p, q) = (ring[i], ring[(i + 1) % ring.len()]);
                product_terms(&[p[0]], &[q[1]], &mut terms);
                product_terms(&[-q[0]], &[p[1]], &mut terms);
            }
            match sum_sign(&terms) {
                Ordering::Equal => None,
                Ordering::Less => {
                    ring.reverse();
                    Some(ring)
                }
                Ordering::Greater => Some(ring),
            }
        })
        .collect();
    run(subject, clip, OverlayRule::Difference, FillRule::NonZero)
}

/// Runs one operation on the `i64` engine, on a grid centred on the origin whose scale fits
/// the largest coordinate magnitude.
fn overlay(
    a: &MultiPolygon<f64>,
    b: &MultiPolygon<f64>,
    rule: OverlayRule,
) -> Result<MultiPolygon<f64>, ClipError> {
    run(rings(a), rings(b), rule, FillRule::EvenOdd)
}

/// [`overlay`] on rings, with a fill rule.
fn run(
    subject: Vec<Vec<[f64; 2]>>,
    clip: Vec<Vec<[f64; 2]>>,
    rule: OverlayRule,
    fill: FillRule,
) -> Result<MultiPolygon<f64>, ClipError> {
    let mut max = 0.0_f64;
    for p in subject.iter().chain(&clip).flatten() {
        if !(p[0].is_finite() && p[1].is_finite()) {
            return Err(ClipError::NotFinite);
        }
        max = max.max(p[0].abs()).max(p[1].abs());
    }
    // A square symmetric about the origin: the adapter translates by its centre, 0, and picks
    // the power of two 2^k with max · 2^k ≤ 2^61. Finite coordinates fail only beyond 2^500.
    let bounds = FloatRect::new(-max, max, -max, max).map_err(|_| ClipError::TooLarge)?;
    let adapter = FloatPointAdapter::<[f64; 2], i64>::new_conservative(bounds);
    let capacity = subject.iter().chain(&clip).map(Vec::len).sum();
    // Default options: no collinear vertices, outer rings counter-clockwise, and the float
    // result cleaned of vertices that rounding to f64 made equal or collinear.
    let shapes = FloatOverlay::with_adapter(adapter, capacity)
        .unsafe_add_source(&subject, ShapeType::Subject)
        .unsafe_add_source(&clip, ShapeType::Clip)
        .overlay(rule, fill);
    Ok(shapes
        .into_iter()
        .filter_map(|shape| {
            let mut rings = shape.into_iter().map(without_collinear);
            let exterior = rings.next().flatten()?;
            Some(Polygon::new(
                line_string(&exterior),
                rings.flatten().map(|hole| line_string(&hole)).collect(),
            ))
        })
        .collect())
}

/// The ring without the vertices that rounding to `f64` left exactly collinear with their
/// neighbours (spikes along an edge, or points in the middle of one; exact `orient2d`, so only
/// zero area goes), `None` when fewer than three remain (a ring of zero area).
fn without_collinear(mut ring: Vec<[f64; 2]>) -> Option<Vec<[f64; 2]>> {
    let mut i = 0;
    let mut kept = 0;
    // Walk round until a whole turn keeps every vertex, removing as we go.
    while ring.len() >= 3 && kept < ring.len() {
        let n = ring.len();
        let (prev, next) = (ring[(i + n - 1) % n], ring[(i + 1) % n]);
        if collinear(prev, ring[i], next) {
            ring.remove(i);
            kept = 0;
            if i >= ring.len() {
                i = 0;
            }
        } else {
            kept += 1;
            i = (i + 1) % n;
        }
    }
    (ring.len() >= 3).then_some(ring)
}

/// Every ring of `polygons` as an open path (without the closing vertex), the engine's form.
fn rings(polygons: &MultiPolygon<f64>) -> Vec<Vec<[f64; 2]>> {
    polygons
        .iter()
        .flat_map(|polygon| std::iter::once(polygon.exterior()).chain(polygon.interiors()))
        .map(|ring| {
            let mut path: Vec<[f64; 2]> = ring.coords().map(|c| [c.x, c.y]).collect();
            if path.len() > 1 && path.first() == path.last() {
                path.pop();
            }
            path
        })
        .collect()
}

/// Whether three points are collinear, exactly. Coordinates below 1 are first scaled up by a
/// power of two (exact, no overflow), so that the predicate's products cannot underflow.
fn collinear(a: [f64; 2], b: [f64; 2], c: [f64; 2]) -> bool {
    let m = [a, b, c]
        .iter()
        .flatten()
        .fold(0.0f64, |m, v| m.max(v.abs()));
    if m == 0.0 {
        return true;
    }
    let [a, b, c] = if m < 1.0 {
        // Two steps, so that even a subnormal maximum reaches [1, 2) without overflow.
        let e = -(m.log2().floor() as i32);
        let (s, t) = (2f64.powi(e / 2), 2f64.powi(e - e / 2));
        [a, b, c].map(|p| p.map(|v| v * s * t))
    } else {
        [a, b, c]
    };
    orient2d(a, b, c) == Ordering::Equal
}

/// An engine path as a geo ring (closed by [`Polygon::new`]).
fn line_string(path: &[[f64; 2]]) -> LineString<f64> {
    path.iter().map(|&[x, y]| Coord { x, y }).collect()
}
