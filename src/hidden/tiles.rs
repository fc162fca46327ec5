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
//! [`stitch`] then joins the pieces of each line that meet where a window's plane passes,
//! with the same visibility, puts the pieces in the order of the whole pass (lines are named
//! the same in every tile: an edge by its object and its index, an intersection segment by
//! its two objects and its index) and chains them: the polylines of [`draw`](super::draw),
//! bit for bit (`tests/tiles.rs` checks it on every bundled scene, in several views and grids).
//!
//! A tile travels between processes as bytes ([`TileDrawing::to_bytes`]): the Python package
//! renders tiles on Dask workers and stitches them on the client.
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

use super::chain::{Piece, chain};
use super::{DrawError, Drawing, EdgeClass, Options, Result, decided, scaled_back};
use crate::queries::frustum::{TilePlanes, pictured};
use crate::queries::range::{in_working_range, working_shift};
use crate::scene::Scene;
use crate::views::{Picture, View, Window};

/// A line's name, the same in every tile: an edge by its mesh object (its index among the
/// scene's mesh objects) and its index among the object's classified edges; an intersection
/// segment by its two objects and its index among their segments. Ordered as the whole pass
/// orders its lines.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub(crate) enum LineId {
    /// An edge: object, index.
    Edge(u32, u32),
    /// An intersection segment: objects, index.
    Meet(u32, u32, u32),
}

/// A piece of a line drawn in a tile.
#[derive(Debug, Clone, Copy, PartialEq)]
struct TilePiece {
    id: LineId,
    class: EdgeClass,
    visible: bool,
    ends: [[f64; 2]; 2],
    /// The range of the line's parameter it covers (rough: for ordering only).
    t: [f64; 2],
    /// Whether a window's plane passes through each end.
    border: [bool; 2],
}

/// The pieces of one window of a drawing, ready to be [`stitch`]ed with the other windows of
/// a grid, in the working range of the scene (see `queries/range.rs`; [`stitch`] scales them
/// back).
///
/// ```
/// use kepler::{scene::Scene, views::{View, Window}, hidden::{Options, tiles::{TileDrawing, draw_tile}}};
/// let mut scene = Scene::new();
/// scene.add_mesh(None, "cube", kepler::solids::cube(2.0).unwrap()).unwrap();
/// let left = Window::new([f64::NEG_INFINITY, 0.5], [f64::NEG_INFINITY, f64::INFINITY]).unwrap();
/// let tile = draw_tile(&scene, &View::standard(), &Options::default(), &left).unwrap();
/// assert!(!tile.is_empty());
/// assert_eq!(TileDrawing::from_bytes(&tile.to_bytes()).unwrap(), tile);
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct TileDrawing {
    pieces: Vec<TilePiece>,
    /// The working range's power of two.
    shift: i32,
    /// Whether the view is a perspective one (its picture does not scale).
    perspective: bool,
}

/// The first bytes of a tile's bytes, with the format's version.
const MAGIC: &[u8; 8] = b"KTILE\x00\x00\x01";

/// Bytes per piece: the name (13), class and flags (2), parameters and ends (48).
const PIECE_BYTES: usize = 13 + 2 + 6 * 8;

impl TileDrawing {
    /// How many pieces the tile drew.
    ///
    /// ```
    /// use kepler::{scene::Scene, views::{View, Window}, hidden::{Options, tiles::draw_tile}};
    /// let mut scene = Scene::new();
    /// scene.add_mesh(None, "cube", kepler::solids::cube(2.0).unwrap()).unwrap();
    /// let far = Window::new([100.0, 200.0], [0.0, 1.0]).unwrap();
    /// assert_eq!(draw_tile(&scene, &View::standard(), &Options::default(), &far).unwrap().len(), 0);
    /// ```
    pub fn len(&self) -> usize {
        self.pieces.len()
    }

    /// Whether the tile drew nothing.
    ///
    /// ```
    /// let t = kepler::hidden::tiles::TileDrawing::from_bytes(&kepler::hidden::tiles::TileDrawing::empty().to_bytes()).unwrap();
    /// assert!(t.is_empty());
    /// ```
    pub fn is_empty(&self) -> bool {
        self.pieces.is_empty()
    }

    /// A tile with nothing drawn in it (of an orthographic view in the working range).
    ///
    /// ```
    /// assert!(kepler::hidden::tiles::TileDrawing::empty().is_empty());
    /// ```
    pub fn empty() -> TileDrawing {
        TileDrawing {
            pieces: Vec::new(),
            shift: 0,
            perspective: false,
        }
    }

    /// The tile as bytes, to send to another process ([`TileDrawing::from_bytes`] reads
    /// them back; doubles are kept bit for bit, little-endian).
    ///
    /// ```
    /// let b = kepler::hidden::tiles::TileDrawing::empty().to_bytes();
    /// assert_eq!(b.len(), 8 + 4 + 1 + 8);
    /// ```
    pub fn to_bytes(&self) -> Vec<u8> {
        let mut out = Vec::with_capacity(21 + PIECE_BYTES * self.pieces.len());
        out.extend_from_slice(MAGIC);
        out.extend_from_slice(&self.shift.to_le_bytes());
        out.push(self.perspective as u8);
        out.extend_from_slice(&(self.pieces.len() as u64).to_le_bytes());
        for p in &self.pieces {
            let (kind, names) = match p.id {
                LineId::Edge(o, k) => (0u8, [o, k, 0]),
                LineId::Meet(o, q, k) => (1u8, [o, q, k]),
            };
            out.push(kind);
            for n in names {
                out.extend_from_slice(&n.to_le_bytes());
            }
            out.push(p.class as u8);
            out.push(p.visible as u8 | (p.border[0] as u8) << 1 | (p.border[1] as u8) << 2);
            for x in p.t.iter().chain(p.ends.iter().flatten()) {
                out.extend_from_slice(&x.to_le_bytes());
            }
        }
        out
    }

    /// A tile from the bytes of [`TileDrawing::to_bytes`]; an error for bytes that are not
    /// one.
    ///
    /// ```
    /// use kepler::hidden::tiles::TileDrawing;
    /// assert!(TileDrawing::from_bytes(b"not a tile").is_err());
    /// ```
    pub fn from_bytes(bytes: &[u8]) -> Result<TileDrawing> {
        let bad = |why: &str| DrawError::Tiles(format!("not a tile's bytes: {why}"));
        let rest = bytes
            .strip_prefix(MAGIC.as_slice())
            .ok_or_else(|| bad("wrong header"))?;
        let mut reader = Reader(rest);
        let shift = i32::from_le_bytes(reader.take().ok_or_else(|| bad("too short"))?);
        let perspective = match reader.take::<1>() {
            Some([0]) => false,
            Some([1]) => true,
            _ => return Err(bad("wrong header")),
        };
        let count = u64::from_le_bytes(reader.take().ok_or_else(|| bad("too short"))?);
        if reader.0.len() as u64 != count.saturating_mul(PIECE_BYTES as u64) {
            return Err(bad("wrong length"));
        }
        let mut pieces = Vec::with_capacity(count as usize);
        while !reader.0.is_empty() {
            let piece = reader.piece().ok_or_else(|| bad("a piece is malformed"))?;
            pieces.push(piece);
        }
        Ok(TileDrawing {
            pieces,
            shift,
            perspective,
        })
    }
}

/// Reads a tile's bytes in order.
struct Reader<'b>(&'b [u8]);

impl Reader<'_> {
    /// The next `N` bytes.
    fn take<const N: usize>(&mut self) -> Option<[u8; N]> {
        let (head, rest) = self.0.split_first_chunk::<N>()?;
        self.0 = rest;
        Some(*head)
    }

    fn u32(&mut self) -> Option<u32> {
        self.take().map(u32::from_le_bytes)
    }

    fn f64(&mut self) -> Option<f64> {
        self.take().map(f64::from_le_bytes)
    }

    /// The next piece.
    fn piece(&mut self) -> Option<TilePiece> {
        let [kind] = self.take()?;
        let names = [self.u32()?, self.u32()?, self.u32()?];
        let id = match kind {
            0 => LineId::Edge(names[0], names[1]),
            1 => LineId::Meet(names[0], names[1], names[2]),
            _ => return None,
        };
        let [class, flags] = self.take()?;
        let class = *EdgeClass::ALL.iter().find(|c| **c as u8 == class)?;
        if flags > 7 {
            return None;
        }
        let t = [self.f64()?, self.f64()?];
        let ends = [[self.f64()?, self.f64()?], [self.f64()?, self.f64()?]];
        Some(TilePiece {
            id,
            class,
            visible: flags & 1 != 0,
            ends,
            t,
            border: [flags & 2 != 0, flags & 4 != 0],
        })
    }
}

/// Draws the part of the drawing of `scene` from `view` inside `window` (in the view's
/// picture coordinates), from the objects whose CBOX may reach it: see the module
/// documentation. Its pieces keep their hidden parts whatever `options.hidden` says;
/// [`stitch`] applies it.
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
    let (pieces, _) = in_working_range::<_, DrawError>(scene, view, |scene, view| {
        let tile = TilePlanes::of(view, &window)?;
        let (pass, pieces) = decided(scene, view, tile, options, &|_, _| {})?;
        Ok(pieces
            .into_iter()
            .map(|p| TilePiece {
                id: pass.lines[p.line].id,
                class: p.class,
                visible: p.visible,
                ends: p.ends,
                t: p.t,
                border: p.border,
            })
            .collect())
    })?;
    Ok(TileDrawing {
        pieces,
        shift,
        perspective,
    })
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
/// the pieces of a line that meet where a window's plane passes, with the same visibility,
/// joined; the pieces in the order of the whole pass; chained (see the module documentation).
/// Equal, polyline for polyline and bit for bit, to [`draw`](super::draw) of the same scene
/// and view when the windows cover the picture once (a grid of [`tile_windows`]). The
/// drawing has no stage reports. An error for tiles of different scales or projections.
///
/// ```
/// use kepler::hidden::{Options, tiles::{TileDrawing, stitch}};
/// let d = stitch(&[TileDrawing::empty()], &Options::default()).unwrap();
/// assert!(d.polylines.is_empty());
/// ```
pub fn stitch(tiles: &[TileDrawing], options: &Options) -> Result<Drawing> {
    let Some(first) = tiles.first() else {
        return Ok(Drawing {
            polylines: Vec::new(),
            stages: Vec::new(),
        });
    };
    if tiles
        .iter()
        .any(|t| (t.shift, t.perspective) != (first.shift, first.perspective))
    {
        return Err(DrawError::Tiles(
            "the tiles are not of one scene and view (their scales or projections differ)"
                .to_string(),
        ));
    }
    let mut pieces: Vec<TilePiece> = tiles
        .iter()
        .flat_map(|t| t.pieces.iter().copied())
        .collect();
    pieces.sort_unstable_by(|p, q| {
        p.id.cmp(&q.id)
            .then(p.t[0].total_cmp(&q.t[0]))
            .then(p.t[1].total_cmp(&q.t[1]))
    });
    let mut joined: Vec<TilePiece> = Vec::with_capacity(pieces.len());
    for p in pieces {
        match joined.last_mut() {
            Some(last)
                if last.id == p.id
                    && last.visible == p.visible
                    && last.border[1]
                    && p.border[0]
                    && last.ends[1] == p.ends[0] =>
            {
                last.ends[1] = p.ends[1];
                last.t[1] = p.t[1];
                last.border[1] = p.border[1];
            }
            _ => joined.push(p),
        }
    }
    let pieces: Vec<Piece> = joined
        .iter()
        .enumerate()
        .filter(|(_, p)| options.hidden || p.visible)
        .map(|(line, p)| Piece {
            class: p.class,
            visible: p.visible,
            ends: p.ends,
            line,
            t: p.t,
            border: p.border,
        })
        .collect();
    let drawing = Drawing {
        polylines: chain(&pieces),
        stages: Vec::new(),
    };
    Ok(scaled_back(drawing, first.perspective, first.shift))
}
