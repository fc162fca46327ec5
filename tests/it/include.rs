//! INCLUDE (Franklin 1981, algorithm A) against an independent exact reference.
//!
//! The reference below uses exact rational arithmetic (every `f64` converted exactly with
//! `BigRational::from_float`, then brought to one power-of-two denominator so that the signs
//! are computed on `BigInt` numerators) and a ray in the +X direction, where the library
//! shoots its ray along +Z: a point is ON if it lies on some closed triangle of an object's mesh, else IN iff the
//! symbolically perturbed +X ray crosses an odd number of triangles; a group is the union of
//! its subobjects (IN if any is IN, else ON if any is ON, else OUT). Every test point is
//! checked against the single query [`include`] (for every object of the subtree),
//! [`IncludeIndex::include`], [`IncludeIndex::include_all`] and, for each mesh,
//! [`ProjectionGrid::classify`]; every disagreement fails the test with the point and both
//! answers.
//!
//! Shapes: random voxel shapes (also inside out), random stacks of unit cubes, random
//! star-shaped lattice polyhedra, randomly rotated Platonic solids, a torus, non-convex prisms
//! and nested objects; points on lattices through the vertices, edges and faces, the vertices,
//! edge midpoints and face centroids themselves, points whose axis-parallel rays pass exactly
//! through them, and random points.

use std::collections::HashSet;
use std::path::Path;

use crate::common::SplitMix64;

use kepler::geometry::{Point3, Vector3};
use kepler::mesh::Mesh;
use kepler::queries::include::{IncludeIndex, Inclusion, include};
use kepler::queries::projection_grid::ProjectionGrid;
use kepler::queries::{Counters, Stage};
use kepler::scene::{ObjectId, Scene};
use kepler::solids;
use nalgebra::{Matrix4, Quaternion, Translation3, UnitQuaternion};
use num_bigint::{BigInt, Sign};
use num_rational::BigRational;
use num_traits::{One, Signed, Zero};
use proptest::prelude::*;
use rayon::prelude::*;

// ---------------------------------------------------------------------------------------------
// The exact reference.

/// Exact coordinates. Every `f64` is a dyadic rational `m / 2^k` (its exact value is
/// `BigRational::from_float`); multiplying all the coordinates of a test by one power of two
/// `2^s` with `s` at least every such `k` makes them integers, which are then exact `BigInt`s.
/// Every predicate below is a homogeneous polynomial in coordinate differences, so its sign
/// is unchanged by that positive factor. (`BigRational` arithmetic directly gives the same
/// signs, but reduces by a gcd at every operation, which made the reference about twenty
/// times slower.)
type Z = BigInt;

/// The common scale `2^s` of a test's coordinates.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
struct Scale(u64);

impl Scale {
    /// The exact rational value of a finite `f64`, as `numerator / 2^k`.
    fn dyadic(x: f64) -> (Z, u64) {
        let r = BigRational::from_float(x).expect("finite coordinate");
        let k = r.denom().bits() - 1;
        assert_eq!(
            r.denom(),
            &(Z::one() << k),
            "the denominator of {x:?} is a power of 2"
        );
        (r.numer().clone(), k)
    }

    /// The smallest scale that makes all `values` integers.
    fn of(values: impl IntoIterator<Item = f64>) -> Scale {
        Scale(
            values
                .into_iter()
                .map(|x| Scale::dyadic(x).1)
                .max()
                .unwrap_or(0),
        )
    }

    /// The smallest scale that makes the coordinates of all these points integers.
    fn of_points<'a>(points: impl IntoIterator<Item = &'a Point3>) -> Scale {
        Scale::of(points.into_iter().flat_map(|p| [p.x, p.y, p.z]))
    }

    fn max(self, other: Scale) -> Scale {
        Scale(self.0.max(other.0))
    }

    /// `x · 2^s`, exactly; panics if that is not an integer.
    fn int(self, x: f64) -> Z {
        let (m, k) = Scale::dyadic(x);
        assert!(
            k <= self.0,
            "{x:?} needs a scale of 2^{k}, more than 2^{}",
            self.0
        );
        m << (self.0 - k)
    }

    fn point(self, p: &Point3) -> [Z; 3] {
        [self.int(p.x), self.int(p.y), self.int(p.z)]
    }
}

/// -1, 0 or 1.
fn sign(x: &Z) -> i8 {
    match x.sign() {
        Sign::Plus => 1,
        Sign::Minus => -1,
        Sign::NoSign => 0,
    }
}

fn sub(a: &[Z; 3], b: &[Z; 3]) -> [Z; 3] {
    [&a[0] - &b[0], &a[1] - &b[1], &a[2] - &b[2]]
}

fn cross(a: &[Z; 3], b: &[Z; 3]) -> [Z; 3] {
    [
        &a[1] * &b[2] - &a[2] * &b[1],
        &a[2] * &b[0] - &a[0] * &b[2],
        &a[0] * &b[1] - &a[1] * &b[0],
    ]
}

fn dot(a: &[Z; 3], b: &[Z; 3]) -> Z {
    &a[0] * &b[0] + &a[1] * &b[1] + &a[2] * &b[2]
}

/// Twice the signed area of the triangle (a, b, c) in the plane of coordinates (i, j):
/// positive when it turns counter-clockwise from axis i towards axis j.
fn orient2(a: &[Z; 3], b: &[Z; 3], c: &[Z; 3], i: usize, j: usize) -> Z {
    (&b[i] - &a[i]) * (&c[j] - &a[j]) - (&b[j] - &a[j]) * (&c[i] - &a[i])
}

/// A point, as `f64` (for exact comparisons) and exactly, at a scale.
struct RefPoint {
    f: [f64; 3],
    q: [Z; 3],
    scale: Scale,
}

impl RefPoint {
    fn new(p: &Point3, scale: Scale) -> RefPoint {
        RefPoint {
            f: [p.x, p.y, p.z],
            q: scale.point(p),
            scale,
        }
    }
}

/// A triangle (a, b, c) with what the tests below need precomputed: its exact corners, its
/// normal `n = (b - a) × (c - a)` and `n · a`, its edges in the (y, z) projection, and its
/// closed bounding box in `f64` (comparisons of `f64`s are exact, so the box only rules out
/// triangles that certainly cannot matter).
struct RefTri {
    v: [[Z; 3]; 3],
    n: [Z; 3],
    n_dot_a: Z,
    /// The sign of `n.x`, which is `orient_yz(a, b, c)`.
    nx_sign: i8,
    edges: [YzEdge; 3],
    lo: [f64; 3],
    hi: [f64; 3],
}

/// A directed edge (a, b) in the (y, z) projection: `orient_yz(a, b, p) = dy·p.z - dz·p.y - k`
/// with `dy = b.y - a.y`, `dz = b.z - a.z`, `k = dy·a.z - dz·a.y`, and the sign the
/// perturbation gives it when that is 0.
///
/// With u = y, v = z, `orient(a, b, q) = (b.u - a.u)(q.v - a.v) - (b.v - a.v)(q.u - a.u)`;
/// for the perturbed point `q = p + (ε, ε²)` (ε > 0 infinitesimal) it is
/// `orient(a, b, p) + (a.v - b.v)·ε + (b.u - a.u)·ε²`. So when `orient(a, b, p) = 0` its sign
/// is that of `a.z - b.z`, or if that is 0 of `b.y - a.y`: it depends on the edge only. Every
/// term changes sign when a and b are swapped, so the two triangles on either side of an
/// edge see the perturbed point on opposite sides of it: a ray through a shared edge or
/// vertex is counted exactly once. All terms are 0 only when a and b project to the same
/// point; the triangle's projection is then a segment, which the perturbed ray misses (the
/// tie sign 0 never matches the triangle's nonzero sign, and `n.x = 0` anyway).
struct YzEdge {
    dy: Z,
    dz: Z,
    k: Z,
    tie: i8,
}

impl YzEdge {
    fn new(a: &[Z; 3], b: &[Z; 3]) -> YzEdge {
        let (y, z) = (1, 2);
        let dy = &b[y] - &a[y];
        let dz = &b[z] - &a[z];
        let k = &dy * &a[z] - &dz * &a[y];
        let tie = match sign(&dz) {
            0 => sign(&dy),
            s => -s,
        };
        YzEdge { dy, dz, k, tie }
    }

    /// The sign of `orient_yz(a, b, p + (0, ε, ε²))`.
    fn perturbed_side(&self, p: &[Z; 3]) -> i8 {
        match sign(&(&self.dy * &p[2] - &self.dz * &p[1] - &self.k)) {
            0 => self.tie,
            s => s,
        }
    }
}

impl RefTri {
    fn new(t: &[Point3; 3], scale: Scale) -> RefTri {
        let v = t.map(|p| scale.point(&p));
        let n = cross(&sub(&v[1], &v[0]), &sub(&v[2], &v[0]));
        let n_dot_a = dot(&n, &v[0]);
        let nx_sign = sign(&n[0]);
        let edges = [0, 1, 2].map(|e| YzEdge::new(&v[e], &v[(e + 1) % 3]));
        RefTri {
            v,
            n,
            n_dot_a,
            nx_sign,
            edges,
            lo: [0, 1, 2].map(|k| t[0][k].min(t[1][k]).min(t[2][k])),
            hi: [0, 1, 2].map(|k| t[0][k].max(t[1][k]).max(t[2][k])),
        }
    }

    /// The sign of the 3x3 determinant `det[b - a; c - a; p - a] = n · (p - a)`: 0 iff p is
    /// on the triangle's plane.
    fn plane_side(&self, p: &RefPoint) -> i8 {
        sign(&(dot(&self.n, &p.q) - &self.n_dot_a))
    }

    /// Whether `p` lies on the closed triangle, exactly.
    fn contains(&self, p: &RefPoint) -> bool {
        // A point of the triangle is a convex combination of the corners: inside their box.
        if !(0..3).all(|k| self.lo[k] <= p.f[k] && p.f[k] <= self.hi[k]) {
            return false;
        }
        if self.plane_side(p) != 0 {
            return false;
        }
        // n[k] is the triangle's doubled signed area in the plane of the coordinates
        // ((k + 1) % 3, (k + 2) % 3); projecting along a k with n[k] ≠ 0 maps the plane
        // one-to-one, so p is in the triangle iff its projection is in the projected one.
        match (0..3).find(|&k| !self.n[k].is_zero()) {
            Some(k) => {
                let (i, j) = ((k + 1) % 3, (k + 2) % 3);
                let s = sign(&self.n[k]);
                (0..3).all(|e| {
                    let side = sign(&orient2(&self.v[e], &self.v[(e + 1) % 3], &p.q, i, j));
                    side * s >= 0
                })
            }
            // A triangle with collinear corners (the library should never make one): a
            // segment, or a point.
            None => (0..3).any(|e| {
                let (a, b) = (&self.v[e], &self.v[(e + 1) % 3]);
                let (ab, ap) = (sub(b, a), sub(&p.q, a));
                let t = dot(&ab, &ap);
                cross(&ab, &ap).iter().all(|x| x.is_zero())
                    && !t.is_negative()
                    && t <= dot(&ab, &ab)
            }),
        }
    }

    /// Whether the ray from `p' = p + (0, ε, ε²)` in the +X direction crosses the triangle at
    /// x > p.x. `p` must not lie on the triangle.
    ///
    /// The perturbed point is strictly inside the projected triangle iff the three edge signs
    /// ([`YzEdge`]) are equal and nonzero, and then they equal the sign s of
    /// `n.x = orient_yz(a, b, c)`. The ray `p + t·(1, 0, 0)` meets the plane
    /// `n · (x - a) = 0` at `t = -n · (p - a) / n.x`, so it crosses at x > p.x iff
    /// `sign(det[b - a; c - a; p - a]) = sign(n · (p - a)) = -s`. (That determinant is never 0
    /// here: p would be in the plane and, its projection being in the closed projected
    /// triangle, on the triangle. The perturbation moves p only in y and z, within the plane
    /// x = p.x, so the side of the plane at p' is the side at p.)
    fn crossed_by_x_ray(&self, p: &RefPoint) -> bool {
        // The perturbed point's projection is in the projected triangle only if p's (y, z)
        // is in the triangle's closed (y, z) box; a crossing at x > p.x needs x > p.x
        // somewhere on the triangle.
        if !(self.lo[1] <= p.f[1]
            && p.f[1] <= self.hi[1]
            && self.lo[2] <= p.f[2]
            && p.f[2] <= self.hi[2]
            && p.f[0] < self.hi[0])
        {
            return false;
        }
        let s = self.nx_sign;
        if s == 0 || self.edges.iter().any(|e| e.perturbed_side(&p.q) != s) {
            return false;
        }
        let d = self.plane_side(p);
        assert_ne!(
            d, 0,
            "reference: p is on the triangle's plane, so it should be ON"
        );
        d == -s
    }
}

/// A closed mesh as the reference sees it: its triangles.
struct RefMesh {
    tris: Vec<RefTri>,
    scale: Scale,
}

impl RefMesh {
    fn new(mesh: &Mesh, scale: Scale) -> RefMesh {
        RefMesh {
            tris: (0..mesh.triangles().len())
                .map(|t| RefTri::new(&mesh.triangle(t), scale))
                .collect(),
            scale,
        }
    }

    /// ON if p is on a triangle, else IN iff the perturbed +X ray crosses an odd number.
    fn classify(&self, p: &RefPoint) -> Inclusion {
        assert_eq!(p.scale, self.scale);
        if self.tris.iter().any(|t| t.contains(p)) {
            return Inclusion::On;
        }
        let crossings = self.tris.iter().filter(|t| t.crossed_by_x_ray(p)).count();
        if crossings % 2 == 1 {
            Inclusion::In
        } else {
            Inclusion::Out
        }
    }
}

/// The union rule: IN if any is IN, else ON if any is ON, else OUT.
fn union(answers: impl IntoIterator<Item = Inclusion>) -> Inclusion {
    let mut result = Inclusion::Out;
    for a in answers {
        match a {
            Inclusion::In => return Inclusion::In,
            Inclusion::On => result = Inclusion::On,
            Inclusion::Out => {}
        }
    }
    result
}

/// An object of the scene, as the reference sees it.
struct RefNode<'s> {
    id: ObjectId,
    path: String,
    kind: RefKind<'s>,
}

enum RefKind<'s> {
    Leaf(RefMesh, ProjectionGrid<'s>),
    Group(Vec<RefNode<'s>>),
}

impl<'s> RefNode<'s> {
    fn new(scene: &'s Scene, id: ObjectId, scale: Scale) -> RefNode<'s> {
        let o = &scene[id];
        let kind = match o.mesh() {
            Some(mesh) => RefKind::Leaf(RefMesh::new(mesh, scale), ProjectionGrid::new(mesh)),
            None => RefKind::Group(
                o.subobjects()
                    .iter()
                    .map(|&c| RefNode::new(scene, c, scale))
                    .collect(),
            ),
        };
        RefNode {
            id,
            path: scene.path(id),
            kind,
        }
    }

    /// The reference answer for this object, checking on the way the library's single query
    /// for it (and, for a mesh, its projection grid); disagreements go to `bad`.
    fn check(&self, scene: &Scene, p: &Point3, rp: &RefPoint, bad: &mut Vec<String>) -> Inclusion {
        let expected = match &self.kind {
            RefKind::Leaf(mesh, grid) => {
                let expected = mesh.classify(rp);
                let got: Inclusion = grid.classify(p).into();
                if got != expected {
                    bad.push(mismatch(
                        p,
                        &self.path,
                        "ProjectionGrid::classify",
                        got,
                        expected,
                    ));
                }
                expected
            }
            RefKind::Group(children) => {
                // Every child is checked, even after an IN.
                let answers: Vec<Inclusion> = children
                    .iter()
                    .map(|c| c.check(scene, p, rp, bad))
                    .collect();
                union(answers)
            }
        };
        let (got, stage) = include(scene, self.id, p).expect("closed meshes");
        if got != expected {
            bad.push(mismatch(p, &self.path, "include", got, expected));
        }
        check_stage(p, &self.path, "include", got, stage, bad);
        expected
    }
}

fn mismatch(p: &Point3, object: &str, how: &str, got: Inclusion, expected: Inclusion) -> String {
    format!(
        "point ({:?}, {:?}, {:?}), object '{object}', {how}: library {got}, reference {expected}",
        p.x, p.y, p.z
    )
}

/// The stage must fit the answer: an INBOX decides IN, a CBOX or tribox OUT, ON needs faces.
fn check_stage(
    p: &Point3,
    object: &str,
    how: &str,
    got: Inclusion,
    stage: Stage,
    bad: &mut Vec<String>,
) {
    let fits = match stage {
        Stage::Inbox => got == Inclusion::In,
        Stage::Cbox | Stage::Tribox => got == Inclusion::Out,
        Stage::Faces => true,
    };
    if !fits {
        bad.push(format!(
            "point ({:?}, {:?}, {:?}), object '{object}', {how}: answer {got} decided by stage {stage:?}",
            p.x, p.y, p.z
        ));
    }
}

/// Checks every point against the reference for the union of `roots` (and every object below
/// them): the single query, the index's single and batch queries, and the projection grids.
/// Fails with every disagreement. Returns the reference answers, for tests that want to
/// check more.
fn check_points(
    scene: &Scene,
    roots: &[ObjectId],
    points: &[Point3],
    what: &str,
) -> Vec<Inclusion> {
    let mut scale = Scale::of_points(points);
    for &root in roots {
        for mesh in scene.meshes(root) {
            scale = scale.max(Scale::of_points(mesh.vertices()));
        }
    }
    let nodes: Vec<RefNode> = roots
        .iter()
        .map(|&id| RefNode::new(scene, id, scale))
        .collect();
    let index = IncludeIndex::new(scene, roots).expect("closed meshes");
    let (batch, counters) = index.include_all(points);
    assert_eq!(batch.len(), points.len(), "{what}: include_all answers");
    assert_eq!(
        counters.total(),
        points.len() as u64,
        "{what}: counters {counters:?}"
    );
    let results: Vec<(Inclusion, Vec<String>)> = points
        .par_iter()
        .zip(batch.par_iter())
        .map(|(p, &batch_answer)| {
            let rp = RefPoint::new(p, scale);
            let mut bad = Vec::new();
            let expected = union(
                nodes
                    .iter()
                    .map(|n| n.check(scene, p, &rp, &mut bad))
                    .collect::<Vec<_>>(),
            );
            let (got, stage) = index.include(p);
            if got != expected {
                bad.push(mismatch(
                    p,
                    "(index)",
                    "IncludeIndex::include",
                    got,
                    expected,
                ));
            }
            check_stage(p, "(index)", "IncludeIndex::include", got, stage, &mut bad);
            if batch_answer != expected {
                bad.push(mismatch(
                    p,
                    "(index)",
                    "include_all",
                    batch_answer,
                    expected,
                ));
            }
            (expected, bad)
        })
        .collect();
    let bad: Vec<&String> = results.iter().flat_map(|(_, b)| b).collect();
    if !bad.is_empty() {
        let shown: Vec<&str> = bad.iter().take(40).map(|s| s.as_str()).collect();
        panic!(
            "{what}: {} disagreements over {} points:\n{}",
            bad.len(),
            points.len(),
            shown.join("\n")
        );
    }
    results.into_iter().map(|(e, _)| e).collect()
}

/// How many of each answer (so tests can make sure they exercised all three).
fn tally(answers: &[Inclusion]) -> [usize; 3] {
    let count = |x: Inclusion| answers.iter().filter(|&&a| a == x).count();
    [
        count(Inclusion::In),
        count(Inclusion::Out),
        count(Inclusion::On),
    ]
}

fn assert_all_kinds(answers: &[Inclusion], what: &str) {
    let [i, o, n] = tally(answers);
    assert!(i > 0 && o > 0 && n > 0, "{what}: IN {i}, OUT {o}, ON {n}");
}

// ---------------------------------------------------------------------------------------------
// Sanity checks of the reference itself on a unit cube [0, 1]³ with hand-known answers.

#[test]
fn reference_agrees_with_hand_answers_on_a_unit_cube() {
    // 1e-9 has its lowest bit at 2^-82, 1 - 1e-9 at 2^-53.
    let scale = Scale(90);
    let r = RefMesh::new(&voxel_mesh(&[[0, 0, 0]], false), scale);
    let at = |x: f64, y: f64, z: f64| r.classify(&RefPoint::new(&Point3::new(x, y, z), scale));
    use Inclusion::*;
    // Inside, with the +X ray through an edge, a vertex, a face diagonal.
    assert_eq!(at(0.5, 0.5, 0.5), In);
    assert_eq!(at(0.5, 1.0 - 1e-9, 1.0 - 1e-9), In);
    assert_eq!(at(0.25, 0.5, 0.5), In);
    // Outside, with the +X ray through a vertex, an edge, a face, the face's diagonal.
    assert_eq!(at(-1.0, 0.0, 0.0), Out);
    assert_eq!(at(-1.0, 1.0, 1.0), Out);
    assert_eq!(at(-1.0, 0.5, 1.0), Out);
    assert_eq!(at(-1.0, 0.5, 0.5), Out);
    assert_eq!(at(-1.0, 0.25, 0.25), Out);
    assert_eq!(at(-1.0, 0.75, 0.25), Out);
    assert_eq!(at(2.0, 0.5, 0.5), Out);
    assert_eq!(at(0.5, 0.5, 1.5), Out);
    // On a vertex, an edge, a face.
    assert_eq!(at(0.0, 0.0, 0.0), On);
    assert_eq!(at(1.0, 0.5, 0.0), On);
    assert_eq!(at(0.5, 0.5, 1.0), On);
    assert_eq!(at(0.3, 0.7, 1.0), On);
    // Inside out: the same.
    let r = RefMesh::new(&voxel_mesh(&[[0, 0, 0]], true), scale);
    let at = |x: f64, y: f64, z: f64| r.classify(&RefPoint::new(&Point3::new(x, y, z), scale));
    assert_eq!(at(0.5, 0.5, 0.5), In);
    assert_eq!(at(-1.0, 0.5, 1.0), Out);
    assert_eq!(at(1.0, 1.0, 1.0), On);
}

// ---------------------------------------------------------------------------------------------
// Shapes and points.

/// A closed mesh of unit cubes at the given integer cells: each face of a cube whose
/// neighbouring cell is empty, as a quad (outward, or inward when `inside_out`). Closed when
/// no two cubes meet along an edge only (see [`random_voxels`]).
fn voxel_mesh(cells: &[[i32; 3]], inside_out: bool) -> Mesh {
    let filled: HashSet<[i32; 3]> = cells.iter().copied().collect();
    let mut vertices = Vec::new();
    let mut faces = Vec::new();
    for c in cells {
        for k in 0..3 {
            for dir in [-1, 1] {
                let mut n = *c;
                n[k] += dir;
                if filled.contains(&n) {
                    continue;
                }
                let (i, j) = ((k + 1) % 3, (k + 2) % 3);
                // Corners (0,0), (1,0), (1,1), (0,1) in (i, j) turn about +k (e_i × e_j = e_k).
                let mut loop_: Vec<Point3> = [(0, 0), (1, 0), (1, 1), (0, 1)]
                    .iter()
                    .map(|&(di, dj)| {
                        let mut v = [c[0] as f64, c[1] as f64, c[2] as f64];
                        v[k] += if dir > 0 { 1.0 } else { 0.0 };
                        v[i] += di as f64;
                        v[j] += dj as f64;
                        Point3::new(v[0], v[1], v[2])
                    })
                    .collect();
                if (dir < 0) != inside_out {
                    loop_.reverse();
                }
                let base = vertices.len() as u32;
                vertices.extend(loop_);
                faces.push((base..base + 4).collect());
            }
        }
    }
    let mesh = Mesh::from_polygons(vertices, faces).expect("voxel mesh");
    assert_eq!(
        mesh.topology().odd_edges,
        0,
        "voxel mesh not closed: {cells:?}"
    );
    mesh
}

/// A random set of cells of an n×n×n grid, each filled with probability `fill`; with
/// `manifold`, repaired so that no two cubes meet along an edge only (four faces on one edge,
/// a non-manifold edge that INCLUDE accepts since every edge still has an even number of
/// faces): for such a pair one of the two cells beside both is filled, until none is left.
/// Cubes meeting at a vertex only remain.
fn random_voxels(rng: &mut SplitMix64, n: i32, fill: f64, manifold: bool) -> Vec<[i32; 3]> {
    let mut filled: HashSet<[i32; 3]> = HashSet::new();
    for x in 0..n {
        for y in 0..n {
            for z in 0..n {
                if rng.unit() < fill {
                    filled.insert([x, y, z]);
                }
            }
        }
    }
    if filled.is_empty() {
        filled.insert([0, 0, 0]);
    }
    if manifold {
        loop {
            let mut added = None;
            'search: for a in &filled {
                for i in 0..3 {
                    for j in i + 1..3 {
                        for (di, dj) in [(1, 1), (1, -1)] {
                            let mut b = *a;
                            b[i] += di;
                            b[j] += dj;
                            let (mut n1, mut n2) = (*a, *a);
                            n1[i] += di;
                            n2[j] += dj;
                            if filled.contains(&b) && !filled.contains(&n1) && !filled.contains(&n2)
                            {
                                added = Some(if rng.unit() < 0.5 { n1 } else { n2 });
                                break 'search;
                            }
                        }
                    }
                }
            }
            match added {
                Some(c) => {
                    filled.insert(c);
                }
                None => break,
            }
        }
    }
    let mut cells: Vec<[i32; 3]> = filled.into_iter().collect();
    cells.sort();
    cells
}

/// The points of the grid of spacing `step` in the box [lo, hi] (lo on the grid).
fn lattice(lo: [f64; 3], hi: [f64; 3], step: f64) -> Vec<Point3> {
    let n = |k: usize| ((hi[k] - lo[k]) / step).round() as i64;
    let mut out = Vec::new();
    for i in 0..=n(0) {
        for j in 0..=n(1) {
            for k in 0..=n(2) {
                out.push(Point3::new(
                    lo[0] + i as f64 * step,
                    lo[1] + j as f64 * step,
                    lo[2] + k as f64 * step,
                ));
            }
        }
    }
    out
}

/// Sample sizes: in full when optimized, a quarter in debug builds (where big-integer
/// arithmetic is slow); exhaustive lattices and special points are always complete.
fn budget(count: usize) -> usize {
    if cfg!(debug_assertions) {
        count.div_ceil(4)
    } else {
        count
    }
}

/// `count` random points of `points` (see [`budget`]).
fn sample(rng: &mut SplitMix64, points: &[Point3], count: usize) -> Vec<Point3> {
    (0..budget(count))
        .map(|_| points[rng.below(points.len())])
        .collect()
}

/// Uniform random points in the box (see [`budget`]).
fn random_points(rng: &mut SplitMix64, lo: [f64; 3], hi: [f64; 3], count: usize) -> Vec<Point3> {
    (0..budget(count))
        .map(|_| {
            Point3::new(
                rng.range(lo[0], hi[0]),
                rng.range(lo[1], hi[1]),
                rng.range(lo[2], hi[2]),
            )
        })
        .collect()
}

/// The vertices of a mesh, the midpoints of its triangles' edges (face edges and the
/// triangulation's diagonals) and the centroids of its faces and triangles. On
/// axis-aligned lattice shapes all of these are exactly on the surface.
fn special_points(mesh: &Mesh) -> Vec<Point3> {
    let mut out: Vec<Point3> = mesh.vertices().to_vec();
    for t in 0..mesh.triangles().len() {
        let c = mesh.triangle(t);
        for e in 0..3 {
            out.push(nalgebra::center(&c[e], &c[(e + 1) % 3]));
        }
        out.push(Point3::from(
            (c[0].coords + c[1].coords + c[2].coords) / 3.0,
        ));
    }
    for f in 0..mesh.faces().len() {
        let pts: Vec<Point3> = mesh.face_points(f).collect();
        let sum = pts.iter().fold(Vector3::zeros(), |s, p| s + p.coords);
        out.push(Point3::from(sum / pts.len() as f64));
    }
    out
}

/// Each point moved by ±d along each axis: their rays along that axis (the library's +Z, the
/// reference's +X) pass exactly through the original point.
fn axis_shifted(points: &[Point3], d: f64) -> Vec<Point3> {
    let mut out = Vec::with_capacity(points.len() * 6);
    for p in points {
        for k in 0..3 {
            for s in [-d, d] {
                let mut m = *p;
                m[k] += s;
                out.push(m);
            }
        }
    }
    out
}

/// The bounding box of the points, grown by `margin` and widened to multiples of `step`.
fn grid_box(points: &[Point3], margin: f64, step: f64) -> ([f64; 3], [f64; 3]) {
    let lo = [0, 1, 2].map(|k| {
        let m = points.iter().map(|p| p[k]).fold(f64::INFINITY, f64::min);
        ((m - margin) / step).floor() * step
    });
    let hi = [0, 1, 2].map(|k| {
        let m = points
            .iter()
            .map(|p| p[k])
            .fold(f64::NEG_INFINITY, f64::max);
        ((m + margin) / step).ceil() * step
    });
    (lo, hi)
}

/// Lattice points (all, or a sample), the special points, some of them axis-shifted, and
/// random points, for one mesh.
fn points_for(
    rng: &mut SplitMix64,
    mesh: &Mesh,
    step: f64,
    lattice_cap: usize,
    randoms: usize,
) -> Vec<Point3> {
    let (lo, hi) = grid_box(mesh.vertices(), step, step);
    let grid = lattice(lo, hi, step);
    let mut points = if grid.len() > lattice_cap {
        sample(rng, &grid, lattice_cap)
    } else {
        grid
    };
    let special = special_points(mesh);
    points.extend(axis_shifted(&sample(rng, &special, 200), step));
    points.extend(axis_shifted(&sample(rng, &special, 100), 0.1));
    points.extend(special);
    points.extend(random_points(rng, lo, hi, randoms));
    points
}

fn one_mesh_scene(name: &str, mesh: Mesh) -> (Scene, ObjectId) {
    let mut scene = Scene::new();
    let id = scene.add_mesh(None, name, mesh).unwrap();
    (scene, id)
}

fn translation(x: f64, y: f64, z: f64) -> Matrix4<f64> {
    Translation3::new(x, y, z).to_homogeneous()
}

/// A unit cube with its lowest corner at `corner`.
fn unit_cube_at(corner: [f64; 3]) -> Mesh {
    solids::cube(1.0)
        .unwrap()
        .transformed(&translation(
            corner[0] + 0.5,
            corner[1] + 0.5,
            corner[2] + 0.5,
        ))
        .unwrap()
}

fn outline(points: &[(f64, f64)]) -> geo::Polygon<f64> {
    geo::Polygon::new(geo::LineString::from(points.to_vec()), vec![])
}

// ---------------------------------------------------------------------------------------------
// Random small polyhedra.

#[test]
fn random_voxel_shapes_agree_with_the_reference() {
    let mut rng = SplitMix64(0x5eed_0001);
    let mut all = Vec::new();
    for shape in 0..8 {
        let cells = random_voxels(&mut rng, 4, 0.35 + 0.05 * shape as f64, shape % 2 == 0);
        let inside_out = shape % 3 == 2;
        let mesh = voxel_mesh(&cells, inside_out);
        let mut points = points_for(&mut rng, &mesh, 0.5, 5000, 200);
        // Quarter-integer points: on faces off the edges, and rays between the edges.
        points.extend(sample(&mut rng, &lattice([-0.5; 3], [4.5; 3], 0.25), 1500));
        let (scene, id) = one_mesh_scene("voxels", mesh);
        let what = format!("voxel shape {shape} (inside out: {inside_out}) {cells:?}");
        let answers = check_points(&scene, &[id], &points, &what);
        assert_all_kinds(&answers, &what);
        all.extend(answers);
    }
    assert_all_kinds(&all, "voxel shapes");
}

/// Random unit cubes on a half-integer grid, as separate objects of one group: they touch
/// face to face, overlap, and stand on each other shifted by half a cube, so that vertices of
/// one lie on the faces and edges of another.
#[test]
fn random_stacks_of_cubes_agree_with_the_reference() {
    let mut rng = SplitMix64(0x5eed_0002);
    for stack in 0..6 {
        let mut scene = Scene::new();
        let g = scene.add_group(None, "stack").unwrap();
        let mut corners = Vec::new();
        for c in 0..7 {
            let corner = [0, 1, 2].map(|_| rng.below(6) as f64 * 0.5);
            corners.push(corner);
            scene
                .add_mesh(Some(g), format!("cube{c}"), unit_cube_at(corner))
                .unwrap();
        }
        let mut points = lattice([-0.5; 3], [4.0; 3], 0.25);
        points = sample(&mut rng, &points, 4000);
        points.extend(random_points(&mut rng, [-0.5; 3], [4.0; 3], 300));
        let what = format!("stack {stack} of cubes at {corners:?}");
        let answers = check_points(&scene, &[g], &points, &what);
        assert_all_kinds(&answers, &what);
    }
}

/// A column of cubes stacked exactly face to face, with a half-shifted cube on top and one
/// beside it: vertical rays run down the shared edges and through the shared vertices.
#[test]
fn a_fixed_stack_of_cubes_agrees_with_the_reference() {
    let mut scene = Scene::new();
    let g = scene.add_group(None, "tower").unwrap();
    let corners = [
        [0.0, 0.0, 0.0],
        [0.0, 0.0, 1.0],
        [0.0, 0.0, 2.0],
        [0.5, 0.5, 3.0],
        [1.0, 0.0, 0.0],
        [0.0, 1.0, 1.0],
    ];
    for (i, c) in corners.iter().enumerate() {
        scene
            .add_mesh(Some(g), format!("c{i}"), unit_cube_at(*c))
            .unwrap();
    }
    let points = lattice([-0.5; 3], [2.5, 2.5, 4.5], 0.25);
    let answers = check_points(&scene, &[g], &points, "tower of cubes");
    assert_all_kinds(&answers, "tower of cubes");
    // The union rule: on the common face of two cubes touching face to face, each says ON
    // and none IN, so the group is ON; so is a point where a cube's vertex or face rests on
    // another's face.
    let single = |x, y, z| include(&scene, g, &Point3::new(x, y, z)).unwrap().0;
    assert_eq!(single(0.5, 0.5, 1.0), Inclusion::On);
    assert_eq!(single(1.0, 0.5, 0.5), Inclusion::On);
    assert_eq!(single(0.5, 0.5, 0.5), Inclusion::In);
    assert_eq!(single(0.5, 0.5, 3.0), Inclusion::On);
    assert_eq!(single(1.25, 1.25, 3.0), Inclusion::On);
}

/// Star-shaped polyhedra on a quarter-integer lattice: the icosahedron's and the
/// octahedron's triangles with each vertex moved radially by a random factor and rounded.
#[test]
fn random_lattice_polyhedra_agree_with_the_reference() {
    let mut rng = SplitMix64(0x5eed_0003);
    let templates = [
        solids::icosahedron(2.0).unwrap(),
        solids::octahedron(2.0).unwrap(),
        solids::dodecahedron(1.2).unwrap(),
    ];
    let mut made = 0;
    let mut attempt = 0;
    while made < 9 {
        attempt += 1;
        assert!(attempt < 100, "could not build random polyhedra");
        let template = &templates[made % templates.len()];
        let vertices: Vec<Point3> = template
            .vertices()
            .iter()
            .map(|v| {
                let r = [0.75, 1.0, 1.25, 1.5][rng.below(4)];
                (v * r).map(|x| (x * 4.0).round() / 4.0)
            })
            .collect();
        let faces: Vec<Vec<u32>> = template.triangles().iter().map(|t| t.to_vec()).collect();
        let Ok(mesh) = Mesh::from_polygons(vertices, faces) else {
            continue;
        };
        if !mesh.topology().closed || mesh.merged_vertices() > 0 {
            continue;
        }
        let mut points = points_for(&mut rng, &mesh, 0.25, 3000, 300);
        points.extend(points_for(&mut rng, &mesh, 0.5, 2000, 0));
        let (scene, id) = one_mesh_scene("star", mesh);
        let what = format!("random lattice polyhedron {made}");
        let answers = check_points(&scene, &[id], &points, &what);
        assert_all_kinds(&answers, &what);
        made += 1;
    }
}

/// Platonic solids under random rotations and translations: no exact structure left, but
/// vertices, midpoints and axis-shifted points still meet the surface exactly or nearly.
#[test]
fn randomly_rotated_solids_agree_with_the_reference() {
    let mut rng = SplitMix64(0x5eed_0004);
    let solids: Vec<(&str, Mesh)> = vec![
        ("tetrahedron", solids::tetrahedron(2.0).unwrap()),
        ("octahedron", solids::octahedron(2.0).unwrap()),
        ("icosahedron", solids::icosahedron(1.5).unwrap()),
        ("cube", solids::cube(1.5).unwrap()),
        ("dodecahedron", solids::dodecahedron(1.0).unwrap()),
    ];
    for round in 0..3 {
        for (name, solid) in &solids {
            let rotation = UnitQuaternion::from_quaternion(Quaternion::new(
                rng.range(-1.0, 1.0),
                rng.range(-1.0, 1.0),
                rng.range(-1.0, 1.0),
                rng.range(-1.0, 1.0),
            ));
            let m = translation(
                rng.range(-2.0, 2.0),
                rng.range(-2.0, 2.0),
                rng.range(-2.0, 2.0),
            ) * rotation.to_homogeneous();
            let mesh = solid.transformed(&m).unwrap();
            let points = points_for(&mut rng, &mesh, 0.25, 2000, 1000);
            let (scene, id) = one_mesh_scene(name, mesh);
            let what = format!("rotated {name} (round {round})");
            let answers = check_points(&scene, &[id], &points, &what);
            assert_all_kinds(&answers, &what);
        }
    }
}

/// The Platonic solids as built, and turned by exact quarter turns (permutation matrices):
/// their symmetric vertices put many points exactly over vertices and edges.
#[test]
fn platonic_solids_in_exact_orientations_agree_with_the_reference() {
    let mut rng = SplitMix64(0x5eed_0005);
    let quarter = Matrix4::new(
        0.0, -1.0, 0.0, 0.0, //
        0.0, 0.0, 1.0, 0.0, //
        1.0, 0.0, 0.0, 0.0, //
        0.0, 0.0, 0.0, 1.0,
    );
    for (name, solid) in [
        ("tetrahedron", solids::tetrahedron(2.0).unwrap()),
        ("octahedron", solids::octahedron(2.0).unwrap()),
        ("icosahedron", solids::icosahedron(2.0).unwrap()),
        ("dodecahedron", solids::dodecahedron(1.0).unwrap()),
        ("cube", solids::cube(2.0).unwrap()),
    ] {
        for turned in [false, true] {
            let mesh = if turned {
                solid.transformed(&quarter).unwrap()
            } else {
                solid.clone()
            };
            let points = points_for(&mut rng, &mesh, 0.25, 3000, 300);
            let (scene, id) = one_mesh_scene(name, mesh);
            let what = format!("{name} (turned: {turned})");
            let answers = check_points(&scene, &[id], &points, &what);
            assert_all_kinds(&answers, &what);
        }
    }
}

// ---------------------------------------------------------------------------------------------
// A torus, non-convex prisms, nested objects, an inside-out mesh.

#[test]
fn torus_agrees_with_the_reference() {
    let mut rng = SplitMix64(0x5eed_0006);
    let mesh = solids::torus(2.0, 0.5, 24, 12).unwrap();
    let mut points = points_for(&mut rng, &mesh, 0.25, 3000, 2000);
    // The central axis, the plane z = 0 and the tube's core circle.
    points.extend((0..40).map(|i| Point3::new(0.0, 0.0, -1.0 + i as f64 * 0.05)));
    points.extend(lattice([-3.0, -3.0, 0.0], [3.0, 3.0, 0.0], 0.125));
    points.extend((0..96).map(|i| {
        let (s, c) = (i as f64 * std::f64::consts::TAU / 96.0).sin_cos();
        Point3::new(2.0 * c, 2.0 * s, 0.0)
    }));
    let (scene, id) = one_mesh_scene("ring", mesh);
    let answers = check_points(&scene, &[id], &points, "torus");
    assert_all_kinds(&answers, "torus");
    let single = |x, y, z| include(&scene, id, &Point3::new(x, y, z)).unwrap().0;
    assert_eq!(single(2.0, 0.0, 0.0), Inclusion::In);
    assert_eq!(single(0.0, 0.0, 0.0), Inclusion::Out);
    assert_eq!(single(2.5, 0.0, 0.0), Inclusion::On);
}

#[test]
fn non_convex_prisms_agree_with_the_reference() {
    let mut rng = SplitMix64(0x5eed_0007);
    let shapes: [(&str, Vec<(f64, f64)>); 4] = [
        (
            "L",
            vec![
                (0.0, 0.0),
                (2.0, 0.0),
                (2.0, 1.0),
                (1.0, 1.0),
                (1.0, 2.0),
                (0.0, 2.0),
            ],
        ),
        (
            "star",
            vec![
                (4.0, 0.0),
                (1.5, 0.5),
                (3.0, 3.0),
                (0.5, 1.5),
                (0.0, 4.0),
                (-0.5, 1.5),
                (-3.0, 3.0),
                (-1.5, 0.5),
                (-4.0, 0.0),
                (-1.5, -0.5),
                (-3.0, -3.0),
                (-0.5, -1.5),
                (0.0, -4.0),
                (0.5, -1.5),
                (3.0, -3.0),
                (1.5, -0.5),
            ],
        ),
        (
            "comb",
            vec![
                (0.0, 0.0),
                (5.0, 0.0),
                (5.0, 3.0),
                (4.0, 3.0),
                (4.0, 1.0),
                (3.0, 1.0),
                (3.0, 3.0),
                (2.0, 3.0),
                (2.0, 1.0),
                (1.0, 1.0),
                (1.0, 3.0),
                (0.0, 3.0),
            ],
        ),
        (
            // Wound clockwise, with a vertex of one tooth straight above another's edge.
            "zigzag",
            vec![
                (0.0, 0.0),
                (0.0, 2.0),
                (1.0, 1.0),
                (2.0, 2.0),
                (3.0, 1.0),
                (4.0, 2.0),
                (4.0, 0.0),
                (2.0, 0.5),
            ],
        ),
    ];
    for (name, ring) in &shapes {
        for (height, lift) in [(2.0, 0.0), (1.5, -0.5)] {
            let mesh = solids::prism(&outline(ring), height)
                .unwrap()
                .transformed(&translation(0.0, 0.0, lift))
                .unwrap();
            let mut points = points_for(&mut rng, &mesh, 0.5, 4000, 300);
            points.extend(points_for(&mut rng, &mesh, 0.25, 3000, 0));
            let (scene, id) = one_mesh_scene(name, mesh);
            let what = format!("prism {name} (height {height})");
            let answers = check_points(&scene, &[id], &points, &what);
            assert_all_kinds(&answers, &what);
        }
    }
}

#[test]
fn nested_objects_follow_the_union_rule() {
    let mut rng = SplitMix64(0x5eed_0008);
    let mut scene = Scene::new();
    // A big cube holding a small one, which touches its floor from inside, and a third cube
    // outside touching the big one's wall.
    let boxes = scene.add_group(None, "boxes").unwrap();
    scene
        .add_mesh(Some(boxes), "big", solids::cube(4.0).unwrap())
        .unwrap();
    let inner = scene.add_group(Some(boxes), "inner").unwrap();
    scene
        .add_mesh(Some(inner), "small", unit_cube_at([-0.5, -0.5, -2.0]))
        .unwrap();
    scene
        .add_mesh(Some(inner), "outside", unit_cube_at([2.0, -0.5, -0.5]))
        .unwrap();
    // A torus with a cube in its hole, one inside its tube, and one crossing its surface.
    let ring = scene.add_group(None, "ring").unwrap();
    let torus = solids::torus(2.0, 0.5, 24, 12)
        .unwrap()
        .transformed(&translation(0.0, 0.0, 5.0))
        .unwrap();
    scene.add_mesh(Some(ring), "torus", torus).unwrap();
    scene
        .add_mesh(Some(ring), "hole", unit_cube_at([-0.5, -0.5, 4.5]))
        .unwrap();
    let tube = solids::cube(0.25)
        .unwrap()
        .transformed(&translation(2.0, 0.0, 5.0))
        .unwrap();
    scene.add_mesh(Some(ring), "in tube", tube).unwrap();
    scene
        .add_mesh(Some(ring), "crossing", unit_cube_at([-2.5, -0.5, 4.75]))
        .unwrap();
    let roots = scene.roots().to_vec();
    let mut points = lattice([-3.0, -3.0, -2.5], [3.5, 3.0, 6.0], 0.25);
    points = sample(&mut rng, &points, 8000);
    for id in scene.walk().into_iter().map(|(id, _)| id) {
        if let Some(mesh) = scene[id].mesh() {
            let special = special_points(mesh);
            points.extend(sample(&mut rng, &special, 300));
            points.extend(axis_shifted(&sample(&mut rng, &special, 100), 0.25));
        }
    }
    points.extend(random_points(
        &mut rng,
        [-3.0, -3.0, -2.5],
        [3.5, 3.0, 6.0],
        1000,
    ));
    let answers = check_points(&scene, &roots, &points, "nested objects");
    assert_all_kinds(&answers, "nested objects");
    // The whole scene's index is the union of the roots.
    let whole = IncludeIndex::whole_scene(&scene).unwrap();
    let (batch, counters) = whole.include_all(&points);
    assert_eq!(batch, answers);
    assert_eq!(counters.total(), points.len() as u64);
    // The union rule, by hand: on the small cube's faces but inside the big one is IN; on the
    // big one's floor where the small one touches it is ON; on the touching wall, ON.
    let single = |id, x, y, z| include(&scene, id, &Point3::new(x, y, z)).unwrap().0;
    assert_eq!(single(boxes, 0.0, 0.0, -1.0), Inclusion::In);
    assert_eq!(single(boxes, 0.5, 0.5, -1.5), Inclusion::In);
    assert_eq!(single(boxes, 0.0, 0.0, -2.0), Inclusion::On);
    assert_eq!(single(inner, 0.0, 0.0, -1.0), Inclusion::On);
    assert_eq!(single(boxes, 2.0, 0.0, 0.0), Inclusion::On);
    assert_eq!(single(boxes, 2.5, 0.0, 0.0), Inclusion::In);
    assert_eq!(single(ring, 0.0, 0.0, 5.0), Inclusion::In);
    assert_eq!(single(ring, 2.0, 0.0, 5.0), Inclusion::In);
    assert_eq!(single(ring, 1.0, 1.0, 5.0), Inclusion::Out);
    assert_eq!(single(ring, 0.0, 0.0, 5.5), Inclusion::On);
}

#[test]
fn inside_out_meshes_agree_with_the_reference() {
    let mut rng = SplitMix64(0x5eed_0009);
    let dir = Path::new(env!("CARGO_MANIFEST_DIR"));
    let off = kepler::io::read_mesh(&dir.join("scenes/meshes/inside_out.off")).unwrap();
    let cells = random_voxels(&mut rng, 3, 0.5, true);
    for (name, mesh) in [
        ("inside_out.off", off),
        ("voxels inside out", voxel_mesh(&cells, true)),
    ] {
        assert!(mesh.topology().closed, "{name}");
        let mut points = points_for(&mut rng, &mesh, 0.25, 3000, 200);
        points.extend(points_for(&mut rng, &mesh, 0.5, 3000, 0));
        let (scene, id) = one_mesh_scene(name, mesh);
        let answers = check_points(&scene, &[id], &points, name);
        assert_all_kinds(&answers, name);
    }
}

// ---------------------------------------------------------------------------------------------
// Batch against single, by property.

/// A fixed voxel shape: an arch with a tower, cubes meeting at a vertex only, and a hole.
fn fixed_voxels() -> Vec<[i32; 3]> {
    vec![
        [0, 0, 0],
        [0, 0, 1],
        [0, 0, 2],
        [1, 0, 2],
        [2, 0, 2],
        [2, 0, 1],
        [2, 0, 0],
        [3, 0, 0],
        [3, 1, 0],
        [3, 2, 0],
        [2, 2, 0],
        [1, 2, 0],
        [1, 2, 1],
        [2, 3, 2],
        [3, 2, 3],
        [0, 3, 3],
    ]
}

fn voxel_scene() -> &'static (Scene, ObjectId, RefMesh) {
    static SCENE: std::sync::OnceLock<(Scene, ObjectId, RefMesh)> = std::sync::OnceLock::new();
    SCENE.get_or_init(|| {
        let mesh = voxel_mesh(&fixed_voxels(), false);
        // Integer vertices and quarter-integer points.
        let reference = RefMesh::new(&mesh, Scale(2));
        let (scene, id) = one_mesh_scene("arch", mesh);
        (scene, id, reference)
    })
}

fn voxel_index() -> &'static IncludeIndex<'static> {
    static INDEX: std::sync::OnceLock<IncludeIndex<'static>> = std::sync::OnceLock::new();
    INDEX.get_or_init(|| {
        let (scene, id, _) = voxel_scene();
        IncludeIndex::new(scene, &[*id]).unwrap()
    })
}

/// A point of the quarter-integer lattice around the fixed voxel shape.
fn quarter_lattice_point() -> impl Strategy<Value = Point3> {
    (-2i32..=18, -2i32..=18, -2i32..=18)
        .prop_map(|(x, y, z)| Point3::new(x as f64 / 4.0, y as f64 / 4.0, z as f64 / 4.0))
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(192))]

    #[test]
    fn batch_equals_single_equals_reference(
        points in prop::collection::vec(quarter_lattice_point(), 1..24),
    ) {
        let (scene, id, reference) = voxel_scene();
        let index = voxel_index();
        let (batch, counters) = index.include_all(&points);
        prop_assert_eq!(counters.total(), points.len() as u64);
        for (p, b) in points.iter().zip(&batch) {
            let expected = reference.classify(&RefPoint::new(p, Scale(2)));
            let single = include(scene, *id, p).unwrap();
            prop_assert_eq!(single.0, expected, "single at {:?}", p);
            prop_assert_eq!(*b, expected, "batch at {:?}", p);
            prop_assert_eq!(index.include(p), single, "index single at {:?}", p);
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Stages.

#[test]
fn stages_are_the_expected_ones() {
    let mut scene = Scene::new();
    let cube = scene
        .add_mesh(None, "cube", solids::cube(2.0).unwrap())
        .unwrap();
    let inbox = scene.inbox(cube).expect("a cube has an inbox").aabb;
    let centre = nalgebra::center(&inbox.min_point(), &inbox.max_point());
    assert_eq!(
        include(&scene, cube, &centre).unwrap(),
        (Inclusion::In, Stage::Inbox)
    );
    let far = Point3::new(10.0, 0.0, 0.0);
    assert_eq!(
        include(&scene, cube, &far).unwrap(),
        (Inclusion::Out, Stage::Cbox)
    );
    let face = Point3::new(1.0, 0.25, -0.5);
    assert_eq!(
        include(&scene, cube, &face).unwrap(),
        (Inclusion::On, Stage::Faces)
    );
    let index = IncludeIndex::whole_scene(&scene).unwrap();
    assert_eq!(index.include(&centre), (Inclusion::In, Stage::Inbox));
    assert_eq!(index.include(&far), (Inclusion::Out, Stage::Cbox));
    assert_eq!(index.include(&face), (Inclusion::On, Stage::Faces));
    let (answers, counters) = index.include_all(&[centre, far, face, far, Point3::origin()]);
    assert_eq!(
        answers,
        vec![
            Inclusion::In,
            Inclusion::Out,
            Inclusion::On,
            Inclusion::Out,
            Inclusion::In
        ]
    );
    assert_eq!(
        counters,
        Counters {
            inbox: 2,
            cbox: 2,
            tribox: 0,
            faces: 1
        }
    );

    // An octahedron: a point in its CBOX's corner region is cut off by its tribox.
    let mut scene = Scene::new();
    let octa = scene
        .add_mesh(None, "octahedron", solids::octahedron(2.0).unwrap())
        .unwrap();
    let a = 2f64.sqrt(); // the vertices are at distance edge / √2 on the axes
    let corner = Point3::new(0.9 * a, 0.9 * a, 0.0);
    assert!(scene.cbox(octa).contains_point(&corner));
    assert_eq!(
        include(&scene, octa, &corner).unwrap(),
        (Inclusion::Out, Stage::Tribox)
    );
    let index = IncludeIndex::whole_scene(&scene).unwrap();
    assert_eq!(index.include(&corner), (Inclusion::Out, Stage::Tribox));
}

/// Counters over a large batch add up to the number of points, and match the stages of the
/// single queries one by one.
#[test]
fn counters_add_up_to_the_points() {
    let mut rng = SplitMix64(0x5eed_000a);
    let mut scene = Scene::new();
    let g = scene.add_group(None, "g").unwrap();
    scene
        .add_mesh(Some(g), "torus", solids::torus(2.0, 0.5, 24, 12).unwrap())
        .unwrap();
    scene
        .add_mesh(Some(g), "octa", solids::octahedron(1.5).unwrap())
        .unwrap();
    let points = random_points(&mut rng, [-4.0; 3], [4.0; 3], 5000);
    let index = IncludeIndex::whole_scene(&scene).unwrap();
    let (answers, counters) = index.include_all(&points);
    assert_eq!(counters.total(), points.len() as u64);
    let mut expected = Counters::default();
    for (p, a) in points.iter().zip(&answers) {
        let (single, stage) = index.include(p);
        assert_eq!(single, *a, "at {p:?}");
        assert_eq!(include(&scene, g, p).unwrap().0, *a, "at {p:?}");
        expected.record(stage);
    }
    assert_eq!(counters, expected);
    assert!(
        counters.inbox > 0 && counters.cbox > 0 && counters.faces > 0,
        "{counters:?}"
    );
}

// ---------------------------------------------------------------------------------------------
// Bad input.

#[test]
fn include_on_an_open_mesh_is_an_error_naming_it() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/meshes/tent.stl");
    let tent = kepler::io::read_mesh(&path).unwrap();
    assert!(!tent.topology().closed);
    let mut scene = Scene::new();
    let g = scene.add_group(None, "camp").unwrap();
    let cube = scene
        .add_mesh(Some(g), "crate", solids::cube(1.0).unwrap())
        .unwrap();
    let t = scene.add_mesh(Some(g), "tent", tent).unwrap();
    let p = Point3::new(0.0, 0.0, 0.0);
    let errors = [
        include(&scene, t, &p).unwrap_err().to_string(),
        include(&scene, g, &p).unwrap_err().to_string(),
        IncludeIndex::new(&scene, &[g]).unwrap_err().to_string(),
        IncludeIndex::new(&scene, &[cube, t])
            .unwrap_err()
            .to_string(),
        IncludeIndex::whole_scene(&scene).unwrap_err().to_string(),
    ];
    for e in &errors {
        assert!(e.contains("open"), "{e}");
        assert!(e.contains("tent"), "{e}");
    }
    // The closed object next to it is still fine.
    assert_eq!(include(&scene, cube, &p).unwrap().0, Inclusion::In);
    assert!(IncludeIndex::new(&scene, &[cube]).is_ok());
}
