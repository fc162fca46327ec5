//! Validated polygon meshes: the vertices and faces of a leaf object (Franklin's VERT and FACE).
//!
//! [`Mesh::from_polygons`] decides everything the engine relies on exactly, at every scale,
//! and says what is wrong with which vertex or face: finite coordinates, faces of at least 3
//! vertices with valid indices, simple (not self-crossing) faces. Vertices with exactly equal
//! coordinates are merged, as the paper requires ("no two vertices may have the same
//! coordinates"); the number merged is kept ([`Mesh::merged_vertices`]).
//!
//! What is valid input but not a face as it is gets repaired, and counted
//! ([`Validation::Repair`]), or refused ([`Validation::Strict`]):
//!
//! - A face that repeats a vertex (the same index, or equal coordinates) or has zero area (its
//!   vertices exactly collinear) is dropped: it hides nothing and has no edges
//!   ([`Mesh::degenerate_faces`]). A vertex repeated in a row is only a zero-length side: the
//!   face without the repetition is kept.
//! - A polygon of more than 3 vertices that is not exactly planar (every vertex on the plane
//!   of three of them, decided by `orient3d`), such as the usual rounding of an exported quad,
//!   is split into triangles in a projection where it is simple, each a face
//!   ([`Mesh::split_polygons`]). The diagonals of the split are edges between two faces like
//!   any other, but not edges of the input polygon ([`Face::is_polygon_edge`]).
//!
//! Where faces meet in T-junctions (a vertex lying exactly inside another face's side, as
//! after a dropped sliver), the side is matched piecewise with the sides that cover it, so
//! such a mesh is closed ([`Topology`]) and draws as the mesh without the junctions.
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

mod buckets;
mod build;
mod containment;
mod face;
mod topology;
mod tree;

pub(crate) use buckets::by_bucket;
pub use containment::{
    Containment, classify_among, classify_point, classify_point_brute_force, crosses_column,
};
pub(crate) use face::Loop;
pub use face::{Face, Plane, TextureFrame};
pub use topology::Topology;
pub(crate) use topology::sort_by_edge;
pub use tree::TriangleTree;

use crate::geometry::Point3;
use crate::geometry::exact::{compress, estimate, expansion_sum};
use crate::geometry::kernel::{
    Estimate, Exponents, Polynomial, UNIT_ROUNDOFF, expansion_sign, sum_error_bound,
};
use crate::geometry::predicates::{Orient3d, orient3d};
use build::{Shape, diagonals_of};
pub(crate) use build::{largest_coordinate, normalising_exponent, times_power_of_two};
use nalgebra::Matrix4;
use num_rational::BigRational;
use num_traits::{ToPrimitive, Zero};
use std::cmp::Ordering;
use topology::Junction;

/// What [`Mesh::from_polygons_with`] does with input faces that are valid but not faces as
/// they are: degenerate ones (a repeated vertex, zero area) and polygons that are not exactly
/// planar.
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
    /// counting both ([`Mesh::degenerate_faces`], [`Mesh::split_polygons`]).
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
    degenerate_faces: usize,
    split_polygons: usize,
    /// The sides of faces cut by vertices lying exactly inside them, by face and side.
    junctions: Vec<Junction>,
}

/// From this many polygons (or triangles) on, a pass over a mesh runs in parallel.
pub(crate) const PARALLEL_POLYGONS: usize = 4096;

/// A polygon to become faces: its vertex loop, which of its sides are diagonals of a split
/// polygon (bit `i`: the side from vertex `i`), and the input polygon it is (part of).
type Polygon = (Loop, u8, u32);

impl Mesh {
    /// Builds a mesh from vertices and faces (each a loop of vertex indices, counter-clockwise
    /// seen from outside), validating them, merging vertices with equal coordinates, dropping
    /// degenerate faces and splitting polygons that are not exactly planar
    /// ([`Validation::Repair`]).
    ///
    /// ```
    /// use kepler::{mesh::{Mesh, MeshError}, geometry::Point3};
    /// let p = |x: f64, y: f64| Point3::new(x, y, 0.0);
    /// // The second face is a line: dropped.
    /// let m = Mesh::from_polygons(vec![p(0., 0.), p(1., 0.), p(0., 1.), p(2., 0.)],
    ///     vec![vec![0, 1, 2], vec![0, 1, 3]]).unwrap();
    /// assert_eq!((m.faces().len(), m.degenerate_faces()), (1, 1));
    /// // A bow tie crosses itself: refused.
    /// let e = Mesh::from_polygons(vec![p(0., 0.), p(1., 1.), p(1., 0.), p(0., 1.)], vec![vec![0, 1, 2, 3]]);
    /// assert_eq!(e, Err(MeshError::NotSimple { face: 0 }));
    /// ```
    pub fn from_polygons(vertices: Vec<Point3>, faces: Vec<Vec<u32>>) -> Result<Mesh, MeshError> {
        Mesh::from_polygons_with(vertices, faces, Validation::Repair)
    }

    /// [`Mesh::from_polygons`] with the given treatment of degenerate faces and polygons that
    /// are not exactly planar: [`Validation::Strict`] refuses them with the error naming the
    /// first.
    ///
    /// ```
    /// use kepler::{mesh::{Mesh, MeshError, Validation}, geometry::Point3};
    /// let v = vec![Point3::new(0.0, 0.0, 0.0), Point3::new(1.0, 0.0, 0.0), Point3::new(2.0, 0.0, 0.0)];
    /// let e = Mesh::from_polygons_with(v, vec![vec![0, 1, 2]], Validation::Strict);
    /// assert_eq!(e, Err(MeshError::ZeroArea { face: 0 }));
    /// ```
    pub fn from_polygons_with(
        vertices: Vec<Point3>,
        faces: Vec<Vec<u32>>,
        validation: Validation,
    ) -> Result<Mesh, MeshError> {
        let loops = faces.iter().map(|f| Loop::from_slice(f)).collect();
        Mesh::from_loops_with(vertices, loops, validation)
    }

    /// [`Mesh::from_polygons_with`] for faces whose loops are already [`Loop`]s (what the
    /// file readers make): a face's loop is renumbered in place, not copied.
    pub(crate) fn from_loops_with(
        vertices: Vec<Point3>,
        faces: Vec<Loop>,
        validation: Validation,
    ) -> Result<Mesh, MeshError> {
        let (vertices, remap, merged_vertices) = build::merge_duplicates(vertices)?;
        let mut polygons = Vec::with_capacity(faces.len());
        for (fi, mut idx) in faces.into_iter().enumerate() {
            if idx.len() < 3 {
                return Err(MeshError::TooFewVertices {
                    face: fi,
                    count: idx.len(),
                });
            }
            for i in idx.iter_mut() {
                let Some(&j) = remap.get(*i as usize) else {
                    return Err(MeshError::IndexOutOfRange {
                        face: fi,
                        index: i64::from(*i),
                        vertex_count: remap.len(),
                    });
                };
                *i = j;
            }
            polygons.push((idx, 0, fi as u32));
        }
        let mut mesh = Mesh::assemble(vertices, polygons, validation)?;
        mesh.merged_vertices = merged_vertices;
        Ok(mesh)
    }

    /// The mesh of the polygons (indices valid, vertices distinct), with their faces,
    /// triangles, counts of repairs, T-junctions and topology.
    fn assemble(
        vertices: Vec<Point3>,
        polygons: Vec<Polygon>,
        validation: Validation,
    ) -> Result<Mesh, MeshError> {
        use rayon::prelude::*;
        // Each polygon validated and made into faces independently, in parallel; the first
        // error by polygon index is reported, whatever the threads; the triangle ranges are
        // assigned in order afterwards.
        type Built = (
            bool,
            bool,
            smallvec::SmallVec<[(Face, build::Triangles); 1]>,
        );
        let one = |(fi, (idx, diagonals, polygon)): (usize, Polygon)| -> Result<Built, MeshError> {
            Ok(match build::shape(&vertices, idx, fi, validation)? {
                Shape::Degenerate => (true, false, smallvec::SmallVec::new()),
                Shape::Planar(idx, local) => {
                    let face = build::face(&vertices, (idx, diagonals, polygon), &local, 0);
                    (false, false, smallvec::smallvec![face])
                }
                Shape::Split(idx, local) => {
                    let faces = local
                        .iter()
                        .map(|t| {
                            let corners = t.iter().map(|&k| idx[k]).collect();
                            build::face(
                                &vertices,
                                (corners, diagonals_of(t, idx.len()), polygon),
                                &[[0, 1, 2]],
                                0,
                            )
                        })
                        .collect();
                    (false, true, faces)
                }
            })
        };
        // In blocks, each in parallel, so that what a block made is moved into place before
        // the next is made; small meshes (the copies of an array) on the calling thread:
        // handing a few polygons to the pool costs more than building them.
        let mut faces = Vec::with_capacity(polygons.len());
        let mut triangles = Vec::with_capacity(polygons.len() * 2);
        let (mut degenerate_faces, mut split_polygons) = (0, 0);
        let parallel = polygons.len() >= PARALLEL_POLYGONS;
        let mut polygons = polygons.into_iter().enumerate();
        loop {
            let block: Vec<(usize, Polygon)> = polygons.by_ref().take(1 << 16).collect();
            if block.is_empty() {
                break;
            }
            let built: Vec<Result<Built, MeshError>> = if parallel {
                block.into_par_iter().map(one).collect()
            } else {
                block.into_iter().map(one).collect()
            };
            for b in built {
                let (degenerate, split, made) = b?;
                degenerate_faces += usize::from(degenerate);
                split_polygons += usize::from(split);
                for (mut face, tris) in made {
                    face.triangles = triangles.len()..triangles.len() + tris.len();
                    triangles.extend(tris);
                    faces.push(face);
                }
            }
        }
        let (junctions, topology) = topology::junctions_and_topology(&vertices, &faces);
        Ok(Mesh {
            vertices,
            faces,
            triangles,
            topology,
            merged_vertices: 0,
            degenerate_faces,
            split_polygons,
            junctions,
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
        // Every face has at least one triangle: as many faces as triangles means one each.
        if self.faces.len() == self.triangles.len() {
            return t;
        }
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

    /// How many input faces were dropped as degenerate: a vertex repeated (not in a row), or
    /// zero area ([`Validation::Repair`]).
    ///
    /// ```
    /// use kepler::{mesh::Mesh, geometry::Point3};
    /// let p = |x: f64, y: f64| Point3::new(x, y, 0.0);
    /// let m = Mesh::from_polygons(vec![p(0., 0.), p(1., 0.), p(0., 1.)],
    ///     vec![vec![0, 1, 2], vec![0, 1, 0], vec![2, 1, 1, 0]]).unwrap();
    /// // [0, 1, 0] is dropped; [2, 1, 1, 0] is the triangle [2, 1, 0].
    /// assert_eq!((m.faces().len(), m.degenerate_faces()), (2, 1));
    /// ```
    pub fn degenerate_faces(&self) -> usize {
        self.degenerate_faces
    }

    /// How many input polygons were not exactly planar and were split into triangles
    /// ([`Validation::Repair`]).
    ///
    /// ```
    /// use kepler::{mesh::Mesh, geometry::Point3};
    /// let p = |x: f64, y: f64, z: f64| Point3::new(x, y, z);
    /// let one_ulp = 1.0 + f64::EPSILON;
    /// let quad = vec![p(0., 0., 0.), p(1., 0., 0.), p(1., 1., one_ulp - 1.0), p(0., 1., 0.)];
    /// let m = Mesh::from_polygons(quad, vec![vec![0, 1, 2, 3]]).unwrap();
    /// assert_eq!((m.faces().len(), m.split_polygons()), (2, 1));
    /// ```
    pub fn split_polygons(&self) -> usize {
        self.split_polygons
    }

    /// How many sides of faces have vertices of the mesh lying exactly inside them
    /// (T-junctions), where they are matched piecewise with the sides that cover them.
    ///
    /// ```
    /// use kepler::{mesh::Mesh, geometry::Point3};
    /// let p = |x: f64, y: f64| Point3::new(x, y, 0.0);
    /// // Two triangles below the side (0,0)-(2,0) of a third one, meeting at (1,0).
    /// let v = vec![p(0., 0.), p(2., 0.), p(1., 1.), p(1., 0.), p(1., -1.)];
    /// let m = Mesh::from_polygons(v, vec![vec![0, 1, 2], vec![0, 4, 3], vec![3, 4, 1]]).unwrap();
    /// assert_eq!(m.t_junctions(), 1);
    /// assert_eq!(m.topology().boundary_edges, 4);
    /// ```
    pub fn t_junctions(&self) -> usize {
        self.junctions.len()
    }

    /// The vertices lying exactly inside side `side` of face `face`, in order from its first
    /// vertex, if there are any (see [`Mesh::t_junctions`]).
    pub(crate) fn side_junctions(&self, face: usize, side: usize) -> Option<&[u32]> {
        if self.junctions.is_empty() {
            return None;
        }
        let at = (face as u32, side as u32);
        self.junctions
            .binary_search_by(|j| (j.face, j.side).cmp(&at))
            .ok()
            .map(|k| self.junctions[k].inner.as_slice())
    }

    /// The signed volume enclosed (divergence theorem over the triangles): positive for a
    /// closed mesh whose faces point outward, negative for one turned inside out. Meaningful
    /// only for closed meshes. Accurate to the last few bits: the sum of the triangles'
    /// determinants is taken in floating point when its certified error is below `2^-40` of
    /// it, else exactly (as [`Mesh::orientation`] does) and rounded once, so a needle of a
    /// solid has its true tiny volume.
    ///
    /// ```
    /// use kepler::{geometry::Point3, mesh::Mesh};
    /// assert!((kepler::solids::cube(3.0).unwrap().volume() - 27.0).abs() < 1e-12);
    /// // A needle 1e8 long with a 1e-9 wide base: the rounded sum cancels to noise.
    /// let p = |x: f64, y: f64, z: f64| Point3::new(x, y, z);
    /// let v = vec![p(1e8, 0.0, 0.0), p(1e8, 1e-9, 0.0), p(1e8, 0.0, 1e-9), p(2e8, 0.0, 0.0)];
    /// let needle = Mesh::from_polygons(v, vec![vec![0, 2, 1], vec![0, 1, 3], vec![1, 2, 3], vec![2, 0, 3]]).unwrap();
    /// let exact = 1e8 * 1e-9 * 1e-9 / 6.0;
    /// assert!((needle.volume() - exact).abs() < 1e-12 * exact);
    /// ```
    pub fn volume(&self) -> f64 {
        let Some(o) = self.vertices.first() else {
            return 0.0;
        };
        // On coordinates scaled by a power of two when they are very large or very small, so
        // that the products neither overflow nor underflow; scaled back, the value may
        // overflow to an infinity of the right sign.
        let e = normalising_exponent(largest_coordinate(&self.vertices), 300);
        let scaled = |p: &Point3| p.map(|c| times_power_of_two(c, e));
        let o = scaled(o);
        let dets = || {
            self.triangles.iter().map(move |t| {
                let [a, b, c] = t.map(|i| scaled(&self.vertices[i as usize]));
                Orient3d([a, b, c, o])
            })
        };
        let (mut value, mut bound) = (0.0f64, 0.0f64);
        for d in dets() {
            let e = d.estimate();
            value += e.value;
            bound += e.bound + 2.0 * UNIT_ROUNDOFF * (value.abs() + e.value.abs());
        }
        let six_v = if value.is_finite() && bound <= value.abs() / (1u64 << 40) as f64 {
            value
        } else {
            let points: Vec<Point3> = self.vertices.iter().map(scaled).collect();
            match exact_sum(&points, dets()) {
                ExactSum::Expansion(sum) => estimate(&sum),
                ExactSum::Rational(sum) => sum.to_f64().unwrap_or(f64::NAN),
            }
        };
        times_power_of_two(six_v / 6.0, -3 * e)
    }

    /// The exact sign of the signed volume ([`Mesh::volume`]): `Greater` for a closed mesh
    /// whose faces point outward, `Less` for one turned inside out, `Equal` for none (or a
    /// flat one). The volume is the sum over the triangles of `orient3d(a, b, c, o)` / 6 for
    /// any point `o` (here the first vertex); the sum of their estimates decides when its
    /// certified bound allows, else the exact sum (expansions, compressed as they grow, or
    /// rationals where the coordinates' exponents are too far apart for expansions). A thin
    /// solid whose rounded volume has the wrong sign is oriented rightly.
    ///
    /// ```
    /// use std::cmp::Ordering;
    /// let cube = kepler::solids::cube(2.0).unwrap();
    /// assert_eq!(cube.orientation(), Ordering::Greater);
    /// ```
    pub fn orientation(&self) -> Ordering {
        let Some(o) = self.vertices.first() else {
            return Ordering::Equal;
        };
        let det = |t: &[u32; 3]| {
            let [a, b, c] = t.map(|i| self.vertices[i as usize]);
            Orient3d([a, b, c, *o])
        };
        let dets = || self.triangles.iter().map(det);
        // The estimates summed in any order (in parallel for a large mesh): the error bound
        // of a sum of n terms holds for every order of the additions.
        let add =
            |(v, b, m): (f64, f64, f64), e: Estimate| (v + e.value, b + e.bound, m + e.value.abs());
        let (value, bound, magnitude) = if self.triangles.len() >= PARALLEL_POLYGONS {
            use rayon::prelude::*;
            self.triangles
                .par_iter()
                .map(|t| det(t).estimate())
                .fold(|| (0.0, 0.0, 0.0), add)
                .reduce(|| (0.0, 0.0, 0.0), |x, y| (x.0 + y.0, x.1 + y.1, x.2 + y.2))
        } else {
            dets().map(|d| d.estimate()).fold((0.0, 0.0, 0.0), add)
        };
        let bound = (bound + sum_error_bound(self.triangles.len() + 1, magnitude))
            * (1.0 + 1.0 / (1u64 << 20) as f64);
        let filtered = Estimate { value, bound }.sign();
        if let Some(sign) = filtered {
            return sign;
        }
        match exact_sum(&self.vertices, dets()) {
            ExactSum::Expansion(sum) => expansion_sign(&sum),
            ExactSum::Rational(sum) => sum.cmp(&BigRational::zero()),
        }
    }

    /// The total area of the faces.
    ///
    /// ```
    /// assert_eq!(kepler::solids::cube(2.0).unwrap().surface_area(), 24.0);
    /// ```
    pub fn surface_area(&self) -> f64 {
        self.faces.iter().map(Face::area).sum()
    }

    /// The input polygons the faces are: each face's vertex loop, except that the triangle
    /// faces of a split polygon ([`Mesh::split_polygons`]) make one loop again, along their
    /// polygon edges ([`Face::is_polygon_edge`]), starting at a vertex of its first face. In
    /// the order of [`Face::polygon`]; dropped faces have none.
    ///
    /// ```
    /// use kepler::{mesh::Mesh, geometry::Point3};
    /// let p = |x: f64, y: f64, z: f64| Point3::new(x, y, z);
    /// let v = vec![p(0., 0., 0.), p(1., 0., 0.), p(2., 1., 1e-9), p(1., 2., 0.), p(0., 1., 0.)];
    /// let m = Mesh::from_polygons(v, vec![vec![0, 1, 2, 3, 4]]).unwrap();
    /// assert_eq!(m.faces().len(), 3);
    /// assert_eq!(m.polygons(), [vec![0, 1, 2, 3, 4]]);
    /// ```
    pub fn polygons(&self) -> Vec<Vec<u32>> {
        self.faces
            .chunk_by(|f, g| f.polygon == g.polygon)
            .map(|faces| {
                let [face] = faces else {
                    return polygon_loop(faces);
                };
                face.vertices.to_vec()
            })
            .collect()
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
    /// // Scalings by large powers of two (whose determinant is not a double) are not singular.
    /// let huge = c.transformed(&Matrix4::new_scaling(2f64.powi(-600))).unwrap();
    /// let scaled = |x: f64| x * 2f64.powi(-600);
    /// assert!(huge.vertices().iter().zip(c.vertices()).all(|(a, b)| *a == b.map(scaled)));
    /// ```
    pub fn transformed(&self, m: &Matrix4<f64>) -> Result<Mesh, MeshError> {
        if m.iter().any(|x| !x.is_finite()) {
            return Err(MeshError::SingularTransform);
        }
        // The sign of the determinant of the linear part, exactly: a rounded determinant
        // overflows or underflows for scalings by large powers of two.
        let row = |i: usize| Point3::new(m[(i, 0)], m[(i, 1)], m[(i, 2)]);
        let mirrors = match orient3d(&row(0), &row(1), &row(2), &Point3::origin()) {
            Ordering::Greater => false,
            Ordering::Less => true,
            Ordering::Equal => return Err(MeshError::SingularTransform),
        };
        let vertices = self.vertices.iter().map(|p| m.transform_point(p)).collect();
        let polygons = self
            .faces
            .iter()
            .map(|f| {
                let mut v = f.vertices.clone();
                let mut diagonals = f.diagonals;
                if mirrors {
                    v.reverse();
                    // Side i of the reversed loop is side n - 2 - i of the loop, reversed
                    // (and the last side stays the last).
                    let n = v.len();
                    diagonals = (0..n.min(8)).fold(0, |bits, i| {
                        let old = if i + 1 < n { n - 2 - i } else { n - 1 };
                        if f.is_polygon_edge(old) {
                            bits
                        } else {
                            bits | 1 << i
                        }
                    });
                }
                (v, diagonals, f.polygon)
            })
            .collect();
        Mesh::rebuilt(vertices, polygons, [self])
    }

    /// The mesh scaled by `2^exponent`, when that is exact for every coordinate (no overflow,
    /// no bit lost below the normal range); `None` otherwise.
    ///
    /// Every sign the mesh was built from is a sign of a polynomial in the coordinates, the
    /// same after an exact scaling, so the faces, their triangulations, the topology and the
    /// T-junctions are the mesh's own: only what is rounded from coordinates (each face's
    /// plane, texture frame and area) is computed again, from the scaled vertices, as a
    /// rebuild would. Bringing a million-triangle scene into the working range then costs a
    /// pass over its faces, not a new validation.
    ///
    /// ```
    /// let sphere = kepler::solids::uv_sphere(1.0, 16, 8).unwrap();
    /// let big = sphere.scaled_exactly(40).unwrap();
    /// let rebuilt = sphere.transformed(&nalgebra::Matrix4::new_scaling(2f64.powi(40))).unwrap();
    /// assert_eq!(big, rebuilt);
    /// assert!(sphere.scaled_exactly(2000).is_none());
    /// ```
    pub fn scaled_exactly(&self, exponent: i32) -> Option<Mesh> {
        use rayon::prelude::*;
        let scale = |c: f64| {
            let s = build::times_power_of_two(c, exponent);
            (s.is_finite() && build::times_power_of_two(s, -exponent) == c).then_some(s)
        };
        let parallel = self.faces.len() >= PARALLEL_POLYGONS;
        let vertex = |p: &Point3| Some(Point3::new(scale(p.x)?, scale(p.y)?, scale(p.z)?));
        let vertices: Vec<Point3> = if parallel {
            self.vertices
                .par_iter()
                .map(vertex)
                .collect::<Option<_>>()?
        } else {
            self.vertices.iter().map(vertex).collect::<Option<_>>()?
        };
        let face = |f: &Face| {
            let local: Vec<[usize; 3]> = self.triangles[f.triangles.clone()]
                .iter()
                .map(|t| t.map(|v| f.vertices.iter().position(|&w| w == v).unwrap_or(0)))
                .collect();
            let polygon = (f.vertices.clone(), f.diagonals, f.polygon);
            build::face(&vertices, polygon, &local, f.triangles.start).0
        };
        let faces = if parallel {
            self.faces.par_iter().map(face).collect()
        } else {
            self.faces.iter().map(face).collect()
        };
        Some(Mesh {
            vertices,
            faces,
            triangles: self.triangles.clone(),
            topology: self.topology,
            merged_vertices: self.merged_vertices,
            degenerate_faces: self.degenerate_faces,
            split_polygons: self.split_polygons,
            junctions: self.junctions.clone(),
        })
    }

    /// The meshes as one: their vertex lists appended (equal vertices merged) and their faces
    /// renumbered, each keeping what it is of its input polygon (renumbered after the
    /// polygons of the meshes before it); the counts of repairs add up.
    ///
    /// ```
    /// use kepler::{mesh::Mesh, solids};
    /// let (a, b) = (solids::cube(1.0).unwrap(), solids::dodecahedron(1.0).unwrap());
    /// let both = Mesh::concatenate([&a, &b]).unwrap();
    /// assert_eq!(both.faces().len(), a.faces().len() + b.faces().len());
    /// assert_eq!(both.polygons().len(), 6 + 12);
    /// assert_eq!(both.split_polygons(), b.split_polygons());
    /// ```
    pub fn concatenate<'a>(meshes: impl IntoIterator<Item = &'a Mesh>) -> Result<Mesh, MeshError> {
        let meshes: Vec<&Mesh> = meshes.into_iter().collect();
        let mut vertices: Vec<Point3> = Vec::new();
        let mut polygons = Vec::new();
        let mut first_polygon = 0;
        for mesh in &meshes {
            let offset = vertices.len() as u32;
            vertices.extend_from_slice(&mesh.vertices);
            polygons.extend(mesh.faces.iter().map(|f| {
                let v = f.vertices.iter().map(|&i| i + offset).collect();
                (v, f.diagonals, f.polygon + first_polygon)
            }));
            first_polygon += mesh.faces.iter().map(|f| f.polygon + 1).max().unwrap_or(0);
        }
        Mesh::rebuilt(vertices, polygons, meshes)
    }

    /// The mesh of `polygons` over `vertices` (not yet merged), faces of meshes `from`, whose
    /// counts of repairs it inherits.
    fn rebuilt<'a>(
        vertices: Vec<Point3>,
        polygons: Vec<Polygon>,
        from: impl IntoIterator<Item = &'a Mesh>,
    ) -> Result<Mesh, MeshError> {
        let (vertices, remap, merged_vertices) = build::merge_duplicates(vertices)?;
        let polygons = polygons
            .into_iter()
            .map(|(v, diagonals, polygon)| {
                (
                    v.iter().map(|&i| remap[i as usize]).collect(),
                    diagonals,
                    polygon,
                )
            })
            .collect();
        let mut mesh = Mesh::assemble(vertices, polygons, Validation::Repair)?;
        mesh.merged_vertices = merged_vertices;
        for m in from {
            mesh.merged_vertices += m.merged_vertices;
            mesh.degenerate_faces += m.degenerate_faces;
            mesh.split_polygons += m.split_polygons;
        }
        Ok(mesh)
    }
}

/// The loop of a split polygon from its triangle faces: its polygon edges chained from the
/// first face's first one.
fn polygon_loop(faces: &[Face]) -> Vec<u32> {
    let mut next: Vec<(u32, u32)> = faces
        .iter()
        .flat_map(|f| {
            let v = &f.vertices;
            (0..v.len())
                .filter(|&i| f.is_polygon_edge(i))
                .map(move |i| (v[i], v[(i + 1) % v.len()]))
        })
        .collect();
    let Some(&(start, _)) = next.first() else {
        return Vec::new();
    };
    next.sort_unstable();
    let mut out = vec![start];
    while out.len() <= next.len() {
        let last = out[out.len() - 1];
        let Ok(k) = next.binary_search_by_key(&last, |e| e.0) else {
            break;
        };
        if next[k].1 == start {
            break;
        }
        out.push(next[k].1);
    }
    out
}

/// A sum of determinants of a mesh's points, exactly.
enum ExactSum {
    /// As an expansion (when the points' exponents allow exact expansions of degree 3).
    Expansion(Vec<f64>),
    /// As a rational.
    Rational(BigRational),
}

/// The exact sum of `dets` (determinants of `points`): expansions, compressed as they grow,
/// or rationals where the points' exponents are too far apart for expansions.
fn exact_sum(points: &[Point3], dets: impl Iterator<Item = Orient3d>) -> ExactSum {
    let exponents = Exponents::of(
        &points
            .iter()
            .flat_map(|p| p.coords.iter().copied())
            .collect::<Vec<f64>>(),
    );
    if exponents.exact_for(3) {
        let mut sum: Vec<f64> = Vec::new();
        for (k, d) in dets.enumerate() {
            sum = expansion_sum(&sum, &d.expansion());
            if k % 64 == 63 {
                sum = compress(&sum);
            }
        }
        return ExactSum::Expansion(compress(&sum));
    }
    ExactSum::Rational(dets.fold(BigRational::zero(), |s, d| s + d.evaluate::<BigRational>()))
}
