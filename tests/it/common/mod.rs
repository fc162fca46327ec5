//! Helpers shared by the integration tests: a deterministic random generator and exact
//! rational arithmetic for references. Each test crate uses a subset of them.
#![allow(dead_code)]

pub mod exact;
pub mod invariance;

use kepler::geometry::Vector3;
use num_rational::BigRational;
use num_traits::Signed;
use std::cmp::Ordering;

/// SplitMix64: a small deterministic generator, so failures reproduce.
pub struct Rng(pub u64);

impl Rng {
    pub fn next_u64(&mut self) -> u64 {
        // SplitMix64.
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^ (z >> 31)
    }

    pub fn unit(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64
    }

    pub fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.unit()
    }

    pub fn below(&mut self, n: usize) -> usize {
        (self.next_u64() % n as u64) as usize
    }

    pub fn int(&mut self, lo: i32, hi: i32) -> f64 {
        f64::from(lo + self.below((hi - lo + 1) as usize) as i32)
    }

    pub fn vector(&mut self, r: f64) -> Vector3 {
        Vector3::new(self.range(-r, r), self.range(-r, r), self.range(-r, r))
    }

    pub fn pick<T: Copy>(&mut self, items: &[T]) -> T {
        items[self.below(items.len())]
    }
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
