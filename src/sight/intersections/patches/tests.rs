//! The certified patches against an exact rational test of every pair they leave out (the
//! pair search with them is tested against every pair in `intersections/tests.rs`).

use super::{self as patches, NONE};
use crate::geometry::{Aabb, Point3};
use crate::mesh::Mesh;
use crate::random::SplitMix64;
use crate::sight::intersections::surely_apart;
use crate::solids::{torus, uv_sphere};
use num_rational::BigRational;
use num_traits::Zero;

type Q = BigRational;

fn rational(p: &Point3) -> [Q; 3] {
    [0, 1, 2].map(|k| Q::from_float(p[k]).unwrap())
}

fn sub(a: &[Q; 3], b: &[Q; 3]) -> [Q; 3] {
    [0, 1, 2].map(|k| &a[k] - &b[k])
}

fn cross(a: &[Q; 3], b: &[Q; 3]) -> [Q; 3] {
    [0, 1, 2].map(|k| {
        let (i, j) = ((k + 1) % 3, (k + 2) % 3);
        &a[i] * &b[j] - &a[j] * &b[i]
    })
}

fn dot(a: &[Q; 3], b: &[Q; 3]) -> Q {
    (0..3).fold(Q::zero(), |s, k| s + &a[k] * &b[k])
}

/// Whether two non-degenerate closed triangles share a point, exactly (after the float
/// filter [`surely_apart`], itself tested against exact tests): they do unless one
/// of the separating axes of two flat convex polygons (both normals, the nine cross
/// products of their sides, and each normal crossed with the other's sides) separates them.
pub(in crate::sight::intersections) fn meet_exactly(t: &[Point3; 3], u: &[Point3; 3]) -> bool {
    if surely_apart(t, u) {
        return false;
    }
    let (a, b) = (t.map(|p| rational(&p)), u.map(|p| rational(&p)));
    let sides = |x: &[[Q; 3]; 3]| [0, 1, 2].map(|i| sub(&x[(i + 1) % 3], &x[i]));
    let (e, f) = (sides(&a), sides(&b));
    let (n, m) = (cross(&e[0], &e[1]), cross(&f[0], &f[1]));
    let mut axes = vec![n.clone(), m.clone()];
    for i in 0..3 {
        axes.extend(f.iter().map(|fj| cross(&e[i], fj)));
        axes.push(cross(&n, &e[i]));
        axes.push(cross(&m, &f[i]));
    }
    !axes.iter().any(|axis| {
        let span = |x: &[[Q; 3]; 3]| {
            let d: Vec<Q> = x.iter().map(|p| dot(axis, p)).collect();
            let lo = d.iter().min().unwrap().clone();
            let hi = d.iter().max().unwrap().clone();
            (lo, hi)
        };
        let ((lo_a, hi_a), (lo_b, hi_b)) = (span(&a), span(&b));
        hi_a < lo_b || hi_b < lo_a
    })
}

/// The boxes, size sum and classes of `m`'s triangles, as the pair search computes them.
fn classified(m: &Mesh) -> (Vec<Aabb>, f64, Vec<u32>) {
    let mut boxes = Vec::new();
    let (mut sizes, mut classes) = (0.0, Vec::new());
    for t in 0..m.triangles().len() {
        let [a, b, c] = m.triangle(t);
        let normal = (b - a).cross(&(c - a));
        boxes.push(Aabb::from_points(&[a, b, c]));
        sizes += normal.norm().sqrt();
        classes.push(patches::class(&[a, b, c], &normal));
    }
    (boxes, sizes, classes)
}

/// Certifies `m` with cells of `cell` mean triangle sizes, and checks the certificate: no
/// two triangles of one certified patch that share no vertex meet (exactly). Returns the
/// share of triangles certified and how many pairs in `m` meet that share no vertex.
fn check_certificate(m: &Mesh, cell: f64) -> (f64, usize) {
    let (boxes, sizes, classes) = classified(m);
    let whole = boxes.iter().fold(Aabb::EMPTY, |u, b| u.union(b));
    let n = boxes.len();
    let patch = patches::certified(m, &boxes, &classes, whole, cell * sizes / n as f64).patch;
    let tri = m.triangles();
    let mut meeting = 0;
    for i in 0..n {
        for j in i + 1..n {
            if !boxes[i].intersects(&boxes[j]) || tri[i].iter().any(|v| tri[j].contains(v)) {
                continue;
            }
            if meet_exactly(&m.triangle(i), &m.triangle(j)) {
                meeting += 1;
                let p = patch[i];
                assert!(
                    p == NONE || p != patch[j],
                    "{i} and {j} meet in one certified patch: {:?} {:?}",
                    m.triangle(i),
                    m.triangle(j)
                );
            }
        }
    }
    let certified = patch.iter().filter(|&&p| p != NONE).count();
    (certified as f64 / n as f64, meeting)
}

/// A UV sphere whose vertices are moved by up to `bump` along each axis (seeded): clean for
/// small bumps, piercing itself for large ones.
pub(in crate::sight::intersections) fn bumpy(
    segments: u32,
    rings: u32,
    bump: f64,
    seed: u64,
) -> Mesh {
    let s = uv_sphere(1.0, segments, rings).unwrap();
    let mut rng = SplitMix64(seed);
    let vertices = s.vertices().iter().map(|p| p + rng.vector(bump)).collect();
    let faces = s.triangles().iter().map(|t| t.to_vec()).collect();
    Mesh::from_polygons(vertices, faces).unwrap()
}

/// Square grids of `n × n` vertices as one mesh: `sheets` gives each sheet's corner, its two
/// side vectors (the normal is their cross product) and the height it rises by across.
fn sheets(n: usize, sheets: &[([f64; 3], [f64; 3], [f64; 3])]) -> Mesh {
    let (mut vertices, mut faces) = (Vec::new(), Vec::new());
    for &(corner, u, v) in sheets {
        let base = vertices.len() as u32;
        for j in 0..n {
            for i in 0..n {
                let (s, t) = (i as f64 / (n - 1) as f64, j as f64 / (n - 1) as f64);
                vertices.push(Point3::from(
                    [0, 1, 2].map(|k| corner[k] + s * u[k] + t * v[k]),
                ));
            }
        }
        let at = |i: usize, j: usize| base + (j * n + i) as u32;
        for j in 0..n - 1 {
            for i in 0..n - 1 {
                faces.push(vec![at(i, j), at(i + 1, j), at(i + 1, j + 1)]);
                faces.push(vec![at(i, j), at(i + 1, j + 1), at(i, j + 1)]);
            }
        }
    }
    Mesh::from_polygons(vertices, faces).unwrap()
}

#[test]
fn certified_patches_hold_no_meeting_pair() {
    // Clean closed surfaces: almost all certified, in small cells and in one.
    for (m, cell) in [
        (bumpy(40, 20, 0.01, 1), 8.0),
        (bumpy(40, 20, 0.01, 2), 1e9),
        (torus(1.0, 0.3, 48, 16).unwrap(), 6.0),
        (uv_sphere(1.0, 300, 2).unwrap(), 4.0),
    ] {
        let (share, meeting) = check_certificate(&m, cell);
        assert_eq!(meeting, 0);
        assert!(
            share > 0.9,
            "only {share} certified of {}",
            m.triangles().len()
        );
    }
    // Crumpled spheres pierce themselves; the patches where they do are not certified.
    // (Moving the vertices by up to 0.08 along each axis, on triangles of about 0.2.)
    for seed in 0..6 {
        let m = bumpy(30, 15, 0.08, seed);
        let (share, meeting) = check_certificate(&m, 4.0 + seed as f64);
        assert!(meeting > 0, "seed {seed} does not pierce itself");
        assert!(share > 0.05, "seed {seed}: only {share} certified");
    }
}

#[test]
fn sheets_that_cross_or_cover_each_other_are_not_certified_together() {
    // Two sheets facing up, one tilted through the other (same class, one cell): their
    // loops nest or cross in the picture.
    let flat = ([0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]);
    for tilted in [
        ([0.2, 0.2, -0.1], [0.6, 0.0, 0.2], [0.0, 0.6, 0.0]),
        ([0.5, 0.5, -0.1], [1.0, 0.0, 0.3], [0.0, 1.0, 0.0]),
    ] {
        let m = sheets(12, &[flat, tilted]);
        let (_, meeting) = check_certificate(&m, 1e9);
        assert!(meeting > 0);
    }
    // One sheet above another, apart: covered twice in the picture, so two patches (their
    // pairs are tested), each certified.
    let above = ([0.25, 0.25, 0.5], [0.5, 0.0, 0.0], [0.0, 0.5, 0.0]);
    let m = sheets(12, &[flat, above]);
    let (boxes, sizes, classes) = classified(&m);
    let whole = boxes.iter().fold(Aabb::EMPTY, |u, b| u.union(b));
    let patch = patches::certified(&m, &boxes, &classes, whole, 1e9 * sizes).patch;
    let half = m.triangles().len() / 2;
    assert_ne!(patch[0], patch[half]);
    assert!(patch[..half].iter().all(|&p| p == patch[0]));
    assert!(patch.iter().all(|&p| p != NONE));
}

/// The boundary of loops of points `(x, y)`, each loop's points in order, numbered in
/// order of `points` (a point shared by two loops is given again by its number, as `[-1, n]`).
fn boundary_of(points: &[[f64; 2]], loops: &[&[usize]]) -> Vec<(u32, u32)> {
    let _ = points;
    loops
        .iter()
        .flat_map(|l| (0..l.len()).map(|i| (l[i] as u32, l[(i + 1) % l.len()] as u32)))
        .collect()
}

#[test]
fn loops_wind_once_round_what_they_cover() {
    let points = [
        [0.0, 0.0],
        [4.0, 0.0],
        [4.0, 4.0],
        [0.0, 4.0], // 0-3: a square
        [1.0, 1.0],
        [3.0, 1.0],
        [3.0, 3.0],
        [1.0, 3.0], // 4-7: a square inside it
        [5.0, 0.0],
        [6.0, 0.0],
        [6.0, 1.0],
        [5.0, 1.0], // 8-11: a square beside it
        [2.0, 1.0],
        [1.0, 2.0], // 12-13: a notch at corner 0
        [5.0, 4.0],
        [5.0, 5.0],
        [4.0, 5.0], // 14-16: a square at corner 2
    ];
    let at = |v: u32| points[v as usize];
    let certified = |loops: &[&[usize]], s: i32| {
        patches::boundary_certified(boundary_of(&points, loops), &at, s)
    };
    let (outer, inner, beside): (&[usize], &[usize], &[usize]) =
        (&[0, 1, 2, 3], &[4, 5, 6, 7], &[8, 9, 10, 11]);
    let reversed = |l: &[usize]| l.iter().rev().copied().collect::<Vec<_>>();
    // A disk, its reverse, each for the sign that covers it.
    assert!(certified(&[outer], 1));
    assert!(!certified(&[outer], -1));
    assert!(certified(&[&reversed(outer)], -1));
    // A disk with a hole, and two disks one inside the other (covered twice).
    assert!(certified(&[outer, &reversed(inner)], 1));
    assert!(!certified(&[outer, inner], 1));
    // Two disks side by side, and a disk beside a hole in nothing.
    assert!(certified(&[outer, beside], 1));
    assert!(!certified(&[outer, &reversed(beside)], 1));
    // A hole touching the boundary at corner 0 (a pinch), and two squares touching at
    // corner 2: loops that touch without crossing.
    assert!(certified(&[outer, &[0, 13, 12]], 1));
    assert!(!certified(&[outer, &[0, 12, 13]], 1));
    assert!(certified(&[outer, &[2, 14, 15, 16]], 1));
    // A loop through the corner of another, crossing it there.
    assert!(!certified(&[outer, &[2, 16, 15, 14]], 1));
    // The square and the square inside it, joined at one corner into one walk.
    assert!(!certified(&[&[0, 1, 2, 3, 0, 4, 5, 6, 7, 4]], 1));
}

#[test]
fn loops_through_a_pinch_may_touch_but_not_cross() {
    // Vertex 0 at the origin, and six points round it every 60 degrees from 1.
    let points: Vec<[f64; 2]> = std::iter::once([0.0, 0.0])
        .chain((0..6).map(|k| {
            let a = std::f64::consts::PI / 3.0 * k as f64;
            [a.cos(), a.sin()]
        }))
        .collect();
    let at = |v: u32| points[v as usize];
    let touch = |loops: &[Vec<u32>]| patches::touch_without_crossing(&[0], loops, &at);
    // Each loop arrives from one point and leaves to the next: three lobes touching.
    assert!(touch(&[vec![0, 2, 1], vec![0, 4, 3], vec![0, 6, 5]]));
    // Nested pairs touch too: (1, 4) round (2, 3).
    assert!(touch(&[vec![0, 4, 1], vec![0, 3, 2]]));
    // Interleaved pairs cross: (1, 3) and (2, 4).
    assert!(!touch(&[vec![0, 3, 1], vec![0, 4, 2]]));
    assert!(!touch(&[vec![0, 2, 1], vec![0, 5, 3], vec![0, 6, 4]]));
}
