//! The edges of a mesh, each once, and their classes in a view.
//!
//! An edge is a side of a face (the diagonals of a face's triangulation are not edges); the
//! faces of a polygon that was split into triangles because it is not exactly planar meet
//! along its diagonals, which are edges like any other but not edges of the input polygon.
//! Its class depends on the view only through exact signs: the side of the picture of the
//! edge on which each of its faces lies (`orient3d` of the edge, the face's third vertex and
//! the eye). Two faces on the same side make a silhouette whatever their orientation, so an
//! inside-out or inconsistently oriented mesh draws as the correct one does. Coplanar
//! neighbours (decided exactly) share no edge at all, so a triangulated flat face draws as one
//! polygon. Only the crease angle is a measurement (a user's threshold, not a sign).
//!
//! A side with vertices of the mesh lying exactly inside it (a T-junction, as where a sliver
//! face was dropped) is matched piecewise with the sides that cover it; consecutive pieces
//! between the same two surfaces (the same triangle on one side, coplanar faces turned the
//! same way on the other) draw as one edge, so the mesh draws as it would without the
//! junction.

use super::cuts::frustum_cuts;
use super::line::Line;
use super::line::LineId;
use super::pass::{Leaf, Pass};
use super::{EdgeClass, EdgeSelection, Options};
use crate::geometry::exact::ldexp;
use crate::geometry::kernel::Exponents;
use crate::geometry::predicates::{orient2d, orient3d, project};
use crate::geometry::{Point3, Vector3};
use crate::mesh::Mesh;
use crate::sight::frustum::{Clip, TilePlanes};
use crate::sight::own_solid::turned_away;
use crate::union_find::UnionFind;
use crate::views::{Eye, Picture};
use rayon::prelude::*;
use std::cmp::Ordering;
use std::time::Instant;

/// One edge of a mesh: its vertices (indices into the mesh) and class.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct MeshEdge {
    /// The first vertex.
    pub a: u32,
    /// The second vertex.
    pub b: u32,
    /// The class in the view.
    pub class: EdgeClass,
    /// The triangles on its first two sides (the same twice for a boundary edge).
    pub triangles: [u32; 2],
}

/// What [`classify`] found besides the edges it returns.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub(crate) struct EdgeCounts {
    /// Edges between coplanar faces, which are not edges of the drawing.
    pub flat: usize,
    /// Edges seen end-on (pointing at the eye), whose picture is a point.
    pub end_on: usize,
    /// Edges classified but not asked for by the selection.
    pub left_out: usize,
    /// The edges classified, by class (those left out included).
    pub by_class: [usize; 5],
}

/// A face's side of an edge: the face's triangle with that side, its vertex off the edge, and
/// whether the side is an edge of the input polygon.
#[derive(Debug, Clone, Copy, Default)]
struct FaceSide {
    key: u64,
    third: u32,
    triangle: u32,
    polygon_edge: bool,
}

/// The undirected key of the edge `pq`.
fn key(p: u32, q: u32) -> u64 {
    (u64::from(p.min(q)) << 32) | u64::from(p.max(q))
}

/// Every edge of `mesh` that `selection` draws, with its class as seen from `eye` (each
/// triangle's turn there given by `turns`, from [`triangle_turns`]);
/// `crease_cos` is `-cos` of the crease angle (an edge is a crease when the cosine of the
/// angle between its faces exceeds it). Coplanar (except polygon edges for
/// [`EdgeSelection::Mesh`], drawn as smooth edges), end-on and unselected edges are left out
/// and counted. [`EdgeSelection::Mesh`] selects the polygon edges and the diagonals of split
/// polygons that are silhouettes or boundaries (the outline is drawn whole).
pub(crate) fn classify(
    mesh: &Mesh,
    eye: &Eye,
    turns: &[Ordering],
    crease_cos: f64,
    selection: EdgeSelection,
) -> (Vec<MeshEdge>, EdgeCounts) {
    let mut sides = face_sides(mesh);
    crate::mesh::sort_by_edge(&mut sides, |s| s.key);
    let vertices = mesh.vertices();
    let seen = Seen {
        vertices,
        triangles: mesh.triangles(),
        turns,
        eye,
    };
    let same_edge = |x: &FaceSide, y: &FaceSide| x.key == y.key;
    if mesh.t_junctions() == 0 {
        // Each edge decided on its own: only the drawn ones are kept (for feature edges, a
        // few thousandths of a scan's), the others only counted.
        return sides
            .par_chunk_by(same_edge)
            .fold(
                || (Vec::new(), EdgeCounts::default()),
                |(mut edges, mut counts), group| {
                    let decided = decide(group, &seen, crease_cos, selection);
                    counts.count(&decided);
                    edges.extend(decided.ok());
                    (edges, counts)
                },
            )
            .reduce(
                || (Vec::new(), EdgeCounts::default()),
                |(mut edges, counts), (more, other)| {
                    edges.extend(more);
                    (edges, counts.plus(&other))
                },
            );
    }
    let groups: Vec<&[FaceSide]> = sides.chunk_by(same_edge).collect();
    let mut decided: Vec<Result<MeshEdge, Left>> = groups
        .par_iter()
        .map(|group| decide(group, &seen, crease_cos, selection))
        .collect();
    join_pieces(mesh, eye, &groups, &mut decided);
    let mut counts = EdgeCounts::default();
    for d in &decided {
        counts.count(d);
    }
    let mut edges: Vec<MeshEdge> = decided.into_iter().filter_map(Result::ok).collect();
    // In the order of their ends, as the edges of the mesh without the junctions are.
    edges.sort_unstable_by_key(|e| key(e.a, e.b));
    (edges, counts)
}

/// Every side of every face, as the side of the face's triangle that has it; a side cut at
/// T-junctions as one side per piece between consecutive vertices on it.
fn face_sides(mesh: &Mesh) -> Vec<FaceSide> {
    let triangles = mesh.triangles();
    mesh.faces()
        .par_iter()
        .enumerate()
        .flat_map_iter(|(f, face)| {
            let v = face.vertices();
            (0..v.len()).flat_map(move |i| {
                let (p, q) = (v[i], v[(i + 1) % v.len()]);
                // The triangle of the face's triangulation that has this side.
                let side = face.triangle_range().find_map(|t| {
                    let tri = triangles[t];
                    if !(tri.contains(&p) && tri.contains(&q)) {
                        return None;
                    }
                    let third = tri.iter().copied().find(|&w| w != p && w != q)?;
                    Some(FaceSide {
                        key: key(p, q),
                        third,
                        triangle: t as u32,
                        polygon_edge: face.is_polygon_edge(i),
                    })
                });
                let inner = side.and(mesh.side_junctions(f, i)).unwrap_or_default();
                let pieces = std::iter::once(p)
                    .chain(inner.iter().copied())
                    .zip(inner.iter().copied().chain(std::iter::once(q)));
                pieces.filter_map(move |(a, b)| {
                    side.map(|s| FaceSide {
                        key: key(a, b),
                        ..s
                    })
                })
            })
        })
        .collect()
}

/// What [`decide`] reads of a mesh seen from an eye: its vertices and triangles, and each
/// triangle's turn in the picture (its exact [`Eye::orient3d`]).
struct Seen<'a> {
    vertices: &'a [Point3],
    triangles: &'a [[u32; 3]],
    turns: &'a [Ordering],
    eye: &'a Eye,
}

impl Seen<'_> {
    /// `eye.orient3d(a, b, c)` for the side `ab` of triangle `t` whose third vertex is `c`:
    /// when `a` and `b` are vertices of `t`, its turn, reversed when `a` to `b` runs against
    /// its order (an exact sign keeps under cyclic shifts and reverses under a swap); for a
    /// piece of a side cut at T-junctions, the sign itself.
    fn side(&self, t: u32, [a, b, c]: [u32; 3]) -> Ordering {
        let tri = self.triangles[t as usize];
        let turn = self.turns[t as usize];
        if (0..3).any(|i| tri[i] == a && tri[(i + 1) % 3] == b) {
            turn
        } else if (0..3).any(|i| tri[i] == b && tri[(i + 1) % 3] == a) {
            turn.reverse()
        } else {
            let [pa, pb, pc] = [a, b, c].map(|v| &self.vertices[v as usize]);
            self.eye.orient3d(pa, pb, pc)
        }
    }
}

/// Each triangle's turn in the picture, its exact [`Eye::orient3d`]: taken once per triangle,
/// and read by the edges on its three sides.
pub(crate) fn triangle_turns(mesh: &Mesh, eye: &Eye) -> Vec<Ordering> {
    let turn = |tri: &[u32; 3]| {
        let [p, q, r] = tri.map(|v| &mesh.vertices()[v as usize]);
        eye.orient3d(p, q, r)
    };
    if mesh.triangles().len() >= crate::mesh::PARALLEL_POLYGONS {
        mesh.triangles().par_iter().map(turn).collect()
    } else {
        mesh.triangles().iter().map(turn).collect()
    }
}

/// The edge that the faces' sides `group` (one edge's) make, or why it is not drawn.
fn decide(
    group: &[FaceSide],
    seen: &Seen,
    crease_cos: f64,
    selection: EdgeSelection,
) -> Result<MeshEdge, Left> {
    let (vertices, eye) = (seen.vertices, seen.eye);
    let (a, b) = ((group[0].key >> 32) as u32, group[0].key as u32);
    let (pa, pb) = (&vertices[a as usize], &vertices[b as usize]);
    let sides =
        [0, group.len().min(2) - 1].map(|k| seen.side(group[k].triangle, [a, b, group[k].third]));
    // Seen end-on, every face at the edge is seen edge-on: one that is not tells at once.
    if sides[0] == Ordering::Equal && eye.sees_end_on(pa, pb) {
        return Err(Left::EndOn);
    }
    let third = |k: usize| &vertices[group[k].third as usize];
    let class = match group.len() {
        1 => Some(EdgeClass::Boundary),
        2 => class_of(pa, pb, [third(0), third(1)], sides, crease_cos),
        _ => Some(class_of_many(
            pa,
            pb,
            group.iter().map(|s| &vertices[s.third as usize]),
            eye,
        )),
    };
    let polygon_edge = group.iter().any(|s| s.polygon_edge);
    let class = match class {
        Some(class) => class,
        None if selection == EdgeSelection::Mesh && polygon_edge => EdgeClass::Smooth,
        None => return Err(Left::Flat),
    };
    let drawn = match selection {
        EdgeSelection::Feature => class != EdgeClass::Smooth,
        EdgeSelection::All => class != EdgeClass::Smooth || polygon_edge,
        // A diagonal of a split polygon where the surface folds out of sight (or
        // ends) is part of the outline: without it the outline has a gap.
        EdgeSelection::Mesh => {
            polygon_edge || matches!(class, EdgeClass::Silhouette | EdgeClass::Boundary)
        }
    };
    let edge = MeshEdge {
        a,
        b,
        class,
        triangles: [group[0].triangle, group[group.len().min(2) - 1].triangle],
    };
    if drawn {
        Ok(edge)
    } else {
        Err(Left::NotAsked(class))
    }
}

impl EdgeCounts {
    /// Counts an edge decided: drawn or left out by class, flat or end-on.
    fn count(&mut self, decided: &Result<MeshEdge, Left>) {
        match decided {
            Ok(e) => self.by_class[e.class as usize] += 1,
            Err(Left::NotAsked(class)) => {
                self.by_class[*class as usize] += 1;
                self.left_out += 1;
            }
            Err(Left::Flat) => self.flat += 1,
            Err(Left::EndOn) => self.end_on += 1,
            Err(Left::Joined) => {}
        }
    }

    /// The counts of both.
    fn plus(&self, other: &EdgeCounts) -> EdgeCounts {
        EdgeCounts {
            flat: self.flat + other.flat,
            end_on: self.end_on + other.end_on,
            left_out: self.left_out + other.left_out,
            by_class: std::array::from_fn(|k| self.by_class[k] + other.by_class[k]),
        }
    }
}

/// Why an edge is not part of the drawing.
#[derive(Debug, Clone, Copy)]
enum Left {
    /// Between coplanar faces.
    Flat,
    /// Seen end-on.
    EndOn,
    /// Of a class the selection leaves out.
    NotAsked(EdgeClass),
    /// A piece of a side cut at T-junctions, joined into the edge of its first piece.
    Joined,
}

/// Joins the consecutive pieces of each side cut at T-junctions that lie between the same two
/// surfaces into one edge: the same class, the side's own triangle on one side, and on the
/// other coplanar triangles on the same side of the edge, turned the same way in the view. The
/// joined edge replaces the first piece; the others are left out.
fn join_pieces(
    mesh: &Mesh,
    eye: &Eye,
    groups: &[&[FaceSide]],
    decided: &mut [Result<MeshEdge, Left>],
) {
    let group_of = |p: u32, q: u32| groups.binary_search_by_key(&key(p, q), |g| g[0].key).ok();
    // Disjoint sets of groups: each joined run is named by its first piece.
    let mut joined = UnionFind::new(groups.len());
    for (f, face) in mesh.faces().iter().enumerate() {
        let v = face.vertices();
        for i in 0..v.len() {
            let Some(inner) = mesh.side_junctions(f, i) else {
                continue;
            };
            let (p, q) = (v[i], v[(i + 1) % v.len()]);
            let ends: Vec<u32> = std::iter::once(p)
                .chain(inner.iter().copied())
                .chain(std::iter::once(q))
                .collect();
            for w in ends.windows(3) {
                let (Some(g1), Some(g2)) = (group_of(w[0], w[1]), group_of(w[1], w[2])) else {
                    continue;
                };
                let pieces = [groups[g1], groups[g2]];
                if one_edge(
                    mesh,
                    eye,
                    pieces,
                    [&decided[g1], &decided[g2]],
                    [w[0], w[2]],
                ) {
                    joined.union(g1, g2);
                }
            }
        }
    }
    stretch_runs(mesh, &mut joined, decided);
}

/// Whether two consecutive pieces of a side (the faces' sides `pieces`, decided as
/// `decided`), from `ends[0]` to `ends[1]`, lie between the same two surfaces (see
/// [`join_pieces`]).
fn one_edge(
    mesh: &Mesh,
    eye: &Eye,
    pieces: [&[FaceSide]; 2],
    decided: [&Result<MeshEdge, Left>; 2],
    ends: [u32; 2],
) -> bool {
    let [g1, g2] = pieces;
    let (Ok(e1), Ok(e2)) = (decided[0], decided[1]) else {
        return false;
    };
    if e1.class != e2.class || g1.len() != 2 || g2.len() != 2 {
        return false;
    }
    // The triangle both pieces share (this side's), and the other of each.
    let shared = g1.iter().find_map(|s| {
        g2.iter()
            .any(|t| t.triangle == s.triangle)
            .then_some(s.triangle)
    });
    let Some(shared) = shared else {
        return false;
    };
    let other = |g: &[FaceSide]| g.iter().find(|s| s.triangle != shared).copied();
    let (Some(o1), Some(o2)) = (other(g1), other(g2)) else {
        return false;
    };
    let vertices = mesh.vertices();
    let point = |v: u32| &vertices[v as usize];
    let (a, b) = (point(ends[0]), point(ends[1]));
    let (c1, c2) = (point(o1.third), point(o2.third));
    let turned = |t: u32| {
        let [x, y, z] = mesh.triangle(t as usize);
        eye.orient3d(&x, &y, &z)
    };
    same_half_plane(a, b, c1, c2) && turned(o1.triangle) == turned(o2.triangle)
}

/// Each run of joined pieces (a set of `joined` with more than one decided piece) made its
/// first piece, stretched to the run's extreme ends; the others are left out as joined.
fn stretch_runs(mesh: &Mesh, joined: &mut UnionFind, decided: &mut [Result<MeshEdge, Left>]) {
    let vertices = mesh.vertices();
    let point = |v: u32| &vertices[v as usize];
    // Each run becomes its first piece stretched to the run's extreme ends, along a
    // coordinate in which the run's (collinear) ends differ.
    let mut runs: Vec<(usize, usize)> = (0..decided.len())
        .filter(|&g| decided[g].is_ok())
        .map(|g| (joined.find(g), g))
        .filter(|&(r, g)| r != g)
        .collect();
    runs.sort_unstable();
    for run in runs.chunk_by(|x, y| x.0 == y.0) {
        let r = run[0].0;
        let Ok(first) = decided[r] else {
            continue;
        };
        let (pa, pb) = (point(first.a), point(first.b));
        let k = (0..3).find(|&k| pa[k] != pb[k]).unwrap_or(0);
        let mut ends: Vec<u32> = vec![first.a, first.b];
        for &(_, g) in run {
            if let Ok(e) = decided[g] {
                ends.extend([e.a, e.b]);
            }
            decided[g] = Err(Left::Joined);
        }
        let along = |v: &u32| point(*v)[k];
        let low = ends
            .iter()
            .copied()
            .min_by(|x, y| along(x).total_cmp(&along(y)));
        let high = ends
            .iter()
            .copied()
            .max_by(|x, y| along(x).total_cmp(&along(y)));
        if let (Some(low), Some(high), Ok(e)) = (low, high, &mut decided[r]) {
            (e.a, e.b) = (low.min(high), low.max(high));
        }
    }
}

/// Whether `c1` and `c2`, lying in one plane with the line `ab`, are on either side of it.
fn on_either_side(a: &Point3, b: &Point3, c1: &Point3, c2: &Point3) -> bool {
    let side = |k: usize, c: &Point3| orient2d(project(a, k), project(b, k), project(c, k));
    (0..3)
        .find(|&k| side(k, c1) != Ordering::Equal)
        .is_some_and(|k| side(k, c1) == side(k, c2).reverse())
}

/// Whether `c1` and `c2` lie in one plane with the line `ab` and on the same side of it.
fn same_half_plane(a: &Point3, b: &Point3, c1: &Point3, c2: &Point3) -> bool {
    if orient3d(a, b, c1, c2) != Ordering::Equal {
        return false;
    }
    let side = |k: usize, c: &Point3| orient2d(project(a, k), project(b, k), project(c, k));
    (0..3)
        .find(|&k| side(k, c1) != Ordering::Equal)
        .is_some_and(|k| side(k, c1) == side(k, c2))
}

/// The class of an edge `ab` of more than two faces (third vertices `thirds`): a silhouette
/// when all lie on one side of its picture or one is seen edge-on, else a crease.
fn class_of_many<'a>(
    a: &Point3,
    b: &Point3,
    thirds: impl Iterator<Item = &'a Point3>,
    eye: &Eye,
) -> EdgeClass {
    let mut seen = [false; 3];
    for c in thirds {
        seen[(eye.orient3d(a, b, c) as i8 + 1) as usize] = true;
    }
    if seen[1] || !(seen[0] && seen[2]) {
        EdgeClass::Silhouette
    } else {
        EdgeClass::Crease
    }
}

/// The class of the edge `ab` of two faces whose third vertices are `c1` and `c2` and whose
/// sides of the edge's picture are `s1` and `s2` (`eye.orient3d(a, b, c_k)`), or `None` for an
/// edge between two coplanar faces on either side of it, in every view (seen edge-on, such
/// faces are one flat face seen edge-on: its outline is drawn, not the edge, as for a face
/// that is not split).
fn class_of(
    a: &Point3,
    b: &Point3,
    [c1, c2]: [&Point3; 2],
    [s1, s2]: [Ordering; 2],
    crease_cos: f64,
) -> Option<EdgeClass> {
    let coplanar = || orient3d(a, b, c1, c2) == Ordering::Equal;
    if s1 == Ordering::Equal && s2 == Ordering::Equal && coplanar() && on_either_side(a, b, c1, c2)
    {
        return None;
    }
    if s1 == Ordering::Equal || s2 == Ordering::Equal || s1 == s2 {
        return Some(EdgeClass::Silhouette);
    }
    if coplanar() {
        // Coplanar, and (their picture sides differing) on either side of the edge.
        if on_either_side(a, b, c1, c2) {
            return None;
        }
        return Some(EdgeClass::Crease);
    }
    // The angle between the faces: between the components of c1 - a and c2 - a across the
    // edge, from the differences scaled by a power of two (exactly) so that their products
    // neither underflow nor overflow: the same class at every scale.
    let (e, v1, v2) = (b - a, c1 - a, c2 - a);
    let largest = [e, v1, v2]
        .iter()
        .flat_map(|v| v.iter())
        .fold(0.0f64, |m, x| m.max(x.abs()));
    let k = Exponents::of(&[largest]).max;
    let unit = |v: Vector3| {
        if largest.is_finite() && largest > 0.0 {
            v.map(|x| ldexp(x, -k))
        } else {
            v
        }
    };
    let (e, v1, v2) = (unit(e), unit(v1), unit(v2));
    let across = |v: Vector3| -> Vector3 { v - e * (v.dot(&e) / e.dot(&e)) };
    let (u1, u2) = (across(v1), across(v2));
    let cos = u1.dot(&u2) / (u1.norm() * u2.norm());
    Some(if cos > crease_cos {
        EdgeClass::Crease
    } else {
        EdgeClass::Smooth
    })
}

/// A mesh's edges classified in the view (with what [`classify`] counted), and its vertices'
/// pictures, whether each vertex is in front of the eye when the view clips, and whether each
/// is inside the frustum and the tile (both empty when there is neither).
struct LeafEdges {
    edges: Vec<MeshEdge>,
    counts: EdgeCounts,
    pictures: Vec<[f64; 2]>,
    front: Vec<bool>,
    inside: Vec<bool>,
    /// Each triangle's turn in the picture.
    turns: Vec<Ordering>,
}

/// The edges of `leaf` classified from `eye` (see [`LeafEdges`]), its vertices pictured by
/// `picture`, placed against the frustum `clip` and the `tile`.
fn leaf_edges(
    leaf: &Leaf,
    (eye, picture): (&Eye, &Picture),
    clip: Option<Clip>,
    tile: Option<&TilePlanes>,
    crease_cos: f64,
    selection: EdgeSelection,
) -> LeafEdges {
    let vertices = leaf.mesh.vertices();
    let front: Vec<bool> = match &clip {
        Some(n) => vertices.par_iter().map(|p| n.in_front(p)).collect(),
        None => Vec::new(),
    };
    let inside: Vec<bool> = match (&clip, tile) {
        (None, None) => Vec::new(),
        _ => vertices
            .par_iter()
            .map(|p| {
                clip.is_none_or(|n| n.contains(eye, p)) && tile.is_none_or(|t| t.contains(eye, p))
            })
            .collect(),
    };
    let pictures: Vec<[f64; 2]> = vertices
        .par_iter()
        .enumerate()
        .map(|(i, p)| match front.get(i) {
            Some(false) => [0.0, 0.0],
            _ => picture.point(p),
        })
        .collect();
    let turns = triangle_turns(leaf.mesh, eye);
    let (edges, counts) = classify(leaf.mesh, eye, &turns, crease_cos, selection);
    LeafEdges {
        edges,
        counts,
        pictures,
        front,
        inside,
        turns,
    }
}

impl Pass<'_> {
    /// Stage 1: every mesh's edges, classified, and its vertices' pictures; the lines to draw.
    pub(super) fn edges(&mut self, options: &Options) {
        let clock = Instant::now();
        let (eye, picture, clip) = (&self.eye, &self.picture, self.clip);
        let tile = self.tile.as_ref();
        let crease_cos = -options.crease_angle.to_radians().cos();
        let classified: Vec<LeafEdges> = self
            .leaves
            .par_iter()
            .map(|leaf| leaf_edges(leaf, (eye, picture), clip, tile, crease_cos, options.edges))
            .collect();
        let mut total = EdgeCounts::default();
        let (mut behind, mut outside_tile) = (0, 0);
        for (n, found) in classified.into_iter().enumerate() {
            let counts = found.counts;
            total.flat += counts.flat;
            total.end_on += counts.end_on;
            total.left_out += counts.left_out;
            for (total, n) in total.by_class.iter_mut().zip(counts.by_class) {
                *total += n;
            }
            let (b, o) = self.leaf_lines(n, found);
            behind += b;
            outside_tile += o;
        }
        let (done, skipped) = self.edges_report(&total, options.edges, behind, outside_tile);
        self.stage("edges", clock, done, Some(skipped));
    }

    /// The lines of the edges of leaf `n` (see [`Line`]), and the cuts where those the view
    /// clips leave its frustum or the tile; the leaf keeps its vertices' pictures and the
    /// range of its lines. How many edges were left out as wholly behind the eye, and as
    /// wholly outside the tile.
    fn leaf_lines(&mut self, n: usize, found: LeafEdges) -> (usize, usize) {
        let (eye, clip, tile) = (&self.eye, self.clip, self.tile.as_ref());
        let LeafEdges {
            edges,
            pictures,
            front,
            inside,
            turns,
            ..
        } = found;
        let (id, mesh, global) = {
            let leaf = &self.leaves[n];
            (leaf.id, leaf.mesh, leaf.global)
        };
        let (mut behind, mut outside_tile) = (0, 0);
        // Each triangle's side once (an edge would ask for each of its two).
        let turned: Vec<bool> = turned_away(self.scene, id, mesh, eye)
            .map(|side| turns.iter().map(|&t| t == side).collect())
            .unwrap_or_default();
        let first = self.lines.len();
        for (k, e) in edges.into_iter().enumerate() {
            let (a, b) = (e.a as usize, e.b as usize);
            let in_front = |v: usize| front.get(v).is_none_or(|&f| f);
            if !in_front(a) && !in_front(b) {
                // Wholly behind the eye: nothing of it is drawn or bounds what is seen.
                behind += 1;
                continue;
            }
            let ends = [mesh.vertices()[a], mesh.vertices()[b]];
            if tile.is_some_and(|t| t.surely_outside(&ends)) {
                // Wholly outside the tile: nothing of it is drawn there, and where it
                // crosses a contour or pierces a face is outside too.
                outside_tile += 1;
                continue;
            }
            let clipped = !(inside.is_empty() || inside[a] && inside[b]);
            let back = e.class != EdgeClass::Boundary
                && !turned.is_empty()
                && e.triangles.iter().all(|&t| turned[t as usize]);
            self.lines.push(Line {
                a: mesh.vertices()[a],
                b: mesh.vertices()[b],
                ends: [pictures[a], pictures[b]],
                class: e.class,
                meet: None,
                back,
                triangles: Some(e.triangles),
                wide: !(in_front(a) && in_front(b)),
                clipped,
                leaf: n as u32,
                vertices: [e.a, e.b],
                id: LineId::Edge(global, k as u32),
            });
            if clipped {
                let i = self.lines.len() - 1;
                self.cuts
                    .extend(frustum_cuts(clip, tile, eye, (i, &self.lines[i], None)));
            }
        }
        let leaf = &mut self.leaves[n];
        leaf.pictures = pictures;
        leaf.front = front;
        leaf.lines = first..self.lines.len();
        leaf.turned = turned;
        (behind, outside_tile)
    }

    /// What stage 1 did and what it left out, for `--stats`: the edges by class, and the
    /// edges and objects skipped (`behind` the eye, `outside_tile`).
    fn edges_report(
        &self,
        total: &EdgeCounts,
        selection: EdgeSelection,
        behind: usize,
        outside_tile: usize,
    ) -> (String, String) {
        let count = |c: EdgeClass| total.by_class[c as usize];
        let done = format!(
            "{} objects: {} silhouette, {} boundary, {} crease, {} smooth edges",
            self.leaves.len(),
            count(EdgeClass::Silhouette),
            count(EdgeClass::Boundary),
            count(EdgeClass::Crease),
            count(EdgeClass::Smooth)
        );
        let smooth = match (total.left_out, selection) {
            (0, _) => String::new(),
            (n, EdgeSelection::Feature) => {
                format!(", {n} smooth edges not asked for (--edges all draws them)")
            }
            (n, EdgeSelection::All) => {
                format!(", {n} smooth diagonals of split polygons (not polygon edges)")
            }
            (n, EdgeSelection::Mesh) => {
                format!(", {n} diagonals of split polygons (not polygon edges)")
            }
        };
        let clipping = if self.clip.is_some() {
            format!(
                ", {behind} behind the eye (the view clips to its frustum: part of the scene \
                 is not in front of the eye)"
            )
        } else {
            String::new()
        };
        let copies = match self.copies {
            0 => String::new(),
            n => format!(", {n} objects that are exact copies of another (drawn once)"),
        };
        let tiled = match &self.tile {
            Some(_) => format!(
                ", {} objects and {outside_tile} edges outside the tile",
                self.outside_tile
            ),
            None => String::new(),
        };
        let (flat, end_on) = (total.flat, total.end_on);
        let skipped = format!(
            "{flat} edges between coplanar faces (no edge), {end_on} seen end-on (a point)\
             {smooth}{clipping}{copies}{tiled}"
        );
        (done, skipped)
    }
}
