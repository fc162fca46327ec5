//! What validation does with faces that are valid input but not faces as they are
//! ([`Validation`]), and what is wrong with a mesh it refuses ([`MeshError`]).

/// What [`Mesh::from_polygons_with`](super::Mesh::from_polygons_with) does with input faces
/// that are valid but not faces as they are: degenerate ones (a repeated vertex, zero area)
/// and polygons that are not exactly planar.
///
/// ```
/// use kepler::{mesh::{Mesh, MeshError, Validation}, geometry::Point3};
/// let p = |x: f64, y: f64, z: f64| Point3::new(x, y, z);
/// let bent = vec![p(0., 0., 0.), p(1., 0., 0.), p(1., 1., 1e-12), p(0., 1., 0.)];
/// let m = Mesh::from_polygons_with(bent.clone(), vec![vec![0, 1, 2, 3]], Validation::Repair).unwrap();
/// assert_eq!((m.faces().len(), m.split_polygons()), (2, 1));
/// let e = Mesh::from_polygons_with(bent, vec![vec![0, 1, 2, 3]], Validation::Strict).unwrap_err();
/// assert_eq!(e, MeshError::NonPlanar { face: 0, corner: 3 });
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Validation {
    /// Drop degenerate faces and split polygons that are not exactly planar into triangles,
    /// counting both ([`Mesh::degenerate_faces`](super::Mesh::degenerate_faces),
    /// [`Mesh::split_polygons`](super::Mesh::split_polygons)).
    #[default]
    Repair,
    /// Refuse them: [`MeshError::RepeatedVertex`], [`MeshError::ZeroArea`],
    /// [`MeshError::NonPlanar`].
    Strict,
}

/// What is wrong with a mesh, naming the vertex or face: indices are 0-based in input order,
/// messages number from 1 (the first face is "face 1").
///
/// ```
/// use kepler::{mesh::{Mesh, MeshError}, geometry::Point3};
/// let v = vec![Point3::new(0.0, 0.0, 0.0), Point3::new(1.0, 0.0, 0.0)];
/// let e = Mesh::from_polygons(v, vec![vec![0, 1]]).unwrap_err();
/// assert_eq!(e, MeshError::TooFewVertices { face: 0, count: 2 });
/// ```
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum MeshError {
    /// A coordinate is NaN or infinite.
    #[error("vertex {} has a coordinate that is not a finite number", vertex + 1)]
    NonFinite {
        /// The vertex.
        vertex: usize,
    },
    /// A face has fewer than 3 vertices.
    #[error("face {} has {count} vertices; a face needs at least 3", face + 1)]
    TooFewVertices {
        /// The face.
        face: usize,
        /// How many it has.
        count: usize,
    },
    /// A face refers to a vertex that does not exist.
    #[error("face {} refers to vertex {} but there are only {vertex_count} vertices", face + 1, index + 1)]
    IndexOutOfRange {
        /// The face.
        face: usize,
        /// The offending index (0-based).
        index: i64,
        /// Number of vertices.
        vertex_count: usize,
    },
    /// A face visits the same point twice (the same index, or two vertices with equal
    /// coordinates). Refused only by [`Validation::Strict`].
    #[error("face {} visits the point ({x}, {y}, {z}) twice", face + 1)]
    RepeatedVertex {
        /// The face.
        face: usize,
        /// Coordinates of the repeated point.
        x: f64,
        /// y.
        y: f64,
        /// z.
        z: f64,
    },
    /// A face has zero area: its vertices are exactly collinear. Refused only by
    /// [`Validation::Strict`].
    #[error("face {} has zero area", face + 1)]
    ZeroArea {
        /// The face.
        face: usize,
    },
    /// A polygon is not exactly planar. Refused only by [`Validation::Strict`].
    #[error(
        "face {} is not planar: its corner {} is off the plane of its first corners", face + 1, corner + 1
    )]
    NonPlanar {
        /// The face.
        face: usize,
        /// The first corner (0-based, in the face's order) off the plane of the first two and
        /// the first corner not on their line.
        corner: usize,
    },
    /// A face crosses or overlaps itself (in every projection along a coordinate axis, for a
    /// polygon that is not planar).
    #[error("face {} crosses or overlaps itself", face + 1)]
    NotSimple {
        /// The face.
        face: usize,
    },
    /// A transform that squashes space flat (zero determinant) or is not finite.
    #[error("the transform is singular or not finite")]
    SingularTransform,
}
