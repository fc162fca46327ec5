//! The hierarchy and its bottom-up construction.
//!
//! "We proceed in a 'bottom-up' fashion, starting at the leaves and combining pairs of
//! 'neighboring' boxes." The paper builds its planar boxtree level by level: "we pick a
//! maximal set of disjoint rectangle pairs [...] We now replace the chosen pairs by their
//! enclosing boxes and iterate on this process recursively", and in 3-D picks pairs by "the
//! minimum-area (volume) enclosing box", concluding that "area (or volume) criteria are the
//! most important factors". So each round here:
//!
//! 1. proposes, for every node of the round, its [`NEIGHBOURS`] nearest other nodes by centre
//!    (an R-tree, `rstar`, over the centres; all pairs when the round has few nodes), the
//!    paper's "pairs of adjacent or overlapping boxes";
//! 2. scores each candidate pair by the [`Measures`] of the parent it would make, under the
//!    [`Merge`] rule;
//! 3. matches greedily, cheapest pair first, each node at most once (a maximal matching of the
//!    candidate graph), and makes the parents;
//! 4. passes the parents and the unmatched nodes to the next round.
//!
//! Scoring runs in parallel (rayon); everything is deterministic. A round matches at least one
//! pair, and in practice most nodes, so the tree is close to balanced.
//!
//! ```
//! use kepler::lab::boxtree::{BoxTree, Merge, pca::PcaMin};
//! let sphere = kepler::solids::uv_sphere(1.0, 16, 8).unwrap();
//! let tree: BoxTree<PcaMin> = BoxTree::build(&sphere, Merge::Volume);
//! assert_eq!(tree.len(), sphere.triangles().len());
//! assert_eq!(tree.nodes().len(), 2 * tree.len() - 1);
//! assert!(tree.height() <= 12);
//! ```

use super::{Measures, Merge, NodeShape};
use crate::geometry::Point3;
use crate::mesh::Mesh;
use rayon::prelude::*;
use rstar::RTree;
use rstar::primitives::GeomWithData;

/// Candidate partners proposed for each node in a round: as many as a triangle has edge
/// neighbours. (Six or twelve gave slightly larger trees, in total area and in the tests of
/// the sphere experiment, and took longer.)
///
/// ```
/// assert_eq!(kepler::lab::boxtree::tree::NEIGHBOURS, 3);
/// ```
pub const NEIGHBOURS: usize = 3;

/// Marks a leaf in [`Node`]'s first child slot.
const LEAF: u32 = u32::MAX;

/// A node of the hierarchy: its bound, and its two children or its triangle.
///
/// ```
/// use kepler::lab::boxtree::{BoxTree, Merge};
/// use kepler::geometry::Aabb;
/// let tree: BoxTree<Aabb> = BoxTree::build(&kepler::solids::tetrahedron(1.0).unwrap(), Merge::Area);
/// let leaf = &tree.nodes()[0];
/// assert_eq!((leaf.triangle(), leaf.children()), (Some(0), None));
/// let root = &tree.nodes()[tree.root().unwrap()];
/// assert!(root.children().is_some());
/// ```
#[derive(Debug, Clone)]
pub struct Node<S> {
    bound: S,
    measures: Measures,
    link: [u32; 2],
}

/// What a node holds: a triangle, or two children (indices in [`BoxTree::nodes`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Link {
    Leaf(usize),
    Inner([usize; 2]),
}

impl<S: NodeShape> Node<S> {
    fn new(bound: S, link: [u32; 2]) -> Node<S> {
        Node {
            measures: bound.measures(),
            bound,
            link,
        }
    }
}

impl<S> Node<S> {
    /// The node's bound.
    ///
    /// ```
    /// use kepler::lab::boxtree::{BoxTree, Merge};
    /// use kepler::geometry::Aabb;
    /// let tree: BoxTree<Aabb> = BoxTree::build(&kepler::solids::cube(2.0).unwrap(), Merge::Area);
    /// assert_eq!(tree.nodes()[tree.root().unwrap()].bound().max, [1.0; 3]);
    /// ```
    pub fn bound(&self) -> &S {
        &self.bound
    }

    /// The indices (in [`BoxTree::nodes`]) of the two children, or `None` for a leaf.
    ///
    /// ```
    /// use kepler::lab::boxtree::{BoxTree, Merge};
    /// use kepler::geometry::Aabb;
    /// let tree: BoxTree<Aabb> = BoxTree::build(&kepler::solids::cube(2.0).unwrap(), Merge::Area);
    /// assert!(tree.nodes()[..12].iter().all(|n| n.children().is_none()));
    /// ```
    pub fn children(&self) -> Option<[usize; 2]> {
        (self.link[0] != LEAF).then(|| self.link.map(|c| c as usize))
    }

    /// The index of a leaf's triangle (in the mesh's triangles), or `None` for an inner node.
    ///
    /// ```
    /// use kepler::lab::boxtree::{BoxTree, Merge};
    /// use kepler::geometry::Aabb;
    /// let tree: BoxTree<Aabb> = BoxTree::build(&kepler::solids::cube(2.0).unwrap(), Merge::Area);
    /// assert_eq!(tree.nodes()[5].triangle(), Some(5));
    /// ```
    pub fn triangle(&self) -> Option<usize> {
        (self.link[0] == LEAF).then_some(self.link[1] as usize)
    }

    /// The bound's surface area and volume (computed once, when the node was made).
    ///
    /// ```
    /// use kepler::lab::boxtree::{BoxTree, Merge};
    /// use kepler::geometry::Aabb;
    /// let tree: BoxTree<Aabb> = BoxTree::build(&kepler::solids::cube(2.0).unwrap(), Merge::Area);
    /// assert_eq!(tree.nodes()[tree.root().unwrap()].measures().volume, 8.0);
    /// ```
    pub fn measures(&self) -> Measures {
        self.measures
    }

    /// The triangle or the children.
    pub(crate) fn link(&self) -> Link {
        if self.link[0] == LEAF {
            Link::Leaf(self.link[1] as usize)
        } else {
            Link::Inner(self.link.map(|c| c as usize))
        }
    }
}

/// A boxtree over the triangles of a mesh: leaves `0..len()` hold triangles `0..len()` in the
/// mesh's order, inner nodes follow in the order they were made, and the root is last.
///
/// ```
/// use kepler::lab::boxtree::{BoxTree, Merge};
/// use kepler::bounds::tribox::TriboxBounds;
/// let torus = kepler::solids::torus(2.0, 0.5, 24, 12).unwrap();
/// let tree: BoxTree<TriboxBounds> = BoxTree::build(&torus, Merge::Area);
/// assert_eq!(tree.len(), 576);
/// assert_eq!(tree.root(), Some(2 * 576 - 2));
/// ```
#[derive(Debug, Clone)]
pub struct BoxTree<S> {
    nodes: Vec<Node<S>>,
    triangles: Vec<[Point3; 3]>,
}

impl<S: NodeShape> BoxTree<S> {
    /// Builds the hierarchy over the triangles of `mesh`, pairing by `merge` (see the module
    /// documentation).
    ///
    /// ```
    /// use kepler::lab::boxtree::{BoxTree, Merge, pca::PcaAll};
    /// let cube = kepler::solids::cube(1.0).unwrap();
    /// let tree: BoxTree<PcaAll> = BoxTree::build(&cube, Merge::Area);
    /// let root = tree.nodes()[tree.root().unwrap()].bound();
    /// assert!(cube.vertices().iter().all(|v| root.oriented().contains_point(v)));
    /// ```
    pub fn build(mesh: &Mesh, merge: Merge) -> BoxTree<S> {
        let triangles: Vec<[Point3; 3]> = (0..mesh.triangles().len())
            .map(|t| mesh.triangle(t))
            .collect();
        let mut nodes: Vec<Node<S>> = triangles
            .par_iter()
            .enumerate()
            .map(|(t, corners)| Node::new(S::leaf(corners), [LEAF, t as u32]))
            .collect();
        let mut round: Vec<u32> = (0..nodes.len() as u32).collect();
        while round.len() > 1 {
            let bound = |i: u32| &nodes[round[i as usize] as usize].bound;
            let mut scored: Vec<([f64; 2], u32, u32)> = candidates(&nodes, &round)
                .into_par_iter()
                .map(|(i, j)| (merge.key(&S::parent_measures(bound(i), bound(j))), i, j))
                .collect();
            scored.sort_unstable_by(|a, b| {
                (a.0[0].total_cmp(&b.0[0]))
                    .then(a.0[1].total_cmp(&b.0[1]))
                    .then((a.1, a.2).cmp(&(b.1, b.2)))
            });
            let mut matched = vec![false; round.len()];
            let mut pairs = Vec::with_capacity(round.len() / 2);
            for (_, i, j) in scored {
                let (i, j) = (i as usize, j as usize);
                if !matched[i] && !matched[j] {
                    matched[i] = true;
                    matched[j] = true;
                    pairs.push([round[i], round[j]]);
                }
            }
            let parents: Vec<Node<S>> = pairs
                .par_iter()
                .map(|&[a, b]| {
                    let bound = S::parent(&nodes[a as usize].bound, &nodes[b as usize].bound);
                    Node::new(bound, [a, b])
                })
                .collect();
            let first = nodes.len() as u32;
            nodes.extend(parents);
            let made = first..nodes.len() as u32;
            round = made
                .chain(
                    round
                        .iter()
                        .zip(&matched)
                        .filter(|(_, m)| !**m)
                        .map(|(&n, _)| n),
                )
                .collect();
        }
        BoxTree { nodes, triangles }
    }

    /// The number of triangles (leaves).
    ///
    /// ```
    /// use kepler::lab::boxtree::{BoxTree, Merge};
    /// use kepler::geometry::Aabb;
    /// let tree: BoxTree<Aabb> = BoxTree::build(&kepler::solids::cube(1.0).unwrap(), Merge::Area);
    /// assert_eq!(tree.len(), 12);
    /// ```
    pub fn len(&self) -> usize {
        self.triangles.len()
    }

    /// Whether the tree has no triangle.
    ///
    /// ```
    /// use kepler::lab::boxtree::{BoxTree, Merge};
    /// use kepler::geometry::Aabb;
    /// let tree: BoxTree<Aabb> = BoxTree::build(&kepler::solids::cube(1.0).unwrap(), Merge::Area);
    /// assert!(!tree.is_empty());
    /// ```
    pub fn is_empty(&self) -> bool {
        self.triangles.is_empty()
    }

    /// All nodes: the leaves first (leaf `t` holds triangle `t`), the root last.
    ///
    /// ```
    /// use kepler::lab::boxtree::{BoxTree, Merge};
    /// use kepler::geometry::Aabb;
    /// let tree: BoxTree<Aabb> = BoxTree::build(&kepler::solids::octahedron(1.0).unwrap(), Merge::Area);
    /// assert_eq!(tree.nodes().iter().filter(|n| n.triangle().is_some()).count(), 8);
    /// ```
    pub fn nodes(&self) -> &[Node<S>] {
        &self.nodes
    }

    /// The index of the root node, `None` for an empty tree.
    ///
    /// ```
    /// use kepler::lab::boxtree::{BoxTree, Merge};
    /// use kepler::geometry::Aabb;
    /// let tree: BoxTree<Aabb> = BoxTree::build(&kepler::solids::tetrahedron(1.0).unwrap(), Merge::Area);
    /// assert_eq!(tree.root(), Some(6));
    /// ```
    pub fn root(&self) -> Option<usize> {
        self.nodes.len().checked_sub(1)
    }

    /// The triangles' corners, in the mesh's order.
    ///
    /// ```
    /// use kepler::lab::boxtree::{BoxTree, Merge};
    /// use kepler::geometry::Aabb;
    /// let cube = kepler::solids::cube(1.0).unwrap();
    /// let tree: BoxTree<Aabb> = BoxTree::build(&cube, Merge::Area);
    /// assert_eq!(tree.triangles()[3], cube.triangle(3));
    /// ```
    pub fn triangles(&self) -> &[[Point3; 3]] {
        &self.triangles
    }

    /// The number of edges on the longest path from the root to a leaf (0 for a single leaf
    /// or an empty tree).
    ///
    /// ```
    /// use kepler::lab::boxtree::{BoxTree, Merge};
    /// use kepler::geometry::Aabb;
    /// let tree: BoxTree<Aabb> = BoxTree::build(&kepler::solids::cube(1.0).unwrap(), Merge::Area);
    /// assert!((4..=6).contains(&tree.height()));
    /// ```
    pub fn height(&self) -> usize {
        // Children precede their parents, so one pass in order computes every node's height.
        let mut heights = vec![0usize; self.nodes.len()];
        for (i, node) in self.nodes.iter().enumerate() {
            if let Some([a, b]) = node.children() {
                heights[i] = 1 + heights[a].max(heights[b]);
            }
        }
        heights.last().copied().unwrap_or(0)
    }

    /// The paper's expected cost of a query by a random plane: "the expected number of nodes
    /// visited in a query determined by a random plane is equal to (1/S_r) Σ_v S_v", the sum
    /// of the nodes' surface areas over the root's (Cauchy's formula; 0 for an empty tree).
    ///
    /// ```
    /// use kepler::lab::boxtree::{BoxTree, Merge};
    /// use kepler::geometry::Aabb;
    /// let tree: BoxTree<Aabb> = BoxTree::build(&kepler::solids::cube(1.0).unwrap(), Merge::Area);
    /// let cost = tree.plane_cost();
    /// assert!(cost > 1.0 && cost < tree.nodes().len() as f64);
    /// ```
    pub fn plane_cost(&self) -> f64 {
        let Some(root) = self.nodes.last() else {
            return 0.0;
        };
        let total: f64 = self.nodes.iter().map(|n| n.measures.area).sum();
        total / root.measures.area
    }

    /// The mean measures of the nodes at each height above the leaves (index 0: the leaves),
    /// as the paper's Figures 3 and 4 plot them per level.
    ///
    /// ```
    /// use kepler::lab::boxtree::{BoxTree, Merge};
    /// use kepler::geometry::Aabb;
    /// let tree: BoxTree<Aabb> = BoxTree::build(&kepler::solids::cube(2.0).unwrap(), Merge::Area);
    /// let levels = tree.mean_measures_by_height();
    /// assert_eq!(levels.len(), tree.height() + 1);
    /// assert_eq!(levels.last().unwrap().area, 24.0);
    /// ```
    pub fn mean_measures_by_height(&self) -> Vec<Measures> {
        let mut heights = vec![0usize; self.nodes.len()];
        let mut sums: Vec<(Measures, usize)> = Vec::new();
        for (i, node) in self.nodes.iter().enumerate() {
            if let Some([a, b]) = node.children() {
                heights[i] = 1 + heights[a].max(heights[b]);
            }
            if sums.len() <= heights[i] {
                sums.resize(
                    heights[i] + 1,
                    (
                        Measures {
                            area: 0.0,
                            volume: 0.0,
                        },
                        0,
                    ),
                );
            }
            let m = node.measures;
            let (sum, count) = &mut sums[heights[i]];
            sum.area += m.area;
            sum.volume += m.volume;
            *count += 1;
        }
        sums.into_iter()
            .map(|(s, c)| Measures {
                area: s.area / c.max(1) as f64,
                volume: s.volume / c.max(1) as f64,
            })
            .collect()
    }
}

/// The candidate pairs `(i, j)`, `i < j`, of positions in `round`: all pairs of a small round,
/// otherwise each node with its [`NEIGHBOURS`] nearest by centre; sorted, without repeats.
fn candidates<S: NodeShape>(nodes: &[Node<S>], round: &[u32]) -> Vec<(u32, u32)> {
    let n = round.len() as u32;
    if round.len() <= NEIGHBOURS + 1 {
        return (0..n)
            .flat_map(|i| (i + 1..n).map(move |j| (i, j)))
            .collect();
    }
    let centres: Vec<[f64; 3]> = round
        .par_iter()
        .map(|&r| nodes[r as usize].bound.center().into())
        .collect();
    let tree = RTree::bulk_load(
        centres
            .iter()
            .enumerate()
            .map(|(i, &c)| GeomWithData::new(c, i as u32))
            .collect(),
    );
    let mut pairs: Vec<(u32, u32)> = (0..n)
        .into_par_iter()
        .flat_map_iter(|i| {
            tree.nearest_neighbor_iter(&centres[i as usize])
                .filter(move |g| g.data != i)
                .take(NEIGHBOURS)
                .map(move |g| (i.min(g.data), i.max(g.data)))
                .collect::<Vec<_>>()
        })
        .collect();
    pairs.par_sort_unstable();
    pairs.dedup();
    pairs
}
