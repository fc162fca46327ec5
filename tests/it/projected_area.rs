//! Projected areas of boxes (Schmalstieg and Tobler 1999) and triboxes, checked against
//! references built here: the corners numbered from the paper's figure, a monotone-chain
//! convex hull of the projected corners, and the textbook shoelace formula.

use crate::common::SplitMix64;
use kepler::bounds::tribox::TriboxBounds;
use kepler::geometry::{Aabb, Point3, Vector3};
use kepler::lab::oriented::OrientedBox;
use kepler::lab::projected_area::{bounding_rect_area, projected_area, projected_area_tribox};
use kepler::views::projected_area::{HULL, classify, projected_area_aabb};
use kepler::views::{Eye, Picture, View};
use nalgebra::{Rotation3, Unit};
use proptest::prelude::*;
use std::collections::BTreeMap;

/// The corners in the paper's numbering, read off its table's rows for single faces (left
/// "0 4 7 3", bottom "0 1 5 4", front "0 3 2 1"): 0 is left-bottom-front (all minima), 1
/// right of it, 2 above 1, 3 above 0, and 4 to 7 the same at the back.
fn paper_corners(min: [f64; 3], max: [f64; 3]) -> [[f64; 3]; 8] {
    let at = |right: bool, top: bool, back: bool| {
        [
            if right { max[0] } else { min[0] },
            if top { max[1] } else { min[1] },
            if back { max[2] } else { min[2] },
        ]
    };
    [
        at(false, false, false),
        at(true, false, false),
        at(true, true, false),
        at(false, true, false),
        at(false, false, true),
        at(true, false, true),
        at(true, true, true),
        at(false, true, true),
    ]
}

/// The hull of the points (Andrew's monotone chain), counter-clockwise, as indices; collinear
/// and repeated points are left out.
fn hull(points: &[[f64; 2]]) -> Vec<usize> {
    let mut order: Vec<usize> = (0..points.len()).collect();
    order.sort_by(|&a, &b| points[a].partial_cmp(&points[b]).expect("finite"));
    order.dedup_by(|a, b| points[*a] == points[*b]);
    if order.len() < 3 {
        return order;
    }
    let cross = |o: usize, a: usize, b: usize| {
        let (o, a, b) = (points[o], points[a], points[b]);
        (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0])
    };
    let mut chain: Vec<usize> = Vec::new();
    for pass in [order.clone(), order.into_iter().rev().collect()] {
        let base = chain.len();
        for i in pass {
            while chain.len() >= base + 2
                && cross(chain[chain.len() - 2], chain[chain.len() - 1], i) <= 0.0
            {
                chain.pop();
            }
            chain.push(i);
        }
        chain.pop();
    }
    chain
}

/// The shoelace formula, `Σ (x_i y_(i+1) − x_(i+1) y_i) / 2`, about the first vertex.
fn shoelace(polygon: &[[f64; 2]]) -> f64 {
    let n = polygon.len();
    let o = polygon[0];
    (0..n)
        .map(|i| {
            let (a, b) = (polygon[i], polygon[(i + 1) % n]);
            (a[0] - o[0]) * (b[1] - o[1]) - (b[0] - o[0]) * (a[1] - o[1])
        })
        .sum::<f64>()
        / 2.0
}

/// The area of the convex hull of the pictures of `points`.
fn hull_area(view: &View, points: &[Point3]) -> f64 {
    let picture = Picture::of(view);
    let projected: Vec<[f64; 2]> = points.iter().map(|p| picture.point(p)).collect();
    let h: Vec<[f64; 2]> = hull(&projected).into_iter().map(|i| projected[i]).collect();
    if h.len() < 3 { 0.0 } else { shoelace(&h) }
}

/// The area of the 2-D bounding box of the pictures of `points`.
fn rect_area(view: &View, points: &[Point3]) -> f64 {
    let picture = Picture::of(view);
    let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
    for p in points {
        let q = picture.point(p);
        for i in 0..2 {
            lo[i] = lo[i].min(q[i]);
            hi[i] = hi[i].max(q[i]);
        }
    }
    (hi[0] - lo[0]) * (hi[1] - lo[1])
}

fn assert_close(got: f64, expected: f64, what: &str) {
    assert!(
        (got - expected).abs() <= 1e-12 * expected.abs(),
        "{what}: {got} against {expected} (relative error {:e})",
        (got - expected).abs() / expected.abs()
    );
}

/// The region of a code: per axis −1 (below the minimum), 0 (between) or 1 (above the
/// maximum); `None` for the invalid codes (both bits of an axis) and the eye inside.
fn region(code: u8) -> Option<[i32; 3]> {
    let mut s = [0; 3];
    for (i, s) in s.iter_mut().enumerate() {
        *s = match (code >> (2 * i) & 1, code >> (2 * i + 1) & 1) {
            (1, 1) => return None,
            (1, 0) => -1,
            (0, 1) => 1,
            _ => 0,
        };
    }
    (s != [0; 3]).then_some(s)
}

/// The 26 valid codes, built from the bit layout of the paper's Table 1.
fn valid_codes() -> Vec<u8> {
    (0..64).filter(|&c| region(c).is_some()).collect()
}

/// A coordinate in the region `s` along `[lo, hi]`, kept away from the planes.
fn coordinate(rng: &mut SplitMix64, s: i32, lo: f64, hi: f64) -> f64 {
    let size = hi - lo;
    match s {
        -1 => lo - size * rng.range(0.05, 3.0),
        1 => hi + size * rng.range(0.05, 3.0),
        _ => lo + size * rng.range(0.05, 0.95),
    }
}

fn random_box(rng: &mut SplitMix64) -> Aabb {
    let min = [0; 3].map(|_| rng.range(-20.0, 20.0));
    let size = [0; 3].map(|_| 10f64.powf(rng.range(-1.0, 1.0)));
    Aabb {
        min,
        max: [0, 1, 2].map(|i| min[i] + size[i]),
    }
}

fn random_rotation(rng: &mut SplitMix64) -> Rotation3<f64> {
    let axis = Unit::new_normalize(rng.vector(1.0) + Vector3::new(1e-3, 0.0, 0.0));
    Rotation3::from_axis_angle(&axis, rng.range(0.0, std::f64::consts::TAU))
}

/// A perspective view from `eye` looking at `target`, random up and field of view.
fn perspective(rng: &mut SplitMix64, eye: Point3, target: Point3) -> View {
    loop {
        let up = rng.vector(1.0);
        if let Ok(v) = View::perspective(eye, target, up, rng.range(20.0, 120.0)) {
            return v;
        }
    }
}

/// An orthographic view whose eye is at infinity along `toward_viewer`, random up.
fn orthographic(rng: &mut SplitMix64, toward_viewer: Vector3) -> View {
    loop {
        if let Ok(v) = View::orthographic(-toward_viewer, rng.vector(1.0)) {
            return v;
        }
    }
}

fn in_front(view: &View, points: &[Point3]) -> bool {
    let picture = Picture::of(view);
    points.iter().all(|p| picture.in_front(p))
}

/// The hull of the projected corners (paper numbering), as a row of the table: the count and
/// the corners counter-clockwise from the lowest.
fn brute_force_row(view: &View, corners: &[[f64; 3]; 8]) -> Vec<u8> {
    let picture = Picture::of(view);
    let projected: Vec<[f64; 2]> = corners.iter().map(|&c| picture.point(&c.into())).collect();
    let mut h: Vec<u8> = hull(&projected).into_iter().map(|i| i as u8).collect();
    let first = (0..h.len()).min_by_key(|&i| h[i]).expect("a hull");
    h.rotate_left(first);
    let mut row = vec![h.len() as u8];
    row.extend(h);
    row.resize(7, 0);
    row
}

#[test]
fn hull_table_matches_the_hulls_of_projected_corners() {
    let mut rng = SplitMix64(1);
    for code in valid_codes() {
        let s = region(code).expect("valid");
        let mut checked = 0;
        while checked < 40 {
            let b = random_box(&mut rng);
            let eye =
                Point3::from([0, 1, 2].map(|i| coordinate(&mut rng, s[i], b.min[i], b.max[i])));
            let target = Point3::from([0, 1, 2].map(|i| rng.range(b.min[i], b.max[i])));
            let view = perspective(&mut rng, eye, target);
            let corners = paper_corners(b.min, b.max);
            if !in_front(&view, &corners.map(Point3::from)) {
                continue;
            }
            checked += 1;
            assert_eq!(
                HULL[usize::from(code)].to_vec(),
                brute_force_row(&view, &corners),
                "code {code}, box {b:?}, eye {eye}"
            );
        }
    }
}

#[test]
fn hull_table_rows() {
    let valid = valid_codes();
    assert_eq!(valid.len(), 26);
    assert!(valid.iter().all(|&c| c < 43));
    for code in 0..43u8 {
        let row = HULL[usize::from(code)];
        let n = usize::from(row[0]);
        let Some(s) = region(code) else {
            assert_eq!(row, [0; 7], "code {code}");
            continue;
        };
        let outside = s.iter().filter(|&&s| s != 0).count();
        assert_eq!(n, if outside == 1 { 4 } else { 6 }, "code {code}");
        let vertices = &row[1..=n];
        let mut sorted = vertices.to_vec();
        sorted.sort();
        sorted.dedup();
        assert_eq!(sorted.len(), n, "code {code}: repeated corner");
        assert_eq!(vertices.iter().min(), Some(&vertices[0]), "code {code}");
        assert!(row[n + 1..].iter().all(|&k| k == 0));
        // Every silhouette edge is an edge of the box: its corners differ along one axis.
        let bits = paper_corners([0.0; 3], [1.0; 3]);
        for i in 0..n {
            let (a, b) = (
                bits[usize::from(vertices[i])],
                bits[usize::from(vertices[(i + 1) % n])],
            );
            assert_eq!((0..3).filter(|&k| a[k] != b[k]).count(), 1, "code {code}");
        }
    }
}

/// The paper's Table 2 as printed: (case, vertex indices).
const PAPER_TABLE: [(u8, &[u8]); 26] = [
    (1, &[0, 4, 7, 3]),
    (2, &[1, 2, 6, 5]),
    (4, &[0, 1, 5, 4]),
    (5, &[0, 1, 2, 6, 5, 4]),
    (6, &[0, 1, 2, 6, 5, 4]),
    (8, &[2, 3, 7, 6]),
    (9, &[4, 7, 6, 2, 3, 0]),
    (10, &[2, 3, 7, 6, 5, 1]),
    (16, &[0, 3, 2, 1]),
    (17, &[0, 4, 7, 3, 2, 1]),
    (18, &[0, 3, 2, 6, 5, 1]),
    (20, &[0, 3, 2, 1, 5, 4]),
    (21, &[1, 5, 4, 7, 3, 2]),
    (22, &[0, 3, 2, 6, 5, 4]),
    (24, &[0, 3, 7, 6, 2, 1]),
    (25, &[0, 4, 7, 6, 2, 1]),
    (26, &[0, 3, 7, 6, 5, 1]),
    (32, &[4, 5, 6, 7]),
    (33, &[4, 5, 6, 7, 3, 0]),
    (34, &[1, 2, 6, 7, 4, 5]),
    (36, &[0, 1, 5, 6, 7, 4]),
    (37, &[0, 1, 5, 6, 7, 3]),
    (38, &[0, 1, 2, 6, 7, 4]),
    (40, &[2, 3, 7, 4, 5, 6]),
    (41, &[0, 4, 5, 6, 2, 3]),
    (42, &[1, 2, 3, 7, 4, 5]),
];

#[test]
fn paper_table_is_wrong_only_in_row_5() {
    let paper: BTreeMap<u8, &[u8]> = PAPER_TABLE.into_iter().collect();
    // The printed rows cover exactly the valid codes.
    assert_eq!(paper.keys().copied().collect::<Vec<_>>(), valid_codes());
    // Same cycle, same orientation, possibly another starting vertex.
    let agrees = |code: u8, printed: &[u8]| {
        let row = HULL[usize::from(code)];
        let ours = &row[1..=usize::from(row[0])];
        ours.len() == printed.len()
            && (0..ours.len()).any(|r| {
                let mut turned = printed.to_vec();
                turned.rotate_left(r);
                turned == ours
            })
    };
    let wrong: Vec<u8> = paper
        .iter()
        .filter(|&(&code, printed)| !agrees(code, printed))
        .map(|(&code, _)| code)
        .collect();
    assert_eq!(wrong, [5]);
    assert_eq!(paper[&5], paper[&6], "row 5 is printed as a copy of row 6");
    assert_eq!(HULL[5], [6, 0, 1, 5, 4, 7, 3]);
}

#[test]
fn classify_is_exact_in_every_region() {
    let mut rng = SplitMix64(2);
    let b = Aabb {
        min: [-1.0, 0.5, 2.0],
        max: [3.0, 0.75, 2.5],
    };
    for code in valid_codes() {
        let s = region(code).expect("valid");
        for _ in 0..10 {
            let e = Point3::from([0, 1, 2].map(|i| coordinate(&mut rng, s[i], b.min[i], b.max[i])));
            assert_eq!(classify(&b, &Eye::Point(e)), code, "eye {e}");
            let u = Vector3::from(s.map(|s| f64::from(s) * rng.range(0.1, 2.0)));
            assert_eq!(classify(&b, &Eye::Infinity(u)), code);
            assert_eq!(classify(&b, orthographic(&mut rng, u).eye()), code);
        }
    }
    // On a plane is not outside; one ulp beyond is.
    for on in [Point3::new(3.0, 0.75, 2.5), Point3::new(-1.0, 0.5, 2.0)] {
        assert_eq!(classify(&b, &Eye::Point(on)), 0);
    }
    let beyond = Point3::new(3.0f64.next_up(), 0.5f64.next_down(), 2.5f64.next_up());
    assert_eq!(classify(&b, &Eye::Point(beyond)), 2 | 4 | 32);
    let below = Point3::new((-1.0f64).next_down(), 0.75f64.next_up(), 2.0f64.next_down());
    assert_eq!(classify(&b, &Eye::Point(below)), 1 | 8 | 16);
    assert_eq!(
        classify(&b, &Eye::Infinity(Vector3::new(-0.0, 0.0, -1e-300))),
        16
    );
}

#[test]
fn exact_values() {
    let cube = Aabb {
        min: [0.0; 3],
        max: [1.0; 3],
    };
    let oriented = OrientedBox::from_aabb(&cube);
    // Orthographic along a face, an edge direction and the diagonal: the projection of the
    // unit cube along a unit direction u has area |u_x| + |u_y| + |u_z|.
    let face = View::orthographic(Vector3::new(0.0, 0.0, -1.0), Vector3::y()).expect("view");
    assert_eq!(projected_area_aabb(&cube, &face), 1.0);
    assert_eq!(bounding_rect_area(&oriented, &face), 1.0);
    let edge = View::orthographic(Vector3::new(-1.0, -1.0, 0.0), Vector3::z()).expect("view");
    assert!((projected_area_aabb(&cube, &edge) - 2f64.sqrt()).abs() < 1e-15);
    assert!((bounding_rect_area(&oriented, &edge) - 2f64.sqrt()).abs() < 1e-15);
    let diagonal = View::orthographic(Vector3::new(1.0, -1.0, 1.0), Vector3::y()).expect("view");
    assert!((projected_area_aabb(&cube, &diagonal) - 3f64.sqrt()).abs() < 1e-15);
    assert!((projected_area(&oriented, &diagonal) - 3f64.sqrt()).abs() < 1e-15);
    // Perspective, face-on from distance 3 to the centre of [-1, 1]³ with a 90° field of
    // view: the near face at depth 2 spans [-1/2, 1/2]² (up to the rounding of tan 45°).
    let big = Aabb {
        min: [-1.0; 3],
        max: [1.0; 3],
    };
    let v = View::perspective(
        Point3::new(0.0, 0.0, 3.0),
        Point3::origin(),
        Vector3::y(),
        90.0,
    )
    .expect("view");
    assert!((projected_area_aabb(&big, &v) - 1.0).abs() < 1e-15);
    // From (0, 3, 3) towards the centre, looking down the diagonal of the y-z plane: the
    // picture of (x, y, z) is (x, (y − z)/√2) over the depth 3√2 − (y + z)/√2. The silhouette
    // is the hexagon of corners (±1, 1, −1), (±1, 1, 1), (±1, −1, 1): the near edge
    // (±1, 1, 1) at depth 2√2 on the picture's x-axis, half-width 1/(2√2); the far edges at
    // depth 3√2, height ±1/3, half-width 1/(3√2). Two trapezoids of height 1/3.
    let v = View::perspective(
        Point3::new(0.0, 3.0, 3.0),
        Point3::origin(),
        Vector3::y(),
        90.0,
    )
    .expect("view");
    let r2 = 2f64.sqrt();
    let expected = (1.0 / 3.0) * (2.0 / (3.0 * r2) + 2.0 / (2.0 * r2));
    assert!((projected_area_aabb(&big, &v) - expected).abs() < 1e-15);
    // A unit square turned 45° about z, seen from above: area 1, bounding square 2.
    let s = 0.5f64.sqrt();
    let turned = OrientedBox {
        axes: [
            Vector3::new(s, s, 0.0),
            Vector3::new(-s, s, 0.0),
            Vector3::z(),
        ],
        min: [0.0; 3],
        max: [1.0; 3],
    };
    assert!((projected_area(&turned, &View::standard()) - 1.0).abs() < 1e-15);
    assert!((bounding_rect_area(&turned, &View::standard()) - 2.0).abs() < 1e-15);
    // Empty boxes have no picture.
    assert_eq!(projected_area_aabb(&Aabb::EMPTY, &v), 0.0);
    assert_eq!(
        projected_area(&OrientedBox::from_aabb(&Aabb::EMPTY), &v),
        0.0
    );
    assert_eq!(
        bounding_rect_area(&OrientedBox::from_aabb(&Aabb::EMPTY), &v),
        0.0
    );
    assert_eq!(
        projected_area_tribox(&TriboxBounds::empty().boundary(), &v),
        0.0
    );
}

#[test]
fn area_is_the_hull_of_the_projected_corners() {
    let mut rng = SplitMix64(3);
    let mut hits: [BTreeMap<u8, usize>; 4] = Default::default();
    for code in valid_codes() {
        let s = region(code).expect("valid");
        for _ in 0..200 {
            let b = random_box(&mut rng);
            let rotation = random_rotation(&mut rng);
            let corners = b.corners();
            // Axis-aligned, perspective: the eye in the region of `code`.
            let e = Point3::from([0, 1, 2].map(|i| coordinate(&mut rng, s[i], b.min[i], b.max[i])));
            let target = Point3::from([0, 1, 2].map(|i| rng.range(b.min[i], b.max[i])));
            let view = perspective(&mut rng, e, target);
            if in_front(&view, &corners) {
                *hits[0].entry(classify(&b, view.eye())).or_default() += 1;
                let expected = hull_area(&view, &corners);
                assert_close(
                    projected_area_aabb(&b, &view),
                    expected,
                    "aabb, perspective",
                );
                let same = projected_area(&OrientedBox::from_aabb(&b), &view);
                assert_eq!(same, projected_area_aabb(&b, &view));
                let rect = bounding_rect_area(&OrientedBox::from_aabb(&b), &view);
                assert_close(rect, rect_area(&view, &corners), "rect, perspective");
                assert!(rect >= expected);
            }
            // Axis-aligned, orthographic: the direction towards the eye has the region's signs
            // (zero along the axes where the eye is between the planes).
            let u = Vector3::from(s.map(|s| f64::from(s) * rng.range(0.01, 1.0)));
            let view = orthographic(&mut rng, u);
            *hits[1].entry(classify(&b, view.eye())).or_default() += 1;
            let expected = hull_area(&view, &corners);
            assert_close(
                projected_area_aabb(&b, &view),
                expected,
                "aabb, orthographic",
            );
            // Oriented: the same box turned about the origin, the eye in the region in the
            // box's frame.
            let axes = [0, 1, 2].map(|k| rotation * Vector3::ith(k, 1.0));
            let ob = OrientedBox {
                axes,
                min: b.min,
                max: b.max,
            };
            let corners = ob.corners();
            let local = [0, 1, 2].map(|i| coordinate(&mut rng, s[i], b.min[i], b.max[i]));
            let e = Point3::from(axes[0] * local[0] + axes[1] * local[1] + axes[2] * local[2]);
            let target = corners[rng.below(8)];
            let view = perspective(&mut rng, e, target);
            if in_front(&view, &corners) {
                *hits[2].entry(code).or_default() += 1;
                let expected = hull_area(&view, &corners);
                assert_close(
                    projected_area(&ob, &view),
                    expected,
                    "oriented, perspective",
                );
                let rect = bounding_rect_area(&ob, &view);
                assert_close(
                    rect,
                    rect_area(&view, &corners),
                    "oriented rect, perspective",
                );
                assert!(rect >= expected);
            }
            let u = rotation * Vector3::from(s.map(|s| f64::from(s) * rng.range(0.01, 1.0)));
            let view = orthographic(&mut rng, u);
            *hits[3].entry(code).or_default() += 1;
            let expected = hull_area(&view, &corners);
            assert_close(
                projected_area(&ob, &view),
                expected,
                "oriented, orthographic",
            );
        }
    }
    for (k, h) in hits.iter().enumerate() {
        assert_eq!(
            h.keys().copied().collect::<Vec<_>>(),
            valid_codes(),
            "set {k}"
        );
        assert!(h.values().all(|&n| n >= 50), "set {k}: {h:?}");
    }
}

#[test]
fn eye_in_the_box_covers_the_view() {
    let mut rng = SplitMix64(4);
    let b = Aabb {
        min: [-1.0, 2.0, 0.0],
        max: [1.0, 3.0, 0.5],
    };
    let ob = OrientedBox::from_aabb(&b);
    let corners = b.corners();
    let tribox = TriboxBounds::from_points(&corners).boundary();
    let mut eyes: Vec<Point3> = (0..50)
        .map(|_| Point3::from([0, 1, 2].map(|i| rng.range(b.min[i], b.max[i]))))
        .collect();
    // On a face, an edge and a corner: in the closed box, looking into it or away from it.
    eyes.extend([
        Point3::new(1.0, 2.5, 0.25),
        Point3::new(-1.0, 2.5, 0.25),
        Point3::new(1.0, 3.0, 0.25),
        Point3::new(-1.0, 2.0, 0.0),
    ]);
    for e in eyes {
        assert_eq!(classify(&b, &Eye::Point(e)), 0);
        for x in [10.0, -10.0] {
            let target = e + Vector3::new(x, 0.0, 0.0);
            let view = perspective(&mut rng, e, target);
            assert_eq!(projected_area_aabb(&b, &view), f64::INFINITY, "eye {e}");
            assert_eq!(projected_area(&ob, &view), f64::INFINITY, "eye {e}");
            assert_eq!(projected_area_tribox(&tribox, &view), f64::INFINITY);
        }
    }
    // Strictly inside, the corners are on both sides of the eye.
    let view = perspective(
        &mut rng,
        Point3::new(0.0, 2.5, 0.25),
        Point3::new(5.0, 2.5, 0.25),
    );
    assert_eq!(bounding_rect_area(&ob, &view), f64::INFINITY);
    // A rotated box: the eye at its centre.
    let rotation = random_rotation(&mut rng);
    let turned = OrientedBox {
        axes: [0, 1, 2].map(|k| rotation * Vector3::ith(k, 1.0)),
        ..ob
    };
    let centre = Point3::from(turned.corners().iter().map(|p| p.coords).sum::<Vector3>() / 8.0);
    let view = perspective(&mut rng, centre, Point3::new(9.0, 9.0, 9.0));
    assert_eq!(projected_area(&turned, &view), f64::INFINITY);
}

#[test]
fn boxes_behind_or_across_the_eye() {
    let eye = Point3::origin();
    let view =
        View::perspective(eye, Point3::new(0.0, 0.0, 1.0), Vector3::y(), 60.0).expect("view");
    let cases = [
        // Wholly behind, seen face-on and from a corner region.
        ([-1.0, -1.0, -5.0], [1.0, 1.0, -3.0], 0.0),
        ([2.0, 3.0, -5.0], [4.0, 5.0, -3.0], 0.0),
        // At or behind: a face in the plane through the eye.
        ([2.0, -1.0, -1.0], [3.0, 1.0, 0.0], 0.0),
        // Across the plane, or touching it from in front.
        ([2.0, -1.0, -1.0], [3.0, 1.0, 1.0], f64::INFINITY),
        ([2.0, -1.0, 0.0], [3.0, 1.0, 1.0], f64::INFINITY),
        ([-1.0, 2.0, -3.0], [1.0, 3.0, 4.0], f64::INFINITY),
    ];
    for (min, max, expected) in cases {
        let b = Aabb { min, max };
        assert_ne!(classify(&b, view.eye()), 0);
        let ob = OrientedBox::from_aabb(&b);
        assert_eq!(projected_area_aabb(&b, &view), expected, "{b:?}");
        assert_eq!(projected_area(&ob, &view), expected, "{b:?}");
        assert_eq!(bounding_rect_area(&ob, &view), expected, "{b:?}");
        let t = TriboxBounds::from_points(&b.corners()).boundary();
        assert_eq!(projected_area_tribox(&t, &view), expected, "{b:?}");
    }
}

#[test]
fn tribox_picture_lies_between_the_object_and_its_cbox() {
    let mut rng = SplitMix64(5);
    let solids = [
        kepler::solids::tetrahedron(2.0),
        kepler::solids::octahedron(2.0),
        kepler::solids::dodecahedron(1.0),
        kepler::solids::icosahedron(1.5),
        kepler::solids::uv_sphere(1.0, 12, 8),
        kepler::solids::torus(2.0, 0.5, 16, 8),
        kepler::solids::cylinder(1.0, 3.0, 12),
    ]
    .map(|m| m.expect("solid"));
    let (mut checked, mut smaller_than_cbox) = (0, 0);
    for mesh in &solids {
        for _ in 0..60 {
            let rotation = random_rotation(&mut rng);
            let shift = rng.vector(10.0);
            let points: Vec<Point3> = mesh
                .vertices()
                .iter()
                .map(|p| rotation * p + shift)
                .collect();
            let cbox = Aabb::from_points(&points);
            let tribox = TriboxBounds::from_points(&points).boundary();
            let code = rng.pick(&valid_codes());
            let s = region(code).expect("valid");
            let e = Point3::from(
                [0, 1, 2].map(|i| coordinate(&mut rng, s[i], cbox.min[i], cbox.max[i])),
            );
            let target = points[rng.below(points.len())];
            let u = Vector3::from(s.map(|s| f64::from(s) * rng.range(0.01, 1.0)));
            for view in [perspective(&mut rng, e, target), orthographic(&mut rng, u)] {
                if !in_front(&view, &cbox.corners()) {
                    continue;
                }
                checked += 1;
                let area = projected_area_tribox(&tribox, &view);
                assert_close(area, hull_area(&view, tribox.vertices()), "tribox");
                let object = hull_area(&view, &points);
                let cbox_area = projected_area_aabb(&cbox, &view);
                assert!(area >= object * (1.0 - 1e-12), "{area} < object {object}");
                assert!(
                    area <= cbox_area * (1.0 + 1e-12),
                    "{area} > cbox {cbox_area}"
                );
                if area < cbox_area * (1.0 - 1e-6) {
                    smaller_than_cbox += 1;
                }
            }
        }
    }
    assert!(checked > 600, "{checked}");
    assert!(
        smaller_than_cbox > checked * 9 / 10,
        "{smaller_than_cbox} of {checked}"
    );
    // Inside the CBOX of an octahedron but outside its tribox: the CBOX covers the view, the
    // tribox does not.
    let points = kepler::solids::octahedron(2.0)
        .expect("solid")
        .vertices()
        .to_vec();
    let cbox = Aabb::from_points(&points);
    let tribox = TriboxBounds::from_points(&points).boundary();
    let e = Point3::from(cbox.max.map(|c| 0.9 * c));
    let view = perspective(&mut rng, e, Point3::new(5.0, 5.0, 5.0));
    assert_eq!(projected_area_aabb(&cbox, &view), f64::INFINITY);
    assert_eq!(projected_area_tribox(&tribox, &view), 0.0);
    let view = perspective(&mut rng, e, Point3::new(-5.0, -5.0, -5.0));
    let area = projected_area_tribox(&tribox, &view);
    assert!(area.is_finite() && area > 0.0);
    assert_close(
        area,
        hull_area(&view, tribox.vertices()),
        "tribox from inside the cbox",
    );
    // In the tribox.
    let view = perspective(
        &mut rng,
        Point3::new(0.1, 0.2, 0.3),
        Point3::new(5.0, 0.0, 0.0),
    );
    assert_eq!(projected_area_tribox(&tribox, &view), f64::INFINITY);
}

/// What the area must be for a box with these corners: ∞ with the eye in the closed box
/// (`inside`), otherwise the hull area, 0 or ∞ as all, none or some corners are in front.
fn expected_area(view: &View, corners: &[Point3], inside: bool) -> f64 {
    let picture = Picture::of(view);
    let in_front = corners.iter().filter(|p| picture.in_front(p)).count();
    if inside {
        f64::INFINITY
    } else if in_front == corners.len() {
        hull_area(view, corners)
    } else if in_front == 0 {
        0.0
    } else {
        f64::INFINITY
    }
}

fn check(got: f64, expected: f64) -> Result<(), TestCaseError> {
    if expected.is_finite() && expected > 0.0 {
        prop_assert!(
            (got - expected).abs() <= 1e-12 * expected,
            "{} against {}",
            got,
            expected
        );
    } else {
        prop_assert_eq!(got, expected);
    }
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(2000))]

    #[test]
    fn any_box_any_perspective_eye(
        min in prop::array::uniform3(-4i32..4),
        size in prop::array::uniform3(1i32..4),
        eye in prop::array::uniform3(-8.0f64..8.0),
        target in prop::array::uniform3(-8.0f64..8.0),
        up in prop::array::uniform3(-1.0f64..1.0),
        fov in 10.0f64..150.0,
        angles in prop::array::uniform3(0.0f64..6.3),
    ) {
        let view = View::perspective(eye.into(), target.into(), up.into(), fov);
        prop_assume!(view.is_ok());
        let view = view.expect("checked");
        let b = Aabb {
            min: min.map(f64::from),
            max: [0, 1, 2].map(|i| f64::from(min[i] + size[i])),
        };
        let inside = b.contains_point(&eye.into());
        check(projected_area_aabb(&b, &view), expected_area(&view, &b.corners(), inside))?;
        let rotation = Rotation3::from_euler_angles(angles[0], angles[1], angles[2]);
        let ob = OrientedBox {
            axes: [0, 1, 2].map(|k| rotation * Vector3::ith(k, 1.0)),
            min: b.min,
            max: b.max,
        };
        let inside = ob.contains_point(&eye.into());
        check(projected_area(&ob, &view), expected_area(&view, &ob.corners(), inside))?;
    }

    #[test]
    fn any_box_any_orthographic_view(
        min in prop::array::uniform3(-4.0f64..4.0),
        size in prop::array::uniform3(0.1f64..4.0),
        direction in prop::array::uniform3(-2i32..3),
        up in prop::array::uniform3(-1.0f64..1.0),
    ) {
        let view = View::orthographic(Vector3::from(direction.map(f64::from)), up.into());
        prop_assume!(view.is_ok());
        let view = view.expect("checked");
        let b = Aabb { min, max: [0, 1, 2].map(|i| min[i] + size[i]) };
        let area = projected_area_aabb(&b, &view);
        check(area, hull_area(&view, &b.corners()))?;
        prop_assert!(bounding_rect_area(&OrientedBox::from_aabb(&b), &view) >= area);
    }
}
