//! # kepler — an exact visibility engine for scenes of polyhedra
//!
//! The engine follows W.R. Franklin's KEPLER (1981): a hierarchical scene graph whose objects
//! each keep a circumscribing box (CBOX), an inscribing box (INBOX) and, after Crosnier and
//! Rossignac (1999), a tribox. Every sign (orientation, side of a plane, inside or outside) is
//! decided with exact predicates; every constructed point is computed once, in `f64`, from input
//! coordinates.
//!
//! Modules, with dependencies pointing one way (each uses only those above it):
//! - [`geometry`]: points, exact predicates and exact sums, polygons.
//! - [`grid`]: Franklin's uniform grid: every intersecting pair of segments in the plane.
//! - [`clip`]: boolean operations on polygons (intersection, difference, union), to an ulp.
//! - [`mesh`]: validated polygon meshes (faces, planes, texture coordinate systems, topology).
//! - [`io`]: mesh files (OBJ, STL, OFF).
//! - [`solids`]: built-in closed solids (box, Platonic, Archimedean, prism, sphere, torus, cylinder).
//! - [`bounds`]: CBOX, INBOX and TRIBOX.
//! - [`scene`]: the scene graph, instancing, flattening and the scene file.
//! - [`views`]: orthographic and perspective views, and exact predicates with the eye.
//! - [`queries`]: INCLUDE and VISP through the hierarchy, batch INCLUDE, ray shooting.
//! - [`hidden`]: exact hidden-line drawings (edge classes, intersection lines, visibility).
//! - [`surfaces`]: visible surfaces, Franklin's VISFAC: the visible part of a face as polygons.
//!
//! ```
//! use kepler::solids;
//! let cube = solids::cube(2.0).unwrap();
//! assert_eq!(cube.faces().len(), 6);
//! assert!((cube.volume() - 8.0).abs() < 1e-12);
//! ```

pub mod bounds;
pub mod clip;
pub mod error;
pub mod geometry;
pub mod grid;
pub mod hidden;
pub mod io;
pub mod lab;
pub mod mesh;
pub mod output;
pub mod queries;
pub mod scene;
pub mod solids;
pub mod surfaces;
pub mod views;

pub use error::{Error, Result};
