//! The lab: the papers' experiments, reproduced beside the engine but not part of it.
//!
//! The engine (every other module of the crate) answers questions about a scene: what is
//! inside, what is visible, what to draw. The lab measures how well the papers' bounding
//! volumes would serve those answers, and reproduces their tables and figures. The engine never
//! imports the lab (a test, `tests/layering.rs`, keeps it so); the lab builds on the engine's
//! kernel, meshes, bounds and views.
//!
//! - [`boxtree`]: Barequet, Chazelle, Guibas, Mitchell and Tal (1996), BOXTREE: bottom-up
//!   bounding hierarchies over a surface's triangles (axis-aligned, principal-component and
//!   tribox nodes), ray shooting and collision tests with their counts, the concentric-sphere
//!   experiment of the paper's Table 1.
//! - [`tribox_hierarchy`]: Crosnier and Rossignac (1999), §4: hierarchical triboxes by recursive
//!   splitting, the levels of detail with their compression, volume and area excess and
//!   Hausdorff bounds. It builds on the engine's one tribox, [`crate::bounds::tribox`].
//! - [`culling`]: each bounding volume (rstar on projected boxes, CBOX, TRIBOX, INBOX) as a
//!   filter on the pairs of objects of one view, and the work it would save.
//! - [`oriented`]: oriented boxes (three slabs with exact containment), for BOXTREE's
//!   principal-component nodes and the projected-area comparison.
//! - [`projected_area`]: Schmalstieg and Tobler (1999) on oriented boxes and triboxes, beside
//!   the engine's axis-aligned [`crate::views::projected_area`].
//! - [`stiff`]: stiff and extreme scenes (issue 15), ten families each with a stiffness `k`
//!   and a seed (near-coplanar faces, slivers, huge offsets and scales, edge-on faces, fans,
//!   nested, touching, tangent and inside-out solids), to measure how drawings go wrong
//!   where floating point decides; `kepler gen` writes them as scene files.
//!
//! ```
//! use kepler::lab::oriented::OrientedBox;
//! use kepler::geometry::Aabb;
//! let b = OrientedBox::from_aabb(&Aabb { min: [0.0; 3], max: [1.0, 2.0, 3.0] });
//! assert!(!b.is_empty());
//! ```

pub mod boxtree;
pub mod culling;
pub mod oriented;
pub mod projected_area;
pub mod report;
pub mod stiff;
pub mod tribox_hierarchy;
