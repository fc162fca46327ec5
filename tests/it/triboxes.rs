//! Hierarchical triboxes (`kepler::lab::tribox_hierarchy`): the cells partition the object (their volumes,
//! computed here independently by clipping the object's signed tetrahedra to each leaf's
//! region, sum to the object's volume), the tree's regions and triboxes nest, the levels'
//! figures agree with direct computations, and the Hausdorff bounds bracket distances
//! measured by brute force. The exact containment of each cell in its tribox is checked in
//! `tests/triboxes_exact.rs`.

use geo::polygon;
use kepler::bounds::tribox::{Tribox, TriboxBounds};
use kepler::geometry::{Point3, Vector3};
use kepler::lab::tribox_hierarchy::{
    Hierarchy, HierarchyOptions, SplitRule, Stop, hausdorff, tribox_mesh, union_area,
};
use kepler::mesh::{Containment, Mesh, TriangleTree, classify_point};
use proptest::prelude::*;
use proptest::test_runner::{RngAlgorithm, TestRng};

fn l_wall() -> Mesh {
    let outline = polygon![(x: 0.0, y: 0.0), (x: 6.0, y: 0.0), (x: 6.0, y: 1.0),
        (x: 1.0, y: 1.0), (x: 1.0, y: 4.0), (x: 0.0, y: 4.0)];
    kepler::solids::prism(&outline, 3.0).unwrap()
}

fn u_prism() -> Mesh {
    let outline = polygon![(x: 0.0, y: 0.0), (x: 5.0, y: 0.0), (x: 5.0, y: 5.0), (x: 4.0, y: 5.0),
        (x: 4.0, y: 1.0), (x: 1.0, y: 1.0), (x: 1.0, y: 5.0), (x: 0.0, y: 5.0)];
    kepler::solids::prism(&outline, 2.0).unwrap()
}

fn star() -> Mesh {
    let outline = polygon![(x: 0.0, y: 3.0), (x: 0.7, y: 1.0), (x: 2.9, y: 0.9), (x: 1.1, y: -0.4),
        (x: 1.8, y: -2.5), (x: 0.0, y: -1.2), (x: -1.8, y: -2.5), (x: -1.1, y: -0.4),
        (x: -2.9, y: 0.9), (x: -0.7, y: 1.0)];
    kepler::solids::prism(&outline, 1.5).unwrap()
}

fn torus() -> Mesh {
    kepler::solids::torus(2.0, 0.7, 16, 10).unwrap()
}

fn sphere() -> Mesh {
    kepler::solids::uv_sphere(2.0, 24, 12).unwrap()
}

/// HierarchyOptions that split every cell down to `depth` (a negative gain accepts any split).
fn deep(depth: usize, split: SplitRule) -> HierarchyOptions {
    HierarchyOptions {
        gain: -10.0,
        max_depth: depth,
        split,
        ..HierarchyOptions::default()
    }
}

// ---------------------------------------------------------------------------------------
// Volume of S ∩ C, independently: S's indicator is the signed sum of the indicators of the
// tetrahedra (o, triangle) for any o, so vol(S ∩ C) = Σ ± vol(tet ∩ C); each tet ∩ C is cut
// plane by plane into tetrahedra.
// ---------------------------------------------------------------------------------------

type Tet = [Point3; 4];

/// The point where the plane value goes from `fa` at `a` to `fb` at `b` (opposite signs).
fn crossing(a: &Point3, b: &Point3, fa: f64, fb: f64) -> Point3 {
    a + (b - a) * (fa / (fa - fb))
}

/// The part of tetrahedron `t` with n · x ≤ beta, as tetrahedra (a vertex on the plane
/// counts as inside): the corner tetrahedron, or a prism cut into three.
fn clip(t: &Tet, n: &Vector3, beta: f64, out: &mut Vec<Tet>) {
    let f: Vec<f64> = t.iter().map(|p| n.dot(&p.coords) - beta).collect();
    let inside: Vec<usize> = (0..4).filter(|&i| f[i] <= 0.0).collect();
    let outside: Vec<usize> = (0..4).filter(|&i| f[i] > 0.0).collect();
    let x = |i: usize, o: usize| crossing(&t[i], &t[o], f[i], f[o]);
    let prism = |a: [Point3; 3], b: [Point3; 3], out: &mut Vec<Tet>| {
        out.push([a[0], a[1], a[2], b[0]]);
        out.push([a[1], a[2], b[0], b[1]]);
        out.push([a[2], b[0], b[1], b[2]]);
    };
    match (inside.as_slice(), outside.as_slice()) {
        (_, []) => out.push(*t),
        ([], _) => {}
        (&[a], &[b, c, d]) => out.push([t[a], x(a, b), x(a, c), x(a, d)]),
        (&[a, b, c], &[d]) => prism([t[a], t[b], t[c]], [x(a, d), x(b, d), x(c, d)], out),
        (&[a, b], &[c, d]) => prism([t[a], x(a, c), x(a, d)], [t[b], x(b, c), x(b, d)], out),
        _ => unreachable!("four vertices"),
    }
}

fn tet_volume(t: &Tet) -> f64 {
    (t[1] - t[0])
        .dot(&(t[2] - t[0]).cross(&(t[3] - t[0])))
        .abs()
        / 6.0
}

/// vol(S ∩ region) by signed tetrahedra from `o` (a point of the root region).
fn cell_volume(mesh: &Mesh, region: &TriboxBounds, o: Point3) -> f64 {
    let planes: Vec<(Vector3, f64)> = (0..18)
        .map(|j| {
            let n = Vector3::from(Tribox::PLANE_NORMALS[j]);
            let beta = if j % 2 == 0 {
                -region.min()[j / 2]
            } else {
                region.max()[j / 2]
            };
            (n, beta)
        })
        .collect();
    (0..mesh.triangles().len())
        .map(|t| {
            let [a, b, c] = mesh.triangle(t);
            let sign = (a - o).dot(&(b - o).cross(&(c - o))).signum();
            let mut pieces = vec![[o, a, b, c]];
            for (n, beta) in &planes {
                let mut next = Vec::new();
                for t in &pieces {
                    clip(t, n, *beta, &mut next);
                }
                pieces = next;
            }
            sign * pieces.iter().map(tet_volume).sum::<f64>()
        })
        .sum()
}

fn centre(b: &TriboxBounds) -> Point3 {
    Point3::new(
        0.5 * (b.min()[0] + b.max()[0]),
        0.5 * (b.min()[1] + b.max()[1]),
        0.5 * (b.min()[2] + b.max()[2]),
    )
}

/// The leaves' cells partition the object, and every node's cell has volume, at most its
/// tribox's.
fn check_partition(mesh: &Mesh, options: &HierarchyOptions) {
    let h = Hierarchy::build(mesh, options).unwrap();
    let o = centre(&h.nodes()[0].region);
    let leaves = h.leaves();
    let mut total = 0.0;
    for &i in &leaves {
        let node = &h.nodes()[i];
        let v = cell_volume(mesh, &node.region, o);
        // A feature plane through a vertex can leave a true sliver (its tribox of volume
        // ~1e-31 on a unit object) that clipping in doubles loses; the exact reference of
        // tests/triboxes_exact.rs checks such cells.
        let sliver = node.volume <= 1e-15 * h.nodes()[0].volume;
        assert!(v > 0.0 || sliver, "node {i}: empty cell ({v})");
        assert!(
            v <= node.volume * (1.0 + 1e-12),
            "node {i}: cell {v} > tribox {}",
            node.volume
        );
        total += v;
    }
    let exact = mesh.volume();
    assert!(
        ((total - exact) / exact).abs() <= 1e-9,
        "cells sum to {total}, object {exact} ({} leaves)",
        leaves.len()
    );
}

#[test]
fn cells_partition_the_object() {
    for mesh in [l_wall(), u_prism(), star(), torus()] {
        for split in [
            SplitRule::Bisectors,
            SplitRule::Thickest,
            SplitRule::Features,
        ] {
            check_partition(&mesh, &deep(3, split));
        }
        check_partition(&mesh, &HierarchyOptions::default());
    }
}

#[test]
fn the_partition_test_sees_a_missing_cell() {
    // The same sum without one leaf falls short: the check can fail.
    let mesh = u_prism();
    let h = Hierarchy::build(&mesh, &deep(2, SplitRule::Bisectors)).unwrap();
    let o = centre(&h.nodes()[0].region);
    let leaves = h.leaves();
    assert_eq!(leaves.len(), 4);
    let partial: f64 = leaves[1..]
        .iter()
        .map(|&i| cell_volume(&mesh, &h.nodes()[i].region, o))
        .sum();
    assert!(mesh.volume() - partial > 1.0, "{partial}");
}

// ---------------------------------------------------------------------------------------
// The tree.
// ---------------------------------------------------------------------------------------

fn within(inner: &TriboxBounds, outer: &TriboxBounds) -> bool {
    (0..9).all(|d| outer.min()[d] <= inner.min()[d] && inner.max()[d] <= outer.max()[d])
}

/// Children's regions are the parent's cut by its plane; triboxes lie in their regions and
/// in their parents' triboxes; splits obey the area rule.
fn check_tree(mesh: &Mesh, options: &HierarchyOptions) {
    let h = Hierarchy::build(mesh, options).unwrap();
    let nodes = h.nodes();
    assert_eq!(nodes[0].region, nodes[0].tribox);
    assert_eq!(nodes[0].tribox, TriboxBounds::from_points(mesh.vertices()));
    for (i, n) in nodes.iter().enumerate() {
        assert!(within(&n.tribox, &n.region), "node {i}");
        assert!(n.depth <= options.max_depth);
        match (n.children, n.split) {
            (Some([a, b]), Some(plane)) => {
                let d = plane.direction;
                assert!(n.tribox.min()[d] < plane.offset && plane.offset < n.tribox.max()[d]);
                assert_eq!(nodes[a].region, n.region.split(d, plane.offset)[0]);
                assert_eq!(nodes[b].region, n.region.split(d, plane.offset)[1]);
                for c in [a, b] {
                    assert_eq!((nodes[c].parent, nodes[c].depth), (Some(i), n.depth + 1));
                    assert!(within(&nodes[c].tribox, &n.tribox), "node {c} in {i}");
                }
                assert!(nodes[a].area + nodes[b].area <= (1.0 - options.gain) * n.area);
            }
            (None, None) => {}
            other => panic!("node {i}: children and split disagree: {other:?}"),
        }
    }
    // Every cut covers each leaf exactly once (through itself or an ancestor).
    for depth in 0..=h.depth() {
        let cut = h.cut(depth);
        for leaf in h.leaves() {
            let mut chain = vec![leaf];
            while let Some(p) = nodes[*chain.last().unwrap()].parent {
                chain.push(p);
            }
            assert_eq!(chain.iter().filter(|c| cut.contains(c)).count(), 1);
        }
    }
}

#[test]
fn the_tree_nests() {
    for mesh in [l_wall(), u_prism(), star(), torus()] {
        check_tree(&mesh, &deep(4, SplitRule::Bisectors));
        check_tree(&mesh, &deep(3, SplitRule::Features));
        check_tree(&mesh, &deep(4, SplitRule::Thickest));
        check_tree(&mesh, &HierarchyOptions::default());
    }
}

#[test]
fn the_paper_rule_splits_the_l_wall_once_and_keeps_a_cube_whole() {
    let h = Hierarchy::build(&l_wall(), &HierarchyOptions::default()).unwrap();
    assert_eq!(h.nodes().len(), 3);
    let split = h.nodes()[0].split.unwrap();
    // The L is cut across x at 3: the bisector of its slab [0, 6].
    assert_eq!((split.direction, split.offset), (0, 3.0));
    // The two halves' triboxes, exactly: the left L's corner is cut by x + y <= 5.
    let [a, b] = h.nodes()[0].children.unwrap();
    assert_eq!(h.nodes()[a].tribox.max()[3], 5.0);
    assert_eq!(h.nodes()[b].tribox.max()[1], 1.0);
    assert_eq!(h.nodes()[b].volume, 9.0);
    let cube = Hierarchy::build(
        &kepler::solids::cube(1.0).unwrap(),
        &HierarchyOptions::default(),
    )
    .unwrap();
    assert_eq!(cube.nodes().len(), 1);
}

#[test]
fn bad_options_and_open_meshes_are_errors() {
    let wall = l_wall();
    for gain in [1.0, f64::NAN, f64::NEG_INFINITY] {
        let o = HierarchyOptions {
            gain,
            ..HierarchyOptions::default()
        };
        assert!(Hierarchy::build(&wall, &o).is_err(), "gain {gain}");
    }
    let o = HierarchyOptions {
        hausdorff_tolerance: 0.0,
        ..HierarchyOptions::default()
    };
    assert!(Hierarchy::build(&wall, &o).is_err());
    let open = Mesh::from_polygons(
        vec![
            Point3::new(0.0, 0.0, 0.0),
            Point3::new(1.0, 0.0, 0.0),
            Point3::new(0.0, 1.0, 0.0),
            Point3::new(0.0, 0.0, 1.0),
        ],
        vec![vec![0, 2, 1], vec![0, 1, 3], vec![1, 2, 3]],
    )
    .unwrap();
    assert!(Hierarchy::build(&open, &HierarchyOptions::default()).is_err());
}

// ---------------------------------------------------------------------------------------
// Levels.
// ---------------------------------------------------------------------------------------

#[test]
fn level_figures_agree_with_direct_computations() {
    let mesh = u_prism();
    let h = Hierarchy::build(&mesh, &deep(3, SplitRule::Bisectors)).unwrap();
    let levels = h.levels(10);
    assert_eq!(levels.len(), 4);
    for (depth, l) in levels.iter().enumerate() {
        let cut = h.cut(depth);
        assert_eq!((l.depth, l.triboxes), (depth, cut.len()));
        let faces: usize = cut.iter().map(|&i| h.nodes()[i].faces).sum();
        assert_eq!(l.faces, faces);
        assert_eq!(l.compression, mesh.faces().len() as f64 / faces as f64);
        let volume: f64 = cut
            .iter()
            .map(|&i| Tribox::new(&h.nodes()[i].tribox).cleaned().volume())
            .sum();
        assert_eq!(l.volume, volume);
        assert_eq!(l.volume_excess, volume / mesh.volume() - 1.0);
        assert!(l.volume_excess >= 0.0);
        assert_eq!(l.area_excess, l.area / mesh.surface_area() - 1.0);
        assert!(l.hausdorff_lower <= l.hausdorff);
    }
    // Splitting to depth 3 leaves only corner chamfers: the bound is within a few percent.
    assert!(levels[3].volume_excess < 0.1 && levels[0].volume_excess > 0.9);
    // Each tribox has at least 4 faces; the U has 10.
    assert!(levels.iter().all(|l| l.faces >= 6 * l.triboxes));
}

#[test]
fn union_area_removes_shared_faces() {
    // The L wall's halves meet on x = 3: the left face there is 2 × 3, the right one 1 × 3,
    // so the union loses twice the 3 of their overlap.
    let h = Hierarchy::build(&l_wall(), &HierarchyOptions::default()).unwrap();
    let level = h.levels(2)[1];
    let [a, b] = h.nodes()[0].children.unwrap();
    let sum = h.nodes()[a].area + h.nodes()[b].area;
    assert!(
        (level.area - (sum - 6.0)).abs() < 1e-12,
        "{} {sum}",
        level.area
    );
    // A unit cube cut by x + y = 1: two prisms whose union is the cube, area 6.
    let corners: Vec<Point3> = (0..8)
        .map(|i| Point3::new((i & 1) as f64, ((i >> 1) & 1) as f64, ((i >> 2) & 1) as f64))
        .collect();
    let [lo, hi] = TriboxBounds::from_points(&corners).split(3, 1.0);
    let area = union_area(&[lo, hi]).unwrap();
    assert!((area - 6.0).abs() < 1e-12, "{area}");
    // Apart, nothing is shared.
    let apart: Vec<Point3> = corners
        .iter()
        .map(|p| p + Vector3::new(5.0, 0.0, 0.0))
        .collect();
    let far = TriboxBounds::from_points(&apart);
    assert_eq!(
        union_area(&[lo, far]).unwrap(),
        union_area(&[lo]).unwrap() + 6.0
    );
}

// ---------------------------------------------------------------------------------------
// Hausdorff bounds against brute force.
// ---------------------------------------------------------------------------------------

/// The distance from p to segment ab.
fn segment_distance(p: &Point3, a: &Point3, b: &Point3) -> f64 {
    let ab = b - a;
    let t = ((p - a).dot(&ab) / ab.norm_squared()).clamp(0.0, 1.0);
    (p - (a + ab * t)).norm()
}

/// The distance from p to a triangle: to its plane when the foot is inside, else to an edge.
fn triangle_distance(p: &Point3, t: &[Point3; 3]) -> f64 {
    let n = (t[1] - t[0]).cross(&(t[2] - t[0]));
    let foot = p - n * ((p - t[0]).dot(&n) / n.norm_squared());
    let inside = (0..3).all(|i| {
        let (a, b) = (t[i], t[(i + 1) % 3]);
        (b - a).cross(&(foot - a)).dot(&n) >= 0.0
    });
    if inside {
        (p - foot).norm()
    } else {
        (0..3)
            .map(|i| segment_distance(p, &t[i], &t[(i + 1) % 3]))
            .fold(f64::INFINITY, f64::min)
    }
}

/// d(p, S): 0 inside, else the distance to the nearest triangle (all of them).
fn solid_distance(mesh: &Mesh, tree: &TriangleTree, p: &Point3) -> f64 {
    if classify_point(tree, p) != Containment::Outside {
        return 0.0;
    }
    (0..mesh.triangles().len())
        .map(|t| triangle_distance(p, &mesh.triangle(t)))
        .fold(f64::INFINITY, f64::min)
}

/// A uniform number in [0, 1) from proptest's deterministic generator.
fn unit(rng: &mut TestRng) -> f64 {
    (rng.next_u64() >> 11) as f64 / (1u64 << 53) as f64
}

/// Sampled distances from the union never exceed the upper bound, the tribox vertices'
/// distances either, and the bounds are within the tolerance.
fn check_hausdorff(mesh: &Mesh, triboxes: &[TriboxBounds], rng: &mut TestRng) {
    let tree = TriangleTree::new(mesh);
    // Prisms reach their distance along ridges and plateaus, where boxes grow as 1/tol²:
    // 1% of these objects' size stays within the box budget.
    let tol = 1e-2;
    let d = hausdorff(triboxes, &tree, tol);
    assert!(
        d.lower <= d.upper && d.upper - d.lower <= tol * 1.000001,
        "{d:?}"
    );
    let mut sampled: f64 = 0.0;
    let mut corners: f64 = 0.0;
    for t in triboxes {
        let boundary = Tribox::new(t).cleaned();
        for v in boundary.vertices() {
            corners = corners.max(solid_distance(mesh, &tree, v));
        }
        let (lo, hi) = (t.min(), t.max());
        let mut taken = 0;
        while taken < 300 {
            let p = Point3::new(
                lo[0] + unit(rng) * (hi[0] - lo[0]),
                lo[1] + unit(rng) * (hi[1] - lo[1]),
                lo[2] + unit(rng) * (hi[2] - lo[2]),
            );
            if t.contains_point(&p) {
                taken += 1;
                sampled = sampled.max(solid_distance(mesh, &tree, &p));
            }
        }
    }
    let sampled = sampled.max(corners);
    assert!(sampled <= d.upper, "sampled {sampled} > upper {}", d.upper);
    // The lower bound is at least what the triboxes' corners give.
    assert!(
        corners <= d.lower + 1e-12,
        "corners {corners} > lower {}",
        d.lower
    );
}

#[test]
fn hausdorff_bounds_bracket_brute_force_distances() {
    let mut rng = TestRng::deterministic_rng(RngAlgorithm::ChaCha);
    for mesh in [l_wall(), u_prism(), star(), torus()].iter() {
        let h = Hierarchy::build(mesh, &deep(2, SplitRule::Bisectors)).unwrap();
        for depth in 0..=h.depth() {
            let triboxes: Vec<TriboxBounds> =
                h.cut(depth).iter().map(|&i| h.nodes()[i].tribox).collect();
            check_hausdorff(mesh, &triboxes, &mut rng);
        }
    }
}

#[test]
fn hausdorff_of_the_l_walls_tribox_is_its_notch_corner() {
    // The tribox of the L wall reaches the notch's far corner region: (6, 1, z) to (1, 4, z)
    // is cut by x + y <= 7, and the farthest points from the L are on that face's middle line
    // (3.5, 3.5, z), at distance 2.5 from the L (from (1, 3.5, z) and from (3.5, 1, z)): a
    // ridge, the hard case of branch and bound.
    let mesh = l_wall();
    let t = TriboxBounds::from_points(mesh.vertices());
    let d = hausdorff(&[t], &TriangleTree::new(&mesh), 1e-3);
    assert!(
        d.lower <= 2.5 && 2.5 <= d.upper && d.upper - d.lower <= 1e-3,
        "{d:?}"
    );
}

#[test]
fn hausdorff_of_a_shape_equal_to_its_tribox_is_zero() {
    // Every box across the surface has a positive upper bound, so a union hugging the
    // object is the costly case: the box budget runs out and the bounds stay valid.
    let cube = kepler::solids::cube(3.0).unwrap();
    let d = hausdorff(
        &[TriboxBounds::from_points(cube.vertices())],
        &TriangleTree::new(&cube),
        1e-6,
    );
    assert_eq!(d.lower, 0.0);
    assert!(d.upper > 0.0 && d.upper <= 0.01, "{d:?}");
    let coarse = hausdorff(
        &[TriboxBounds::from_points(cube.vertices())],
        &TriangleTree::new(&cube),
        0.05,
    );
    assert!(coarse.lower == 0.0 && coarse.upper <= 0.05, "{coarse:?}");
}

// ---------------------------------------------------------------------------------------
// Drawing meshes.
// ---------------------------------------------------------------------------------------

#[test]
fn tribox_meshes_are_closed_and_match_the_bounds() {
    // The star's cells meet chamfers within rounding of a line: slivers the mesh must drop.
    for (mesh, split) in [
        (torus(), SplitRule::Bisectors),
        (star(), SplitRule::Features),
    ] {
        let h = Hierarchy::build(&mesh, &deep(3, split)).unwrap();
        for n in h.nodes() {
            let m = tribox_mesh(&n.tribox, h.simplify_tolerance()).unwrap();
            assert!(m.is_solid());
            assert!(((m.volume() - n.volume) / n.volume).abs() < 1e-6);
            assert_eq!(m.polygons().len(), n.faces);
            // Simplifying moves planes outward only.
            let b = TriboxBounds::from_points(m.vertices());
            assert!((0..9).all(|d| b.max()[d] >= n.tribox.max()[d] - 1e-9));
            assert!((0..9).all(|d| b.min()[d] <= n.tribox.min()[d] + 1e-9));
        }
    }
}

// ---------------------------------------------------------------------------------------
// Levels asked for (`HierarchyOptions::levels`): made below the gain where the gain stops.
// ---------------------------------------------------------------------------------------

/// The paper's options, asking for `levels` levels.
fn asking(levels: usize) -> HierarchyOptions {
    HierarchyOptions {
        levels: Some(levels),
        ..HierarchyOptions::default()
    }
}

#[test]
fn the_gain_stops_a_torus_and_a_sphere_at_the_root_and_names_the_gain_that_splits() {
    for mesh in [torus(), sphere()] {
        let h = Hierarchy::build(&mesh, &HierarchyOptions::default()).unwrap();
        assert_eq!(h.depth(), 0);
        let Stop::Gain { best_gain } = h.stop() else {
            panic!("{:?}", h.stop());
        };
        assert!(best_gain < 0.0, "{best_gain}");
        // Under the best gain the root splits; a little above it, it does not.
        let depth = |gain| {
            let o = HierarchyOptions {
                gain,
                ..HierarchyOptions::default()
            };
            Hierarchy::build(&mesh, &o).unwrap().depth()
        };
        assert!(depth(best_gain) > 0);
        assert_eq!(depth(best_gain + 1e-9), 0);
    }
}

#[test]
fn asked_levels_are_made_below_the_gain_and_marked() {
    for mesh in [torus(), sphere()] {
        let options = asking(4);
        let h = Hierarchy::build(&mesh, &options).unwrap();
        let levels = h.levels(4);
        assert_eq!(levels.len(), 4);
        assert!(!levels[0].below_gain && levels[1].below_gain);
        for pair in levels.windows(2) {
            assert!(pair[1].triboxes > pair[0].triboxes);
            assert!(pair[1].volume <= pair[0].volume);
        }
        // A level is marked exactly when the splits that made it all miss the gain.
        let nodes = h.nodes();
        for l in &levels[1..] {
            let fits: Vec<bool> = nodes
                .iter()
                .filter(|n| n.depth + 1 == l.depth)
                .filter_map(|n| n.children)
                .map(|[a, b]| {
                    let parent = nodes[a].parent.unwrap();
                    nodes[a].area + nodes[b].area <= (1.0 - options.gain) * nodes[parent].area
                })
                .collect();
            assert!(!fits.is_empty());
            assert!(fits.iter().all(|&fit| fit != l.below_gain), "{l:?}");
        }
        check_partition(&mesh, &options);
    }
}

#[test]
fn asked_levels_change_nothing_where_the_gain_reaches_them() {
    // The star splits to depth 3 under a gain of -0.5: asking for its 4 levels keeps the tree.
    let o = HierarchyOptions {
        gain: -0.5,
        max_depth: 3,
        split: SplitRule::Features,
        ..HierarchyOptions::default()
    };
    let asked = HierarchyOptions {
        levels: Some(4),
        ..o
    };
    let (a, b) = (
        Hierarchy::build(&star(), &o).unwrap(),
        Hierarchy::build(&star(), &asked).unwrap(),
    );
    assert_eq!(a.nodes(), b.nodes());
    assert!(b.levels(4).iter().all(|l| !l.below_gain));
    // The L wall's one split fits the gain; a third level is made below it.
    let h = Hierarchy::build(&l_wall(), &asking(3)).unwrap();
    let marks: Vec<bool> = h.levels(3).iter().map(|l| l.below_gain).collect();
    assert_eq!(marks, [false, false, true]);
    let split = h.nodes()[0].split.unwrap();
    assert_eq!((split.direction, split.offset), (0, 3.0));
}

#[test]
fn max_depth_bounds_the_levels_asked_for() {
    let o = HierarchyOptions {
        max_depth: 2,
        levels: Some(6),
        ..HierarchyOptions::default()
    };
    let h = Hierarchy::build(&torus(), &o).unwrap();
    assert_eq!((h.depth(), h.stop()), (2, Stop::MaxDepth));
    assert_eq!(h.levels(6).len(), 3);
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(16))]

    /// Random star-shaped prisms: the partition and the nesting hold.
    #[test]
    fn random_prisms_partition_and_nest(
        radii in prop::collection::vec(0.5f64..4.0, 5..12),
        height in 0.5f64..3.0,
        depth in 1usize..4,
        rule in 0usize..3,
    ) {
        let n = radii.len();
        let outline: Vec<(f64, f64)> = radii
            .iter()
            .enumerate()
            .map(|(i, r)| {
                let a = std::f64::consts::TAU * i as f64 / n as f64;
                (r * a.cos(), r * a.sin())
            })
            .collect();
        let polygon = geo::Polygon::new(geo::LineString::from(outline), vec![]);
        let mesh = kepler::solids::prism(&polygon, height).unwrap();
        let split = [SplitRule::Thickest, SplitRule::Bisectors, SplitRule::Features][rule];
        check_partition(&mesh, &deep(depth, split));
        check_tree(&mesh, &deep(depth, split));
    }
}
