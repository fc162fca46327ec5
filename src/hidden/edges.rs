//! The edges of a mesh, each once, and their classes in a view.
//!
//! An edge is a side of a polygon face (the diagonals of a face's triangulation are not
//! edges). Its class depends on the view only through exact signs: the side of the picture of
//! the edge on which each of its faces lies (`orient3d` of the edge, the face's third vertex
//! and the eye). Two faces on the same side make a silhouette whatever their orientation, so
//! an inside-out or inconsistently oriented mesh draws as the correct one does. Coplanar
//! neighbours (decided exactly) share no edge at all, so a triangulated flat face draws as one
//! polygon. Only the crease angle is a measurement (a user's threshold, not a sign).

use super::EdgeClass;
use crate::geometry::predicates::{orient2d, orient3d, project};
use crate::geometry::{Point3, Vector3};
use crate::mesh::Mesh;
use crate::views::Eye;
use rayon::prelude::*;
use std::cmp::Ordering;

/// One edge of a mesh: its vertices (indices into the mesh) and class.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct MeshEdge {
    /// The first vertex.
    pub a: u32,
    /// The second vertex.
    pub b: u32,
    /// The class in the view.
    pub class: EdgeClass,
    /// The triangles on its first two sides (the same twice for a boundary edge).
    pub triangles: [u32; 2],
}

/// What [`classify`] found besides the edges.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub(crate) struct EdgeCounts {
    /// Edges between coplanar faces, which are not edges of the drawing.
    pub flat: usize,
    /// Edges seen end-on (pointing at the eye), whose picture is a point.
    pub end_on: usize,
}

/// A face's side of an edge: the face and its triangle's vertex off the edge.
#[derive(Debug, Clone, Copy)]
struct Side {
    key: u64,
    third: u32,
    triangle: u32,
}

/// Every edge of `mesh` with its class as seen from `eye`; `crease_cos` is `-cos` of the
/// crease angle (an edge is a crease when the cosine of the angle between its faces exceeds
/// it). Coplanar and end-on edges are left out and counted.
pub(crate) fn classify(mesh: &Mesh, eye: &Eye, crease_cos: f64) -> (Vec<MeshEdge>, EdgeCounts) {
    let triangles = mesh.triangles();
    let mut sides: Vec<Side> = mesh
        .faces()
        .par_iter()
        .flat_map_iter(|face| {
            let v = face.vertices();
            (0..v.len()).filter_map(move |i| {
                let (p, q) = (v[i], v[(i + 1) % v.len()]);
                // The triangle of the face's triangulation that has this side.
                face.triangle_range().find_map(|t| {
                    let tri = triangles[t];
                    if !(tri.contains(&p) && tri.contains(&q)) {
                        return None;
                    }
                    let third = tri.iter().copied().find(|&w| w != p && w != q)?;
                    Some(Side {
                        key: (u64::from(p.min(q)) << 32) | u64::from(p.max(q)),
                        third,
                        triangle: t as u32,
                    })
                })
            })
        })
        .collect();
    sides.par_sort_unstable_by_key(|s| s.key);
    let groups: Vec<&[Side]> = sides.chunk_by(|x, y| x.key == y.key).collect();
    let vertices = mesh.vertices();
    let decided: Vec<Result<MeshEdge, Left>> = groups
        .par_iter()
        .map(|group| {
            let (a, b) = ((group[0].key >> 32) as u32, group[0].key as u32);
            let (pa, pb) = (&vertices[a as usize], &vertices[b as usize]);
            if eye.sees_end_on(pa, pb) {
                return Err(Left::EndOn);
            }
            let third = |k: usize| &vertices[group[k].third as usize];
            let class = match group.len() {
                1 => Some(EdgeClass::Boundary),
                2 => class_of(pa, pb, [third(0), third(1)], eye, crease_cos),
                _ => Some(class_of_many(
                    pa,
                    pb,
                    group.iter().map(|s| &vertices[s.third as usize]),
                    eye,
                )),
            };
            class.map_or(Err(Left::Flat), |class| {
                Ok(MeshEdge {
                    a,
                    b,
                    class,
                    triangles: [group[0].triangle, group[group.len().min(2) - 1].triangle],
                })
            })
        })
        .collect();
    let mut counts = EdgeCounts::default();
    let mut edges = Vec::with_capacity(decided.len());
    for d in decided {
        match d {
            Ok(e) => edges.push(e),
            Err(Left::Flat) => counts.flat += 1,
            Err(Left::EndOn) => counts.end_on += 1,
        }
    }
    (edges, counts)
}

/// Why an edge is not part of the drawing.
#[derive(Debug, Clone, Copy)]
enum Left {
    /// Between coplanar faces.
    Flat,
    /// Seen end-on.
    EndOn,
}

/// The class of an edge `ab` of more than two faces (third vertices `thirds`): a silhouette
/// when all lie on one side of its picture or one is seen edge-on, else a crease.
fn class_of_many<'a>(
    a: &Point3,
    b: &Point3,
    thirds: impl Iterator<Item = &'a Point3>,
    eye: &Eye,
) -> EdgeClass {
    let mut seen = [false; 3];
    for c in thirds {
        seen[(eye.orient3d(a, b, c) as i8 + 1) as usize] = true;
    }
    if seen[1] || !(seen[0] && seen[2]) {
        EdgeClass::Silhouette
    } else {
        EdgeClass::Crease
    }
}

/// The class of the edge `ab` of two faces whose third vertices are `c1` and `c2`, or `None`
/// for an edge between two coplanar faces on either side of it.
fn class_of(
    a: &Point3,
    b: &Point3,
    [c1, c2]: [&Point3; 2],
    eye: &Eye,
    crease_cos: f64,
) -> Option<EdgeClass> {
    let (s1, s2) = (eye.orient3d(a, b, c1), eye.orient3d(a, b, c2));
    if s1 == Ordering::Equal || s2 == Ordering::Equal || s1 == s2 {
        return Some(EdgeClass::Silhouette);
    }
    if orient3d(a, b, c1, c2) == Ordering::Equal {
        // Coplanar, and (their picture sides differing) on either side of the edge.
        let k = (0..3)
            .find(|&k| orient2d(project(a, k), project(b, k), project(c1, k)) != Ordering::Equal);
        let opposite = k.is_some_and(|k| {
            let side = |c: &Point3| orient2d(project(a, k), project(b, k), project(c, k));
            side(c1) == side(c2).reverse()
        });
        if opposite {
            return None;
        }
        return Some(EdgeClass::Crease);
    }
    // The angle between the faces: between the components of c1 - a and c2 - a across the edge.
    let e = b - a;
    let across = |c: &Point3| -> Vector3 {
        let v = c - a;
        v - e * (v.dot(&e) / e.dot(&e))
    };
    let (u1, u2) = (across(c1), across(c2));
    let cos = u1.dot(&u2) / (u1.norm() * u2.norm());
    Some(if cos > crease_cos {
        EdgeClass::Crease
    } else {
        EdgeClass::Smooth
    })
}
