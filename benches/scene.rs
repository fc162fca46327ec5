//! Loading and bounding scenes: the 100,000-face metropolis (target: load and bound in
//! under 0.5 s) and the INBOX constructions on single solids.
//!
//!   cargo bench --bench scene

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use kepler::bounds::inbox;
use kepler::scene::file;
use kepler::solids::{self, Polyhedron};
use std::hint::black_box;
use std::time::Duration;

fn metropolis(c: &mut Criterion) {
    let path = std::path::Path::new("scenes/metropolis.toml");
    let faces = {
        let s = file::load(path).expect("bundled scene");
        s.roots().iter().map(|&r| s.face_count(r)).sum::<usize>()
    };
    let mut g = c.benchmark_group("metropolis");
    g.sample_size(10).measurement_time(Duration::from_secs(8));
    g.throughput(Throughput::Elements(faces as u64));
    g.bench_function("load", |b| {
        b.iter(|| black_box(file::load(path).expect("bundled scene")))
    });
    g.bench_function("load_and_bound", |b| {
        b.iter(|| {
            let s = file::load(path).expect("bundled scene");
            s.compute_bounds();
            s
        })
    });
    g.finish();
}

fn inboxes(c: &mut Criterion) {
    let mut g = c.benchmark_group("inbox");
    let cases = [
        ("cube", solids::cube(1.0).expect("valid")),
        (
            "truncated-octahedron",
            Polyhedron::TruncatedOctahedron.mesh(1.0).expect("valid"),
        ),
        (
            "snub-dodecahedron",
            Polyhedron::SnubDodecahedron.mesh(1.0).expect("valid"),
        ),
        (
            "sphere-32x16",
            solids::uv_sphere(1.0, 32, 16).expect("valid"),
        ),
        (
            "torus-48x24",
            solids::torus(3.0, 1.0, 48, 24).expect("valid"),
        ),
    ];
    for (name, mesh) in &cases {
        g.throughput(Throughput::Elements(mesh.faces().len() as u64));
        g.bench_function(*name, |b| b.iter(|| black_box(inbox(mesh))));
    }
    g.finish();
}

criterion_group!(benches, metropolis, inboxes);
criterion_main!(benches);
