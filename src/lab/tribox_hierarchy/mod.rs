//! Hierarchical triboxes (Crosnier and Rossignac 1999, §4): a closed object is split
//! recursively by planes across the tribox's 9 directions, and the triboxes of the cells make
//! tighter and tighter bounds.
//!
//! Each node of the binary tree is a cell `S ∩ C`, where `C` (the node's *region*) is the
//! root tribox cut by the planes on the way down; the node keeps the cell's tribox. A cell is
//! split by a plane across one of the 9 directions: the paper takes the bisector of the
//! thickest slab ([`SplitRule::Thickest`]); by default all nine bisectors are candidates
//! ([`SplitRule::Bisectors`]), and [`SplitRule::Features`] adds planes through the object's
//! vertices in the cell. A candidate is admissible when the two triboxes' total area is at
//! most `1 − gain` times the cell's ([`HierarchyOptions::gain`], the paper's stopping rule); of those,
//! the one with the least total volume is taken. A cell stays a leaf when no candidate is
//! admissible, or at [`HierarchyOptions::max_depth`]; [`Hierarchy::stop`] tells which ended
//! the tree. Asked for more levels ([`HierarchyOptions::levels`]), a level the rule would not
//! make is made regardless, of the best candidates below the gain ([`Level::below_gain`]).
//!
//! The cells' vertices are computed exactly as the paper lists them, incrementally from the
//! parent cell (see the `cell` module): every tribox contains its exact cell. A level of
//! detail is the union of the triboxes of a cut through the tree ([`Hierarchy::cut`]); the
//! triboxes of a cut have disjoint interiors, since each lies in its region. [`Level`] reports
//! its size, compression, volume and area excess and a bounded Hausdorff distance.
//!
//! ```
//! use kepler::lab::tribox_hierarchy::{Hierarchy, HierarchyOptions};
//! use kepler::geometry::Point3;
//! // An L-shaped wall: one tribox covers the notch; two fit the L much better.
//! use geo::polygon;
//! let outline = polygon![(x: 0.0, y: 0.0), (x: 6.0, y: 0.0), (x: 6.0, y: 1.0),
//!     (x: 1.0, y: 1.0), (x: 1.0, y: 4.0), (x: 0.0, y: 4.0)];
//! let wall = kepler::solids::prism(&outline, 3.0).unwrap();
//! let h = Hierarchy::build(&wall, &HierarchyOptions::default()).unwrap();
//! let levels = h.levels(2);
//! assert_eq!(levels[0].triboxes, 1);
//! assert!(levels[1].triboxes >= 2 && levels[1].volume_excess < levels[0].volume_excess);
//! ```

mod cell;
mod hausdorff;
mod levels;

pub use hausdorff::{DistanceBounds, hausdorff};
pub use levels::{Level, union_area};

use crate::bounds::tribox::{Tribox, TriboxBounds};
use crate::geometry::Point3;
use crate::mesh::{Mesh, MeshError, TriangleTree};
use crate::scene::Scene;
use crate::views::View;
use cell::Cell;
use rayon::prelude::*;
use serde::Serialize;

/// Why a hierarchy cannot be built.
///
/// ```
/// use kepler::lab::tribox_hierarchy::{Hierarchy, HierarchyOptions, TriboxesError};
/// let cube = kepler::solids::cube(1.0).unwrap();
/// let bad = HierarchyOptions { gain: 1.0, ..HierarchyOptions::default() };
/// assert!(matches!(Hierarchy::build(&cube, &bad), Err(TriboxesError::Option(_))));
/// ```
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum TriboxesError {
    /// The mesh does not bound a solid: its cells would have no inside.
    #[error("hierarchical triboxes need a closed, consistently oriented mesh")]
    NotSolid,
    /// The mesh has no triangle.
    #[error("the mesh has no face")]
    Empty,
    /// An option out of range.
    #[error("{0}")]
    Option(String),
}

/// Which planes are candidates to split a cell. Of those that lower the total tribox area
/// enough ([`HierarchyOptions::gain`], the paper's rule), the one whose two triboxes have the least
/// total volume is taken: the paper's greedy choice by area alone favours shaving off thin
/// corners, which lowers the area sum a little and the volume not at all.
///
/// ```
/// use kepler::lab::tribox_hierarchy::{Hierarchy, HierarchyOptions, SplitRule};
/// use geo::polygon;
/// let l = polygon![(x: 0.0, y: 0.0), (x: 6.0, y: 0.0), (x: 6.0, y: 1.0),
///     (x: 1.0, y: 1.0), (x: 1.0, y: 4.0), (x: 0.0, y: 4.0)];
/// let wall = kepler::solids::prism(&l, 3.0).unwrap();
/// // A plane through the notch's corner cuts the L into its two arms exactly.
/// let o = HierarchyOptions { split: SplitRule::Features, ..HierarchyOptions::default() };
/// let level = Hierarchy::build(&wall, &o).unwrap().levels(2)[1];
/// assert_eq!((level.triboxes, level.volume), (2, 27.0));
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize)]
// The command line's --split: its `--help` lists the values by name only.
#[cfg_attr(feature = "cli", derive(clap::ValueEnum))]
#[serde(rename_all = "kebab-case")]
pub enum SplitRule {
    /// The paper's first choice: the bisector of the thickest slab, alone.
    #[cfg_attr(feature = "cli", value(help = None::<&str>))]
    Thickest,
    /// The bisectors of all nine slabs.
    #[default]
    #[cfg_attr(feature = "cli", value(help = None::<&str>))]
    Bisectors,
    /// The nine bisectors and, along each direction, up to [`FEATURE_PLANES`] planes through
    /// the object's vertices in the cell: they can cut off a concave corner, which bisectors
    /// never reach (the paper's suggestion of planes at local extrema).
    #[cfg_attr(feature = "cli", value(help = None::<&str>))]
    Features,
}

/// The most planes through vertices tried per direction by [`SplitRule::Features`].
///
/// ```
/// assert_eq!(kepler::lab::tribox_hierarchy::FEATURE_PLANES, 4);
/// ```
pub const FEATURE_PLANES: usize = 4;

/// The options of [`Hierarchy::build`].
///
/// ```
/// let o = kepler::lab::tribox_hierarchy::HierarchyOptions::default();
/// assert_eq!((o.gain, o.max_depth, o.levels), (0.05, 8, None));
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HierarchyOptions {
    /// A cell is split only when its children's triboxes have a total area at most
    /// `(1 − gain)` times its own tribox's area (the paper's rule, with `gain` below 1). A
    /// negative gain lets splits raise the area by up to `−gain` times, to build deeper levels
    /// of objects whose cavities no single cut makes cheaper (a U-shaped prism, a torus).
    pub gain: f64,
    /// No cell deeper than this is split (the root is at depth 0).
    pub max_depth: usize,
    /// How the splitting plane is chosen.
    pub split: SplitRule,
    /// The Hausdorff bounds of [`Hierarchy::levels`] stop when their gap is at most this
    /// fraction of the root tribox's diagonal.
    pub hausdorff_tolerance: f64,
    /// How many levels the tree must have (depths 0 to `levels − 1`, within `max_depth`):
    /// where the gain leaves a level above that depth with no split, each of its cells is
    /// split by its best candidate (the least total volume, then area) whatever the area it
    /// saves, and [`Level::below_gain`] marks the level made. `None`: the gain alone decides.
    pub levels: Option<usize>,
}

impl Default for HierarchyOptions {
    fn default() -> HierarchyOptions {
        HierarchyOptions {
            gain: 0.05,
            max_depth: 8,
            split: SplitRule::Bisectors,
            hausdorff_tolerance: 1e-3,
            levels: None,
        }
    }
}

/// Why a hierarchy has no deeper level: what kept every cell of its deepest level whole.
///
/// ```
/// use kepler::lab::tribox_hierarchy::{Hierarchy, HierarchyOptions, Stop};
/// let cube = kepler::solids::cube(1.0).unwrap();
/// let o = HierarchyOptions { max_depth: 0, ..HierarchyOptions::default() };
/// assert_eq!(Hierarchy::build(&cube, &o).unwrap().stop(), Stop::MaxDepth);
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Stop {
    /// The cells are at [`HierarchyOptions::max_depth`].
    MaxDepth,
    /// No candidate lowers a cell's tribox area by the gain. `best_gain` is (within a few
    /// ulps) the largest gain that admits a candidate of one of the cells, about `1 − area
    /// after / area before` (negative when every candidate raises the area): that cell splits
    /// under a gain at most `best_gain`.
    Gain {
        /// The largest gain that admits a candidate.
        best_gain: f64,
    },
    /// No candidate plane splits a cell: none has a vertex of the cell strictly on each side.
    NoPlane,
}

/// The tolerance of the simplification of [`HierarchyNode::faces`] and of the drawn triboxes,
/// relative to the root tribox's diagonal: rounding slivers go, real faces stay.
///
/// ```
/// assert_eq!(kepler::lab::tribox_hierarchy::SIMPLIFY, 1e-9);
/// ```
pub const SIMPLIFY: f64 = 1e-9;

/// A splitting plane `d · x = offset` across direction `d` of
/// [`TriboxBounds::DIRECTIONS`].
///
/// ```
/// let p = kepler::lab::tribox_hierarchy::SplitPlane { direction: 3, offset: 1.5 }; // x + y = 1.5
/// assert_eq!(kepler::bounds::tribox::TriboxBounds::DIRECTIONS[p.direction], [1.0, 1.0, 0.0]);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct SplitPlane {
    /// The direction's index.
    pub direction: usize,
    /// The plane's value along the direction.
    pub offset: f64,
}

/// A node of the hierarchy: a cell `S ∩ region` and its tribox.
///
/// ```
/// use kepler::lab::tribox_hierarchy::{Hierarchy, HierarchyOptions};
/// let h = Hierarchy::build(&kepler::solids::cube(2.0).unwrap(), &HierarchyOptions::default()).unwrap();
/// let root = &h.nodes()[0];
/// assert_eq!((root.depth, root.children, root.faces, root.volume), (0, None, 6, 8.0));
/// ```
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct HierarchyNode {
    /// The tribox of the cell (contains the exact cell, and lies in the region and in the
    /// parent's tribox).
    pub tribox: TriboxBounds,
    /// The region `C`: the root tribox cut by the planes above this node.
    pub region: TriboxBounds,
    /// The depth (0 at the root).
    pub depth: usize,
    /// The parent's index.
    pub parent: Option<usize>,
    /// The children's indices, below and above the split plane.
    pub children: Option<[usize; 2]>,
    /// The plane splitting the cell, if it is split.
    pub split: Option<SplitPlane>,
    /// The number of vertices kept for the cell.
    pub cell_vertices: usize,
    /// The number of the object's triangles that may meet the region.
    pub triangles: usize,
    /// The tribox's volume.
    pub volume: f64,
    /// The tribox's surface area.
    pub area: f64,
    /// The tribox's number of faces as drawn by [`tribox_mesh`] with the tolerance
    /// [`SIMPLIFY`] times the root tribox's diagonal (simplified as the paper does, rounding
    /// slivers removed).
    pub faces: usize,
}

/// The binary tree of hierarchical triboxes of one closed object.
///
/// ```
/// use kepler::lab::tribox_hierarchy::{Hierarchy, HierarchyOptions};
/// // A torus: every bisecting plane cuts the ring, and the two halves' triboxes have more
/// // area than the whole one, so the paper's rule keeps a single tribox.
/// let torus = kepler::solids::torus(2.0, 0.5, 24, 12).unwrap();
/// let h = Hierarchy::build(&torus, &HierarchyOptions::default()).unwrap();
/// assert_eq!((h.depth(), h.cut(0)), (0, vec![0]));
/// ```
#[derive(Debug)]
pub struct Hierarchy {
    nodes: Vec<HierarchyNode>,
    /// The depths of the levels split below the gain (for [`HierarchyOptions::levels`]).
    below_gain: Vec<usize>,
    stop: Stop,
    tree: TriangleTree,
    object_faces: usize,
    object_volume: f64,
    object_area: f64,
    tolerance: f64,
    simplify: f64,
}

impl Hierarchy {
    /// Builds the hierarchy of a closed, consistently oriented mesh, level by level (the cells
    /// of a level in parallel).
    ///
    /// ```
    /// use kepler::lab::tribox_hierarchy::{Hierarchy, HierarchyOptions, TriboxesError};
    /// let open = kepler::mesh::Mesh::from_polygons(
    ///     vec![[0.0, 0.0, 0.0].into(), [1.0, 0.0, 0.0].into(), [0.0, 1.0, 0.0].into()],
    ///     vec![vec![0, 1, 2]],
    /// ).unwrap();
    /// assert_eq!(Hierarchy::build(&open, &HierarchyOptions::default()).unwrap_err(), TriboxesError::NotSolid);
    /// ```
    pub fn build(mesh: &Mesh, options: &HierarchyOptions) -> Result<Hierarchy, TriboxesError> {
        check_input(mesh, options)?;
        let tree = TriangleTree::new(mesh);
        let root = Cell::root(mesh);
        let diagonal = {
            let (lo, hi) = (root.tribox.min(), root.tribox.max());
            ((hi[0] - lo[0]).powi(2) + (hi[1] - lo[1]).powi(2) + (hi[2] - lo[2]).powi(2)).sqrt()
        };
        let simplify = SIMPLIFY * diagonal;
        let node =
            |cell: &Cell, depth: usize, parent: Option<usize>| node(cell, depth, parent, simplify);
        let mut nodes = vec![node(&root, 0, None)];
        let mut below_gain = Vec::new();
        // The cells of one depth, split together (a level the gain leaves whole may be split
        // regardless, for `options.levels`).
        let mut level = vec![(0usize, root)];
        let mut depth = 0;
        let stop = loop {
            if depth >= options.max_depth {
                break Stop::MaxDepth;
            }
            let choices: Vec<Choice> = level
                .par_iter()
                .map(|(index, cell)| choose(cell, mesh, &tree, options, nodes[*index].area))
                .collect();
            let forced = choices.iter().all(|c| c.fit.is_none())
                && options.levels.is_some_and(|levels| depth + 1 < levels);
            let best_gain = choices
                .iter()
                .filter_map(|c| c.best_gain)
                .max_by(f64::total_cmp);
            let mut next = Vec::new();
            for ((index, _), choice) in level.into_iter().zip(choices) {
                let split = if forced { choice.unfit } else { choice.fit };
                let Some(Candidate {
                    plane, children, ..
                }) = split
                else {
                    continue;
                };
                let first = nodes.len();
                for cell in children {
                    nodes.push(node(&cell, depth + 1, Some(index)));
                    next.push((nodes.len() - 1, cell));
                }
                nodes[index].children = Some([first, first + 1]);
                nodes[index].split = Some(plane);
            }
            if next.is_empty() {
                break best_gain.map_or(Stop::NoPlane, |best_gain| Stop::Gain { best_gain });
            }
            depth += 1;
            if forced {
                below_gain.push(depth);
            }
            level = next;
        };
        Ok(Hierarchy {
            nodes,
            below_gain,
            stop,
            tree,
            object_faces: mesh.faces().len(),
            object_volume: mesh.volume(),
            object_area: mesh.surface_area(),
            tolerance: options.hausdorff_tolerance * diagonal,
            simplify,
        })
    }

    /// The nodes, the root first; children follow their parents.
    ///
    /// ```
    /// use kepler::lab::tribox_hierarchy::{Hierarchy, HierarchyOptions};
    /// let h = Hierarchy::build(&kepler::solids::cube(1.0).unwrap(), &HierarchyOptions::default()).unwrap();
    /// assert_eq!(h.nodes().len(), 1); // no split makes a cube's tribox smaller
    /// ```
    pub fn nodes(&self) -> &[HierarchyNode] {
        &self.nodes
    }

    /// The depth of the deepest node.
    ///
    /// ```
    /// use kepler::lab::tribox_hierarchy::{Hierarchy, HierarchyOptions};
    /// let h = Hierarchy::build(&kepler::solids::cube(1.0).unwrap(), &HierarchyOptions::default()).unwrap();
    /// assert_eq!(h.depth(), 0);
    /// ```
    pub fn depth(&self) -> usize {
        self.nodes.iter().map(|n| n.depth).max().unwrap_or(0)
    }

    /// The cut at `depth`: the nodes at that depth and the leaves above it. Their triboxes
    /// cover the object and have disjoint interiors.
    ///
    /// ```
    /// use geo::polygon;
    /// use kepler::lab::tribox_hierarchy::{Hierarchy, HierarchyOptions};
    /// // A U-shaped prism: no single cut lowers the total area, so allow it to rise by 20%.
    /// let u = polygon![(x: 0.0, y: 0.0), (x: 5.0, y: 0.0), (x: 5.0, y: 5.0), (x: 4.0, y: 5.0),
    ///     (x: 4.0, y: 1.0), (x: 1.0, y: 1.0), (x: 1.0, y: 5.0), (x: 0.0, y: 5.0)];
    /// let o = HierarchyOptions { gain: -0.2, max_depth: 3, ..HierarchyOptions::default() };
    /// let h = Hierarchy::build(&kepler::solids::prism(&u, 1.0).unwrap(), &o).unwrap();
    /// assert_eq!(h.cut(1).len(), 2);
    /// assert_eq!(h.cut(h.depth() + 5), h.cut(h.depth()));
    /// assert_eq!(h.cut(h.depth()), h.leaves());
    /// ```
    pub fn cut(&self, depth: usize) -> Vec<usize> {
        (0..self.nodes.len())
            .filter(|&i| {
                let n = &self.nodes[i];
                n.depth == depth || (n.depth < depth && n.children.is_none())
            })
            .collect()
    }

    /// The leaves.
    ///
    /// ```
    /// use kepler::lab::tribox_hierarchy::{Hierarchy, HierarchyOptions};
    /// let h = Hierarchy::build(&kepler::solids::cube(1.0).unwrap(), &HierarchyOptions::default()).unwrap();
    /// assert_eq!(h.leaves(), vec![0]);
    /// ```
    pub fn leaves(&self) -> Vec<usize> {
        (0..self.nodes.len())
            .filter(|&i| self.nodes[i].children.is_none())
            .collect()
    }

    /// The simplification tolerance of [`HierarchyNode::faces`] ([`SIMPLIFY`] times the root
    /// tribox's diagonal), for [`tribox_mesh`].
    ///
    /// ```
    /// use kepler::lab::tribox_hierarchy::{Hierarchy, HierarchyOptions};
    /// let h = Hierarchy::build(&kepler::solids::cube(1.0).unwrap(), &HierarchyOptions::default()).unwrap();
    /// assert_eq!(h.simplify_tolerance(), 1e-9 * 3f64.sqrt());
    /// ```
    pub fn simplify_tolerance(&self) -> f64 {
        self.simplify
    }

    /// The report of the first `count` levels (depths `0..count`, and no deeper than the
    /// tree), computed in parallel.
    ///
    /// ```
    /// use kepler::lab::tribox_hierarchy::{Hierarchy, HierarchyOptions};
    /// let h = Hierarchy::build(&kepler::solids::cube(1.0).unwrap(), &HierarchyOptions::default()).unwrap();
    /// let l = &h.levels(3)[0];
    /// assert_eq!((l.triboxes, l.faces, l.volume_excess, l.hausdorff_lower), (1, 6, 0.0, 0.0));
    /// assert!(l.hausdorff < 0.01); // the tribox hugs the cube: the costly case, bounded
    /// ```
    pub fn levels(&self, count: usize) -> Vec<Level> {
        let depths = count.min(self.depth() + 1);
        (0..depths)
            .into_par_iter()
            .map(|depth| levels::level(self, depth))
            .collect()
    }

    /// Why the tree goes no deeper: what kept every cell at [`Hierarchy::depth`] whole.
    ///
    /// ```
    /// use kepler::lab::tribox_hierarchy::{Hierarchy, HierarchyOptions, Stop};
    /// // No split of a torus's tribox lowers the area: the two halves' have more.
    /// let torus = kepler::solids::torus(2.0, 0.5, 24, 12).unwrap();
    /// let h = Hierarchy::build(&torus, &HierarchyOptions::default()).unwrap();
    /// let Stop::Gain { best_gain } = h.stop() else { panic!("{:?}", h.stop()) };
    /// assert!(best_gain < 0.0);
    /// // A gain at most the best one admits that split: the tree goes deeper.
    /// let o = HierarchyOptions { gain: best_gain, ..HierarchyOptions::default() };
    /// assert!(Hierarchy::build(&torus, &o).unwrap().depth() > 0);
    /// ```
    pub fn stop(&self) -> Stop {
        self.stop
    }

    /// The object and its first `levels` levels of detail (no deeper than the tree) side by
    /// side, as a scene to draw in `view`: the object as `object`, then the triboxes of the
    /// cut at depth `d` as group `level-d` of meshes `tribox-i` (as [`tribox_mesh`] draws
    /// them), each panel moved along the picture's horizontal by 1.25 times the root tribox's
    /// width across it, so that panels never overlap.
    ///
    /// ```
    /// use kepler::lab::tribox_hierarchy::{Hierarchy, HierarchyOptions};
    /// use geo::polygon;
    /// let l = polygon![(x: 0.0, y: 0.0), (x: 6.0, y: 0.0), (x: 6.0, y: 1.0),
    ///     (x: 1.0, y: 1.0), (x: 1.0, y: 4.0), (x: 0.0, y: 4.0)];
    /// let wall = kepler::solids::prism(&l, 3.0).unwrap();
    /// let h = Hierarchy::build(&wall, &HierarchyOptions::default()).unwrap();
    /// let view = kepler::views::View::standard();
    /// let scene = h.panels(&wall, 5, &view)?;
    /// // The wall, one tribox, then the two of depth 1: the tree is no deeper.
    /// assert_eq!(scene.roots().len(), 3);
    /// assert!(scene.find("level-1/tribox-1").is_some());
    /// let drawing = kepler::hidden::draw(&scene, &view, &kepler::hidden::Options::default())?;
    /// assert!(!drawing.polylines.is_empty());
    /// # Ok::<(), kepler::Error>(())
    /// ```
    pub fn panels(&self, mesh: &Mesh, levels: usize, view: &View) -> crate::Result<Scene> {
        let (right, _) = view.right_up();
        let root = Tribox::new(&self.nodes[0].tribox).cleaned();
        let along = root.vertices().iter().map(|v| v.coords.dot(&right));
        let (lo, hi) = along.fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), x| {
            (lo.min(x), hi.max(x))
        });
        let pitch = 1.25 * (hi - lo);
        let shifted = |m: &Mesh, k: usize| {
            m.transformed(&nalgebra::Matrix4::new_translation(
                &(right * (pitch * k as f64)),
            ))
        };
        let mut scene = Scene::new();
        scene.add_mesh(None, "object", shifted(mesh, 0)?)?;
        for depth in 0..levels.min(self.depth() + 1) {
            let group = scene.add_group(None, format!("level-{depth}"))?;
            for (i, node) in self.cut(depth).into_iter().enumerate() {
                let m = tribox_mesh(&self.nodes[node].tribox, self.simplify)?;
                scene.add_mesh(Some(group), format!("tribox-{i}"), shifted(&m, depth + 1)?)?;
            }
        }
        Ok(scene)
    }
}

/// The boundary of a tribox as a mesh (its faces counter-clockwise seen from outside), for
/// drawing a level of detail: the boundary simplified as the paper does
/// ([`Tribox::simplified`]: planes moved outward by at most `tol` where that removes a face),
/// then vertices closer than `tol` merged and the faces they collapse dropped (slivers where
/// three planes meet within rounding of one line, which no single plane's move removes).
///
/// ```
/// use kepler::bounds::tribox::TriboxBounds;
/// use kepler::geometry::Point3;
/// let b = TriboxBounds::from_points(&[Point3::new(0.0, 0.0, 0.0), Point3::new(1.0, 2.0, 3.0),
///     Point3::new(1.0, 0.0, 0.0), Point3::new(0.0, 2.0, 3.0)]);
/// let m = kepler::lab::tribox_hierarchy::tribox_mesh(&b, 0.0).unwrap();
/// assert!(m.is_solid());
/// assert!((m.volume() - b.boundary().cleaned().volume()).abs() < 1e-12);
/// ```
pub fn tribox_mesh(tribox: &TriboxBounds, tol: f64) -> Result<Mesh, MeshError> {
    let (vertices, faces) = snapped_boundary(tribox, tol);
    Mesh::from_polygons(vertices, faces)
}

/// The simplified boundary with vertices closer than `tol` merged (to the first of them) and
/// the faces left with fewer than 3 vertices dropped.
fn snapped_boundary(tribox: &TriboxBounds, tol: f64) -> (Vec<Point3>, Vec<Vec<u32>>) {
    let boundary = Tribox::new(tribox).simplified(tol);
    let points = boundary.vertices();
    let mut target: Vec<usize> = (0..points.len()).collect();
    for i in 0..points.len() {
        if let Some(j) = (0..i).find(|&j| target[j] == j && (points[i] - points[j]).norm() < tol) {
            target[i] = j;
        }
    }
    let mut index = vec![u32::MAX; points.len()];
    let mut vertices = Vec::new();
    for i in 0..points.len() {
        if target[i] == i {
            index[i] = vertices.len() as u32;
            vertices.push(points[i]);
        }
    }
    let faces = boundary
        .faces()
        .filter_map(|(_, f)| {
            let mut face: Vec<u32> = Vec::with_capacity(f.len());
            for &v in f {
                let k = index[target[v as usize]];
                if face.last() != Some(&k) {
                    face.push(k);
                }
            }
            while face.len() > 1 && face.first() == face.last() {
                face.pop();
            }
            (face.len() >= 3).then_some(face)
        })
        .collect();
    (vertices, faces)
}

/// Refuses what [`Hierarchy::build`] cannot build on: a gain of 1 or more, a Hausdorff
/// tolerance not positive, a mesh without triangles or not solid.
fn check_input(mesh: &Mesh, options: &HierarchyOptions) -> Result<(), TriboxesError> {
    if !(options.gain < 1.0 && options.gain.is_finite()) {
        return Err(TriboxesError::Option(format!(
            "the gain must be a number below 1, not {}",
            options.gain
        )));
    }
    if !(options.hausdorff_tolerance > 0.0 && options.hausdorff_tolerance.is_finite()) {
        return Err(TriboxesError::Option(format!(
            "the Hausdorff tolerance must be positive, not {}",
            options.hausdorff_tolerance
        )));
    }
    if mesh.triangles().is_empty() {
        return Err(TriboxesError::Empty);
    }
    if !mesh.is_solid() {
        return Err(TriboxesError::NotSolid);
    }
    Ok(())
}

/// A node for a cell.
fn node(cell: &Cell, depth: usize, parent: Option<usize>, simplify: f64) -> HierarchyNode {
    let boundary = Tribox::new(&cell.tribox).cleaned();
    HierarchyNode {
        tribox: cell.tribox,
        region: cell.region,
        depth,
        parent,
        children: None,
        split: None,
        cell_vertices: cell.vertex_count(),
        triangles: cell.triangle_count(),
        volume: boundary.volume(),
        area: boundary.surface_area(),
        faces: snapped_boundary(&cell.tribox, simplify).1.len(),
    }
}

/// A candidate split of a cell: its plane, the two cells, and their triboxes' total volume and
/// area.
struct Candidate {
    plane: SplitPlane,
    children: [Cell; 2],
    volume: f64,
    area: f64,
}

impl Candidate {
    /// The order of choice: the least total volume, then area (then the plane, for a result
    /// independent of the order of evaluation).
    fn order(&self, other: &Candidate) -> std::cmp::Ordering {
        self.volume
            .total_cmp(&other.volume)
            .then(self.area.total_cmp(&other.area))
            .then(self.plane.direction.cmp(&other.plane.direction))
            .then(self.plane.offset.total_cmp(&other.plane.offset))
    }
}

/// The candidates of a cell sorted out by the gain: the best that lowers the area enough (the
/// paper's rule), the best of the others (for a level split regardless), and the largest gain
/// that admits one.
#[derive(Default)]
struct Choice {
    fit: Option<Candidate>,
    unfit: Option<Candidate>,
    best_gain: Option<f64>,
}

impl Choice {
    /// The choice of one candidate of a cell of tribox area `area`.
    fn of(candidate: Candidate, gain: f64, area: f64) -> Choice {
        let best_gain = Some(admitting_gain(candidate.area, area));
        if admits(gain, candidate.area, area) {
            Choice {
                fit: Some(candidate),
                unfit: None,
                best_gain,
            }
        } else {
            Choice {
                fit: None,
                unfit: Some(candidate),
                best_gain,
            }
        }
    }

    /// The choice of the candidates of both.
    fn merge(self, other: Choice) -> Choice {
        let better = |a: Option<Candidate>, b: Option<Candidate>| match (a, b) {
            (Some(a), Some(b)) => Some(if b.order(&a).is_lt() { b } else { a }),
            (a, b) => a.or(b),
        };
        Choice {
            fit: better(self.fit, other.fit),
            unfit: better(self.unfit, other.unfit),
            best_gain: [self.best_gain, other.best_gain]
                .into_iter()
                .flatten()
                .max_by(f64::total_cmp),
        }
    }
}

/// Whether children of total tribox area `after` split a cell of area `before` under `gain`:
/// the paper's rule, `after ≤ (1 − gain) · before`.
fn admits(gain: f64, after: f64, before: f64) -> bool {
    after <= (1.0 - gain) * before
}

/// Nearly the largest gain (within a few ulps) under which children of total area `after`
/// split a cell of area `before`: `1 − after / before`, lowered until [`admits`] holds as it
/// rounds. The steps double: where `after` and `before` are within rounding of each other
/// (a flat cell), the quotient gives a gain of 0 and ulps of 0 would never reach the next
/// value of `1 − gain`.
fn admitting_gain(after: f64, before: f64) -> f64 {
    let mut gain = 1.0 - after / before;
    let mut step = f64::EPSILON * gain.abs().max(1.0);
    while gain.is_finite() && !admits(gain, after, before) {
        gain -= step;
        step *= 2.0;
    }
    gain
}

/// The candidates of the rule for a cell, evaluated: among them, the least total volume
/// (then area) of those whose two triboxes have a total area at most `(1 − gain)` times the
/// cell's `area` (the paper's rule), and of the others.
fn choose(
    cell: &Cell,
    mesh: &Mesh,
    tree: &TriangleTree,
    options: &HierarchyOptions,
    area: f64,
) -> Choice {
    let mut candidates: Vec<(usize, f64)> = match options.split {
        SplitRule::Thickest => (0..9)
            .filter(|&d| cell.bisector(d).is_some())
            .max_by(|&a, &b| cell.thickness(a).total_cmp(&cell.thickness(b)))
            .into_iter()
            .filter_map(|d| Some((d, cell.bisector(d)?)))
            .collect(),
        SplitRule::Bisectors | SplitRule::Features => (0..9)
            .filter_map(|d| Some((d, cell.bisector(d)?)))
            .collect(),
    };
    if options.split == SplitRule::Features {
        for d in 0..9 {
            let planes = cell.feature_planes(d, FEATURE_PLANES);
            candidates.extend(planes.into_iter().map(|h| (d, h)));
        }
    }
    candidates
        .into_par_iter()
        .filter_map(|(d, h)| {
            let children = cell.split(mesh, tree, d, h)?;
            let boundaries = children
                .each_ref()
                .map(|c| Tribox::new(&c.tribox).cleaned());
            let candidate = Candidate {
                plane: SplitPlane {
                    direction: d,
                    offset: h,
                },
                children,
                volume: boundaries.iter().map(Tribox::volume).sum(),
                area: boundaries.iter().map(Tribox::surface_area).sum(),
            };
            Some(Choice::of(candidate, options.gain, area))
        })
        .reduce(Choice::default, Choice::merge)
}

#[cfg(test)]
mod tests {
    use super::{admits, admitting_gain};

    #[test]
    fn the_admitting_gain_admits_and_is_the_largest_to_rounding() {
        // The last pair's quotient rounds to 1: the gain of 0 does not admit, nor any gain
        // within an ulp of 0.
        for (after, before) in [
            (68.0, 103.0),
            (103.0, 68.0),
            (1.0, 1.0),
            (2.0, 2f64.next_down()),
        ] {
            let gain = admitting_gain(after, before);
            assert!(admits(gain, after, before), "{after} {before}: {gain}");
            assert!(
                !admits(gain + 1e-12, after, before),
                "{after} {before}: {gain}"
            );
        }
    }
}
