//! Hierarchical triboxes (Crosnier and Rossignac 1999, §4) on a closed torus of 69,600
//! triangles (`torus(2, 0.7, 240, 145)`, the `scenes/torus.toml` object) and on the L-shaped
//! wall of `scenes/solids.toml`: building the hierarchy to depth 3 with each split rule (the
//! paper's thickest-slab bisector, the nine bisectors, and bisectors plus planes through
//! vertices), against the single tribox of all vertices as the baseline; and the report of
//! the levels (dominated by the Hausdorff bounds). A negative gain (−0.5) makes every rule
//! split, so the rules do comparable work. Before measuring, prints each hierarchy's levels.
//! Throughput is in triangles.
//!
//!   cargo bench --bench triboxes

use std::hint::black_box;
use std::time::Duration;

use criterion::{BenchmarkId, Criterion, Throughput, criterion_group, criterion_main};
use geo::polygon;
use kepler::bounds::tribox::TriboxBounds;
use kepler::lab::tribox_hierarchy::{Hierarchy, HierarchyOptions, SplitRule};
use kepler::mesh::Mesh;

const RULES: [(&str, SplitRule); 3] = [
    ("thickest", SplitRule::Thickest),
    ("bisectors", SplitRule::Bisectors),
    ("features", SplitRule::Features),
];

fn options(split: SplitRule) -> HierarchyOptions {
    HierarchyOptions {
        gain: -0.5,
        max_depth: 3,
        split,
        ..HierarchyOptions::default()
    }
}

fn meshes() -> Vec<(&'static str, Mesh)> {
    let wall = polygon![(x: 0.0, y: 0.0), (x: 6.0, y: 0.0), (x: 6.0, y: 1.0),
        (x: 1.0, y: 1.0), (x: 1.0, y: 4.0), (x: 0.0, y: 4.0)];
    vec![
        (
            "torus-69600",
            kepler::solids::torus(2.0, 0.7, 240, 145).expect("a torus"),
        ),
        (
            "l-wall",
            kepler::solids::prism(&wall, 3.0).expect("a prism"),
        ),
    ]
}

fn build(c: &mut Criterion) {
    for (name, mesh) in meshes() {
        for (rule, split) in RULES {
            let h = Hierarchy::build(&mesh, &options(split)).expect("a solid");
            println!("{name} {rule}: {} nodes", h.nodes().len());
            for l in h.levels(4) {
                println!(
                    "  depth {} triboxes {:>2} faces {:>3} volume excess {:>7.2}% hausdorff {:.4}",
                    l.depth,
                    l.triboxes,
                    l.faces,
                    100.0 * l.volume_excess,
                    l.hausdorff
                );
            }
        }
        let mut g = c.benchmark_group(format!("triboxes/build/{name}"));
        g.sample_size(10).measurement_time(Duration::from_secs(6));
        g.throughput(Throughput::Elements(mesh.triangles().len() as u64));
        g.bench_function("one tribox", |b| {
            b.iter(|| TriboxBounds::from_points(black_box(mesh.vertices())))
        });
        for (rule, split) in RULES {
            g.bench_with_input(BenchmarkId::new("hierarchy", rule), &split, |b, &split| {
                b.iter(|| Hierarchy::build(black_box(&mesh), &options(split)))
            });
        }
        g.finish();
    }
}

fn levels(c: &mut Criterion) {
    for (name, mesh) in meshes() {
        let h = Hierarchy::build(&mesh, &options(SplitRule::Bisectors)).expect("a solid");
        let mut g = c.benchmark_group(format!("triboxes/levels/{name}"));
        g.sample_size(10).measurement_time(Duration::from_secs(5));
        g.throughput(Throughput::Elements(mesh.triangles().len() as u64));
        g.bench_function("4 levels", |b| b.iter(|| black_box(&h).levels(4)));
        g.finish();
    }
}

criterion_group!(benches, build, levels);
criterion_main!(benches);
