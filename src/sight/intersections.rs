//! Intersection lines: where two faces pierce each other, in different objects or in one.
//!
//! Candidate triangle pairs are those whose boxes meet, found with a uniform 3-D grid over the
//! region where the two meshes' boxes overlap (a crowded cell, such as where the rims of two
//! fans of slivers meet, split into smaller cells); objects whose CBOXes do not overlap are
//! not compared at all. Which vertices lie on which side of the other triangle's plane is
//! decided exactly, and two triangles pierce each other only when each has vertices strictly
//! on both sides of the other's plane, or lies on it along a diagonal of its flat face (the
//! face is then cut along the diagonal, whichever way it is triangulated): touching faces (a
//! box resting on another, neighbours sharing an edge or a vertex) make no intersection line,
//! and coplanar faces none either.
//!
//! The part of the line inside both triangles runs between two of the points where a
//! triangle's edge crosses the other's plane (or a vertex lies on it): each such end is an
//! input vertex or the crossing of an input edge with an input plane, and the four candidates
//! are ordered along the line exactly ([`Meet::compare`]). Where a face is a polygon whose
//! vertices lie exactly on one plane, that plane stands for all its triangles (through the
//! three of its vertices with the smallest indices that are not collinear), and the pieces of
//! one pair of faces that touch end to end are merged: a segment runs from face boundary to
//! face boundary, whatever the triangulation (a reversed face is triangulated differently).
//! Where several candidates are the same point, the end is named the same way whatever the
//! triangulation: an input vertex first, then the crossing of a face's edge (of the first
//! mesh, then of the second), then of a diagonal.

use super::along::{Form, Zero};
use super::meet::{Meet, OnLine, reversed};
use crate::geometry::predicates::{collinear, orient3d};
use crate::geometry::{Aabb, Point3};
use crate::grid::Voxels;
use crate::mesh::{Mesh, by_bucket};
use crate::views::Eye;
use rayon::prelude::*;
use std::cmp::Ordering;
use std::collections::HashMap;

/// Which plane stands for a face in a segment: the face's own (its vertices lie exactly on one
/// plane), or one triangle's.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
pub(crate) enum PlaneKey {
    /// The plane of a face.
    Face(usize),
    /// The plane of a triangle of a face that is not exactly flat.
    Triangle(usize),
}

/// A maximal segment along which two faces (of meshes 0 and 1) pierce each other.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Segment {
    /// The line, on the planes of the two faces.
    pub meet: Meet,
    /// Its ends, in the line's direction.
    pub ends: [OnLine; 2],
    /// Its ends, approximately.
    pub points: [Point3; 2],
    /// The faces, in meshes 0 and 1.
    pub faces: [usize; 2],
    /// The pairs of triangles (in meshes 0 and 1) whose pieces make it up.
    pub triangles: Vec<[usize; 2]>,
}

/// The part of a segment from one pair of triangles.
#[derive(Debug, Clone, Copy)]
struct Piece {
    keys: [PlaneKey; 2],
    meet: Meet,
    ends: [OnLine; 2],
    faces: [usize; 2],
    triangles: [usize; 2],
}

/// The intersection segments of the faces of `m0` with those of `m1` (`same` when they are
/// one mesh: then each pair once, and triangles sharing a vertex or a face are not compared).
pub(crate) fn between(m0: &Mesh, m1: &Mesh, same: bool, eye: &Eye) -> Vec<Segment> {
    meetings(m0, m1, same, eye).0
}

/// [`between`], and the pairs of triangles `(t, u)` (in meshes `k` and `1 − k`, as
/// `[k, t, u]`) where a side of `t` crosses `u`'s plane strictly and passes through the closed
/// triangle `u`: an edge piercing a face, also where the faces along the edge only touch `u`
/// (an edge that enters a solid exactly across an edge of its surface, making no intersection
/// segment).
pub(crate) fn meetings(
    m0: &Mesh,
    m1: &Mesh,
    same: bool,
    eye: &Eye,
) -> (Vec<Segment>, Vec<[usize; 3]>) {
    // The pairs that pierce each other, and those where a face's side passes through the
    // other triangle (partners for piercings even where they make no segment).
    type Found = (Vec<(usize, usize, Sides)>, Vec<[usize; 3]>);
    let (crossing, contacts): Found = candidate_pairs(m0, m1, same)
        .par_iter()
        .fold(
            || (Vec::new(), Vec::new()),
            |(mut crossing, mut contacts): Found, &(i, j)| {
                let (i, j) = (i as usize, j as usize);
                if let Some([s0, s1]) = sides(m0, i, m1, j) {
                    if crosses(&s0, m0, i)
                        && crosses(&s1, m1, j)
                        && !surely_apart(&m0.triangle(i), &m1.triangle(j))
                    {
                        crossing.push((i, j, [s0, s1]));
                    }
                    // (Also for a pair that pierces: it may meet in one point, no segment.)
                    if straddles(&s0) || straddles(&s1) {
                        let (t0, t1) = (m0.triangle(i), m1.triangle(j));
                        if edge_through(&t0, &s0, m0, i, &t1) {
                            contacts.push([0, i, j]);
                        }
                        if edge_through(&t1, &s1, m1, j, &t0) {
                            contacts.push([1, j, i]);
                        }
                    }
                }
                (crossing, contacts)
            },
        )
        .reduce(
            || (Vec::new(), Vec::new()),
            |(mut a, mut b), (c, d)| {
                a.extend(c);
                b.extend(d);
                (a, b)
            },
        );
    if crossing.is_empty() {
        return (Vec::new(), contacts);
    }
    // The plane of each face met, once.
    let planes = |m: &Mesh, side: usize| -> HashMap<usize, (PlaneKey, [Point3; 3])> {
        let mut faces: Vec<(usize, usize)> = crossing
            .iter()
            .map(|p| {
                let t = if side == 0 { p.0 } else { p.1 };
                (m.face_of(t), t)
            })
            .collect();
        faces.sort_unstable();
        faces.dedup_by_key(|f| f.0);
        faces
            .par_iter()
            .map(|&(f, t)| (f, plane_of(m, t)))
            .collect()
    };
    let (planes0, planes1) = (planes(m0, 0), planes(m1, 1));
    let plane = |m: &Mesh, planes: &HashMap<usize, (PlaneKey, [Point3; 3])>, t: usize| match planes
        [&m.face_of(t)]
    {
        (PlaneKey::Face(f), p) => (PlaneKey::Face(f), p),
        (PlaneKey::Triangle(_), _) => (PlaneKey::Triangle(t), m.triangle(t)),
    };
    let mut pieces: Vec<Piece> = crossing
        .par_iter()
        .filter_map(|&(i, j, sides)| {
            let planes = [plane(m0, &planes0, i), plane(m1, &planes1, j)];
            piece(m0, i, m1, j, sides, planes, eye)
        })
        .collect();
    pieces.par_sort_unstable_by(|x, y| x.keys.cmp(&y.keys).then(x.triangles.cmp(&y.triangles)));
    let groups: Vec<&[Piece]> = pieces.chunk_by(|x, y| x.keys == y.keys).collect();
    let segments = groups
        .par_iter()
        .flat_map_iter(|group| merged(group, eye))
        .collect();
    (segments, contacts)
}

/// The pieces of one pair of planes, merged where they touch end to end.
fn merged(group: &[Piece], eye: &Eye) -> Vec<Segment> {
    let meet = group[0].meet;
    let mut order: Vec<&Piece> = group.iter().collect();
    order.sort_by(|x, y| {
        meet.compare(eye, &x.ends[0], &y.ends[0])
            .then(x.triangles.cmp(&y.triangles))
    });
    let mut out: Vec<Segment> = Vec::new();
    for p in order {
        if let Some(last) = out.last_mut()
            && meet.compare(eye, &last.ends[1], &p.ends[0]) != Ordering::Less
        {
            if meet.compare(eye, &last.ends[1], &p.ends[1]) == Ordering::Less {
                last.ends[1] = p.ends[1];
            }
            last.triangles.push(p.triangles);
            continue;
        }
        out.push(Segment {
            meet,
            ends: p.ends,
            points: [Point3::origin(); 2],
            faces: p.faces,
            triangles: vec![p.triangles],
        });
    }
    for s in &mut out {
        s.points = s.ends.map(|e| meet.approximate(eye, &e));
    }
    out
}

/// The pairs of triangles (of `m0`, of `m1`) whose closed boxes meet and that may meet, each
/// once, in increasing order: a uniform 3-D grid ([`Voxels`]) over the region where the
/// meshes' boxes overlap, each triangle listed in the cells it meets (not in all the cells of
/// its box: the slivers of a fan all share the fan's box), pairs tested cell by cell. For one
/// mesh (`same`), pairs sharing a vertex or a face are left out, and where most of a cell's
/// triangles share one vertex (a fan's apex, a pole of a UV sphere) those are not paired with
/// each other at all: only with the rest, so ten thousand edges at one point cost no more
/// than ten thousand elsewhere. A crowded cell is split into smaller ones ([`Pairing::cell`]).
fn candidate_pairs(m0: &Mesh, m1: &Mesh, same: bool) -> Vec<(u32, u32)> {
    // Each triangle read once for its box and its size (the square root of twice its area).
    let boxes = |m: &Mesh| -> (Vec<Aabb>, f64) {
        let (boxes, sizes): (Vec<Aabb>, Vec<f64>) = (0..m.triangles().len())
            .into_par_iter()
            .map(|t| {
                let [a, b, c] = m.triangle(t);
                (
                    Aabb::from_points(&[a, b, c]),
                    (b - a).cross(&(c - a)).norm().sqrt(),
                )
            })
            .unzip();
        (boxes, sizes.iter().sum())
    };
    let (b0, s0) = boxes(m0);
    let (b1, s1) = if same { (Vec::new(), 0.0) } else { boxes(m1) };
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
    let list = |m: &Mesh, b: &[Aabb], mesh: u32| -> Vec<(u64, u32)> {
        b.par_iter()
            .enumerate()
            .fold(
                || (Vec::new(), Vec::new()),
                |(mut out, mut cells): (Vec<(u64, u32)>, Vec<u64>), (t, bx)| {
                    if (0..3).any(|k| bx.max[k] < region.min[k] || bx.min[k] > region.max[k]) {
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
    };
    let mut items = list(m0, &b0, 0);
    if !same {
        items.extend(list(m1, &b1, 1));
    }
    // By cell, then mesh, then triangle, sorted in place (a counting pass would need a second
    // array of the entries at once, the largest of this stage).
    items.par_sort_unstable();
    let runs: Vec<&[(u64, u32)]> = items.chunk_by(|x, y| x.0 == y.0).collect();
    let pairing = Pairing {
        meshes: [m0, m1],
        boxes: [&b0, second],
        same,
    };
    let mut pairs: Vec<(u32, u32)> = runs
        .par_iter()
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
        });
    // A pair meeting in several cells was found in each.
    pairs.par_sort_unstable();
    pairs.dedup();
    pairs
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
struct Pairing<'a> {
    meshes: [&'a Mesh; 2],
    boxes: [&'a [Aabb]; 2],
    same: bool,
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
const SPLITS: usize = 3;

impl Pairing<'_> {
    /// The mesh and index of an item.
    fn of(&self, item: u32) -> (&Mesh, usize) {
        (
            self.meshes[(item >> 31) as usize],
            (item & 0x7fff_ffff) as usize,
        )
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
    fn split(
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

/// Whether the closed triangles `a` and `b` are certainly disjoint: some direction across an
/// edge of each (one of the nine cross products of their sides) separates their projections by
/// more than the rounding of the projections can move them. A filter before the exact section
/// of a pair whose planes cross (on a curved surface, most near neighbours cross each other's
/// planes without meeting): the direction may be rounded, any direction that separates proves
/// them apart; only the comparison must be sure, and each projection `p·d` is within
/// `γ₃·Σ|pₖ·dₖ|` of its rounded value (with a term for underflow).
fn surely_apart(a: &[Point3; 3], b: &[Point3; 3]) -> bool {
    const GAMMA: f64 = 4.0 * f64::EPSILON / 2.0;
    let sides = |t: &[Point3; 3]| [t[1] - t[0], t[2] - t[1], t[0] - t[2]];
    let (sa, sb) = (sides(a), sides(b));
    let range = |t: &[Point3; 3], d: &crate::geometry::Vector3| {
        t.iter().fold(
            (f64::INFINITY, f64::NEG_INFINITY, 0.0f64),
            |(lo, hi, err), p| {
                let v = p.x * d.x + p.y * d.y + p.z * d.z;
                let e = (p.x * d.x).abs() + (p.y * d.y).abs() + (p.z * d.z).abs();
                (lo.min(v), hi.max(v), err.max(e))
            },
        )
    };
    sa.iter().any(|ea| {
        sb.iter().any(|eb| {
            let d = ea.cross(eb);
            let (alo, ahi, ae) = range(a, &d);
            let (blo, bhi, be) = range(b, &d);
            let slack = GAMMA * (ae + be) + 8.0 * f64::MIN_POSITIVE;
            let gap = (blo - ahi).max(alo - bhi);
            gap.is_finite() && gap > slack
        })
    })
}

/// A triangle whose box spans at most this many cells is listed in all of them (found from
/// its box alone); a larger one only in the cells it meets.
const BOX_CELLS: usize = 4;

/// Up to this many triangle pairs, every pair is tested: no grid.
const FEW_PAIRS: usize = 1 << 14;

/// [`candidate_pairs`] by testing every pair of the triangles' boxes `b0` and `b1`.
fn few_pairs(m0: &Mesh, b0: &[Aabb], b1: &[Aabb], same: bool) -> Vec<(u32, u32)> {
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

/// The plane that stands for the face of triangle `t`, and its key: for a face whose vertices
/// lie exactly on one plane, the three of them with the smallest indices that are not
/// collinear (in increasing order of index, so the same for the face reversed); else the
/// triangle itself.
pub(crate) fn plane_of(mesh: &Mesh, t: usize) -> (PlaneKey, [Point3; 3]) {
    let f = mesh.face_of(t);
    let mut idx = mesh.faces()[f].vertices().to_vec();
    idx.sort_unstable();
    let v = |i: u32| mesh.vertices()[i as usize];
    let (a, b) = (v(idx[0]), v(idx[1]));
    let third = idx[2..].iter().position(|&i| !collinear(&a, &b, &v(i)));
    if let Some(k) = third {
        let c = v(idx[2 + k]);
        // A face whose vertices share one coordinate is flat (boxes' faces), without asking.
        let level = (0..3).any(|axis| idx.iter().all(|&i| v(i)[axis] == a[axis]));
        let flat = level
            || idx[2..]
                .iter()
                .enumerate()
                .all(|(n, &i)| n == k || orient3d(&a, &b, &c, &v(i)) == Ordering::Equal);
        if flat {
            return (PlaneKey::Face(f), [a, b, c]);
        }
    }
    (PlaneKey::Triangle(t), mesh.triangle(t))
}

/// Which sides of triangle `t` of `mesh` are sides of its face (not diagonals of the face's
/// triangulation).
fn face_sides(mesh: &Mesh, t: usize) -> [bool; 3] {
    let tri = mesh.triangles()[t];
    let face = mesh.faces()[mesh.face_of(t)].vertices();
    let n = face.len();
    let at = |v: u32| face.iter().position(|&w| w == v);
    [0, 1, 2].map(|i| match (at(tri[i]), at(tri[(i + 1) % 3])) {
        (Some(x), Some(y)) => (x + 1) % n == y || (y + 1) % n == x,
        _ => false,
    })
}

/// The sides of each triangle's vertices against the other's plane.
type Sides = [[Ordering; 3]; 2];

/// The sides of each triangle's vertices against the other's plane, unless the first lies
/// strictly on one side of the second's (then they do not meet). They pierce each other only
/// when each crosses the other's plane (see [`crosses`]).
fn sides(m0: &Mesh, i: usize, m1: &Mesh, j: usize) -> Option<Sides> {
    let (t0, t1) = (m0.triangle(i), m1.triangle(j));
    let s0 = t0.map(|p| orient3d(&t1[0], &t1[1], &t1[2], &p));
    // Wholly on one side of the other's plane, the triangles do not meet; on it (coplanar),
    // neither crosses the other's plane.
    if s0[0] == s0[1] && s0[1] == s0[2] {
        return None;
    }
    let s1 = t1.map(|p| orient3d(&t0[0], &t0[1], &t0[2], &p));
    Some([s0, s1])
}

/// Whether triangle `t` of `mesh`, with the sides `s` of its vertices, crosses the other's
/// plane: it has vertices strictly on both sides ([`straddles`]), or it lies along it on a
/// diagonal of its face (two vertices on the plane, joined by a side of the triangle that is
/// not a side of the face). A flat face is then cut by the plane along that diagonal, its
/// triangles on either side of it: whichever way the face is triangulated, its segment is
/// found.
fn crosses(s: &[Ordering; 3], mesh: &Mesh, t: usize) -> bool {
    if straddles(s) {
        return true;
    }
    let on = s.iter().filter(|&&x| x == Ordering::Equal).count();
    let off = s.iter().position(|&x| x != Ordering::Equal);
    match off {
        Some(k) if on == 2 => !face_sides(mesh, t)[(k + 1) % 3],
        _ => false,
    }
}

/// The piece where triangle `i` of `m0` and triangle `j` of `m1` (which [`pierce`] each
/// other, with the sides `sides`; their faces' planes `planes`) meet, if they do along a
/// segment of positive length.
fn piece(
    m0: &Mesh,
    i: usize,
    m1: &Mesh,
    j: usize,
    [s0, s1]: Sides,
    [(k0, p0), (k1, p1)]: [(PlaneKey, [Point3; 3]); 2],
    eye: &Eye,
) -> Option<Piece> {
    let (t0, t1) = (m0.triangle(i), m1.triangle(j));
    // A triangle along the other's plane on a diagonal: only a flat face is cut there.
    let along = |s: &[Ordering; 3], key| !straddles(s) && matches!(key, PlaneKey::Triangle(_));
    if along(&s0, k0) || along(&s1, k1) {
        return None;
    }
    // The sides against the planes that stand for the faces (the triangles', or reversed).
    let s0 = against(s0, &p1, &t0);
    let s1 = against(s1, &p0, &t1);
    let meet = Meet { planes: [p0, p1] };
    let sides = [face_sides(m0, i), face_sides(m1, j)];
    let e0 = section(&meet, eye, 0, (&t0, &s0, &sides[0]), (&t1, &s1))?;
    let e1 = section(&meet, eye, 1, (&t1, &s1, &sides[1]), (&t0, &s0))?;
    // The later start and the earlier end; of two candidates at one point, the lower rank.
    let pick = |x: (OnLine, u8), y: (OnLine, u8), later: bool| match meet.compare(eye, &x.0, &y.0) {
        Ordering::Equal => {
            if x.1 <= y.1 {
                x
            } else {
                y
            }
        }
        Ordering::Less => {
            if later {
                y
            } else {
                x
            }
        }
        Ordering::Greater => {
            if later {
                x
            } else {
                y
            }
        }
    };
    let start = pick(e0[0], e1[0], true).0;
    let end = pick(e0[1], e1[1], false).0;
    (meet.compare(eye, &start, &end) == Ordering::Less).then_some(Piece {
        keys: [k0, k1],
        meet,
        ends: [start, end],
        faces: [m0.face_of(i), m1.face_of(j)],
        triangles: [i, j],
    })
}

/// The sides `s` of the vertices of `t` against its partner's triangle, made the sides against
/// `plane`, the same plane perhaps oriented the other way.
fn against(s: [Ordering; 3], plane: &[Point3; 3], t: &[Point3; 3]) -> [Ordering; 3] {
    let k = s.iter().position(|&x| x != Ordering::Equal).unwrap_or(0);
    if orient3d(&plane[0], &plane[1], &plane[2], &t[k]) == s[k] {
        s
    } else {
        s.map(Ordering::reverse)
    }
}

/// Whether the triangle has vertices strictly on both sides of the other's plane. Without,
/// the triangles are apart, coplanar, or only touch (a face resting on another meets it along
/// an edge that is drawn already): no intersection line.
/// Whether a side of triangle `t` (triangle `index` of `mesh`) that is a side of its face (the
/// vertices' sides `s` of `u`'s plane) crosses `u`'s plane strictly and passes through the
/// closed triangle `u`, decided exactly.
fn edge_through(
    t: &[Point3; 3],
    s: &[Ordering; 3],
    mesh: &Mesh,
    index: usize,
    u: &[Point3; 3],
) -> bool {
    if !straddles(s) {
        return false;
    }
    let edges = face_sides(mesh, index);
    (0..3).filter(|&k| edges[k]).any(|k| {
        let (a, b) = (&t[k], &t[(k + 1) % 3]);
        let crossing =
            s[k] != Ordering::Equal && s[(k + 1) % 3] != Ordering::Equal && s[k] != s[(k + 1) % 3];
        crossing && {
            let sides = [0, 1, 2].map(|m| orient3d(a, b, &u[m], &u[(m + 1) % 3]));
            !(sides.contains(&Ordering::Greater) && sides.contains(&Ordering::Less))
        }
    })
}

fn straddles(s: &[Ordering; 3]) -> bool {
    s.contains(&Ordering::Greater) && s.contains(&Ordering::Less)
}

/// The two ends of the section of triangle `t` (on side `side` of `meet`, with the sides `s`
/// of its vertices against the other plane and which of its sides are the face's) by the
/// other plane, in the line's direction, each with its rank (see the module documentation);
/// `other` is the other triangle with its vertices' sides against this plane.
fn section(
    meet: &Meet,
    eye: &Eye,
    side: usize,
    (t, s, face_sides): (&[Point3; 3], &[Ordering; 3], &[bool; 3]),
    (other, s_other): (&[Point3; 3], &[Ordering; 3]),
) -> Option<[(OnLine, u8); 2]> {
    let apart = other[s_other.iter().position(|&x| x != Ordering::Equal)?];
    let plane = Form::Plane(meet.planes[1 - side]);
    let mut ends = Vec::with_capacity(2);
    for i in 0..3 {
        let j = (i + 1) % 3;
        if s[i] == Ordering::Equal {
            let off = t[(i + 1..i + 3)
                .map(|k| k % 3)
                .find(|&k| s[k] != Ordering::Equal)?];
            let pivot = meet.increasing(eye, Form::Plane([t[i], off, apart]));
            ends.push((OnLine::Vertex { point: t[i], pivot }, 0));
        } else if s[j] != Ordering::Equal && s[i] != s[j] {
            let edge = if s[i] == Ordering::Greater {
                [t[i], t[j]]
            } else {
                [t[j], t[i]]
            };
            let pivot = meet.increasing(eye, Form::Plane([edge[0], edge[1], apart]));
            let rank = if face_sides[i] { 1 } else { 3 } + side as u8;
            ends.push((OnLine::Crossing { edge, plane, pivot }, rank));
        }
    }
    match ends[..] {
        [a, b] => match meet.compare(eye, &a.0, &b.0) {
            Ordering::Less => Some([a, b]),
            Ordering::Greater => Some([b, a]),
            Ordering::Equal => None,
        },
        _ => None,
    }
}

/// Where the segment `ab` passes through the closed triangle `t` of `mesh` crossing its plane
/// (its ends strictly on either side of it), the crossing: the zero along `ab` of the plane of
/// its face (see [`plane_of`]).
pub(crate) fn pierces(eye: &Eye, a: &Point3, b: &Point3, mesh: &Mesh, t: usize) -> Option<Zero> {
    let tri = mesh.triangle(t);
    let (sa, sb) = (
        orient3d(&tri[0], &tri[1], &tri[2], a),
        orient3d(&tri[0], &tri[1], &tri[2], b),
    );
    if sa == Ordering::Equal || sb == Ordering::Equal || sa == sb {
        return None;
    }
    let (mut above, mut below) = (false, false);
    for i in 0..3 {
        match orient3d(a, b, &tri[i], &tri[(i + 1) % 3]) {
            Ordering::Greater => above = true,
            Ordering::Less => below = true,
            Ordering::Equal => {}
        }
    }
    if above && below {
        return None;
    }
    Form::Plane(plane_of(mesh, t).1).zero_on(eye, a, b)
}

/// Where the segment `ends` of the line `meet` passes through the closed triangle `tri`
/// strictly between its ends: the plane `plane` of its face (see [`plane_of`]), oriented to
/// increase along the line. Decided exactly, like [`pierces`] for an edge.
pub(crate) fn pierces_line(
    meet: &Meet,
    eye: &Eye,
    ends: &[OnLine; 2],
    tri: &[Point3; 3],
    plane: &[Point3; 3],
) -> Option<Form> {
    let form = Form::Plane(*plane);
    let sx = meet.sign_at(eye, &ends[0], &form);
    let sy = meet.sign_at(eye, &ends[1], &form);
    if sx == Ordering::Equal || sy == Ordering::Equal || sx == sy {
        return None;
    }
    let (mut above, mut below) = (false, false);
    for i in 0..3 {
        match meet.twist(&tri[i], &tri[(i + 1) % 3]) {
            Ordering::Greater => above = true,
            Ordering::Less => below = true,
            Ordering::Equal => {}
        }
    }
    if above && below {
        return None;
    }
    Some(if sx == Ordering::Less {
        form
    } else {
        reversed(&form)
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::solids::uv_sphere;
    use nalgebra::{Matrix4, Vector3};

    /// Whether the pair `(i, j)` gives the pass anything: a piece of an intersection segment,
    /// or a contact (an edge through the other triangle).
    fn productive(m0: &Mesh, i: usize, m1: &Mesh, j: usize) -> bool {
        let Some([s0, s1]) = sides(m0, i, m1, j) else {
            return false;
        };
        let (t0, t1) = (m0.triangle(i), m1.triangle(j));
        let eye = Eye::Infinity(Vector3::z());
        let planes = [plane_of(m0, i), plane_of(m1, j)];
        (crosses(&s0, m0, i)
            && crosses(&s1, m1, j)
            && piece(m0, i, m1, j, [s0, s1], planes, &eye).is_some())
            || edge_through(&t0, &s0, m0, i, &t1)
            || edge_through(&t1, &s1, m1, j, &t0)
    }

    /// The grid's pairs against every pair: none that gives anything is missed, and each
    /// found is a pair whose boxes meet (and, in one mesh, that shares no vertex).
    fn check(m0: &Mesh, m1: &Mesh, same: bool) -> usize {
        let boxes = |m: &Mesh| {
            (0..m.triangles().len())
                .map(|t| Aabb::from_points(&m.triangle(t)))
                .collect::<Vec<_>>()
        };
        let (b0, b1) = (boxes(m0), boxes(m1));
        assert!(b0.len() * b1.len() > FEW_PAIRS, "the grid is not used");
        let grid = candidate_pairs(m0, m1, same);
        assert!(
            grid.windows(2).all(|w| w[0] < w[1]),
            "not sorted and unique"
        );
        let all = few_pairs(m0, &b0, &b1, same);
        for &(i, j) in &grid {
            assert!(
                all.binary_search(&(i, j)).is_ok(),
                "({i}, {j}) is not a candidate"
            );
        }
        let mut productive_pairs = 0;
        for &(i, j) in &all {
            if productive(m0, i as usize, m1, j as usize) {
                productive_pairs += 1;
                assert!(
                    grid.binary_search(&(i, j)).is_ok(),
                    "({i}, {j}) missed: {:?} {:?} same {same}",
                    m0.triangle(i as usize),
                    m1.triangle(j as usize)
                );
            }
        }
        productive_pairs
    }

    fn moved(m: &Mesh, by: [f64; 3], scale: f64) -> Mesh {
        let t = Matrix4::new_translation(&Vector3::from(by)) * Matrix4::new_scaling(scale);
        m.transformed(&t).unwrap()
    }

    /// Random triangles, some large and some slivers, crossing each other everywhere.
    fn soup(n: usize, seed: u64) -> Mesh {
        let mut s = seed;
        let mut next = || {
            s = s
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (s >> 11) as f64 / (1u64 << 53) as f64
        };
        let mut vertices = Vec::new();
        let mut faces = Vec::new();
        for k in 0..n {
            let c = Point3::new(next(), next(), next());
            let r = if k % 3 == 0 { 0.5 } else { 0.08 };
            let thin = if k % 5 == 0 { 1e-6 } else { 1.0 };
            let a = c + Vector3::new(next() - 0.5, next() - 0.5, next() - 0.5) * r;
            let b = c + Vector3::new(next() - 0.5, next() - 0.5, next() - 0.5) * r;
            let d = a
                + (b - a) * 0.5
                + Vector3::new(next() - 0.5, next() - 0.5, next() - 0.5) * r * thin;
            let v = vertices.len() as u32;
            vertices.extend([a, b, d]);
            faces.push(vec![v, v + 1, v + 2]);
        }
        Mesh::from_polygons(vertices, faces).unwrap()
    }

    #[test]
    fn triangles_surely_apart_make_nothing() {
        // Pairs of the soups, and pairs that touch exactly: at a vertex, along an edge, a
        // vertex on the other's interior; and pairs apart by one ulp.
        let mut apart = 0;
        for seed in 0..3 {
            let (s, t) = (soup(300, seed), soup(300, seed + 50));
            for i in 0..s.triangles().len() {
                for j in 0..t.triangles().len() {
                    if surely_apart(&s.triangle(i), &t.triangle(j)) {
                        apart += 1;
                        assert!(!productive(&s, i, &t, j), "{i} {j} are not apart");
                    }
                }
            }
        }
        assert!(apart > 10_000);
        let p = |x: f64, y: f64, z: f64| Point3::new(x, y, z);
        let a = [p(0.0, 0.0, 0.0), p(1.0, 0.0, 0.0), p(0.0, 1.0, 0.0)];
        let touching = [
            [p(1.0, 0.0, 0.0), p(2.0, 1.0, 1.0), p(2.0, -1.0, 0.5)],
            [p(0.5, 0.5, 0.0), p(0.5, 0.5, 1.0), p(1.5, 1.5, 0.3)],
            [p(0.25, 0.25, 0.0), p(3.0, 1.0, 1.0), p(1.0, 3.0, -1.0)],
            [p(0.1, 0.1, -1.0), p(0.1, 0.1, 1.0), p(-3.0, 0.1, 0.0)],
        ];
        for b in &touching {
            assert!(!surely_apart(&a, b), "{b:?} touches");
            assert!(!surely_apart(b, &a), "{b:?} touches");
        }
        let next = 1.0f64.next_up();
        let beyond = [p(next, 0.0, 0.0), p(2.0, 1.0, 1.0), p(2.0, -1.0, 0.5)];
        // One ulp away is apart, but too close for the filter to be sure: the exact test decides.
        assert!(!surely_apart(&a, &beyond));
        let far = [p(1.5, 0.0, 0.0), p(2.0, 1.0, 1.0), p(2.0, -1.0, 0.5)];
        assert!(surely_apart(&a, &far));
    }

    #[test]
    fn crowded_cells_are_split_and_miss_no_pair() {
        // Two fans of 3,000 slivers, one turned by a third of a sliver about the axis and
        // raised a little: along the rims, each sliver crosses several of the other's, and
        // the rims' cells hold hundreds of triangles.
        let fan = uv_sphere(1.0, 1500, 2).unwrap();
        let turn =
            nalgebra::Rotation3::from_axis_angle(&Vector3::z_axis(), 0.7e-3).to_homogeneous();
        let turned = fan
            .transformed(&(Matrix4::new_translation(&Vector3::new(0.0, 0.0, 1e-3)) * turn))
            .unwrap();
        assert!(check(&fan, &turned, false) > 1000);
        // A crowded cell on the rims is split, and the smaller cells find every pair that
        // meets in it.
        let boxes = |m: &Mesh| -> Vec<Aabb> {
            (0..m.triangles().len())
                .map(|t| Aabb::from_points(&m.triangle(t)))
                .collect()
        };
        let (b0, b1) = (boxes(&fan), boxes(&turned));
        let pairing = Pairing {
            meshes: [&fan, &turned],
            boxes: [&b0, &b1],
            same: false,
        };
        let region = Aabb::new(
            Point3::new(0.95, -0.05, -0.05),
            Point3::new(1.05, 0.05, 0.05),
        );
        let near = |b: &[Aabb]| -> Vec<u32> {
            (0..b.len() as u32)
                .filter(|&t| b[t as usize].intersects(&region))
                .collect()
        };
        let (near0, near1) = (near(&b0), near(&b1));
        assert!(near0.len() > 30 && near1.len() > 30);
        let items: Vec<u32> = near0
            .iter()
            .copied()
            .chain(near1.iter().map(|t| t | 1 << 31))
            .collect();
        let mut out = Vec::new();
        let load = |sub: &[u32]| {
            let firsts = sub.partition_point(|i| i >> 31 == 0);
            firsts * (sub.len() - firsts)
        };
        assert!(pairing.split(&items, &region, 0, &mut out, load));
        out.sort_unstable();
        out.dedup();
        let mut productive_pairs = 0;
        for &i in &near0 {
            for &j in &near1 {
                let (t0, t1) = (fan.triangle(i as usize), turned.triangle(j as usize));
                // Pairs that meet in the region: slivers with a rim corner well inside it
                // (they meet within a sliver's width of their rim corners).
                let inner = Aabb::new(
                    Point3::new(0.96, -0.04, -0.04),
                    Point3::new(1.04, 0.04, 0.04),
                );
                let inside = |t: &[Point3; 3]| t.iter().any(|p| inner.contains_point(p));
                if inside(&t0) && inside(&t1) && productive(&fan, i as usize, &turned, j as usize) {
                    productive_pairs += 1;
                    assert!(out.binary_search(&(i, j)).is_ok(), "({i}, {j}) missed");
                }
            }
        }
        assert!(productive_pairs > 30);
        // One mesh: the two fans as one soup of crossing slivers.
        let both = Mesh::from_polygons(
            fan.vertices()
                .iter()
                .chain(turned.vertices())
                .copied()
                .collect(),
            fan.triangles()
                .iter()
                .map(|t| t.to_vec())
                .chain(
                    turned
                        .triangles()
                        .iter()
                        .map(|t| t.iter().map(|v| v + fan.vertices().len() as u32).collect()),
                )
                .collect(),
        )
        .unwrap();
        assert!(check(&both, &both, true) > 1000);
    }

    #[test]
    fn the_grid_misses_no_pair_of_a_fan_or_a_soup() {
        // Two cones of 600 slivers base to base: every pair meets at an apex or the rim.
        let fan = uv_sphere(1.0, 600, 2).unwrap();
        check(&fan, &fan, true);
        // The fan against itself turned and moved so the apexes pierce the other's sides.
        let other = moved(&fan, [0.25, 0.1, 0.5], 0.75);
        assert!(check(&fan, &other, false) > 0);
        for seed in 0..4 {
            let s = soup(400, seed);
            assert!(check(&s, &s, true) > 0);
            let t = soup(300, seed + 100);
            assert!(check(&s, &t, false) > 0);
        }
        // Spheres that cut each other, and at extreme scales and offsets.
        let sphere = uv_sphere(1.0, 48, 24).unwrap();
        for (by, scale) in [
            ([0.5, 0.3, 0.2], 1.0),
            ([1e8, 0.0, 0.0], 1e-7),
            ([0.0; 3], 1e-90),
        ] {
            let a = moved(&sphere, by, scale);
            let b = moved(&sphere, [by[0] + 0.7 * scale, by[1], by[2]], scale);
            assert!(check(&a, &b, false) > 0);
        }
    }
}
