//! Hidden lines: the edges of a scene as a line drawing, split into their visible and hidden
//! pieces, exactly.
//!
//! The pass, for one [`View`]:
//! 1. **Edges.** Every side of a polygon face, once, classified by exact signs (see
//!    [`EdgeClass`]): silhouette, boundary, crease, smooth; edges between coplanar faces and
//!    edges seen end-on are not part of the drawing.
//! 2. **Intersection lines.** Where faces pierce each other, between objects whose CBOXes
//!    overlap and within each object: each a segment of the line where two faces' planes meet,
//!    from face boundary to face boundary, its ends input vertices or crossings of input edges
//!    with input planes, ordered along the line exactly (see `queries::meet`).
//! 3. **Cuts.** Visibility along an edge can change only where its picture crosses the picture
//!    of a contour edge (silhouette or boundary, including the edges of faces seen edge-on) or
//!    where the edge pierces a face. Franklin's uniform grid ([`crate::grid`]) finds the
//!    candidate crossings among the pictures; each is decided exactly in 3-D with the eye's
//!    predicates, and a contour behind the line at the crossing changes nothing and cuts
//!    nothing. A line whose picture lies on a contour's (both in one plane through the eye) is
//!    cut at the pictures of the contour's ends and where it crosses the planes of the
//!    contour's faces. Piercings come from step 2: where an edge passes through a face, and where an
//!    intersection line passes through a third face (a triple point).
//! 4. **Visibility.** Each piece between cuts is decided by one VISP query at a point inside
//!    it, through the object hierarchy (CBOX rejects, INBOX accepts, then the faces near the
//!    line of sight, from an R-tree). The point is never rounded: every face test is evaluated
//!    exactly at it (see `along.rs`), so an edge lying on another object's face is on it. On an
//!    intersection line, the cuts are ordered exactly and each piece is decided at a point
//!    strictly inside it defined from the input (`Meet::sign_between`).
//!    A face hides the point when the point is strictly behind its plane and the line of sight
//!    meets the closed face.
//! 5. **Chains.** Consecutive pieces of one edge with the same visibility merge; pieces of one
//!    class and visibility that share an end are chained into maximal polylines.
//!
//! [`verify`] checks a drawing against answers found independently (`kepler render --verify`).
//!
//! Every vertex of the drawing is the picture of an input vertex, of a cut (where an edge's
//! picture crosses a contour's, or where it pierces a face; on an intersection line, where a
//! third face or a contour's plane of sight crosses it), or of an intersection line's end,
//! each built once from input coordinates and exact expansions and rounded once (see
//! [`Picture`]): within 1.5 units in the last place of the exact point (2 for a perspective
//! view's vertices). Of several cuts at one point, the one named by the smallest indices is
//! drawn, so the drawing is the same, bit for bit, under mirroring, face reversal, axis
//! permutation, scaling by powers of two and exact translations of scene and eye (those that
//! leave the exact picture unchanged: any in perspective, along the view in orthographic).
//!
//! Picture coordinates: `x` to the right, `y` up; scene units for an orthographic view; for a
//! perspective view, the field of view spans `y` in `[-1, 1]`. A perspective view with part of
//! the scene not strictly in front of its eye (an eye inside a room or a street) draws the
//! parts of lines inside its frustum (see `queries/frustum.rs`).
//!
//! ```
//! use kepler::{geometry::Vector3, scene::Scene, views::View};
//! use kepler::hidden::{EdgeClass, Options, draw};
//! let mut scene = Scene::new();
//! scene.add_mesh(None, "cube", kepler::solids::cube(2.0).unwrap()).unwrap();
//! let view = View::orthographic(Vector3::new(-1.0, -2.0, -3.0), Vector3::z()).unwrap();
//! let drawing = draw(&scene, &view, &Options::default()).unwrap();
//! // Six silhouette edges around the outline, three creases inside it: all visible.
//! let visible = |c| drawing.polylines.iter().filter(|p| p.visible && p.class == c)
//!     .map(|p| p.points.len() - 1).sum::<usize>();
//! assert_eq!((visible(EdgeClass::Silhouette), visible(EdgeClass::Crease)), (6, 3));
//! ```

mod chain;
mod cover;
mod drawing;
mod edges;
pub mod ideographs;
mod marks;
mod overlaps;
pub mod tiles;
pub mod verify;

pub use drawing::{Drawing, EdgeClass, Polyline, StageReport};
pub use overlaps::OverlapReport;

use crate::geometry::exact::ldexp;
use crate::geometry::kernel::Polynomial;
use crate::geometry::predicates::{collinear, orient3d};
use crate::geometry::{Aabb, Point3};
use crate::grid::SegmentGrid;
use crate::mesh::Mesh;
use crate::queries::Counters;
use crate::queries::along::{Form, Sample, Zero, cut_point, hides_at};
use crate::queries::collinear::corners;
use crate::queries::frustum::{Clip, Framed, FramedLine, TilePlanes, contour_in_front, pictured};
use crate::queries::intersections;
use crate::queries::meet::{Meet, OnLine, balance, reversed};
use crate::queries::own_solid::turned_away;
use crate::queries::range::in_working_range;
use crate::queries::visp::Visibility;
use crate::scene::{ObjectId, Scene, SceneError};
use crate::views::{Eye, Picture, View, ViewError};
use chain::{Piece, chain};
use cover::{Occluders, PicturedMesh};
use geo::{Line as GeoLine, coord};
use marks::{Mark, MarkKey};
use rayon::prelude::*;
use rstar::RTree;
use rstar::primitives::{GeomWithData, Rectangle};
use std::cmp::Ordering;
use std::collections::HashMap;
use std::sync::atomic::{AtomicU64, Ordering as Atomic};
use std::time::Instant;
use tiles::LineId;

/// Why a drawing could not be made: the hidden-line layer's error.
///
/// ```
/// use kepler::{geometry::{Point3, Vector3}, hidden::{DrawError, Options, draw}, scene::Scene, views::View};
/// let mut scene = Scene::new();
/// scene.add_mesh(None, "cube", kepler::solids::cube(2.0).unwrap()).unwrap();
/// // An eye inside the cube: the view clips to its frustum and draws.
/// let inside = View::perspective(Point3::origin(), Point3::new(1.0, 0.0, 0.0), Vector3::z(), 40.0).unwrap();
/// assert!(draw(&scene, &inside, &Options::default()).is_ok());
/// let e = DrawError::from(kepler::views::ViewError::EyeAtTarget);
/// assert!(e.to_string().starts_with("invalid view"));
/// ```
#[derive(Debug, thiserror::Error)]
pub enum DrawError {
    /// The scene cannot be pictured in the view.
    #[error(transparent)]
    View(#[from] ViewError),
    /// The scene to draw could not be built (see [`ideographs`]).
    #[error(transparent)]
    Scene(#[from] SceneError),
    /// Tiles that cannot be stitched together, or bytes that are not a tile (see [`tiles`]).
    #[error("tiles: {0}")]
    Tiles(String),
}

/// `Result` with the hidden-line layer's [`DrawError`].
pub type Result<T, E = DrawError> = std::result::Result<T, E>;

/// Which edges a drawing shows.
///
/// ```
/// assert_eq!(kepler::hidden::EdgeSelection::default(), kepler::hidden::EdgeSelection::Feature);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
// The command line's --edges: its `--help` lists the values by name only.
#[cfg_attr(feature = "cli", derive(clap::ValueEnum))]
pub enum EdgeSelection {
    /// Silhouette, boundary, crease and intersection edges: a scanned mesh draws as a line
    /// drawing.
    #[default]
    #[cfg_attr(feature = "cli", value(help = None::<&str>))]
    Feature,
    /// Every edge (smooth ones too) with its hidden parts removed: a wireframe. The diagonals
    /// of polygons split because they are not exactly planar are drawn only where they are
    /// feature edges.
    #[cfg_attr(feature = "cli", value(help = None::<&str>))]
    All,
    /// Every edge of the input polygons, even between coplanar faces, with its hidden parts
    /// removed (the wireframe of a polygon mesh): no diagonals of triangulated polygons, no
    /// edges of dropped degenerate faces. Edges between coplanar faces are drawn as smooth
    /// edges. A diagonal along which a polygon that is not exactly planar was split is drawn
    /// only where it is a silhouette (or a boundary), so that the outline is whole; its other
    /// diagonals (creases, smooth or flat) are not.
    #[cfg_attr(feature = "cli", value(help = None::<&str>))]
    Mesh,
}

/// Whether a drawing draws every piece of every line, or each stretch of a picture line once
/// (see `overlaps.rs`).
///
/// ```
/// assert_eq!(kepler::hidden::Overlaps::default(), kepler::hidden::Overlaps::Keep);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Overlaps {
    /// Every piece of every line, also where pieces of two lines run along one stretch of the
    /// picture (two boxes touching along an edge draw it twice).
    #[default]
    Keep,
    /// Each stretch once: of the pieces along it, the one drawn on top (visible over hidden,
    /// then the later class in [`EdgeClass::ALL`]). What a pen plotter should draw; the
    /// command line's default.
    Once,
}

/// The options of the hidden-line pass.
///
/// ```
/// let o = kepler::hidden::Options::default();
/// assert_eq!((o.crease_angle, o.hidden), (30.0, true));
/// assert_eq!(o.overlaps, kepler::hidden::Overlaps::Keep);
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Options {
    /// Which edges to draw.
    pub edges: EdgeSelection,
    /// An edge whose faces bend by more than this many degrees is a crease.
    pub crease_angle: f64,
    /// Whether the drawing keeps the hidden pieces (as polylines with `visible == false`).
    pub hidden: bool,
    /// Whether a stretch along which pieces of several lines run is drawn by each or once.
    pub overlaps: Overlaps,
}

impl Default for Options {
    fn default() -> Options {
        Options {
            edges: EdgeSelection::Feature,
            crease_angle: 30.0,
            hidden: true,
            overlaps: Overlaps::Keep,
        }
    }
}

/// Meshes with more triangles than this use no INBOX: their picture cells answer directly,
/// and the greedy INBOX of a large non-convex mesh costs more to build than it saves.
const INBOX_LIMIT: usize = 4096;

/// Below this many lines, crossings are found by testing every pair: no grid.
const FEW_LINES: usize = 64;

/// A line of the drawing before visibility: an edge or an intersection segment.
#[derive(Debug, Clone, Copy)]
struct Line {
    a: Point3,
    b: Point3,
    /// The pictures of `a` and `b`.
    ends: [[f64; 2]; 2],
    class: EdgeClass,
    /// For an intersection segment: its index in [`Pass::meets`].
    meet: Option<usize>,
    /// Whether the line is an edge between two faces turned away from the eye on a solid that
    /// the eye is outside of: then the solid itself hides all of it.
    back: bool,
    /// For an edge: the triangles on its sides (in its mesh).
    triangles: Option<[u32; 2]>,
    /// Whether the line crosses the plane of a perspective eye that clips: its picture is
    /// unbounded (see `queries/frustum.rs`).
    wide: bool,
    /// Whether the line is not wholly inside the frustum of a view that clips: its pieces
    /// outside it are not drawn.
    clipped: bool,
    /// For an edge: the index of its leaf and its ends' vertex indices (which name a cut that
    /// it makes on an intersection line the same way in a transformed scene).
    leaf: u32,
    vertices: [u32; 2],
    /// The line's name, the same in every tile of a grid (see [`tiles`]).
    id: LineId,
}

/// An intersection segment in the pass: where it lies and the faces that do not hide it.
#[derive(Debug, Clone, Copy)]
struct MeetLine {
    meet: Meet,
    ends: [OnLine; 2],
    on_faces: [(ObjectId, usize); 2],
    /// The names of its ends (see [`MarkKey`]).
    keys: [MarkKey; 2],
}

impl Line {
    /// The index among the scene's mesh objects of the edge's object (of the first object of
    /// an intersection segment): the same in every tile, so cuts are named by it.
    fn object(&self) -> u32 {
        match self.id {
            LineId::Edge(o, _) | LineId::Meet(o, _, _) => o,
        }
    }

    /// Whether the line's picture bounds regions where the visible surface changes.
    fn is_contour(&self) -> bool {
        matches!(self.class, EdgeClass::Silhouette | EdgeClass::Boundary)
    }
}

/// Where a line is cut: the zero of a form along it, strictly inside it (on an edge, with its
/// approximate parameter and a bound on that parameter's error, ordered exactly; on an
/// intersection line, a form increasing along it with a rough parameter for a first sort,
/// ordered exactly by the line). `sighted` is the picture of an input vertex when the cut is
/// where the line of sight through that vertex meets the line (collinear pictures); the other
/// cuts' pictures are built from their forms. `key` names the cut from the indices of what
/// makes it, the same in a transformed scene (of two cuts at one point, the one with the
/// smaller key is drawn).
#[derive(Debug, Clone, Copy, PartialEq)]
struct Cut {
    zero: Zero,
    sighted: Option<[f64; 2]>,
    key: [u32; 4],
}

impl Cut {
    /// A cut of an edge.
    fn on_edge(zero: Zero, sighted: Option<[f64; 2]>, key: [u32; 4]) -> Cut {
        Cut { zero, sighted, key }
    }

    /// A cut of an intersection line where `form`, increasing along it, vanishes; `t` its
    /// rough parameter.
    fn on_line(form: Form, t: f64, sighted: Option<[f64; 2]>, key: [u32; 4]) -> Cut {
        let zero = Zero {
            form,
            rising: true,
            t,
            error: f64::INFINITY,
        };
        Cut { zero, sighted, key }
    }

    /// The cut of an intersection line, as a point of it.
    fn point(&self) -> OnLine {
        OnLine::Cut(self.zero.form)
    }
}

/// Draws the scene from the view: see the module documentation.
///
/// ```
/// use kepler::{scene::Scene, views::View, hidden::{Options, draw}};
/// let mut scene = Scene::new();
/// scene.add_mesh(None, "cube", kepler::solids::cube(2.0).unwrap()).unwrap();
/// // Straight down: the top face's outline is visible, the bottom's lies under it, hidden.
/// let d = draw(&scene, &View::standard(), &Options::default()).unwrap();
/// assert_eq!(d.length(kepler::hidden::EdgeClass::Silhouette, true), 8.0);
/// assert_eq!(d.length(kepler::hidden::EdgeClass::Silhouette, false), 8.0);
/// ```
pub fn draw(scene: &Scene, view: &View, options: &Options) -> Result<Drawing> {
    draw_with_progress(scene, view, options, &|_, _| {})
}

/// [`draw`], calling `progress(done, total)` now and then while deciding visibility (the long
/// stage), from any thread.
///
/// ```
/// use kepler::{scene::Scene, views::View, hidden::{Options, draw_with_progress}};
/// use std::sync::atomic::{AtomicU64, Ordering};
/// let mut scene = Scene::new();
/// scene.add_mesh(None, "cube", kepler::solids::cube(2.0).unwrap()).unwrap();
/// let last = AtomicU64::new(0);
/// draw_with_progress(&scene, &View::standard(), &Options::default(), &|done, _| {
///     last.store(done, Ordering::Relaxed);
/// }).unwrap();
/// assert!(last.load(Ordering::Relaxed) > 0);
/// ```
pub fn draw_with_progress(
    scene: &Scene,
    view: &View,
    options: &Options,
    progress: &(dyn Fn(u64, u64) + Sync),
) -> Result<Drawing> {
    let (drawing, shift) = in_working_range::<_, DrawError>(scene, view, |scene, view| {
        let (mut pass, pieces) = decided(scene, view, None, options, progress)?;
        Ok(chained(&mut pass, pieces, options))
    })?;
    Ok(scaled_back(drawing, view.is_perspective(), shift))
}

/// A line of a drawing before its visibility is decided (stages 1 and 2): an edge of the
/// scene or a segment of an intersection line, in scene coordinates.
///
/// ```
/// use kepler::{scene::Scene, views::View, hidden::{EdgeClass, Options, strokes}};
/// let mut scene = Scene::new();
/// scene.add_mesh(None, "cube", kepler::solids::cube(2.0).unwrap()).unwrap();
/// let lines = strokes(&scene, &View::standard(), &Options::default()).unwrap();
/// // Seen from above: the eight edges of the top and bottom squares are silhouettes, the four
/// // vertical ones are seen end-on and left out.
/// assert_eq!(lines.len(), 8);
/// assert!(lines.iter().all(|s| s.class == EdgeClass::Silhouette));
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Stroke {
    /// The line's ends.
    pub ends: [Point3; 2],
    /// Its class.
    pub class: EdgeClass,
    /// For a segment of an intersection line: a triangle of each of the two faces it lies on
    /// (the line is where their planes meet, exactly).
    pub planes: Option<[[Point3; 3]; 2]>,
}

/// The lines that [`draw`] would split into visible and hidden pieces, before any visibility
/// is decided: the classified edges and the intersection segments. For measuring other ways of
/// deciding visibility (sampling each line, a z-buffer) on exactly the lines the engine draws.
/// An intersection segment's ends are rounded (each within a few units in the last place).
///
/// ```
/// use kepler::{geometry::Vector3, scene::Scene, views::View, hidden::{Options, strokes}};
/// let mut scene = Scene::new();
/// scene.add_mesh(None, "cube", kepler::solids::cube(2.0).unwrap()).unwrap();
/// let view = View::orthographic(Vector3::new(-1.0, -2.0, -3.0), Vector3::z()).unwrap();
/// assert_eq!(strokes(&scene, &view, &Options::default()).unwrap().len(), 12);
/// ```
pub fn strokes(scene: &Scene, view: &View, options: &Options) -> Result<Vec<Stroke>> {
    let (strokes, shift) = in_working_range::<_, DrawError>(scene, view, |scene, view| {
        let mut pass = Pass::new(scene, view, None)?;
        pass.edges(options);
        pass.intersections();
        Ok(pass
            .lines
            .iter()
            .map(|l| Stroke {
                ends: [l.a, l.b],
                class: l.class,
                planes: l.meet.map(|m| pass.meets[m].meet.planes),
            })
            .collect::<Vec<_>>())
    })?;
    let back = |p: &Point3| p.map(|x| ldexp(x, -shift));
    Ok(strokes
        .into_iter()
        .map(|s| Stroke {
            ends: s.ends.map(|p| back(&p)),
            class: s.class,
            planes: s.planes.map(|t| t.map(|q| q.map(|p| back(&p)))),
        })
        .collect())
}

/// A drawing made in the working range by `2^shift` brought back to the view's scale: a
/// perspective picture does not scale.
fn scaled_back(drawing: Drawing, perspective: bool, shift: i32) -> Drawing {
    if shift == 0 || perspective {
        drawing
    } else {
        drawing.scaled(-shift)
    }
}

/// Stages 1 to 4 of the pass (in one tile, with `tile`): the pass and every piece with its
/// visibility.
fn decided<'a>(
    scene: &'a Scene,
    view: &View,
    tile: Option<TilePlanes>,
    options: &Options,
    progress: &(dyn Fn(u64, u64) + Sync),
) -> Result<(Pass<'a>, Vec<Piece>)> {
    let mut pass = Pass::new(scene, view, tile)?;
    pass.edges(options);
    pass.intersections();
    pass.contour_cuts();
    let pieces = pass.visibility(progress);
    Ok((pass, pieces))
}

/// Stage 5 of the pass: the drawing chained from the pieces, each stretch of line once when
/// the options ask for it. The pass keeps the stages' reports.
fn chained(pass: &mut Pass, pieces: Vec<Piece>, options: &Options) -> Drawing {
    let clock = Instant::now();
    let (pieces, report) = finished(&*pass, pieces, options);
    match report {
        Some(r) => {
            let done = format!(
                "{} groups of {} segments on one line drawn once ({:.6} of line no longer drawn \
                 twice)",
                r.groups, r.segments, r.removed_length
            );
            pass.stage("overlaps", clock, done, None);
        }
        None => {
            let skipped = "each stretch drawn once (asked to keep overlapping pieces)";
            pass.stage("overlaps", clock, String::new(), Some(skipped.to_string()));
        }
    }
    let clock = Instant::now();
    let polylines = chain(&pieces);
    pass.stage(
        "chains",
        clock,
        format!("{} polylines from {} runs", polylines.len(), pieces.len()),
        (!options.hidden).then(|| "hidden pieces (not asked for)".to_string()),
    );
    Drawing {
        polylines,
        stages: pass.stages.clone(),
    }
}

/// The pieces a drawing chains: hidden ones dropped unless the options ask for them, each
/// stretch of a picture line once when they ask for that (with what was removed).
fn finished<P: marks::Provenance>(
    provenance: &P,
    mut pieces: Vec<Piece>,
    options: &Options,
) -> (Vec<Piece>, Option<OverlapReport>) {
    if !options.hidden {
        pieces.retain(|p| p.visible);
    }
    match options.overlaps {
        Overlaps::Once => {
            let (pieces, report) = overlaps::drawn_once(provenance, pieces);
            (pieces, Some(report))
        }
        Overlaps::Keep => (pieces, None),
    }
}

/// A mesh of the scene in the pass: its object, its vertices' pictures, and the range of its
/// edges in [`Pass::lines`].
struct Leaf<'a> {
    id: ObjectId,
    /// Its index among the scene's mesh objects, the same in every tile.
    global: u32,
    mesh: &'a Mesh,
    pictures: Vec<[f64; 2]>,
    /// When the view clips: whether each vertex is strictly in front of the eye (the others'
    /// pictures mean nothing).
    front: Vec<bool>,
    lines: std::ops::Range<usize>,
}

/// The state of one hidden-line pass, stage by stage.
struct Pass<'a> {
    scene: &'a Scene,
    eye: Eye,
    picture: Picture,
    leaves: Vec<Leaf<'a>>,
    /// The lines to draw: edges, then intersection segments.
    lines: Vec<Line>,
    /// The intersection segments, indexed by [`Line::meet`].
    meets: Vec<MeetLine>,
    /// Cuts, by line index.
    cuts: Vec<(usize, Cut)>,
    stages: Vec<StageReport>,
    /// The frustum, when the view clips (a perspective eye with part of the scene not in
    /// front of it).
    clip: Option<Clip>,
    /// The mesh objects left out as exact copies of an earlier one.
    copies: usize,
    /// The window, when the pass draws one tile of a grid (see [`tiles`]).
    tile: Option<TilePlanes>,
    /// The mesh objects left out because their CBOX lies outside the tile.
    outside_tile: usize,
    /// See [`Provenance::slack`](marks::Provenance::slack).
    slack: f64,
}

impl<'a> Pass<'a> {
    /// The pass over every mesh of the scene; a perspective view with a vertex not strictly
    /// in front of the eye clips to its frustum (see `queries/frustum.rs`).
    /// With a `tile`, the pass draws only what lies in it, from the objects whose CBOX may
    /// reach it (see [`tiles`]).
    fn new(scene: &'a Scene, view: &View, tile: Option<TilePlanes>) -> Result<Pass<'a>> {
        let picture = Picture::of(view);
        let (meshes, clip) = pictured(scene, view)?;
        // In a tile, the objects that may reach it, each with its index among all (so named
        // the same in every tile). Exact copies share their CBOX: a copy and its first are
        // left out together, so the copies found among the rest are those of the whole.
        let all = meshes.len();
        let meshes: Vec<(usize, (ObjectId, &Mesh))> = meshes
            .into_iter()
            .enumerate()
            .filter(|(_, (id, _))| {
                tile.as_ref()
                    .is_none_or(|t| !t.surely_outside(&scene.cbox(*id).corners()))
            })
            .collect();
        let outside_tile = all - meshes.len();
        let (globals, meshes): (Vec<usize>, Vec<(ObjectId, &Mesh)>) = meshes.into_iter().unzip();
        // Exact copies of an earlier mesh are left out (see [`originals`]): a copy hides
        // exactly what the first hides, meets nothing the first does not (coincident faces
        // make no intersection line), and its edges are the first's. Copies stacked in one
        // place would otherwise cost every pair of them.
        let first = originals(&meshes);
        let copies = (0..meshes.len()).filter(|&n| first[n] != n).count();
        let leaves: Vec<Leaf> = meshes
            .into_iter()
            .zip(globals)
            .enumerate()
            .filter(|(n, _)| first[*n] == *n)
            .map(|(_, ((id, mesh), global))| Leaf {
                id,
                global: global as u32,
                mesh,
                pictures: Vec::new(),
                front: Vec::new(),
                lines: 0..0,
            })
            .collect();
        let slack = picture_slack(scene, &picture, leaves.iter().map(|l| l.id));
        Ok(Pass {
            slack,
            tile,
            outside_tile,
            clip,
            scene,
            eye: *view.eye(),
            picture,
            leaves,
            lines: Vec::new(),
            meets: Vec::new(),
            cuts: Vec::new(),
            stages: Vec::new(),
            copies,
        })
    }

    /// Records a stage for `--stats`.
    fn stage(&mut self, name: &'static str, clock: Instant, done: String, skipped: Option<String>) {
        timed(&mut self.stages, name, clock, done, skipped);
    }

    /// Stage 1: every mesh's edges, classified, and its vertices' pictures; the lines to draw.
    fn edges(&mut self, options: &Options) {
        let clock = Instant::now();
        let (eye, picture, clip) = (&self.eye, &self.picture, self.clip);
        let tile = self.tile.as_ref();
        let crease_cos = -options.crease_angle.to_radians().cos();
        let classified: Vec<_> = self
            .leaves
            .par_iter()
            .map(|leaf| {
                let vertices = leaf.mesh.vertices();
                let front: Vec<bool> = match &clip {
                    Some(n) => vertices.par_iter().map(|p| n.in_front(p)).collect(),
                    None => Vec::new(),
                };
                let inside: Vec<bool> = match (&clip, tile) {
                    (None, None) => Vec::new(),
                    _ => vertices
                        .par_iter()
                        .map(|p| {
                            clip.is_none_or(|n| n.contains(eye, p))
                                && tile.is_none_or(|t| t.contains(eye, p))
                        })
                        .collect(),
                };
                let pictures: Vec<[f64; 2]> = vertices
                    .par_iter()
                    .enumerate()
                    .map(|(i, p)| match front.get(i) {
                        Some(false) => [0.0, 0.0],
                        _ => picture.point(p),
                    })
                    .collect();
                let classes = edges::classify(leaf.mesh, eye, crease_cos, options.edges);
                (classes, pictures, (front, inside))
            })
            .collect();
        let (mut flat, mut end_on, mut left_out) = (0, 0, 0);
        let mut by_class = [0usize; 5];
        let (mut behind, mut outside_tile) = (0, 0);
        for (n, (leaf, ((edges, counts), pictures, (front, inside)))) in
            self.leaves.iter_mut().zip(classified).enumerate()
        {
            let mesh = leaf.mesh;
            let away = turned_away(self.scene, leaf.id, mesh, eye);
            let first = self.lines.len();
            flat += counts.flat;
            end_on += counts.end_on;
            left_out += counts.left_out;
            for (total, n) in by_class.iter_mut().zip(counts.by_class) {
                *total += n;
            }
            for (k, e) in edges.into_iter().enumerate() {
                let (a, b) = (e.a as usize, e.b as usize);
                let in_front = |v: usize| front.get(v).is_none_or(|&f| f);
                if !in_front(a) && !in_front(b) {
                    // Wholly behind the eye: nothing of it is drawn or bounds what is seen.
                    behind += 1;
                    continue;
                }
                let ends = [mesh.vertices()[a], mesh.vertices()[b]];
                if tile.is_some_and(|t| t.surely_outside(&ends)) {
                    // Wholly outside the tile: nothing of it is drawn there, and where it
                    // crosses a contour or pierces a face is outside too.
                    outside_tile += 1;
                    continue;
                }
                let clipped = !(inside.is_empty() || inside[a] && inside[b]);
                let back = e.class != EdgeClass::Boundary
                    && away.is_some_and(|away| {
                        e.triangles.iter().all(|&t| {
                            let [p, q, r] = mesh.triangle(t as usize);
                            eye.orient3d(&p, &q, &r) == away
                        })
                    });
                self.lines.push(Line {
                    a: mesh.vertices()[a],
                    b: mesh.vertices()[b],
                    ends: [pictures[a], pictures[b]],
                    class: e.class,
                    meet: None,
                    back,
                    triangles: Some(e.triangles),
                    wide: !(in_front(a) && in_front(b)),
                    clipped,
                    leaf: n as u32,
                    vertices: [e.a, e.b],
                    id: LineId::Edge(leaf.global, k as u32),
                });
                if clipped {
                    let i = self.lines.len() - 1;
                    self.cuts
                        .extend(frustum_cuts(clip, tile, eye, (i, &self.lines[i], None)));
                }
            }
            leaf.pictures = pictures;
            leaf.front = front;
            leaf.lines = first..self.lines.len();
        }
        let count = |c: EdgeClass| by_class[c as usize];
        let done = format!(
            "{} objects: {} silhouette, {} boundary, {} crease, {} smooth edges",
            self.leaves.len(),
            count(EdgeClass::Silhouette),
            count(EdgeClass::Boundary),
            count(EdgeClass::Crease),
            count(EdgeClass::Smooth)
        );
        let smooth = match (left_out, options.edges) {
            (0, _) => String::new(),
            (n, EdgeSelection::Feature) => {
                format!(", {n} smooth edges not asked for (--edges all draws them)")
            }
            (n, EdgeSelection::All) => {
                format!(", {n} smooth diagonals of split polygons (not polygon edges)")
            }
            (n, EdgeSelection::Mesh) => {
                format!(", {n} diagonals of split polygons (not polygon edges)")
            }
        };
        let clipping = if clip.is_some() {
            format!(
                ", {behind} behind the eye (the view clips to its frustum: part of the scene \
                 is not in front of the eye)"
            )
        } else {
            String::new()
        };
        let copies = match self.copies {
            0 => String::new(),
            n => format!(", {n} objects that are exact copies of another (drawn once)"),
        };
        let tiled = match &self.tile {
            Some(_) => format!(
                ", {} objects and {outside_tile} edges outside the tile",
                self.outside_tile
            ),
            None => String::new(),
        };
        let skipped = format!(
            "{flat} edges between coplanar faces (no edge), {end_on} seen end-on (a point)\
             {smooth}{clipping}{copies}{tiled}"
        );
        self.stage("edges", clock, done, Some(skipped));
    }

    /// Stage 2: intersection lines between objects whose CBOXes overlap and within each
    /// object, and the cuts where edges pierce faces.
    fn intersections(&mut self) {
        let clock = Instant::now();
        let (eye, clip) = (self.eye, self.clip);
        let tile = self.tile.as_ref();
        let ids: Vec<ObjectId> = self.leaves.iter().map(|l| l.id).collect();
        // Each object's index among the scene's mesh objects (the same in every tile), for
        // naming cuts.
        let leaf_of: HashMap<ObjectId, u32> = self
            .leaves
            .iter()
            .map(|leaf| (leaf.id, leaf.global))
            .collect();
        let pairs = overlapping_cboxes(self.scene, &ids);
        let apart = ids.len() * (ids.len() + 1) / 2 - pairs.len();
        let leaves = &self.leaves;
        let found: Vec<(Vec<intersections::Segment>, Vec<[usize; 3]>)> = pairs
            .par_iter()
            .map(|&(i, j)| intersections::meetings(leaves[i].mesh, leaves[j].mesh, i == j, &eye))
            .collect();
        let mut segments = 0usize;
        let mut self_intersecting = Vec::new();
        // Each triangle's partners in intersections, and each line's triangles.
        let mut partners: HashMap<(ObjectId, usize), Vec<(ObjectId, usize)>> = HashMap::new();
        // The lines to cut, and each intersection line's triangles (by its index in `meets`).
        let mut crossings: Vec<usize> = Vec::new();
        let mut owned: Vec<Vec<(ObjectId, usize)>> = Vec::new();
        for (&(i, j), (found, contacts)) in pairs.iter().zip(found) {
            let (id0, id1) = (ids[i], ids[j]);
            // A triangle that crosses another's plane: an edge of it may pass through the other
            // even where their faces only touch (an edge entering a solid exactly across an
            // edge of its surface), so the other is its partner for piercings.
            for [k, t, u] in contacts {
                let (x, y) = if k == 0 {
                    ((id0, t), (id1, u))
                } else {
                    ((id1, t), (id0, u))
                };
                partners.entry(x).or_default().push(y);
            }
            for (k, s) in found.into_iter().enumerate() {
                segments += 1;
                // Which ends are in front of the eye, and whether both are inside the frustum,
                // decided exactly at the ends (points of the meet line).
                let sign_at = |k: usize| move |form: &Form| s.meet.sign_at(&eye, &s.ends[k], form);
                let front = [0, 1]
                    .map(|k| clip.is_none_or(|n| sign_at(k)(&n.depth()) == Ordering::Greater));
                let inside = [0, 1].map(|k| {
                    clip.is_none_or(|n| n.contains_by(sign_at(k)))
                        && tile.is_none_or(|t| t.contains_by(sign_at(k)))
                });
                if front == [false, false] {
                    // Wholly behind the eye: nothing of it is drawn or bounds what is seen.
                    continue;
                }
                let mut own = Vec::with_capacity(2 * s.triangles.len());
                for &[t0, t1] in &s.triangles {
                    let (x, y) = ((id0, t0), (id1, t1));
                    partners.entry(x).or_default().push(y);
                    partners.entry(y).or_default().push(x);
                    own.extend([x, y]);
                }
                owned.push(own);
                crossings.push(self.lines.len());
                self.lines.push(Line {
                    a: s.points[0],
                    b: s.points[1],
                    ends: [0, 1].map(|k| match front[k] {
                        true => s.meet.picture(&self.picture, &eye, &s.ends[k]),
                        false => [0.0, 0.0],
                    }),
                    class: EdgeClass::Intersection,
                    meet: Some(self.meets.len()),
                    back: false,
                    triangles: None,
                    wide: front != [true, true],
                    clipped: inside != [true, true],
                    leaf: 0,
                    vertices: [0; 2],
                    id: LineId::Meet(leaves[i].global, leaves[j].global, k as u32),
                });
                let meshes = [i, j].map(|n| (leaves[n].global, leaves[n].mesh));
                self.meets.push(MeetLine {
                    meet: s.meet,
                    ends: s.ends,
                    on_faces: [(id0, s.faces[0]), (id1, s.faces[1])],
                    keys: marks::end_keys(&s.ends, meshes, &s.triangles, s.faces),
                });
                let line = self.lines.len() - 1;
                if self.lines[line].clipped {
                    let meet = self.meets.last();
                    let cuts = frustum_cuts(clip, tile, &eye, (line, &self.lines[line], meet));
                    self.cuts.extend(cuts);
                }
                if i == j {
                    self_intersecting.push(i);
                }
            }
        }
        // An edge may pass through a face, and an intersection line through a third face (a
        // triple point), where it may go behind it; that face pierces a face the line lies on,
        // so it is among that face's partners. Each cut is where the face's plane (the one
        // that stands for all its triangles) vanishes on the line.
        for leaf in self.leaves.iter().filter(|_| !partners.is_empty()) {
            for l in leaf.lines.clone() {
                if self.lines[l].triangles.is_some() {
                    crossings.push(l);
                }
            }
        }
        let (mut triple, mut pierced) = (0usize, 0usize);
        let scene = self.scene;
        let triangle = |(object, t): (ObjectId, usize)| scene[object].mesh().map(|m| m.triangle(t));
        for l in crossings {
            let line = self.lines[l];
            let edge_triangles;
            let own: &[(ObjectId, usize)] = match (line.meet, line.triangles) {
                (Some(m), _) => &owned[m],
                (None, Some(triangles)) => {
                    edge_triangles = triangles.map(|t| (ids[line.leaf as usize], t as usize));
                    &edge_triangles
                }
                (None, None) => &[],
            };
            // An intersection line's box, grown by far more than the error of its approximate
            // ends (a few units in 2⁻⁴⁴ of its triangles' coordinates): a face whose box misses
            // it cannot meet the line.
            let reach = line.meet.map(|_| {
                let size = own
                    .iter()
                    .filter_map(|&t| triangle(t))
                    .flatten()
                    .fold(0.0f64, |m, p| m.max(p.coords.amax()));
                let margin = size / (1u64 << 40) as f64;
                let b = Aabb::from_points(&[line.a, line.b]);
                Aabb::new(
                    Point3::from(b.min.map(|v| v - margin)),
                    Point3::from(b.max.map(|v| v + margin)),
                )
            });
            let mut third: Vec<(ObjectId, usize)> = own
                .iter()
                .flat_map(|t| partners.get(t).into_iter().flatten().copied())
                .filter(|t| !own.contains(t))
                .collect();
            third.sort_unstable();
            third.dedup();
            for (object, t) in third {
                let Some(mesh) = self.scene[object].mesh() else {
                    continue;
                };
                let tri = mesh.triangle(t);
                match line.meet {
                    Some(m) => {
                        let MeetLine { meet, ends, .. } = &self.meets[m];
                        let apart = reach.is_some_and(|r| !r.intersects(&Aabb::from_points(&tri)));
                        if apart || on_faces(&self.meets[m], self.scene, object, t) {
                            continue;
                        }
                        let (_, plane) = intersections::plane_of(mesh, t);
                        if let Some(form) =
                            intersections::pierces_line(meet, &eye, ends, &tri, &plane)
                        {
                            triple += 1;
                            let face = mesh.face_of(t) as u32;
                            let t = rough_parameter(&eye, &form, &line.a, &line.b);
                            let key = [1, leaf_of[&object], face, 0];
                            self.cuts.push((l, Cut::on_line(form, t, None, key)));
                        }
                    }
                    None => {
                        let key = [1, leaf_of[&object], mesh.face_of(t) as u32, 0];
                        if let Some(zero) = intersections::pierces(&eye, &line.a, &line.b, mesh, t)
                        {
                            pierced += 1;
                            self.cuts.push((l, Cut::on_edge(zero, None, key)));
                        }
                    }
                }
            }
        }
        // A mesh that pierces itself is not a proper solid: its back faces decide nothing.
        for i in self_intersecting {
            let range = self.leaves[i].lines.clone();
            self.lines[range].iter_mut().for_each(|l| l.back = false);
        }
        let done = format!(
            "{segments} segments from {} object pairs with overlapping CBOXes (each object with \
             itself included); {pierced} cuts where edges pierce faces, {triple} triple points",
            pairs.len()
        );
        let skipped =
            (apart > 0).then(|| format!("{apart} object pairs whose CBOXes do not overlap"));
        self.stage("intersections", clock, done, skipped);
    }

    /// Stage 3: the cuts where a line's picture crosses the picture of a contour in front of
    /// it, from the uniform grid over the lines' pictures (or every pair, for few lines).
    fn contour_cuts(&mut self) {
        let clock = Instant::now();
        let (lines, meets, eye, leaves, clip) =
            (&self.lines, &self.meets, &self.eye, &self.leaves, self.clip);
        // The triangles on the sides of edge `j` (none for an intersection line).
        let sides = |j: usize| -> Vec<[Point3; 3]> {
            let leaf = leaves.get(leaves.partition_point(|leaf| leaf.lines.end <= j));
            match (lines[j].triangles, leaf) {
                (Some(ts), Some(leaf)) => ts.map(|t| leaf.mesh.triangle(t as usize)).to_vec(),
                _ => Vec::new(),
            }
        };
        let cuts_needed = |i: usize, j: usize| {
            (lines[j].is_contour() && !lines[i].back) || (lines[i].is_contour() && !lines[j].back)
        };
        let crossing_cuts = |i: usize, j: usize| -> Vec<(usize, Cut)> {
            let mut out = Vec::new();
            for (x, y) in [(i, j), (j, i)] {
                let found = || match lines[x].meet {
                    Some(m) => crossing_line(eye, &meets[m], &lines[x], &lines[y]),
                    None => crossing(eye, clip, &lines[x], &lines[y], || sides(y)),
                };
                if lines[y].is_contour()
                    && !lines[x].back
                    && let Some(c) = found()
                {
                    out.extend(c.into_iter().map(|c| (x, c)));
                }
            }
            out
        };
        let (found, method) = if lines.len() < FEW_LINES {
            let all: Vec<(usize, Cut)> = (0..lines.len())
                .flat_map(|i| (i + 1..lines.len()).map(move |j| (i, j)))
                .filter(|&(i, j)| cuts_needed(i, j))
                .flat_map(|(i, j)| crossing_cuts(i, j))
                .collect();
            let method = format!(
                "every pair of {} lines tested (fewer than {FEW_LINES}: no grid)",
                lines.len()
            );
            (all, method)
        } else {
            // Lines hidden by their own solid are neither cut nor contours: not in the grid.
            // When the view clips, each line is gridded by the part of its picture inside the
            // window (none: left out), or, where that cannot be bounded, tested against every
            // other line.
            let (mut gridded, mut segments, mut untamed) = (Vec::new(), Vec::new(), Vec::new());
            let mut relevant = vec![false; lines.len()];
            for (i, l) in lines.iter().enumerate().filter(|(_, l)| !l.back) {
                let framed = match clip {
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
            let grid = SegmentGrid::new(&segments);
            let candidates = grid.candidates(|i, j| cuts_needed(gridded[i], gridded[j]));
            let is_untamed = |j: usize| untamed.binary_search(&j).is_ok();
            let (relevant, is_untamed) = (&relevant, &is_untamed);
            let with_untamed: Vec<(usize, usize)> = untamed
                .iter()
                .flat_map(|&w| {
                    (0..lines.len())
                        .filter(move |&j| j != w && relevant[j] && !(is_untamed(j) && j < w))
                        .map(move |j| (w, j))
                })
                .filter(|&(i, j)| cuts_needed(i, j))
                .collect();
            let all: Vec<(usize, Cut)> = candidates
                .par_iter()
                .map(|&(i, j)| (gridded[i], gridded[j]))
                .chain(with_untamed.par_iter().copied())
                .flat_map_iter(|(i, j)| crossing_cuts(i, j))
                .collect();
            let [nx, ny] = grid.shape();
            let own = lines.iter().filter(|l| l.back).count();
            let outside = lines.len() - own - gridded.len() - untamed.len();
            let framing = match clip {
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
        };
        let done = format!(
            "{} cuts where a picture crosses a contour's; {method}",
            found.len()
        );
        self.cuts.extend(found);
        self.stage("cuts", clock, done, None);
    }

    /// The part of line `l`'s picture inside the window of a view that clips (see
    /// [`Clip::framed`]): a wide intersection line is unbounded.
    fn framed(&self, clip: &Clip, l: &Line) -> Framed {
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

    /// Stage 4: the occluder index, then the visible and hidden runs of every line.
    fn visibility(&mut self, progress: &(dyn Fn(u64, u64) + Sync)) -> Vec<Piece> {
        let clock = Instant::now();
        let meshes: Vec<PicturedMesh> = self
            .leaves
            .iter()
            .map(|l| (l.id, l.mesh, l.pictures.as_slice(), l.front.as_slice()))
            .collect();
        let queries = self.lines.iter().filter(|l| !l.back).count() + self.cuts.len();
        let occluders = Occluders::new(
            self.scene,
            (self.eye, self.picture),
            self.clip.map(|c| c.window()),
            &meshes,
            INBOX_LIMIT,
            queries,
        );
        let large = meshes
            .iter()
            .filter(|(_, m, _, _)| m.triangles().len() > INBOX_LIMIT)
            .count();
        let done = format!(
            "{} meshes' triangles listed by picture cells ({} entries)",
            meshes.len(),
            occluders.entries()
        );
        let skipped = (large > 0).then(|| {
            format!(
                "INBOX of {large} meshes of more than {INBOX_LIMIT} triangles (their picture \
                 cells answer directly)"
            )
        });
        timed(&mut self.stages, "occluders", clock, done, skipped);

        let clock = Instant::now();
        let cuts = &self.cuts;
        let lines = &self.lines;
        // The cuts grouped by line (a counting sort of their indices: the cuts stay in place).
        let mut first_cut = vec![0usize; lines.len() + 1];
        for &(l, _) in cuts.iter() {
            first_cut[l + 1] += 1;
        }
        for l in 0..lines.len() {
            first_cut[l + 1] += first_cut[l];
        }
        let mut by_line = vec![0u32; cuts.len()];
        let mut next = first_cut.clone();
        for (k, &(l, _)) in cuts.iter().enumerate() {
            by_line[next[l]] = k as u32;
            next[l] += 1;
        }
        let done = AtomicU64::new(0);
        let total = lines.len() as u64;
        let (scene, eye, picture, meets) = (self.scene, &self.eye, &self.picture, &self.meets);
        let clip = (self.clip, self.tile.as_ref());
        let decided: Vec<(Vec<Piece>, Counters)> = (0..lines.len())
            .into_par_iter()
            .map(|l| {
                let n = done.fetch_add(1, Atomic::Relaxed) + 1;
                if n.is_multiple_of(1024) || n == total {
                    progress(n, total);
                }
                let mut line_cuts: Vec<(u32, &Cut)> = by_line[first_cut[l]..first_cut[l + 1]]
                    .iter()
                    .map(|&k| (k, &cuts[k as usize].1))
                    .collect();
                line_cuts.sort_unstable_by(|x, y| x.1.zero.t.total_cmp(&y.1.zero.t));
                match lines[l].meet {
                    Some(m) => line_pieces(
                        &occluders,
                        scene,
                        eye,
                        picture,
                        clip,
                        (l, &lines[l], &meets[m]),
                        &line_cuts,
                    ),
                    None => pieces(
                        &occluders,
                        scene,
                        eye,
                        picture,
                        clip,
                        (l, &lines[l]),
                        &line_cuts,
                    ),
                }
            })
            .collect();
        let mut counters = Counters::default();
        let mut all = Vec::new();
        for (p, c) in decided {
            counters = counters.merged(&c);
            all.extend(p);
        }
        let done = format!(
            "{} pieces decided by VISP: {} by CBOX, {} by INBOX, {} by faces",
            counters.total(),
            counters.cbox,
            counters.inbox,
            counters.faces
        );
        timed(&mut self.stages, "visibility", clock, done, None);
        all
    }
}

/// How far the picture of a point of the objects `ids` may lie from the picture line of its
/// plane of sight beyond its rounding (see [`Provenance::slack`](marks::Provenance::slack)):
/// an orthographic picture's rows are rounded unit vectors, whose products with the view
/// direction are within a few units in the last place of zero, times the depth of a point
/// from the picture's origin.
fn picture_slack(scene: &Scene, picture: &Picture, ids: impl Iterator<Item = ObjectId>) -> f64 {
    if picture.is_perspective() {
        return 0.0;
    }
    let (_, origin) = picture.rows();
    let extent = ids
        .flat_map(|id| scene.cbox(id).corners())
        .fold(0.0f64, |m, c| m.max((c - origin).amax()));
    16.0 * f64::EPSILON * extent
}

/// Records a stage that started at `clock` (a free function, for stages that hold borrows of
/// the pass's other fields).
fn timed(
    stages: &mut Vec<StageReport>,
    name: &'static str,
    clock: Instant,
    done: String,
    skipped: Option<String>,
) {
    stages.push(StageReport {
        name,
        done,
        skipped,
        seconds: clock.elapsed().as_secs_f64(),
    });
}

/// The cuts on `l` where its picture meets the picture of the contour `c`: a crossing (one
/// cut), or, for collinear pictures, at the pictures of `c`'s ends inside `l` and where `l`
/// passes through the plane of one of `c`'s faces (`c_sides`, the triangles on its sides).
/// When the view clips (`clip`), a wide contour cuts only where its point behind the crossing
/// is in front of the eye.
fn crossing(
    eye: &Eye,
    clip: Option<Clip>,
    l: &Line,
    c: &Line,
    c_sides: impl Fn() -> Vec<[Point3; 3]>,
) -> Option<Vec<Cut>> {
    // Lines with a common end meet there, at the end of each: no cut (and the exact zero
    // determinants would take the predicates' slowest path).
    if l.a == c.a || l.a == c.b || l.b == c.a || l.b == c.b {
        return None;
    }
    let (sc, sd) = (
        eye.orient3d(&l.a, &l.b, &c.a),
        eye.orient3d(&l.a, &l.b, &c.b),
    );
    let (sa, sb) = (
        eye.orient3d(&c.a, &c.b, &l.a),
        eye.orient3d(&c.a, &c.b, &l.b),
    );
    let zero = Ordering::Equal;
    if [sc, sd, sa, sb].iter().all(|&s| s == zero) {
        // Collinear pictures: cut where the lines of sight through the contour's ends (those in
        // front of the eye, whose pictures are drawn) meet this line strictly inside it, each
        // the zero of the plane through the eye, the end and a point off the plane of both
        // lines. On a wide line the point may lie behind the eye: then it bounds no drawn piece.
        let sides = c_sides();
        let ends_in_front = [c.a, c.b].map(|x| clip.is_none_or(|n| n.in_front(&x)));
        let off = off_plane(eye, l, sides.iter().flatten());
        let mut cuts: Vec<Cut> = (0..2)
            .filter(|&k| ends_in_front[k])
            .filter_map(|k| {
                let zero = Form::Sight([c.a, c.b][k], off?).zero_on(eye, &l.a, &l.b)?;
                let key = [0, c.object(), c.vertices[k], 0];
                Some(Cut::on_edge(zero, Some(c.ends[k]), key))
            })
            .collect();
        // These cuts are made on a wide line too (its pictures play no part). Besides, where
        // the visibility of `l` changes at an end of `c`, the outline also leaves the plane of
        // both lines there through a contour edge ending at that end, whose crossing with `l`
        // the general case below cuts at the same point (and the grid pairs it with `l`: both
        // pictures hold the end's). So no such end is left uncut (tests/collinear_cuts.rs
        // fails only without both).
        //
        // Both lines lie in one plane through the eye, which meets a face of `c` not seen
        // edge-on only along `c`: behind `c`'s picture, `l` is hidden by the face exactly where
        // it lies behind the face's plane, so it is cut where it crosses that plane too (at an
        // end of `c` when one lies on the line of `l`: cut there already).
        let meets_end = collinear(&l.a, &l.b, &c.a) || collinear(&l.a, &l.b, &c.b);
        for tri in sides.into_iter().filter(|_| !meets_end) {
            let form = Form::Plane(tri);
            if eye.orient3d(&tri[0], &tri[1], &tri[2]) != zero
                && let Some(z) = form.zero_on(eye, &l.a, &l.b)
            {
                let [u, v] = c.vertices;
                cuts.push(Cut::on_edge(z, None, [1, c.object(), u.min(v), u.max(v)]));
            }
        }
        return Some(cuts);
    }
    if (sc == sd && sc != zero) || (sa == sb && sa != zero) {
        return None;
    }
    if let Some(n) = &clip
        && c.wide
        && !contour_in_front(n, eye, [&l.a, &l.b], [&c.a, &c.b], [sc, sd])
    {
        return None;
    }
    // Where the contour passes behind the line it changes nothing on it. Which of two lines
    // whose pictures cross is in front is the sign of orient3d(a, b, c0, c1) against the side
    // of the picture of ab that c0 lies on (the same sign when c is in front).
    let c_side = if sc != zero {
        (sc, c.a, c.b)
    } else {
        (sd, c.b, c.a)
    };
    let volume = orient3d(&l.a, &l.b, &c_side.1, &c_side.2);
    if volume != zero && volume != c_side.0 {
        return None;
    }
    let zero = Form::Sight(c.a, c.b).zero_on(eye, &l.a, &l.b)?;
    let [u, v] = c.vertices;
    Some(vec![Cut::on_edge(
        zero,
        None,
        [2, c.object(), u.min(v), u.max(v)],
    )])
}

/// A point off the plane through the eye and the edge `l` (not seen end-on): one of `near`
/// if any is, else one of four affinely independent points at the scale of `l`'s ends, of
/// which one must be. Only the plane it spans with the eye and a point of `l`'s plane matters,
/// never where it is.
fn off_plane<'p>(eye: &Eye, l: &Line, near: impl Iterator<Item = &'p Point3>) -> Option<Point3> {
    let top = l.a.coords.amax().max(l.b.coords.amax());
    near.copied()
        .chain(corners(top))
        .find(|w| eye.orient3d(&l.a, &l.b, w) != Ordering::Equal)
}

/// The cuts on the intersection line `l` (lying on `m`) where its picture meets the picture of
/// the contour `c` in front of it, decided exactly as [`crossing`] decides for an edge: the
/// sides of `c`'s ends against the plane through the line and the eye, the sides of the line's
/// ends against `c`'s sight plane, and which passes in front where they cross
/// ([`Meet::twist`]). For collinear pictures, at the lines of sight through `c`'s ends.
fn crossing_line(eye: &Eye, m: &MeetLine, l: &Line, c: &Line) -> Option<Vec<Cut>> {
    let (meet, [x, y]) = (&m.meet, &m.ends);
    let is_end = |p: &Point3| {
        [x, y]
            .iter()
            .any(|e| matches!(e, OnLine::Vertex { point, .. } if point == p))
    };
    if is_end(&c.a) || is_end(&c.b) {
        return None;
    }
    let (sc, sd) = (meet.sight_side(eye, &c.a), meet.sight_side(eye, &c.b));
    let sight = Form::Sight(c.a, c.b);
    let (sa, sb) = (meet.sign_at(eye, x, &sight), meet.sign_at(eye, y, &sight));
    let zero = Ordering::Equal;
    let rough = |form: &Form| rough_parameter(eye, form, &l.a, &l.b);
    if [sc, sd, sa, sb].iter().all(|&s| s == zero) {
        // Collinear pictures: cut where the lines of sight through the contour's ends meet the
        // line inside it, each point given by a sight plane through the end that crosses it.
        let off = *meet
            .planes
            .iter()
            .flatten()
            .find(|q| meet.sight_side(eye, q) != zero)?;
        let cuts = [0, 1]
            .into_iter()
            .filter_map(|k| {
                let (p, picture) = ([c.a, c.b][k], c.ends[k]);
                let form = meet.increasing(eye, Form::Sight(p, off));
                let inside = meet.sign_at(eye, x, &form) == Ordering::Less
                    && meet.sign_at(eye, y, &form) == Ordering::Greater;
                let key = [0, c.object(), c.vertices[k], 0];
                inside.then(|| Cut::on_line(form, rough(&form), Some(picture), key))
            })
            .collect();
        return Some(cuts);
    }
    if sa == sb || sa == zero || sb == zero || (sc == sd && sc != zero) {
        return None;
    }
    // Where the contour passes behind the line it changes nothing on it: the contour is in
    // front when its end `d` lies on the eye's side of the plane through the line and `c`.
    let volume = meet.twist(&c.a, &c.b);
    let in_front = if sc != zero {
        volume == zero || volume == sc
    } else {
        volume == zero || volume.reverse() == sd
    };
    if !in_front {
        return None;
    }
    let form = if sa == Ordering::Less {
        sight
    } else {
        reversed(&sight)
    };
    let (sighted, key) = if sc == zero {
        (Some(c.ends[0]), [0, c.object(), c.vertices[0], 0])
    } else if sd == zero {
        (Some(c.ends[1]), [0, c.object(), c.vertices[1], 0])
    } else {
        let [u, v] = c.vertices;
        (None, [2, c.object(), u.min(v), u.max(v)])
    };
    Some(vec![Cut::on_line(form, rough(&form), sighted, key)])
}

/// The parameter along `ab` where `form` vanishes, roughly (for a first sort of cuts only).
fn rough_parameter(eye: &Eye, form: &Form, a: &Point3, b: &Point3) -> f64 {
    let (fa, fb) = (
        form.at(eye, a).estimate().value,
        form.at(eye, b).estimate().value,
    );
    let t = fa / (fa - fb);
    if t.is_finite() {
        t.clamp(0.0, 1.0)
    } else {
        0.5
    }
}

/// The visible and hidden runs of the edge `l` (index `line`) cut at `cuts` (sorted by their
/// approximate parameters), and the stages that decided its pieces. The cuts are put in their
/// exact order along the edge (their parameters' error bounds leave only near ties to decide
/// exactly, and a near tie's parameter is then correctly rounded, so the pieces' ranges follow
/// that order), those at one point taken once (the smallest key); each piece between two
/// consecutive cuts is decided at a point strictly inside it ([`Sample`]).
fn pieces(
    occluders: &Occluders,
    scene: &Scene,
    eye: &Eye,
    picture: &Picture,
    (clip, tile): (Option<Clip>, Option<&TilePlanes>),
    (line, l): (usize, &Line),
    cuts: &[(u32, &Cut)],
) -> (Vec<Piece>, Counters) {
    let mut counters = Counters::default();
    if l.back && !l.clipped {
        let piece = Piece {
            class: l.class,
            visible: false,
            ends: l.ends,
            line,
            t: [0.0, 1.0],
            border: [false; 2],
            marks: [Mark::First, Mark::Last],
        };
        return (vec![piece], counters);
    }
    let (a, b) = (&l.a, &l.b);
    let order = |x: &Cut, y: &Cut| x.zero.compare(&y.zero, eye, a, b);
    // Insertion sort: the cuts come sorted by parameter, so only near ties move.
    let mut sorted = cuts.to_vec();
    for i in 1..sorted.len() {
        let mut j = i;
        while j > 0 && order(sorted[j].1, sorted[j - 1].1) == Ordering::Less {
            sorted.swap(j, j - 1);
            j -= 1;
        }
    }
    // Each point once, with whether a tile's plane passes through it.
    let mut merged: Vec<((u32, Cut), bool)> = Vec::with_capacity(sorted.len());
    for (index, c) in sorted {
        let border = c.key[0] == TILE_CUT;
        match merged.last_mut() {
            Some((last, on_border)) if order(&last.1, c) == Ordering::Equal => {
                *on_border |= border;
                if c.key < last.1.key {
                    *last = (index, *c);
                }
            }
            _ => merged.push(((index, *c), border)),
        }
    }
    // The pieces' parameter ranges in the exact order too (verify checks the pieces by them):
    // a near tie's rough parameters may be out of order, so each point near another takes its
    // parameter correctly rounded, which is monotone.
    let near: Vec<bool> = (0..merged.len())
        .map(|k| {
            let z = &merged[k].0.1.zero;
            let near = |j: usize| merged.get(j).is_some_and(|(c, _)| c.1.zero.near(z));
            (k > 0 && near(k - 1)) || near(k + 1)
        })
        .collect();
    for (((_, cut), _), near) in merged.iter_mut().zip(near) {
        if near {
            cut.zero = cut.zero.correctly_rounded(eye, a, b);
        }
    }
    let bounds: Vec<((u32, &Cut), bool)> = merged.iter().map(|((i, c), b)| ((*i, c), *b)).collect();
    let mut runs = Runs::new(l, line);
    for k in 0..=bounds.len() {
        let (lo, border) = match k.checked_sub(1).map(|k| bounds[k]) {
            Some(((index, c), border)) => (Some((index, c)), border),
            None => (None, false),
        };
        let mark = lo.map_or(Mark::First, |(index, _)| Mark::Cut(index));
        let lo = lo.map(|(_, c)| c);
        let sample = Sample::between(
            eye,
            a,
            b,
            [lo.map(|c| &c.zero), bounds.get(k).map(|c| &c.0.1.zero)],
        );
        let sign = |form: &Form| sample.sign(form, eye, a, b);
        let state = if l.clipped && !inside(clip, tile, sign) {
            None
        } else if l.back {
            Some(false)
        } else {
            let (approximate, radius) = sample.point(a, b);
            let hides = |object: ObjectId, tri: usize| {
                scene[object]
                    .mesh()
                    .is_some_and(|m| hides_at(eye, &m.triangle(tri), sign))
            };
            let answer = occluders.visp((&approximate, radius), hides, &mut counters);
            Some(answer == Visibility::Visible)
        };
        runs.step(state, (lo.map_or(0.0, |c| c.zero.t), mark), border, || {
            cut_picture(picture, eye, l, lo)
        });
    }
    (runs.finish(l.ends[1]), counters)
}

/// The visible and hidden runs of the intersection line `l` (lying on `m`) cut at `cuts`
/// (strictly inside it), and the stages that decided its pieces. The cuts are ordered along
/// the line exactly, those at one point taken once (the smallest key); each piece between two
/// consecutive points is decided at a point strictly inside it defined from the input
/// ([`Meet::sign_between`]).
fn line_pieces(
    occluders: &Occluders,
    scene: &Scene,
    eye: &Eye,
    picture: &Picture,
    (clip, tile): (Option<Clip>, Option<&TilePlanes>),
    (line, l, m): (usize, &Line, &MeetLine),
    cuts: &[(u32, &Cut)],
) -> (Vec<Piece>, Counters) {
    let meet = &m.meet;
    let mut sorted: Vec<(OnLine, (u32, &Cut))> = cuts.iter().map(|&c| (c.1.point(), c)).collect();
    // Stable: the cuts come roughly sorted already.
    sorted.sort_by(|x, y| {
        meet.compare(eye, &x.0, &y.0)
            .then(x.1.1.key.cmp(&y.1.1.key))
    });
    // Each point once (the smallest key), with whether a tile's plane passes through it.
    let mut inner: Vec<(OnLine, (u32, &Cut), bool)> = Vec::with_capacity(sorted.len());
    for (point, cut) in sorted {
        let border = cut.1.key[0] == TILE_CUT;
        match inner.last_mut() {
            Some(last) if meet.compare(eye, &last.0, &point).is_eq() => last.2 |= border,
            _ => inner.push((point, cut, border)),
        }
    }
    let points: Vec<OnLine> = std::iter::once(m.ends[0])
        .chain(inner.iter().map(|x| x.0))
        .chain(std::iter::once(m.ends[1]))
        .collect();
    let drawn = |k: usize| -> [f64; 2] {
        if k == 0 {
            return l.ends[0];
        }
        if k == points.len() - 1 {
            return l.ends[1];
        }
        match inner[k - 1].1.1.sighted {
            Some(p) => p,
            None => meet.picture(picture, eye, &points[k]),
        }
    };
    let weights: Vec<f64> = points.iter().map(|p| meet.weight(eye, p)).collect();
    let places: Vec<Point3> = points.iter().map(|p| meet.approximate(eye, p)).collect();
    let magnitudes: Vec<f64> = points.iter().map(|p| meet.magnitude(p)).collect();
    // Each point's rough parameter along the line, for the pieces' provenance.
    let along = |k: usize| {
        if k == 0 {
            (0.0, Mark::First)
        } else {
            (inner[k - 1].1.1.zero.t, Mark::Cut(inner[k - 1].1.0))
        }
    };
    let mut counters = Counters::default();
    let mut runs = Runs::new(l, line);
    for k in 0..points.len() - 1 {
        let scales = [balance(weights[k]), balance(weights[k + 1])];
        let sign = |form: &Form| meet.sign_between(eye, [&points[k], &points[k + 1]], scales, form);
        let state = if l.clipped && !inside(clip, tile, sign) {
            None
        } else {
            let (u, v) = (weights[k] * scales[0], weights[k + 1] * scales[1]);
            let approximate =
                Point3::from((places[k].coords * u + places[k + 1].coords * v) / (u + v));
            // The places are within 2⁻⁴² of their magnitudes, the weights within 2⁻⁴² of
            // theirs: the point between them is within 2⁻³⁹ of those magnitudes.
            let radius = [k, k + 1]
                .iter()
                .map(|&i| magnitudes[i].max(places[i].coords.amax()))
                .fold(0.0f64, f64::max)
                / (1u64 << 39) as f64;
            let hides = |object: ObjectId, tri: usize| {
                !on_faces(m, scene, object, tri)
                    && scene[object]
                        .mesh()
                        .is_some_and(|mesh| hides_at(eye, &mesh.triangle(tri), sign))
            };
            let answer = occluders.visp((&approximate, radius), hides, &mut counters);
            Some(answer == Visibility::Visible)
        };
        let border = k > 0 && inner[k - 1].2;
        runs.step(state, along(k), border, || drawn(k));
    }
    (runs.finish(l.ends[1]), counters)
}

/// The visible and hidden runs of a line, piece by piece; the pieces a view that clips leaves
/// out are not runs.
struct Runs {
    class: EdgeClass,
    /// The line's index in the pass.
    line: usize,
    /// Whether the line is clipped (see [`Line::clipped`]).
    clipped: bool,
    /// The picture of the line's first end.
    first: [f64; 2],
    out: Vec<Piece>,
    /// The current run.
    run: Option<Run>,
}

/// A run of pieces of one state along a line, from its start.
#[derive(Debug, Clone, Copy)]
struct Run {
    /// `None` where the view clips the line away, else the run's visibility.
    state: Option<bool>,
    /// The picture of its start.
    start: [f64; 2],
    /// Its start's rough parameter and mark.
    from: (f64, Mark),
    /// Whether a tile's plane passes through its start.
    border: bool,
}

impl Runs {
    /// Runs of line `l` (index `line`), from its first end.
    fn new(l: &Line, line: usize) -> Runs {
        Runs {
            class: l.class,
            line,
            clipped: l.clipped,
            first: l.ends[0],
            out: Vec::new(),
            run: None,
        }
    }

    /// The piece of the current run, ending at the picture `end` of the point `to`, where a
    /// tile's plane passes if `border`.
    fn piece(&self, run: &Run, end: [f64; 2], to: (f64, Mark), border: bool) -> Option<Piece> {
        let visible = run.state?;
        Some(Piece {
            class: self.class,
            visible,
            ends: [run.start, end],
            line: self.line,
            t: [run.from.0, to.0],
            border: [run.border, border],
            marks: [run.from.1, to.1],
        })
    }

    /// The next piece's state, from the point `at` (where a tile's plane passes if `border`);
    /// where it changes, the run ends at the picture `picture` of the piece's start.
    fn step(
        &mut self,
        state: Option<bool>,
        at: (f64, Mark),
        border: bool,
        picture: impl FnOnce() -> [f64; 2],
    ) {
        match self.run {
            Some(run) if run.state != state => {
                let start = picture();
                if let Some(p) = self.piece(&run, start, at, border) {
                    self.out.push(p);
                }
                self.run = Some(Run {
                    state,
                    start,
                    from: at,
                    border,
                });
            }
            None => {
                self.run = Some(Run {
                    state,
                    start: self.first,
                    from: (0.0, Mark::First),
                    border: false,
                })
            }
            _ => {}
        }
    }

    /// The runs, the last ending at `end`.
    fn finish(mut self, end: [f64; 2]) -> Vec<Piece> {
        if let Some(run) = self.run
            && let Some(p) = self.piece(&run, end, (1.0, Mark::Last), false)
        {
            self.out.push(p);
        }
        if self.clipped {
            // A drawn end is inside the frustum, in front of the eye, so its picture is finite
            // but for a cut rounded onto an end: such a piece has no length to draw.
            self.out
                .retain(|p| p.ends.iter().flatten().all(|c| c.is_finite()));
        }
        self.out
    }
}

/// Whether a point of a clipped line is drawn: inside the frustum of a view that clips and
/// inside the tile, given the exact sign of each plane's form at it.
fn inside(clip: Option<Clip>, tile: Option<&TilePlanes>, sign: impl Fn(&Form) -> Ordering) -> bool {
    clip.is_none_or(|n| n.contains_by(&sign)) && tile.is_none_or(|t| t.contains_by(&sign))
}

/// Whether triangle `tri` of `object` lies on one of the faces an intersection line runs on.
fn on_faces(m: &MeetLine, scene: &Scene, object: ObjectId, tri: usize) -> bool {
    m.on_faces
        .iter()
        .any(|&(o, f)| o == object && scene[object].mesh().is_some_and(|m| m.face_of(tri) == f))
}

/// The cuts of line `l` (index `i`) where it crosses the planes of the frustum of a view
/// that clips, and the planes of a tile, strictly inside it. A tile's cuts have the largest
/// keys (see [`TILE_CUT`]): where one falls on another cut, the other is drawn, as in the
/// whole drawing.
fn frustum_cuts(
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
const TILE_CUT: u32 = 4;

/// The picture of a cut of the edge `l` (`None`: its first end).
fn cut_picture(picture: &Picture, eye: &Eye, l: &Line, cut: Option<&Cut>) -> [f64; 2] {
    match cut {
        Some(Cut {
            sighted: Some(p), ..
        }) => *p,
        Some(c) => cut_point(picture, eye, &c.zero.form, &l.a, &l.b),
        None => l.ends[0],
    }
}

/// For each mesh object, the index of the first whose mesh is the same (the same vertices, bit
/// for bit, and the same faces and triangles): itself unless it is an exact copy.
pub(crate) fn originals(meshes: &[(ObjectId, &Mesh)]) -> Vec<usize> {
    use std::hash::{Hash, Hasher};
    let key = |m: &Mesh| {
        let mut h = std::collections::hash_map::DefaultHasher::new();
        for p in m.vertices() {
            p.map(f64::to_bits).hash(&mut h);
        }
        m.triangles().hash(&mut h);
        h.finish()
    };
    let keys: Vec<u64> = meshes.par_iter().map(|(_, m)| key(m)).collect();
    let mut seen: HashMap<u64, Vec<usize>> = HashMap::new();
    let mut first = Vec::with_capacity(meshes.len());
    for (n, (&(_, m), k)) in meshes.iter().zip(keys).enumerate() {
        let earlier = seen.entry(k).or_default();
        let same = earlier.iter().copied().find(|&e| {
            let o = meshes[e].1;
            o.vertices() == m.vertices()
                && o.triangles() == m.triangles()
                && o.faces().len() == m.faces().len()
                && o.faces()
                    .iter()
                    .zip(m.faces())
                    .all(|(f, g)| f.vertices() == g.vertices())
        });
        first.push(same.unwrap_or_else(|| {
            earlier.push(n);
            n
        }));
    }
    first
}

/// Every pair `(i, j)`, `i <= j`, of the objects `ids` whose CBOXes meet (closed boxes), in
/// increasing order: a simultaneous descent of an R-tree of the CBOXes with itself.
fn overlapping_cboxes(scene: &Scene, ids: &[ObjectId]) -> Vec<(usize, usize)> {
    let boxes: Vec<GeomWithData<Rectangle<[f64; 3]>, usize>> = ids
        .iter()
        .enumerate()
        .map(|(i, &id)| {
            let b = scene.cbox(id);
            GeomWithData::new(Rectangle::from_corners(b.min, b.max), i)
        })
        .collect();
    let tree = RTree::bulk_load(boxes);
    let mut pairs: Vec<(usize, usize)> = tree
        .intersection_candidates_with_other_tree(&tree)
        .filter(|(a, b)| a.data <= b.data)
        .map(|(a, b)| (a.data, b.data))
        .collect();
    pairs.sort_unstable();
    pairs
}
