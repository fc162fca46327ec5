//! Tests of the exact sums and of the tribox against exact references: num-rational for
//! bounds and sums, and a brute-force intersection of the 18 half-spaces (every triple of
//! planes solved in exact integer arithmetic) for the boundary.

use std::cmp::Ordering;
use std::collections::HashMap;

use kepler::bounds::tribox::{Tribox, TriboxBounds};
use kepler::geometry::Point3;
use kepler::geometry::exact::{accurate_sum, add_round_down, add_round_up, sum_sign, two_sum};
use kepler::random::SplitMix64;
use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::{Float, Signed, ToPrimitive, Zero};
use proptest::prelude::*;

// ---------------------------------------------------------------------------------------------
// Exact references.

fn rat(x: f64) -> BigRational {
    BigRational::from_float(x).expect("finite")
}

fn exact_sum(terms: &[f64]) -> BigRational {
    terms
        .iter()
        .fold(BigRational::zero(), |acc, &t| acc + rat(t))
}

fn sign(r: &BigRational) -> Ordering {
    r.cmp(&BigRational::zero())
}

/// Whether `r` is the double nearest `exact`, ties to even.
fn is_correctly_rounded(r: f64, exact: &BigRational) -> bool {
    let two = BigRational::from_integer(BigInt::from(2));
    let err = (rat(r) - exact).abs();
    let below = (rat(r) - rat(r.next_down())) / &two;
    let above = (rat(r.next_up()) - rat(r)) / &two;
    let half = if &rat(r) > exact { below } else { above };
    err < half || (err == half && r.to_bits().is_multiple_of(2))
}

// ---------------------------------------------------------------------------------------------
// Strategies for sums.

/// A double m · 2^e with a random 53-bit mantissa and an exponent in `exp`.
fn scaled(exp: std::ops::Range<i32>) -> impl Strategy<Value = f64> {
    (any::<u64>(), exp, any::<bool>()).prop_map(|(m, e, neg)| {
        let v = ((m >> 11) as f64) * 2f64.powi(e - 52);
        if neg { -v } else { v }
    })
}

/// Terms that cancel: random terms, then some of them negated (possibly perturbed by tiny
/// terms), shuffled.
fn cancelling_terms() -> impl Strategy<Value = Vec<f64>> {
    (
        prop::collection::vec(scaled(-60..60), 1..7),
        prop::collection::vec(scaled(-200..-100), 0..4),
    )
        .prop_flat_map(|(base, tiny)| {
            let mut v = base.clone();
            v.extend(base.iter().map(|x| -x));
            v.extend(tiny);
            Just(v).prop_shuffle()
        })
}

/// Sums at or next to a half-way point between two doubles: x + ulp(x)/2, split into parts,
/// plus possibly a tiny term of either sign that breaks the tie.
fn half_way_terms() -> impl Strategy<Value = Vec<f64>> {
    (
        scaled(-40..40),
        prop_oneof![Just(0.0), scaled(-300..-100)],
        any::<bool>(),
    )
        .prop_flat_map(|(x, tiny, split)| {
            let half = (x.abs().next_up() - x.abs()) / 2.0 * x.signum();
            let mut v = if split {
                vec![0.75 * x, 0.25 * x]
            } else {
                vec![x]
            };
            v.push(half);
            v.push(tiny);
            Just(v).prop_shuffle()
        })
}

fn any_terms() -> impl Strategy<Value = Vec<f64>> {
    prop_oneof![
        half_way_terms(),
        prop::collection::vec(-1e3..1e3f64, 0..17),
        prop::collection::vec(scaled(-900..900), 0..17),
        prop::collection::vec(scaled(-1074..-1000), 0..17),
        cancelling_terms(),
    ]
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(512))]

    #[test]
    fn two_sum_is_exact(a in scaled(-500..500), b in scaled(-500..500)) {
        let (s, e) = two_sum(a, b);
        prop_assert_eq!(s, a + b);
        prop_assert_eq!(rat(s) + rat(e), rat(a) + rat(b));
    }

    #[test]
    fn directed_additions(a in scaled(-60..60), b in scaled(-120..60)) {
        let exact = rat(a) + rat(b);
        let up = add_round_up(a, b);
        let down = add_round_down(a, b);
        prop_assert!(rat(up) >= exact && rat(up.next_down()) < exact);
        prop_assert!(rat(down) <= exact && rat(down.next_up()) > exact);
    }

    #[test]
    fn sum_sign_is_exact(terms in any_terms()) {
        prop_assert_eq!(sum_sign(&terms), sign(&exact_sum(&terms)));
    }

    #[test]
    fn accurate_sum_is_correctly_rounded(terms in any_terms()) {
        let exact = exact_sum(&terms);
        let r = accurate_sum(&terms);
        prop_assert!(is_correctly_rounded(r, &exact), "{:?}: {} vs {}", terms, r, exact);
    }
}

#[test]
fn sums_with_many_terms_and_ties() {
    // Half-way cases: 1 + 2^-53 rounds to even (1), broken upward by any positive remainder.
    let h = 2f64.powi(-53);
    assert_eq!(accurate_sum(&[1.0, h, 0.0]), 1.0);
    assert_eq!(accurate_sum(&[1.0, h, 2f64.powi(-300)]), 1.0f64.next_up());
    assert_eq!(sum_sign(&[1.0, h, -1.0, -h]), Ordering::Equal);
    // 40 terms (beyond the stack buffer of the exact path).
    let mut t: Vec<f64> = (0..20).map(|i| 1.1f64.powi(i) * 1e10).collect();
    t.extend((0..20).map(|i| -(1.1f64.powi(i) * 1e10)));
    assert_eq!(sum_sign(&t), Ordering::Equal);
    t.push(-1e-300);
    assert_eq!(sum_sign(&t), Ordering::Less);
    assert_eq!(accurate_sum(&t), -1e-300);
}

// ---------------------------------------------------------------------------------------------
// Exact tribox bounds.

const DIRS: [[i64; 3]; 9] = [
    [1, 0, 0],
    [0, 1, 0],
    [0, 0, 1],
    [1, 1, 0],
    [1, 0, 1],
    [0, 1, 1],
    [1, 0, -1],
    [-1, 1, 0],
    [0, -1, 1],
];

/// Outward normal of plane j: −d for the minimum (j = 2d), +d for the maximum (j = 2d + 1).
fn normal(j: usize) -> [i64; 3] {
    let d = DIRS[j / 2];
    if j % 2 == 1 { d } else { d.map(|c| -c) }
}

fn projection(p: &Point3, d: usize) -> BigRational {
    let c = [p.x, p.y, p.z];
    (0..3).fold(BigRational::zero(), |acc, i| {
        acc + rat(c[i]) * BigRational::from_integer(DIRS[d][i].into())
    })
}

fn check_bounds(points: &[Point3], b: &TriboxBounds) -> Result<(), TestCaseError> {
    for p in points {
        prop_assert!(b.contains_point(p), "{:?} not in {:?}", p, b);
    }
    for d in 0..9 {
        let proj: Vec<BigRational> = points.iter().map(|p| projection(p, d)).collect();
        let lo = proj.iter().min().expect("nonempty");
        let hi = proj.iter().max().expect("nonempty");
        let (mn, mx) = (b.min()[d], b.max()[d]);
        // The bound is the exact extreme rounded outward: at or beyond it, and the next double
        // inward is strictly inside.
        prop_assert!(
            &rat(mx) >= hi && &rat(mx.next_down()) < hi,
            "max {} {}",
            d,
            mx
        );
        prop_assert!(
            &rat(mn) <= lo && &rat(mn.next_up()) > lo,
            "min {} {}",
            d,
            mn
        );
        if d < 3 {
            prop_assert!(&rat(mx) == hi && &rat(mn) == lo);
        }
    }
    Ok(())
}

// ---------------------------------------------------------------------------------------------
// Point set strategies, including degenerate ones.

fn pt(c: [f64; 3]) -> Point3 {
    Point3::new(c[0], c[1], c[2])
}

fn random_cloud() -> impl Strategy<Value = Vec<Point3>> {
    prop::collection::vec(prop::array::uniform3(-10.0..10.0f64), 1..25)
        .prop_map(|v| v.into_iter().map(pt).collect())
}

/// Points of a small integer grid (many ties, every sum exact), possibly scaled by 0.1 (sums
/// rounded).
fn grid_cloud() -> impl Strategy<Value = Vec<Point3>> {
    (
        prop::collection::vec(prop::array::uniform3(-3i32..=3), 1..12),
        prop_oneof![Just(1.0), Just(0.1), Just(0.7)],
    )
        .prop_map(|(v, s)| v.into_iter().map(|c| pt(c.map(|k| k as f64 * s))).collect())
}

/// Collinear points a + t·d (integers: exactly collinear; with a float offset).
fn collinear_cloud() -> impl Strategy<Value = Vec<Point3>> {
    (
        prop::array::uniform3(-5i32..=5),
        prop::array::uniform3(-2i32..=2),
        prop::collection::vec(-4i32..=4, 1..6),
        prop_oneof![Just(0.0), Just(0.1), Just(1e-9)],
    )
        .prop_map(|(a, d, ts, off)| {
            ts.into_iter()
                .map(|t| pt(std::array::from_fn(|i| (a[i] + t * d[i]) as f64 + off)))
                .collect()
        })
}

/// Coplanar points: on z = c, or on x + y = c, or on x − z = c.
fn coplanar_cloud() -> impl Strategy<Value = Vec<Point3>> {
    (
        prop::collection::vec(prop::array::uniform2(-4i32..=4), 1..10),
        0usize..3,
        -3i32..=3,
        prop_oneof![Just(1.0), Just(0.1)],
    )
        .prop_map(|(uv, kind, c, s)| {
            uv.into_iter()
                .map(|[u, v]| {
                    let (u, v, c) = (u as f64 * s, v as f64 * s, c as f64 * s);
                    match kind {
                        0 => pt([u, v, c]),
                        1 => pt([u, c - u, v]),
                        _ => pt([u, v, u - c]),
                    }
                })
                .collect()
        })
}

fn any_cloud() -> impl Strategy<Value = Vec<Point3>> {
    prop_oneof![
        random_cloud(),
        grid_cloud(),
        collinear_cloud(),
        coplanar_cloud(),
        prop::array::uniform3(-1e3..1e3f64).prop_map(|c| vec![pt(c)]),
    ]
}

// ---------------------------------------------------------------------------------------------
// Brute force: the intersection of the 18 half-spaces n_j · x ≤ β_j, exactly.

/// The 18 offsets scaled to integers: β_j = offs[j] · 2^exp.
struct ExactOffsets {
    offs: Vec<BigInt>,
    exp: i32,
}

fn exact_offsets(b: &TriboxBounds) -> ExactOffsets {
    let a = b.to_array18();
    let beta: Vec<f64> = (0..18)
        .map(|j| if j % 2 == 0 { -a[j] } else { a[j] })
        .collect();
    let parts: Vec<(BigInt, i32)> = beta
        .iter()
        .map(|&x| {
            let (m, e, s) = x.integer_decode();
            let m = BigInt::from(m) * BigInt::from(s);
            (m, e as i32)
        })
        .collect();
    let exp = parts.iter().map(|p| p.1).min().expect("18");
    let offs = parts
        .into_iter()
        .map(|(m, e)| m << ((e - exp) as usize))
        .collect();
    ExactOffsets { offs, exp }
}

/// A vertex of the brute-force polytope, in units of 2^(exp − 1): x = y · 2^(exp − 1).
type Exact3 = [BigInt; 3];

struct Brute {
    vertices: Vec<Exact3>,
    /// Per plane, its vertices (indices), counter-clockwise from outside; empty unless the face
    /// has positive area.
    faces: Vec<Vec<usize>>,
    /// 6 · volume in units of 2^(3 (exp − 1)).
    six_volume: BigInt,
    exp: i32,
}

fn det3(m: &[[i64; 3]; 3]) -> i64 {
    m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1])
        - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
        + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0])
}

fn dot(n: &[i64; 3], y: &Exact3) -> BigInt {
    (0..3).fold(BigInt::zero(), |acc, i| acc + &y[i] * n[i])
}

fn brute_force(b: &TriboxBounds) -> Brute {
    let ex = exact_offsets(b);
    let twice: Vec<BigInt> = ex.offs.iter().map(|o| o * 2).collect();
    let mut vertices: Vec<Exact3> = Vec::new();
    for a in 0..18 {
        for bb in a + 1..18 {
            for c in bb + 1..18 {
                let m = [normal(a), normal(bb), normal(c)];
                let det = det3(&m);
                if det == 0 {
                    continue;
                }
                assert!(det.abs() <= 2, "tribox determinants are ±1 or ±2");
                // y = 2 x = (2 / det) · adj(m) · β, with the cofactors by cyclic indices.
                let rhs = [&ex.offs[a], &ex.offs[bb], &ex.offs[c]];
                let y: Exact3 = std::array::from_fn(|i| {
                    let (i1, i2) = ((i + 1) % 3, (i + 2) % 3);
                    let num = (0..3).fold(BigInt::zero(), |acc, k| {
                        let (k1, k2) = ((k + 1) % 3, (k + 2) % 3);
                        let cof = m[k1][i1] * m[k2][i2] - m[k1][i2] * m[k2][i1];
                        acc + rhs[k] * cof
                    });
                    num * (2 / det)
                });
                if (0..18).all(|j| dot(&normal(j), &y) <= twice[j]) {
                    vertices.push(y);
                }
            }
        }
    }
    vertices.sort();
    vertices.dedup();

    let mut faces = Vec::new();
    let mut six_volume = BigInt::zero();
    for (j, tw) in twice.iter().enumerate() {
        let n = normal(j);
        let on: Vec<usize> = (0..vertices.len())
            .filter(|&v| &dot(&n, &vertices[v]) == tw)
            .collect();
        let loop_ = order_face(&n, &on, &vertices);
        for i in 1..loop_.len().saturating_sub(1) {
            let (p, q, r) = (
                &vertices[loop_[0]],
                &vertices[loop_[i]],
                &vertices[loop_[i + 1]],
            );
            six_volume += det_big(p, q, r);
        }
        faces.push(loop_);
    }
    Brute {
        vertices,
        faces,
        six_volume,
        exp: ex.exp,
    }
}

fn det_big(p: &Exact3, q: &Exact3, r: &Exact3) -> BigInt {
    &p[0] * (&q[1] * &r[2] - &q[2] * &r[1]) - &p[1] * (&q[0] * &r[2] - &q[2] * &r[0])
        + &p[2] * (&q[0] * &r[1] - &q[1] * &r[0])
}

/// Orders the vertices of a face counter-clockwise seen from outside (normal n), or returns
/// an empty loop if they do not span a positive area.
fn order_face(n: &[i64; 3], on: &[usize], vs: &[Exact3]) -> Vec<usize> {
    if on.len() < 3 {
        return Vec::new();
    }
    let k = (0..3).find(|&i| n[i] != 0).expect("nonzero normal");
    let (u, w) = ((k + 1) % 3, (k + 2) % 3);
    let cnt = BigInt::from(on.len());
    let su: BigInt = on.iter().map(|&v| vs[v][u].clone()).sum();
    let sw: BigInt = on.iter().map(|&v| vs[v][w].clone()).sum();
    // Coordinates relative to the centroid, scaled by the vertex count.
    let rel: Vec<(usize, BigInt, BigInt)> = on
        .iter()
        .map(|&v| (v, &vs[v][u] * &cnt - &su, &vs[v][w] * &cnt - &sw))
        .collect();
    let upper = |x: &BigInt, y: &BigInt| y.is_positive() || (y.is_zero() && x.is_positive());
    let mut sorted = rel;
    sorted.sort_by(|a, b| {
        let (ua, ub) = (upper(&a.1, &a.2), upper(&b.1, &b.2));
        if ua != ub {
            return ub.cmp(&ua);
        }
        let cross = &a.1 * &b.2 - &a.2 * &b.1;
        BigInt::zero().cmp(&cross)
    });
    let area: BigInt = (0..sorted.len())
        .map(|i| {
            let (a, b) = (&sorted[i], &sorted[(i + 1) % sorted.len()]);
            &a.1 * &b.2 - &a.2 * &b.1
        })
        .sum();
    if area.is_zero() {
        return Vec::new();
    }
    let mut out: Vec<usize> = sorted.into_iter().map(|r| r.0).collect();
    if n[k] < 0 {
        out.reverse();
    }
    out
}

fn exact_coord(y: &BigInt, exp: i32) -> BigRational {
    let v = BigRational::from_integer(y.clone());
    let e = exp - 1;
    let two = BigRational::from_integer(BigInt::from(2));
    if e >= 0 {
        v * two.pow(e)
    } else {
        v / two.pow(-e)
    }
}

fn brute_point(y: &Exact3, exp: i32) -> [f64; 3] {
    std::array::from_fn(|i| exact_coord(&y[i], exp).to_f64().expect("finite"))
}

fn brute_volume(br: &Brute) -> f64 {
    let e = 3 * (br.exp - 1);
    let two = BigRational::from_integer(BigInt::from(2));
    let s = BigRational::from_integer(br.six_volume.clone()) / BigRational::from_integer(6.into());
    let v = if e >= 0 {
        s * two.pow(e)
    } else {
        s / two.pow(-e)
    };
    v.to_f64().expect("finite")
}

/// Scale of a tribox: the largest magnitude of an axis bound (at least 1e-300).
fn scale(b: &TriboxBounds) -> f64 {
    (0..3)
        .map(|d| b.min()[d].abs().max(b.max()[d].abs()))
        .fold(1e-300, f64::max)
}

fn near(p: &[f64; 3], q: &Point3, tol: f64) -> bool {
    (0..3).all(|i| (p[i] - q[i]).abs() <= tol)
}

/// Whether every sum the bounds were made of is exact (then the bounds are attained, the
/// tribox is exactly the intersection and everything must match exactly).
fn exact_bounds(points: &[Point3]) -> bool {
    points.iter().all(|p| {
        [
            (p.x, p.y),
            (p.x, p.z),
            (p.y, p.z),
            (p.x, -p.z),
            (p.y, -p.x),
            (p.z, -p.y),
        ]
        .iter()
        .all(|&(a, b)| two_sum(a, b).1 == 0.0)
    })
}

/// Checks the cleaned boundary of the tribox of `points` against the brute force.
fn check_boundary(points: &[Point3]) -> Result<(), TestCaseError> {
    let b = TriboxBounds::from_points(points);
    let raw = b.boundary();
    let t = raw.cleaned();
    let br = brute_force(&b);
    let s = scale(&b);
    let tol = 1e-12 * s;
    let bp: Vec<[f64; 3]> = br.vertices.iter().map(|y| brute_point(y, br.exp)).collect();

    // Raw vertices (the paper's algorithm on the rounded bounds) are near the polytope's.
    for v in raw.vertices() {
        prop_assert!(bp.iter().any(|q| near(q, v, tol)), "raw vertex {:?} off", v);
    }
    for q in &bp {
        prop_assert!(
            raw.vertices().iter().any(|v| near(q, v, tol)),
            "raw misses {:?}",
            q
        );
    }

    // The cleaned boundary is the exact polytope: its vertices are the exact vertices, each
    // coordinate correctly rounded (one to one), and its faces are the brute force's faces
    // with the same vertices in the same cyclic order.
    let exact_vertices: Vec<[BigRational; 3]> = br
        .vertices
        .iter()
        .map(|y| std::array::from_fn(|i| exact_coord(&y[i], br.exp)))
        .collect();
    let same = |p: &Point3, q: &[BigRational; 3]| (0..3).all(|i| is_correctly_rounded(p[i], &q[i]));
    let key = |p: &[f64; 3]| p.map(f64::to_bits);
    let mut rounded: Vec<[u64; 3]> = Vec::new();
    for q in &exact_vertices {
        let r: [f64; 3] = std::array::from_fn(|i| q[i].to_f64().expect("finite"));
        prop_assert!((0..3).all(|i| is_correctly_rounded(r[i], &q[i])));
        rounded.push(key(&r));
    }
    let mut mine: Vec<[u64; 3]> = t.vertices().iter().map(|v| key(&[v.x, v.y, v.z])).collect();
    rounded.sort_unstable();
    mine.sort_unstable();
    prop_assert_eq!(mine, rounded, "vertices {:?} vs {:?}", t.vertices(), bp);
    let brute_faces = br.faces.iter().filter(|f| !f.is_empty()).count();
    prop_assert_eq!(t.face_count(), brute_faces);
    for j in 0..18 {
        let mine: Vec<Point3> = t
            .face(j)
            .iter()
            .map(|&v| t.vertices()[v as usize])
            .collect();
        let theirs: Vec<&[BigRational; 3]> =
            br.faces[j].iter().map(|&v| &exact_vertices[v]).collect();
        prop_assert_eq!(mine.len(), theirs.len(), "face {}", j);
        // Same cyclic order (two exact vertices may round to the same doubles: try every
        // alignment).
        let aligned = mine.is_empty()
            || (0..theirs.len()).any(|shift| {
                mine.iter()
                    .enumerate()
                    .all(|(i, p)| same(p, theirs[(i + shift) % theirs.len()]))
            });
        prop_assert!(aligned, "face {} order", j);
    }
    // Each vertex's planes have independent normals and pass exactly through it (n · x = β
    // for the exact vertex it rounds).
    let beta_exact: Vec<BigRational> = b
        .to_array18()
        .iter()
        .enumerate()
        .map(|(j, &a)| if j % 2 == 0 { -rat(a) } else { rat(a) })
        .collect();
    let on_plane = |q: &[BigRational; 3], j: usize| {
        let n = normal(j);
        let lhs = (0..3).fold(BigRational::zero(), |acc, i| {
            acc + &q[i] * BigRational::from_integer(n[i].into())
        });
        lhs == beta_exact[j]
    };
    for (v, planes) in t.vertices().iter().zip(t.vertex_planes()) {
        let rows = planes.map(|j| normal(j as usize));
        prop_assert!(det3(&rows) != 0, "dependent planes {:?}", planes);
        let ok = exact_vertices
            .iter()
            .filter(|q| same(v, q))
            .any(|q| planes.iter().all(|&j| on_plane(q, j as usize)));
        prop_assert!(ok, "vertex {:?} not on its planes {:?}", v, planes);
    }

    // Faces: on their plane, convex and counter-clockwise seen from outside.
    let beta = {
        let a = b.to_array18();
        (0..18)
            .map(|j| if j % 2 == 0 { -a[j] } else { a[j] })
            .collect::<Vec<_>>()
    };
    for (j, f) in t.faces() {
        prop_assert!(f.len() >= 3);
        let n = Tribox::PLANE_NORMALS[j];
        let nv = nalgebra::Vector3::new(n[0], n[1], n[2]);
        for &v in f {
            let p = t.vertices()[v as usize];
            prop_assert!(
                (nv.dot(&p.coords) - beta[j]).abs() <= 4.0 * tol,
                "off plane {}",
                j
            );
        }
        for i in 0..f.len() {
            let a = t.vertices()[f[i] as usize];
            let b2 = t.vertices()[f[(i + 1) % f.len()] as usize];
            let c = t.vertices()[f[(i + 2) % f.len()] as usize];
            let turn = (b2 - a).cross(&(c - b2)).dot(&nv);
            prop_assert!(turn >= -tol * s, "face {} not convex/ccw: {}", j, turn);
        }
    }

    // Closed, oriented surface: every directed edge once, with its reverse.
    let mut edges: HashMap<(u8, u8), usize> = HashMap::new();
    for (_, f) in t.faces() {
        for i in 0..f.len() {
            *edges.entry((f[i], f[(i + 1) % f.len()])).or_default() += 1;
        }
    }
    for (&(a, c), &k) in &edges {
        prop_assert_eq!(k, 1, "edge {:?} repeated", (a, c));
        prop_assert!(
            edges.contains_key(&(c, a)),
            "edge {:?} without its twin",
            (a, c)
        );
    }
    let v = t.vertices().len() as i64;
    let e = edges.len() as i64 / 2;
    let fc = t.face_count() as i64;
    if fc > 0 {
        prop_assert_eq!(v - e + fc, 2, "Euler characteristic");
    }

    // Volume.
    let vb = brute_volume(&br);
    let vt = t.volume();
    prop_assert!(
        (vt - vb).abs() <= 1e-12 * vb.abs() + 1e-13 * s * s * s,
        "volume {} vs {}",
        vt,
        vb
    );
    prop_assert!((raw.volume() - vb).abs() <= 1e-12 * vb.abs() + 1e-13 * s * s * s);
    Ok(())
}

/// Whether `p` satisfies the 18 inequalities, in exact arithmetic.
fn contains_exactly(b: &TriboxBounds, p: &Point3) -> bool {
    (0..9).all(|d| {
        let x = projection(p, d);
        rat(b.min()[d]) <= x && x <= rat(b.max()[d])
    })
}

/// Query points on, just inside and just outside the bounding planes: the cloud's points moved
/// by one or two ulps per coordinate, and sums that round onto a bound.
fn near_boundary(points: &[Point3], moves: &[[i8; 3]]) -> Vec<Point3> {
    let step = |x: f64, k: i8| match k {
        -2 => x.next_down().next_down(),
        -1 => x.next_down(),
        1 => x.next_up(),
        2 => x.next_up().next_up(),
        _ => x,
    };
    points
        .iter()
        .zip(moves.iter().cycle())
        .map(|(p, m)| Point3::new(step(p.x, m[0]), step(p.y, m[1]), step(p.z, m[2])))
        .collect()
}

// ---------------------------------------------------------------------------------------------
// Properties.

proptest! {
    #![proptest_config(ProptestConfig::with_cases(200))]

    #[test]
    fn bounds_are_exact_extremes_rounded_outward(points in any_cloud()) {
        let b = TriboxBounds::from_points(&points);
        check_bounds(&points, &b)?;
        prop_assert_eq!(TriboxBounds::par_from_points(&points), b);
        let (l, r) = points.split_at(points.len() / 2);
        let u = TriboxBounds::from_points(l).union(&TriboxBounds::from_points(r));
        prop_assert_eq!(u, b);
    }

    #[test]
    fn contains_point_is_exact(
        points in any_cloud(),
        moves in prop::collection::vec(prop::array::uniform3(-2i8..=2), 1..8),
    ) {
        let b = TriboxBounds::from_points(&points);
        for q in near_boundary(&points, &moves) {
            prop_assert_eq!(b.contains_point(&q), contains_exactly(&b, &q), "{:?}", q);
        }
    }

    #[test]
    fn boundary_matches_brute_force(points in any_cloud()) {
        check_boundary(&points)?;
    }

    #[test]
    fn intersects_matches_exact_slabs(a in any_cloud(), b in any_cloud(), shift in -3i32..=3) {
        let b: Vec<Point3> = b.iter().map(|p| Point3::new(p.x + shift as f64, p.y, p.z)).collect();
        let (ta, tb) = (TriboxBounds::from_points(&a), TriboxBounds::from_points(&b));
        let overlap = (0..9).all(|d| {
            let pa: Vec<BigRational> = a.iter().map(|p| projection(p, d)).collect();
            let pb: Vec<BigRational> = b.iter().map(|p| projection(p, d)).collect();
            pa.iter().min() <= pb.iter().max() && pb.iter().min() <= pa.iter().max()
        });
        let got = ta.intersects(&tb);
        prop_assert_eq!(got, tb.intersects(&ta));
        if overlap {
            prop_assert!(got);
        } else if exact_bounds(&a) && exact_bounds(&b) {
            prop_assert!(!got);
        }
    }

    #[test]
    fn simplified_contains_and_has_no_more_faces(points in any_cloud(), tol in 0.0..2.0f64) {
        let b = TriboxBounds::from_points(&points);
        let t = b.boundary().cleaned();
        let s = t.simplified(tol);
        prop_assert!(s.face_count() <= t.face_count());
        for p in &points {
            prop_assert!(s.bounds().contains_point(p));
        }
        for d in 0..9 {
            prop_assert!(s.bounds().min()[d] <= b.min()[d] && s.bounds().max()[d] >= b.max()[d]);
        }
        prop_assert!(s.volume() >= t.volume() - 1e-9 * scale(&b).powi(3));
    }
}

// ---------------------------------------------------------------------------------------------
// Singular and hand-computed cases.

fn unit_box(lo: [f64; 3], hi: [f64; 3]) -> Vec<Point3> {
    (0..8)
        .map(|i| {
            pt(std::array::from_fn(|k| {
                if (i >> k) & 1 == 0 { lo[k] } else { hi[k] }
            }))
        })
        .collect()
}

#[test]
fn bounds_of_many_points_across_blocks_and_threads() {
    // Coordinates whose sums round: equal rounded sums with exact errors of both signs, spread
    // over many blocks and rayon chunks, in several orders.
    let vals = [
        0.1,
        0.2,
        0.3,
        0.7,
        0.6,
        0.4,
        -0.1,
        -0.3,
        1.0 / 3.0,
        2.0 / 3.0,
    ];
    let mut pts: Vec<Point3> = (0..5000)
        .map(|i| pt([vals[i % 10], vals[(i / 10) % 10], vals[(i / 100) % 10]]))
        .collect();
    let b = TriboxBounds::from_points(&pts);
    check_bounds(&pts, &b).unwrap();
    let key = |p: &Point3| (p.x + p.y, p.y - p.x, p.z - p.y);
    pts.sort_by(|p, q| key(p).partial_cmp(&key(q)).unwrap());
    assert_eq!(TriboxBounds::from_points(&pts), b);
    pts.reverse();
    assert_eq!(TriboxBounds::from_points(&pts), b);
    let many: Vec<Point3> = (0..40).flat_map(|_| pts.iter().copied()).collect();
    assert_eq!(TriboxBounds::par_from_points(&many), b);
    assert_eq!(TriboxBounds::from_points(&many), b);

    // max (x + y) rounds to 1 at two points in different blocks: exactly 1, and 1 + 2^-54
    // (rounded down). The bound must be the next double above 1 whatever their order.
    let above = pt([1.0, 2f64.powi(-54), 0.0]);
    let exact = pt([1.0, 0.0, 0.0]);
    for (first, second) in [(above, exact), (exact, above)] {
        let mut pts = vec![pt([0.5, 0.25, 0.0]); 5000];
        pts[0] = first;
        pts[4000] = second;
        let b = TriboxBounds::from_points(&pts);
        assert_eq!(b.max()[3], 1.0f64.next_up());
        check_bounds(&pts, &b).unwrap();
        let many: Vec<Point3> = (0..20).flat_map(|_| pts.iter().copied()).collect();
        assert_eq!(TriboxBounds::par_from_points(&many), b);
    }
}

#[test]
fn contains_point_decides_rounded_sums_exactly() {
    // max (x + y) = 1 exactly; 1 + 2^-60 rounds to 1 but is outside, 1 - 2^-53 + 2^-60 inside.
    let b = TriboxBounds::from_points(&[
        pt([1.0, 0.0, 0.0]),
        pt([0.0, 1.0, 0.0]),
        pt([0.0, 0.0, 1.0]),
    ]);
    let t = 2f64.powi(-60);
    assert!(b.contains_point(&pt([1.0f64.next_down(), t, 0.0])));
    assert!(!b.contains_point(&pt([1.0, t, 0.0])));
    assert!(b.contains_point(&pt([1.0, 0.0, 0.0])));
    // min (y - x) = -1; -1 - 2^-60 rounds to -1 but is outside.
    assert!(!b.contains_point(&pt([1.0, -t, 0.0])));
}

#[test]
fn empty_and_single_point() {
    let e = TriboxBounds::empty();
    assert!(e.is_empty());
    let t = e.boundary();
    assert!(t.is_empty() && t.cleaned().is_empty());
    assert_eq!(
        (t.face_count(), t.volume(), t.surface_area()),
        (0, 0.0, 0.0)
    );
    assert!(!e.contains_point(&Point3::origin()));
    assert!(!e.intersects(&e));
    assert_eq!(TriboxBounds::from_points(&[]), e);

    let p = Point3::new(0.1, 0.7, -0.3);
    let b = TriboxBounds::from_points(&[p]);
    assert!(b.contains_point(&p));
    assert!(!b.contains_point(&Point3::new(0.1f64.next_up(), 0.7, -0.3)));
    let t = b.boundary();
    assert!(
        t.vertices().iter().all(|v| *v == p),
        "all bounds of one point"
    );
    let c = t.cleaned();
    assert_eq!(c.vertices(), &[p]);
    assert_eq!((c.face_count(), c.volume()), (0, 0.0));
    check_boundary(&[p]).unwrap();
    assert!(!b.contains_point(&Point3::new(f64::NAN, 0.7, -0.3)));
}

#[test]
fn axis_aligned_boxes_are_their_own_tribox() {
    for (lo, hi) in [
        ([0.0, 0.0, 0.0], [1.0, 1.0, 1.0]),
        ([0.1, 0.1, 0.1], [0.7, 0.7, 0.7]),
        ([-0.3, 0.1, 1e-5], [0.7, 0.2, 3.3]),
        ([1e8, -1e-8, 0.1], [1e8 + 0.5, 1e-8, 0.7]),
    ] {
        let pts = unit_box(lo, hi);
        let t = TriboxBounds::from_points(&pts).boundary().cleaned();
        assert_eq!(t.face_count(), 6);
        assert_eq!(t.vertices().len(), 8);
        for v in t.vertices() {
            assert!(pts.contains(v), "{v:?}");
        }
        for (j, f) in t.faces() {
            assert!(j < 6 && f.len() == 4);
        }
        let exact: f64 = (0..3).map(|k| hi[k] - lo[k]).product();
        assert!(
            (t.volume() - exact).abs() <= 1e-15 * exact.max(1.0) * 8.0,
            "{}",
            t.volume()
        );
        check_boundary(&pts).unwrap();
    }
    let t = TriboxBounds::from_points(&unit_box([0.0; 3], [1.0, 2.0, 3.0]))
        .boundary()
        .cleaned();
    assert_eq!((t.volume(), t.surface_area()), (6.0, 22.0));
}

#[test]
fn rotated_cube() {
    // The cube [-0.5, 0.5]^3 rotated 45° about z has vertices (±r, 0, ±0.5) and (0, ±r, ±0.5),
    // r = √2/2. Its 18 bounds: x, y ∈ [−r, r]; z ∈ [−0.5, 0.5]; x+y, y−x ∈ [−r, r] (attained
    // exactly: r + 0 = r); x+z, y+z, x−z, z−y ∈ [−(r + 0.5), r + 0.5] (rounded outward).
    // In the xy plane |x+y| ≤ r and |y−x| ≤ r is the square |x| + |y| ≤ r, which lies inside
    // |x|, |y| ≤ r; the four mixed chamfers are at the block's edges (redundant). So the tribox
    // is the rotated cube itself: 8 vertices, 6 faces (z min/max and the x+y, y−x slabs), and
    // volume 2 r² · 1 (= 1 up to the rounding of r).
    let r = std::f64::consts::FRAC_1_SQRT_2;
    let pts: Vec<Point3> = [(r, 0.0), (-r, 0.0), (0.0, r), (0.0, -r)]
        .iter()
        .flat_map(|&(x, y)| [pt([x, y, -0.5]), pt([x, y, 0.5])])
        .collect();
    let b = TriboxBounds::from_points(&pts);
    let a = b.to_array18();
    assert_eq!(&a[..8], &[-r, r, -r, r, -0.5, 0.5, -r, r]);
    assert_eq!((a[14], a[15]), (-r, r));
    for j in [8, 10, 12, 16] {
        assert_eq!(a[j], -add_round_up(r, 0.5));
        assert_eq!(a[j + 1], add_round_up(r, 0.5));
    }
    let t = b.boundary().cleaned();
    assert_eq!(t.vertices().len(), 8);
    assert_eq!(t.face_count(), 6);
    let planes: Vec<usize> = t.faces().map(|(j, _)| j).collect();
    assert_eq!(planes, vec![4, 5, 6, 7, 14, 15]);
    for v in t.vertices() {
        assert!(pts.contains(v));
    }
    let exact_volume = rat(r) * rat(r) * BigRational::from_integer(2.into());
    assert!((t.volume() - exact_volume.to_f64().unwrap()).abs() < 1e-15);
    assert!((t.volume() - 1.0).abs() < 1e-15);
    // Four faces √(1/2 + 1/2)... side faces are 1×1 squares, top and bottom diamonds of area 1.
    assert!((t.surface_area() - 6.0).abs() < 1e-14);
    check_boundary(&pts).unwrap();
}

#[test]
fn p_exactly_on_a_principal_plane() {
    // At corner (max x, max y, max z): α_A = 1, α_AB = α_AC = 1.5, α_BC = 1, so
    // x_p = (1.5 + 1.5 − 1) / 2 = 1 = α_A: p lies on h_A, between cases 1 and 2.
    let pts = [
        pt([1.0, 0.5, 0.5]),
        pt([0.0, 1.0, 0.0]),
        pt([0.0, 0.0, 1.0]),
        pt([0.0; 3]),
    ];
    let raw = TriboxBounds::from_points(&pts).boundary();
    assert_eq!(raw.corner_cases()[0], 1);
    check_boundary(&pts).unwrap();
    // Same, scaled by 0.1 (bounds rounded).
    let scaled: Vec<Point3> = pts
        .iter()
        .map(|p| pt([p.x * 0.1, p.y * 0.1, p.z * 0.1]))
        .collect();
    check_boundary(&scaled).unwrap();
    // And just past the plane (α_AB = α_AC = 1.6, x_p = 1.1 > α_A): case 2.
    let pts3 = [
        pt([1.0, 0.6, 0.6]),
        pt([0.0, 1.0, 0.0]),
        pt([0.0, 0.0, 1.0]),
        pt([0.0; 3]),
    ];
    assert_eq!(
        TriboxBounds::from_points(&pts3).boundary().corner_cases()[0],
        2
    );
    check_boundary(&pts3).unwrap();
}

#[test]
fn all_four_cases_occur_and_match() {
    // Deterministic pseudo-random clouds: every case appears at some corner, and each cloud
    // matches the brute force.
    let mut seen = [false; 5];
    let mut rng = SplitMix64(0x9e37_79b9_7f4a_7c15);
    let mut next = || rng.unit();
    for _ in 0..60 {
        let n = 3 + (next() * 6.0) as usize;
        let pts: Vec<Point3> = (0..n).map(|_| pt([next(), next(), next()])).collect();
        let t = TriboxBounds::from_points(&pts).boundary();
        for c in t.corner_cases() {
            seen[c as usize] = true;
        }
        check_boundary(&pts).unwrap();
    }
    assert!(seen[1] && seen[2] && seen[3] && seen[4], "{seen:?}");
}

#[test]
fn needles_and_plates() {
    // A thin needle along (1, 1, 1): the differences pin it to the segment.
    let needle: Vec<Point3> = (0..5)
        .map(|i| {
            let t = i as f64 * 0.1;
            pt([t, t, t])
        })
        .collect();
    let t = TriboxBounds::from_points(&needle).boundary().cleaned();
    assert_eq!((t.vertices().len(), t.face_count()), (2, 0));
    check_boundary(&needle).unwrap();
    // A slightly thickened needle.
    let mut thick = needle.clone();
    thick.push(pt([0.2, 0.2 + 1e-9, 0.2]));
    thick.push(pt([0.3 + 1e-9, 0.3, 0.3 - 1e-9]));
    check_boundary(&thick).unwrap();
    // A flat plate: its two sides.
    let plate = [
        pt([0.0, 0.0, 0.3]),
        pt([1.0, 0.2, 0.3]),
        pt([0.4, 1.0, 0.3]),
        pt([-0.2, 0.6, 0.3]),
    ];
    let t = TriboxBounds::from_points(&plate).boundary().cleaned();
    assert_eq!(t.volume(), 0.0);
    assert!(!t.face(4).is_empty() && !t.face(5).is_empty());
    check_boundary(&plate).unwrap();
    // A plate on the slanted plane x + y = 1.
    let slanted = [
        pt([0.0, 1.0, 0.0]),
        pt([1.0, 0.0, 0.0]),
        pt([0.3, 0.7, 1.0]),
        pt([0.9, 0.1, 0.5]),
    ];
    check_boundary(&slanted).unwrap();
}

#[test]
fn simplified_snaps_thin_faces() {
    // A box with its x = y = 1 edge shaved by 1e-4: the x + y chamfer face is a thin strip.
    let mut pts: Vec<Point3> = unit_box([0.0; 3], [1.0; 3])
        .into_iter()
        .filter(|p| p.x + p.y < 2.0)
        .collect();
    for z in [0.0, 1.0] {
        pts.push(pt([1.0, 1.0 - 1e-4, z]));
        pts.push(pt([1.0 - 1e-4, 1.0, z]));
    }
    let t = TriboxBounds::from_points(&pts).boundary().cleaned();
    assert_eq!(t.face_count(), 7);
    assert_eq!(t.simplified(1e-5).face_count(), 7); // the strip is 1e-4/√2 away
    let s = t.simplified(1e-3);
    assert_eq!(s.face_count(), 6);
    assert_eq!(s.vertices().len(), 8);
    assert_eq!(s.bounds().max()[3], 2.0);
    assert_eq!(t.simplified(-1.0).face_count(), 7);
    assert_eq!(t.simplified(f64::NAN).face_count(), 7);
}

#[test]
fn serialises_as_18_numbers() {
    let b = TriboxBounds::from_points(&[pt([1.0, 2.0, 3.0])]);
    let json = serde_json::to_string(&b).unwrap();
    let back: Vec<f64> = serde_json::from_str(&json).unwrap();
    assert_eq!(back, b.to_array18().to_vec());
}

#[test]
fn huge_and_tiny_coordinates_do_not_panic() {
    for pts in [
        vec![pt([1e308, 1e308, -1e308]), pt([-1e308, 1e308, 1e308])],
        vec![pt([1e-310, -1e-320, 5e-324]), pt([0.0, 1e-310, -1e-310])],
        vec![pt([f64::MAX, 0.0, 0.0])],
    ] {
        let b = TriboxBounds::from_points(&pts);
        let t = b.boundary();
        let _ = (t.cleaned(), t.simplified(1.0), t.volume(), t.surface_area());
        for p in &pts {
            let _ = b.contains_point(p);
        }
    }
    check_boundary(&[pt([1e-310, -1e-320, 5e-324]), pt([0.0, 1e-310, -1e-310])]).unwrap();
}
