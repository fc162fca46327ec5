//! Exact predicates and polygon triangulation against independent references.

use kepler::geometry::polygon::{
    is_simple, newell_normal, segments_meet, surely_farther, triangulate,
};
use kepler::geometry::predicates::triangle_meets_open_box;
use kepler::geometry::{Aabb, Point3};
use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::{Signed, Zero};
use proptest::prelude::*;

type Q = BigRational;
type QPoint = [Q; 3];

fn q(x: f64) -> Q {
    BigRational::from_float(x).expect("finite")
}

/// Reference: clip the triangle by the six closed half-spaces of the box in exact rational
/// arithmetic (Sutherland–Hodgman). The clipped convex set P meets the open box unless it is
/// empty or lies in one facet of the box (a convex set in a box's boundary lies in a facet).
fn reference_meets_open_box(t: &[Point3; 3], b: &Aabb) -> bool {
    let mut poly: Vec<QPoint> = t.iter().map(|p| [q(p.x), q(p.y), q(p.z)]).collect();
    for k in 0..3 {
        for (bound, keep_above) in [(q(b.min[k]), true), (q(b.max[k]), false)] {
            let inside = |p: &QPoint| {
                if keep_above {
                    p[k] >= bound
                } else {
                    p[k] <= bound
                }
            };
            let mut out = Vec::new();
            for i in 0..poly.len() {
                let (p, r) = (&poly[i], &poly[(i + 1) % poly.len()]);
                if inside(p) {
                    out.push(p.clone());
                }
                if inside(p) != inside(r) {
                    let s = (&bound - &p[k]) / (&r[k] - &p[k]);
                    out.push(std::array::from_fn(|j| &p[j] + (&r[j] - &p[j]) * &s));
                }
            }
            poly = out;
            if poly.is_empty() {
                return false;
            }
        }
    }
    !(0..3).any(|k| {
        let (lo, hi) = (q(b.min[k]), q(b.max[k]));
        poly.iter().all(|p| p[k] == lo) || poly.iter().all(|p| p[k] == hi)
    })
}

fn collinear_q(t: &[Point3; 3]) -> bool {
    let p: Vec<QPoint> = t.iter().map(|p| [q(p.x), q(p.y), q(p.z)]).collect();
    let u: Vec<Q> = (0..3).map(|k| &p[1][k] - &p[0][k]).collect();
    let v: Vec<Q> = (0..3).map(|k| &p[2][k] - &p[0][k]).collect();
    (0..3).all(|k| {
        let (i, j) = ((k + 1) % 3, (k + 2) % 3);
        (&u[i] * &v[j] - &u[j] * &v[i]).is_zero()
    })
}

fn small_point() -> impl Strategy<Value = Point3> {
    (-3i32..=3, -3i32..=3, -3i32..=3)
        .prop_map(|(x, y, z)| Point3::new(x as f64, y as f64, z as f64))
}

fn small_box() -> impl Strategy<Value = Aabb> {
    (
        (-2i32..=1, 1i32..=3),
        (-2i32..=1, 1i32..=3),
        (-2i32..=1, 1i32..=3),
    )
        .prop_map(|(x, y, z)| {
            Aabb::new(
                Point3::new(x.0 as f64, y.0 as f64, z.0 as f64),
                Point3::new((x.0 + x.1) as f64, (y.0 + y.1) as f64, (z.0 + z.1) as f64),
            )
        })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(3000))]

    /// Integer coordinates make touching, coplanar and edge-on cases frequent.
    #[test]
    fn triangle_box_matches_rational_reference_on_grid(
        a in small_point(), b in small_point(), c in small_point(), bx in small_box()
    ) {
        let t = [a, b, c];
        prop_assume!(!collinear_q(&t));
        prop_assert_eq!(triangle_meets_open_box(&t, &bx), reference_meets_open_box(&t, &bx));
    }

    #[test]
    fn triangle_box_matches_rational_reference_random(
        c in prop::array::uniform9(-2.0f64..2.0), lo in prop::array::uniform3(-1.0f64..0.5),
        size in prop::array::uniform3(0.01f64..1.5)
    ) {
        let t = [Point3::new(c[0], c[1], c[2]), Point3::new(c[3], c[4], c[5]), Point3::new(c[6], c[7], c[8])];
        prop_assume!(!collinear_q(&t));
        let bx = Aabb::new(Point3::from(lo), Point3::new(lo[0] + size[0], lo[1] + size[1], lo[2] + size[2]));
        prop_assert_eq!(triangle_meets_open_box(&t, &bx), reference_meets_open_box(&t, &bx));
    }

    /// Triangles through a box corner at tiny offsets: only exact arithmetic gets these right.
    #[test]
    fn triangle_box_near_corner(e in prop::sample::select(vec![0.0, 1e-300, 1e-17, -1e-17, 5e-324]), k in 0usize..3) {
        let bx = Aabb::new(Point3::new(0.0, 0.0, 0.0), Point3::new(1.0, 1.0, 1.0));
        // A plane x + y + z = 3 + e touches the corner (1, 1, 1) when e = 0.
        let mut p = [Point3::new(3.0, 0.0, 0.0), Point3::new(0.0, 3.0, 0.0), Point3::new(0.0, 0.0, 3.0)];
        p[k][k] += e * 3.0;
        prop_assert_eq!(triangle_meets_open_box(&p, &bx), reference_meets_open_box(&p, &bx));
    }
}

#[test]
fn triangle_touching_a_face_or_edge_does_not_meet_the_open_box() {
    let bx = Aabb::new(Point3::new(0.0, 0.0, 0.0), Point3::new(1.0, 1.0, 1.0));
    let on_face = [
        Point3::new(-1.0, -1.0, 1.0),
        Point3::new(3.0, -1.0, 1.0),
        Point3::new(-1.0, 3.0, 1.0),
    ];
    assert!(!triangle_meets_open_box(&on_face, &bx));
    let on_edge = [
        Point3::new(0.0, 0.0, -1.0),
        Point3::new(0.0, 0.0, 2.0),
        Point3::new(-1.0, -1.0, 0.5),
    ];
    assert!(!triangle_meets_open_box(&on_edge, &bx));
    let inside = [
        Point3::new(0.2, 0.2, 0.2),
        Point3::new(0.3, 0.2, 0.2),
        Point3::new(0.2, 0.3, 0.2),
    ];
    assert!(triangle_meets_open_box(&inside, &bx));
}

/// Reference for closed-segment intersection: exact rational parameters.
fn reference_segments_meet(a: [i32; 2], b: [i32; 2], c: [i32; 2], d: [i32; 2]) -> bool {
    let z = |p: [i32; 2]| [BigInt::from(p[0]), BigInt::from(p[1])];
    let (a, b, c, d) = (z(a), z(b), z(c), z(d));
    let cross = |u: &[BigInt; 2], v: &[BigInt; 2]| &u[0] * &v[1] - &u[1] * &v[0];
    let sub = |u: &[BigInt; 2], v: &[BigInt; 2]| [&u[0] - &v[0], &u[1] - &v[1]];
    let (r, s) = (sub(&b, &a), sub(&d, &c));
    let den = cross(&r, &s);
    let ca = sub(&c, &a);
    if !den.is_zero() {
        let t = BigRational::new(cross(&ca, &s), den.clone());
        let u = BigRational::new(cross(&ca, &r), den);
        let unit = |x: &BigRational| !x.is_negative() && *x <= BigRational::from_integer(1.into());
        return unit(&t) && unit(&u);
    }
    if !cross(&ca, &r).is_zero() {
        return false;
    }
    // Collinear: project on the axis where the first segment (or the second) extends.
    let on = |p: &[BigInt; 2], q0: &[BigInt; 2], q1: &[BigInt; 2]| {
        (0..2).all(|k| {
            q0[k].clone().min(q1[k].clone()) <= p[k] && p[k] <= q0[k].clone().max(q1[k].clone())
        })
    };
    on(&c, &a, &b) || on(&d, &a, &b) || on(&a, &c, &d) || on(&b, &c, &d)
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(5000))]
    #[test]
    fn segments_meet_matches_reference(
        a in prop::array::uniform2(-3i32..=3), b in prop::array::uniform2(-3i32..=3),
        c in prop::array::uniform2(-3i32..=3), d in prop::array::uniform2(-3i32..=3)
    ) {
        // Polygon edges join distinct vertices.
        prop_assume!(a != b && c != d);
        let f = |p: [i32; 2]| [p[0] as f64, p[1] as f64];
        prop_assert_eq!(segments_meet(f(a), f(b), f(c), f(d)), reference_segments_meet(a, b, c, d));
    }
}

#[test]
fn simple_and_non_simple_polygons() {
    let star: Vec<[f64; 2]> = (0..5)
        .map(|i| {
            let a = std::f64::consts::TAU * (2 * i) as f64 / 5.0;
            [a.cos(), a.sin()]
        })
        .collect();
    assert!(!is_simple(&star), "a pentagram crosses itself");
    assert!(is_simple(&[
        [0.0, 0.0],
        [4.0, 0.0],
        [4.0, 4.0],
        [2.0, 1.0],
        [0.0, 4.0]
    ]));
    // A spike folding back along an edge.
    assert!(!is_simple(&[
        [0.0, 0.0],
        [2.0, 0.0],
        [1.0, 0.0],
        [1.0, 1.0]
    ]));
}

/// Twice the signed area of a planar polygon in the xy-plane, exactly.
fn area2(p: &[Point3]) -> Q {
    (0..p.len()).fold(Q::zero(), |s, i| {
        let (a, b) = (&p[i], &p[(i + 1) % p.len()]);
        s + q(a.x) * q(b.y) - q(b.x) * q(a.y)
    })
}

#[test]
fn triangulations_cover_their_polygons_exactly() {
    let shapes: Vec<Vec<(f64, f64)>> = vec![
        vec![(0., 0.), (2., 0.), (2., 1.), (1., 1.), (1., 2.), (0., 2.)],
        // A comb with collinear vertices along its base.
        vec![
            (0., 0.),
            (1., 0.),
            (2., 0.),
            (3., 0.),
            (3., 3.),
            (2.5, 1.),
            (2., 3.),
            (1.5, 1.),
            (1., 3.),
            (0.5, 1.),
            (0., 3.),
        ],
        // A square with a T-junction vertex in the middle of an edge.
        vec![(0., 0.), (0.5, 0.), (1., 0.), (1., 1.), (0., 1.)],
        vec![
            (0.1, 0.1),
            (0.7, 0.1),
            (0.7, 0.3),
            (0.3, 0.3),
            (0.3, 0.7),
            (0.7, 0.7),
            (0.7, 0.9),
            (0.1, 0.9),
        ],
    ];
    for s in shapes {
        for reverse in [false, true] {
            let mut pts: Vec<Point3> = s.iter().map(|&(x, y)| Point3::new(x, y, 0.0)).collect();
            if reverse {
                pts.reverse();
            }
            let tris = triangulate(&pts, &newell_normal(&pts)).expect("simple polygon");
            assert_eq!(
                tris.len(),
                pts.len() - 2 - collinear_dropped(&tris, pts.len())
            );
            let total = tris.iter().fold(Q::zero(), |acc, t| {
                acc + area2(&[pts[t[0]], pts[t[1]], pts[t[2]]])
            });
            // Same signed area exactly, and every triangle turns the polygon's way.
            assert_eq!(total, area2(&pts));
            for t in &tris {
                let a = area2(&[pts[t[0]], pts[t[1]], pts[t[2]]]);
                assert_eq!(a.is_positive(), area2(&pts).is_positive());
                assert!(!a.is_zero());
            }
        }
    }
}

/// Number of polygon vertices no triangle uses (none, for these shapes).
fn collinear_dropped(tris: &[[usize; 3]], n: usize) -> usize {
    n - tris
        .iter()
        .flatten()
        .collect::<std::collections::HashSet<_>>()
        .len()
}

/// The exact squared distance from `p` to the closed triangle `t` (rationals): zero inside,
/// else the least over the sides of the distance to the closed segment.
fn distance2_q(t: &[[f64; 2]; 3], p: [f64; 2]) -> Q {
    let v = |a: [f64; 2]| [q(a[0]), q(a[1])];
    let (p, t) = (v(p), t.map(v));
    let cross = |a: &[Q; 2], b: &[Q; 2], c: &[Q; 2]| {
        (&b[0] - &a[0]) * (&c[1] - &a[1]) - (&b[1] - &a[1]) * (&c[0] - &a[0])
    };
    let signs: Vec<Q> = (0..3).map(|i| cross(&t[i], &t[(i + 1) % 3], &p)).collect();
    let area = cross(&t[0], &t[1], &t[2]);
    let inside = !area.is_zero()
        && (signs.iter().all(|s| !s.is_negative()) || signs.iter().all(|s| !s.is_positive()));
    if inside {
        return Q::zero();
    }
    (0..3)
        .map(|i| {
            let (a, b) = (&t[i], &t[(i + 1) % 3]);
            let d = [&b[0] - &a[0], &b[1] - &a[1]];
            let w = [&p[0] - &a[0], &p[1] - &a[1]];
            let len2 = &d[0] * &d[0] + &d[1] * &d[1];
            let mut s = if len2.is_zero() {
                Q::zero()
            } else {
                (&w[0] * &d[0] + &w[1] * &d[1]) / &len2
            };
            if s.is_negative() {
                s = Q::zero();
            } else if s > Q::from_integer(1.into()) {
                s = Q::from_integer(1.into());
            }
            let e = [&w[0] - &s * &d[0], &w[1] - &s * &d[1]];
            &e[0] * &e[0] + &e[1] * &e[1]
        })
        .min()
        .expect("three sides")
}

/// A plane point on a small lattice scaled by `scale` and moved by `at` (so that points fall
/// exactly on sides and corners, and triangles are often flat).
fn lattice_point(scale: f64, at: f64) -> impl Strategy<Value = [f64; 2]> {
    (-4i32..=4, -4i32..=4)
        .prop_map(move |(x, y)| [at + scale * f64::from(x), at + scale * f64::from(y)])
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(3000))]

    /// The filter is never wrong: a point it calls farther than `d` is, exactly.
    #[test]
    fn surely_farther_never_rejects_a_point_within_reach(
        (scale, at) in prop::sample::select(vec![(1.0, 0.0), (1e-90, 0.0), (1e90, 0.0), (1.0, 1e8), (1e-3, -1e8), (3e-170, 0.0)]),
        k in 0usize..6,
        seed in any::<u64>(),
    ) {
        let mut r = seed;
        let mut next = || { r ^= r << 13; r ^= r >> 7; r ^= r << 17; ((r >> 11) as f64 / (1u64 << 53) as f64) * 8.0 - 4.0 };
        let mut point = |snap: bool| {
            let (x, y) = (next(), next());
            if snap { [at + scale * x.round(), at + scale * y.round()] } else { [at + scale * x, at + scale * y] }
        };
        let snap = k % 2 == 0;
        let t = [point(snap), point(snap), point(snap)];
        let p = point(snap);
        let d = scale * [0.0, 0.5, 1.0, 0.01, 2.0, 1e-9][k];
        if surely_farther(&t, p, d) {
            prop_assert!(distance2_q(&t, p) > q(d) * q(d), "{t:?} {p:?} {d}");
        }
    }

    /// On a lattice (points on sides and corners, flat triangles): never wrong either.
    #[test]
    fn surely_farther_is_exact_on_a_lattice(
        a in lattice_point(1.0, 0.0), b in lattice_point(1.0, 0.0), c in lattice_point(1.0, 0.0),
        p in lattice_point(1.0, 0.0), d in prop::sample::select(vec![0.0, 1.0, 2.0, 0.5]),
    ) {
        let t = [a, b, c];
        if surely_farther(&t, p, d) {
            prop_assert!(distance2_q(&t, p) > q(d) * q(d));
        }
    }
}

/// The filter decides the easy cases: far points are rejected, at every scale.
#[test]
fn surely_farther_rejects_far_points() {
    for (scale, at) in [(1.0, 0.0), (1e-90, 0.0), (1e90, 0.0), (1.0, 1e8)] {
        let t =
            [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]].map(|v| [at + scale * v[0], at + scale * v[1]]);
        let p = |x: f64, y: f64| [at + scale * x, at + scale * y];
        assert!(surely_farther(&t, p(3.0, 3.0), scale));
        assert!(surely_farther(&t, p(0.8, 0.8), 0.1 * scale)); // beyond the hypotenuse only
        assert!(!surely_farther(&t, p(0.8, 0.8), 0.5 * scale));
        assert!(!surely_farther(&t, p(0.2, 0.2), 0.0));
        assert!(!surely_farther(&t, p(1.0, 0.0), 0.0)); // a corner
        // A flat triangle (a segment): the box test still rejects points off its ends.
        let flat = [p(0.0, 0.0), p(1.0, 1.0), p(2.0, 2.0)];
        assert!(surely_farther(&flat, p(5.0, 5.0), scale));
        assert!(!surely_farther(&flat, p(1.5, 1.5), 0.0));
    }
}
