//! The faces of one mesh listed by the cells of the picture, so that a face is tested only
//! against the faces whose pictures may overlap its own.

use crate::geometry::polygon::bounding_box;
use crate::grid::{CellLists, Cells};
use crate::mesh::{Face, Mesh};
use crate::scene::{ObjectId, Scene};
use crate::sight::frustum::Clip;
use crate::sight::own_solid::hidden_by_own_solid;
use crate::views::{Picture, View};
use std::cmp::Ordering;

/// The faces of one mesh listed by the cells of the picture their pictures' bounding boxes
/// (grown by a margin of 2⁻⁴⁰ of the largest coordinate, far above rounding) cover, so that
/// a face is tested only against the faces whose pictures may overlap its own.
#[derive(Debug)]
pub(super) struct FaceGrid {
    cells: Cells,
    margin: f64,
    lists: CellLists,
    /// The side of its faces that its own solid hides (see [`hidden_by_own_solid`]).
    pub(super) back_side: Option<Ordering>,
}

impl FaceGrid {
    /// The grid of the faces of `mesh` (object `id`), about one cell per face. When the view
    /// clips (`clip`), only the vertices strictly in front of the eye are pictured: a face
    /// with none cannot hide anything in front of the eye and is listed nowhere, one with some
    /// but not all is listed in every cell, and the grid spans the picture's window too.
    pub(super) fn new(
        scene: &Scene,
        (id, mesh): (ObjectId, &Mesh),
        view: &View,
        picture: &Picture,
        clip: Option<&Clip>,
    ) -> FaceGrid {
        let front: Vec<bool> = mesh
            .vertices()
            .iter()
            .map(|v| clip.is_none_or(|c| c.in_front(v)))
            .collect();
        let pictures: Vec<[f64; 2]> = mesh
            .vertices()
            .iter()
            .zip(&front)
            .map(|(v, &f)| if f { picture.point(v) } else { [0.0; 2] })
            .collect();
        let reach = |f: &Face| {
            let inside = f.vertices().iter().filter(|&&v| front[v as usize]).count();
            (inside > 0, inside == f.vertices().len())
        };
        let boxes: Vec<[[f64; 2]; 2]> = mesh
            .faces()
            .iter()
            .map(|f| match reach(f) {
                (_, true) => bounding_box(f.vertices().iter().map(|&v| pictures[v as usize])),
                _ => [[f64::INFINITY; 2], [f64::NEG_INFINITY; 2]],
            })
            .collect();
        let window = clip.and(window(view));
        let pictured = boxes.iter().zip(mesh.faces()).filter(|(_, f)| reach(f).1);
        let [lo, hi] = bounding_box(pictured.map(|(b, _)| b).chain(&window).flatten().copied());
        let side = (boxes.len().max(1) as f64).sqrt().ceil() as usize;
        let extent = [0, 1].map(|k| (hi[k] - lo[k]).max(0.0));
        let cells = Cells::new(lo, extent, [side, side]);
        let margin = GRID_MARGIN * lo.iter().chain(&hi).fold(0.0f64, |m, v| m.max(v.abs()));
        let pairs = boxes
            .iter()
            .zip(mesh.faces())
            .enumerate()
            .flat_map(|(f, ([low, high], face))| {
                let span = match reach(face) {
                    (_, true) => Some([*low, *high]),
                    (true, false) => Some([lo, hi]),
                    (false, false) => None,
                };
                let cells = &cells;
                span.into_iter().flat_map(move |[low, high]| {
                    cells
                        .covering(low, high, margin)
                        .map(move |c| (c as u32, f as u32))
                })
            })
            .collect();
        FaceGrid {
            lists: CellLists::new(cells.count(), pairs),
            cells,
            margin,
            back_side: hidden_by_own_solid(scene, id, mesh, view.eye()),
        }
    }

    /// The faces listed in the cells the box `[low, high]` covers, each once, in order.
    pub(super) fn near(&self, [low, high]: [[f64; 2]; 2]) -> Vec<usize> {
        let mut out: Vec<usize> = self
            .cells
            .covering(low, high, self.margin)
            .flat_map(|c| self.lists.get(c).iter().map(|&f| f as usize))
            .collect();
        out.sort_unstable();
        out.dedup();
        out
    }
}

/// A box holding the picture's window (the pictures of the points inside the frustum of a
/// view that clips: `|x| ≤ aspect`, `|y| ≤ 1`), grown by a relative 2⁻²⁰ over the rounding of
/// the picture's scale; `None` without a field of view.
pub(super) fn window(view: &View) -> Option<[[f64; 2]; 2]> {
    let [h, v] = view.window()?;
    let [x, y] = [h / v, 1.0].map(|s| s * (1.0 + 2f64.powi(-20)));
    Some([[-x, -y], [x, y]])
}

/// The relative margin of the face grid: 2⁻⁴⁰.
pub(super) const GRID_MARGIN: f64 = 1.0 / (1u64 << 40) as f64;
