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
//!    with input planes, ordered along the line exactly (see `sight::meet`).
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
//! One step per file: `pass.rs` holds the pass's state and runs stages 1 to 4 in order;
//! `edges.rs` (stage 1, with the classification of a mesh's edges), `intersections.rs`
//! (stage 2), `cuts.rs` (stage 3, deciding each crossing in `crossing.rs`), `visibility.rs`
//! (stage 4, each line's pieces in `pieces.rs`, gathered into runs by `runs.rs`, against the
//! occluder index of `cover.rs`) and `chain.rs` (stage 5, after overlap removal in
//! `overlaps/`); `line.rs` holds the lines and cuts the stages pass along, `marks.rs` what a
//! piece's ends are exactly, `drawing.rs` the result.
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
mod crossing;
mod cuts;
mod drawing;
mod edges;
mod finish;
mod hubs;
pub mod ideographs;
mod intersections;
mod line;
mod marks;
mod overlaps;
mod pass;
mod piece;
mod pieces;
mod runs;
pub mod tiles;
pub mod verify;
mod visibility;

pub use drawing::{Drawing, EdgeClass, Polyline, StageReport};
pub use overlaps::OverlapReport;

use crate::geometry::Point3;
use crate::geometry::exact::ldexp;
use crate::scene::{Scene, SceneError};
use crate::sight::range::in_working_range;
use crate::views::{View, ViewError};
// The pass's parts, named here for the files that read them through `super` (tiles, verify,
// marks, overlaps).
use finish::{chained, finished};
use line::{Cut, Line, MeetLine};
use pass::{Pass, decided};
use piece::Piece;

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
