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
mod locality;
mod measure;
mod topology;
mod transform;
mod tree;
mod validation;

pub(crate) use buckets::by_bucket;
pub use containment::{
    Containment, classify_among, classify_point, classify_point_brute_force, crosses_column,
};
pub(crate) use face::Loop;
pub use face::{Face, Plane, TextureFrame};
pub(crate) use locality::faces_in_space_order;
pub use topology::Topology;
pub(crate) use topology::sort_by_edge;
pub use tree::TriangleTree;

pub use validation::{MeshError, Validation};

use crate::geometry::Point3;
use build::{Shape, diagonals_of};
pub(crate) use build::{largest_coordinate, normalising_exponent, times_power_of_two};
use topology::Junction;

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

    /// A mesh rebuilt from what [`Mesh::faces`] and [`Mesh::vertices`] hold of one (each
    /// face's loop, diagonals and input polygon) and its counts of repairs (merged vertices,
    /// degenerate faces dropped, polygons split): the same mesh, for a scene index read back.
    pub(crate) fn restored(
        vertices: Vec<Point3>,
        faces: Vec<(Loop, u8, u32)>,
        [merged, degenerate, split]: [usize; 3],
    ) -> Result<Mesh, MeshError> {
        if let Some(face) = faces
            .iter()
            .position(|f| f.0.iter().any(|&v| v as usize >= vertices.len()))
        {
            return Err(MeshError::IndexOutOfRange {
                face,
                index: i64::from(faces[face].0.iter().copied().max().unwrap_or(0)),
                vertex_count: vertices.len(),
            });
        }
        let mut mesh = Mesh::assemble(vertices, faces, Validation::Repair)?;
        (
            mesh.merged_vertices,
            mesh.degenerate_faces,
            mesh.split_polygons,
        ) = (merged, degenerate, split);
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
        // The input polygons' buffer is not held through the topology's sort of the sides.
        drop(polygons);
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
