//! Merging the cells into polygons: along each line the cells' edges are cut where their
//! endpoints fall; a piece of line with a cell on exactly one side is boundary, one with cells
//! on both sides joins them. The boundary's rings ([`super::rings`]) are grouped by connected
//! cells into polygons, and each vertex is constructed once from the input.

use super::rings::BoundaryPiece;
use super::signs::{form, times};
use super::{At, Vertex, Vtp};
use crate::geometry::kernel::Polynomial;
use crate::mesh::TextureFrame;
use crate::sight::along::{cut_point, cut_point_on_plane};
use crate::surfaces::lines::{self, Kind, Turn};
use crate::union_find::UnionFind;
use geo::{Coord, LineString, MultiPolygon, Polygon};
use std::cmp::Ordering;
use std::collections::HashMap;

impl<'a> Vtp<'a> {
    /// The visible polygons, in the picture and in the texture coordinates `texture`: outer
    /// rings counter-clockwise in the picture, holes clockwise; each outer ring starts at the
    /// vertex before its leftmost (lowest) one, each hole at its leftmost; polygons and holes
    /// in the order of their leftmost vertices (the conventions of [`crate::clip`]).
    pub(in crate::surfaces) fn polygons(
        mut self,
        texture: &TextureFrame,
        eye_side: Ordering,
    ) -> (MultiPolygon<f64>, MultiPolygon<f64>) {
        let merged = self.merge();
        let mut points: HashMap<u32, ([f64; 2], [f64; 2])> = HashMap::new();
        for (outer, holes) in &merged.polygons {
            for &v in outer.iter().chain(holes.iter().flatten()) {
                if let std::collections::hash_map::Entry::Vacant(e) = points.entry(v) {
                    e.insert(self.construct(&merged.classes[&v], texture));
                }
            }
        }
        // Rings in the picture: reversed when the eye sees F's plane from its negative side.
        let ring = |r: &Vec<u32>| -> Vec<([f64; 2], [f64; 2])> {
            let mut out: Vec<_> = r.iter().map(|v| points[v]).collect();
            if eye_side == Ordering::Less {
                out.reverse();
            }
            out
        };
        type Ring = Vec<([f64; 2], [f64; 2])>;
        let mut built: Vec<(Ring, Vec<Ring>)> = merged
            .polygons
            .iter()
            .map(|(outer, holes)| {
                let mut outer = ring(outer);
                rotate(&mut outer, 1);
                let mut holes: Vec<Ring> = holes.iter().map(ring).collect();
                for h in &mut holes {
                    rotate(h, 0);
                }
                holes.sort_by(|a, b| leftmost(a).total_cmp2(&leftmost(b)));
                (outer, holes)
            })
            .collect();
        built.sort_by(|a, b| leftmost(&a.0).total_cmp2(&leftmost(&b.0)));
        let polygon = |k: usize| -> MultiPolygon<f64> {
            built
                .iter()
                .map(|(outer, holes)| {
                    let ring = |r: &Ring| -> LineString<f64> {
                        r.iter()
                            .map(|p| {
                                let [x, y] = if k == 0 { p.0 } else { p.1 };
                                Coord { x, y }
                            })
                            .collect()
                    };
                    Polygon::new(ring(outer), holes.iter().map(ring).collect())
                })
                .collect()
        };
        (polygon(0), polygon(1))
    }

    /// The picture and texture coordinates of a point, from the vertices that are it: the
    /// picture of an input point, else the cut of an edge, else the point of three planes.
    pub(super) fn construct(&self, class: &[u32], texture: &TextureFrame) -> ([f64; 2], [f64; 2]) {
        let eye = &self.frame.eye;
        let vertices: Vec<&Vertex> = class.iter().map(|&v| &self.vertices[v as usize]).collect();
        let general = |v: &Vertex| {
            lines::construct(
                &self.frame,
                &self.lines[v.lines[0] as usize],
                &self.lines[v.lines[1] as usize],
                self.picture,
                texture,
            )
        };
        for v in &vertices {
            if let At::Input(p, on_plane) = v.at {
                let uv = if on_plane {
                    lines::texture_of(texture, &p)
                } else {
                    lines::texture_on_sight_line(texture, &self.frame, &p)
                };
                return (self.picture.point(&p), uv);
            }
        }
        for v in &vertices {
            if let At::Cut(a, b, m, _) = v.at {
                let xy = match m {
                    Kind::Plane(t) if t == self.frame.plane => {
                        cut_point_on_plane(self.picture, eye, &t, &a, &b)
                    }
                    _ => cut_point(self.picture, eye, &form(&m), &a, &b),
                };
                return (xy, lines::texture_of_cut(texture, eye, &m, &a, &b));
            }
        }
        general(vertices[0])
    }

    /// The boundary of the union of the cells, as polygons of vertex ids (each standing for its
    /// class of equal points), outer rings counter-clockwise seen from the side F's plane's
    /// gradient points to.
    pub(super) fn merge(&mut self) -> Merged {
        let mut points = UnionFind::new(self.vertices.len());
        let mut components = UnionFind::new(self.cells.len());
        let by_line = self.edges_by_line();
        let mut line_ids: Vec<u32> = by_line.keys().copied().collect();
        line_ids.sort_unstable();
        // Boundary pieces: (from, to, line, direction along q_L, cell on the left).
        let mut pieces: Vec<BoundaryPiece> = Vec::new();
        for l in line_ids {
            self.cut_line(l, &by_line[&l], &mut points, &mut components, &mut pieces);
        }
        for p in &mut pieces {
            p.from = points.find(p.from as usize) as u32;
            p.to = points.find(p.to as usize) as u32;
        }
        let rings = self.link(&pieces);
        let polygons = self.group_rings(rings, &pieces, &mut components);
        let mut classes: HashMap<u32, Vec<u32>> = HashMap::new();
        for v in 0..self.vertices.len() {
            classes
                .entry(points.find(v) as u32)
                .or_default()
                .push(v as u32);
        }
        Merged { polygons, classes }
    }

    /// The cells' edges by line.
    fn edges_by_line(&self) -> HashMap<u32, Vec<Edge>> {
        let mut by_line: HashMap<u32, Vec<Edge>> = HashMap::new();
        for (c, cell) in self.cells.iter().enumerate() {
            let n = cell.v.len();
            for i in 0..n {
                let (l, side) = cell.e[i];
                by_line
                    .entry(l)
                    .or_default()
                    .push((cell.v[i], cell.v[(i + 1) % n], side, c));
            }
        }
        by_line
    }

    /// Cuts line `l` where the endpoints of its `edges` fall: equal points go to one class of
    /// `points`, the cells on both sides of an interval to one class of `components`, and each
    /// interval with a cell on one side only is a boundary piece, pushed to `pieces` with that
    /// cell on its left.
    fn cut_line(
        &mut self,
        l: u32,
        edges: &[Edge],
        points: &mut UnionFind,
        components: &mut UnionFind,
        pieces: &mut Vec<BoundaryPiece>,
    ) {
        let mut ends: Vec<u32> = edges.iter().flat_map(|e| [e.0, e.1]).collect();
        ends.sort_unstable();
        ends.dedup();
        ends.sort_by(|&u, &v| self.along(l, u, v));
        // Positions of the distinct points along the line.
        let mut position: HashMap<u32, usize> = HashMap::new();
        let mut at: Vec<u32> = Vec::new();
        for (i, &v) in ends.iter().enumerate() {
            if i > 0 && self.along(l, ends[i - 1], v) == Ordering::Equal {
                points.union_least(ends[i - 1] as usize, v as usize);
            } else {
                at.push(v);
            }
            position.insert(v, at.len() - 1);
        }
        let intervals = at.len().saturating_sub(1);
        let mut cover: [Vec<Option<usize>>; 2] = [vec![None; intervals], vec![None; intervals]];
        for &(u, v, side, c) in edges {
            let (pu, pv) = (position[&u], position[&v]);
            let s = usize::from(side == Ordering::Less);
            for slot in &mut cover[s][pu.min(pv)..pu.max(pv)] {
                *slot = Some(c);
            }
        }
        for j in 0..intervals {
            match (cover[0][j], cover[1][j]) {
                (Some(a), Some(b)) => components.union_least(a, b),
                // The cell on the positive side: walk against q_L, keeping it on the left.
                (Some(c), None) => pieces.push(BoundaryPiece {
                    from: at[j + 1],
                    to: at[j],
                    line: l,
                    forward: false,
                    cell: c,
                }),
                (None, Some(c)) => pieces.push(BoundaryPiece {
                    from: at[j],
                    to: at[j + 1],
                    line: l,
                    forward: true,
                    cell: c,
                }),
                (None, None) => {}
            }
        }
    }

    /// The rings as polygons of vertex ids, grouped by connected cells (`components`): each
    /// group's counter-clockwise ring is its outer ring, its clockwise rings its holes; groups
    /// in the order of their first ring.
    fn group_rings(
        &self,
        rings: Vec<Vec<usize>>,
        pieces: &[BoundaryPiece],
        components: &mut UnionFind,
    ) -> Vec<(VertexRing, Vec<VertexRing>)> {
        let mut groups: HashMap<usize, (Vec<VertexRing>, Vec<VertexRing>)> = HashMap::new();
        let mut order: Vec<usize> = Vec::new();
        for ring in rings {
            let group = components.find(pieces[ring[0]].cell);
            let entry = groups.entry(group).or_insert_with(|| {
                order.push(group);
                (Vec::new(), Vec::new())
            });
            let outer = self.turning(pieces, &ring) > 0.0;
            let vertices = ring.iter().map(|&p| pieces[p].from).collect();
            if outer {
                entry.0.push(vertices);
            } else {
                entry.1.push(vertices);
            }
        }
        let mut polygons = Vec::new();
        for g in order {
            let (outers, holes) = groups.remove(&g).unwrap_or_default();
            let mut outers = outers.into_iter();
            if let Some(first) = outers.next() {
                polygons.push((first, holes));
            }
            polygons.extend(outers.map(|o| (o, Vec::new())));
        }
        polygons
    }

    /// The order of vertices `u` and `v` of line `l` along its direction `q_L`.
    pub(super) fn along(&mut self, l: u32, u: u32, v: u32) -> Ordering {
        if u == v {
            return Ordering::Equal;
        }
        let [a, b] = self.vertices[u as usize].lines;
        let m = if a == l { b } else { a };
        let s = self.sign_at(v, m);
        if s == Ordering::Equal {
            return Ordering::Equal;
        }
        // s_M grows along q_L as det(g_F, g_L, g_M) = W(L, M).
        let turn = self.turn(l, m);
        times(s, turn).reverse()
    }

    /// The exact sign of `W` for lines `a` and `b`.
    pub(super) fn turn(&self, a: u32, b: u32) -> Ordering {
        if a == b {
            return Ordering::Equal;
        }
        Turn {
            frame: &self.frame,
            a: &self.lines[a as usize],
            b: &self.lines[b as usize],
        }
        .sign()
    }
}

/// A cell's edge on a line: its ends, the side of the line the cell is on, and the cell.
pub(super) type Edge = (u32, u32, Ordering, usize);

/// A ring of vertex ids.
pub(super) type VertexRing = Vec<u32>;

/// What [`Vtp::merge`] finds: polygons of point classes and the classes' vertices.
pub(super) struct Merged {
    pub(super) polygons: Vec<(Vec<u32>, Vec<Vec<u32>>)>,
    pub(super) classes: HashMap<u32, Vec<u32>>,
}

/// The ring rotated so that its leftmost (then lowest) picture point comes at index `at`.
pub(super) fn rotate(ring: &mut [([f64; 2], [f64; 2])], at: usize) {
    if ring.is_empty() {
        return;
    }
    let n = ring.len();
    let i = (0..n)
        .min_by(|&a, &b| ring[a].0.total_cmp2(&ring[b].0))
        .unwrap_or(0);
    ring.rotate_left((i + n - at) % n);
}

/// The leftmost (then lowest) picture point of a ring.
pub(super) fn leftmost(ring: &[([f64; 2], [f64; 2])]) -> [f64; 2] {
    ring.iter()
        .map(|p| p.0)
        .min_by(|a, b| a.total_cmp2(b))
        .unwrap_or([0.0; 2])
}

/// Lexicographic total order on points.
pub(super) trait TotalCmp2 {
    fn total_cmp2(&self, other: &Self) -> Ordering;
}

impl TotalCmp2 for [f64; 2] {
    fn total_cmp2(&self, other: &[f64; 2]) -> Ordering {
        self[0]
            .total_cmp(&other[0])
            .then(self[1].total_cmp(&other[1]))
    }
}
