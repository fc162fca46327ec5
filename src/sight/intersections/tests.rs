//! The candidate pairs against every pair, and the exact filters against the exact tests.

use super::candidates::{FEW_PAIRS, Pairing, candidate_pairs, few_pairs};
use super::patches::tests::{bumpy, meet_exactly};
use super::*;
use crate::geometry::Aabb;
use crate::random::SplitMix64;
use crate::solids::uv_sphere;
use nalgebra::{Matrix4, Vector3};

/// Whether the pair `(i, j)` gives the pass anything: a piece of an intersection segment,
/// or a contact (an edge through the other triangle).
fn productive(m0: &Mesh, i: usize, m1: &Mesh, j: usize) -> bool {
    let Some([s0, s1]) = sides(m0, i, m1, j) else {
        return false;
    };
    let (t0, t1) = (m0.triangle(i), m1.triangle(j));
    let eye = Eye::Infinity(Vector3::z());
    let planes = [plane_of(m0, i), plane_of(m1, j)];
    (crosses(&s0, m0, i)
        && crosses(&s1, m1, j)
        && piece(m0, i, m1, j, [s0, s1], planes, &eye).is_some())
        || edge_through(&t0, &s0, m0, i, &t1)
        || edge_through(&t1, &s1, m1, j, &t0)
}

/// The grid's pairs against every pair: none that gives anything is missed, and each
/// found is a pair whose boxes meet (and, in one mesh, that shares no vertex).
fn check(m0: &Mesh, m1: &Mesh, same: bool) -> usize {
    let boxes = |m: &Mesh| {
        (0..m.triangles().len())
            .map(|t| Aabb::from_points(&m.triangle(t)))
            .collect::<Vec<_>>()
    };
    let (b0, b1) = (boxes(m0), boxes(m1));
    assert!(b0.len() * b1.len() > FEW_PAIRS, "the grid is not used");
    let grid = candidate_pairs(m0, m1, same);
    assert!(
        grid.windows(2).all(|w| w[0] < w[1]),
        "not sorted and unique"
    );
    let all = few_pairs(m0, &b0, &b1, same);
    for &(i, j) in &grid {
        assert!(
            all.binary_search(&(i, j)).is_ok(),
            "({i}, {j}) is not a candidate"
        );
    }
    let mut productive_pairs = 0;
    for &(i, j) in &all {
        if productive(m0, i as usize, m1, j as usize) {
            productive_pairs += 1;
            assert!(
                grid.binary_search(&(i, j)).is_ok(),
                "({i}, {j}) missed: {:?} {:?} same {same}",
                m0.triangle(i as usize),
                m1.triangle(j as usize)
            );
        }
    }
    productive_pairs
}

fn moved(m: &Mesh, by: [f64; 3], scale: f64) -> Mesh {
    let t = Matrix4::new_translation(&Vector3::from(by)) * Matrix4::new_scaling(scale);
    m.transformed(&t).unwrap()
}

/// Random triangles, some large and some slivers, crossing each other everywhere.
fn soup(n: usize, seed: u64) -> Mesh {
    let mut rng = SplitMix64(seed);
    let mut next = || rng.unit();
    let mut vertices = Vec::new();
    let mut faces = Vec::new();
    for k in 0..n {
        let c = Point3::new(next(), next(), next());
        let r = if k % 3 == 0 { 0.5 } else { 0.08 };
        let thin = if k % 5 == 0 { 1e-6 } else { 1.0 };
        let a = c + Vector3::new(next() - 0.5, next() - 0.5, next() - 0.5) * r;
        let b = c + Vector3::new(next() - 0.5, next() - 0.5, next() - 0.5) * r;
        let d =
            a + (b - a) * 0.5 + Vector3::new(next() - 0.5, next() - 0.5, next() - 0.5) * r * thin;
        let v = vertices.len() as u32;
        vertices.extend([a, b, d]);
        faces.push(vec![v, v + 1, v + 2]);
    }
    Mesh::from_polygons(vertices, faces).unwrap()
}

#[test]
fn triangles_surely_apart_make_nothing() {
    // Pairs of the soups, and pairs that touch exactly: at a vertex, along an edge, a
    // vertex on the other's interior; and pairs apart by one ulp.
    let mut apart = 0;
    for seed in 0..3 {
        let (s, t) = (soup(300, seed), soup(300, seed + 50));
        for i in 0..s.triangles().len() {
            for j in 0..t.triangles().len() {
                if surely_apart(&s.triangle(i), &t.triangle(j)) {
                    apart += 1;
                    assert!(!productive(&s, i, &t, j), "{i} {j} are not apart");
                }
            }
        }
    }
    assert!(apart > 10_000);
    let p = |x: f64, y: f64, z: f64| Point3::new(x, y, z);
    let a = [p(0.0, 0.0, 0.0), p(1.0, 0.0, 0.0), p(0.0, 1.0, 0.0)];
    let touching = [
        [p(1.0, 0.0, 0.0), p(2.0, 1.0, 1.0), p(2.0, -1.0, 0.5)],
        [p(0.5, 0.5, 0.0), p(0.5, 0.5, 1.0), p(1.5, 1.5, 0.3)],
        [p(0.25, 0.25, 0.0), p(3.0, 1.0, 1.0), p(1.0, 3.0, -1.0)],
        [p(0.1, 0.1, -1.0), p(0.1, 0.1, 1.0), p(-3.0, 0.1, 0.0)],
    ];
    for b in &touching {
        assert!(!surely_apart(&a, b), "{b:?} touches");
        assert!(!surely_apart(b, &a), "{b:?} touches");
    }
    let next = 1.0f64.next_up();
    let beyond = [p(next, 0.0, 0.0), p(2.0, 1.0, 1.0), p(2.0, -1.0, 0.5)];
    // One ulp away is apart, but too close for the filter to be sure: the exact test decides.
    assert!(!surely_apart(&a, &beyond));
    let far = [p(1.5, 0.0, 0.0), p(2.0, 1.0, 1.0), p(2.0, -1.0, 0.5)];
    assert!(surely_apart(&a, &far));
}

/// Splits a crowded cell on the rims of the fans `fan` and `turned` (two meshes): the
/// smaller cells find every pair that meets in it.
fn split_rim_cell_misses_no_pair(fan: &Mesh, turned: &Mesh) {
    let boxes = |m: &Mesh| -> Vec<Aabb> {
        (0..m.triangles().len())
            .map(|t| Aabb::from_points(&m.triangle(t)))
            .collect()
    };
    let (b0, b1) = (boxes(fan), boxes(turned));
    let pairing = Pairing {
        meshes: [fan, turned],
        boxes: [&b0, &b1],
        same: false,
        patch: &[],
    };
    let region = Aabb::new(
        Point3::new(0.95, -0.05, -0.05),
        Point3::new(1.05, 0.05, 0.05),
    );
    let near = |b: &[Aabb]| -> Vec<u32> {
        (0..b.len() as u32)
            .filter(|&t| b[t as usize].intersects(&region))
            .collect()
    };
    let (near0, near1) = (near(&b0), near(&b1));
    assert!(near0.len() > 30 && near1.len() > 30);
    let items: Vec<u32> = near0
        .iter()
        .copied()
        .chain(near1.iter().map(|t| t | 1 << 31))
        .collect();
    let mut out = Vec::new();
    let load = |sub: &[u32]| {
        let firsts = sub.partition_point(|i| i >> 31 == 0);
        firsts * (sub.len() - firsts)
    };
    assert!(pairing.split(&items, &region, 0, &mut out, load));
    out.sort_unstable();
    out.dedup();
    let mut productive_pairs = 0;
    for &i in &near0 {
        for &j in &near1 {
            let (t0, t1) = (fan.triangle(i as usize), turned.triangle(j as usize));
            // Pairs that meet in the region: slivers with a rim corner well inside it
            // (they meet within a sliver's width of their rim corners).
            let inner = Aabb::new(
                Point3::new(0.96, -0.04, -0.04),
                Point3::new(1.04, 0.04, 0.04),
            );
            let inside = |t: &[Point3; 3]| t.iter().any(|p| inner.contains_point(p));
            if inside(&t0) && inside(&t1) && productive(fan, i as usize, turned, j as usize) {
                productive_pairs += 1;
                assert!(out.binary_search(&(i, j)).is_ok(), "({i}, {j}) missed");
            }
        }
    }
    assert!(productive_pairs > 30);
}

/// The meshes `a` and `b` as one mesh (`b`'s vertices after `a`'s).
pub(super) fn joined(a: &Mesh, b: &Mesh) -> Mesh {
    Mesh::from_polygons(
        a.vertices().iter().chain(b.vertices()).copied().collect(),
        a.triangles()
            .iter()
            .map(|t| t.to_vec())
            .chain(
                b.triangles()
                    .iter()
                    .map(|t| t.iter().map(|v| v + a.vertices().len() as u32).collect()),
            )
            .collect(),
    )
    .unwrap()
}

#[test]
fn crowded_cells_are_split_and_miss_no_pair() {
    // Two fans of 3,000 slivers, one turned by a third of a sliver about the axis and
    // raised a little: along the rims, each sliver crosses several of the other's, and
    // the rims' cells hold hundreds of triangles.
    let fan = uv_sphere(1.0, 1500, 2).unwrap();
    let turn = nalgebra::Rotation3::from_axis_angle(&Vector3::z_axis(), 0.7e-3).to_homogeneous();
    let turned = fan
        .transformed(&(Matrix4::new_translation(&Vector3::new(0.0, 0.0, 1e-3)) * turn))
        .unwrap();
    assert!(check(&fan, &turned, false) > 1000);
    // A crowded cell on the rims is split, and the smaller cells find every pair that
    // meets in it.
    split_rim_cell_misses_no_pair(&fan, &turned);
    // One mesh: the two fans as one soup of crossing slivers.
    let both = joined(&fan, &turned);
    assert!(check(&both, &both, true) > 1000);
}

#[test]
fn the_grid_misses_no_pair_of_a_fan_or_a_soup() {
    // Two cones of 600 slivers base to base: every pair meets at an apex or the rim.
    let fan = uv_sphere(1.0, 600, 2).unwrap();
    check(&fan, &fan, true);
    // The fan against itself turned and moved so the apexes pierce the other's sides.
    let other = moved(&fan, [0.25, 0.1, 0.5], 0.75);
    assert!(check(&fan, &other, false) > 0);
    for seed in 0..4 {
        let s = soup(400, seed);
        assert!(check(&s, &s, true) > 0);
        let t = soup(300, seed + 100);
        assert!(check(&s, &t, false) > 0);
    }
    // Spheres that cut each other, and at extreme scales and offsets.
    let sphere = uv_sphere(1.0, 48, 24).unwrap();
    for (by, scale) in [
        ([0.5, 0.3, 0.2], 1.0),
        ([1e8, 0.0, 0.0], 1e-7),
        ([0.0; 3], 1e-90),
    ] {
        let a = moved(&sphere, by, scale);
        let b = moved(&sphere, [by[0] + 0.7 * scale, by[1], by[2]], scale);
        assert!(check(&a, &b, false) > 0);
    }
}

/// Whether the pair `(i, j)` of `m`'s triangles meets, sharing no vertex and no face.
fn apart_neighbours(m: &Mesh, i: usize, j: usize) -> bool {
    let tri = m.triangles();
    tri[i].iter().any(|v| tri[j].contains(v)) || m.face_of(i) == m.face_of(j)
}

#[test]
fn the_pair_search_with_patches_misses_no_meeting_pair() {
    // Every pair of one mesh that meets (exactly) and shares no vertex or face is among the
    // candidates: clean, crumpled, and two spheres in one mesh cutting each other, also far
    // from the origin and tiny.
    let two = |by: [f64; 3], scale: f64| {
        let a = bumpy(24, 12, 0.02, 7);
        let b = a
            .transformed(&nalgebra::Matrix4::new_translation(&Vector3::new(
                0.6, 0.2, 0.1,
            )))
            .unwrap();
        let both = joined(&a, &b);
        let t = nalgebra::Matrix4::new_translation(&Vector3::from(by))
            * nalgebra::Matrix4::new_scaling(scale);
        both.transformed(&t).unwrap()
    };
    let meshes = [
        bumpy(40, 20, 0.01, 3),
        bumpy(30, 15, 0.3, 4),
        two([0.0; 3], 1.0),
        two([1e8, 0.0, 0.0], 1e-7),
        two([0.0; 3], 1e-90),
    ];
    for m in &meshes {
        let n = m.triangles().len();
        assert!(n * n > FEW_PAIRS);
        let boxes: Vec<Aabb> = (0..n).map(|t| Aabb::from_points(&m.triangle(t))).collect();
        let found = candidate_pairs(m, m, true);
        let mut meeting = 0;
        for (i, j) in few_pairs(m, &boxes, &boxes, true) {
            let (i, j) = (i as usize, j as usize);
            if !apart_neighbours(m, i, j) && meet_exactly(&m.triangle(i), &m.triangle(j)) {
                meeting += 1;
                assert!(
                    found.binary_search(&(i as u32, j as u32)).is_ok(),
                    "({i}, {j}) missed"
                );
            }
        }
        assert!(meeting > 0 || n == meshes[0].triangles().len());
    }
}
