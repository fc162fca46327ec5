//! The second, simple method that finds a mesh's silhouette and boundary edges for check 2
//! (see `contours.rs`): the side of the eye each triangle along an edge is turned to, with
//! the sides cut at T-junctions as the pass cuts them.

use super::super::EdgeClass;
use crate::geometry::Point3;
use crate::mesh::Mesh;
use crate::union_find::UnionFind;
use crate::views::Eye;
use std::cmp::Ordering;
use std::collections::HashMap;

/// The bits of an unordered pair of points, to match an edge with the pieces on it.
pub(super) type EdgeKey = [[u64; 3]; 2];

/// The bits of a point's coordinates (`-0.0` and `0.0` made equal).
pub(super) fn point_key(p: &Point3) -> [u64; 3] {
    [p.x, p.y, p.z].map(|v| (v + 0.0).to_bits())
}

/// A silhouette or boundary edge found by the sign test: a side of a triangle, or a piece of
/// one between consecutive vertices lying on it (at T-junctions).
pub(super) struct Contour {
    pub(super) vertices: [u32; 2],
    pub(super) class: EdgeClass,
    /// The chain (see [`Chains`]) it is a piece of, for a piece of a side with T-junctions.
    pub(super) chain: Option<usize>,
}

/// What the sign test found in a mesh.
pub(super) struct Contours {
    /// The silhouette and boundary edges.
    pub(super) contours: Vec<Contour>,
    /// The sides with T-junctions the contours lie on.
    pub(super) chains: Chains,
    /// The number of edges it does not decide.
    pub(super) unchecked: usize,
}

/// The sides of a mesh's triangles that have T-junctions, joined into chains where they share
/// a piece (so lie on one line): each chain's vertices in order along the line. A line of the
/// drawing along a side with T-junctions (its pieces joined, as the pass joins them) runs
/// between two vertices of one chain.
#[derive(Debug, Default)]
pub(super) struct Chains {
    /// Each chain's vertices, in order along it.
    pub(super) points: Vec<Vec<u32>>,
    /// For each vertex on a chain, the chains it lies on and its position on each.
    pub(super) at: HashMap<u32, Vec<(usize, usize)>>,
}

/// For each chain, for each segment between consecutive vertices of it, the lines of the
/// drawing (by their ends) that run along it.
pub(super) type Cover = Vec<Vec<Vec<EdgeKey>>>;

impl Chains {
    /// The chains of the sides `long` (each its vertices in order along it), of which those
    /// in one of the disjoint `sets` share pieces; and the chain
    /// of each side.
    pub(super) fn new(
        vertices: &[Point3],
        long: &[Vec<u32>],
        sets: &mut UnionFind,
    ) -> (Chains, Vec<usize>) {
        let mut chains = Chains::default();
        let mut of_root: HashMap<usize, usize> = HashMap::new();
        let mut chain_of = Vec::with_capacity(long.len());
        for (id, side) in long.iter().enumerate() {
            let r = sets.find(id);
            let c = *of_root.entry(r).or_insert_with(|| {
                chains.points.push(Vec::new());
                chains.points.len() - 1
            });
            chains.points[c].extend(side);
            chain_of.push(c);
        }
        let point = |v: u32| vertices.get(v as usize).copied().unwrap_or_default();
        for (c, points) in chains.points.iter_mut().enumerate() {
            // Exactly collinear, so in order along a coordinate in which two of them differ
            // (the first two: consecutive on a side).
            let (p, q) = (points.first(), points.get(1));
            let (p, q) = (
                point(p.copied().unwrap_or(0)),
                point(q.copied().unwrap_or(0)),
            );
            let k = (0..3).find(|&k| p[k] != q[k]).unwrap_or(0);
            points.sort_by(|&x, &y| point(x)[k].total_cmp(&point(y)[k]).then(x.cmp(&y)));
            points.dedup();
            for (i, &w) in points.iter().enumerate() {
                chains.at.entry(w).or_default().push((c, i));
            }
        }
        (chains, chain_of)
    }

    /// The position of vertex `v` on chain `c`.
    pub(super) fn position(&self, c: usize, v: u32) -> Option<usize> {
        let on = self.at.get(&v)?;
        on.iter().find(|x| x.0 == c).map(|x| x.1)
    }

    /// Which of the `lines` of the drawing (by their ends: vertices of `mesh`) run along which
    /// segments of the chains.
    pub(super) fn covering(&self, mesh: &Mesh, lines: &[EdgeKey]) -> Cover {
        let mut cover: Cover = self
            .points
            .iter()
            .map(|p| vec![Vec::new(); p.len().saturating_sub(1)])
            .collect();
        if self.points.is_empty() {
            return cover;
        }
        let vertex: HashMap<[u64; 3], u32> = self
            .at
            .keys()
            .filter_map(|&v| Some((point_key(mesh.vertices().get(v as usize)?), v)))
            .collect();
        for key in lines {
            let (Some(&a), Some(&b)) = (vertex.get(&key[0]), vertex.get(&key[1])) else {
                continue;
            };
            for &(c, i) in self.at.get(&a).into_iter().flatten() {
                if let Some(j) = self.position(c, b) {
                    for segment in cover[c].iter_mut().take(i.max(j)).skip(i.min(j)) {
                        segment.push(*key);
                    }
                }
            }
        }
        cover
    }

    /// The segments of chain `c` between consecutive vertices that make up the piece between
    /// vertices `ends`, each with the lines of the drawing that run along it.
    pub(super) fn between<'a>(
        &self,
        c: usize,
        ends: [u32; 2],
        cover: &'a Cover,
    ) -> Vec<([u32; 2], &'a [EdgeKey])> {
        let (Some(i), Some(j), Some(points), Some(lines)) = (
            self.position(c, ends[0]),
            self.position(c, ends[1]),
            self.points.get(c),
            cover.get(c),
        ) else {
            return vec![(ends, &[])];
        };
        (i.min(j)..i.max(j))
            .map(|k| {
                let w = [points[k], points[k + 1]];
                let w = if w == [ends[1], ends[0]] { ends } else { w };
                (w, lines.get(k).map(Vec::as_slice).unwrap_or_default())
            })
            .collect()
    }
}

/// A side of a triangle, or a piece of one between consecutive vertices lying on it (at
/// T-junctions): the edge (lower, higher vertex), the triangle, whether the triangle runs along
/// the edge from lower to higher, and the index of the side with T-junctions it is a piece of
/// ([`WHOLE`] for a whole side).
type SidePiece = ([u32; 2], usize, bool, usize);

/// The [`SidePiece`] of a whole side.
const WHOLE: usize = usize::MAX;

/// A mesh's face sides with T-junctions, by face and (lower, higher) end: each side's first
/// vertex and the vertices inside it, in order from there.
type Junctions<'a> = HashMap<(usize, [u32; 2]), (u32, &'a [u32])>;

/// An edge's vertices, lower first.
fn ordered(p: u32, q: u32) -> [u32; 2] {
    [p.min(q), p.max(q)]
}

/// Each face's sides with T-junctions: the side's first vertex and those inside it, in order
/// from there.
fn face_junctions(mesh: &Mesh) -> Junctions<'_> {
    let mut junctions: Junctions = HashMap::new();
    if mesh.t_junctions() > 0 {
        for (f, face) in mesh.faces().iter().enumerate() {
            let v = face.vertices();
            for i in 0..v.len() {
                if let Some(inner) = mesh.side_junctions(f, i) {
                    junctions.insert((f, ordered(v[i], v[(i + 1) % v.len()])), (v[i], inner));
                }
            }
        }
    }
    junctions
}

/// Each triangle's sides, cut at T-junctions (see [`SidePiece`]), and each side with them
/// (its vertices in order, in the triangle's direction).
fn side_pieces(mesh: &Mesh, junctions: &Junctions) -> (Vec<Vec<u32>>, Vec<SidePiece>) {
    let triangles = mesh.triangles();
    let mut long: Vec<Vec<u32>> = Vec::new();
    let mut sides: Vec<SidePiece> = Vec::with_capacity(3 * triangles.len());
    for (f, face) in mesh.faces().iter().enumerate() {
        for t in face.triangle_range() {
            let Some(tri) = triangles.get(t) else {
                continue;
            };
            for k in 0..3 {
                let (p, q) = (tri[k], tri[(k + 1) % 3]);
                let Some(&(from, inner)) = junctions.get(&(f, ordered(p, q))) else {
                    sides.push((ordered(p, q), t, p < q, WHOLE));
                    continue;
                };
                let to = if from == p { q } else { p };
                let mut on: Vec<u32> = std::iter::once(from)
                    .chain(inner.iter().copied())
                    .chain(std::iter::once(to))
                    .collect();
                // In the triangle's direction, from p to q.
                if from != p {
                    on.reverse();
                }
                for w in on.windows(2) {
                    sides.push((ordered(w[0], w[1]), t, w[0] < w[1], long.len()));
                }
                long.push(on);
            }
        }
    }
    (long, sides)
}

/// The silhouette and boundary edges of `mesh` by the sign test (see the module
/// documentation), and the number of edges it does not decide. A side with vertices of the
/// mesh lying exactly inside it (a T-junction) is cut there, as the pass cuts it
/// ([`Mesh::side_junctions`]): the pieces between consecutive vertices on it are matched, across
/// triangles, with the sides or pieces that cover them, and each is tested as an edge.
pub(super) fn contour_edges(mesh: &Mesh, eye: &Eye) -> Contours {
    let junctions = face_junctions(mesh);
    let (long, mut sides) = side_pieces(mesh, &junctions);
    sides.sort_unstable();
    let groups: Vec<&[SidePiece]> = sides.chunk_by(|x, y| x.0 == y.0).collect();
    // Sides with T-junctions that share a piece lie on one line: one chain.
    let mut sets = UnionFind::new(long.len());
    for group in &groups {
        let mut ids = group.iter().map(|s| s.3).filter(|&id| id != WHOLE);
        if let Some(first) = ids.next() {
            for id in ids {
                sets.union(first, id);
            }
        }
    }
    let vertices = mesh.vertices();
    let mut contours = Vec::new();
    let mut unchecked = 0;
    for group in groups {
        let edge = group[0].0;
        let (a, b) = (&vertices[edge[0] as usize], &vertices[edge[1] as usize]);
        // The triangle's side of the eye, as if it ran from lower to higher.
        let facing = |&(_, t, forward, _): &SidePiece| {
            let [p, q, r] = mesh.triangle(t);
            let s = eye.orient3d(&p, &q, &r);
            if forward { s } else { s.reverse() }
        };
        let class = match group {
            [_] if eye.sees_end_on(a, b) => None,
            [_] => Some(EdgeClass::Boundary),
            // A diagonal of a face's triangulation: not an edge.
            [x, y] if mesh.face_of(x.1) == mesh.face_of(y.1) => continue,
            [x, y] => {
                let (fx, fy) = (facing(x), facing(y));
                let edge_on = [fx, fy].iter().filter(|&&f| f == Ordering::Equal).count();
                if eye.sees_end_on(a, b) || edge_on == 2 {
                    None
                } else if fx == fy || edge_on == 1 {
                    // Made to run the same way along the edge, their sides agree: with the
                    // triangles oriented alike (one runs the edge the other way), one is
                    // turned towards the eye and the other away. Or one is seen edge-on, and
                    // the surface seen ends at the edge.
                    Some(EdgeClass::Silhouette)
                } else {
                    continue;
                }
            }
            _ => None,
        };
        match class {
            Some(class) => contours.push(Contour {
                vertices: edge,
                class,
                // For now the side with T-junctions it is a piece of.
                chain: group.iter().find(|s| s.3 != WHOLE).map(|s| s.3),
            }),
            None => unchecked += 1,
        }
    }
    let (chains, chain_of) = Chains::new(vertices, &long, &mut sets);
    for c in &mut contours {
        c.chain = c.chain.and_then(|id| chain_of.get(id).copied());
    }
    Contours {
        contours,
        chains,
        unchecked,
    }
}
