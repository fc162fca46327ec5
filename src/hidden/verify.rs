//! Self-verification of a drawing (`kepler render --verify`): the drawing checked against
//! answers found independently of the hidden-line pass.
//!
//! [`draw_traced`] makes the drawing as [`draw`](super::draw) does (the same bits) and keeps
//! every piece with the 3-D line it lies on, its range of that line's parameter and its
//! visibility ([`TracedPiece`]). [`verify`] then checks:
//!
//! 1. **Visibility.** At sample points inside every piece of an edge (at the fractions
//!    [`SAMPLES`] of its parameter range, never its midpoint, where the pass decided it, and
//!    never within a few units in the last place of its ends), VISP through the object
//!    hierarchy ([`VisibilityIndex`], its CBOXes, INBOXes and R-trees of triangles, not the
//!    pass's picture grid of occluders) must give the piece's visibility. The sample point
//!    `X(t) = a + t·(b − a)` is never rounded: each face test is an affine form at `X(t)`,
//!    `(1 − t)·O(a) + t·O(b)`, decided exactly ([`Between`]).
//!    A face hides the point when the point lies strictly behind its plane and the line of
//!    sight meets the closed face (the drawing's rule: see [`crate::hidden`]). Where the line
//!    of sight passes exactly through an edge of such a face (a piece right behind a contour),
//!    [`crate::queries::visp`]'s symbolic perturbation may answer otherwise: those samples are
//!    counted (`grazing`). On an intersection line, each sample is where a plane `x_k = c`
//!    (a double `c` along the coordinate in which the piece runs furthest) cuts the exact line
//!    the two faces' planes meet on, a point defined from the input; each face test is the
//!    exact sign of a plane's form there, and the faces the line lies on do not hide it.
//! 2. **Silhouettes and boundaries.** A second, simple method finds them: an edge between two
//!    triangles of different faces, one turned towards the eye and one away (each triangle's
//!    side of the eye by [`Eye::orient3d`], taken along the edge's direction in that triangle,
//!    so it holds for inside-out and inconsistently oriented meshes as well), or an edge of one
//!    triangle only; and an edge of a face seen edge-on (the surface seen ends there). Each
//!    must be drawn whole: pieces of that class on that edge (matched by object and exact input
//!    end points, never by rounded pictures) whose parameter ranges tile `[0, 1]`. Edges seen
//!    end-on, edges between two faces seen edge-on and edges of more than two triangles are
//!    not checked. A piece here is a traced one, drawn or not: one whose picture is a point
//!    (see 3) still covers its part of the edge.
//!
//!    A side with vertices of the mesh lying exactly inside it (a T-junction) is cut there
//!    first, as the pass cuts it (see [`Mesh::t_junctions`]): each piece between consecutive
//!    vertices on the side is an edge of the sign test, between the triangles of every side or
//!    piece of a side that covers it. The pass draws consecutive pieces of such a side between
//!    the same two surfaces as one line, so a contour piece is matched with the line of the
//!    drawing that runs along it (sides with T-junctions that share a piece make one chain of
//!    vertices in order along their line; a line of the drawing runs between two of them): its
//!    pieces over the contour piece must be of its class and tile the part of the line's
//!    parameter range between the contour piece's ends. Those ends' parameters are not doubles:
//!    the pieces' ends are compared with them exactly (the sign of `X(t) − w` along a
//!    coordinate of the line).
//! 3. **The drawing.** Its segments are exactly the pieces' pictures as drawn (with their class
//!    and visibility; hidden ones only when the drawing keeps them), each piece's ends as
//!    [`draw_traced`] gives them, at the input's scale: each piece checked is one that is
//!    drawn, except a piece whose ends are equal, which the drawing never holds (a piece of
//!    zero length, or one whose picture rounds to a single point when the drawing is scaled
//!    back from the kernel's working range: see [`Drawing::scaled`]).
//!
//! ```
//! use kepler::{scene::Scene, views::View};
//! use kepler::hidden::{Options, verify::{draw_traced, verify}};
//! let mut scene = Scene::new();
//! scene.add_mesh(None, "cube", kepler::solids::cube(2.0).unwrap()).unwrap();
//! let (view, options) = (View::standard(), Options::default());
//! let mut traced = draw_traced(&scene, &view, &options, &|_, _| {}).unwrap();
//! let report = verify(&scene, &view, &options, &traced);
//! assert!(report.checks() > 0 && report.disagreements == 0);
//! // The top face's outline is visible: say it is hidden, and the check finds out.
//! let top = traced.pieces.iter().position(|p| p.visible).unwrap();
//! traced.pieces[top].visible = false;
//! assert!(verify(&scene, &view, &options, &traced).disagreements > 0);
//! ```

use super::{
    DrawError, Drawing, EdgeClass, Options, Overlaps, Pass, Piece, Result, chained, decided,
    scaled_back,
};
use crate::geometry::exact::ldexp;
use crate::geometry::kernel::{Between, Polynomial};
use crate::geometry::predicates::Side;
use crate::geometry::{Point3, Vector3};
use crate::mesh::Mesh;
use crate::queries::along::{Form, Sample};
use crate::queries::frustum::pictured;
use crate::queries::meet::{Meet, OnLine};
use crate::queries::range::in_working_range;
use crate::queries::visp::{Visibility, VisibilityIndex};
use crate::scene::{ObjectId, Scene};
use crate::views::{Eye, View};
use rayon::prelude::*;
use std::cell::Cell;
use std::cmp::Ordering;
use std::collections::HashMap;
use std::fmt;
use std::time::Instant;

/// The fractions of a piece's parameter range where its visibility is checked: not its
/// midpoint, where the pass decided it.
pub const SAMPLES: [f64; 4] = [0.125, 0.375, 0.625, 0.875];

/// A sample closer than this many units in the last place to an end of its piece is not
/// checked: an end's parameter is rounded, the point it stands for is exact.
pub const NEAR_END_ULPS: f64 = 64.0;

/// How many disagreements a [`Verification`] describes.
pub const DESCRIBED: usize = 10;

/// The 3-D line a piece of a drawing lies on.
///
/// ```
/// use kepler::{scene::Scene, views::View, hidden::{Options, verify::{Source, draw_traced}}};
/// let mut scene = Scene::new();
/// let cube = scene.add_mesh(None, "cube", kepler::solids::cube(2.0).unwrap()).unwrap();
/// let traced = draw_traced(&scene, &View::standard(), &Options::default(), &|_, _| {}).unwrap();
/// assert!(traced.pieces.iter().all(|p| p.source == Source::Edge { object: cube }));
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Source {
    /// An edge of an object's mesh (its ends are input vertices).
    Edge {
        /// The object.
        object: ObjectId,
    },
    /// An intersection line: where two faces, each `(object, face index)`, pierce each other
    /// (its ends are rounded).
    Intersection {
        /// The two faces.
        faces: [(ObjectId, usize); 2],
    },
}

/// A visible or hidden piece of a drawing with the 3-D line it lies on: the piece is the part
/// `t[0] ≤ t ≤ t[1]` of `X(t) = line[0] + t·(line[1] − line[0])`.
///
/// ```
/// use kepler::{scene::Scene, views::View, hidden::{EdgeClass, Options, verify::draw_traced}};
/// let mut scene = Scene::new();
/// scene.add_mesh(None, "cube", kepler::solids::cube(2.0).unwrap()).unwrap();
/// let traced = draw_traced(&scene, &View::standard(), &Options::default(), &|_, _| {}).unwrap();
/// // Straight down: four visible silhouette edges on top, four hidden under them.
/// let count = |v| traced.pieces.iter().filter(|p| p.class == EdgeClass::Silhouette && p.visible == v).count();
/// assert_eq!((count(true), count(false)), (4, 4));
/// assert!(traced.pieces.iter().all(|p| p.t == [0.0, 1.0]));
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct TracedPiece {
    /// The line's provenance.
    pub source: Source,
    /// The line's ends in 3-D.
    pub line: [Point3; 2],
    /// The line's class.
    pub class: EdgeClass,
    /// Whether the piece is visible.
    pub visible: bool,
    /// The piece's range of the line's parameter.
    pub t: [f64; 2],
    /// The pictures of the piece's ends, as drawn.
    pub ends: [[f64; 2]; 2],
    /// For an intersection line: the exact line it lies on (its `line` ends are rounded).
    pub(crate) meet: Option<Meet>,
}

/// A drawing with its pieces traced to their 3-D lines (see [`draw_traced`]).
///
/// ```
/// let t = kepler::hidden::verify::Traced {
///     drawing: kepler::hidden::Drawing { polylines: Vec::new(), stages: Vec::new() },
///     pieces: Vec::new(),
///     kept: None,
/// };
/// assert!(t.pieces.is_empty());
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct Traced {
    /// The drawing, bit for bit as [`draw`](super::draw) makes it.
    pub drawing: Drawing,
    /// Every piece, hidden ones too (even when the drawing leaves them out), in the pass's
    /// order: by line, then along it.
    pub pieces: Vec<TracedPiece>,
    /// When the drawing draws each stretch of line once ([`Overlaps::Once`]): the pieces
    /// chained as they are, which check 3 compares them with.
    pub kept: Option<Drawing>,
}

/// [`draw_with_progress`](super::draw_with_progress), keeping every piece with its 3-D line.
///
/// ```
/// use kepler::{scene::Scene, views::View, hidden::{Options, draw, verify::draw_traced}};
/// let mut scene = Scene::new();
/// scene.add_mesh(None, "cube", kepler::solids::cube(2.0).unwrap()).unwrap();
/// let (view, options) = (View::standard(), Options::default());
/// let traced = draw_traced(&scene, &view, &options, &|_, _| {}).unwrap();
/// assert_eq!(traced.drawing.polylines, draw(&scene, &view, &options).unwrap().polylines);
/// ```
pub fn draw_traced(
    scene: &Scene,
    view: &View,
    options: &Options,
    progress: &(dyn Fn(u64, u64) + Sync),
) -> Result<Traced> {
    let (traced, shift) = in_working_range::<_, DrawError>(scene, view, |scene, view| {
        let (pass, pieces) = decided(scene, view, None, options, progress)?;
        Ok(traced(pass, pieces, options))
    })?;
    // Back to the input's scale, exactly.
    Ok(traced.scaled(-shift, view))
}

impl Traced {
    /// The traced drawing of the scene scaled by `2^shift`, from this one: lines always,
    /// pictures when they scale (orthographic views). Exact while nothing overflows or
    /// underflows.
    fn scaled(self, shift: i32, view: &View) -> Traced {
        if shift == 0 {
            return self;
        }
        let pictures = if view.is_perspective() { 0 } else { shift };
        let pieces = self
            .pieces
            .into_iter()
            .map(|p| TracedPiece {
                line: p.line.map(|q| q.map(|c| ldexp(c, shift))),
                ends: p.ends.map(|e| e.map(|c| ldexp(c, pictures))),
                meet: p.meet.map(|m| Meet {
                    planes: m.planes.map(|t| t.map(|q| q.map(|c| ldexp(c, shift)))),
                }),
                ..p
            })
            .collect();
        Traced {
            drawing: scaled_back(self.drawing, view.is_perspective(), -shift),
            pieces,
            kept: self
                .kept
                .map(|d| scaled_back(d, view.is_perspective(), -shift)),
        }
    }
}

/// The drawing of a pass and its pieces, each traced to its line.
fn traced(mut pass: Pass, pieces: Vec<Piece>, options: &Options) -> Traced {
    let mut sources: Vec<Option<Source>> = pass
        .lines
        .iter()
        .map(|l| {
            l.meet.map(|m| Source::Intersection {
                faces: pass.meets[m].on_faces,
            })
        })
        .collect();
    for leaf in &pass.leaves {
        for l in leaf.lines.clone() {
            sources[l] = Some(Source::Edge { object: leaf.id });
        }
    }
    // Every line is an edge of a leaf or an intersection line: no piece is left out.
    let pieces_traced = pieces
        .iter()
        .filter_map(|p| {
            let line = &pass.lines[p.line];
            Some(TracedPiece {
                source: sources[p.line]?,
                line: [line.a, line.b],
                class: p.class,
                visible: p.visible,
                t: p.t,
                ends: p.ends,
                meet: line.meet.map(|m| pass.meets[m].meet),
            })
        })
        .collect();
    // The pieces chained as they are, for check 3, when the drawing draws each stretch once.
    let kept = (options.overlaps == Overlaps::Once).then(|| {
        let stages = pass.stages.clone();
        let keep = Options {
            overlaps: Overlaps::Keep,
            ..*options
        };
        let kept = chained(&mut pass, pieces.clone(), &keep);
        pass.stages = stages;
        kept
    });
    Traced {
        drawing: chained(&mut pass, pieces, options),
        pieces: pieces_traced,
        kept,
    }
}

/// Which check a disagreement failed.
///
/// ```
/// assert_eq!(kepler::hidden::verify::Check::Visibility.to_string(), "visibility");
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Check {
    /// VISP at a sample point against the piece's visibility.
    Visibility,
    /// A silhouette edge (found by the sign test) drawn whole as silhouette pieces.
    Silhouette,
    /// A boundary edge drawn whole as boundary pieces.
    Boundary,
    /// The drawing's segments against the pieces.
    Drawing,
}

impl fmt::Display for Check {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Check::Visibility => "visibility",
            Check::Silhouette => "silhouette",
            Check::Boundary => "boundary",
            Check::Drawing => "drawing",
        })
    }
}

/// One disagreement, described for a person.
///
/// ```
/// use kepler::hidden::verify::{Check, Disagreement};
/// let d = Disagreement {
///     check: Check::Visibility,
///     object: "cube".into(),
///     line: "edge v0–v1".into(),
///     at: "t = 0.25".into(),
///     expected: "hidden".into(),
///     found: "visible".into(),
/// };
/// assert_eq!(d.to_string(), "visibility: object 'cube', edge v0–v1, at t = 0.25: expected hidden, found visible");
/// ```
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Disagreement {
    /// The check.
    pub check: Check,
    /// The object's path (empty for a segment of the drawing).
    pub object: String,
    /// The line: an edge by its vertices, an intersection line by its faces, or a segment.
    pub line: String,
    /// Where on it.
    pub at: String,
    /// What the independent check says.
    pub expected: String,
    /// What the drawing has.
    pub found: String,
}

impl fmt::Display for Disagreement {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}: ", self.check)?;
        if !self.object.is_empty() {
            write!(f, "object '{}', ", self.object)?;
        }
        write!(
            f,
            "{}, at {}: expected {}, found {}",
            self.line, self.at, self.expected, self.found
        )
    }
}

/// What [`verify`] checked and found.
///
/// ```
/// let v = kepler::hidden::verify::Verification::default();
/// assert_eq!((v.checks(), v.disagreements), (0, 0));
/// assert!(v.to_string().starts_with("verify: 0 checks, 0 disagreements"));
/// ```
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Verification {
    /// Sample points whose visibility VISP checked.
    pub samples: usize,
    /// Of those, samples whose line of sight passes exactly through an edge of a face that
    /// hides them (there the closed face hides, as the drawing's rule says).
    pub grazing: usize,
    /// Silhouette edges found by the sign test, each checked drawn whole.
    pub silhouettes: usize,
    /// Boundary edges, each checked drawn whole.
    pub boundaries: usize,
    /// Segments of the drawing matched with pieces.
    pub segments: usize,
    /// The number of disagreements.
    pub disagreements: usize,
    /// The first few of them ([`DESCRIBED`]).
    pub described: Vec<Disagreement>,
    /// Pieces of intersection lines, whose visibility is not checked yet.
    pub unchecked_intersections: usize,
    /// Samples not checked for lying within a few units in the last place of a piece's end.
    pub near_ends: usize,
    /// Edges the sign test does not decide: seen end-on, between two faces seen edge-on, or of
    /// more than two triangles; and, in a view that clips, contours not wholly inside its
    /// frustum.
    pub unchecked_edges: usize,
    /// The time the checks took, in seconds.
    pub seconds: f64,
}

impl Verification {
    /// The number of checks made.
    ///
    /// ```
    /// let v = kepler::hidden::verify::Verification { samples: 5, segments: 2, ..Default::default() };
    /// assert_eq!(v.checks(), 7);
    /// ```
    pub fn checks(&self) -> usize {
        self.samples + self.silhouettes + self.boundaries + self.segments
    }

    fn disagree(&mut self, d: Disagreement) {
        self.disagreements += 1;
        if self.described.len() < DESCRIBED {
            self.described.push(d);
        }
    }
}

impl fmt::Display for Verification {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        writeln!(
            f,
            "verify: {} checks, {} disagreements ({:.3} s)",
            self.checks(),
            self.disagreements,
            self.seconds
        )?;
        writeln!(
            f,
            "verify: {} visibility samples by VISP ({} grazing a hiding face's edge), {} \
             silhouette and {} boundary edges drawn whole, {} drawing segments matched to pieces",
            self.samples, self.grazing, self.silhouettes, self.boundaries, self.segments
        )?;
        writeln!(
            f,
            "verify: not checked: {} intersection-line pieces (without their exact line), \
             {} samples within {NEAR_END_ULPS} ulps of a piece's end, {} edges end-on, between \
             faces edge-on or of more than two triangles",
            self.unchecked_intersections, self.near_ends, self.unchecked_edges
        )?;
        for d in &self.described {
            writeln!(f, "verify: disagreement: {d}")?;
        }
        if self.disagreements > self.described.len() {
            writeln!(
                f,
                "verify: ... and {} more disagreements",
                self.disagreements - self.described.len()
            )?;
        }
        Ok(())
    }
}

/// Checks a traced drawing of `scene` from `view`, made with `options` (see the module
/// documentation).
///
/// ```
/// use kepler::{geometry::Vector3, scene::Scene, views::View};
/// use kepler::hidden::{Options, verify::{draw_traced, verify}};
/// let mut scene = Scene::new();
/// scene.add_mesh(None, "cube", kepler::solids::cube(2.0).unwrap()).unwrap();
/// let view = View::orthographic(Vector3::new(-1.0, -2.0, -3.0), Vector3::z()).unwrap();
/// let options = Options::default();
/// let mut traced = draw_traced(&scene, &view, &options, &|_, _| {}).unwrap();
/// // Six silhouette edges around the outline, each drawn whole.
/// assert_eq!(verify(&scene, &view, &options, &traced).silhouettes, 6);
/// // Leave out a piece: its edge is no longer drawn whole.
/// traced.pieces.remove(0);
/// assert!(verify(&scene, &view, &options, &traced).disagreements > 0);
/// ```
pub fn verify(scene: &Scene, view: &View, options: &Options, traced: &Traced) -> Verification {
    // In the kernel's working range, as the drawing was made: the checks' own arithmetic
    // (sample points, pictures, the VISP filters) then neither overflows nor underflows.
    let shift = scene.exponents().union(view.exponents()).shift();
    if shift != 0
        && let Ok(scaled) = scene.scaled(shift)
    {
        let traced = traced.clone().scaled(shift, view);
        return verify_in_range(&scaled, &view.scaled(shift), options, &traced);
    }
    verify_in_range(scene, view, options, traced)
}

/// [`verify`] on a scene in the working range.
fn verify_in_range(scene: &Scene, view: &View, options: &Options, traced: &Traced) -> Verification {
    let clock = Instant::now();
    let mut report = Verification::default();
    visibility(scene, view, traced, &mut report);
    contours(scene, view, traced, &mut report);
    drawing(options, traced, &mut report);
    report.seconds = clock.elapsed().as_secs_f64();
    report
}

/// What one sample found.
enum Sampled {
    Agrees { grazing: bool },
    NearEnd,
    Disagrees { t: f64, visibility: Visibility },
}

/// Check 1: VISP at the samples of every edge piece.
fn visibility(scene: &Scene, view: &View, traced: &Traced, report: &mut Verification) {
    let index = VisibilityIndex::whole_scene(scene, view.clone());
    let eye = view.eye();
    let found: Vec<(usize, Vec<Sampled>)> = traced
        .pieces
        .par_iter()
        .enumerate()
        .map(|(i, p)| match (p.source, &p.meet) {
            (Source::Intersection { faces }, Some(meet)) => {
                (i, line_samples(scene, &index, eye, p, meet, faces))
            }
            _ => (i, samples(&index, eye, p)),
        })
        .collect();
    report.unchecked_intersections = traced
        .pieces
        .iter()
        .filter(|p| matches!(p.source, Source::Intersection { .. }) && p.meet.is_none())
        .count();
    for (i, sampled) in found {
        let p = &traced.pieces[i];
        for s in sampled {
            match s {
                Sampled::Agrees { grazing } => {
                    report.samples += 1;
                    report.grazing += usize::from(grazing);
                }
                Sampled::NearEnd => report.near_ends += 1,
                Sampled::Disagrees { t, visibility } => {
                    report.samples += 1;
                    report.disagree(Disagreement {
                        check: Check::Visibility,
                        object: object_of(scene, &p.source),
                        line: describe(scene, p),
                        at: format!("t = {t:e} (piece t = [{:e}, {:e}])", p.t[0], p.t[1]),
                        expected: visibility.to_string().to_lowercase(),
                        found: if p.visible { "visible" } else { "hidden" }.to_string(),
                    });
                }
            }
        }
    }
}

/// VISP at the samples of one edge piece.
fn samples(index: &VisibilityIndex, eye: &Eye, p: &TracedPiece) -> Vec<Sampled> {
    let [lo, hi] = p.t;
    SAMPLES
        .iter()
        .map(|&f| {
            let at = |f: f64| lo + (hi - lo) * f;
            let inside = |t: f64| {
                let margin = NEAR_END_ULPS * f64::EPSILON * t.abs();
                t - lo > margin && hi - t > margin && t > 0.0 && t < 1.0
            };
            // A sample whose line of sight passes exactly through the edge of the only faces
            // that hide it (a vertex's picture on the piece, say) stands for no piece around
            // it: the sample moves (a sixteenth of the piece either way), unless every try
            // grazes (a piece right behind a contour): then the closed faces hide it.
            if !inside(at(f)) {
                return Sampled::NearEnd;
            }
            let tries = [at(f), at(f + 1.0 / 16.0), at(f - 1.0 / 16.0)];
            let mut first = None;
            for t in tries.into_iter().filter(|&t| inside(t)) {
                let (visibility, grazing) = visp_at(index, eye, &p.line, t);
                first.get_or_insert((t, visibility));
                if !grazing {
                    return sampled(p, t, visibility, false);
                }
            }
            match first {
                Some((t, visibility)) => sampled(p, t, visibility, true),
                None => Sampled::NearEnd,
            }
        })
        .collect()
}

/// VISP at the samples of one piece of an intersection line (on the exact line `meet`, of the
/// faces `faces`): each sample is where a plane `x_k = c` across the line (a double `c` of the
/// coordinate along which the piece runs furthest, at the fractions [`SAMPLES`] of the piece's
/// rounded span) cuts it, a point of the line defined from the input and never rounded; every
/// face test is the exact sign of a plane's form there ([`Meet::sign_at`]). The faces the line
/// lies on do not hide it. Samples within 2⁻³⁰ of the piece's span of its ends are not taken
/// (the piece's ends are known here only as rounded points).
fn line_samples(
    scene: &Scene,
    index: &VisibilityIndex,
    eye: &Eye,
    p: &TracedPiece,
    meet: &Meet,
    faces: [(ObjectId, usize); 2],
) -> Vec<Sampled> {
    let [a, b] = &p.line;
    let k = (0..3)
        .max_by(|&i, &j| (b[i] - a[i]).abs().total_cmp(&(b[j] - a[j]).abs()))
        .unwrap_or(0);
    let [lo, hi] = p.t.map(|t| a[k] + t * (b[k] - a[k]));
    let margin = (hi - lo).abs() / (1u64 << 30) as f64;
    // The triangles of the faces the line lies on, which do not hide it.
    let own: Vec<[Point3; 3]> = faces
        .iter()
        .filter_map(|&(o, f)| {
            let mesh = scene[o].mesh()?;
            let face = mesh.faces().get(f)?;
            Some(
                face.triangle_range()
                    .map(|t| mesh.triangle(t))
                    .collect::<Vec<_>>(),
            )
        })
        .flatten()
        .collect();
    SAMPLES
        .iter()
        .map(|&f| {
            let c = lo + (hi - lo) * f;
            // The sample's parameter along the rounded line, for the report.
            let t = p.t[0] + (p.t[1] - p.t[0]) * f;
            if !((c - lo).abs() > margin && (hi - c).abs() > margin) {
                return Sampled::NearEnd;
            }
            let mut corner = [0.0; 3];
            corner[k] = c;
            let (p0, mut p1, mut p2) = (
                Point3::from(corner),
                Point3::from(corner),
                Point3::from(corner),
            );
            p1[(k + 1) % 3] = 1.0;
            p2[(k + 2) % 3] = 1.0;
            let across = Form::Plane([p0, p1, p2]);
            if meet.slope_sign(eye, &across) == Ordering::Equal {
                return Sampled::NearEnd;
            }
            let at = OnLine::Cut(meet.increasing(eye, across));
            let sign = |form: &Form| meet.sign_at(eye, &at, form);
            let near = meet.approximate(eye, &at);
            let radius = meet.magnitude(&at).max(near.coords.amax()) / (1u64 << 39) as f64;
            let grazed = Cell::new(false);
            let hides = |tri: &[Point3; 3], strict: bool| {
                if own.contains(tri) {
                    return false;
                }
                let (hides, grazes) = hides_by(eye, tri, &sign);
                grazed.set(grazed.get() || grazes);
                hides && !(strict && grazes)
            };
            let (closed, _) = index.visp_by((&near, radius), |tri| hides(tri, false));
            let visibility = if closed == Visibility::Visible || !grazed.get() {
                closed
            } else {
                let (open, _) = index.visp_by((&near, radius), |tri| hides(tri, true));
                if open == Visibility::Visible {
                    // The answer rests on lines of sight through faces' edges only.
                    return sampled(p, t, closed, true);
                }
                closed
            };
            sampled(p, t, visibility, false)
        })
        .collect()
}

/// Whether the triangle `tri` hides a point given by the exact sign of any form there, and
/// whether its line of sight passes exactly through an edge of the triangle (see [`hides_at`]).
fn hides_by(eye: &Eye, tri: &[Point3; 3], sign: &impl Fn(&Form) -> Ordering) -> (bool, bool) {
    let facing = eye.orient3d(&tri[0], &tri[1], &tri[2]);
    if facing == Ordering::Equal || sign(&Form::Plane(*tri)) != facing.reverse() {
        return (false, false);
    }
    let sides = [0, 1, 2].map(|i| sign(&Form::Sight(tri[i], tri[(i + 1) % 3])));
    let inside = !(sides.contains(&Ordering::Greater) && sides.contains(&Ordering::Less));
    (inside, inside && sides.contains(&Ordering::Equal))
}

/// A sample's outcome: VISP found `visibility` at `t`.
fn sampled(p: &TracedPiece, t: f64, visibility: Visibility, grazing: bool) -> Sampled {
    if (visibility == Visibility::Visible) == p.visible {
        Sampled::Agrees { grazing }
    } else {
        Sampled::Disagrees { t, visibility }
    }
}

/// VISP at `X(t)` on `line`, with the closed faces, and whether the answer rests on lines of
/// sight through faces' edges only (HIDDEN with the closed faces, VISIBLE with the open ones).
fn visp_at(index: &VisibilityIndex, eye: &Eye, [a, b]: &[Point3; 2], t: f64) -> (Visibility, bool) {
    let (near, radius) = Sample::At(t).point(a, b);
    let near = (&near, radius);
    let grazed = Cell::new(false);
    let (closed, _) = index.visp_by(near, |tri| {
        let (hides, grazes) = hides_at(eye, tri, a, b, t);
        grazed.set(grazed.get() || grazes);
        hides
    });
    if closed == Visibility::Visible || !grazed.get() {
        return (closed, false);
    }
    let (open, _) = index.visp_by(near, |tri| hides_at(eye, tri, a, b, t) == (true, false));
    (closed, open == Visibility::Visible)
}

/// Whether the triangle `tri` hides `X(t) = a + t·(b − a)` (strictly behind its plane, the
/// line of sight through the closed triangle), and whether that line of sight passes exactly
/// through an edge of the triangle.
fn hides_at(eye: &Eye, tri: &[Point3; 3], a: &Point3, b: &Point3, t: f64) -> (bool, bool) {
    let facing = eye.orient3d(&tri[0], &tri[1], &tri[2]);
    if facing == Ordering::Equal || Form::Plane(*tri).sign_along(eye, a, b, t) != facing.reverse() {
        return (false, false);
    }
    let sides = [0, 1, 2].map(|i| Form::Sight(tri[i], tri[(i + 1) % 3]).sign_along(eye, a, b, t));
    let inside = !(sides.contains(&Ordering::Greater) && sides.contains(&Ordering::Less));
    (inside, inside && sides.contains(&Ordering::Equal))
}

/// The path of a piece's object (of its first face's, for an intersection line).
fn object_of(scene: &Scene, source: &Source) -> String {
    match source {
        Source::Edge { object } => scene.path(*object),
        Source::Intersection { faces } => faces
            .first()
            .map(|&(o, _)| scene.path(o))
            .unwrap_or_default(),
    }
}

/// A piece's line, for a person: an edge by its vertex indices, else by its ends.
fn describe(scene: &Scene, p: &TracedPiece) -> String {
    let [a, b] = p.line;
    let class = p.class.name();
    let vertex = |mesh: &Mesh, x: &Point3| mesh.vertices().iter().position(|v| v == x);
    if let Source::Edge { object } = p.source
        && let Some(mesh) = scene[object].mesh()
        && let (Some(i), Some(j)) = (vertex(mesh, &a), vertex(mesh, &b))
    {
        return format!("{class} edge v{i}–v{j}");
    }
    format!(
        "{class} line ({}, {}, {})–({}, {}, {})",
        a.x, a.y, a.z, b.x, b.y, b.z
    )
}

/// The bits of an unordered pair of points, to match an edge with the pieces on it.
type EdgeKey = [[u64; 3]; 2];

/// The bits of a point's coordinates (`-0.0` and `0.0` made equal).
fn point_key(p: &Point3) -> [u64; 3] {
    [p.x, p.y, p.z].map(|v| (v + 0.0).to_bits())
}

fn edge_key(a: &Point3, b: &Point3) -> EdgeKey {
    let (x, y) = (point_key(a), point_key(b));
    if x <= y { [x, y] } else { [y, x] }
}

/// Check 2: every silhouette and boundary edge of the sign test drawn whole.
fn contours(scene: &Scene, view: &View, traced: &Traced, report: &mut Verification) {
    let eye = view.eye();
    // A view that clips draws contours only inside its frustum: those are checked.
    let clip = pictured(scene, view).ok().and_then(|(_, clip)| clip);
    let mut on: HashMap<(ObjectId, EdgeKey), Vec<usize>> = HashMap::new();
    // The lines of each object whose mesh has T-junctions: one may run along several pieces
    // of a side.
    let mut lines_of: HashMap<ObjectId, Vec<EdgeKey>> = HashMap::new();
    let has_junctions =
        |object: ObjectId| scene[object].mesh().is_some_and(|m| m.t_junctions() > 0);
    for (i, p) in traced.pieces.iter().enumerate() {
        if let Source::Edge { object } = p.source {
            let key = edge_key(&p.line[0], &p.line[1]);
            let pieces = on.entry((object, key)).or_default();
            if pieces.is_empty() && has_junctions(object) {
                lines_of.entry(object).or_default().push(key);
            }
            pieces.push(i);
        }
    }
    let meshes = scene.mesh_objects(scene.roots());
    // An exact copy of an earlier mesh is drawn by that one's pieces.
    let first = super::originals(&meshes);
    let drawn_as: HashMap<ObjectId, ObjectId> = meshes
        .iter()
        .zip(&first)
        .map(|(&(id, _), &f)| (id, meshes[f].0))
        .collect();
    let found: Vec<(ObjectId, Contours)> = meshes
        .par_iter()
        .map(|&(id, mesh)| (id, contour_edges(mesh, eye)))
        .collect();
    for (object, found) in found {
        report.unchecked_edges += found.unchecked;
        let Some(mesh) = scene[object].mesh() else {
            continue;
        };
        let source = drawn_as[&object];
        let lines = lines_of.get(&source).map(Vec::as_slice).unwrap_or_default();
        let cover = found.chains.covering(mesh, lines);
        for c in found.contours {
            let (a, b) = (
                mesh.vertices()[c.vertices[0] as usize],
                mesh.vertices()[c.vertices[1] as usize],
            );
            if clip.is_some_and(|n| !(n.contains(eye, &a) && n.contains(eye, &b))) {
                report.unchecked_edges += 1;
                continue;
            }
            let (check, class) = match c.class {
                EdgeClass::Boundary => {
                    report.boundaries += 1;
                    (Check::Boundary, EdgeClass::Boundary)
                }
                _ => {
                    report.silhouettes += 1;
                    (Check::Silhouette, EdgeClass::Silhouette)
                }
            };
            let pieces = |key: &EdgeKey| {
                on.get(&(source, *key))
                    .map(Vec::as_slice)
                    .unwrap_or_default()
            };
            let drawn = match c.chain {
                None => whole(traced, pieces(&edge_key(&a, &b)), class),
                Some(chain) => {
                    let mut drawn = Ok(());
                    for (w, lines) in found.chains.between(chain, c.vertices, &cover) {
                        let ends = w.map(|v| mesh.vertices()[v as usize]);
                        let part = match lines {
                            [] => Err(("t = [0e0, 1]".to_string(), "nothing".to_string())),
                            [line] => tiled_between(traced, pieces(line), class, ends),
                            more => Err((
                                "its line".to_string(),
                                format!("pieces of {} lines covering it", more.len()),
                            )),
                        };
                        if let Err((at, found)) = part {
                            let at = if w == c.vertices {
                                at
                            } else {
                                format!("its piece v{}–v{}, {at}", w[0], w[1])
                            };
                            drawn = Err((at, found));
                            break;
                        }
                    }
                    drawn
                }
            };
            if let Err((at, found)) = drawn {
                report.disagree(Disagreement {
                    check,
                    object: scene.path(object),
                    line: format!("edge v{}–v{}", c.vertices[0], c.vertices[1]),
                    at,
                    expected: format!("{} pieces covering it", class.name()),
                    found,
                });
            }
        }
    }
}

/// Whether the pieces `on` an edge, all of `class`, tile its parameter range `[0, 1]`; else
/// where they do not and what is there.
fn whole(traced: &Traced, on: &[usize], class: EdgeClass) -> Result<(), (String, String)> {
    if let Some(&i) = on.iter().find(|&&i| traced.pieces[i].class != class) {
        let p = &traced.pieces[i];
        return Err((
            format!("t = [{:e}, {:e}]", p.t[0], p.t[1]),
            format!("a {} piece", p.class.name()),
        ));
    }
    let mut ranges: Vec<[f64; 2]> = on.iter().map(|&i| traced.pieces[i].t).collect();
    ranges.sort_by(|x, y| x[0].total_cmp(&y[0]));
    let mut reached = 0.0;
    for r in ranges {
        if r[0] != reached {
            let what = if r[0] > reached {
                "nothing"
            } else {
                "overlapping pieces"
            };
            return Err((format!("t = {reached:e}"), what.to_string()));
        }
        reached = r[1];
    }
    if reached != 1.0 {
        return Err((format!("t = [{reached:e}, 1]"), "nothing".to_string()));
    }
    Ok(())
}

/// Whether the pieces `on` a line of the drawing (an edge cut at T-junctions and joined, whose
/// ends are input vertices collinear with `part`), those over the segment `part` all of
/// `class`, tile the line's parameter range over `part`; else where they do not and what is
/// there. The ends of `part` are input vertices on the line, at parameters that are not
/// doubles: each piece's ends are compared with them exactly.
fn tiled_between(
    traced: &Traced,
    on: &[usize],
    class: EdgeClass,
    part: [Point3; 2],
) -> Result<(), (String, String)> {
    let nothing = || ("t = [0e0, 1]".to_string(), "nothing".to_string());
    let Some(first) = on.first().map(|&i| &traced.pieces[i]) else {
        return Err(nothing());
    };
    let [a, b] = first.line;
    let Some(k) = (0..3).find(|&k| a[k] != b[k]) else {
        return Err(nothing());
    };
    let rising = a[k] < b[k];
    // The parameter `t` compared with the parameter of the point `w` of the line, exactly:
    // the sign of `X(t)ₖ − wₖ` along the coordinate `k`, which the line runs along.
    let compare = |t: f64, w: &Point3| -> Ordering {
        if w == &a || w == &b {
            let end = if w == &a { 0.0 } else { 1.0 };
            return t.partial_cmp(&end).unwrap_or(Ordering::Equal);
        }
        let mut normal = Vector3::zeros();
        normal[k] = 1.0;
        let side = |x: Point3| Side {
            origin: *w,
            normal,
            offset: 0.0,
            x,
        };
        let sign = Between(side(a), side(b), t).sign();
        if rising { sign } else { sign.reverse() }
    };
    // The ends of `part` in the order of the line's parameter.
    let [lo, hi] = if (part[0][k] < part[1][k]) == rising {
        part
    } else {
        [part[1], part[0]]
    };
    let mut over: Vec<&TracedPiece> = on
        .iter()
        .map(|&i| &traced.pieces[i])
        .filter(|p| compare(p.t[0], &hi) == Ordering::Less)
        .filter(|p| compare(p.t[1], &lo) == Ordering::Greater)
        .collect();
    if let Some(p) = over.iter().find(|p| p.class != class) {
        return Err((
            format!("t = [{:e}, {:e}] of its line", p.t[0], p.t[1]),
            format!("a {} piece", p.class.name()),
        ));
    }
    over.sort_by(|x, y| x.t[0].total_cmp(&y.t[0]));
    let (Some(start), Some(end)) = (over.first(), over.last()) else {
        return Err(nothing());
    };
    if compare(start.t[0], &lo) == Ordering::Greater {
        return Err((
            format!("t < {:e} of its line", start.t[0]),
            "nothing".to_string(),
        ));
    }
    for w in over.windows(2) {
        let (reached, next) = (w[0].t[1], w[1].t[0]);
        if next != reached {
            let what = if next > reached {
                "nothing"
            } else {
                "overlapping pieces"
            };
            return Err((format!("t = {reached:e} of its line"), what.to_string()));
        }
    }
    if compare(end.t[1], &hi) == Ordering::Less {
        return Err((
            format!("t > {:e} of its line", end.t[1]),
            "nothing".to_string(),
        ));
    }
    Ok(())
}

/// A silhouette or boundary edge found by the sign test: a side of a triangle, or a piece of
/// one between consecutive vertices lying on it (at T-junctions).
struct Contour {
    vertices: [u32; 2],
    class: EdgeClass,
    /// The chain (see [`Chains`]) it is a piece of, for a piece of a side with T-junctions.
    chain: Option<usize>,
}

/// What the sign test found in a mesh.
struct Contours {
    /// The silhouette and boundary edges.
    contours: Vec<Contour>,
    /// The sides with T-junctions the contours lie on.
    chains: Chains,
    /// The number of edges it does not decide.
    unchecked: usize,
}

/// The sides of a mesh's triangles that have T-junctions, joined into chains where they share
/// a piece (so lie on one line): each chain's vertices in order along the line. A line of the
/// drawing along a side with T-junctions (its pieces joined, as the pass joins them) runs
/// between two vertices of one chain.
#[derive(Debug, Default)]
struct Chains {
    /// Each chain's vertices, in order along it.
    points: Vec<Vec<u32>>,
    /// For each vertex on a chain, the chains it lies on and its position on each.
    at: HashMap<u32, Vec<(usize, usize)>>,
}

/// For each chain, for each segment between consecutive vertices of it, the lines of the
/// drawing (by their ends) that run along it.
type Cover = Vec<Vec<Vec<EdgeKey>>>;

impl Chains {
    /// The chains of the sides `long` (each its vertices in order along it), of which those
    /// with an index of one root in `parent` (a union-find forest) share pieces; and the chain
    /// of each side.
    fn new(vertices: &[Point3], long: &[Vec<u32>], parent: &mut [usize]) -> (Chains, Vec<usize>) {
        let mut chains = Chains::default();
        let mut of_root: HashMap<usize, usize> = HashMap::new();
        let mut chain_of = Vec::with_capacity(long.len());
        for (id, side) in long.iter().enumerate() {
            let r = root(parent, id);
            let c = *of_root.entry(r).or_insert_with(|| {
                chains.points.push(Vec::new());
                chains.points.len() - 1
            });
            chains.points[c].extend(side);
            chain_of.push(c);
        }
        let point = |v: u32| vertices.get(v as usize).copied().unwrap_or_default();
        for (c, points) in chains.points.iter_mut().enumerate() {
            // Exactly collinear, so in order along a coordinate in which two of them differ
            // (the first two: consecutive on a side).
            let (p, q) = (points.first(), points.get(1));
            let (p, q) = (
                point(p.copied().unwrap_or(0)),
                point(q.copied().unwrap_or(0)),
            );
            let k = (0..3).find(|&k| p[k] != q[k]).unwrap_or(0);
            points.sort_by(|&x, &y| point(x)[k].total_cmp(&point(y)[k]).then(x.cmp(&y)));
            points.dedup();
            for (i, &w) in points.iter().enumerate() {
                chains.at.entry(w).or_default().push((c, i));
            }
        }
        (chains, chain_of)
    }

    /// The position of vertex `v` on chain `c`.
    fn position(&self, c: usize, v: u32) -> Option<usize> {
        let on = self.at.get(&v)?;
        on.iter().find(|x| x.0 == c).map(|x| x.1)
    }

    /// Which of the `lines` of the drawing (by their ends: vertices of `mesh`) run along which
    /// segments of the chains.
    fn covering(&self, mesh: &Mesh, lines: &[EdgeKey]) -> Cover {
        let mut cover: Cover = self
            .points
            .iter()
            .map(|p| vec![Vec::new(); p.len().saturating_sub(1)])
            .collect();
        if self.points.is_empty() {
            return cover;
        }
        let vertex: HashMap<[u64; 3], u32> = self
            .at
            .keys()
            .filter_map(|&v| Some((point_key(mesh.vertices().get(v as usize)?), v)))
            .collect();
        for key in lines {
            let (Some(&a), Some(&b)) = (vertex.get(&key[0]), vertex.get(&key[1])) else {
                continue;
            };
            for &(c, i) in self.at.get(&a).into_iter().flatten() {
                if let Some(j) = self.position(c, b) {
                    for segment in cover[c].iter_mut().take(i.max(j)).skip(i.min(j)) {
                        segment.push(*key);
                    }
                }
            }
        }
        cover
    }

    /// The segments of chain `c` between consecutive vertices that make up the piece between
    /// vertices `ends`, each with the lines of the drawing that run along it.
    fn between<'a>(
        &self,
        c: usize,
        ends: [u32; 2],
        cover: &'a Cover,
    ) -> Vec<([u32; 2], &'a [EdgeKey])> {
        let (Some(i), Some(j), Some(points), Some(lines)) = (
            self.position(c, ends[0]),
            self.position(c, ends[1]),
            self.points.get(c),
            cover.get(c),
        ) else {
            return vec![(ends, &[])];
        };
        (i.min(j)..i.max(j))
            .map(|k| {
                let w = [points[k], points[k + 1]];
                let w = if w == [ends[1], ends[0]] { ends } else { w };
                (w, lines.get(k).map(Vec::as_slice).unwrap_or_default())
            })
            .collect()
    }
}

/// The root of `g` in the union-find forest `parent`, halving the path.
fn root(parent: &mut [usize], mut g: usize) -> usize {
    while parent[g] != g {
        parent[g] = parent[parent[g]];
        g = parent[g];
    }
    g
}

/// A side of a triangle, or a piece of one between consecutive vertices lying on it (at
/// T-junctions): the edge (lower, higher vertex), the triangle, whether the triangle runs along
/// the edge from lower to higher, and the index of the side with T-junctions it is a piece of
/// ([`WHOLE`] for a whole side).
type SidePiece = ([u32; 2], usize, bool, usize);

/// The [`SidePiece`] of a whole side.
const WHOLE: usize = usize::MAX;

/// A mesh's face sides with T-junctions, by face and (lower, higher) end: each side's first
/// vertex and the vertices inside it, in order from there.
type Junctions<'a> = HashMap<(usize, [u32; 2]), (u32, &'a [u32])>;

/// The silhouette and boundary edges of `mesh` by the sign test (see the module
/// documentation), and the number of edges it does not decide. A side with vertices of the
/// mesh lying exactly inside it (a T-junction) is cut there, as the pass cuts it
/// ([`Mesh::side_junctions`]): the pieces between consecutive vertices on it are matched, across
/// triangles, with the sides or pieces that cover them, and each is tested as an edge.
fn contour_edges(mesh: &Mesh, eye: &Eye) -> Contours {
    let ordered = |p: u32, q: u32| [p.min(q), p.max(q)];
    // Each face's sides with T-junctions: the side's first vertex and those inside it, in
    // order from there.
    let mut junctions: Junctions = HashMap::new();
    if mesh.t_junctions() > 0 {
        for (f, face) in mesh.faces().iter().enumerate() {
            let v = face.vertices();
            for i in 0..v.len() {
                if let Some(inner) = mesh.side_junctions(f, i) {
                    junctions.insert((f, ordered(v[i], v[(i + 1) % v.len()])), (v[i], inner));
                }
            }
        }
    }
    // Each triangle's sides, cut at T-junctions; each side with them (its vertices in order).
    let triangles = mesh.triangles();
    let mut long: Vec<Vec<u32>> = Vec::new();
    let mut sides: Vec<SidePiece> = Vec::with_capacity(3 * triangles.len());
    for (f, face) in mesh.faces().iter().enumerate() {
        for t in face.triangle_range() {
            let Some(tri) = triangles.get(t) else {
                continue;
            };
            for k in 0..3 {
                let (p, q) = (tri[k], tri[(k + 1) % 3]);
                let Some(&(from, inner)) = junctions.get(&(f, ordered(p, q))) else {
                    sides.push((ordered(p, q), t, p < q, WHOLE));
                    continue;
                };
                let to = if from == p { q } else { p };
                let mut on: Vec<u32> = std::iter::once(from)
                    .chain(inner.iter().copied())
                    .chain(std::iter::once(to))
                    .collect();
                // In the triangle's direction, from p to q.
                if from != p {
                    on.reverse();
                }
                for w in on.windows(2) {
                    sides.push((ordered(w[0], w[1]), t, w[0] < w[1], long.len()));
                }
                long.push(on);
            }
        }
    }
    sides.sort_unstable();
    let groups: Vec<&[SidePiece]> = sides.chunk_by(|x, y| x.0 == y.0).collect();
    // Sides with T-junctions that share a piece lie on one line: one chain.
    let mut parent: Vec<usize> = (0..long.len()).collect();
    for group in &groups {
        let mut ids = group.iter().map(|s| s.3).filter(|&id| id != WHOLE);
        if let Some(first) = ids.next() {
            for id in ids {
                let (r1, r2) = (root(&mut parent, first), root(&mut parent, id));
                parent[r2] = r1;
            }
        }
    }
    let vertices = mesh.vertices();
    let mut contours = Vec::new();
    let mut unchecked = 0;
    for group in groups {
        let edge = group[0].0;
        let (a, b) = (&vertices[edge[0] as usize], &vertices[edge[1] as usize]);
        // The triangle's side of the eye, as if it ran from lower to higher.
        let facing = |&(_, t, forward, _): &SidePiece| {
            let [p, q, r] = mesh.triangle(t);
            let s = eye.orient3d(&p, &q, &r);
            if forward { s } else { s.reverse() }
        };
        let class = match group {
            [_] if eye.sees_end_on(a, b) => None,
            [_] => Some(EdgeClass::Boundary),
            // A diagonal of a face's triangulation: not an edge.
            [x, y] if mesh.face_of(x.1) == mesh.face_of(y.1) => continue,
            [x, y] => {
                let (fx, fy) = (facing(x), facing(y));
                let edge_on = [fx, fy].iter().filter(|&&f| f == Ordering::Equal).count();
                if eye.sees_end_on(a, b) || edge_on == 2 {
                    None
                } else if fx == fy || edge_on == 1 {
                    // Made to run the same way along the edge, their sides agree: with the
                    // triangles oriented alike (one runs the edge the other way), one is
                    // turned towards the eye and the other away. Or one is seen edge-on, and
                    // the surface seen ends at the edge.
                    Some(EdgeClass::Silhouette)
                } else {
                    continue;
                }
            }
            _ => None,
        };
        match class {
            Some(class) => contours.push(Contour {
                vertices: edge,
                class,
                // For now the side with T-junctions it is a piece of.
                chain: group.iter().find(|s| s.3 != WHOLE).map(|s| s.3),
            }),
            None => unchecked += 1,
        }
    }
    let (chains, chain_of) = Chains::new(vertices, &long, &mut parent);
    for c in &mut contours {
        c.chain = c.chain.and_then(|id| chain_of.get(id).copied());
    }
    Contours {
        contours,
        chains,
        unchecked,
    }
}

/// Check 3: the drawing's segments are the pieces'.
fn drawing(options: &Options, traced: &Traced, report: &mut Verification) {
    let key = |p: [f64; 2]| p.map(|x| (x + 0.0).to_bits());
    let segment = |class: EdgeClass, visible: bool, [p, q]: [[f64; 2]; 2]| {
        let (p, q) = (key(p), key(q));
        (class, visible, if p <= q { [p, q] } else { [q, p] })
    };
    let mut count: HashMap<(EdgeClass, bool, [[u64; 2]; 2]), i64> = HashMap::new();
    // A piece whose ends are equal, as traced at the input's scale (of zero length, or
    // rounded to one point when scaled back: `draw_traced` scales them as `Drawing::scaled`
    // scales the drawing), is not drawn.
    for p in &traced.pieces {
        if p.ends[0] != p.ends[1] && (p.visible || options.hidden) {
            *count
                .entry(segment(p.class, p.visible, p.ends))
                .or_default() += 1;
        }
    }
    for l in &traced.kept.as_ref().unwrap_or(&traced.drawing).polylines {
        for w in l.points.windows(2) {
            report.segments += 1;
            *count
                .entry(segment(l.class, l.visible, [w[0], w[1]]))
                .or_default() -= 1;
        }
    }
    let mut differing: Vec<_> = count.into_iter().filter(|&(_, n)| n != 0).collect();
    differing.sort_unstable_by_key(|x| x.0);
    for ((class, visible, [p, q]), n) in differing {
        let point = |k: [u64; 2]| {
            let [x, y] = k.map(f64::from_bits);
            format!("({x}, {y})")
        };
        let what = |n: i64| {
            format!(
                "{} {} {} segment{}",
                n.abs(),
                if visible { "visible" } else { "hidden" },
                class.name(),
                if n.abs() == 1 { "" } else { "s" }
            )
        };
        let (expected, found) = if n > 0 {
            (what(n), "none drawn".to_string())
        } else {
            ("no piece".to_string(), what(n))
        };
        report.disagree(Disagreement {
            check: Check::Drawing,
            object: String::new(),
            line: format!("segment {}–{}", point(p), point(q)),
            at: "its ends".to_string(),
            expected,
            found,
        });
    }
}
