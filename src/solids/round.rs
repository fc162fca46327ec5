//! Faceted solids of revolution about the z-axis: UV sphere, torus and cylinder. Each
//! revolves a polygon in `segments` equal steps, so the faces between two meridians are
//! isosceles trapezoids (planar), or triangles at the poles.

use super::{MAX_FACES, MAX_POLYGON_VERTICES, SolidError, at_least, at_most, positive};
use crate::geometry::Point3;
use crate::mesh::{Loop, Mesh, Validation};
use std::f64::consts::{PI, TAU};

/// A UV sphere of the given radius centred at the origin: `rings` bands of latitude between
/// the poles (z = ±radius), each cut into `segments` faces. The poles are single vertices
/// with fans of triangles; the other faces are quads (isosceles trapezoids). All vertices lie
/// on the sphere. Needs a finite radius > 0, `segments` ≥ 3, `rings` ≥ 2, and at most
/// [`MAX_FACES`] faces (`segments × rings`).
///
/// ```
/// let s = kepler::solids::uv_sphere(1.0, 16, 8).unwrap();
/// assert_eq!((s.vertices().len(), s.polygons().len()), (16 * 7 + 2, 16 * 8));
/// assert!(s.volume() < 4.0 / 3.0 * std::f64::consts::PI);
/// let e = kepler::solids::uv_sphere(1.0, 16, 1).unwrap_err();
/// assert_eq!(e.to_string(), "sphere: rings must be at least 2, got 1");
/// ```
pub fn uv_sphere(radius: f64, segments: u32, rings: u32) -> Result<Mesh, SolidError> {
    let r = positive("sphere", "radius", radius)?;
    let n = at_least("sphere", "segments", segments, 3)?;
    let m = at_least("sphere", "rings", rings, 2)?;
    at_most(
        "sphere",
        "segments × rings",
        u64::from(segments) * u64::from(rings),
        MAX_FACES,
    )?;
    // Vertex 0 is the north pole, then the inner latitude circles 1..m from north to south,
    // n vertices each, then the south pole.
    let around = circle(n);
    let mut vertices = Vec::with_capacity(n * (m - 1) + 2);
    vertices.push(Point3::new(0.0, 0.0, r));
    for i in 1..m {
        let (s, c) = (i as f64 * PI / m as f64).sin_cos();
        let (rho, z) = (r * s, r * c);
        vertices.extend(
            around
                .iter()
                .map(|&(x, y)| Point3::new(rho * x, rho * y, z)),
        );
    }
    let south = vertices.len() as u32;
    vertices.push(Point3::new(0.0, 0.0, -r));

    let (n32, m32) = (n as u32, m as u32);
    let at = |i: u32, j: u32| 1 + (i - 1) * n32 + j % n32;
    // Loops inline (no allocation per face), built straight into the mesh.
    let mut faces: Vec<Loop> = Vec::with_capacity(n * m);
    faces.extend((0..n32).map(|j| Loop::from_slice(&[0, at(1, j), at(1, j + 1)])));
    for i in 1..m32 - 1 {
        faces.extend(
            (0..n32).map(|j| {
                Loop::from_slice(&[at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)])
            }),
        );
    }
    faces.extend((0..n32).map(|j| Loop::from_slice(&[south, at(m32 - 1, j + 1), at(m32 - 1, j)])));
    Ok(Mesh::from_loops_with(vertices, faces, Validation::Repair)?)
}

/// A torus about the z-axis, centred at the origin: its tube is a regular `sides`-gon of
/// circumradius `minor_radius` centred at distance `major_radius` from the axis, revolved in
/// `segments` steps; all faces are quads (isosceles trapezoids). Needs finite radii with
/// 0 < minor < major, `segments` ≥ 3, `sides` ≥ 3 and at most [`MAX_FACES`] faces.
///
/// ```
/// let t = kepler::solids::torus(2.0, 0.5, 24, 12).unwrap();
/// assert_eq!((t.vertices().len(), t.polygons().len()), (24 * 12, 24 * 12));
/// assert!(t.is_solid());
/// let e = kepler::solids::torus(1.0, 2.0, 24, 12).unwrap_err();
/// assert_eq!(e.to_string(), "torus: minor radius must be less than the major radius 1, got 2");
/// ```
pub fn torus(
    major_radius: f64,
    minor_radius: f64,
    segments: u32,
    sides: u32,
) -> Result<Mesh, SolidError> {
    let big = positive("torus", "major radius", major_radius)?;
    let small = positive("torus", "minor radius", minor_radius)?;
    if small >= big {
        return Err(super::invalid(
            "torus",
            "minor radius",
            super::show(small),
            format!("less than the major radius {}", super::show(big)),
        ));
    }
    let n = at_least("torus", "segments", segments, 3)?;
    let m = at_least("torus", "sides", sides, 3)?;
    at_most(
        "torus",
        "segments × sides",
        u64::from(segments) * u64::from(sides),
        MAX_FACES,
    )?;
    // Vertex i·m + j: meridian i (angle 2πi/n about z), tube point j (angle 2πj/m).
    let tube: Vec<(f64, f64)> = circle(m)
        .into_iter()
        .map(|(c, s)| (big + small * c, small * s))
        .collect();
    let vertices = circle(n)
        .into_iter()
        .flat_map(|(x, y)| {
            tube.iter()
                .map(move |&(rho, z)| Point3::new(rho * x, rho * y, z))
        })
        .collect();
    let (n32, m32) = (n as u32, m as u32);
    let at = |i: u32, j: u32| (i % n32) * m32 + j % m32;
    let faces = (0..n32)
        .flat_map(|i| {
            (0..m32).map(move |j| vec![at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)])
        })
        .collect();
    Ok(Mesh::from_polygons(vertices, faces)?)
}

/// A cylinder about the z-axis from z = −height/2 to z = height/2: two regular
/// `segments`-gon caps of circumradius `radius` and `segments` quad walls. Needs a finite
/// radius and height > 0 and 3 ≤ `segments` ≤ [`MAX_POLYGON_VERTICES`].
///
/// ```
/// let c = kepler::solids::cylinder(1.0, 2.0, 4).unwrap();
/// assert_eq!(c.faces().len(), 6);
/// assert!((c.volume() - 4.0).abs() < 1e-12); // a square of diagonal 2, times 2
/// let e = kepler::solids::cylinder(1.0, 0.0, 8).unwrap_err();
/// assert_eq!(e.to_string(), "cylinder: height must be a finite number greater than 0, got 0");
/// ```
pub fn cylinder(radius: f64, height: f64, segments: u32) -> Result<Mesh, SolidError> {
    let r = positive("cylinder", "radius", radius)?;
    let h = positive("cylinder", "height", height)? / 2.0;
    let n = at_least("cylinder", "segments", segments, 3)?;
    at_most(
        "cylinder",
        "segments",
        u64::from(segments),
        MAX_POLYGON_VERTICES as u64,
    )?;
    // Vertices 0..n: the bottom circle; n..2n: the top one.
    let around = circle(n);
    let vertices = [-h, h]
        .into_iter()
        .flat_map(|z| {
            around
                .iter()
                .map(move |&(x, y)| Point3::new(r * x, r * y, z))
        })
        .collect();
    let n32 = n as u32;
    let mut faces: Vec<Vec<u32>> = Vec::with_capacity(n + 2);
    faces.push((0..n32).rev().collect());
    faces.push((n32..2 * n32).collect());
    faces.extend((0..n32).map(|j| {
        let k = (j + 1) % n32;
        vec![j, k, n32 + k, n32 + j]
    }));
    Ok(Mesh::from_polygons(vertices, faces)?)
}

/// `(cos, sin)` of the angles 2πk/n, k = 0..n.
fn circle(n: usize) -> Vec<(f64, f64)> {
    (0..n)
        .map(|k| {
            let (s, c) = (k as f64 * TAU / n as f64).sin_cos();
            (c, s)
        })
        .collect()
}
