//! An order of a mesh's faces in which faces near in space come near in the order (a
//! Z-order, or Morton, curve through the mesh's bounding box), so that a pass which looks at
//! each face and its neighbours in that order finds them in the cache rather than in memory.
//!
//! Only the order in which work is done depends on it, never a result: the key is a rounded
//! position, and callers put each face's answer back at the face's own index. Written by hand
//! because it is a bit interleaving of a few lines.

use super::Mesh;
use crate::geometry::Aabb;

/// Bits per axis of the Morton key: 21, so that three fit in a `u64`.
const BITS: u32 = 21;

/// The mesh's face indices ordered along a Morton curve of their first vertices (ties, and
/// faces whose vertex is not finite in the box's scale, by index).
pub(crate) fn faces_in_space_order(mesh: &Mesh) -> Vec<u32> {
    let vertices = mesh.vertices();
    let Aabb { min: lo, max: hi } = Aabb::from_points(vertices);
    // The scale of each axis in cells per unit; a flat axis (or an overflowing extent) gets 0.
    let scale = [0, 1, 2].map(|k| {
        let s = f64::from((1u32 << BITS) - 1) / (hi[k] - lo[k]);
        if s.is_finite() { s } else { 0.0 }
    });
    let mut keyed: Vec<(u64, u32)> = mesh
        .faces()
        .iter()
        .enumerate()
        .map(|(f, face)| {
            let p = &vertices[face.vertices()[0] as usize];
            let cell = [0, 1, 2].map(|k| ((p[k] - lo[k]) * scale[k]) as u32);
            (morton(cell), f as u32)
        })
        .collect();
    keyed.sort_unstable();
    keyed.into_iter().map(|(_, f)| f).collect()
}

/// The Morton key of a cell: the bits of its three coordinates interleaved.
fn morton(cell: [u32; 3]) -> u64 {
    // Spreads the low 21 bits of `x` to every third bit.
    fn spread(x: u32) -> u64 {
        let mut x = u64::from(x) & ((1 << BITS) - 1);
        x = (x | x << 32) & 0x1f00000000ffff;
        x = (x | x << 16) & 0x1f0000ff0000ff;
        x = (x | x << 8) & 0x100f00f00f00f00f;
        x = (x | x << 4) & 0x10c30c30c30c30c3;
        (x | x << 2) & 0x1249249249249249
    }
    spread(cell[0]) | spread(cell[1]) << 1 | spread(cell[2]) << 2
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::Point3;

    #[test]
    fn morton_interleaves_the_bits_of_each_axis() {
        // Brute force: bit b of axis k is bit 3b + k of the key.
        let cells = [
            [0, 0, 0],
            [1, 0, 0],
            [0, 1, 0],
            [0, 0, 1],
            [5, 3, 7],
            [(1 << 21) - 1, 12345, 999_999],
        ];
        for cell in cells {
            let mut expected = 0u64;
            for b in 0..BITS {
                for (k, &c) in cell.iter().enumerate() {
                    expected |= u64::from(c >> b & 1) << (3 * b + k as u32);
                }
            }
            assert_eq!(morton(cell), expected, "{cell:?}");
        }
    }

    /// A grid of `n` × `n` unit squares in the plane z = `z`, its faces listed in a shuffled
    /// order (as a scanner's export leaves them).
    fn shuffled_grid(n: u32, z: f64) -> Mesh {
        let vertices = (0..=n)
            .flat_map(|i| (0..=n).map(move |j| Point3::new(f64::from(i), f64::from(j), z)))
            .collect();
        let at = |i: u32, j: u32| i * (n + 1) + j;
        let mut faces: Vec<Vec<u32>> = (0..n)
            .flat_map(|i| {
                (0..n).map(move |j| vec![at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)])
            })
            .collect();
        let mut seed = 7u64;
        for k in (1..faces.len()).rev() {
            seed = seed
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            faces.swap(k, (seed >> 33) as usize % (k + 1));
        }
        Mesh::from_polygons(vertices, faces).unwrap()
    }

    #[test]
    fn every_face_once_and_neighbours_near() {
        // A flat grid (one axis without extent) and the same grid lifted far from the origin.
        for z in [0.0, 1e8] {
            let mesh = shuffled_grid(64, z);
            let order = faces_in_space_order(&mesh);
            let mut sorted = order.clone();
            sorted.sort_unstable();
            assert_eq!(sorted, (0..mesh.faces().len() as u32).collect::<Vec<_>>());
            // Consecutive faces in the order are near: a Z-order curve through a 64 × 64 grid
            // moves about 1.6 cells a step on average, a random order about 34.
            let first = |f: u32| mesh.vertices()[mesh.faces()[f as usize].vertices()[0] as usize];
            let mean = order
                .windows(2)
                .map(|w| (first(w[0]) - first(w[1])).norm())
                .sum::<f64>()
                / (order.len() - 1) as f64;
            assert!(mean < 2.0, "{mean}");
            let shuffled = (1..mesh.faces().len() as u32)
                .map(|f| (first(f - 1) - first(f)).norm())
                .sum::<f64>()
                / (mesh.faces().len() - 1) as f64;
            assert!(shuffled > 20.0, "{shuffled}");
        }
    }
}
