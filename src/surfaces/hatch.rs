//! Hatching: visible faces filled with parallel lines, clipped exactly by their visible
//! polygons (VISFAC), so that a hatch never crosses a hidden surface.
//!
//! The hatch lines of a face are the lines `u = k·s` of the picture (`k` an integer, `s` the
//! face's spacing, `u = n·x` the coordinate across the hatch direction `d = (cos θ, sin θ)`,
//! `n = (−sin θ, cos θ)`, `θ` the hatch angle), so faces of the same spacing share their lines
//! and neighbouring faces' hatches line up. Each line is `n·x = c` with `n` and `c = k·s`
//! doubles (`c` rounded once): an exact line, the same for every face.
//!
//! **Clipping is exact in its decisions.** For each line, the side of every polygon vertex
//! (the sign of `n·x − c`) is exact, and so is the order along the line of the points where
//! edges meet it (the sign of a polynomial of degree 6 in the input doubles, decided by the
//! kernel: a filter, then expansions, then rationals). A stretch of the line is hatched when the
//! polygons (even-odd over all their rings: several pieces, holes) cover both sides of it: it
//! lies in their interior. So a line through a vertex, along an edge, or across a zero-area
//! sliver is decided as the exact figure says: a line along an edge of the outline is not
//! hatched (it is the outline), one along an edge two pieces share is.
//!
//! **Points are constructed once.** The end of a hatch on an edge is the edge's crossing with
//! the line, each coordinate `lerp(p, q, t)` with `t` the ratio of the two ends' exact offsets
//! from the line, each rounded once (across an axis-parallel line, the line's own coordinate);
//! a hatch ending on a vertex ends on the vertex itself.
//! Every point where the line meets the polygons' outline (a vertex on the line, a crossing)
//! splits the hatch, so each segment's inside runs between two consecutive meeting points and
//! nothing of the outline lies strictly between its ends. A rounded end may still lie a unit in
//! the last place outside its edge: it is moved by units in the last place along the hatch into
//! the polygon (the exact side test decides). Where the polygons cover both sides of the
//! edges meeting the line at one point (an edge two pieces share, an outline pinched to a
//! point), the hatch runs on through that point and may cross those edges within rounding
//! there. Finally every segment with a constructed end is checked exactly against the edges
//! near its line (no other edge crossed properly, its midpoint inside or on the polygons); one
//! that fails (only possible within rounding of a vertex, for input that nearly but not
//! exactly touches a line) is dropped and counted.
//!
//! All this works on the polygons scaled by a power of two into the kernel's working range
//! ([`Exponents::shift`]), exactly, and scales the hatches back: coordinates from `1e-300` to
//! `1e300` give the same segments, scaled.
//!
//! ```
//! use geo::{LineString, MultiPolygon, Polygon};
//! use kepler::surfaces::hatch::hatch_polygons;
//! let square = Polygon::new(LineString::from(vec![(0.0, 0.0), (4.0, 0.0), (4.0, 4.0), (0.0, 4.0)]), vec![]);
//! // Horizontal lines y = 0, 1, 2, 3, 4: those on the outline are not hatched.
//! let hatch = hatch_polygons(&MultiPolygon::new(vec![square]), 0.0, 1.0).unwrap();
//! let lines: Vec<(i64, Vec<[f64; 2]>)> = hatch.runs.into_iter().map(|r| (r.line, r.points)).collect();
//! assert_eq!(lines, vec![
//!     (1, vec![[0.0, 1.0], [4.0, 1.0]]),
//!     (2, vec![[0.0, 2.0], [4.0, 2.0]]),
//!     (3, vec![[0.0, 3.0], [4.0, 3.0]]),
//! ]);
//! ```

use super::{FaceReport, Result, SurfacesError};
use crate::geometry::exact::ldexp;
use crate::geometry::kernel::Exponents;
use crate::scene::ObjectId;
use geo::MultiPolygon;
use rayon::prelude::*;

mod line;

use line::{HatchFrame, HatchLine, PolygonEdge};

/// The most hatch lines one face may span: more is refused as an error (a spacing far below
/// the face's size).
pub const MAX_LINES: u64 = 1 << 20;

/// How faces are hatched: the hatch angle, and the range of spacings that shades map to.
///
/// ```
/// use kepler::surfaces::hatch::Hatching;
/// let h = Hatching { angle: 45.0, spacing: [0.5, 3.0] };
/// assert_eq!(h.spacing_for(0.0), Some(0.5)); // darkest: densest
/// assert_eq!(h.spacing_for(1.0), None); // fully lit: no hatch
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Hatching {
    /// The angle of the hatch lines from the picture's `x` axis, in degrees, counter-clockwise
    /// (multiples of 90 are exact).
    pub angle: f64,
    /// The smallest and largest spacing between hatch lines, in picture units.
    pub spacing: [f64; 2],
}

impl Hatching {
    /// An error unless the angle is finite and `0 < min ≤ max` are finite spacings.
    ///
    /// ```
    /// use kepler::surfaces::hatch::Hatching;
    /// assert!(Hatching { angle: 30.0, spacing: [1.0, 2.0] }.check().is_ok());
    /// assert!(Hatching { angle: 30.0, spacing: [2.0, 1.0] }.check().is_err());
    /// ```
    pub fn check(&self) -> Result<()> {
        let [min, max] = self.spacing;
        if !self.angle.is_finite() {
            return Err(SurfacesError::Hatch(format!(
                "the hatch angle {} is not finite",
                self.angle
            )));
        }
        if !(min.is_finite() && max.is_finite() && min > 0.0 && min <= max) {
            return Err(SurfacesError::Hatch(format!(
                "hatch spacings {min}, {max} are not 0 < min ≤ max"
            )));
        }
        Ok(())
    }

    /// The spacing of the hatch lines of a face of shade `shade` (0 darkest, 1 fully lit), or
    /// `None` for no hatch. The density of lines follows the darkness `1 − shade`: the spacing
    /// is `min / darkness`, rounded to the nearest of the levels `min·2^(j/4)` (so that faces of
    /// nearly the same shade share their lines), and a face whose level would exceed `max` (or
    /// of shade 1, or not a number) gets no hatch. Shades are clamped to `[0, 1]`.
    ///
    /// ```
    /// use kepler::surfaces::hatch::Hatching;
    /// let h = Hatching { angle: 0.0, spacing: [1.0, 4.0] };
    /// assert_eq!(h.spacing_for(0.5), Some(2.0)); // half as dark: lines twice as far apart
    /// assert_eq!(h.spacing_for(0.52), Some(2.0)); // the same level
    /// assert_eq!(h.spacing_for(0.8), None); // 5 > 4
    /// ```
    pub fn spacing_for(&self, shade: f64) -> Option<f64> {
        let [min, max] = self.spacing;
        if shade.is_nan() {
            return None;
        }
        let darkness = 1.0 - shade.clamp(0.0, 1.0);
        if darkness <= 0.0 {
            return None;
        }
        let level = (4.0 * (1.0 / darkness).log2()).round();
        let spacing = min * (level / 4.0).exp2();
        (spacing.is_finite() && spacing <= max * (1.0 + 1e-12)).then_some(spacing)
    }
}

/// A run of hatch along one line: a polyline whose consecutive points are the hatch segments,
/// split wherever the line meets the polygons' outline.
///
/// ```
/// let r = kepler::surfaces::hatch::HatchRun { line: 3, points: vec![[0.0, 3.0], [1.0, 3.0]] };
/// assert_eq!(r.segments().count(), 1);
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct HatchRun {
    /// The line's index `k`: the run lies on `u = k·s`.
    pub line: i64,
    /// The points, in order along the hatch direction (at least two).
    pub points: Vec<[f64; 2]>,
}

impl HatchRun {
    /// The run's segments, in order.
    ///
    /// ```
    /// let r = kepler::surfaces::hatch::HatchRun { line: 0, points: vec![[0.0, 0.0], [1.0, 0.0], [3.0, 0.0]] };
    /// let s: Vec<[[f64; 2]; 2]> = r.segments().collect();
    /// assert_eq!(s, vec![[[0.0, 0.0], [1.0, 0.0]], [[1.0, 0.0], [3.0, 0.0]]]);
    /// ```
    pub fn segments(&self) -> impl Iterator<Item = [[f64; 2]; 2]> + '_ {
        self.points.windows(2).map(|w| [w[0], w[1]])
    }
}

/// The hatch of one set of polygons: its runs, line by line in increasing `k`, each line's runs
/// in order along the hatch direction; and how many segments failed the exact final check
/// (see the [module documentation](self)) and were dropped.
///
/// ```
/// let h = kepler::surfaces::hatch::Hatch::default();
/// assert!(h.runs.is_empty() && h.dropped == 0);
/// ```
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Hatch {
    /// The runs.
    pub runs: Vec<HatchRun>,
    /// Segments dropped by the final check.
    pub dropped: usize,
}

/// The hatch of one face.
///
/// ```
/// let f = kepler::surfaces::hatch::FaceHatch {
///     object: Default::default(), face: 0, spacing: 1.0, hatch: Default::default(),
/// };
/// assert_eq!(f.hatch.runs.len(), 0);
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct FaceHatch {
    /// The mesh object.
    pub object: ObjectId,
    /// The face's index in its mesh.
    pub face: usize,
    /// The spacing of its lines, in picture units.
    pub spacing: f64,
    /// Its hatch.
    pub hatch: Hatch,
}

/// The hatches of the visible faces: each face of `faces` with its shade in `shades` (the same
/// order; 0 darkest, 1 fully lit) hatched with the spacing [`Hatching::spacing_for`] gives it,
/// clipped to its visible polygons; faces without hatch left out. In parallel; the answer
/// does not depend on the number of threads.
///
/// An error if the hatching is out of range ([`Hatching::check`]), `shades` is not as long as
/// `faces`, or a face would take more than [`MAX_LINES`] lines.
///
/// ```
/// use kepler::{geometry::Vector3, scene::Scene, views::View};
/// use kepler::surfaces::{hatch::{Hatching, hatch_faces}, visible_surfaces};
/// let mut scene = Scene::new();
/// scene.add_mesh(None, "cube", kepler::solids::cube(2.0).unwrap()).unwrap();
/// let view = View::orthographic(Vector3::new(-1.0, -2.0, -3.0), Vector3::z()).unwrap();
/// let faces = visible_surfaces(&scene, &view).unwrap();
/// let shades = vec![0.0; faces.len()];
/// let hatches = hatch_faces(&faces, &shades, &Hatching { angle: 45.0, spacing: [0.1, 1.0] }).unwrap();
/// assert_eq!(hatches.len(), 3); // the three visible faces
/// assert!(hatches.iter().all(|h| h.spacing == 0.1 && h.hatch.dropped == 0));
/// ```
pub fn hatch_faces(
    faces: &[FaceReport],
    shades: &[f64],
    hatching: &Hatching,
) -> Result<Vec<FaceHatch>> {
    hatching.check()?;
    if shades.len() != faces.len() {
        return Err(SurfacesError::Hatch(format!(
            "{} shades for {} faces",
            shades.len(),
            faces.len()
        )));
    }
    let hatched: Vec<Option<FaceHatch>> = faces
        .par_iter()
        .zip(shades)
        .map(|(f, &shade)| {
            let Some(spacing) = hatching.spacing_for(shade) else {
                return Ok(None);
            };
            if f.visible.polygons.0.is_empty() {
                return Ok(None);
            }
            let hatch = hatch_polygons(&f.visible.polygons, hatching.angle, spacing)?;
            Ok((!hatch.runs.is_empty()).then_some(FaceHatch {
                object: f.object,
                face: f.face,
                spacing,
                hatch,
            }))
        })
        .collect::<Result<_>>()?;
    Ok(hatched.into_iter().flatten().collect())
}

/// The hatch of `polygons` (their interior by the even-odd rule over all rings) with lines at
/// `angle` degrees and `spacing` picture units apart: the lines `u = k·spacing`, clipped as the
/// [module documentation](self) describes. Polygons with a point that is not finite, and rings
/// of fewer than three distinct points, hatch nothing.
///
/// An error if the angle is not finite, the spacing is not finite and positive, or the polygons
/// span more than [`MAX_LINES`] lines.
///
/// ```
/// use geo::{LineString, MultiPolygon, Polygon};
/// use kepler::surfaces::hatch::hatch_polygons;
/// // A square with a square hole, hatched vertically at x = 1, 2, 3.
/// let ring = |c: &[(f64, f64)]| LineString::from(c.to_vec());
/// let outer = ring(&[(0.0, 0.0), (4.0, 0.0), (4.0, 4.0), (0.0, 4.0)]);
/// let hole = ring(&[(1.5, 1.0), (2.5, 1.0), (2.5, 3.0), (1.5, 3.0)]);
/// let hatch = hatch_polygons(&MultiPolygon::new(vec![geo::Polygon::new(outer, vec![hole])]), 90.0, 1.0).unwrap();
/// let at_two: Vec<&Vec<[f64; 2]>> = hatch.runs.iter().filter(|r| r.line == -2).map(|r| &r.points).collect();
/// assert_eq!(at_two, vec![&vec![[2.0, 0.0], [2.0, 1.0]], &vec![[2.0, 3.0], [2.0, 4.0]]]);
/// assert_eq!(hatch.runs.len(), 4);
/// ```
pub fn hatch_polygons(polygons: &MultiPolygon<f64>, angle: f64, spacing: f64) -> Result<Hatch> {
    if !(spacing.is_finite() && spacing > 0.0) {
        return Err(SurfacesError::Hatch(format!(
            "the hatch spacing {spacing} is not finite and positive"
        )));
    }
    let Some(dir) = direction(angle) else {
        return Err(SurfacesError::Hatch(format!(
            "the hatch angle {angle} is not finite"
        )));
    };
    let rings = rings(polygons);
    let coordinates: Vec<f64> = rings.iter().flatten().flatten().copied().collect();
    if coordinates.is_empty() || coordinates.iter().any(|c| !c.is_finite()) {
        return Ok(Hatch::default());
    }
    let shift = Exponents::of(&coordinates).shift();
    let rings: Vec<Vec<[f64; 2]>> = rings
        .iter()
        .map(|r| r.iter().map(|p| p.map(|c| ldexp(c, shift))).collect())
        .collect();
    let frame = HatchFrame {
        normal: [-dir[1], dir[0]],
        dir,
    };
    let edges: Vec<PolygonEdge> = rings
        .iter()
        .flat_map(|r| (0..r.len()).map(move |i| (r[i], r[(i + 1) % r.len()])))
        .map(|(p, q)| PolygonEdge::new(p, q, &frame))
        .collect();
    let magnitude = coordinates.iter().fold(0.0f64, |m, c| m.max(c.abs()));
    let magnitude = ldexp(magnitude, shift);
    let margin = magnitude * MARGIN;
    let low = edges.iter().map(|e| e.u[0]).fold(f64::INFINITY, f64::min);
    let high = edges
        .iter()
        .map(|e| e.u[1])
        .fold(f64::NEG_INFINITY, f64::max);
    let step = ldexp(spacing, shift);
    let first = ((low - margin) / step).ceil();
    let last = ((high + margin) / step).floor();
    if !(first.is_finite() && last.is_finite() && first.abs() < 2f64.powi(62))
        || last.abs() >= 2f64.powi(62)
        || last - first >= MAX_LINES as f64
    {
        return Err(SurfacesError::Hatch(format!(
            "spacing {spacing} would take more than {MAX_LINES} lines across polygons \
             {:e} units wide",
            ldexp(high - low, -shift)
        )));
    }
    let mut hatch = Hatch::default();
    let mut previous = f64::NEG_INFINITY;
    for k in first as i64..=last as i64 {
        let offset = k as f64 * spacing;
        if offset <= previous {
            continue;
        }
        previous = offset;
        let line = HatchLine {
            frame: &frame,
            offset: ldexp(offset, shift),
            margin,
        };
        let (runs, dropped) = line.hatch(&edges);
        hatch.dropped += dropped;
        hatch.runs.extend(runs.into_iter().map(|points| {
            HatchRun {
                line: k,
                points: points
                    .into_iter()
                    .map(|p| p.map(|c| ldexp(c, -shift)))
                    .collect(),
            }
        }));
    }
    Ok(hatch)
}

/// The relative margin by which an edge's rounded extent across the lines is widened before
/// the exact tests: 2⁻⁴⁰ of the largest coordinate, far above rounding.
const MARGIN: f64 = 1.0 / (1u64 << 40) as f64;

/// The hatch direction `d = (cos θ, sin θ)` at `θ = degrees`, as the hatch uses it: exact at
/// multiples of 90, with components of equal magnitude at odd multiples of 45, a component below 2⁻⁶⁰ made zero (so that the final exact checks stay
/// exact in doubles); `None` if not finite. The normal across the lines is `(−d.y, d.x)`.
///
/// ```
/// use kepler::surfaces::hatch::direction;
/// assert_eq!(direction(90.0), Some([0.0, 1.0]));
/// assert_eq!(direction(-180.0), Some([-1.0, 0.0]));
/// let h = std::f64::consts::FRAC_1_SQRT_2;
/// assert_eq!(direction(135.0), Some([-h, h]));
/// assert_eq!(direction(30.0).unwrap()[0], 30f64.to_radians().cos());
/// assert_eq!(direction(f64::NAN), None);
/// ```
pub fn direction(degrees: f64) -> Option<[f64; 2]> {
    if !degrees.is_finite() {
        return None;
    }
    let turn = degrees.rem_euclid(360.0);
    let exact = [[1.0, 0.0], [0.0, 1.0], [-1.0, 0.0], [0.0, -1.0]];
    if turn % 90.0 == 0.0 {
        return exact.get((turn / 90.0) as usize).copied();
    }
    if turn % 45.0 == 0.0 {
        let h = std::f64::consts::FRAC_1_SQRT_2;
        return exact
            .get((turn / 90.0) as usize)
            .map(|&[x, y]| [h * (x - y), h * (x + y)]);
    }
    let (sin, cos) = turn.to_radians().sin_cos();
    let tiny = 2f64.powi(-60);
    Some(match (cos.abs() < tiny, sin.abs() < tiny) {
        (true, _) => [0.0, sin.signum()],
        (_, true) => [cos.signum(), 0.0],
        _ => [cos, sin],
    })
}

/// The rings of the polygons as open lists of points, repeated consecutive points (and the
/// closing point) left out; rings of fewer than three points dropped.
fn rings(polygons: &MultiPolygon<f64>) -> Vec<Vec<[f64; 2]>> {
    polygons
        .iter()
        .flat_map(|p| std::iter::once(p.exterior()).chain(p.interiors()))
        .map(|ring| {
            let mut points: Vec<[f64; 2]> = ring.coords().map(|c| [c.x, c.y]).collect();
            points.dedup();
            while points.len() > 1 && points.first() == points.last() {
                points.pop();
            }
            points
        })
        .filter(|r| r.len() >= 3)
        .collect()
}
