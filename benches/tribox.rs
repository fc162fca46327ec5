//! Tribox benchmarks: the boundary from 18 bounds (the paper's corner classification, raw and
//! cleaned) and the bounds of 1,000,000 points (sequential and rayon).

use std::hint::black_box;

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use kepler::bounds::tribox::TriboxBounds;
use kepler::geometry::Point3;

/// A xorshift generator (no dependency needed for benchmark data).
struct Rng(u64);

impl Rng {
    fn unit(&mut self) -> f64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }

    /// A point in the ball of radius 1 around `c` (rejection sampling).
    fn in_ball(&mut self, c: [f64; 3]) -> Point3 {
        loop {
            let v = [0; 3].map(|_| 2.0 * self.unit() - 1.0);
            if v.iter().map(|x| x * x).sum::<f64>() <= 1.0 {
                return Point3::new(c[0] + v[0], c[1] + v[1], c[2] + v[2]);
            }
        }
    }
}

fn boundary(c: &mut Criterion) {
    // 64 generic clouds: 200 points in a randomly placed ball (every corner in case 1), or 6
    // points in a unit cube (all four cases occur).
    let mut rng = Rng(0x2545_f491_4f6c_dd1d);
    let bounds: Vec<TriboxBounds> = (0..64)
        .map(|k| {
            let pts: Vec<Point3> = if k % 2 == 0 {
                let centre = [0; 3].map(|_| 10.0 * rng.unit() - 5.0);
                (0..200).map(|_| rng.in_ball(centre)).collect()
            } else {
                (0..6)
                    .map(|_| Point3::new(rng.unit(), rng.unit(), rng.unit()))
                    .collect()
            };
            TriboxBounds::from_points(&pts)
        })
        .collect();
    let mut g = c.benchmark_group("tribox_boundary");
    let mut i = 0;
    g.bench_function("raw", |b| {
        b.iter(|| {
            i = (i + 1) % bounds.len();
            let t = black_box(&bounds[i]).boundary();
            black_box(&t);
        })
    });
    g.bench_function("cleaned", |b| {
        b.iter(|| {
            i = (i + 1) % bounds.len();
            let t = black_box(&bounds[i]).boundary().cleaned();
            black_box(&t);
        })
    });
    g.finish();
}

fn bounds_1m(c: &mut Criterion) {
    const N: usize = 1_000_000;
    let mut rng = Rng(0x9e37_79b9_7f4a_7c15);
    let pts: Vec<Point3> = (0..N).map(|_| rng.in_ball([0.3, -0.2, 0.1])).collect();
    let mut g = c.benchmark_group("tribox_bounds_1m");
    g.throughput(Throughput::Elements(N as u64));
    g.sample_size(20);
    g.bench_function("sequential", |b| {
        b.iter(|| black_box(TriboxBounds::from_points(black_box(&pts))))
    });
    g.bench_function("rayon", |b| {
        b.iter(|| black_box(TriboxBounds::par_from_points(black_box(&pts))))
    });
    g.finish();
}

criterion_group!(benches, boundary, bounds_1m);
criterion_main!(benches);
