//! The faces of a convex polyhedron with equal edges whose vertices lie on a sphere about the
//! origin (every Platonic and Archimedean solid): the edges are the vertex pairs at the
//! smallest distance, and the faces are the cycles found by turning, at each vertex, from the
//! incoming edge to the next edge clockwise seen from outside.

use crate::geometry::polygon::newell_normal;
use crate::geometry::{Point3, Vector3};

/// A polyhedron at unit edge length: its vertices and its faces (index loops,
/// counter-clockwise seen from outside).
pub(super) struct Template {
    pub vertices: Vec<Point3>,
    pub faces: Vec<Vec<u32>>,
}

/// Scales `points` to unit edge length and finds the faces.
///
/// Following the turning rule from a directed edge is a permutation of the directed edges
/// (its inverse turns the other way), so every walk closes and each directed edge lies on
/// exactly one face: the result is always a closed, consistently oriented surface. That it is
/// the right one (the expected counts, planar regular faces) is checked by the tests.
pub(super) fn faces_of(points: &[Point3]) -> Template {
    let n = points.len();
    let min_sq = (0..n)
        .flat_map(|i| (i + 1..n).map(move |j| (i, j)))
        .map(|(i, j)| (points[i] - points[j]).norm_squared())
        .fold(f64::INFINITY, f64::min);
    let edge = min_sq.sqrt();
    let vertices: Vec<Point3> = points.iter().map(|p| p / edge).collect();

    // Neighbours of each vertex, sorted counter-clockwise seen from outside.
    let neighbours: Vec<Vec<usize>> = (0..n)
        .map(|i| {
            let v = vertices[i];
            let mut near: Vec<usize> = (0..n)
                .filter(|&j| j != i && (vertices[j] - v).norm_squared() < 1.0 + 1e-6)
                .collect();
            let axis = v.coords.normalize();
            let tangent = |w: &Point3| {
                let d: Vector3 = w - v;
                d - axis * axis.dot(&d)
            };
            if let Some(&first) = near.first() {
                let e1 = tangent(&vertices[first]).normalize();
                let e2 = axis.cross(&e1);
                let angle = |j: &usize| {
                    let t = tangent(&vertices[*j]);
                    t.dot(&e2).atan2(t.dot(&e1))
                };
                near.sort_by(|a, b| angle(a).total_cmp(&angle(b)));
            }
            near
        })
        .collect();

    // Directed edge u → v continues as v → w, w the neighbour of v just clockwise of u.
    let next = |u: usize, v: usize| {
        let around = &neighbours[v];
        let k = around.iter().position(|&x| x == u).unwrap_or(0);
        around[(k + around.len() - 1) % around.len()]
    };
    let mut used: Vec<Vec<bool>> = neighbours.iter().map(|nb| vec![false; nb.len()]).collect();
    let mut faces = Vec::new();
    for start in 0..n {
        for (k, &second) in neighbours[start].iter().enumerate() {
            if used[start][k] {
                continue;
            }
            let mut face = Vec::new();
            let (mut u, mut v) = (start, second);
            loop {
                let slot = neighbours[u].iter().position(|&x| x == v).unwrap_or(0);
                if used[u][slot] {
                    break;
                }
                used[u][slot] = true;
                face.push(u as u32);
                (u, v) = (v, next(u, v));
            }
            faces.push(outward(face, &vertices));
        }
    }
    Template { vertices, faces }
}

/// The face loop, reversed if its normal points towards the origin.
fn outward(mut face: Vec<u32>, vertices: &[Point3]) -> Vec<u32> {
    let pts: Vec<Point3> = face.iter().map(|&i| vertices[i as usize]).collect();
    let centroid = pts.iter().fold(Vector3::zeros(), |s, p| s + p.coords);
    if newell_normal(&pts).dot(&centroid) < 0.0 {
        face.reverse();
    }
    face
}
