//! Tribox benchmarks: the boundary from 18 bounds (the paper's corner classification, raw and
//! cleaned) and the bounds of 1,000,000 points (sequential and rayon).

use std::hint::black_box;

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use kepler::bounds::tribox::TriboxBounds;
use kepler::geometry::Point3;
use kepler::random::SplitMix64;

/// A point in the ball of radius 1 around `c` (rejection sampling).
fn in_ball(rng: &mut SplitMix64, c: [f64; 3]) -> Point3 {
    loop {
        let v = [0; 3].map(|_| 2.0 * rng.unit() - 1.0);
        if v.iter().map(|x| x * x).sum::<f64>() <= 1.0 {
            return Point3::new(c[0] + v[0], c[1] + v[1], c[2] + v[2]);
        }
    }
}

/// Baseline for `tribox_boundary/paper_f64` (not library code): the paper's corner
/// classification (section 3, eqs. 2–9, four cases) transcribed in plain `f64`, with no chamfer
/// clamping, no exact sign tests and no correct rounding. Only the 8 × 4 vertex coordinates
/// are produced (no face loops), which is the cheapest meaningful comparison for the exact path.
mod paper_f64 {
    use kepler::bounds::tribox::{Tribox, TriboxBounds};

    /// The plane (index into the 18 bounds) whose outward normal is `w`.
    const fn plane_of(w: [i8; 3]) -> usize {
        let mut j = 0;
        while j < 18 {
            let n = Tribox::PLANE_NORMALS[j];
            if n[0] == w[0] as f64 && n[1] == w[1] as f64 && n[2] == w[2] as f64 {
                return j;
            }
            j += 1;
        }
        panic!("not a tribox normal")
    }

    /// Per corner (bit i set: minimum along axis i), the planes A, B, C, AB, AC, BC of its
    /// reflected (canonical) frame.
    const CORNER_PLANES: [[usize; 6]; 8] = {
        let local: [[i8; 3]; 6] = [
            [1, 0, 0],
            [0, 1, 0],
            [0, 0, 1],
            [1, 1, 0],
            [1, 0, 1],
            [0, 1, 1],
        ];
        let mut t = [[0; 6]; 8];
        let mut c = 0;
        while c < 8 {
            let s = [
                1 - 2 * (c & 1) as i8,
                1 - 2 * ((c >> 1) & 1) as i8,
                1 - 2 * ((c >> 2) & 1) as i8,
            ];
            let mut k = 0;
            while k < 6 {
                let l = local[k];
                t[c][k] = plane_of([l[0] * s[0], l[1] * s[1], l[2] * s[2]]);
                k += 1;
            }
            c += 1;
        }
        t
    };

    /// The 32 vertices (4 per corner, in the corner's case order) and the 8 cases.
    pub fn boundary(b: &TriboxBounds) -> ([[f64; 3]; 32], [u8; 8]) {
        let (min, max) = (b.min(), b.max());
        let beta: [f64; 18] =
            std::array::from_fn(|j| if j % 2 == 0 { -min[j / 2] } else { max[j / 2] });
        let mut out = [[0.0; 3]; 32];
        let mut cases = [0u8; 8];
        for (c, planes) in CORNER_PLANES.iter().enumerate() {
            let [a, b, cc, ab, ac, bc] = planes.map(|j| beta[j]);
            // p = the meeting point of the three chamfers (eqs. 2–4).
            let xp = 0.5 * (ab + ac - bc);
            let yp = 0.5 * (ab - ac + bc);
            let zp = 0.5 * (-ab + ac + bc);
            let v1 = [ac - cc, bc - cc, cc]; // eq. 5
            let v2 = [a, ab - a, ac - a]; // eq. 6
            let v3 = [ab - b, b, bc - b]; // eq. 7
            let (case, v) = if xp > a {
                // Case 2: eqs. 8, 9.
                (
                    2,
                    [v1, v3, [a, bc - ac + a, ac - a], [a, ab - a, bc - ab + a]],
                )
            } else if yp > b {
                // Case 3 (p beyond h_B): v3 is cut; B∩AB∩AC and B∩AC∩BC replace p.
                (
                    3,
                    [v1, v2, [ab - b, b, ac - ab + b], [ac - bc + b, b, bc - b]],
                )
            } else if zp > cc {
                // Case 4 (p beyond h_C): v1 is cut; C∩AB∩AC and C∩AB∩BC replace p.
                (
                    4,
                    [
                        v2,
                        v3,
                        [ac - cc, ab - ac + cc, cc],
                        [ab - bc + cc, bc - cc, cc],
                    ],
                )
            } else {
                (1, [v1, v2, v3, [xp, yp, zp]])
            };
            cases[c] = case;
            // Reflect back to world coordinates.
            let s = [
                1.0 - 2.0 * (c & 1) as f64,
                1.0 - 2.0 * ((c >> 1) & 1) as f64,
                1.0 - 2.0 * ((c >> 2) & 1) as f64,
            ];
            for (k, w) in v.iter().enumerate() {
                out[4 * c + k] = [s[0] * w[0], s[1] * w[1], s[2] * w[2]];
            }
        }
        (out, cases)
    }
}

fn boundary(c: &mut Criterion) {
    // 64 generic clouds: 200 points in a randomly placed ball (every corner in case 1), or 6
    // points in a unit cube (all four cases occur).
    let mut rng = SplitMix64(0x2545_f491_4f6c_dd1d);
    let bounds: Vec<TriboxBounds> = (0..64)
        .map(|k| {
            let pts: Vec<Point3> = if k % 2 == 0 {
                let centre = [0; 3].map(|_| 10.0 * rng.unit() - 5.0);
                (0..200).map(|_| in_ball(&mut rng, centre)).collect()
            } else {
                (0..6)
                    .map(|_| Point3::new(rng.unit(), rng.unit(), rng.unit()))
                    .collect()
            };
            TriboxBounds::from_points(&pts)
        })
        .collect();
    // Sanity check of the baseline on the ball clouds (no chamfer is clamped there, so it
    // must agree with the exact path up to rounding); the cube clouds have clamped chamfers,
    // which the baseline deliberately ignores.
    for b in bounds.iter().step_by(2) {
        let (v, cases) = paper_f64::boundary(b);
        let t = b.boundary();
        assert_eq!(cases, t.corner_cases());
        for (p, q) in v.iter().zip(t.vertices()) {
            assert!((0..3).all(|k| (p[k] - q[k]).abs() <= 1e-12));
        }
    }
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
    g.bench_function("paper_f64", |b| {
        b.iter(|| {
            i = (i + 1) % bounds.len();
            let t = paper_f64::boundary(black_box(&bounds[i]));
            black_box(&t);
        })
    });
    g.finish();
}

fn bounds_1m(c: &mut Criterion) {
    const N: usize = 1_000_000;
    let mut rng = SplitMix64(0x9e37_79b9_7f4a_7c15);
    let pts: Vec<Point3> = (0..N)
        .map(|_| in_ball(&mut rng, [0.3, -0.2, 0.1]))
        .collect();
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
