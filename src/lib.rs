//! # kepler — an exact visibility engine for scenes of polyhedra
//!
//! The engine follows W.R. Franklin's KEPLER (1981): a hierarchical scene graph whose objects
//! each keep a circumscribing box (CBOX), an inscribing box (INBOX) and, after Crosnier and
//! Rossignac (1999), a tribox. Every sign (orientation, side of a plane, inside or outside) is
//! decided with exact predicates; every constructed point is computed once, in `f64`, from input
//! coordinates.
//!
//! ## Layers
//!
//! The engine is built in layers; each module imports only the modules of the layers above
//! it in this picture (`tests/layering.rs` keeps it so), and none imports the lab.
//!
//! ```text
//!  random,    the one seeded generator (SplitMix64); disjoint sets
//!  union_find (internal)
//!     │
//!  geometry   the exact kernel: points, boxes, predicates, expansions,   Shewchuk 1997
//!             rays; the one place that knows about rounding
//!  clip       polygon booleans to an ulp (with the lab)
//!     │
//!  mesh, io,  validated polygon meshes, mesh files, built-in solids      Franklin: faces
//!  solids                                                                and textures
//!     │
//!  bounds     CBOX, INBOX and TRIBOX of one object                       Franklin; Crosnier
//!     │                                                                  and Rossignac
//!  scene,     the scene graph, instancing, scene files; views, the       Franklin: objects;
//!  views      picture map, projected box areas                           Schmalstieg–Tobler
//!     │
//!  grid       the uniform grid of segments                               Franklin: grid
//!     │
//!  sight      lines of sight: exact forms along edges, meet lines,
//!             intersection lines, the frustum (internal)
//!     │
//!  queries    INCLUDE, VISP, ray shooting                                Franklin:
//!                                                                        algorithms A, B
//!     │
//!  hidden,    hidden lines (and ideographs); visible surfaces, VISFAC    Franklin: HALO,
//!  surfaces   and VISOBJ                                                 algorithms C–E
//!     │
//!  output     SVG and JSON
//!     │
//!  error      every layer's error, wrapped
//!  ─────────────────────────────────────────────────────────────────────────────────────
//!  lab        the papers' experiments: BOXTREE hierarchies, hierarchical  Barequet et al.;
//!             triboxes, culling tables, oriented boxes                    Crosnier–Rossignac
//! ```
//!
//! - [`random`]: the seeded generator of every random scene, test and benchmark.
//! - [`geometry`]: points, [`geometry::kernel`] (polynomials, exact expansions, estimates; the
//!   report's cheaper arithmetic on threads of its own), exact predicates, polygons, rays.
//! - [`clip`]: boolean operations on polygons (intersection, difference, union), to an ulp.
//! - [`mesh`]: validated polygon meshes (faces, planes, texture coordinate systems, topology).
//! - [`io`]: mesh files (OBJ, STL, OFF, PLY) and point files.
//! - [`solids`]: built-in closed solids (box, Platonic, Archimedean, prism, sphere, torus,
//!   cylinder).
//! - [`bounds`]: CBOX, INBOX and TRIBOX of one object.
//! - [`scene`]: the scene graph, instancing, flattening and the scene file.
//! - [`views`]: orthographic and perspective views, exact predicates with the eye, the
//!   picture map, projected areas of boxes.
//! - [`grid`]: Franklin's uniform grid: every intersecting pair of segments in the plane.
//! - [`queries`]: INCLUDE and VISP through the hierarchy, batch INCLUDE, ray shooting.
//! - [`hidden`]: exact hidden-line drawings (edge classes, intersection lines, visibility).
//! - [`surfaces`]: visible surfaces, Franklin's VISFAC: the visible part of a face as polygons.
//! - [`output`]: drawings and visible surfaces as SVG and JSON.
//! - [`error`]: [`Error`], which wraps each layer's typed error.
//! - [`lab`]: the papers' experiments, which the engine never uses.
//!
//! ```
//! use kepler::solids;
//! let cube = solids::cube(2.0).unwrap();
//! assert_eq!(cube.faces().len(), 6);
//! assert!((cube.volume() - 8.0).abs() < 1e-12);
//! ```
//!
//! The root re-exports what a user reaches for first: a [`Scene`] (loaded with [`load`]), a
//! [`View`], [`draw`] with its [`Options`] giving a [`Drawing`], and Franklin's queries
//! [`include`], [`visp`], [`visobj`] and [`visfac`].
//!
//! ```
//! use kepler::{Inclusion, Options, Point3, Scene, Vector3, View, draw, include};
//! let mut scene = Scene::new();
//! let cube = scene.add_mesh(None, "cube", kepler::solids::cube(2.0)?)?;
//! let view = View::orthographic(Vector3::new(-1.0, -2.0, -3.0), Vector3::z())?;
//! let drawing = draw(&scene, &view, &Options::default())?;
//! assert!(!drawing.polylines.is_empty());
//! let (inside, _) = include(&scene, cube, &Point3::new(0.5, 0.5, 0.5))?;
//! assert_eq!(inside, Inclusion::In);
//! # Ok::<(), kepler::Error>(())
//! ```

#![deny(missing_docs)]
#![forbid(unsafe_code)]
// Every dependency is used where it is declared (features included); the test build links
// the dev-dependencies too, so the lint is off there.
#![cfg_attr(not(test), warn(unused_crate_dependencies))]

pub mod bounds;
#[cfg(feature = "lab")]
pub mod clip;
pub mod error;
pub(crate) mod fnv;
pub mod geometry;
pub mod grid;
pub mod hidden;
pub mod io;
#[cfg(feature = "lab")]
pub mod lab;
pub(crate) mod le;
pub mod mesh;
pub mod output;
pub mod queries;
pub mod random;
pub mod scene;
pub(crate) mod sight;
pub mod solids;
pub mod surfaces;
pub(crate) mod union_find;
pub mod views;

pub use error::{Error, Result};

// The curated root (after rstar's): what a user of the library reaches for first, one `use`
// away. Everything else stays in its module, documented there.
pub use geometry::{Aabb, Point3, Vector3};
pub use hidden::{Drawing, EdgeClass, EdgeSelection, Options, Overlaps, Polyline, draw};
pub use mesh::Mesh;
pub use queries::include::{IncludeIndex, Inclusion, include};
pub use queries::visp::{Visibility, VisibilityIndex, visp};
pub use scene::file::load;
pub use scene::{Camera, ObjectId, Scene};
pub use surfaces::{Status, VisibleFace, visfac, visible_surfaces, visobj};
pub use views::{Eye, View};

// Dependencies of the command line (feature `cli`) that only the binary uses.
#[cfg(feature = "cli")]
use {anyhow as _, indicatif as _};
