//! Franklin's segment-intersection experiment (`kepler segx`): N random segments of length L in
//! the unit square (seed 1), every pair that meets. Franklin reports 50,000 edges of length
//! 0.01 in 364 s on a Prime 500; targets here: that case under 10 ms, and 1,000,000 edges of
//! length 0.001 under 0.3 s. On the same inputs: kepler's uniform grid (rayon, one thread, and
//! with the meeting points), geo's sweep (`geo::algorithm::sweep::Intersections`) and a
//! bulk-loaded rstar R-tree of the segments' boxes (one thread and rayon), each pair tested
//! exactly like the grid does.
//!
//!   cargo bench --bench segx

use std::hint::black_box;
use std::time::{Duration, Instant};

use criterion::{Criterion, SamplingMode, Throughput, criterion_group, criterion_main};
use geo::Line;
use geo::algorithm::sweep::Intersections;
use kepler::geometry::polygon::segments_meet;
use kepler::grid::{SegmentGrid, intersecting_pairs, intersections, random_segments};
use rayon::prelude::*;
use rstar::primitives::{GeomWithData, Rectangle};
use rstar::{AABB, RTree};

/// The seed of every input.
const SEED: u64 = 1;

/// A segment's bounding box in the R-tree, with the segment's index.
type Boxed = GeomWithData<Rectangle<[f64; 2]>, usize>;

fn ends(s: &Line<f64>) -> ([f64; 2], [f64; 2]) {
    ([s.start.x, s.start.y], [s.end.x, s.end.y])
}

fn envelope(s: &Line<f64>) -> AABB<[f64; 2]> {
    let (a, b) = ends(s);
    AABB::from_corners(a, b)
}

/// The bulk-loaded R-tree of the segments' boxes.
fn rtree(segments: &[Line<f64>]) -> RTree<Boxed> {
    let boxes = segments
        .iter()
        .enumerate()
        .map(|(i, s)| Boxed::new(Rectangle::from_aabb(envelope(s)), i))
        .collect();
    RTree::bulk_load(boxes)
}

/// The pairs `(i, j)`, `i < j`, with segment `i` that meet: the R-tree's candidates for `i`'s
/// box, tested exactly.
fn rtree_pairs_of<'a>(
    tree: &'a RTree<Boxed>,
    segments: &'a [Line<f64>],
    i: usize,
) -> impl Iterator<Item = (usize, usize)> + 'a {
    let (a, b) = ends(&segments[i]);
    tree.locate_in_envelope_intersecting(&envelope(&segments[i]))
        .filter_map(move |c| {
            let j = c.data;
            let (p, q) = ends(&segments[j]);
            (j > i && segments_meet(a, b, p, q)).then_some((i, j))
        })
}

/// The R-tree's pairs, one thread: bulk load, then a query per segment.
fn rstar_single(segments: &[Line<f64>]) -> Vec<(usize, usize)> {
    let tree = rtree(segments);
    (0..segments.len())
        .flat_map(|i| rtree_pairs_of(&tree, segments, i))
        .collect()
}

/// The R-tree's pairs: bulk load (rstar's is sequential), then the queries in parallel.
fn rstar_rayon(segments: &[Line<f64>]) -> Vec<(usize, usize)> {
    let tree = rtree(segments);
    (0..segments.len())
        .into_par_iter()
        .flat_map_iter(|i| rtree_pairs_of(&tree, segments, i))
        .collect()
}

/// The number of intersections geo's sweep yields (one per pair that meets).
fn geo_sweep(segments: &[Line<f64>]) -> usize {
    Intersections::from_iter(segments).count()
}

/// Runs `f` once, returning its result and how long it took.
fn timed<T>(f: impl FnOnce() -> T) -> (T, Duration) {
    let t = Instant::now();
    let out = f();
    (out, t.elapsed())
}

/// Measurement times (ten flat samples each): the grid's variants, rstar's and geo's sweep's.
struct Times {
    grid: Duration,
    rstar: Duration,
    geo: Duration,
}

fn segx_case(c: &mut Criterion, name: &str, n: usize, len: f64, times: Times) {
    let segments = random_segments(n, len, SEED);
    let single = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .expect("one-thread pool");

    // Setup: every method finds the same pairs.
    let grid = SegmentGrid::new(&segments);
    let [nx, ny] = grid.shape();
    let (pairs, t_grid) = timed(|| intersecting_pairs(&segments));
    let k = pairs.len();
    eprintln!(
        "{name}: N = {n}, L = {len}, seed {SEED}: K = {k} intersecting pairs; grid {nx} × {ny} \
         cells, {:.3} cells per segment (first run {:.2} ms)",
        grid.cells_per_segment(),
        t_grid.as_secs_f64() * 1e3
    );
    assert_eq!(grid.pairs(), pairs, "{name}: SegmentGrid::pairs");
    assert_eq!(
        single.install(|| intersecting_pairs(&segments)),
        pairs,
        "{name}: one-thread grid"
    );
    let with_points = intersections(&segments);
    assert_eq!(with_points.len(), k, "{name}: intersections");
    assert!(
        with_points
            .iter()
            .zip(&pairs)
            .all(|(&(i, j, _), &p)| (i, j) == p),
        "{name}: intersections' pairs"
    );
    let mut from_tree = rstar_single(&segments);
    from_tree.sort_unstable();
    assert_eq!(from_tree, pairs, "{name}: rstar");
    let mut from_tree = rstar_rayon(&segments);
    from_tree.sort_unstable();
    assert_eq!(from_tree, pairs, "{name}: rstar rayon");
    let (swept, t_sweep) = timed(|| geo_sweep(&segments));
    if swept == k {
        eprintln!(
            "{name}: geo's sweep yields {swept} intersections, one per pair (first run {:.2} s)",
            t_sweep.as_secs_f64()
        );
    } else {
        eprintln!(
            "{name}: geo's sweep yields {swept} intersections, kepler finds {k} pairs \
             (difference {})",
            swept as i64 - k as i64
        );
    }

    let mut g = c.benchmark_group(name);
    g.sample_size(10)
        .warm_up_time(Duration::from_secs(1))
        .measurement_time(times.grid)
        .sampling_mode(SamplingMode::Flat)
        .throughput(Throughput::Elements(n as u64));
    g.bench_function("kepler_grid", |b| {
        b.iter(|| black_box(intersecting_pairs(black_box(&segments))))
    });
    g.bench_function("kepler_grid_single", |b| {
        b.iter(|| single.install(|| black_box(intersecting_pairs(black_box(&segments)))))
    });
    g.bench_function("kepler_grid_with_points", |b| {
        b.iter(|| black_box(intersections(black_box(&segments))))
    });
    g.measurement_time(times.rstar);
    g.bench_function("rstar", |b| {
        b.iter(|| black_box(rstar_single(black_box(&segments))))
    });
    g.bench_function("rstar_rayon", |b| {
        b.iter(|| black_box(rstar_rayon(black_box(&segments))))
    });
    g.measurement_time(times.geo);
    g.bench_function("geo_sweep", |b| {
        b.iter(|| black_box(geo_sweep(black_box(&segments))))
    });
    g.finish();
}

fn segx_50k(c: &mut Criterion) {
    let times = Times {
        grid: Duration::from_secs(3),
        rstar: Duration::from_secs(3),
        geo: Duration::from_secs(4),
    };
    segx_case(c, "segx_50k_0.01", 50_000, 0.01, times);
}

fn segx_1m(c: &mut Criterion) {
    let times = Times {
        grid: Duration::from_secs(5),
        rstar: Duration::from_secs(20),
        geo: Duration::from_secs(70),
    };
    segx_case(c, "segx_1m_0.001", 1_000_000, 0.001, times);
}

criterion_group!(benches, segx_50k, segx_1m);
criterion_main!(benches);
