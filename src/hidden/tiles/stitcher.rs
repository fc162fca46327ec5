//! Tiles stitched one at a time: each tile's lines and pieces are taken in as it comes, so a
//! tile need not be held after it is added (a grid's tiles together can be several times the
//! memory of the drawing they make).

use super::bytes::{TileLine, TileMark};
use super::{LineId, Stitched, TileDrawing, same_eye};
use crate::hidden::chain::chain;
use crate::hidden::marks::Mark;
use crate::hidden::piece::Piece;
use crate::hidden::{Cut, DrawError, Drawing, Options, Result, finished, scaled_back};
use crate::views::Eye;
use std::collections::HashMap;

/// The tiles of a grid added one by one, in any order, then finished into the drawing that
/// [`stitch`](super::stitch) makes of them all at once.
///
/// ```
/// use kepler::{scene::Scene, views::View};
/// use kepler::hidden::{Options, draw, tiles::{Stitcher, draw_tile, tile_windows}};
/// let mut scene = Scene::new();
/// scene.add_mesh(None, "cube", kepler::solids::cube(2.0).unwrap()).unwrap();
/// let (view, options) = (View::standard(), Options::default());
/// let mut stitcher = Stitcher::default();
/// for window in tile_windows(&scene, &view, [2, 2]).unwrap() {
///     stitcher.add(&draw_tile(&scene, &view, &options, &window).unwrap()).unwrap();
/// }
/// let whole = draw(&scene, &view, &options).unwrap();
/// assert_eq!(stitcher.finish(&options).unwrap().polylines, whole.polylines);
/// ```
#[derive(Default)]
pub struct Stitcher {
    /// The working range's shift, whether the view is a perspective one, and the eye: those
    /// of the first tile that drew something, which every other must share.
    view: Option<(i32, bool, Eye)>,
    slack: f64,
    /// Each line once, in the order first met, and where each name is in it.
    lines: Vec<TileLine>,
    named: HashMap<LineId, usize>,
    cuts: Vec<Cut>,
    /// The pieces, on `lines` (by index) and `cuts`.
    pieces: Vec<Piece>,
}

impl Stitcher {
    /// Takes in a tile's lines and pieces; an error for a tile of another view, or one that
    /// describes a line differently from an earlier tile.
    pub fn add(&mut self, tile: &TileDrawing) -> Result<()> {
        if tile.is_empty() {
            return Ok(());
        }
        let (shift, perspective, eye) =
            *self
                .view
                .get_or_insert((tile.shift, tile.perspective, tile.eye));
        if (tile.shift, tile.perspective) != (shift, perspective) || !same_eye(&tile.eye, &eye) {
            return Err(DrawError::Tiles(
                "the tiles are not of one scene and view (their scales, projections or eyes differ)"
                    .to_string(),
            ));
        }
        self.slack = self.slack.max(tile.slack);
        // Each of the tile's lines as a line of the whole, the same in every tile.
        let mut local = Vec::with_capacity(tile.lines.len());
        for line in &tile.lines {
            let k = *self.named.entry(line.id).or_insert_with(|| {
                self.lines.push(*line);
                self.lines.len() - 1
            });
            if self.lines[k] != *line {
                return Err(DrawError::Tiles(
                    "the tiles are not of one scene (a line differs between them)".to_string(),
                ));
            }
            local.push(k);
        }
        for p in &tile.pieces {
            let line = &tile.lines[p.line as usize];
            let mut mark = |m: &TileMark| match m {
                TileMark::First => Mark::First,
                TileMark::Last => Mark::Last,
                TileMark::Cut(c) => {
                    self.cuts.push(*c);
                    Mark::Cut((self.cuts.len() - 1) as u32)
                }
            };
            let marks = [mark(&p.marks[0]), mark(&p.marks[1])];
            self.pieces.push(Piece {
                class: line.class,
                visible: p.visible,
                ends: p.ends,
                line: local[p.line as usize],
                t: p.t,
                border: p.border,
                marks,
            });
        }
        Ok(())
    }

    /// The drawing of the tiles added: each line's pieces in exact order along it, joined
    /// where they meet at a window's border with the same visibility, in the whole pass's
    /// order, finished with `options` (see [`stitch`](super::stitch)).
    pub fn finish(self, options: &Options) -> Result<Drawing> {
        let Some((shift, perspective, eye)) = self.view else {
            return Ok(Drawing {
                polylines: Vec::new(),
                stages: Vec::new(),
            });
        };
        // The lines in the whole pass's order: by name.
        let mut order: Vec<usize> = (0..self.lines.len()).collect();
        order.sort_unstable_by_key(|&k| self.lines[k].id);
        let mut rank = vec![0; order.len()];
        for (r, &k) in order.iter().enumerate() {
            rank[k] = r;
        }
        let mut pieces = self.pieces;
        pieces.iter_mut().for_each(|p| p.line = rank[p.line]);
        let mut stitched = Stitched {
            eye,
            slack: self.slack,
            lines: order.iter().map(|&k| self.lines[k]).collect(),
            cuts: self.cuts,
            pieces,
        };
        let pieces = stitched.joined();
        let (pieces, _) = finished(&stitched, pieces, options);
        let drawing = Drawing {
            polylines: chain(&pieces),
            stages: Vec::new(),
        };
        Ok(scaled_back(drawing, perspective, shift))
    }
}
