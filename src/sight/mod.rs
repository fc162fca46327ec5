//! Lines of sight: the geometry that the two drawing layers (`hidden` and `surfaces`) and the
//! point queries ask of a segment, a line or a pair of meshes, exactly.
//!
//! Everything here is a sign or a construction on the exact description of a thing, never on
//! a rounded point: an input edge, the meet line of two input planes, a cut by an exact form.
//!
//! - [`along`]: a plane's form at a point of an edge, its exact sign, and the picture of the
//!   point where the edge crosses the plane, built once from the input; the [`Formula`]
//!   vocabulary for polynomials written once over any ring.
//! - [`meet`]: the line where the planes of two faces meet, its points, their order along it,
//!   and the pictures of its cuts.
//! - [`intersections`]: the lines where two meshes' faces pierce each other (a uniform 3-D
//!   grid for candidate pairs, then exact tests).
//! - [`own_solid`]: the faces a solid seen from outside hides by itself.
//! - [`collinear`]: whether two lines' pictures lie on one line of the picture, and the order
//!   of points along it.
//! - [`frustum`]: the forms of the frustum both drawing layers clip to when a perspective eye
//!   is inside the scene.
//! - [`line`]: a line of sight (or a ray) against boxes, the hierarchy's safe filters.
//! - [`range`]: the power of two that brings a scene of extreme coordinates into the range
//!   where the kernel is exact.
//! - [`ratio`]: ratios of exact polynomials as doubles (each rounded once, or correctly
//!   rounded).
//!
//! The layer sits after the grid and before the queries (INCLUDE, VISP, ray shooting), which
//! use its lines of sight; it is internal to the crate.
//!
//! [`Formula`]: along::Formula

pub(crate) mod along;
pub(crate) mod collinear;
pub(crate) mod frustum;
pub(crate) mod intersections;
pub(crate) mod line;
pub(crate) mod meet;
pub(crate) mod own_solid;
pub(crate) mod range;
pub(crate) mod ratio;

pub(crate) use line::Sight;
