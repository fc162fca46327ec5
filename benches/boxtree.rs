//! BOXTREE (Barequet et al. 1996) per node shape: building the hierarchy over a closed torus
//! of 69,600 triangles (`torus(2, 0.7, 240, 145)`), shooting 10,000 random rays at it (one
//! core), and the complete collision search between the paper's concentric sphere pairs
//! (556, 1,996 and 9,996 facets). Before measuring, prints the sphere experiment (the paper's
//! Table 1 setting) beside the paper's counts, and each torus hierarchy's height, expected
//! random-plane cost and ray work.
//!
//!   cargo bench --bench boxtree

use std::hint::black_box;
use std::time::Duration;

use criterion::measurement::WallTime;
use criterion::{
    BenchmarkGroup, BenchmarkId, Criterion, Throughput, criterion_group, criterion_main,
};
use kepler::bounds::tribox::TriboxBounds;
use kepler::geometry::ray::Ray;
use kepler::geometry::{Aabb, Point3};
use kepler::lab::boxtree::pca::{PcaAll, PcaMax, PcaMin};
use kepler::lab::boxtree::spheres::{DEFAULT_GAP, PAPER_FACETS, paper_pie_slice_tests};
use kepler::lab::boxtree::{BoxTree, Merge, NodeShape, Shape, sphere_experiment, sphere_pair};
use kepler::mesh::Mesh;
use kepler::random::SplitMix64;

/// Rays per ray-shooting batch.
const RAYS: usize = 10_000;

/// The torus: R = 2, r = 0.7, 240 × 145 quads, 69,600 triangles.
fn torus() -> Mesh {
    let mesh = kepler::solids::torus(2.0, 0.7, 240, 145).expect("valid torus");
    assert_eq!(mesh.triangles().len(), 69_600);
    mesh
}

/// Rays from random points on the sphere of radius 6 towards random points of the torus's
/// box (most hit it, some pass through the hole or beside it).
fn rays() -> Vec<Ray> {
    let mut rng = SplitMix64(7);
    (0..RAYS)
        .map(|_| {
            let z = rng.range(-1.0, 1.0);
            let a = rng.range(0.0, std::f64::consts::TAU);
            let r = (1.0 - z * z).sqrt();
            let origin = Point3::new(6.0 * r * a.cos(), 6.0 * r * a.sin(), 6.0 * z);
            let target = Point3::new(
                rng.range(-2.7, 2.7),
                rng.range(-2.7, 2.7),
                rng.range(-0.7, 0.7),
            );
            Ray {
                origin,
                direction: target - origin,
            }
        })
        .collect()
}

/// Prints the sphere experiment for both merge rules, beside the paper's counts.
fn print_sphere_table() {
    println!(
        "\nSphere experiment: collision tests of a complete search, gap {DEFAULT_GAP}, seed 1 \
         (paper: Table 1 and its text; pie slices not built here)"
    );
    println!(
        "{:>6} {:>7} {:>8} | {:>8} {:>8} | {:>8} {:>9} {:>6}",
        "facets", "shape", "volume", "area", "paper", "tri tests", "pairs", "pie"
    );
    let volume = sphere_experiment(&PAPER_FACETS, DEFAULT_GAP, 1, Merge::Volume)
        .expect("valid sphere pairs");
    let area =
        sphere_experiment(&PAPER_FACETS, DEFAULT_GAP, 1, Merge::Area).expect("valid sphere pairs");
    for (v, a) in volume.iter().zip(&area) {
        let show = |x: Option<u64>| x.map_or("-".to_string(), |x| x.to_string());
        println!(
            "{:>6} {:>7} {:>8} | {:>8} {:>8} | {:>8} {:>9} {:>6}",
            v.facets,
            v.shape.name(),
            v.tests,
            a.tests,
            show(v.paper),
            v.triangle_tests,
            v.intersecting_pairs,
            if v.shape == Shape::Aabb {
                show(paper_pie_slice_tests(v.facets))
            } else {
                String::new()
            }
        );
    }
}

/// Prints a torus hierarchy's shape and the mean work of the benchmark's rays. Beside the
/// paper's random-plane cost (relative to the tree's own root) it prints the nodes' total
/// area over the mesh's CBOX area, the same for all shapes: the expected number of nodes cut
/// by a random plane that cuts the CBOX.
fn print_ray_work<S: NodeShape>(tree: &BoxTree<S>, mesh: &Mesh, rays: &[Ray]) {
    let (mut visited, mut met, mut stabbing, mut most, mut hits) = (0, 0, 0, 0, 0);
    for ray in rays {
        let shot = tree.first_hit(ray);
        visited += shot.visited;
        met += shot.met;
        hits += usize::from(shot.hit.is_some());
        let s = tree.stabbing(ray);
        stabbing += s;
        most = most.max(s);
    }
    let n = rays.len() as f64;
    let total: f64 = tree.nodes().iter().map(|v| v.measures().area).sum();
    println!(
        "{:>7}: height {:>2}, plane cost {:>5.1} (over the CBOX {:>6.1}), per ray: {:>5.1} \
         bounds tested, {:>5.1} met, stabbing {:>6.1} (max {:>4}); {hits} hits",
        S::SHAPE.name(),
        tree.height(),
        tree.plane_cost(),
        total / kepler::bounds::cbox(mesh).surface_area(),
        visited as f64 / n,
        met as f64 / n,
        stabbing as f64 / n,
        most,
    );
}

fn build_one<S: NodeShape>(g: &mut BenchmarkGroup<WallTime>, mesh: &Mesh) {
    g.bench_function(S::SHAPE.name(), |b| {
        b.iter(|| BoxTree::<S>::build(black_box(mesh), Merge::Area))
    });
}

fn build(c: &mut Criterion) {
    print_sphere_table();
    let mesh = torus();
    let mut g = c.benchmark_group("boxtree_build_69600");
    g.sample_size(10).measurement_time(Duration::from_secs(8));
    build_one::<Aabb>(&mut g, &mesh);
    build_one::<PcaAll>(&mut g, &mesh);
    build_one::<PcaMax>(&mut g, &mesh);
    build_one::<PcaMin>(&mut g, &mesh);
    build_one::<TriboxBounds>(&mut g, &mesh);
    g.finish();
}

fn shoot_one<S: NodeShape>(g: &mut BenchmarkGroup<WallTime>, mesh: &Mesh, rays: &[Ray]) {
    let tree = BoxTree::<S>::build(mesh, Merge::Area);
    print_ray_work(&tree, mesh, rays);
    g.bench_function(S::SHAPE.name(), |b| {
        b.iter(|| {
            rays.iter()
                .filter(|r| tree.first_hit(black_box(r)).hit.is_some())
                .count()
        })
    });
}

fn shoot(c: &mut Criterion) {
    let mesh = torus();
    let rays = rays();
    println!("\nTorus of 69,600 triangles, {RAYS} rays, merge by area:");
    let mut g = c.benchmark_group("boxtree_rays_10000");
    g.sample_size(10)
        .measurement_time(Duration::from_secs(5))
        .throughput(Throughput::Elements(RAYS as u64));
    shoot_one::<Aabb>(&mut g, &mesh, &rays);
    shoot_one::<PcaAll>(&mut g, &mesh, &rays);
    shoot_one::<PcaMax>(&mut g, &mesh, &rays);
    shoot_one::<PcaMin>(&mut g, &mesh, &rays);
    shoot_one::<TriboxBounds>(&mut g, &mesh, &rays);
    g.finish();
}

fn collide_one<S: NodeShape>(g: &mut BenchmarkGroup<WallTime>, facets: usize, a: &Mesh, b: &Mesh) {
    let (ta, tb) = (
        BoxTree::<S>::build(a, Merge::Volume),
        BoxTree::<S>::build(b, Merge::Volume),
    );
    g.bench_with_input(
        BenchmarkId::new(S::SHAPE.name(), facets),
        &facets,
        |bench, _| bench.iter(|| ta.intersecting_pairs(black_box(&tb)).1.tests),
    );
}

fn collide(c: &mut Criterion) {
    let mut g = c.benchmark_group("boxtree_spheres");
    g.sample_size(10).measurement_time(Duration::from_secs(3));
    for facets in PAPER_FACETS {
        let (a, b) =
            sphere_pair(facets, DEFAULT_GAP, 1 + facets as u64).expect("valid sphere pair");
        collide_one::<Aabb>(&mut g, facets, &a, &b);
        collide_one::<PcaAll>(&mut g, facets, &a, &b);
        collide_one::<PcaMax>(&mut g, facets, &a, &b);
        collide_one::<PcaMin>(&mut g, facets, &a, &b);
        collide_one::<TriboxBounds>(&mut g, facets, &a, &b);
    }
    g.finish();
}

criterion_group!(benches, build, shoot, collide);
criterion_main!(benches);
