//! Built-in closed solids: boxes, the 5 Platonic and 13 Archimedean solids (KEPLER's "database
//! of all the semiregular polyhedra"), prisms over simple polygons, and faceted spheres, tori
//! and cylinders.
//!
//! Every solid is a validated [`Mesh`] that is closed and consistently oriented, with faces
//! counter-clockwise seen from outside. Faces are given as polygons (a cube has 6 quads, a
//! dodecahedron 12 pentagons, a prism's caps are single polygons), not triangulated; a polygon
//! that rounding leaves not exactly planar is split into triangle faces
//! ([`Mesh::split_polygons`]), and [`Mesh::polygons`] gives the polygons back.
//!
//! - [`Polyhedron`]: the 18 Platonic and Archimedean solids, centred at the origin, at any
//!   edge length, with their counts and closed-form volumes and surface areas;
//!   [`cube`], [`tetrahedron`], [`octahedron`], [`dodecahedron`] and [`icosahedron`] are
//!   shorthands, [`cuboid`] is a box with three edge lengths.
//! - [`prism`]: a simple polygon extruded along z.
//! - [`uv_sphere`], [`torus`], [`cylinder`]: solids of revolution with planar quad faces.
//!
//! Parameters are checked and a bad one is reported as [`SolidError::InvalidParameter`];
//! nothing panics, whatever the values.
//!
//! ```
//! use kepler::solids::{self, Polyhedron};
//! let c = solids::cube(2.0).unwrap();
//! assert_eq!(c.faces().len(), 6);
//! assert!((c.volume() - 8.0).abs() < 1e-12);
//! let ti = Polyhedron::TruncatedIcosahedron.mesh(1.0).unwrap();
//! assert_eq!(ti.polygons().len(), 32);
//! let e = solids::uv_sphere(1.0, 2, 8).unwrap_err();
//! assert_eq!(e.to_string(), "sphere: segments must be at least 3, got 2");
//! ```

mod coordinates;
mod hull;
mod polyhedron;
mod prism;
mod round;

pub use polyhedron::Polyhedron;
pub use prism::prism;
pub use round::{cylinder, torus, uv_sphere};

use crate::geometry::{Point3, Vector3};
use crate::mesh::{Mesh, MeshError, Validation};

/// The largest number of faces a sphere or torus may have; larger requests are errors.
///
/// ```
/// use kepler::solids::{MAX_FACES, torus};
/// assert_eq!(MAX_FACES, 1_000_000);
/// assert!(torus(2.0, 1.0, 1001, 1000).is_err());
/// ```
pub const MAX_FACES: u64 = 1_000_000;

/// The largest number of vertices of a single polygon face: of a cylinder's caps and of a
/// prism's outline. (Validating a face costs time quadratic in its number of vertices.)
///
/// ```
/// use kepler::solids::{MAX_POLYGON_VERTICES, cylinder};
/// assert_eq!(MAX_POLYGON_VERTICES, 10_000);
/// assert!(cylinder(1.0, 1.0, 10_001).is_err());
/// ```
pub const MAX_POLYGON_VERTICES: usize = 10_000;

/// Why a solid could not be built.
///
/// ```
/// use kepler::solids::{self, SolidError};
/// let e = solids::cube(-1.0).unwrap_err();
/// assert!(matches!(e, SolidError::InvalidParameter { solid: "cube", parameter: "edge", .. }));
/// assert_eq!(e.to_string(), "cube: edge must be a finite number greater than 0, got -1");
/// ```
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum SolidError {
    /// A size or count outside its allowed range.
    #[error("{solid}: {parameter} must be {requirement}, got {value}")]
    InvalidParameter {
        /// The solid (`"sphere"`, `"torus"`, a polyhedron's name, ...).
        solid: &'static str,
        /// The parameter (`"radius"`, `"segments"`, ...).
        parameter: &'static str,
        /// The value given, as text.
        value: String,
        /// What the value must be (`"at least 3"`, ...).
        requirement: String,
    },
    /// A prism's outline is not a simple polygon without holes.
    #[error("prism: the outline {problem}")]
    InvalidOutline {
        /// What is wrong with it.
        problem: String,
    },
    /// The mesh built from the parameters is invalid (sizes so small or so large that faces
    /// degenerate or coordinates leave the accepted range).
    #[error(transparent)]
    Mesh(#[from] MeshError),
}

/// A cube with the given edge length, centred at the origin, with axis-aligned faces.
///
/// ```
/// let c = kepler::solids::cube(3.0).unwrap();
/// assert_eq!((c.vertices().len(), c.faces().len()), (8, 6));
/// assert!((c.volume() - 27.0).abs() < 1e-12);
/// ```
pub fn cube(edge: f64) -> Result<Mesh, SolidError> {
    Polyhedron::Cube.mesh(edge)
}

/// A regular tetrahedron with the given edge length, centred at the origin.
///
/// ```
/// let t = kepler::solids::tetrahedron(1.0).unwrap();
/// assert_eq!(t.faces().len(), 4);
/// assert!((t.volume() - 1.0 / (6.0 * 2f64.sqrt())).abs() < 1e-15);
/// ```
pub fn tetrahedron(edge: f64) -> Result<Mesh, SolidError> {
    Polyhedron::Tetrahedron.mesh(edge)
}

/// A regular octahedron with the given edge length, centred at the origin.
///
/// ```
/// let o = kepler::solids::octahedron(1.0).unwrap();
/// assert_eq!(o.faces().len(), 8);
/// assert!((o.volume() - 2f64.sqrt() / 3.0).abs() < 1e-15);
/// ```
pub fn octahedron(edge: f64) -> Result<Mesh, SolidError> {
    Polyhedron::Octahedron.mesh(edge)
}

/// A regular dodecahedron (12 pentagons) with the given edge length, centred at the origin.
///
/// ```
/// let d = kepler::solids::dodecahedron(1.0).unwrap();
/// assert!(d.polygons().iter().all(|f| f.len() == 5));
/// ```
pub fn dodecahedron(edge: f64) -> Result<Mesh, SolidError> {
    Polyhedron::Dodecahedron.mesh(edge)
}

/// A regular icosahedron (20 triangles) with the given edge length, centred at the origin.
///
/// ```
/// let i = kepler::solids::icosahedron(2.0).unwrap();
/// assert_eq!((i.vertices().len(), i.faces().len()), (12, 20));
/// ```
pub fn icosahedron(edge: f64) -> Result<Mesh, SolidError> {
    Polyhedron::Icosahedron.mesh(edge)
}

/// An axis-aligned box with edge lengths `size.x`, `size.y`, `size.z`, centred at the origin:
/// 6 quads, in the order −x, +x, −y, +y, −z, +z.
///
/// ```
/// use kepler::geometry::Vector3;
/// let b = kepler::solids::cuboid(Vector3::new(1.0, 2.0, 4.0)).unwrap();
/// assert_eq!(b.faces().len(), 6);
/// assert_eq!(b.volume(), 8.0);
/// assert!(kepler::solids::cuboid(Vector3::new(1.0, 0.0, 1.0)).is_err());
/// ```
pub fn cuboid(size: Vector3) -> Result<Mesh, SolidError> {
    let x = positive("cuboid", "size.x", size.x)? / 2.0;
    let y = positive("cuboid", "size.y", size.y)? / 2.0;
    let z = positive("cuboid", "size.z", size.z)? / 2.0;
    box_between([-x, -y, -z], [x, y, z])
}

/// The axis-aligned box with corners `min` and `max`, exactly (no arithmetic on the
/// coordinates): 6 quads in the order −x, +x, −y, +y, −z, +z, turned outward. An error if it is
/// flat (a face without area) or a coordinate is not finite.
///
/// ```
/// let b = kepler::solids::box_between([0.0, 0.0, 0.0], [1.0, 2.0, 0.1]).unwrap();
/// assert_eq!(kepler::bounds::cbox(&b).max, [1.0, 2.0, 0.1]);
/// assert!(kepler::solids::box_between([0.0; 3], [1.0, 0.0, 1.0]).is_err());
/// ```
pub fn box_between(min: [f64; 3], max: [f64; 3]) -> Result<Mesh, SolidError> {
    // Vertex k takes max along axis i when bit i of k is set.
    let vertices = (0..8)
        .map(|k| {
            let c = |i: usize| if k & (1 << i) != 0 { max[i] } else { min[i] };
            Point3::new(c(0), c(1), c(2))
        })
        .collect();
    let faces = vec![
        vec![0, 4, 6, 2],
        vec![1, 3, 7, 5],
        vec![0, 1, 5, 4],
        vec![2, 6, 7, 3],
        vec![0, 2, 3, 1],
        vec![4, 5, 7, 6],
    ];
    // Its faces are exactly planar; strict validation refuses a flat box's degenerate faces.
    Ok(Mesh::from_polygons_with(
        vertices,
        faces,
        Validation::Strict,
    )?)
}

/// `value` if it is finite and greater than 0, else the error naming `solid` and `parameter`.
fn positive(solid: &'static str, parameter: &'static str, value: f64) -> Result<f64, SolidError> {
    if value.is_finite() && value > 0.0 {
        Ok(value)
    } else {
        Err(invalid(
            solid,
            parameter,
            show(value),
            "a finite number greater than 0",
        ))
    }
}

/// `value` as a `usize` if it is at least `min`, else the error.
fn at_least(
    solid: &'static str,
    parameter: &'static str,
    value: u32,
    min: u32,
) -> Result<usize, SolidError> {
    if value >= min {
        Ok(value as usize)
    } else {
        Err(invalid(
            solid,
            parameter,
            value.to_string(),
            format!("at least {min}"),
        ))
    }
}

/// Checks that `count` (named by `parameter`) is at most `max`.
fn at_most(
    solid: &'static str,
    parameter: &'static str,
    count: u64,
    max: u64,
) -> Result<(), SolidError> {
    if count <= max {
        Ok(())
    } else {
        Err(invalid(
            solid,
            parameter,
            count.to_string(),
            format!("at most {max}"),
        ))
    }
}

/// An [`SolidError::InvalidParameter`].
fn invalid(
    solid: &'static str,
    parameter: &'static str,
    value: String,
    requirement: impl Into<String>,
) -> SolidError {
    SolidError::InvalidParameter {
        solid,
        parameter,
        value,
        requirement: requirement.into(),
    }
}

/// A number as text for messages: plain for ordinary magnitudes, in exponent form for very
/// large or very small ones (plain `Display` prints 1e300 with 301 digits).
fn show(x: f64) -> String {
    if x.is_finite() && x != 0.0 && !(1e-4..1e15).contains(&x.abs()) {
        format!("{x:e}")
    } else {
        format!("{x}")
    }
}
