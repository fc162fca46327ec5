//! New meshes from meshes: under an affine transform, scaled exactly by a power of two, and
//! concatenated; each rebuilt (or, when scaled exactly, only recomputed where it is rounded).

use super::{Face, Mesh, MeshError, PARALLEL_POLYGONS, Polygon, Validation, build};
use crate::geometry::Point3;
use crate::geometry::predicates::orient3d;
use nalgebra::Matrix4;
use std::cmp::Ordering;

impl Mesh {
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
