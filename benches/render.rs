//! End-to-end hidden-line drawings (`kepler::hidden::draw`, everything from edge classes to
//! chained polylines; not file output) of a scan-like closed mesh of 69,600 triangles from
//! four views (one from an eye inside the torus's hole, clipped to its frustum), with `--edges feature` (target: under 0.3 s each) and `--edges all` (under
//! 0.5 s), and of a mesh of 1,000,000 triangles with `--edges feature` (under 3 s).
//!
//! The meshes are tori whose surface is displaced by smooth waves and a little seeded noise,
//! then triangulated: silhouettes wander over the surface as on a scanned object, and nothing
//! about them is aligned with the axes.
//!
//! The group "render crowds" times the cases of issue 16 that once grew with the square of
//! their size: a fan, an array of separate objects, stacked copies, a flat mesh edge-on.
//!
//! The group "render tiles" times the metropolis whole and in tiles (issue 17).
//!
//!   cargo bench --bench render
//!   cargo bench --bench render -- crowds
//!   cargo bench --bench render -- tiles

use std::hint::black_box;
use std::time::Duration;

use criterion::{Criterion, SamplingMode, Throughput, criterion_group, criterion_main};
use kepler::geometry::{Point3, Vector3};
use kepler::hidden::{EdgeSelection, Options, draw, tiles};
use kepler::mesh::Mesh;
use kepler::random::SplitMix64;
use kepler::scene::Scene;
use kepler::views::View;

/// A torus of `segments × sides` quads (twice as many triangles), major radius 3 and minor
/// radius 1, displaced radially by waves of ±15% and seeded noise of ±0.1%.
fn scanlike(segments: u32, sides: u32) -> Mesh {
    let torus = kepler::solids::torus(3.0, 1.0, segments, sides).expect("valid torus");
    let mut rng = SplitMix64(0x9e37_79b9_7f4a_7c15);
    let vertices: Vec<Point3> = torus
        .vertices()
        .iter()
        .map(|p| {
            let noise = rng.unit() - 0.5;
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

/// The crowded cases of issue 16: 10,000 edges through one point (two cones of 10,000 slivers
/// base to base), an array of 10,000 separate cubes seen obliquely, 1,000 exact copies of a
/// cube in one place, and a flat mesh of 100,352 coplanar triangles seen obliquely and edge-on.
fn render_crowds(c: &mut Criterion) {
    let perspective = View::perspective(
        Point3::new(3.0, -4.0, 2.0),
        Point3::origin(),
        Vector3::z(),
        40.0,
    )
    .expect("view");
    let mut group = c.benchmark_group("render crowds");
    group
        .sample_size(10)
        .sampling_mode(SamplingMode::Flat)
        .measurement_time(Duration::from_secs(10));
    let fan = scene_of(kepler::solids::uv_sphere(1.0, 10_000, 2).expect("fan"));
    group.throughput(Throughput::Elements(20_000));
    group.bench_function("fan of 10,000 edges", |b| {
        b.iter(|| draw(black_box(&fan), &perspective, &Options::default()).expect("drawing"))
    });
    let cube = kepler::solids::cube(1.0).expect("cube");
    let mut array = Scene::new();
    let mut stacked = Scene::new();
    for i in 0..100 {
        for j in 0..100 {
            let at = nalgebra::Matrix4::new_translation(&Vector3::new(
                2.0 * i as f64,
                2.0 * j as f64,
                0.0,
            ));
            let placed = cube.transformed(&at).expect("cube");
            array
                .add_mesh(None, format!("c{i}-{j}"), placed)
                .expect("scene");
        }
    }
    for k in 0..1000 {
        stacked
            .add_mesh(None, format!("c{k}"), cube.clone())
            .expect("scene");
    }
    let oblique = View::perspective(
        Point3::new(-70.0, -100.0, 80.0),
        Point3::new(100.0, 100.0, 0.0),
        Vector3::z(),
        45.0,
    )
    .expect("view");
    group.throughput(Throughput::Elements(10_000));
    group.bench_function("array of 10,000 cubes", |b| {
        b.iter(|| draw(black_box(&array), &oblique, &Options::default()).expect("drawing"))
    });
    group.throughput(Throughput::Elements(1_000));
    group.bench_function("1,000 stacked copies", |b| {
        b.iter(|| draw(black_box(&stacked), &perspective, &Options::default()).expect("drawing"))
    });
    let n = 224;
    let vertices: Vec<Point3> = (0..=n)
        .flat_map(|i| {
            (0..=n).map(move |j| Point3::new(i as f64 / n as f64, j as f64 / n as f64, 0.0))
        })
        .collect();
    let faces: Vec<Vec<u32>> = (0..n)
        .flat_map(|i| {
            (0..n).flat_map(move |j| {
                let a = (i * (n + 1) + j) as u32;
                let (b, c, d) = (a + n as u32 + 1, a + n as u32 + 2, a + 1);
                [vec![a, b, c], vec![a, c, d]]
            })
        })
        .collect();
    let flat = scene_of(Mesh::from_polygons(vertices, faces).expect("flat mesh"));
    group.throughput(Throughput::Elements(2 * (n * n) as u64));
    for (name, direction) in [
        ("oblique", Vector3::new(1.0, 2.0, -3.0)),
        ("edge-on", Vector3::new(1.0, 2.0, 0.0)),
    ] {
        let view = View::orthographic(direction, Vector3::z()).expect("view");
        group.bench_function(format!("flat 100,352 triangles {name}"), |b| {
            b.iter(|| draw(black_box(&flat), &view, &Options::default()).expect("drawing"))
        });
    }
    group.finish();
}

/// The bundled metropolis (22,790 objects) drawn whole, and in 2×2 and 8×8 tiles drawn one
/// after another in this process and stitched: what tiling costs on one machine (each tile
/// draws only the objects that reach it, but objects that straddle borders are drawn in
/// every tile they reach). The speed-up of tiles on Dask workers is measured by
/// `scripts/tiles.py`.
fn render_tiles(c: &mut Criterion) {
    let scene = kepler::scene::file::load(std::path::Path::new("scenes/metropolis.toml"))
        .expect("the bundled metropolis");
    let view = kepler::views::ViewOptions::default()
        .resolve(scene.camera())
        .expect("view");
    let view = view.with_aspect(1.5).expect("view");
    let options = Options::default();
    let mut group = c.benchmark_group("render tiles");
    group
        .sample_size(10)
        .sampling_mode(SamplingMode::Flat)
        .measurement_time(Duration::from_secs(20));
    group.throughput(Throughput::Elements(22_790));
    group.bench_function("metropolis whole", |b| {
        b.iter(|| draw(black_box(&scene), &view, &options).expect("drawing"))
    });
    for grid in [[2, 2], [8, 8]] {
        let windows = tiles::tile_windows(&scene, &view, grid).expect("windows");
        group.bench_function(format!("metropolis {}×{} tiles", grid[0], grid[1]), |b| {
            b.iter(|| {
                let parts: Vec<_> = windows
                    .iter()
                    .map(|w| tiles::draw_tile(black_box(&scene), &view, &options, w))
                    .collect::<Result<_, _>>()
                    .expect("tiles");
                tiles::stitch(&parts, &options).expect("stitched")
            })
        });
    }
    group.finish();
}

criterion_group!(benches, render_70k, render_1m, render_crowds, render_tiles);
criterion_main!(benches);
