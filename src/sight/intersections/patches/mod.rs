//! Certified patches: most pairs of triangles of a clean surface proved apart at once, so
//! that a scan that does not pierce itself pays little for the proof (the certified quick
//! "no self-intersection" of issue 29; the pairs across patches are still tested).
//!
//! # The argument
//! Give each triangle the coordinate axis `k` along which its normal is largest (rounded:
//! any axis would do) and the exact sign `s` of that component: the orientation of its
//! picture in the plane that drops coordinate `k` ([`project`]), an exact `orient2d` of
//! input coordinates. A *patch* is any set of triangles of one class `(k, s)`; here, those
//! of one class whose boxes' least corners lie in one cell of a coarse grid, joined across
//! the edges two of them share in opposite directions. Every triangle
//! of a patch has a picture of orientation `s`, so the number of them covering a point `q`
//! of the plane (off their sides) is `s` times the winding number around `q` of the
//! pictures of the patch's *boundary*: its half-edges that no other of its half-edges
//! cancels (the winding number of a sum of triangles is the sum of theirs; no connection
//! between the triangles is needed). The patch is certified when
//!
//! - **(A)** no edge is used twice the same way more than the other, so the boundary is a
//!   sum of loops; where several loops meet at a vertex (a *pinch*), the half-edges round it
//!   alternate in and out (exact angular order) and each arriving one is followed by its
//!   neighbour across the patch; a walk that passes a vertex twice is split there, and the
//!   loops through a pinch must touch without crossing;
//! - **(B)** the pictures of two boundary half-edges meet only when they share an end
//!   vertex, and then only there (exact segment meetings, [`meeting`]);
//! - **(C)** beside every loop, the winding numbers are `0` and `s`: each loop's
//!   orientation (at its lowest vertex) and the winding number of the other loops round it
//!   (crossings of a ray from one of its vertices that no other loop passes, exact; or,
//!   where it has none, the side of the touching loop its first half-edge leaves into) say
//!   so.
//!
//! Then no point of the plane is covered twice (C), and no two triangles that share no
//! vertex touch: a point shared by two triangles would either be covered twice nearby, or
//! lie on two boundary half-edges that share no vertex there (B). So the triangles of a
//! certified patch meet only along their shared vertices and sides, in 3-D as in the
//! picture, and no pair of them needs testing. Every sign above is exact on the input
//! coordinates; a patch that fails any test is simply not certified, and its triangles are
//! paired as before. Nothing here constructs a point, and the drawing does not change.
//!
//! # Which triangles are still paired
//! A certified triangle needs pairing only with triangles of other patches or of none: each
//! patch is cut into 4 × 4 × 4 *pieces* by its cell, and a triangle is listed for the pair
//! search ([`listed`]) only when its box meets the box of a piece of another patch or of an
//! uncertified triangle (an R-tree over those boxes). On a clean scan that is the triangles
//! along the cells' walls and where the class changes, a sixth or so.
//!
//! # Cost
//! One exact orientation per triangle (with its box, in the caller's pass), a counting
//! placement by cell, and per cell a sort of its edge uses, a union-find over them and a
//! segment grid over its boundaries: linear, in parallel over cells. Condition (C) costs
//! loops × boundary half-edges; a patch of more than [`MOST_LOOPS`] loops is left
//! uncertified, and one of fewer than [`FEWEST`] triangles is not worth certifying, so that
//! a soup costs no more than a surface.

use crate::geometry::predicates::{orient2d, project};
use crate::geometry::{Aabb, Point3, Vector3};
use crate::grid::Voxels;
use crate::mesh::{Mesh, by_bucket};
use crate::union_find::UnionFind;
use loops::{loops, meet_only_at_ends, windings_agree};
use rayon::prelude::*;
use std::cmp::Ordering;

mod listed;
mod loops;
#[cfg(test)]
pub(super) mod tests;

pub(super) use listed::listed;
#[cfg(test)]
use loops::touch_without_crossing;

/// The patch of a triangle that is in no certified patch.
pub(super) const NONE: u32 = u32::MAX;

/// The most loops a certified patch may have (a soup has a loop per triangle).
const MOST_LOOPS: usize = 64;

/// The side of the cells that patches are cut into, in mean triangle sizes: a cell of a
/// surface holds some thousands of triangles, so that the boundaries the cells add (and
/// the triangles near them, which are paired as before) are a small part.
pub(super) const PATCH_CELL: f64 = 64.0;

/// A triangle's class: `2k` or `2k + 1` for a picture of positive or negative orientation
/// when coordinate `k` is dropped; [`NONE`] when that orientation is zero (a degenerate
/// triangle, or one whose largest normal component rounds away from an exact zero).
/// (`n` is the triangle's normal, as computed.)
pub(super) fn class(t: &[Point3; 3], n: &Vector3) -> u32 {
    let [a, b, c] = t;
    let size = |k: usize| if n[k].is_nan() { -1.0 } else { n[k].abs() };
    let k = (0..3).fold(0, |best, k| if size(k) > size(best) { k } else { best });
    match orient2d(project(a, k), project(b, k), project(c, k)) {
        Ordering::Greater => 2 * k as u32,
        Ordering::Less => 2 * k as u32 + 1,
        Ordering::Equal => NONE,
    }
}

/// The certified patches of a mesh's triangles ([`certified`]), and their *pieces*: each
/// patch cut by the 4 × 4 × 4 parts of its cell that its triangles' boxes' least corners lie
/// in, so that [`listed`] can tell where in a patch other patches come near.
pub(super) struct Patches {
    /// Each triangle's patch, or [`NONE`].
    pub patch: Vec<u32>,
    /// Each triangle's piece, or [`NONE`]; pieces are numbered from 0.
    pub piece: Vec<u32>,
    /// Each piece's patch.
    pub piece_patch: Vec<u32>,
}

/// The certified patches (numbered from 0 in the order of their cells) of the triangles of
/// `m`. A patch is a set of triangles of one class (`classes`, from [`class`]) whose boxes'
/// least corners lie in one cell of a grid of side about `side` over `region`, joined
/// across the edges two of them share in opposite directions (any partition would do for
/// the argument; this one keeps apart the parts of a mesh that cross each other).
pub(super) fn certified(
    m: &Mesh,
    boxes: &[Aabb],
    classes: &[u32],
    region: Aabb,
    side: f64,
) -> Patches {
    let n = m.triangles().len();
    // No more cells than triangles (a mesh of slivers in a large box would have many).
    let mut grid = Voxels::new(region, side);
    while grid.shape().iter().product::<usize>() > n.max(1) {
        grid = Voxels::new(region, 2.0 * grid_side(&grid, &region));
    }
    let cells = grid.shape().iter().product::<usize>();
    let classed: Vec<u32> = (0..n as u32)
        .filter(|&t| classes[t as usize] != NONE)
        .collect();
    let cell_of = |t: usize| grid.cell_of(&Point3::from(boxes[t].min));
    let (start, placed) = by_bucket(
        cells,
        &classed,
        |&t| cell_of(t as usize) as usize,
        |&t| {
            let (t, c) = (t as usize, cell_of(t as usize));
            let part = part_of_cell(&grid.cell_box(c), &boxes[t]);
            (t as u32, classes[t], m.triangles()[t], part)
        },
    );
    let local: Vec<CellPatches> = start
        .par_windows(2)
        .map(|w| certify_cell(m, &placed[w[0]..w[1]]))
        .collect();
    let mut out = Patches {
        patch: vec![NONE; n],
        piece: vec![NONE; n],
        piece_patch: Vec::new(),
    };
    let mut patches = 0;
    for (w, cell) in start.windows(2).zip(&local) {
        let pieces = out.piece_patch.len() as u32;
        for (&(t, ..), (&p, &q)) in placed[w[0]..w[1]]
            .iter()
            .zip(cell.patch.iter().zip(&cell.piece))
        {
            if p != NONE {
                out.patch[t as usize] = patches + p;
                out.piece[t as usize] = pieces + q;
            }
        }
        out.piece_patch
            .extend(cell.piece_patch.iter().map(|&p| patches + p));
        patches += cell.patches;
    }
    out
}

/// One cell's certified patches: each triangle's patch and piece (numbered from 0 in the
/// cell, [`NONE`] where not certified), how many patches, and each piece's patch.
struct CellPatches {
    patch: Vec<u32>,
    piece: Vec<u32>,
    patches: u32,
    piece_patch: Vec<u32>,
}

/// Which of the 4 × 4 × 4 parts of `cell` the least corner of `b` lies in (clamped).
fn part_of_cell(cell: &Aabb, b: &Aabb) -> u8 {
    let size = cell.size();
    (0..3).rev().fold(0, |index, k| {
        let at = if size[k] > 0.0 {
            ((b.min[k] - cell.min[k]) / size[k] * 4.0).clamp(0.0, 3.0) as u8
        } else {
            0
        };
        index * 4 + at
    })
}

/// The largest side of a cell of `grid` over `region`.
fn grid_side(grid: &Voxels, region: &Aabb) -> f64 {
    let size = region.size();
    (0..3).fold(0.0, |m: f64, k| m.max(size[k] / grid.shape()[k] as f64))
}

/// The certified patches of one cell's triangles `(triangle, class, vertices, part of the
/// cell)`. A patch of fewer than [`FEWEST`] triangles is not worth a number.
fn certify_cell(m: &Mesh, tris: &[(u32, u32, [u32; 3], u8)]) -> CellPatches {
    // Each use of an edge: its key, and its triangle (in `tris`) and direction as
    // `triangle << 1 | forward`. Sorted by key alone: a group's order does not matter.
    let mut uses: Vec<(u64, u32)> = Vec::with_capacity(3 * tris.len());
    for (i, &(_, _, tri, _)) in tris.iter().enumerate() {
        for k in 0..3 {
            let (a, b) = (tri[k], tri[(k + 1) % 3]);
            let key = u64::from(a.min(b)) << 32 | u64::from(a.max(b));
            uses.push((key, (i as u32) << 1 | u32::from(a < b)));
        }
    }
    uses.sort_unstable_by_key(|u| u.0);
    let class = |u: u32| tris[(u >> 1) as usize].1;
    let mut sets = UnionFind::new(tris.len());
    for g in uses.chunk_by(|x, y| x.0 == y.0) {
        if g.len() == 2 && (g[0].1 ^ g[1].1) & 1 == 1 && class(g[0].1) == class(g[1].1) {
            sets.union((g[0].1 >> 1) as usize, (g[1].1 >> 1) as usize);
        }
    }
    let root: Vec<u32> = (0..tris.len()).map(|i| sets.find(i) as u32).collect();
    let mut size = vec![0u32; tris.len()];
    for &r in &root {
        size[r as usize] += 1;
    }
    let (boundaries, unsure) = boundaries(&uses, &root);
    let mut number = vec![NONE; tris.len()];
    let mut patches = 0;
    for (r, boundary) in boundaries {
        if size[r as usize] >= FEWEST
            && unsure.binary_search(&r).is_err()
            && certify(m, tris[r as usize].1, boundary)
        {
            number[r as usize] = patches;
            patches += 1;
        }
    }
    // The pieces: each patch's triangles by part of the cell.
    let mut piece_of = vec![NONE; 64 * patches as usize];
    let mut piece_patch = Vec::new();
    let (mut patch, mut piece) = (
        Vec::with_capacity(tris.len()),
        Vec::with_capacity(tris.len()),
    );
    for (i, &r) in root.iter().enumerate() {
        let p = number[r as usize];
        patch.push(p);
        piece.push(if p == NONE {
            NONE
        } else {
            let slot = &mut piece_of[64 * p as usize + tris[i].3 as usize];
            if *slot == NONE {
                *slot = piece_patch.len() as u32;
                piece_patch.push(p);
            }
            *slot
        });
    }
    CellPatches {
        patch,
        piece,
        patches,
        piece_patch,
    }
}

/// The fewest triangles of a certified patch.
const FEWEST: u32 = 8;

/// A patch (named by its root triangle) and its boundary half-edges `(from, to)`.
type Boundary = (u32, Vec<(u32, u32)>);

/// The boundary half-edges `(from, to)` of each patch (named by its `root` triangle), from
/// the cell's edge uses sorted by key ([`certify_cell`]): per edge and patch, the uses
/// forward less those backward; by patch. Also the patches where an edge is used twice the
/// same way more than the other (not certified), sorted.
fn boundaries(uses: &[(u64, u32)], root: &[u32]) -> (Vec<Boundary>, Vec<u32>) {
    let mut half_edges: Vec<(u32, u32, u32)> = Vec::new();
    let mut unsure = Vec::new();
    let mut net: Vec<(u32, i32)> = Vec::new();
    for g in uses.chunk_by(|x, y| x.0 == y.0) {
        let patch = |u: u32| root[(u >> 1) as usize];
        // The common case: two uses by one patch in opposite directions cancel.
        if g.len() == 2 && (g[0].1 ^ g[1].1) & 1 == 1 && patch(g[0].1) == patch(g[1].1) {
            continue;
        }
        net.clear();
        for u in g {
            let d = if u.1 & 1 == 1 { 1 } else { -1 };
            match net.iter_mut().find(|x| x.0 == patch(u.1)) {
                Some(x) => x.1 += d,
                None => net.push((patch(u.1), d)),
            }
        }
        let (low, high) = ((g[0].0 >> 32) as u32, g[0].0 as u32);
        for &(p, n) in &net {
            match n {
                0 => {}
                1 => half_edges.push((p, low, high)),
                -1 => half_edges.push((p, high, low)),
                _ => unsure.push(p),
            }
        }
    }
    unsure.sort_unstable();
    unsure.dedup();
    half_edges.sort_unstable();
    let by_patch = half_edges
        .chunk_by(|x, y| x.0 == y.0)
        .map(|h| (h[0].0, h.iter().map(|x| (x.1, x.2)).collect()))
        .collect();
    (by_patch, unsure)
}

/// Whether the patch of class `class` with these boundary half-edges is certified.
fn certify(m: &Mesh, class: u32, boundary: Vec<(u32, u32)>) -> bool {
    let at = |v: u32| project(&m.vertices()[v as usize], (class / 2) as usize);
    boundary_certified(boundary, &at, if class.is_multiple_of(2) { 1 } else { -1 })
}

/// Whether a patch of sign `s` whose boundary half-edges `(from, to)` have the pictures
/// `at` passes conditions (A), (B) and (C).
pub(super) fn boundary_certified(
    mut boundary: Vec<(u32, u32)>,
    at: &impl Fn(u32) -> [f64; 2],
    s: i32,
) -> bool {
    boundary.sort_unstable();
    let Some(loops) = loops(&boundary, at, s) else {
        return false;
    };
    loops.len() <= MOST_LOOPS && meet_only_at_ends(&loops, at) && windings_agree(&loops, at, s)
}
