//! Validated polygon meshes: the vertices and faces of a leaf object (Franklin's VERT and FACE).
//!
//! [`Mesh::from_polygons`] checks everything the engine relies on and says what is wrong with
//! which vertex or face: finite coordinates of at most [`MAX_COORDINATE`] in magnitude, faces
//! of at least 3 distinct vertices with valid indices, no zero-area faces, faces planar within
//! [`PLANARITY_TOLERANCE`] of their size, and simple (not self-crossing). Vertices with exactly
//! equal coordinates are merged, as the paper requires ("no two vertices may have the same
//! coordinates"); the number merged is kept ([`Mesh::merged_vertices`]).
//!
//! ```
//! use kepler::{mesh::Mesh, geometry::Point3};
//! let v = vec![
//!     Point3::new(0.0, 0.0, 0.0), Point3::new(1.0, 0.0, 0.0),
//!     Point3::new(0.0, 1.0, 0.0), Point3::new(0.0, 0.0, 1.0),
//! ];
//! let tet = Mesh::from_polygons(v, vec![vec![0, 2, 1], vec![0, 1, 3], vec![1, 2, 3], vec![0, 3, 2]]).unwrap();
//! assert!(tet.topology().closed);
//! assert!((tet.volume() - 1.0 / 6.0).abs() < 1e-15);
//! ```

mod containment;
mod face;
mod topology;
mod tree;

pub use containment::{
    Containment, classify_among, classify_point, classify_point_brute_force, crosses_column,
};
pub use face::{Face, Plane, TextureFrame};
pub use topology::Topology;
pub use tree::TriangleTree;

use crate::geometry::polygon::{newell_normal, triangulate};
use crate::geometry::predicates::{MAX_COORDINATE, collinear};
use crate::geometry::{Point3, Vector3};
use nalgebra::Matrix4;

/// Faces may deviate from their plane by at most this fraction of their size (the diagonal of
/// their bounding box). Exported meshes often print coordinates with 6 to
/// 9 significant digits, so quads are planar only to about that precision; beyond it a face
/// is rejected as non-planar. The exact predicates treat each face as its triangulation, so a
/// face within the tolerance is still handled exactly.
///
/// ```
/// assert_eq!(kepler::mesh::PLANARITY_TOLERANCE, 1e-6);
/// ```
pub const PLANARITY_TOLERANCE: f64 = 1e-6;

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
    /// A coordinate is larger in magnitude than [`MAX_COORDINATE`].
    #[error(
        "vertex {} has a coordinate larger than 1e100 in magnitude (exact predicates could overflow)", vertex + 1)]
    OutOfRange {
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
    /// coordinates).
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
    /// A face has zero area: its vertices are collinear, or its loop cancels itself.
    #[error("face {} has zero area", face + 1)]
    ZeroArea {
        /// The face.
        face: usize,
    },
    /// A face is not planar within [`PLANARITY_TOLERANCE`].
    #[error(
        "face {} is not planar: a vertex is {deviation:.3e} of the face's size off its plane (tolerance 1e-6)", face + 1
    )]
    NonPlanar {
        /// The face.
        face: usize,
        /// The largest distance of a vertex from the plane, relative to the face's size.
        deviation: f64,
    },
    /// A face crosses or overlaps itself.
    #[error("face {} crosses or overlaps itself", face + 1)]
    NotSimple {
        /// The face.
        face: usize,
    },
    /// A transform that squashes space flat (zero determinant) or is not finite.
    #[error("the transform is singular or not finite")]
    SingularTransform,
}

/// A validated polygon mesh: vertices without duplicates, planar simple faces with their
/// planes, texture systems and triangulations, and its edge [`Topology`].
///
/// ```
/// let c = kepler::solids::cube(1.0).unwrap();
/// assert_eq!((c.vertices().len(), c.faces().len(), c.triangles().len()), (8, 6, 12));
/// assert_eq!(c.surface_area(), 6.0);
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct Mesh {
    vertices: Vec<Point3>,
    faces: Vec<Face>,
    triangles: Vec<[u32; 3]>,
    topology: Topology,
    merged_vertices: usize,
}

impl Mesh {
    /// Builds a mesh from vertices and faces (each a loop of vertex indices, counter-clockwise
    /// seen from outside), validating them and merging vertices with equal coordinates.
    ///
    /// ```
    /// use kepler::{mesh::{Mesh, MeshError}, geometry::Point3};
    /// let v = vec![Point3::new(0.0, 0.0, 0.0), Point3::new(1.0, 0.0, 0.0), Point3::new(2.0, 0.0, 0.0)];
    /// assert_eq!(Mesh::from_polygons(v, vec![vec![0, 1, 2]]), Err(MeshError::ZeroArea { face: 0 }));
    /// ```
    pub fn from_polygons(vertices: Vec<Point3>, faces: Vec<Vec<u32>>) -> Result<Mesh, MeshError> {
        let (vertices, remap, merged_vertices) = merge_duplicates(vertices)?;
        let mut out_faces = Vec::with_capacity(faces.len());
        let mut triangles = Vec::with_capacity(faces.len() * 2);
        for (fi, face) in faces.into_iter().enumerate() {
            if face.len() < 3 {
                return Err(MeshError::TooFewVertices {
                    face: fi,
                    count: face.len(),
                });
            }
            let mut idx = Vec::with_capacity(face.len());
            for &i in &face {
                let Some(&j) = remap.get(i as usize) else {
                    return Err(MeshError::IndexOutOfRange {
                        face: fi,
                        index: i64::from(i),
                        vertex_count: remap.len(),
                    });
                };
                idx.push(j);
            }
            let (face, tris) = build_face(&vertices, idx, fi, triangles.len())?;
            triangles.extend(tris);
            out_faces.push(face);
        }
        let topology = Topology::of_faces(out_faces.iter().map(|f| f.vertices()));
        Ok(Mesh {
            vertices,
            faces: out_faces,
            triangles,
            topology,
            merged_vertices,
        })
    }

    /// The vertices, without duplicates.
    ///
    /// ```
    /// assert_eq!(kepler::solids::tetrahedron(1.0).unwrap().vertices().len(), 4);
    /// ```
    pub fn vertices(&self) -> &[Point3] {
        &self.vertices
    }

    /// The faces.
    ///
    /// ```
    /// assert_eq!(kepler::solids::octahedron(1.0).unwrap().faces().len(), 8);
    /// ```
    pub fn faces(&self) -> &[Face] {
        &self.faces
    }

    /// The triangles of all faces (each face's range is [`Face::triangle_range`]), oriented
    /// like their faces. Exact predicates treat a face as these triangles.
    ///
    /// ```
    /// assert_eq!(kepler::solids::dodecahedron(1.0).unwrap().triangles().len(), 36);
    /// ```
    pub fn triangles(&self) -> &[[u32; 3]] {
        &self.triangles
    }

    /// The three corners of triangle `t`.
    ///
    /// ```
    /// let c = kepler::solids::cube(1.0).unwrap();
    /// let [a, b, d] = c.triangle(0);
    /// assert!((b - a).cross(&(d - a)).norm() > 0.0);
    /// ```
    pub fn triangle(&self, t: usize) -> [Point3; 3] {
        self.triangles[t].map(|i| self.vertices[i as usize])
    }

    /// The index of the face that triangle `t` (of [`Mesh::triangles`]) belongs to: faces'
    /// triangles are stored in face order, so a binary search over their ranges finds it.
    ///
    /// ```
    /// let cube = kepler::solids::cube(1.0).unwrap();
    /// assert_eq!((cube.face_of(0), cube.face_of(1), cube.face_of(11)), (0, 0, 5));
    /// ```
    pub fn face_of(&self, t: usize) -> usize {
        self.faces.partition_point(|f| f.triangle_range().end <= t)
    }

    /// The edge structure: closed, consistently oriented, boundary and non-manifold edges.
    ///
    /// ```
    /// assert!(kepler::solids::cube(1.0).unwrap().topology().closed);
    /// ```
    pub fn topology(&self) -> Topology {
        self.topology
    }

    /// Whether the mesh bounds a solid: closed and consistently oriented.
    ///
    /// ```
    /// assert!(kepler::solids::cube(1.0).unwrap().is_solid());
    /// ```
    pub fn is_solid(&self) -> bool {
        self.topology.closed && self.topology.consistently_oriented
    }

    /// How many input vertices were merged into others with equal coordinates.
    ///
    /// ```
    /// use kepler::{mesh::Mesh, geometry::Point3};
    /// let p = |x: f64, y: f64| Point3::new(x, y, 0.0);
    /// let m = Mesh::from_polygons(
    ///     vec![p(0.0, 0.0), p(1.0, 0.0), p(0.0, 1.0), p(1.0, 0.0), p(1.0, 1.0), p(0.0, 1.0)],
    ///     vec![vec![0, 1, 2], vec![3, 4, 5]],
    /// ).unwrap();
    /// assert_eq!((m.vertices().len(), m.merged_vertices()), (4, 2));
    /// ```
    pub fn merged_vertices(&self) -> usize {
        self.merged_vertices
    }

    /// The signed volume enclosed (divergence theorem over the triangles): positive for a
    /// closed mesh whose faces point outward, negative for one turned inside out. Meaningful
    /// only for closed meshes.
    ///
    /// ```
    /// assert!((kepler::solids::cube(3.0).unwrap().volume() - 27.0).abs() < 1e-12);
    /// ```
    pub fn volume(&self) -> f64 {
        let Some(o) = self.vertices.first() else {
            return 0.0;
        };
        let six_v: f64 = self
            .triangles
            .iter()
            .map(|t| {
                let [a, b, c] = t.map(|i| self.vertices[i as usize] - o);
                a.dot(&b.cross(&c))
            })
            .sum();
        six_v / 6.0
    }

    /// The total area of the faces.
    ///
    /// ```
    /// assert_eq!(kepler::solids::cube(2.0).unwrap().surface_area(), 24.0);
    /// ```
    pub fn surface_area(&self) -> f64 {
        self.faces.iter().map(Face::area).sum()
    }

    /// The vertices of face `f`, in order.
    ///
    /// ```
    /// let c = kepler::solids::cube(1.0).unwrap();
    /// assert_eq!(c.face_points(0).count(), 4);
    /// ```
    pub fn face_points(&self, f: usize) -> impl Iterator<Item = Point3> + '_ {
        self.faces[f]
            .vertices
            .iter()
            .map(|&i| self.vertices[i as usize])
    }

    /// The mesh under an affine transform (a 4×4 matrix whose last row is `0 0 0 1`): each
    /// vertex is transformed once from its coordinates; a transform that mirrors space
    /// reverses the faces so that they still point outward. The result is validated again.
    ///
    /// ```
    /// use nalgebra::Matrix4;
    /// let c = kepler::solids::cube(1.0).unwrap();
    /// let m = Matrix4::new_nonuniform_scaling(&nalgebra::Vector3::new(2.0, 3.0, -1.0));
    /// let t = c.transformed(&m).unwrap();
    /// assert!((t.volume() - 6.0).abs() < 1e-12);
    /// ```
    pub fn transformed(&self, m: &Matrix4<f64>) -> Result<Mesh, MeshError> {
        let det = m.fixed_view::<3, 3>(0, 0).determinant();
        if !det.is_finite() || det == 0.0 || m.iter().any(|x| !x.is_finite()) {
            return Err(MeshError::SingularTransform);
        }
        let vertices = self.vertices.iter().map(|p| m.transform_point(p)).collect();
        let faces = self
            .faces
            .iter()
            .map(|f| {
                let mut v = f.vertices.clone();
                if det < 0.0 {
                    v.reverse();
                }
                v
            })
            .collect();
        Mesh::from_polygons(vertices, faces)
    }
}

/// Merges vertices with exactly equal coordinates (`-0.0` equals `0.0`) after checking that
/// they are finite and in range; returns the distinct vertices in first-seen order, the map
/// from input index to output index, and how many were merged.
fn merge_duplicates(
    mut vertices: Vec<Point3>,
) -> Result<(Vec<Point3>, Vec<u32>, usize), MeshError> {
    for (i, p) in vertices.iter_mut().enumerate() {
        if p.iter().any(|c| !c.is_finite()) {
            return Err(MeshError::NonFinite { vertex: i });
        }
        if p.iter().any(|c| c.abs() > MAX_COORDINATE) {
            return Err(MeshError::OutOfRange { vertex: i });
        }
        // Adding +0.0 turns -0.0 into +0.0, so both sort and compare as one value.
        p.apply(|c| *c += 0.0);
    }
    let key = |p: &Point3| (p.x.to_bits(), p.y.to_bits(), p.z.to_bits());
    let mut order: Vec<u32> = (0..vertices.len() as u32).collect();
    order.sort_unstable_by(|&a, &b| {
        let (pa, pb) = (&vertices[a as usize], &vertices[b as usize]);
        pa.x.total_cmp(&pb.x)
            .then(pa.y.total_cmp(&pb.y))
            .then(pa.z.total_cmp(&pb.z))
            .then(a.cmp(&b))
    });
    // Representative of each vertex: the first (lowest index) with the same coordinates.
    let mut rep: Vec<u32> = (0..vertices.len() as u32).collect();
    for w in order.chunk_by(|&a, &b| key(&vertices[a as usize]) == key(&vertices[b as usize])) {
        for &i in w {
            rep[i as usize] = w[0];
        }
    }
    let mut remap = vec![0u32; vertices.len()];
    let mut out = Vec::with_capacity(vertices.len());
    for i in 0..vertices.len() {
        if rep[i] as usize == i {
            remap[i] = out.len() as u32;
            out.push(vertices[i]);
        } else {
            remap[i] = remap[rep[i] as usize];
        }
    }
    let merged = vertices.len() - out.len();
    Ok((out, remap, merged))
}

/// Validates one face and computes its plane, texture frame, area and triangles (with
/// indices offset into the mesh's triangle list starting at `first_triangle`).
fn build_face(
    vertices: &[Point3],
    idx: Vec<u32>,
    fi: usize,
    first_triangle: usize,
) -> Result<(Face, Vec<[u32; 3]>), MeshError> {
    let pts: Vec<Point3> = idx.iter().map(|&i| vertices[i as usize]).collect();
    let mut sorted = idx.clone();
    sorted.sort_unstable();
    if let Some(w) = sorted.windows(2).find(|w| w[0] == w[1]) {
        let p = vertices[w[0] as usize];
        return Err(MeshError::RepeatedVertex {
            face: fi,
            x: p.x,
            y: p.y,
            z: p.z,
        });
    }
    let a = &pts[0];
    let b = &pts[1];
    if pts[2..].iter().all(|c| collinear(a, b, c)) {
        return Err(MeshError::ZeroArea { face: fi });
    }
    let n2 = newell_normal(&pts);
    // The face's size: the diagonal of its bounding box (linear time; between its diameter
    // and √3 times it).
    let diameter = crate::geometry::Aabb::from_points(&pts)
        .size()
        .iter()
        .map(|d| d * d)
        .sum::<f64>()
        .sqrt();
    let len = n2.norm();
    if len.is_nan() || len <= 1e-14 * diameter * diameter {
        return Err(MeshError::ZeroArea { face: fi });
    }
    let normal: Vector3 = n2 / len;
    let centroid = pts.iter().fold(Vector3::zeros(), |s, p| s + p.coords) / pts.len() as f64;
    let deviation = pts
        .iter()
        .map(|p| (p.coords - centroid).dot(&normal).abs())
        .fold(0.0, f64::max)
        / diameter;
    if deviation > PLANARITY_TOLERANCE {
        return Err(MeshError::NonPlanar {
            face: fi,
            deviation,
        });
    }
    let local = triangulate(&pts, &normal).map_err(|_| MeshError::NotSimple { face: fi })?;
    let tris: Vec<[u32; 3]> = local.iter().map(|t| t.map(|k| idx[k])).collect();
    let d = -normal.dot(&centroid);
    let horizontal = pts.iter().all(|p| p.z == a.z);
    let face = Face {
        texture: TextureFrame::new(&normal, d, horizontal),
        plane: Plane::new(normal, d),
        area: len / 2.0,
        triangles: first_triangle..first_triangle + tris.len(),
        vertices: idx,
    };
    Ok((face, tris))
}
