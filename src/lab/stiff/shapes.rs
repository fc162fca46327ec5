//! The solids the stiff scenes are built of (hexahedra, parallelepipeds, tetrahedra and
//! prisms, turned outward or inside out) and the small lengths that place them.

use crate::geometry::exact::ldexp;
use crate::geometry::{Point3, Vector3};
use crate::mesh::Mesh;
use std::cmp::Ordering;

/// `10^e` rounded to the nearest power of two (`10^-15` is `2^-50`): a length that keeps sums
/// with multiples of 1/8 below 4 exact.
pub(super) fn ten_to_the(e: i32) -> f64 {
    ldexp(
        1.0,
        (f64::from(e) * std::f64::consts::LOG2_10).round() as i32,
    )
}

/// The objects with their names as strings.
pub(super) fn named<const N: usize>(objects: [(&str, Mesh); N]) -> Vec<(String, Mesh)> {
    objects
        .into_iter()
        .map(|(name, mesh)| (name.to_string(), mesh))
        .collect()
}

/// The faces of a hexahedron whose corner `c` is on the high side of axis `i` when bit `i` of
/// `c` is set (as [`crate::solids::box_between`] numbers them).
pub(super) const BOX_FACES: [[u32; 4]; 6] = [
    [0, 4, 6, 2],
    [1, 3, 7, 5],
    [0, 1, 5, 4],
    [2, 6, 7, 3],
    [0, 2, 3, 1],
    [4, 5, 7, 6],
];

/// The hexahedron with these corners (numbered as in [`BOX_FACES`]), turned outward.
pub(super) fn hexahedron(corners: [Point3; 8]) -> crate::Result<Mesh> {
    let faces = BOX_FACES.iter().map(|f| f.to_vec()).collect();
    outward(Mesh::from_polygons(corners.to_vec(), faces)?)
}

/// The parallelepiped at `o` with edges `u`, `v`, `w`, turned outward.
pub(super) fn parallelepiped(o: Point3, [u, v, w]: [Vector3; 3]) -> crate::Result<Mesh> {
    hexahedron(std::array::from_fn(|c| {
        let mut p = o;
        for (bit, e) in [u, v, w].iter().enumerate() {
            if c & (1 << bit) != 0 {
                p += *e;
            }
        }
        p
    }))
}

/// The tetrahedron with these corners, turned outward.
pub(super) fn tetrahedron(p: [Point3; 4]) -> crate::Result<Mesh> {
    let faces = vec![vec![0, 2, 1], vec![0, 1, 3], vec![1, 2, 3], vec![0, 3, 2]];
    outward(Mesh::from_polygons(p.to_vec(), faces)?)
}

/// The prism swept by the triangle `t` along `a`, turned outward.
pub(super) fn prism(t: [Point3; 3], a: Vector3) -> crate::Result<Mesh> {
    let vertices = vec![t[0], t[1], t[2], t[0] + a, t[1] + a, t[2] + a];
    let faces = vec![
        vec![0, 2, 1],
        vec![3, 4, 5],
        vec![0, 1, 4, 3],
        vec![1, 2, 5, 4],
        vec![2, 0, 3, 5],
    ];
    outward(Mesh::from_polygons(vertices, faces)?)
}

/// The mesh with its faces turned outward (its exact orientation positive).
pub(super) fn outward(mesh: Mesh) -> crate::Result<Mesh> {
    match mesh.orientation() {
        Ordering::Less => reversed(&mesh),
        _ => Ok(mesh),
    }
}

/// The mesh with every face reversed: inside out.
pub(super) fn reversed(mesh: &Mesh) -> crate::Result<Mesh> {
    let faces = mesh
        .polygons()
        .into_iter()
        .map(|mut f| {
            f.reverse();
            f
        })
        .collect();
    Ok(Mesh::from_polygons(mesh.vertices().to_vec(), faces)?)
}
