//! Candidate pairs of triangles for the intersection lines: a uniform 3-D grid over the region
//! where two meshes' boxes overlap, crowded cells split into smaller ones.

use super::patches::{self, NONE};
use crate::geometry::{Aabb, Point3};
use crate::grid::Voxels;
use crate::mesh::{Mesh, by_bucket};
use rayon::prelude::*;

/// The pairs of triangles (of `m0`, of `m1`) whose closed boxes meet and that may meet, each
/// once, in increasing order: a uniform 3-D grid ([`Voxels`]) over the region where the
/// meshes' boxes overlap, each triangle listed in the cells it meets (not in all the cells of
/// its box: the slivers of a fan all share the fan's box), pairs tested cell by cell. For one
/// mesh (`same`), pairs sharing a vertex or a face are left out, and where most of a cell's
/// triangles share one vertex (a fan's apex, a pole of a UV sphere) those are not paired with
/// each other at all: only with the rest, so ten thousand edges at one point cost no more
/// than ten thousand elsewhere. A crowded cell is split into smaller ones ([`Pairing::cell`]).
/// In one mesh, two triangles of one certified patch ([`patches`]) are proved apart and not
/// paired, and a triangle whose box meets no other patch is not listed at all.
pub(super) fn candidate_pairs(m0: &Mesh, m1: &Mesh, same: bool) -> Vec<(u32, u32)> {
    let (b0, s0, classes) = triangle_boxes(m0, same);
    let (b1, s1, _) = if same {
        (Vec::new(), 0.0, Vec::new())
    } else {
        triangle_boxes(m1, false)
    };
    if b0.len() * if same { b0.len() } else { b1.len() } <= FEW_PAIRS {
        return few_pairs(m0, &b0, if same { &b0 } else { &b1 }, same);
    }
    let second = if same { &b0 } else { &b1 };
    let whole = |b: &[Aabb]| b.iter().fold(Aabb::EMPTY, |u, x| u.union(x));
    let (w0, w1) = (whole(&b0), whole(second));
    let region = Aabb::new(
        Point3::from([0, 1, 2].map(|k| w0.min[k].max(w1.min[k]))),
        Point3::from([0, 1, 2].map(|k| w0.max[k].min(w1.max[k]))),
    );
    if (0..3).any(|k| region.min[k] > region.max[k]) {
        return Vec::new();
    }
    let grid = Voxels::new(region, cell_side(&[&b0, &b1], s0 + s1));
    // In one mesh, the certified patches, and which triangles the grid must list.
    let (patch, listed) = if same {
        let side = patches::PATCH_CELL * s0 / b0.len() as f64;
        let certified = patches::certified(m0, &b0, &classes, w0, side);
        let listed = patches::listed(&certified, &b0);
        (certified.patch, Some(listed))
    } else {
        (Vec::new(), None)
    };
    let mut items = cell_items(&grid, &region, m0, &b0, listed.as_deref(), 0);
    if !same {
        items.extend(cell_items(&grid, &region, m1, &b1, None, 1));
    }
    // By cell, then mesh, then triangle, sorted in place (a counting pass would need a second
    // array of the entries at once, the largest of this stage).
    items.par_sort_unstable();
    let runs: Vec<&[(u64, u32)]> = items.chunk_by(|x, y| x.0 == y.0).collect();
    let pairing = Pairing {
        meshes: [m0, m1],
        boxes: [&b0, second],
        same,
        patch: &patch,
    };
    let mut pairs = cell_pairs(&runs, &grid, &pairing);
    // A pair meeting in several cells was found in each.
    pairs.par_sort_unstable();
    pairs.dedup();
    pairs
}

/// Each triangle of `m` read once for its box, its size (the square root of twice its
/// area) and, when `classify`, its class ([`patches::class`], else [`NONE`]): the boxes, the
/// sum of the sizes, and the classes.
fn triangle_boxes(m: &Mesh, classify: bool) -> (Vec<Aabb>, f64, Vec<u32>) {
    let (boxes, (sizes, classes)): (Vec<Aabb>, (Vec<f64>, Vec<u32>)) = (0..m.triangles().len())
        .into_par_iter()
        .map(|t| {
            let [a, b, c] = m.triangle(t);
            let normal = (b - a).cross(&(c - a));
            let class = if classify {
                patches::class(&[a, b, c], &normal)
            } else {
                NONE
            };
            (Aabb::from_points(&[a, b, c]), (normal.norm().sqrt(), class))
        })
        .unzip();
    (boxes, sizes.iter().sum(), classes)
}

/// The cells of `grid` each triangle of `m` (with the boxes `b`) is listed in, as `(cell,
/// item)` with `mesh` in the item's top bit: the cells of its box when they are few, else
/// those it meets; none for a triangle whose box misses `region` or that is not `listed`
/// (when some are not).
fn cell_items(
    grid: &Voxels,
    region: &Aabb,
    m: &Mesh,
    b: &[Aabb],
    listed: Option<&[bool]>,
    mesh: u32,
) -> Vec<(u64, u32)> {
    b.par_iter()
        .enumerate()
        .fold(
            || (Vec::new(), Vec::new()),
            |(mut out, mut cells): (Vec<(u64, u32)>, Vec<u64>), (t, bx)| {
                if listed.is_some_and(|l| !l[t])
                    || (0..3).any(|k| bx.max[k] < region.min[k] || bx.min[k] > region.max[k])
                {
                    return (out, cells);
                }
                cells.clear();
                if !grid.box_cells(bx, BOX_CELLS, &mut cells) {
                    grid.triangle_cells(&m.triangle(t), &mut cells);
                }
                out.extend(cells.iter().map(|&c| (c, (mesh << 31) | t as u32)));
                (out, cells)
            },
        )
        .map(|(out, _)| out)
        .reduce(Vec::new, |mut x, mut y| {
            x.append(&mut y);
            x
        })
}

/// The pairs of every cell of `grid` (`runs`: the items of each cell, sorted), found by
/// `pairing` ([`Pairing::cell`]), in parallel.
fn cell_pairs(runs: &[&[(u64, u32)]], grid: &Voxels, pairing: &Pairing) -> Vec<(u32, u32)> {
    runs.par_iter()
        .fold(
            || (Vec::new(), Vec::new(), Vec::new()),
            |(mut out, mut items, mut tris): (Vec<(u32, u32)>, Vec<u32>, Vec<CellTriangle>),
             run| {
                // One buffer per thread for the cells' items, not one per cell.
                items.clear();
                items.extend(run.iter().map(|x| x.1));
                let cell = grid.cell_box(run[0].0);
                pairing.cell(&items, &cell, 0, &mut out, &mut tris);
                (out, items, tris)
            },
        )
        .map(|(out, ..)| out)
        .reduce(Vec::new, |mut x, mut y| {
            x.append(&mut y);
            x
        })
}

/// The side of the cells: twice the mean size of a triangle (`sizes` sums the square roots
/// of twice their areas), so that a cell holds a few triangles of a surface; no smaller than
/// a sixteenth of the mean box, so that a mesh of slivers is not cut into more cells than its
/// boxes are across.
fn cell_side(boxes: &[&[Aabb]], sizes: f64) -> f64 {
    let n = boxes.iter().map(|b| b.len()).sum::<usize>().max(1) as f64;
    let boxes: f64 = boxes
        .iter()
        .flat_map(|b| b.iter())
        .map(|b| b.size().into_iter().fold(0.0, f64::max))
        .sum::<f64>()
        / n;
    let side = (2.0 * sizes / n).max(boxes / 16.0);
    if side.is_finite() { side } else { boxes }
}

/// A triangle of a cell, with what the pair tests read: its index, vertices and box (copied
/// together, so a cell's pairs read one small array instead of the whole mesh).
type CellTriangle = (u32, [u32; 3], Aabb);

/// What the pairs of a cell are found from: the two meshes (the same one twice for `same`)
/// and their triangles' boxes. An item is a triangle index with the mesh in its top bit.
pub(super) struct Pairing<'a> {
    pub(super) meshes: [&'a Mesh; 2],
    pub(super) boxes: [&'a [Aabb]; 2],
    pub(super) same: bool,
    /// In one mesh, the certified patch of each triangle ([`patches::certified`], [`NONE`]
    /// for none); may be empty.
    pub(super) patch: &'a [u32],
}

/// A crowded cell is split into this many cells along each axis.
const SPLIT: f64 = 4.0;

/// A cell of at least [`CROWD`] (or [`CROWD_OF_ONE`]) triangles is crowded when it has more
/// than this many pairs to test per triangle (listing a triangle in smaller cells costs a few
/// pair tests).
const CROWDED: usize = 8;

/// The fewest triangles of a crowded cell whose pairs are between two groups (two meshes, or
/// a hub's fan and the others): their boxes mostly meet, and each pair costs an exact test.
const CROWD: usize = 24;

/// The fewest triangles of a crowded cell whose pairs are among them all (a patch of one
/// surface): most of those pairs are told apart by their boxes alone, so a split pays only
/// in a larger cell.
const CROWD_OF_ONE: usize = 64;

/// A cell is split at most this many times over.
const SPLITS: usize = 6;

impl Pairing<'_> {
    /// The mesh and index of an item.
    fn of(&self, item: u32) -> (&Mesh, usize) {
        (
            self.meshes[(item >> 31) as usize],
            (item & 0x7fff_ffff) as usize,
        )
    }

    /// Whether two triangles of one mesh lie in one certified patch.
    fn proved_apart(&self, x: u32, y: u32) -> bool {
        !self.patch.is_empty() && {
            let p = self.patch[x as usize];
            p != NONE && p == self.patch[y as usize]
        }
    }

    /// The box of an item's triangle.
    fn bbox(&self, item: u32) -> &Aabb {
        &self.boxes[(item >> 31) as usize][(item & 0x7fff_ffff) as usize]
    }

    /// Appends to `out` the pairs among the `items` of one cell (`region`, split `depth`
    /// times already) whose boxes meet (in one mesh, those sharing no vertex and no face).
    /// A crowded cell, one whose pairs would be many more than its triangles (the rims of
    /// two fans that touch, slivers crossing), is split into smaller cells in which each
    /// triangle is listed again (in the cells it meets), when that leaves fewer pairs to test:
    /// a pair meeting at a point is listed together in that point's smaller cell.
    fn cell(
        &self,
        items: &[u32],
        region: &Aabb,
        depth: usize,
        out: &mut Vec<(u32, u32)>,
        tris: &mut Vec<CellTriangle>,
    ) {
        if self.same {
            let m = self.meshes[0];
            tris.clear();
            tris.extend(
                items
                    .iter()
                    .map(|&t| (t, m.triangles()[t as usize], self.boxes[0][t as usize])),
            );
            self.same_mesh(tris, region, depth, out);
            return;
        }
        // Items come by mesh within a cell (mesh 0 first): split there.
        let (firsts, seconds) = items.split_at(items.partition_point(|i| i >> 31 == 0));
        if items.len() >= CROWD
            && firsts.len() * seconds.len() > CROWDED * items.len()
            && self.split(items, region, depth, out, |sub| {
                let firsts = sub.partition_point(|i| i >> 31 == 0);
                firsts * (sub.len() - firsts)
            })
        {
            return;
        }
        for &x in firsts {
            for &y in seconds {
                if self.bbox(x).intersects(self.bbox(y)) {
                    out.push((x, y & 0x7fff_ffff));
                }
            }
        }
    }

    /// [`Pairing::cell`] in one mesh. Where at least a quarter of the triangles share one
    /// vertex (a hub: a fan's apex, a pole of a UV sphere), those are paired only with the
    /// others, and the others among themselves the same way: ten thousand edges at one
    /// point cost no more than ten thousand elsewhere.
    fn same_mesh(
        &self,
        tris: &[CellTriangle],
        region: &Aabb,
        depth: usize,
        out: &mut Vec<(u32, u32)>,
    ) {
        let m = self.meshes[0];
        let test = |x: &CellTriangle, y: &CellTriangle, out: &mut Vec<(u32, u32)>| {
            if x.2.intersects(&y.2)
                && !self.proved_apart(x.0, y.0)
                && !shares_vertex(&x.1, &y.1)
                && m.face_of(x.0 as usize) != m.face_of(y.0 as usize)
            {
                out.push((x.0.min(y.0), x.0.max(y.0)));
            }
        };
        let split = |out: &mut Vec<(u32, u32)>, load: &dyn Fn(&[u32]) -> usize| {
            let items: Vec<u32> = tris.iter().map(|t| t.0).collect();
            self.split(&items, region, depth, out, load)
        };
        if tris.len() > 16 {
            let mut vertices: Vec<u32> = tris.iter().flat_map(|t| t.1).collect();
            vertices.sort_unstable();
            let (hub, count) = vertices
                .chunk_by(|x, y| x == y)
                .map(|run| (run[0], run.len()))
                .max_by(|x, y| x.1.cmp(&y.1).then(y.0.cmp(&x.0)))
                .unwrap_or((0, 0));
            if 4 * count >= tris.len() {
                if tris.len() >= CROWD
                    && count * (tris.len() - count) > CROWDED * tris.len()
                    && split(out, &|sub| {
                        let at = sub
                            .iter()
                            .filter(|&&t| m.triangles()[t as usize].contains(&hub))
                            .count();
                        at * (sub.len() - at)
                    })
                {
                    return;
                }
                let (at, rest): (Vec<CellTriangle>, Vec<CellTriangle>) =
                    tris.iter().partition(|t| t.1.contains(&hub));
                for x in &at {
                    for y in &rest {
                        test(x, y, out);
                    }
                }
                self.same_mesh(&rest, region, depth, out);
                return;
            }
        }
        if tris.len() >= CROWD_OF_ONE
            && tris.len() * tris.len() / 2 > CROWDED * tris.len()
            && split(out, &|sub| sub.len() * sub.len())
        {
            return;
        }
        for (n, x) in tris.iter().enumerate() {
            for y in &tris[n + 1..] {
                test(x, y, out);
            }
        }
    }

    /// Splits the cell `region` of `items` into smaller cells and appends their pairs to
    /// `out`, unless it has been split [`SPLITS`] times already or the split would not
    /// lessen the `load` (the pairs to test among some items, as the caller counts them):
    /// triangles all through one point stay together in every split. Then returns `false`
    /// and appends nothing.
    pub(super) fn split(
        &self,
        items: &[u32],
        region: &Aabb,
        depth: usize,
        out: &mut Vec<(u32, u32)>,
        load: impl Fn(&[u32]) -> usize,
    ) -> bool {
        if depth >= SPLITS {
            return false;
        }
        let side = region.size().into_iter().fold(0.0, f64::max) / SPLIT;
        let grid = Voxels::within(*region, side);
        let mut listed: Vec<(u64, u32)> = Vec::new();
        let mut cells = Vec::new();
        for &item in items {
            cells.clear();
            if !grid.box_cells(self.bbox(item), BOX_CELLS, &mut cells) {
                let (m, t) = self.of(item);
                grid.triangle_cells(&m.triangle(t), &mut cells);
            }
            listed.extend(cells.iter().map(|&c| (c, item)));
        }
        let count = grid.shape().iter().product::<usize>();
        let (start, placed) = by_bucket(count, &listed, |x| x.0 as usize, |x| x.1);
        let subcells = || {
            start
                .windows(2)
                .enumerate()
                .filter(|(_, w)| w[1] > w[0])
                .map(|(c, w)| (c as u64, &placed[w[0]..w[1]]))
        };
        if subcells().map(|(_, sub)| load(sub)).sum::<usize>() >= load(items) {
            return false;
        }
        let mut tris = Vec::new();
        for (c, sub) in subcells() {
            self.cell(sub, &grid.cell_box(c), depth + 1, out, &mut tris);
        }
        true
    }
}

/// A triangle whose box spans at most this many cells is listed in all of them (found from
/// its box alone); a larger one only in the cells it meets.
const BOX_CELLS: usize = 4;

/// Up to this many triangle pairs, every pair is tested: no grid.
pub(super) const FEW_PAIRS: usize = 1 << 14;

/// [`candidate_pairs`] by testing every pair of the triangles' boxes `b0` and `b1`.
pub(super) fn few_pairs(m0: &Mesh, b0: &[Aabb], b1: &[Aabb], same: bool) -> Vec<(u32, u32)> {
    let mut out = Vec::new();
    for (i, bi) in b0.iter().enumerate() {
        let start = if same { i + 1 } else { 0 };
        for (j, bj) in b1.iter().enumerate().skip(start) {
            if bi.intersects(bj) && !(same && neighbours(m0, i, j)) {
                out.push((i as u32, j as u32));
            }
        }
    }
    out
}

/// Whether triangles `i` and `j` of one mesh lie on one face or share a vertex: they are
/// not compared for intersection.
fn neighbours(m: &Mesh, i: usize, j: usize) -> bool {
    shares_vertex(&m.triangles()[i], &m.triangles()[j]) || m.face_of(i) == m.face_of(j)
}

/// Whether two triangles share a vertex index.
fn shares_vertex(a: &[u32; 3], b: &[u32; 3]) -> bool {
    a.iter().any(|v| b.contains(v))
}
