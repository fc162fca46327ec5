//! Exact predicates and polygon triangulation against independent references.

use kepler::geometry::polygon::{is_simple, newell_normal, segments_meet, triangulate};
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
