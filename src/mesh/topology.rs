//! Edge structure of a mesh: whether it is closed and consistently oriented, and where faces
//! meet in T-junctions.

use super::face::Face;
use crate::geometry::Point3;
use crate::geometry::predicates::collinear;
use rstar::primitives::GeomWithData;
use rstar::{AABB, RTree};

/// How the faces of a mesh fit together along their edges.
///
/// A mesh is *closed* when every edge is shared by exactly two faces, and *consistently
/// oriented* when no edge is traversed twice in the same direction (for a closed mesh: every
/// edge once in each direction). Only a closed, consistently oriented mesh bounds a solid
/// with an inside, and only such a mesh gets an INBOX.
///
/// ```
/// let t = kepler::solids::cube(1.0).unwrap().topology();
/// assert!(t.closed && t.consistently_oriented);
/// assert_eq!((t.edges, t.boundary_edges, t.nonmanifold_edges), (12, 0, 0));
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
pub struct Topology {
    /// Number of distinct (undirected) edges.
    pub edges: usize,
    /// Edges used by one face only.
    pub boundary_edges: usize,
    /// Edges used by more than two faces.
    pub nonmanifold_edges: usize,
    /// Edges used by an odd number of faces (boundary edges included). With none, every
    /// vertical ray crosses the faces an even number of times, so the mesh has an inside for
    /// ray parity even where solids touch along an edge (four faces on it).
    pub odd_edges: usize,
    /// Edges traversed twice in the same direction by two faces.
    pub misoriented_edges: usize,
    /// Every edge is shared by exactly two faces.
    pub closed: bool,
    /// No edge is traversed twice in the same direction.
    pub consistently_oriented: bool,
}

impl Topology {
    /// Analyses the edges of the given faces (vertex index loops).
    ///
    /// ```
    /// use kepler::mesh::Topology;
    /// // Two triangles sharing an edge in opposite directions: open but consistent.
    /// let t = Topology::of_faces([&[0u32, 1, 2][..], &[2, 1, 3][..]]);
    /// assert_eq!((t.edges, t.boundary_edges), (5, 4));
    /// assert!(!t.closed && t.consistently_oriented);
    /// ```
    pub fn of_faces<'a>(faces: impl IntoIterator<Item = &'a [u32]>) -> Topology {
        let mut uses = Vec::new();
        for f in faces {
            for (i, &a) in f.iter().enumerate() {
                uses.push(edge_use(a, f[(i + 1) % f.len()], 0));
            }
        }
        Topology::of_uses(uses)
    }

    /// The topology of a mesh's faces, each side cut into pieces at its T-junctions.
    pub(crate) fn of_mesh_faces(faces: &[Face], junctions: &[Junction]) -> Topology {
        let mut uses = Vec::new();
        let mut cut = junctions.iter().peekable();
        for (fi, f) in faces.iter().enumerate() {
            let v = f.vertices();
            for (i, &a) in v.iter().enumerate() {
                let b = v[(i + 1) % v.len()];
                match cut.next_if(|j| (j.face as usize, j.side as usize) == (fi, i)) {
                    Some(j) => uses.extend(pieces(a, b, &j.inner).map(|(p, q)| edge_use(p, q, 0))),
                    None => uses.push(edge_use(a, b, 0)),
                }
            }
        }
        Topology::of_uses(uses)
    }

    /// The topology of the edge uses ([`edge_use`]).
    fn of_uses(mut uses: Vec<(u64, u32)>) -> Topology {
        sort(&mut uses);
        Topology::of_sorted_uses(&uses)
    }

    /// The topology of sorted edge uses (only their keys and direction bits count).
    fn of_sorted_uses(uses: &[(u64, u32)]) -> Topology {
        let mut t = Topology {
            edges: 0,
            boundary_edges: 0,
            nonmanifold_edges: 0,
            odd_edges: 0,
            misoriented_edges: 0,
            closed: false,
            consistently_oriented: false,
        };
        for group in uses.chunk_by(|x, y| x.0 == y.0) {
            t.edges += 1;
            let forward = group.iter().filter(|u| u.1 & 1 == 1).count();
            match group.len() {
                1 => t.boundary_edges += 1,
                2 => {}
                _ => t.nonmanifold_edges += 1,
            }
            if group.len() % 2 == 1 {
                t.odd_edges += 1;
            }
            if forward > 1 || group.len() - forward > 1 {
                t.misoriented_edges += 1;
            }
        }
        t.closed = t.edges > 0 && t.boundary_edges == 0 && t.nonmanifold_edges == 0;
        t.consistently_oriented = t.misoriented_edges == 0;
        t
    }
}

/// Sorts edge uses ([`edge_use`]): their indices grow in the order they are made, so the
/// stable sort by key is the sort of the pairs.
fn sort(uses: &mut Vec<(u64, u32)>) {
    sort_by_edge(uses, |u| u.0);
}

/// Sorts items by an edge key `(lower vertex << 32) | higher vertex`, stably: by their lower
/// vertex in one counting pass (linear in the items and the vertices), then each vertex's few
/// items by key. The result is that of a stable comparison sort, which costs several times
/// more on a large mesh (and in parallel, more than the counting pass alone).
pub(crate) fn sort_by_edge<T: Copy + Send + Sync>(
    items: &mut Vec<T>,
    key: impl Fn(&T) -> u64 + Sync,
) {
    use rayon::prelude::*;
    let lower = |u: &T| (key(u) >> 32) as usize;
    let Some(vertices) = items.iter().map(lower).max().map(|m| m + 1) else {
        return;
    };
    if items.len() < 64 || vertices > 4 * items.len() {
        items.sort_by_key(&key);
        return;
    }
    let (start, mut sorted) = super::by_bucket(vertices, items, lower, |u| *u);
    // Each vertex's few items by key, in blocks of vertices in parallel.
    let mut blocks = Vec::new();
    let mut rest = &mut sorted[..];
    for first in (0..vertices).step_by(VERTEX_BLOCK) {
        let last = (first + VERTEX_BLOCK).min(vertices);
        let (here, after) = rest.split_at_mut(start[last] - start[first]);
        blocks.push((first..last, here));
        rest = after;
    }
    blocks.into_par_iter().for_each(|(range, block)| {
        let base = start[range.start];
        for v in range {
            block[start[v] - base..start[v + 1] - base].sort_by_key(&key);
        }
    });
    *items = sorted;
}

/// Vertices whose items [`sort_by_edge`] sorts as one parallel task.
const VERTEX_BLOCK: usize = 1 << 14;

/// A use of the edge from `a` to `b` by side `index` of the mesh's faces: the undirected key
/// (low vertex, high vertex) and the index with the direction in its low bit (1 when `a < b`).
fn edge_use(a: u32, b: u32, index: u32) -> (u64, u32) {
    (
        u64::from(a.min(b)) << 32 | u64::from(a.max(b)),
        index << 1 | u32::from(a < b),
    )
}

/// The pieces of the side from `a` to `b` cut at the vertices `inner` (in order from `a`).
pub(crate) fn pieces(a: u32, b: u32, inner: &[u32]) -> impl Iterator<Item = (u32, u32)> + '_ {
    let ends = std::iter::once(a).chain(inner.iter().copied());
    ends.clone()
        .zip(inner.iter().copied().chain(std::iter::once(b)))
}

/// A side of a face with vertices of the mesh lying exactly inside it (a T-junction): side
/// `side` of face `face` runs from its vertex `side` to the next, through `inner` in order.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Junction {
    pub face: u32,
    pub side: u32,
    pub inner: Vec<u32>,
}

/// The T-junctions of the faces ([`junctions_and_uses`]) and the topology of the faces cut
/// at them: for a mesh without T-junctions (most), from the same sorted sides.
pub(crate) fn junctions_and_topology(
    vertices: &[Point3],
    faces: &[Face],
) -> (Vec<Junction>, Topology) {
    let (junctions, uses) = junctions_and_uses(vertices, faces);
    let topology = if junctions.is_empty() {
        Topology::of_sorted_uses(&uses)
    } else {
        Topology::of_mesh_faces(faces, &junctions)
    };
    (junctions, topology)
}

/// The T-junctions of the faces, by face and side: where a side used by one face only has
/// vertices exactly inside it that are ends of such sides too (the sides that cover it from the
/// other face). Only unmatched sides are searched, their candidate vertices in an R-tree, so
/// a mesh without them costs one sort of its sides.
/// Returns them with the faces' sides as sorted edge uses.
fn junctions_and_uses(vertices: &[Point3], faces: &[Face]) -> (Vec<Junction>, Vec<(u64, u32)>) {
    let mut first_use = Vec::with_capacity(faces.len() + 1);
    let mut uses = Vec::new();
    for f in faces {
        first_use.push(uses.len());
        let v = f.vertices();
        for (i, &a) in v.iter().enumerate() {
            uses.push(edge_use(a, v[(i + 1) % v.len()], uses.len() as u32));
        }
    }
    sort(&mut uses);
    let side_of = |u: u32| {
        let u = (u >> 1) as usize;
        let f = first_use.partition_point(|&first| first <= u) - 1;
        let v = faces[f].vertices();
        let i = u - first_use[f];
        (f, i, v[i], v[(i + 1) % v.len()])
    };
    let unmatched: Vec<_> = uses
        .chunk_by(|x, y| x.0 == y.0)
        .filter(|group| group.len() == 1)
        .map(|group| side_of(group[0].1))
        .collect();
    if unmatched.is_empty() {
        return (Vec::new(), uses);
    }
    let mut candidates: Vec<u32> = unmatched.iter().flat_map(|s| [s.2, s.3]).collect();
    candidates.sort_unstable();
    candidates.dedup();
    let tree = RTree::bulk_load(
        candidates
            .iter()
            .map(|&c| GeomWithData::<[f64; 3], u32>::new(vertices[c as usize].into(), c))
            .collect(),
    );
    let mut found: Vec<Junction> = unmatched
        .iter()
        .filter_map(|&(f, i, a, b)| {
            let (pa, pb) = (&vertices[a as usize], &vertices[b as usize]);
            let envelope = AABB::from_corners(pa.inf(pb).into(), pa.sup(pb).into());
            let mut inner: Vec<u32> = tree
                .locate_in_envelope(&envelope)
                .map(|c| c.data)
                .filter(|&c| c != a && c != b && collinear(pa, pb, &vertices[c as usize]))
                .collect();
            if inner.is_empty() {
                return None;
            }
            // Along the segment, a coordinate in which its ends differ is strictly monotonic
            // (its points are exactly collinear).
            let k = (0..3).find(|&k| pa[k] != pb[k]).unwrap_or(0);
            inner.sort_unstable_by(|&c, &d| {
                let order = vertices[c as usize][k].total_cmp(&vertices[d as usize][k]);
                if pa[k] < pb[k] {
                    order
                } else {
                    order.reverse()
                }
            });
            Some(Junction {
                face: f as u32,
                side: i as u32,
                inner,
            })
        })
        .collect();
    found.sort_unstable_by_key(|j| (j.face, j.side));
    (found, uses)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::random::SplitMix64;

    /// The counting sort gives the stable comparison sort's order: on uses of few and of many
    /// vertices, with repeated keys (an edge used by several faces) in any input order.
    #[test]
    fn sorting_uses_by_lower_vertex_first_is_a_stable_sort() {
        let mut rng = SplitMix64(0x2545_f491_4f6c_dd1d);
        let mut below = |n: u64| rng.next_u64() % n;
        for (len, vertices) in [
            (0, 1),
            (10, 3),
            (100, 5),
            (1000, 40),
            (5000, 3000),
            (300, 5000),
            // Many: placed in parallel, and sorted in several blocks of vertices.
            (200_000, 3 * VERTEX_BLOCK as u64 + 5),
        ] {
            let mut uses: Vec<(u64, u32)> = (0..len)
                .map(|i| {
                    let (a, b) = (below(vertices) as u32, below(vertices) as u32);
                    edge_use(a, b, if i % 7 == 0 { 0 } else { below(1 << 20) as u32 })
                })
                .collect();
            let mut expected = uses.clone();
            expected.sort_by_key(|u| u.0);
            sort(&mut uses);
            assert_eq!(uses, expected, "{len} uses of {vertices} vertices");
        }
    }
}
