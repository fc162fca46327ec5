//! Helpers shared by the integration tests: a deterministic random generator, scenes of
//! meshes, and exact rational arithmetic for references. Each test crate uses a subset of them.
#![allow(dead_code)]

pub mod exact;
pub mod invariance;

use num_rational::BigRational;
use num_traits::Signed;
use std::cmp::Ordering;

/// The crate's seeded generator, so failures reproduce.
pub use kepler::random::SplitMix64;

/// A scene of `meshes`, each an object at the root named `m0`, `m1`, …, and their ids.
pub fn scene_and_ids<M: std::borrow::Borrow<kepler::mesh::Mesh>>(
    meshes: impl IntoIterator<Item = M>,
) -> (kepler::scene::Scene, Vec<kepler::scene::ObjectId>) {
    let mut scene = kepler::scene::Scene::new();
    let ids = meshes
        .into_iter()
        .enumerate()
        .map(|(i, m)| {
            let mesh = m.borrow().clone();
            scene
                .add_mesh(None, format!("m{i}"), mesh)
                .expect("a valid mesh")
        })
        .collect();
    (scene, ids)
}

/// A scene of `meshes`, each an object at the root named `m0`, `m1`, ….
pub fn scene_of<M: std::borrow::Borrow<kepler::mesh::Mesh>>(
    meshes: impl IntoIterator<Item = M>,
) -> kepler::scene::Scene {
    scene_and_ids(meshes).0
}

/// Exact rationals: every finite `f64` converts exactly.
pub type Q = BigRational;

pub fn q(x: f64) -> Q {
    BigRational::from_float(x).expect("finite")
}

pub fn qv(p: [f64; 3]) -> [Q; 3] {
    p.map(q)
}

pub fn qsub(a: &[Q; 3], b: &[Q; 3]) -> [Q; 3] {
    [&a[0] - &b[0], &a[1] - &b[1], &a[2] - &b[2]]
}

pub fn qdot(a: &[Q; 3], b: &[Q; 3]) -> Q {
    &a[0] * &b[0] + &a[1] * &b[1] + &a[2] * &b[2]
}

pub fn qcross(a: &[Q; 3], b: &[Q; 3]) -> [Q; 3] {
    [
        &a[1] * &b[2] - &a[2] * &b[1],
        &a[2] * &b[0] - &a[0] * &b[2],
        &a[0] * &b[1] - &a[1] * &b[0],
    ]
}

pub fn qsign(x: &Q) -> Ordering {
    if x.is_positive() {
        Ordering::Greater
    } else if x.is_negative() {
        Ordering::Less
    } else {
        Ordering::Equal
    }
}

/// The octahedron |x| + |y| + |z| ≤ 1, vertices (±1, 0, 0), (0, ±1, 0), (0, 0, ±1): integer
/// vertices, so rays through vertices and edge midpoints are exact.
pub fn unit_octahedron() -> kepler::mesh::Mesh {
    use kepler::geometry::Point3;
    let v = vec![
        Point3::new(1.0, 0.0, 0.0),
        Point3::new(-1.0, 0.0, 0.0),
        Point3::new(0.0, 1.0, 0.0),
        Point3::new(0.0, -1.0, 0.0),
        Point3::new(0.0, 0.0, 1.0),
        Point3::new(0.0, 0.0, -1.0),
    ];
    let faces = vec![
        vec![0, 2, 4],
        vec![2, 1, 4],
        vec![1, 3, 4],
        vec![3, 0, 4],
        vec![2, 0, 5],
        vec![1, 2, 5],
        vec![3, 1, 5],
        vec![0, 3, 5],
    ];
    kepler::mesh::Mesh::from_polygons(v, faces).expect("valid octahedron")
}

/// The mesh with every vertex scaled by `2^k`, exactly while the coordinates stay normal (its
/// faces as they are); an error if the scaled mesh is refused.
pub fn scaled_mesh(
    mesh: &kepler::mesh::Mesh,
    k: i32,
) -> Result<kepler::mesh::Mesh, kepler::mesh::MeshError> {
    use kepler::geometry::exact::ldexp;
    let vertices = mesh
        .vertices()
        .iter()
        .map(|p| p.map(|c| ldexp(c, k)))
        .collect();
    let faces = mesh.faces().iter().map(|f| f.vertices().to_vec()).collect();
    kepler::mesh::Mesh::from_polygons(vertices, faces)
}
