//! Tiles: a drawing made window by window, on as many machines as there are windows, and
//! stitched into the same drawing as one whole pass, bit for bit.
//!
//! A [`Window`] of the picture is a half-open rectangle; its bounds are planes of space (the
//! points whose picture lies on a bound: through the eye of a perspective view, along the
//! lines of sight of an orthographic one). A tile is the hidden-line pass of the module above
//! with those planes added to the view's own clipping:
//!
//! - **Only what can reach the window.** An object whose CBOX lies wholly outside one of the
//!   window's planes (by more than rounding could account for) is left out of the pass: none
//!   of its faces can hide a point inside the window, for the line of sight from that point
//!   stays on the point's side of every plane, and none of its edges has a piece there. An
//!   edge wholly outside is left out the same way. What is left out is a filter, never a
//!   decision: every sign is still exact.
//! - **Cut where a line leaves the window, exactly.** A line crossing a window's plane is cut
//!   where it crosses it, like any other cut: the zero of an exact form along the line, its
//!   point built once from the input coordinates. The plane is the same double-valued form in
//!   the two tiles on either side, so both build the same point. Its pieces outside the
//!   window are left out, decided by the exact sign of the plane's form at a point inside
//!   each piece; the windows are half open, so every point of every line is in exactly one
//!   tile.
//! - **Everything else as in the whole pass.** Every other cut of a line inside the window is
//!   made by a contour or a face of an object that reaches the window, so the tile has the
//!   same cuts there, named by the same keys (the lines keep their order, so the smallest key
//!   is the same cut); each piece is decided by the same exact queries. Where a window's plane
//!   passes through another cut, that cut is drawn (a window's cut has the largest key).
//!
//! [`stitch`] then puts each line's pieces in order along it and joins those that meet where
//! a window's plane passes, with the same visibility, decided exactly: each piece carries
//! what its ends are (an end of its line, or a cut with its form), so the order of two ends
//! along the line is an exact sign and a border's cut is never kept as a point of the
//! drawing, however near it passes to a vertex or another cut (the rough parameters along the
//! line, which can disagree with the exact order by a few units in the last place, order
//! nothing). Lines are named the same in every tile (an edge by its object and its index, an
//! intersection segment by its two objects and its index) and ordered as the whole pass
//! orders them; where ends of two tiles are one point, the one named by the smallest key is
//! drawn. Then the pieces are finished as the whole pass finishes them (hidden ones dropped
//! unless asked for, each stretch drawn once when asked, see `overlaps`, and chained): the
//! polylines of [`draw`](super::draw), bit for bit (`tests/tiles.rs` checks it on every
//! bundled scene, in random views and grids, with borders through vertices, cuts and
//! crossings and one unit in the last place beside them).
//!
//! A tile travels between processes as bytes ([`TileDrawing::to_bytes`], see `bytes.rs`):
//! the Python package renders tiles on Dask workers and stitches them on the client. As a
//! file ([`TileFile`], see `file.rs`) it also carries its place in its grid and a fingerprint
//! of its scene, view and options: `kepler render --tiles 4x4 --tile 2,3 -o t.kpt` draws one
//! and `kepler stitch *.kpt -o out.svg` checks the set and finishes the drawing.
//!
//! ```
//! use kepler::{geometry::Vector3, scene::Scene, views::View};
//! use kepler::hidden::{Options, draw, tiles::{draw_tile, stitch, tile_windows}};
//! let mut scene = Scene::new();
//! scene.add_mesh(None, "cube", kepler::solids::cube(2.0).unwrap()).unwrap();
//! let view = View::orthographic(Vector3::new(-1.0, -2.0, -3.0), Vector3::z()).unwrap();
//! let options = Options::default();
//! let tiles: Vec<_> = tile_windows(&scene, &view, [3, 2]).unwrap().iter()
//!     .map(|w| draw_tile(&scene, &view, &options, w).unwrap())
//!     .collect();
//! let whole = draw(&scene, &view, &options).unwrap();
//! assert_eq!(stitch(&tiles, &options).unwrap().polylines, whole.polylines);
//! ```

mod bytes;
mod file;
mod stitcher;

pub use bytes::TileDrawing;
pub use file::{TileFile, TileSet};
pub use stitcher::Stitcher;

use super::marks::{Mark, MarkKey, Provenance, cut_key, point_of};
use super::piece::Piece;
use super::{Cut, DrawError, Drawing, Options, Result, decided};
use crate::scene::Scene;
use crate::sight::collinear::{LinePoint, Support};
use crate::sight::frustum::{TilePlanes, pictured};
use crate::sight::range::{in_working_range, working_shift};
use crate::views::{Eye, Picture, View, Window};
use bytes::{TileLine, TileMark, TilePiece};
use std::cmp::Ordering;
use std::collections::HashMap;

pub(crate) use super::line::LineId;

/// Draws the part of the drawing of `scene` from `view` inside `window` (in the view's
/// picture coordinates), from the objects whose CBOX may reach it: see the module
/// documentation. Its pieces keep their hidden parts whatever `options.hidden` says;
/// [`stitch`] applies it, and `options.overlaps`.
///
/// ```
/// use kepler::{scene::Scene, views::{View, Window}, hidden::{Options, tiles::draw_tile}};
/// let mut scene = Scene::new();
/// scene.add_mesh(None, "cube", kepler::solids::cube(2.0).unwrap()).unwrap();
/// let all = draw_tile(&scene, &View::standard(), &Options::default(), &Window::ALL).unwrap();
/// // Seen from above: the top square visible, the bottom one hidden under it.
/// assert_eq!(all.len(), 8);
/// ```
pub fn draw_tile(
    scene: &Scene,
    view: &View,
    options: &Options,
    window: &Window,
) -> Result<TileDrawing> {
    let shift = working_shift(scene, view);
    let perspective = view.is_perspective();
    // An orthographic picture scales with the scene.
    let window = if perspective {
        *window
    } else {
        window.scaled(shift)
    };
    let (tile, _) = in_working_range::<_, DrawError>(scene, view, |scene, view| {
        let planes = TilePlanes::of(view, &window)?;
        let (pass, pieces) = decided(scene, view, planes, options, &|_, _| {})?;
        // The tile's lines, each once, in the pass's order.
        let mut index: HashMap<usize, u32> = HashMap::new();
        let mut lines = Vec::new();
        let mut line_of = |l: usize| {
            *index.entry(l).or_insert_with(|| {
                lines.push(TileLine {
                    id: pass.lines[l].id,
                    class: pass.lines[l].class,
                    support: pass.support(l),
                    keys: [pass.key(l, Mark::First), pass.key(l, Mark::Last)],
                });
                (lines.len() - 1) as u32
            })
        };
        let mark = |m: Mark| match m {
            Mark::First => TileMark::First,
            Mark::Last => TileMark::Last,
            Mark::Cut(k) => TileMark::Cut(pass.cuts[k as usize].1),
        };
        let pieces: Vec<TilePiece> = pieces
            .iter()
            .map(|p| TilePiece {
                line: line_of(p.line),
                visible: p.visible,
                ends: p.ends,
                t: p.t,
                border: p.border,
                marks: p.marks.map(mark),
            })
            .collect();
        Ok(TileDrawing {
            lines,
            pieces,
            shift,
            perspective,
            eye: pass.eye,
            slack: pass.slack,
        })
    })?;
    Ok(tile)
}

/// A grid of `n[0]` by `n[1]` windows over the picture of the scene (see [`Window::grid`]):
/// split evenly over the pictures of the corners of the objects' CBOXes, or over the view's
/// window when it clips (an eye inside the scene). The windows cover the whole picture, so
/// how they split it changes only how the work is shared.
///
/// ```
/// use kepler::{scene::Scene, views::View, hidden::tiles::tile_windows};
/// let mut scene = Scene::new();
/// scene.add_mesh(None, "cube", kepler::solids::cube(2.0).unwrap()).unwrap();
/// let w = tile_windows(&scene, &View::standard(), [2, 2]).unwrap();
/// assert_eq!(w[0].x[1], 0.0);
/// ```
pub fn tile_windows(scene: &Scene, view: &View, n: [usize; 2]) -> Result<Vec<Window>> {
    let (meshes, clip) = pictured(scene, view)?;
    let (low, high) = match (clip, view.window()) {
        (Some(_), Some([h, v])) => ([-h, -v], [h, v]),
        _ => {
            let picture = Picture::of(view);
            let mut low = [f64::INFINITY; 2];
            let mut high = [f64::NEG_INFINITY; 2];
            for (id, _) in meshes {
                for corner in scene.cbox(id).corners() {
                    let p = picture.point(&corner);
                    for k in 0..2 {
                        if p[k].is_finite() {
                            low[k] = low[k].min(p[k]);
                            high[k] = high[k].max(p[k]);
                        }
                    }
                }
            }
            if !(low[0] <= high[0] && low[1] <= high[1]) {
                return Ok(vec![Window::ALL]);
            }
            (low, high)
        }
    };
    Ok(Window::grid(low, high, n)?)
}

/// The drawing of the tiles of a grid ([`draw_tile`] on each of its windows, in any order):
/// each line's pieces in exact order along it, those that meet where a window's plane passes
/// with the same visibility joined, the pieces in the order of the whole pass, finished as the
/// whole pass finishes them (see the module documentation). Equal, polyline for polyline and
/// bit for bit, to [`draw`](super::draw) of the same scene, view and options when the windows
/// cover the picture once (a grid of [`tile_windows`]). The drawing has no stage reports. An
/// error for tiles of different scenes or views.
///
/// ```
/// use kepler::hidden::{Options, tiles::{TileDrawing, stitch}};
/// let d = stitch(&[TileDrawing::empty()], &Options::default()).unwrap();
/// assert!(d.polylines.is_empty());
/// ```
pub fn stitch(tiles: &[TileDrawing], options: &Options) -> Result<Drawing> {
    let mut stitcher = Stitcher::default();
    for tile in tiles {
        stitcher.add(tile)?;
    }
    stitcher.finish(options)
}

/// Whether two eyes are the same, bit for bit.
fn same_eye(a: &Eye, b: &Eye) -> bool {
    let bits = |e: &Eye| match e {
        Eye::Point(p) => (0, p.coords.map(f64::to_bits)),
        Eye::Infinity(u) => (1, u.map(f64::to_bits)),
    };
    bits(a) == bits(b)
}

/// The tiles' lines and cuts in one table, as the whole pass would hold them: what the
/// stitched pieces refer to.
struct Stitched {
    eye: Eye,
    slack: f64,
    /// The lines, in the whole pass's order (by name).
    lines: Vec<TileLine>,
    cuts: Vec<Cut>,
    /// Every tile's pieces, on these lines and cuts.
    pieces: Vec<Piece>,
}

impl Stitched {
    /// The exact order of two marks of line `l`.
    fn compare(&self, l: usize, x: Mark, y: Mark) -> Ordering {
        let rank = |m: Mark| match m {
            Mark::First => 0,
            Mark::Cut(_) => 1,
            Mark::Last => 2,
        };
        match (x, y) {
            (Mark::Cut(i), Mark::Cut(j)) => match &self.lines[l].support {
                Support::Edge([a, b]) => {
                    let (zi, zj) = (&self.cuts[i as usize].zero, &self.cuts[j as usize].zero);
                    zi.compare(zj, &self.eye, a, b)
                }
                Support::Meet { meet, .. } => {
                    let (p, q) = (self.cuts[i as usize].point(), self.cuts[j as usize].point());
                    meet.compare(&self.eye, &p, &q)
                }
            },
            _ => rank(x).cmp(&rank(y)),
        }
    }

    /// The pieces by line in exact order along it, those that meet at a window's border with
    /// the same visibility joined; where two pieces meet at one point, it is drawn as the end
    /// with the smaller key.
    fn joined(&mut self) -> Vec<Piece> {
        let mut pieces = std::mem::take(&mut self.pieces);
        pieces.sort_by(|p, q| {
            p.line
                .cmp(&q.line)
                .then_with(|| self.compare(p.line, p.marks[0], q.marks[0]))
        });
        let mut joined: Vec<Piece> = Vec::with_capacity(pieces.len());
        for p in pieces {
            let Some(last) = joined.last_mut() else {
                joined.push(p);
                continue;
            };
            let meet = last.line == p.line
                && last.border[1]
                && p.border[0]
                && self.compare(p.line, last.marks[1], p.marks[0]) == Ordering::Equal;
            if meet && last.visible == p.visible {
                last.ends[1] = p.ends[1];
                last.t[1] = p.t[1];
                last.border[1] = p.border[1];
                last.marks[1] = p.marks[1];
                continue;
            }
            let mut p = p;
            if meet {
                // One point seen from two tiles: drawn as the end with the smaller key.
                let (kx, ky) = (
                    self.key(p.line, last.marks[1]),
                    self.key(p.line, p.marks[0]),
                );
                if ky < kx {
                    last.ends[1] = p.ends[0];
                    last.marks[1] = p.marks[0];
                } else {
                    p.ends[0] = last.ends[1];
                    p.marks[0] = last.marks[1];
                }
            }
            joined.push(p);
        }
        joined
    }
}

impl Provenance for Stitched {
    fn eye(&self) -> &Eye {
        &self.eye
    }

    fn slack(&self) -> f64 {
        self.slack
    }

    fn support(&self, line: usize) -> Support {
        self.lines[line].support
    }

    fn point(&self, line: usize, mark: Mark) -> LinePoint {
        point_of(&self.lines[line].support, mark, |k| {
            self.cuts[k as usize].zero
        })
    }

    fn key(&self, line: usize, mark: Mark) -> MarkKey {
        match mark {
            Mark::First => self.lines[line].keys[0],
            Mark::Last => self.lines[line].keys[1],
            Mark::Cut(k) => cut_key(self.cuts[k as usize].key),
        }
    }
}
