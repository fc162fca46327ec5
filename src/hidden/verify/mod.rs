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

//!
//! One file per part: `trace.rs` makes the traced drawing, `visibility.rs` does check 1,
//! `contours.rs` check 2 (with the sign test in `sign_test.rs`), `drawing.rs` check 3, and
//! `report.rs` holds what the checks found.

mod contours;
mod drawing;
mod report;
mod sign_test;
mod trace;
mod visibility;

pub use report::{Check, Disagreement, Verification};
pub use trace::{Source, Traced, TracedPiece, draw_traced};

use super::Options;
use crate::scene::Scene;
use crate::views::View;
use std::time::Instant;

/// The fractions of a piece's parameter range where its visibility is checked: not its
/// midpoint, where the pass decided it.
pub const SAMPLES: [f64; 4] = [0.125, 0.375, 0.625, 0.875];

/// A sample closer than this many units in the last place to an end of its piece is not
/// checked: an end's parameter is rounded, the point it stands for is exact.
pub const NEAR_END_ULPS: f64 = 64.0;

/// How many disagreements a [`Verification`] describes.
pub const DESCRIBED: usize = 10;

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
    visibility::visibility(scene, view, traced, &mut report);
    contours::contours(scene, view, traced, &mut report);
    drawing::drawing(options, traced, &mut report);
    report.seconds = clock.elapsed().as_secs_f64();
    report
}
