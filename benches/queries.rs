//! Point queries on a closed torus of 69,600 triangles: batch INCLUDE of 1,000,000 random
//! points in its CBOX (target: at least 5 million points per second on 2 cores, after
//! building; building under 50 ms) against parry3d's point containment on the same mesh and
//! points (single-threaded and rayon, like for like); the builds; and single VISP queries from
//! three views, with the index and without preprocessing.
//!
//!   cargo bench --bench queries

use std::hint::black_box;
use std::time::{Duration, Instant};

use criterion::{BatchSize, Criterion, SamplingMode, Throughput, criterion_group, criterion_main};
use kepler::geometry::{Point3, Vector3};
use kepler::mesh::Mesh;
use kepler::queries::include::{IncludeIndex, Inclusion};
use kepler::queries::projection_grid::ProjectionGrid;
use kepler::queries::visp::{Visibility, VisibilityIndex, visp};
use kepler::random::SplitMix64;
use kepler::scene::{ObjectId, Scene};
use kepler::views::View;
use parry3d::query::PointQuery;
use parry3d::shape::{TriMesh, TriMeshFlags};
use rayon::prelude::*;

/// Points in each batch.
const BATCH: usize = 1_000_000;

/// Points the single-query benchmarks cycle through (the first of the batch).
const SINGLES: usize = 10_000;

/// The torus: R = 2, r = 0.7, 240 × 145 quads, 69,600 triangles.
fn torus() -> Mesh {
    let mesh = kepler::solids::torus(2.0, 0.7, 240, 145).expect("valid torus");
    assert_eq!(mesh.triangles().len(), 69_600);
    mesh
}

/// A scene holding only `mesh`, and its id.
fn scene_of(mesh: Mesh) -> (Scene, ObjectId) {
    let mut scene = Scene::new();
    let id = scene.add_mesh(None, "torus", mesh).expect("valid scene");
    (scene, id)
}

/// `n` uniformly random points in the CBOX of `id`, from a fixed seed.
fn points_in_cbox(scene: &Scene, id: ObjectId, n: usize) -> Vec<Point3> {
    let b = scene.cbox(id);
    let mut rng = SplitMix64(0x6b65_706c_6572);
    (0..n)
        .map(|_| {
            Point3::from(std::array::from_fn(|k| {
                b.min[k] + (b.max[k] - b.min[k]) * rng.unit()
            }))
        })
        .collect()
}

/// The vertices of `mesh` as parry3d's (f32) vectors.
fn parry_vertices(mesh: &Mesh) -> Vec<parry3d::math::Vector> {
    mesh.vertices().iter().map(parry_point).collect()
}

fn parry_point(p: &Point3) -> parry3d::math::Vector {
    parry3d::math::Vector::new(p.x as f32, p.y as f32, p.z as f32)
}

/// parry3d's mesh with the pseudo-normals its `contains_point` needs to tell inside from
/// outside (without them it tests only whether a point is on a triangle). The vertices are
/// already unique, so merging duplicates would change nothing.
fn parry_mesh(vertices: Vec<parry3d::math::Vector>, triangles: Vec<[u32; 3]>) -> TriMesh {
    TriMesh::with_flags(vertices, triangles, TriMeshFlags::ORIENTED).expect("valid trimesh")
}

fn include_batch(c: &mut Criterion) {
    let mesh = torus();
    let parry = parry_mesh(parry_vertices(&mesh), mesh.triangles().to_vec());
    let (scene, id) = scene_of(mesh);
    let points = points_in_cbox(&scene, id, BATCH);
    let parry_points: Vec<_> = points.iter().map(parry_point).collect();
    let index = IncludeIndex::whole_scene(&scene).expect("closed mesh");

    let (answers, counters) = index.include_all(&points);
    let inside = answers.iter().filter(|&&a| a == Inclusion::In).count();
    eprintln!(
        "include_batch: {BATCH} points in the CBOX, {inside} IN; decided by {:?}",
        counters.by_stage()
    );
    let (mut compared, mut disagree) = (0, 0);
    for (k, &answer) in answers.iter().take(10_000).enumerate() {
        if answer != Inclusion::On {
            compared += 1;
            disagree += usize::from(
                (answer == Inclusion::In) != parry.contains_local_point(parry_points[k]),
            );
        }
    }
    if disagree > 0 {
        eprintln!(
            "include_batch: parry3d disagrees with kepler on {disagree} of {compared} points"
        );
    } else {
        eprintln!(
            "include_batch: parry3d agrees with kepler on all {compared} points (ON excluded)"
        );
    }

    let mut g = c.benchmark_group("include_batch");
    g.sample_size(10)
        .measurement_time(Duration::from_secs(5))
        .sampling_mode(SamplingMode::Flat)
        .throughput(Throughput::Elements(BATCH as u64));
    g.bench_function("kepler_rayon", |b| {
        b.iter(|| black_box(index.include_all(black_box(&points))))
    });
    g.bench_function("kepler_single", |b| {
        b.iter(|| {
            black_box(&points)
                .iter()
                .map(|p| index.include(p).0)
                .collect::<Vec<_>>()
        })
    });
    g.bench_function("parry3d_rayon", |b| {
        b.iter(|| {
            black_box(&parry_points)
                .par_iter()
                .map(|&p| parry.contains_local_point(p))
                .collect::<Vec<_>>()
        })
    });
    g.bench_function("parry3d_single", |b| {
        b.iter(|| {
            black_box(&parry_points)
                .iter()
                .map(|&p| parry.contains_local_point(p))
                .collect::<Vec<_>>()
        })
    });
    g.finish();
}

fn include_build(c: &mut Criterion) {
    let mesh = torus();
    let vertices = parry_vertices(&mesh);
    let triangles = mesh.triangles().to_vec();
    let fresh = || scene_of(mesh.clone());

    let mut g = c.benchmark_group("include_build");
    g.sample_size(10).measurement_time(Duration::from_secs(6));
    g.throughput(Throughput::Elements(triangles.len() as u64));
    // A fresh scene each time: its bounds are cached, and the index computes them.
    g.bench_function("kepler_bounds_and_grid", |b| {
        b.iter_batched(
            fresh,
            |(scene, _)| {
                black_box(IncludeIndex::whole_scene(&scene).expect("closed mesh"));
                scene
            },
            BatchSize::PerIteration,
        )
    });
    g.bench_function("kepler_bounds_only", |b| {
        b.iter_batched(
            fresh,
            |(scene, id)| {
                black_box((scene.cbox(id), scene.inbox(id), scene.tribox(id)));
                scene
            },
            BatchSize::PerIteration,
        )
    });
    g.bench_function("kepler_grid_only", |b| {
        b.iter(|| black_box(ProjectionGrid::new(black_box(&mesh))))
    });
    g.bench_function("parry3d_trimesh_oriented", |b| {
        b.iter_batched(
            || (vertices.clone(), triangles.clone()),
            |(v, t)| parry_mesh(v, t),
            BatchSize::PerIteration,
        )
    });
    g.finish();
}

/// The median and 90th percentile of per-query times, in microseconds.
fn percentiles(mut times: Vec<Duration>) -> (f64, f64) {
    times.sort();
    let at = |q: f64| times[((times.len() - 1) as f64 * q) as usize].as_secs_f64() * 1e6;
    (at(0.5), at(0.9))
}

fn visp_single(c: &mut Criterion) {
    let (scene, id) = scene_of(torus());
    let points = points_in_cbox(&scene, id, SINGLES);
    let views = [
        ("standard", View::standard()),
        (
            "orthographic_-1-1-1",
            View::orthographic(Vector3::new(-1.0, -1.0, -1.0), Vector3::z()).expect("valid view"),
        ),
        (
            "perspective_8-65",
            View::perspective(
                Point3::new(8.0, -6.0, 5.0),
                Point3::origin(),
                Vector3::z(),
                40.0,
            )
            .expect("valid view"),
        ),
    ];

    let mut g = c.benchmark_group("visp_single");
    g.sample_size(50).measurement_time(Duration::from_secs(3));
    for (name, view) in &views {
        let index = VisibilityIndex::whole_scene(&scene, view.clone());
        let (answers, counters) = index.visp_all(&points);
        let hidden = answers.iter().filter(|&&a| a == Visibility::Hidden).count();
        let times: Vec<Duration> = points
            .iter()
            .map(|p| {
                let t = Instant::now();
                black_box(index.visp(black_box(p)));
                t.elapsed()
            })
            .collect();
        let (median, p90) = percentiles(times);
        eprintln!(
            "visp_single/index_{name}: {SINGLES} points, {hidden} HIDDEN, decided by {:?}; \
             per query (timed one by one): median {median:.2} µs, p90 {p90:.2} µs",
            counters.by_stage()
        );
        let mut i = 0;
        g.bench_function(format!("index_{name}"), |b| {
            b.iter(|| {
                i = (i + 1) % SINGLES;
                black_box(index.visp(black_box(&points[i])))
            })
        });
    }
    g.finish();

    // Without preprocessing every query that reaches the faces tests all 69,600 triangles.
    let mut g = c.benchmark_group("visp_single");
    g.sample_size(10).measurement_time(Duration::from_secs(5));
    for (name, view) in &views {
        let sample = 300;
        let times: Vec<Duration> = points[..sample]
            .iter()
            .map(|p| {
                let t = Instant::now();
                black_box(visp(&scene, id, view, black_box(p)));
                t.elapsed()
            })
            .collect();
        let (median, p90) = percentiles(times);
        eprintln!(
            "visp_single/brute_{name}: per query over {sample} points (timed one by one): \
             median {median:.1} µs, p90 {p90:.1} µs"
        );
        let mut i = 0;
        g.bench_function(format!("brute_{name}"), |b| {
            b.iter(|| {
                i = (i + 1) % SINGLES;
                black_box(visp(&scene, id, view, black_box(&points[i])))
            })
        });
    }
    g.finish();
}

criterion_group!(benches, include_batch, include_build, visp_single);
criterion_main!(benches);
