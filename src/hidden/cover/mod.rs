//! Which triangles can hide a point: each mesh's triangles listed by the cells of the picture
//! that their pictures cover (Franklin's uniform grid, on the picture plane).
//!
//! Every line of sight is a single point of the picture, so the only triangles that can hide a
//! point are those whose pictures contain the point's picture: the ones listed in its cell.
//! Each triangle is listed in every cell its picture's bounding box meets, grown by a margin of
//! 2⁻⁴⁰ of the largest picture coordinate, far more than the rounding of any picture point; a
//! cell is found by the grid's one monotone index function. So a triangle whose exact picture
//! contains a point's exact picture is always listed in the cell of the point's rounded
//! picture, and the exact test then decides; first, a floating-point distance filter
//! ([`surely_farther`]) passes over the cell's triangles whose pictures are surely too far
//! from the point's to hide it (a crowded cell, such as a fan's apex, costs a few nanoseconds
//! a triangle). A point known only to within a distance (a point
//! of an edge or an intersection line, defined exactly but approximated for finding what is
//! near it) is looked up in every cell within the reach of its picture's error
//! ([`Picture::reach`]): nearly always the one cell.

use super::hubs::{Hub, hubs};
use crate::geometry::polygon::{bounding_box, surely_farther};
use crate::geometry::{Aabb, Point3};
use crate::grid::{CellLists, Cells};
use crate::mesh::Mesh;
use crate::queries::visp::{Visibility, any_hides, descend};
use crate::queries::{Counters, Stage};
use crate::scene::{ObjectId, Scene};
use crate::sight::frustum::ray_direction;
use crate::sight::line::Sight;
use crate::views::{Eye, Picture};
use rayon::prelude::*;
use rstar::primitives::{GeomWithData, Rectangle};
use rstar::{AABB, RTree};
use slotmap::SecondaryMap;
use std::cmp::Ordering;

/// The relative margin of the cells' lists: the space grid's, 2⁻⁴⁰.
use crate::grid::CELL_MARGIN as MARGIN;

/// The triangles of one mesh listed by picture cells, with what filters a cell's triangles
/// before the exact test: the vertices' pictures and the listing's margin.
#[derive(Debug)]
pub(crate) struct PictureGrid<'a> {
    cells: Cells,
    lists: CellLists,
    triangles: &'a [[u32; 3]],
    pictures: &'a [[f64; 2]],
    /// Which vertices are in front of the eye, when the view clips (else empty: all are).
    front: &'a [bool],
    /// The margin the triangles were listed with (more than the rounding of any picture).
    margin: f64,
    /// The triangles round crowded vertices, listed by angle instead of in the cells (see
    /// [`hubs`](super::hubs)).
    hubs: Vec<Hub>,
    /// The triangles turned away from the eye, left out (see [`PictureGrid::new`]).
    away: usize,
}

/// The window of a view that clips (half its width and height, grown), with the picture map:
/// only points whose pictures lie in it are asked about.
pub(crate) type ClipWindow<'a> = (&'a Picture, [f64; 2]);

impl<'a> PictureGrid<'a> {
    /// Lists the triangles of `mesh` whose vertices' pictures are `pictures`, in cells sized
    /// for about `queries` queries (see [`cell_factor`]). When the view clips (`window`),
    /// `front` says which vertices are in front of the eye (the others' pictures mean
    /// nothing), the cells cover the window only (every point asked about lies in the frustum),
    /// and a triangle is listed by the part of its picture's box in the window: a triangle with
    /// no vertex in front hides nothing in front of the eye and is left out; the picture of
    /// the front part of one that crosses the plane of the eye is unbounded along the pictures
    /// of its edges towards the eye's plane (see [`Clip::framed`](crate::sight::frustum)).
    ///
    /// With `turned` (not empty), the mesh bounds a solid seen from outside that does not
    /// pierce itself, and its triangles marked in it (turned away from the eye, decided
    /// exactly) are not listed: whatever one of them hides, a triangle turned towards the eye
    /// hides too. Say the closed triangle B, turned away, meets the line of sight from a point
    /// P to the eye at X, strictly between them. Move P a little so that its line of sight
    /// crosses the inside of B and no edge of the mesh: going towards the eye, it enters the
    /// solid at B, so it must leave it through a triangle turned towards the eye before
    /// reaching the eye, which is outside. As the move shrinks to nothing, one such triangle F
    /// is met each time (there are finitely many), at points that tend to a point Y of the
    /// closed F between X and the eye: F hides P as B does (the closed test of
    /// [`hides_at`](crate::sight::along::hides_at)). (`cover/tests.rs` checks the answers.)
    pub(crate) fn new(
        mesh: &'a Mesh,
        pictures: &'a [[f64; 2]],
        (front, window): (&'a [bool], Option<ClipWindow>),
        turned: &[bool],
        queries: usize,
    ) -> PictureGrid<'a> {
        let in_front = |v: u32| front.get(v as usize).is_none_or(|&f| f);
        let boxes: Vec<Option<[[f64; 2]; 2]>> = mesh
            .triangles()
            .par_iter()
            .enumerate()
            .map(|(t, tri)| match window {
                _ if turned.get(t) == Some(&true) => None,
                None => Some(bounding_box(tri.map(|v| pictures[v as usize]))),
                Some((picture, w)) => framed_box(mesh, tri, pictures, &in_front, picture, w),
            })
            .collect();
        let whole = |tri: &[u32; 3]| window.is_none() || tri.iter().all(|&v| in_front(v));
        // More than the rounding of any triangle's picture, those at hubs included.
        let [lo, hi] = bounding_box(boxes.iter().flatten().flatten().copied());
        let margin = MARGIN * lo.iter().chain(&hi).fold(0.0f64, |m, v| m.max(v.abs()));
        // The triangles round a crowded vertex go to its hub, found by angle, the others to
        // the cells (sized for them alone).
        let (hubs, at_hub) = hubs(mesh.triangles(), pictures, |t| {
            boxes[t].is_some() && whole(&mesh.triangles()[t])
        });
        let boxes: Vec<Option<[[f64; 2]; 2]>> = boxes
            .into_iter()
            .zip(&at_hub)
            .map(|(b, &h)| b.filter(|_| !h))
            .collect();
        let [lo, hi] = bounding_box(boxes.iter().flatten().flatten().copied());
        let n = boxes.iter().flatten().count().max(1);
        let extent = [0, 1].map(|k| (hi[k] - lo[k]).max(0.0));
        // Cells about the size of a triangle's picture times the factor (the size of a sliver
        // is its width, not its length: it is listed along itself), no smaller than one per
        // triangle would give, nor than a sixteenth of the mean picture box.
        let size = mesh
            .triangles()
            .par_iter()
            .zip(&boxes)
            .filter(|(_, b)| b.is_some())
            .map(|(tri, b)| match (whole(tri), b) {
                (true, _) => {
                    let [p, q, r] = tri.map(|v| pictures[v as usize]);
                    let cross = (q[0] - p[0]) * (r[1] - p[1]) - (q[1] - p[1]) * (r[0] - p[0]);
                    cross.abs().sqrt()
                }
                (false, Some([low, high])) => (high[0] - low[0]).max(high[1] - low[1]),
                (false, None) => 0.0,
            })
            .sum::<f64>()
            / n as f64;
        let mean = boxes
            .iter()
            .flatten()
            .map(|[low, high]| (high[0] - low[0]).max(high[1] - low[1]))
            .sum::<f64>()
            / n as f64;
        let side = (cell_factor(n, queries) * size)
            .max(mean / 16.0)
            .max((extent[0] * extent[1] / 4.0 / n as f64).sqrt());
        let cells = Cells::new(lo, extent, cell_shape(side, extent, n));
        let pairs = listed_pairs(mesh, pictures, &boxes, (&cells, margin), whole);
        PictureGrid {
            away: turned.iter().filter(|&&t| t).count(),
            lists: CellLists::new(cells.count(), pairs),
            cells,
            triangles: mesh.triangles(),
            pictures,
            front,
            margin,
            hubs,
        }
    }

    /// The triangles that may hide a point whose picture lies within `reach` of `p`: those
    /// listed in the cells within that reach, less those whose picture is certainly farther
    /// than the reach from `p` (a triangle may come more than once).
    ///
    /// The filter is sound: the exact picture of the point is within `reach` of `p`, plus the
    /// rounding of `p` (less than `MARGIN` of its largest coordinate), and the exact picture of
    /// a triangle within the rounding of its vertices' pictures (less than the grid's margin)
    /// of the triangle of their rounded pictures; a triangle farther than the sum cannot hide
    /// the point. Triangles with a vertex behind the eye (whose picture means nothing) are
    /// never filtered.
    pub(crate) fn near(&self, p: [f64; 2], reach: f64) -> impl Iterator<Item = &u32> {
        let slack = reach + self.margin + MARGIN * p[0].abs().max(p[1].abs());
        let at_hubs = self.hubs.iter().flat_map(move |h| h.near(p, slack));
        self.cells
            .covering(p, p, reach)
            .flat_map(|c| self.lists.get(c))
            .chain(at_hubs)
            .filter(move |&&t| {
                let tri = &self.triangles[t as usize];
                let whole = tri
                    .iter()
                    .all(|&v| self.front.get(v as usize).is_none_or(|&f| f));
                !(whole && surely_farther(&tri.map(|v| self.pictures[v as usize]), p, slack))
            })
    }

    /// The number of (cell, triangle) entries.
    pub(crate) fn entries(&self) -> usize {
        self.lists.entries() + self.hubs.iter().map(Hub::entries).sum::<usize>()
    }
}

/// The number of cells along each axis of a grid over `extent` with cells of about `side`
/// for `n` listed triangles: at most `n` along an axis and about `4·n` in all, one cell for
/// at most [`ONE_CELL`] triangles.
fn cell_shape(side: f64, extent: [f64; 2], n: usize) -> [usize; 2] {
    let mut shape = [0, 1].map(|k| {
        if side > 0.0 && side.is_finite() {
            ((extent[k] / side).ceil() as usize).clamp(1, n)
        } else {
            1
        }
    });
    while shape[0] * shape[1] > 4 * n {
        shape = shape.map(|c| c.div_ceil(2));
    }
    if n <= ONE_CELL {
        shape = [1, 1];
    }
    shape
}

/// Every `(cell, triangle)` listing of the triangles of `mesh` with a box in `boxes`: a
/// triangle wholly pictured (`whole`) in the cells its picture meets, grown by `margin`,
/// another in those its box covers.
fn listed_pairs(
    mesh: &Mesh,
    pictures: &[[f64; 2]],
    boxes: &[Option<[[f64; 2]; 2]>],
    (cells, margin): (&Cells, f64),
    whole: impl Fn(&[u32; 3]) -> bool + Sync,
) -> Vec<(u32, u32)> {
    boxes
        .par_iter()
        .enumerate()
        .filter_map(|(t, b)| b.map(|b| (t, b)))
        .fold(
            || (Vec::new(), Vec::new()),
            |(mut out, mut listed): (Vec<(u32, u32)>, Vec<usize>), (t, [low, high])| {
                let tri = &mesh.triangles()[t];
                if whole(tri) {
                    listed.clear();
                    cells.covering_triangle(tri.map(|v| pictures[v as usize]), margin, &mut listed);
                    out.extend(listed.iter().map(|&c| (c as u32, t as u32)));
                } else {
                    out.extend(
                        cells
                            .covering(low, high, margin)
                            .map(|c| (c as u32, t as u32)),
                    );
                }
                (out, listed)
            },
        )
        .map(|(out, _)| out)
        .reduce(Vec::new, |mut x, mut y| {
            x.append(&mut y);
            x
        })
}

/// The box of the picture of the part of triangle `tri` in front of the eye, within the window
/// `[-w, w]` (`None` when it misses the window or no vertex is in front): the box of its front
/// vertices' pictures, unbounded towards the side of each picture of an edge from a front
/// vertex towards the eye's plane (its direction from [`Clip::framed`]'s formula, each
/// component's sign exact), then cut to the window.
///
/// [`Clip::framed`]: crate::sight::frustum
fn framed_box(
    mesh: &Mesh,
    tri: &[u32; 3],
    pictures: &[[f64; 2]],
    in_front: &impl Fn(u32) -> bool,
    picture: &Picture,
    w: [f64; 2],
) -> Option<[[f64; 2]; 2]> {
    let (mut low, mut high) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
    for &f in tri.iter().filter(|&&v| in_front(v)) {
        let p = pictures[f as usize];
        for k in 0..2 {
            low[k] = low[k].min(p[k]);
            high[k] = high[k].max(p[k]);
        }
        for &g in tri.iter().filter(|&&v| !in_front(v)) {
            let direction = ray_direction(
                picture,
                &mesh.vertices()[f as usize],
                &mesh.vertices()[g as usize],
            );
            for k in 0..2 {
                match direction[k].partial_cmp(&0.0) {
                    Some(Ordering::Greater) => high[k] = f64::INFINITY,
                    Some(Ordering::Less) => low[k] = f64::NEG_INFINITY,
                    _ => {}
                }
            }
        }
    }
    let low = [0, 1].map(|k| low[k].max(-w[k]));
    let high = [0, 1].map(|k| high[k].min(w[k]));
    (low[0] <= high[0] && low[1] <= high[1]).then_some([low, high])
}

/// Up to this many triangles, a mesh's pictures are listed in one cell: [`PictureGrid::near`]
/// passes over a triangle whose picture is far from the point in a few nanoseconds, less than
/// finding and listing the cells of a small mesh costs.
const ONE_CELL: usize = 32;

/// The cell side over the mean triangle picture size that balances building against querying:
/// listing `n` triangles costs about `n·(1 + 1/x)²` entries, and `q` queries test about
/// `q·k·(1 + x)²` triangles (`k ≈ 16`: a triangle test against an entry, times the depth of the
/// scene), least at `x³ = n / (q·k)`; kept within `[1/4, 2]`.
fn cell_factor(n: usize, queries: usize) -> f64 {
    (n as f64 / (16.0 * queries.max(1) as f64))
        .cbrt()
        .clamp(0.25, 2.0)
}

/// The box of the picture of `cbox` (of its corners' pictures, grown by the grids' margin), or
/// `None` when a corner is not strictly in front of a perspective eye (the picture of the box
/// is then unbounded) or the box is empty.
fn cbox_picture(picture: &Picture, cbox: &Aabb) -> Option<[[f64; 2]; 2]> {
    if !(0..3).all(|k| cbox.min[k] <= cbox.max[k]) {
        return None;
    }
    let corners = cbox.corners();
    if !corners.iter().all(|c| picture.in_front(c)) {
        return None;
    }
    let [lo, hi] = bounding_box(corners.iter().map(|c| picture.point(c)));
    let margin = MARGIN * lo.iter().chain(&hi).fold(0.0f64, |m, v| m.max(v.abs()));
    let grown = [lo.map(|v| v - margin), hi.map(|v| v + margin)];
    grown
        .iter()
        .flatten()
        .all(|v| v.is_finite())
        .then_some(grown)
}

/// A mesh object with its vertices' pictures and, when the view clips, which vertices are in
/// front of the eye.
pub(crate) type PicturedMesh<'a> = (ObjectId, &'a Mesh, &'a [[f64; 2]], &'a [bool], &'a [bool]);

/// VISP for the hidden-line pass: Franklin's steps (CBOX rejects, INBOX accepts, faces decide)
/// for each mesh object whose CBOX's picture reaches the point's, with the mesh's faces
/// answered through its [`PictureGrid`].
///
/// The objects are found through an R-tree of their CBOXes' pictures (the box of the corners'
/// pictures, grown by the grids' margin: the picture of a box in front of the eye is the
/// convex hull of its corners' pictures), so a point asks only the objects drawn over it, not
/// every object of the scene: an array of ten thousand cubes costs each point a few, as one
/// cube would. Franklin's descent from the roots, which the picture index replaces here, asks
/// every subobject of every group whose CBOX the line of sight meets.
pub(crate) struct Occluders<'s> {
    scene: &'s Scene,
    eye: Eye,
    /// The picture map the grids' cells are in.
    picture: Picture,
    grids: SecondaryMap<ObjectId, PictureGrid<'s>>,
    /// The mesh objects by the pictures of their CBOXes.
    pictured: RTree<GeomWithData<Rectangle<[f64; 2]>, ObjectId>>,
    /// The mesh objects whose CBOX has a corner not in front of a perspective eye: asked
    /// about every point.
    everywhere: Vec<ObjectId>,
    /// Objects whose INBOX is not used: those with a mesh of more than the limit's triangles.
    no_inbox: SecondaryMap<ObjectId, ()>,
}

impl<'s> Occluders<'s> {
    /// The index over the given meshes (with their vertices' pictures), for about `queries`
    /// queries, over the window of a view that clips (`window`, see [`PictureGrid::new`]);
    /// objects holding a mesh of more than `inbox_limit` triangles use no INBOX.
    pub(crate) fn new(
        scene: &'s Scene,
        (eye, picture): (Eye, Picture),
        window: Option<[f64; 2]>,
        meshes: &[PicturedMesh<'s>],
        inbox_limit: usize,
        queries: usize,
    ) -> Occluders<'s> {
        // Each mesh's share of the queries, by its share of the triangles: a point asks only
        // the meshes drawn over it.
        let total = meshes
            .iter()
            .map(|m| m.1.triangles().len())
            .sum::<usize>()
            .max(1);
        let built: Vec<(ObjectId, PictureGrid<'s>)> = meshes
            .par_iter()
            .map(|&(id, mesh, pictures, front, turned)| {
                // The bounds VISP will ask for, built here in parallel (each is built once, on
                // first use: left to the queries, the first would wait for all of them).
                scene.cbox(id);
                if mesh.triangles().len() <= inbox_limit {
                    scene.inbox(id);
                }
                let window = window.map(|w| (&picture, w));
                (
                    id,
                    PictureGrid::new(
                        mesh,
                        pictures,
                        (front, window),
                        turned,
                        (queries as f64 * mesh.triangles().len() as f64 / total as f64) as usize,
                    ),
                )
            })
            .collect();
        let mut grids = SecondaryMap::new();
        grids.extend(built);
        let boxes: Vec<(ObjectId, Option<[[f64; 2]; 2]>)> = meshes
            .par_iter()
            .map(|&(id, ..)| (id, cbox_picture(&picture, &scene.cbox(id))))
            .collect();
        let everywhere = boxes
            .iter()
            .filter(|(_, b)| b.is_none())
            .map(|&(id, _)| id)
            .collect();
        let pictured = RTree::bulk_load(
            boxes
                .into_iter()
                .filter_map(|(id, b)| {
                    b.map(|[lo, hi]| GeomWithData::new(Rectangle::from_corners(lo, hi), id))
                })
                .collect(),
        );
        let mut no_inbox = SecondaryMap::new();
        for (id, _) in scene.walk() {
            let large = scene
                .subtree(id)
                .iter()
                .filter_map(|&o| scene[o].mesh())
                .any(|m| m.triangles().len() > inbox_limit);
            if large {
                no_inbox.insert(id, ());
            } else {
                scene.inbox(id);
            }
            scene.cbox(id);
        }
        Occluders {
            scene,
            eye,
            picture,
            grids,
            pictured,
            everywhere,
            no_inbox,
        }
    }

    /// The number of triangles left out of the grids as turned away from the eye.
    pub(crate) fn turned_away(&self) -> usize {
        self.grids.values().map(|g| g.away).sum()
    }

    /// The number of (cell, triangle) entries of all the grids.
    pub(crate) fn entries(&self) -> usize {
        self.grids.values().map(PictureGrid::entries).sum()
    }

    /// VISP of a point known exactly only to `hides`: `approximate`, within `radius` of the
    /// exact point, drives the box filters (widened by the radius) and its picture picks each
    /// mesh's cells (all those within the reach of the picture's error), and
    /// `hides(object, triangle)` decides exactly.
    pub(crate) fn visp(
        &self,
        (approximate, radius): (&Point3, f64),
        hides: impl Fn(ObjectId, usize) -> bool,
        counters: &mut Counters,
    ) -> Visibility {
        let picture = self.picture.point(approximate);
        let reach = self.picture.reach(approximate, picture, radius);
        let sight = Sight::to_eye(approximate, &self.eye).blurred(radius);
        let wanted = |id: ObjectId| !self.no_inbox.contains_key(id);
        let ask = |id: ObjectId| {
            descend(self.scene, id, &sight, &wanted, &|leaf, _| {
                self.grids
                    .get(leaf)
                    .is_some_and(|g| g.near(picture, reach).any(|&t| hides(leaf, t as usize)))
            })
        };
        let (answer, stage): (Visibility, Stage) = if reach.is_finite() {
            let around = AABB::from_corners(
                [picture[0] - reach, picture[1] - reach],
                [picture[0] + reach, picture[1] + reach],
            );
            let drawn_over = self.pictured.locate_in_envelope_intersecting(&around);
            any_hides(
                self.everywhere
                    .iter()
                    .copied()
                    .chain(drawn_over.map(|o| o.data))
                    .map(ask),
            )
        } else {
            any_hides(self.grids.keys().map(ask))
        };
        counters.record(stage);
        answer
    }
}

#[cfg(test)]
mod tests;
