//! BOXTREE (`kepler::lab::boxtree`) against exact and brute-force references: every bound of every
//! hierarchy contains its triangles' vertices and its children's bounds (checked exactly, with
//! rational arithmetic for oriented boxes); ray shooting agrees with testing every triangle and
//! with `VisibilityIndex::first_hit`; collision detection agrees with testing every pair of
//! triangles, and the exact triangle test with a rational separating-axis test; the sphere
//! experiment runs on the paper's smallest pair.

use crate::common::{
    Q, SplitMix64, q, qcross, qdot, qsign, qsub, qv, unit_octahedron as octahedron,
};
use kepler::bounds::tribox::TriboxBounds;
use kepler::geometry::predicates::{collinear, orient3d};
use kepler::geometry::ray::Ray;
use kepler::geometry::{Aabb, Point3, Vector3};
use kepler::lab::boxtree::pca::{PcaAll, PcaMax, PcaMin, Principal};
use kepler::lab::boxtree::ray::first_hit_brute_force;
use kepler::lab::boxtree::tritri::triangles_meet;
use kepler::lab::boxtree::{BoxTree, Merge, NodeShape, Shape, sphere_experiment, sphere_pair};
use kepler::mesh::Mesh;
use kepler::queries::visp::VisibilityIndex;
use kepler::scene::Scene;
use kepler::views::View;
use num_traits::Zero;
use proptest::prelude::*;
use std::cmp::Ordering;

// ---------------------------------------------------------------------------------------------
// Meshes.

/// A mesh of `n` separate random triangles (degenerate ones dropped): coordinates on a small
/// integer grid (so triangles touch, share planes and vertices) or random doubles in a box of
/// half-size `scale` about `offset`.
fn soup(rng: &mut SplitMix64, n: usize, grid: bool, scale: f64, offset: f64) -> Option<Mesh> {
    let mut vertices = Vec::new();
    let mut faces = Vec::new();
    while faces.len() < n {
        let t: [Point3; 3] = std::array::from_fn(|_| {
            if grid {
                Point3::new(rng.int(0, 4), rng.int(0, 4), rng.int(0, 4))
            } else {
                Point3::from(rng.vector(scale) + Vector3::repeat(offset))
            }
        });
        if collinear(&t[0], &t[1], &t[2]) {
            continue;
        }
        let base = vertices.len() as u32;
        vertices.extend(t);
        faces.push(vec![base, base + 1, base + 2]);
    }
    Mesh::from_polygons(vertices, faces).ok()
}

/// The triangles below each node (leaves first, so children precede parents).
fn triangles_below<S: NodeShape>(tree: &BoxTree<S>) -> Vec<Vec<usize>> {
    let mut below: Vec<Vec<usize>> = Vec::with_capacity(tree.nodes().len());
    for node in tree.nodes() {
        let list = match (node.triangle(), node.children()) {
            (Some(t), _) => vec![t],
            (None, Some([a, b])) => [below[a].clone(), below[b].clone()].concat(),
            (None, None) => unreachable!("a node is a leaf or has children"),
        };
        below.push(list);
    }
    below
}

// ---------------------------------------------------------------------------------------------
// Exact containment of a child's bound in its parent's.

trait Nested: NodeShape {
    /// Whether `child` lies in `parent`, decided exactly.
    fn nested(child: &Self, parent: &Self) -> bool;
}

impl Nested for Aabb {
    fn nested(child: &Aabb, parent: &Aabb) -> bool {
        (0..3).all(|k| parent.min[k] <= child.min[k] && child.max[k] <= parent.max[k])
    }
}

impl Nested for TriboxBounds {
    fn nested(child: &TriboxBounds, parent: &TriboxBounds) -> bool {
        // The same nine directions: slab by slab.
        (0..9).all(|d| parent.min()[d] <= child.min()[d] && child.max()[d] <= parent.max()[d])
    }
}

impl<P: Principal> Nested for kepler::lab::boxtree::pca::PcaBox<P> {
    /// The exact extremes over the child's box `lo ≤ C x ≤ hi` of each parent axis `a`:
    /// `a · x = λ · (C x)` with `Cᵀ λ = a` (Cramer's rule in rationals), extreme at the corner
    /// picked by the signs of λ.
    fn nested(child: &Self, parent: &Self) -> bool {
        let (c, p) = (child.oriented(), parent.oriented());
        if c.is_empty() {
            return true;
        }
        let rows: [[Q; 3]; 3] = c.axes.map(|a| qv([a.x, a.y, a.z]));
        // Columns of Cᵀ are the rows of C.
        let det3 = |m: &[[Q; 3]; 3]| qdot(&m[0], &qcross(&m[1], &m[2]));
        let det = det3(&rows);
        assert!(!det.is_zero(), "a box's axes are independent");
        (0..3).all(|k| {
            let a = qv([p.axes[k].x, p.axes[k].y, p.axes[k].z]);
            // λ_j = det(Cᵀ with column j replaced by a) / det = det(rows with row j = a) / det.
            let lambda: Vec<Q> = (0..3)
                .map(|j| {
                    let mut m = rows.clone();
                    m[j] = a.clone();
                    det3(&m) / &det
                })
                .collect();
            let (mut lo, mut hi) = (Q::zero(), Q::zero());
            for (j, l) in lambda.iter().enumerate() {
                let (at_min, at_max) = (l * q(c.min[j]), l * q(c.max[j]));
                if qsign(l) == Ordering::Less {
                    lo += at_max;
                    hi += at_min;
                } else {
                    lo += at_min;
                    hi += at_max;
                }
            }
            q(p.min[k]) <= lo && hi <= q(p.max[k])
        })
    }
}

/// Checks every node of a hierarchy over `mesh`: its bound holds its triangles' vertices and
/// its children's bounds, exactly; and the tree's shape.
fn check_containment<S: Nested>(mesh: &Mesh, merge: Merge) -> Result<(), TestCaseError> {
    let tree: BoxTree<S> = BoxTree::build(mesh, merge);
    let n = mesh.triangles().len();
    prop_assert_eq!(tree.len(), n);
    prop_assert_eq!(tree.nodes().len(), 2 * n - 1);
    let below = triangles_below(&tree);
    prop_assert_eq!(below.last().map(|b| b.len()), Some(n));
    for (i, node) in tree.nodes().iter().enumerate() {
        for &t in &below[i] {
            for v in mesh.triangle(t) {
                prop_assert!(
                    node.bound().contains_point(&v),
                    "{}: node {} misses a vertex of triangle {}",
                    S::SHAPE,
                    i,
                    t
                );
            }
        }
        if let Some(children) = node.children() {
            for c in children {
                prop_assert!(c < i, "children precede their parent");
                prop_assert!(
                    S::nested(tree.nodes()[c].bound(), node.bound()),
                    "{}: node {} does not contain its child {}",
                    S::SHAPE,
                    i,
                    c
                );
            }
        }
    }
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(16))]

    #[test]
    fn bounds_contain_children_and_vertices(
        seed in any::<u64>(),
        n in 2usize..20,
        kind in 0usize..4,
    ) {
        let mut rng = SplitMix64(seed);
        let (grid, scale, offset) = match kind {
            0 => (true, 0.0, 0.0),
            1 => (false, 1.0, 0.0),
            2 => (false, 1e-3, 1e3), // small triangles far from the origin
            _ => (false, 1e6, -3e6),
        };
        let mesh = soup(&mut rng, n, grid, scale, offset);
        prop_assume!(mesh.is_some());
        let mesh = mesh.unwrap();
        let merge = if seed % 2 == 0 { Merge::Area } else { Merge::Volume };
        check_containment::<Aabb>(&mesh, merge)?;
        check_containment::<PcaAll>(&mesh, merge)?;
        check_containment::<PcaMax>(&mesh, merge)?;
        check_containment::<PcaMin>(&mesh, merge)?;
        check_containment::<TriboxBounds>(&mesh, merge)?;
    }
}

#[test]
fn bounds_of_solids_contain_children_and_vertices() {
    let meshes = [
        kepler::solids::torus(2.0, 0.7, 8, 5).unwrap(),
        kepler::solids::uv_sphere(1.0, 8, 4).unwrap(),
        sphere_pair(60, 0.01, 5).unwrap().1,
    ];
    for mesh in &meshes {
        check_containment::<Aabb>(mesh, Merge::Area).unwrap();
        check_containment::<PcaAll>(mesh, Merge::Volume).unwrap();
        check_containment::<PcaMax>(mesh, Merge::Area).unwrap();
        check_containment::<PcaMin>(mesh, Merge::Volume).unwrap();
        check_containment::<TriboxBounds>(mesh, Merge::Area).unwrap();
    }
}

// ---------------------------------------------------------------------------------------------
// Ray shooting.

/// Rays at a mesh: random ones, and (when `exact_targets`) rays from integer points aimed
/// exactly at its vertices and at its edges' midpoints.
fn rays(rng: &mut SplitMix64, mesh: &Mesh, random: usize, exact_targets: bool) -> Vec<Ray> {
    let mut out: Vec<Ray> = (0..random)
        .map(|_| Ray {
            origin: Point3::from(rng.vector(3.0)),
            direction: rng.vector(1.0),
        })
        .collect();
    if exact_targets {
        let mut targets: Vec<Point3> = mesh.vertices().to_vec();
        for t in 0..mesh.triangles().len() {
            let c = mesh.triangle(t);
            for i in 0..3 {
                targets.push(Point3::from((c[i].coords + c[(i + 1) % 3].coords) * 0.5));
            }
        }
        for target in targets {
            for _ in 0..3 {
                let origin = Point3::new(rng.int(-4, 4), rng.int(-4, 4), rng.int(-4, 4));
                if origin != target {
                    out.push(Ray {
                        origin,
                        direction: target - origin,
                    });
                }
            }
        }
    }
    out
}

/// Shoots `rays` through a hierarchy of each shape and compares with testing every triangle
/// and with the R-tree ray shooting of `VisibilityIndex`.
fn check_rays<S: NodeShape>(mesh: &Mesh, rays: &[Ray], index: &VisibilityIndex) {
    let tree: BoxTree<S> = BoxTree::build(mesh, Merge::Area);
    for ray in rays {
        let shot = tree.first_hit(ray);
        let brute = first_hit_brute_force(tree.triangles(), ray);
        assert_eq!(shot.hit, brute, "{}: {ray:?}", S::SHAPE);
        let reference = index.first_hit(ray);
        assert_eq!(
            shot.hit.map(|h| h.triangle),
            reference.map(|h| h.triangle),
            "{}: {ray:?} against VisibilityIndex",
            S::SHAPE
        );
        if let (Some(h), Some(r)) = (shot.hit, reference) {
            assert!((h.point - r.point).norm() <= 1e-12 * (1.0 + r.point.coords.norm()));
        }
        assert!(shot.met <= shot.visited && shot.visited <= tree.nodes().len());
        assert!(tree.stabbing(ray) >= shot.met.min(1));
    }
}

#[test]
fn ray_shooting_matches_brute_force() {
    let mut rng = SplitMix64(11);
    let meshes = [
        (octahedron(), true),
        (kepler::solids::cube(2.0).unwrap(), true),
        (kepler::solids::uv_sphere(1.5, 12, 6).unwrap(), false),
        (kepler::solids::torus(2.0, 0.6, 16, 8).unwrap(), false),
        (soup(&mut SplitMix64(3), 40, true, 0.0, 0.0).unwrap(), true),
        (
            soup(&mut SplitMix64(4), 60, false, 2.0, 0.0).unwrap(),
            false,
        ),
    ];
    for (mesh, exact_targets) in &meshes {
        let rays = rays(&mut rng, mesh, 150, *exact_targets);
        let mut scene = Scene::new();
        scene.add_mesh(None, "mesh", mesh.clone()).unwrap();
        let index = VisibilityIndex::whole_scene(&scene, View::standard());
        check_rays::<Aabb>(mesh, &rays, &index);
        check_rays::<PcaAll>(mesh, &rays, &index);
        check_rays::<PcaMax>(mesh, &rays, &index);
        check_rays::<PcaMin>(mesh, &rays, &index);
        check_rays::<TriboxBounds>(mesh, &rays, &index);
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(400))]

    /// The conservative slab interval holds the exact one (rationals), for arbitrary and for
    /// the tribox's fixed directions, rays nearly parallel to the slab, and far origins.
    #[test]
    fn slab_intervals_enclose_the_exact_ones(
        seed in any::<u64>(),
        scale in -3i32..8,
        nearly_parallel in any::<bool>(),
        fixed in 0usize..12,
    ) {
        let mut rng = SplitMix64(seed);
        let big = 10f64.powi(scale);
        let a = if fixed < 9 {
            Vector3::from(TriboxBounds::DIRECTIONS[fixed])
        } else {
            rng.vector(1.0)
        };
        let mut u = rng.vector(1.0);
        if nearly_parallel {
            u -= a * (a.dot(&u) / a.norm_squared());
            u += rng.vector(1e-12);
        }
        let origin = Point3::from(rng.vector(big));
        let probe = kepler::lab::boxtree::RayProbe::new(&Ray { origin, direction: u });
        prop_assume!(probe.is_some());
        let probe = probe.unwrap();
        let (x, y) = (rng.range(-big, big), rng.range(-big, big));
        let (lo, hi) = (x.min(y), x.max(y));
        let projection = if fixed < 9 { *probe.fixed(fixed) } else { probe.along(&a) };
        let [t0, t1] = projection.interval(lo, hi);
        let qa = qv([a.x, a.y, a.z]);
        let d = probe.ray().direction;
        let s = qdot(&qa, &qv([origin.x, origin.y, origin.z]));
        let w = qdot(&qa, &qv([d.x, d.y, d.z]));
        if w.is_zero() {
            if q(lo) <= s && s <= q(hi) {
                prop_assert_eq!([t0, t1], [f64::NEG_INFINITY, f64::INFINITY]);
            }
        } else {
            let (e0, e1) = ((q(lo) - &s) / &w, (q(hi) - &s) / &w);
            let (first, last) = if e0 <= e1 { (e0, e1) } else { (e1, e0) };
            prop_assert!(t0 == f64::NEG_INFINITY || q(t0) <= first, "{t0} > {first}");
            prop_assert!(t1 == f64::INFINITY || q(t1) >= last, "{t1} < {last}");
        }
    }
}

#[test]
fn stabbing_counts_every_bound_the_ray_meets() {
    let mesh = kepler::solids::torus(2.0, 0.6, 16, 8).unwrap();
    let tree: BoxTree<Aabb> = BoxTree::build(&mesh, Merge::Area);
    let mut rng = SplitMix64(5);
    for ray in rays(&mut rng, &mesh, 100, false) {
        // Boxes met, one by one: a node is met only if its parent is, so the descent finds all.
        let probe = kepler::lab::boxtree::RayProbe::new(&ray).unwrap();
        let all = tree
            .nodes()
            .iter()
            .filter(|n| n.bound().ray_interval(&probe).is_some())
            .count();
        assert_eq!(tree.stabbing(&ray), all);
        assert!(tree.first_hit(&ray).met <= all);
    }
}

// ---------------------------------------------------------------------------------------------
// Collision detection.

/// Whether the triangles share a point, by the separating-axis theorem in rational arithmetic
/// (an independent reference for proper triangles): they are disjoint exactly when their
/// projections on one of the candidate axes are disjoint, the candidates being the normals,
/// the cross products of edges, and each normal crossed with every edge (for coplanar and
/// edge-parallel configurations).
fn meet_by_separating_axes(a: &[Point3; 3], b: &[Point3; 3]) -> bool {
    let pa = a.map(|p| qv([p.x, p.y, p.z]));
    let pb = b.map(|p| qv([p.x, p.y, p.z]));
    let edges =
        |p: &[[Q; 3]; 3]| -> Vec<[Q; 3]> { (0..3).map(|i| qsub(&p[(i + 1) % 3], &p[i])).collect() };
    let (ea, eb) = (edges(&pa), edges(&pb));
    let (na, nb) = (qcross(&ea[0], &ea[1]), qcross(&eb[0], &eb[1]));
    let mut axes = vec![na.clone(), nb.clone(), qcross(&na, &nb)];
    for x in &ea {
        for y in &eb {
            axes.push(qcross(x, y));
        }
    }
    for e in ea.iter().chain(&eb) {
        axes.push(qcross(&na, e));
        axes.push(qcross(&nb, e));
    }
    !axes.iter().any(|axis| {
        if axis.iter().all(|c| c.is_zero()) {
            return false;
        }
        let project = |p: &[[Q; 3]; 3]| {
            let d: Vec<Q> = p.iter().map(|v| qdot(axis, v)).collect();
            let lo = d.iter().min().cloned().unwrap();
            let hi = d.iter().max().cloned().unwrap();
            (lo, hi)
        };
        let ((alo, ahi), (blo, bhi)) = (project(&pa), project(&pb));
        ahi < blo || bhi < alo
    })
}

#[test]
fn triangle_test_matches_separating_axes() {
    let mut rng = SplitMix64(21);
    let mut counts = [0usize; 2];
    for i in 0..6_000 {
        let span = if i % 2 == 0 { 2 } else { 4 };
        let t = || -> [Point3; 3] { [Point3::origin(); 3] };
        let (mut a, mut b) = (t(), t());
        for p in a.iter_mut().chain(b.iter_mut()) {
            *p = Point3::new(rng.int(0, span), rng.int(0, span), rng.int(0, span));
        }
        if collinear(&a[0], &a[1], &a[2]) || collinear(&b[0], &b[1], &b[2]) {
            continue;
        }
        let expected = meet_by_separating_axes(&a, &b);
        assert_eq!(triangles_meet(&a, &b), expected, "{a:?} {b:?}");
        assert_eq!(triangles_meet(&b, &a), expected, "{b:?} {a:?}");
        counts[expected as usize] += 1;
    }
    assert!(counts[0] > 500 && counts[1] > 500, "{counts:?}");
}

#[test]
fn degenerate_triangles_meet_as_segments() {
    let p = |x, y, z| Point3::new(x, y, z);
    let t = [p(0.0, 0.0, 0.0), p(4.0, 0.0, 0.0), p(0.0, 4.0, 0.0)];
    let cases = [
        // A segment in t's plane crossing its hypotenuse, and one beyond it.
        ([p(1.0, 1.0, 0.0), p(3.0, 3.0, 0.0), p(2.0, 2.0, 0.0)], true),
        (
            [p(3.0, 3.0, 0.0), p(5.0, 5.0, 0.0), p(4.0, 4.0, 0.0)],
            false,
        ),
        // Ending exactly on t, from above; stopping short of it.
        ([p(1.0, 1.0, 2.0), p(1.0, 1.0, 0.0), p(1.0, 1.0, 1.0)], true),
        (
            [p(1.0, 1.0, 2.0), p(1.0, 1.0, 0.5), p(1.0, 1.0, 1.0)],
            false,
        ),
    ];
    for (s, expected) in cases {
        assert_eq!(triangles_meet(&t, &s), expected, "{s:?}");
        assert_eq!(triangles_meet(&s, &t), expected, "{s:?}");
    }
    // Two segments: crossing, collinear and overlapping, collinear and apart, skew.
    let seg = |a: Point3, b: Point3| [a, b, Point3::from((a.coords + b.coords) * 0.5)];
    let s = seg(p(0.0, 0.0, 0.0), p(2.0, 2.0, 2.0));
    assert!(triangles_meet(&s, &seg(p(0.0, 2.0, 2.0), p(2.0, 0.0, 0.0))));
    assert!(triangles_meet(&s, &seg(p(1.0, 1.0, 1.0), p(3.0, 3.0, 3.0))));
    assert!(!triangles_meet(
        &s,
        &seg(p(3.0, 3.0, 3.0), p(4.0, 4.0, 4.0))
    ));
    assert!(!triangles_meet(
        &s,
        &seg(p(0.0, 2.0, 0.0), p(2.0, 0.0, 1.0))
    ));
}

/// Compares the collision queries of hierarchies of one shape with testing every pair.
fn check_collisions<S: NodeShape>(a: &Mesh, b: &Mesh) {
    let (ta, tb) = (
        BoxTree::<S>::build(a, Merge::Area),
        BoxTree::<S>::build(b, Merge::Volume),
    );
    let mut brute = Vec::new();
    for i in 0..a.triangles().len() {
        for j in 0..b.triangles().len() {
            if triangles_meet(&a.triangle(i), &b.triangle(j)) {
                brute.push([i, j]);
            }
        }
    }
    let first = ta.collide(&tb);
    assert_eq!(first.pair.is_some(), !brute.is_empty(), "{}", S::SHAPE);
    if let Some(pair) = first.pair {
        assert!(brute.contains(&pair));
    }
    let (pairs, all) = ta.intersecting_pairs(&tb);
    assert_eq!(pairs, brute, "{}", S::SHAPE);
    assert!(first.tests <= all.tests && all.tests > 0);
    assert!(all.triangle_tests as usize >= pairs.len());
}

#[test]
fn collisions_match_brute_force() {
    let mut rng = SplitMix64(31);
    for round in 0..24 {
        let grid = round % 3 != 2;
        let a = soup(&mut rng, 12 + round % 7, grid, 1.5, 0.0).unwrap();
        let offset = if round % 4 == 0 { 3.0 } else { 0.5 };
        let b = soup(&mut rng, 10 + round % 5, grid, 1.5, offset).unwrap();
        check_collisions::<Aabb>(&a, &b);
        check_collisions::<PcaAll>(&a, &b);
        check_collisions::<PcaMax>(&a, &b);
        check_collisions::<PcaMin>(&a, &b);
        check_collisions::<TriboxBounds>(&a, &b);
    }
    // Closed surfaces: a torus against a shifted copy, and two nested spheres.
    let t = kepler::solids::torus(2.0, 0.6, 12, 6).unwrap();
    let shifted = t
        .transformed(&nalgebra::Matrix4::new_translation(&Vector3::new(
            0.3, 1.1, 0.2,
        )))
        .unwrap();
    let (inner, outer) = sphere_pair(60, 0.02, 9).unwrap();
    for (a, b) in [(&t, &shifted), (&inner, &outer)] {
        check_collisions::<Aabb>(a, b);
        check_collisions::<PcaMin>(a, b);
        check_collisions::<TriboxBounds>(a, b);
    }
}

// ---------------------------------------------------------------------------------------------
// The sphere experiment.

#[test]
fn sphere_pairs_are_convex_hulls() {
    let (inner, outer) = sphere_pair(200, 0.05, 2).unwrap();
    for mesh in [&inner, &outer] {
        assert_eq!(mesh.triangles().len(), 200);
        assert_eq!(mesh.vertices().len(), 102);
        assert!(mesh.is_solid());
        // Every vertex on or behind every face's plane, exactly.
        for t in 0..mesh.triangles().len() {
            let [a, b, c] = mesh.triangle(t);
            assert!(
                mesh.vertices()
                    .iter()
                    .all(|v| orient3d(&a, &b, &c, v) != Ordering::Less)
            );
        }
    }
    assert!(sphere_pair(3, 0.05, 2).is_err());
    assert!(sphere_pair(100, f64::NAN, 2).is_err());
}

#[test]
fn sphere_experiment_on_the_papers_smallest_pair() {
    let rows = sphere_experiment(&[556], 0.01, 1, Merge::Volume).unwrap();
    assert_eq!(rows.len(), Shape::ALL.len());
    for (row, shape) in rows.iter().zip(Shape::ALL) {
        assert_eq!((row.facets, row.shape), (556, shape));
        assert!(row.tests > 0 && row.triangle_tests > 0);
        // Exact triangle tests: every shape finds the same meeting pairs.
        assert_eq!(row.intersecting_pairs, rows[0].intersecting_pairs);
    }
    assert_eq!(rows[0].paper, Some(9_479));
    assert_eq!(rows[3].paper, Some(7_721));
}

#[test]
fn sphere_experiment_on_the_papers_larger_pairs() {
    for merge in [Merge::Volume, Merge::Area] {
        let rows = sphere_experiment(&[1996, 9996], 0.01, 1, merge).unwrap();
        for row in &rows {
            println!(
                "{merge:>6} {:>5} {:>8} {:>8} paper {:?}",
                row.facets, row.shape, row.tests, row.paper
            );
        }
        assert_eq!(rows.len(), 10);
    }
}
