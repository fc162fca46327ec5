//! Projected area of boxes, after Schmalstieg and Tobler (1999): the exact area of the picture
//! through the hull vertex table (`projected_area`, four or six corners projected) against the
//! area of the 2-D bounding box of the eight projected corners (`bounding_rect_area`), on the
//! same 10,000 random oriented boxes and eyes, perspective and orthographic, and the
//! axis-aligned variant. Throughput is in boxes. The share of boxes seen from a face region
//! (four silhouette corners) is printed once.
//!
//!   cargo bench --bench projected_area

use std::hint::black_box;

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use kepler::geometry::{Aabb, Point3, Vector3};
use kepler::lab::oriented::OrientedBox;
use kepler::lab::projected_area::{bounding_rect_area, projected_area};
use kepler::random::SplitMix64;
use kepler::views::projected_area::{HULL, classify, projected_area_aabb};
use kepler::views::{Picture, View};
use nalgebra::{Rotation3, Unit};

const BOXES: usize = 10_000;

/// A vector with coordinates uniform in `[-1, 1)`.
fn vector(rng: &mut SplitMix64) -> Vector3 {
    Vector3::new(
        rng.range(-1.0, 1.0),
        rng.range(-1.0, 1.0),
        rng.range(-1.0, 1.0),
    )
}

/// A random box: centre in `[-50, 50]³`, extents in `[0.5, 5]`, turned at random.
fn random_box(rng: &mut SplitMix64) -> OrientedBox {
    let axis = Unit::new_normalize(vector(rng) + Vector3::new(1e-3, 0.0, 0.0));
    let rotation = Rotation3::from_axis_angle(&axis, rng.range(0.0, std::f64::consts::TAU));
    let axes = [0, 1, 2].map(|k| rotation * Vector3::ith(k, 1.0));
    let centre = vector(rng) * 50.0;
    let half = [0; 3].map(|_| rng.range(0.25, 2.5));
    let mid = [0, 1, 2].map(|k| axes[k].dot(&centre));
    OrientedBox {
        axes,
        min: [0, 1, 2].map(|k| mid[k] - half[k]),
        max: [0, 1, 2].map(|k| mid[k] + half[k]),
    }
}

/// A perspective view of `corners` from 5 to 50 units away from their centre, looking at it,
/// with every corner in front of the eye.
fn perspective_view(rng: &mut SplitMix64, corners: &[Point3; 8]) -> View {
    let centre = Point3::from(corners.iter().map(|p| p.coords).sum::<Vector3>() / 8.0);
    loop {
        let eye = centre + vector(rng).normalize() * rng.range(5.0, 50.0);
        if let Ok(view) = View::perspective(eye, centre, vector(rng), rng.range(30.0, 90.0)) {
            let picture = Picture::of(&view);
            if corners.iter().all(|p| picture.in_front(p)) {
                return view;
            }
        }
    }
}

fn orthographic_view(rng: &mut SplitMix64) -> View {
    loop {
        if let Ok(view) = View::orthographic(vector(rng), vector(rng)) {
            return view;
        }
    }
}

fn bench(c: &mut Criterion) {
    let mut rng = SplitMix64(0x9e37_79b9_7f4a_7c15);
    let boxes: Vec<OrientedBox> = (0..BOXES).map(|_| random_box(&mut rng)).collect();
    let perspective: Vec<View> = boxes
        .iter()
        .map(|b| perspective_view(&mut rng, &b.corners()))
        .collect();
    let orthographic: Vec<View> = (0..BOXES).map(|_| orthographic_view(&mut rng)).collect();
    let aabbs: Vec<Aabb> = boxes
        .iter()
        .map(|b| Aabb::from_points(&b.corners()))
        .collect();
    let aabb_views: Vec<View> = aabbs
        .iter()
        .map(|b| perspective_view(&mut rng, &b.corners()))
        .collect();
    let faces = aabbs
        .iter()
        .zip(&aabb_views)
        .filter(|(b, v)| HULL[usize::from(classify(b, v.eye()))][0] == 4)
        .count();
    eprintln!("axis-aligned, perspective: {faces} of {BOXES} eyes in a face region (four corners)");

    for (name, views) in [
        ("perspective", &perspective),
        ("orthographic", &orthographic),
    ] {
        let mut group = c.benchmark_group(format!("projected_area/{name}"));
        group.throughput(Throughput::Elements(BOXES as u64));
        group.bench_function("hull_table", |bench| {
            bench.iter(|| {
                boxes
                    .iter()
                    .zip(views)
                    .map(|(b, v)| projected_area(black_box(b), black_box(v)))
                    .sum::<f64>()
            })
        });
        group.bench_function("bounding_rect", |bench| {
            bench.iter(|| {
                boxes
                    .iter()
                    .zip(views)
                    .map(|(b, v)| bounding_rect_area(black_box(b), black_box(v)))
                    .sum::<f64>()
            })
        });
        group.finish();
    }
    let mut group = c.benchmark_group("projected_area/aabb_perspective");
    group.throughput(Throughput::Elements(BOXES as u64));
    group.bench_function("hull_table", |bench| {
        bench.iter(|| {
            aabbs
                .iter()
                .zip(&aabb_views)
                .map(|(b, v)| projected_area_aabb(black_box(b), black_box(v)))
                .sum::<f64>()
        })
    });
    group.bench_function("bounding_rect", |bench| {
        bench.iter(|| {
            aabbs
                .iter()
                .zip(&aabb_views)
                .map(|(b, v)| {
                    bounding_rect_area(&OrientedBox::from_aabb(black_box(b)), black_box(v))
                })
                .sum::<f64>()
        })
    });
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
