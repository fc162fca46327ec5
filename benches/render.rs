//! End-to-end hidden-line drawings (`kepler::hidden::draw`, everything from edge classes to
//! chained polylines; not file output) of a scan-like closed mesh of 69,600 triangles from
//! four views (one from an eye inside the torus's hole, clipped to its frustum), with `--edges feature` (target: under 0.3 s each) and `--edges all` (under
//! 0.5 s), and of a mesh of 1,000,000 triangles with `--edges feature` (under 3 s).
//!
//! The meshes are tori whose surface is displaced by smooth waves and a little seeded noise,
//! then triangulated: silhouettes wander over the surface as on a scanned object, and nothing
//! about them is aligned with the axes.
//!
//!   cargo bench --bench render

use std::hint::black_box;
use std::time::Duration;

use criterion::{Criterion, SamplingMode, Throughput, criterion_group, criterion_main};
use kepler::geometry::{Point3, Vector3};
use kepler::hidden::{EdgeSelection, Options, draw};
use kepler::mesh::Mesh;
use kepler::scene::Scene;
use kepler::views::View;

/// A torus of `segments × sides` quads (twice as many triangles), major radius 3 and minor
/// radius 1, displaced radially by waves of ±15% and seeded noise of ±0.1%.
fn scanlike(segments: u32, sides: u32) -> Mesh {
    let torus = kepler::solids::torus(3.0, 1.0, segments, sides).expect("valid torus");
    let mut state = 0x9e37_79b9_7f4a_7c15u64;
    let vertices: Vec<Point3> = torus
        .vertices()
        .iter()
        .map(|p| {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            let noise = (state >> 11) as f64 / (1u64 << 53) as f64 - 0.5;
            let around = p.y.atan2(p.x);
            let ring = (p.x * p.x + p.y * p.y).sqrt() - 3.0;
            let across = p.z.atan2(ring);
            let centre = Point3::new(3.0 * around.cos(), 3.0 * around.sin(), 0.0);
            let k = 1.0 + 0.15 * (5.0 * around).sin() * (3.0 * across).sin() + 0.002 * noise;
            centre + (p - centre) * k
        })
        .collect();
    let faces = torus.triangles().iter().map(|t| t.to_vec()).collect();
    Mesh::from_polygons(vertices, faces).expect("valid mesh")
}

/// The four views: two orthographic, one perspective from outside, and one from an eye in the
/// torus's hole, which clips to its frustum (the torus surrounds the eye).
fn views() -> [(&'static str, View); 4] {
    [
        (
            "iso",
            View::orthographic(Vector3::new(-1.0, -2.0, -3.0), Vector3::z()).expect("view"),
        ),
        (
            "side",
            View::orthographic(Vector3::new(0.3, 1.0, -0.2), Vector3::z()).expect("view"),
        ),
        (
            "perspective",
            View::perspective(
                Point3::new(9.0, -12.0, 7.0),
                Point3::origin(),
                Vector3::z(),
                40.0,
            )
            .expect("view"),
        ),
        (
            "inside",
            View::perspective(
                Point3::new(0.0, 0.0, 0.25),
                Point3::new(3.0, 1.0, 0.0),
                Vector3::z(),
                70.0,
            )
            .expect("view"),
        ),
    ]
}

fn scene_of(mesh: Mesh) -> Scene {
    let mut scene = Scene::new();
    scene.add_mesh(None, "scan", mesh).expect("valid scene");
    scene
}

fn render_70k(c: &mut Criterion) {
    let mesh = scanlike(240, 145);
    let triangles = mesh.triangles().len() as u64;
    assert_eq!(triangles, 69_600);
    let scene = scene_of(mesh);
    let mut group = c.benchmark_group("render 69,600 triangles");
    group
        .sample_size(20)
        .measurement_time(Duration::from_secs(8));
    group.throughput(Throughput::Elements(triangles));
    for (edges, name) in [
        (EdgeSelection::Feature, "feature"),
        (EdgeSelection::All, "all"),
    ] {
        let options = Options {
            edges,
            ..Options::default()
        };
        for (view_name, view) in views() {
            group.bench_function(format!("{name} {view_name}"), |b| {
                b.iter(|| draw(black_box(&scene), &view, &options).expect("drawing"))
            });
        }
    }
    group.finish();
}

fn render_1m(c: &mut Criterion) {
    let mesh = scanlike(1000, 500);
    let triangles = mesh.triangles().len() as u64;
    assert_eq!(triangles, 1_000_000);
    let scene = scene_of(mesh);
    let mut group = c.benchmark_group("render 1,000,000 triangles");
    group
        .sample_size(10)
        .sampling_mode(SamplingMode::Flat)
        .measurement_time(Duration::from_secs(20));
    group.throughput(Throughput::Elements(triangles));
    let (view_name, view) = &views()[0];
    group.bench_function(format!("feature {view_name}"), |b| {
        b.iter(|| draw(black_box(&scene), view, &Options::default()).expect("drawing"))
    });
    group.finish();
}

criterion_group!(benches, render_70k, render_1m);
criterion_main!(benches);
