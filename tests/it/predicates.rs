//! The orientation predicates with a point at infinity, and the eye's symbolically perturbed
//! orientation, against exact references: rational arithmetic (`BigRational`) for
//! floating-point inputs, and 128-bit integers for lattice inputs.

use kepler::geometry::predicates::{orient2d, orient3d, orient3d_at_infinity};
use kepler::geometry::predicates::{orient2d_at_infinity, project};
use kepler::geometry::{Point3, Vector3};
use kepler::views::Eye;
use num_traits::Signed;
use proptest::prelude::*;
use std::cmp::Ordering;

use crate::common::{Q, q, qsign, qsub, qv};

/// det[r; s; t] with the three vectors as rows.
fn det3(r: &[Q; 3], s: &[Q; 3], t: &[Q; 3]) -> Q {
    &r[0] * (&s[1] * &t[2] - &s[2] * &t[1]) - &r[1] * (&s[0] * &t[2] - &s[2] * &t[0])
        + &r[2] * (&s[0] * &t[1] - &s[1] * &t[0])
}

fn arr(p: &Point3) -> [f64; 3] {
    [p.x, p.y, p.z]
}

/// The definition: the sign of -det[a - c, b - c, u].
fn reference_3d(a: [f64; 3], b: [f64; 3], c: [f64; 3], u: [f64; 3]) -> Ordering {
    let (a, b, c, u) = (qv(a), qv(b), qv(c), qv(u));
    qsign(&-det3(&qsub(&a, &c), &qsub(&b, &c), &u))
}

/// Shewchuk's orient3d: the sign of det[a - d, b - d, c - d].
fn reference_orient3d(a: [f64; 3], b: [f64; 3], c: [f64; 3], d: [f64; 3]) -> Ordering {
    let (a, b, c, d) = (qv(a), qv(b), qv(c), qv(d));
    qsign(&det3(&qsub(&a, &d), &qsub(&b, &d), &qsub(&c, &d)))
}

/// The definition: the sign of -det[a - b, u].
fn reference_2d(a: [f64; 2], b: [f64; 2], u: [f64; 2]) -> Ordering {
    let (dx, dy) = (q(a[0]) - q(b[0]), q(a[1]) - q(b[1]));
    qsign(&-(dx * q(u[1]) - dy * q(u[0])))
}

fn p3(v: [f64; 3]) -> Point3 {
    Point3::new(v[0], v[1], v[2])
}

fn v3(v: [f64; 3]) -> Vector3 {
    Vector3::new(v[0], v[1], v[2])
}

/// Checks `orient3d_at_infinity` against the reference, and its symmetries: an even
/// permutation of `a, b, c` keeps the sign, an odd one flips it, and so does negating `u`.
fn check_3d(a: [f64; 3], b: [f64; 3], c: [f64; 3], u: [f64; 3]) -> Result<(), TestCaseError> {
    let expected = reference_3d(a, b, c, u);
    let (pa, pb, pc, vu) = (p3(a), p3(b), p3(c), v3(u));
    let got = orient3d_at_infinity(&pa, &pb, &pc, &vu);
    prop_assert_eq!(got, expected, "a={:?} b={:?} c={:?} u={:?}", a, b, c, u);
    prop_assert_eq!(orient3d_at_infinity(&pb, &pc, &pa, &vu), expected);
    prop_assert_eq!(orient3d_at_infinity(&pb, &pa, &pc, &vu), expected.reverse());
    prop_assert_eq!(
        orient3d_at_infinity(&pa, &pb, &pc, &-vu),
        expected.reverse()
    );
    Ok(())
}

fn check_2d(a: [f64; 2], b: [f64; 2], u: [f64; 2]) -> Result<(), TestCaseError> {
    let expected = reference_2d(a, b, u);
    prop_assert_eq!(
        orient2d_at_infinity(a, b, u),
        expected,
        "a={:?} b={:?} u={:?}",
        a,
        b,
        u
    );
    prop_assert_eq!(orient2d_at_infinity(b, a, u), expected.reverse());
    prop_assert_eq!(
        orient2d_at_infinity(a, b, [-u[0], -u[1]]),
        expected.reverse()
    );
    Ok(())
}

/// `x` moved by `k` units in the last place (towards +∞ for positive `k`). Zero stays zero:
/// subnormal inputs are outside the predicates' range (their products underflow).
fn ulps(x: f64, k: i32) -> f64 {
    if x == 0.0 {
        return x;
    }
    let mut y = x;
    for _ in 0..k.unsigned_abs() {
        y = if k > 0 { y.next_up() } else { y.next_down() };
    }
    y
}

/// The smallest magnitude (a power of ten) of the terms of a near-degenerate determinant in
/// these tests. Its value can be some 2⁻¹⁶⁰ times its terms (three coordinates each a few
/// ulps from cancelling), so terms below about 1e-260 can make the exact value smaller than
/// the smallest double: its sign is then beyond any double-precision expansion, and the
/// predicates promise exactness only "without overflow or underflow". Such cases are not
/// asked.
const SMALLEST_TERMS: i32 = -250;

fn coord() -> impl Strategy<Value = f64> {
    -10.0f64..10.0
}

fn point() -> impl Strategy<Value = [f64; 3]> {
    [coord(), coord(), coord()]
}

/// A coordinate anywhere from 1e-100 to 1e100 in magnitude, or zero.
fn wide() -> impl Strategy<Value = f64> {
    prop_oneof![
        9 => (1.0f64..10.0, -100i32..100, any::<bool>())
            .prop_map(|(m, e, s)| if s { -m } else { m } * 10f64.powi(e)),
        1 => Just(0.0),
    ]
}

/// Scales `(s, t)` for a near-degenerate case whose points have magnitude `s` and whose
/// direction has magnitude `s·t`, with the determinant's terms (about `s³t`) clear of
/// underflow (see [`SMALLEST_TERMS`]) and every coordinate at most 1e100.
fn joint_scales() -> impl Strategy<Value = (f64, f64)> {
    (
        prop_oneof![Just(99i32), Just(-100), Just(0), -100i32..=99],
        prop_oneof![Just(99i32), Just(-100), Just(0), -100i32..=99],
    )
        .prop_map(|(se, ue)| {
            let ue = ue.max(SMALLEST_TERMS - 2 * se).min(99);
            (10f64.powi(se), 10f64.powi(ue) / 10f64.powi(se))
        })
}

/// A scale for a whole case: all its coordinates near this magnitude.
fn scale() -> impl Strategy<Value = f64> {
    prop_oneof![
        Just(1e99),
        Just(1e-100),
        Just(1.0),
        (-100i32..100).prop_map(|e| 10f64.powi(e)),
    ]
}

fn small_int() -> impl Strategy<Value = f64> {
    (-1000i32..=1000).prop_map(f64::from)
}

fn int_point() -> impl Strategy<Value = [f64; 3]> {
    [small_int(), small_int(), small_int()]
}

/// A direction with some components zero: the axis-aligned fast path (one nonzero component)
/// and the general path with one zero component.
fn zeroed(u: [f64; 3], mask: u8) -> [f64; 3] {
    let mut v = u;
    for (k, c) in v.iter_mut().enumerate() {
        if mask & (1 << k) != 0 {
            *c = 0.0;
        }
    }
    v
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(1000))]

    #[test]
    fn orient3d_at_infinity_on_random_inputs(
        a in point(), b in point(), c in point(), u in point(),
    ) {
        check_3d(a, b, c, u)?;
    }

    #[test]
    fn orient3d_at_infinity_with_zero_components(
        a in point(), b in point(), c in point(), u in point(), mask in 0u8..7,
    ) {
        // mask 0 keeps u; 3, 5, 6 leave one axis (the fast path); 1, 2, 4 zero one component.
        check_3d(a, b, c, zeroed(u, mask))?;
    }

    #[test]
    fn orient3d_at_infinity_on_huge_and_tiny_inputs(
        a in [wide(), wide(), wide()], b in [wide(), wide(), wide()],
        c in [wide(), wide(), wide()], u in [wide(), wide(), wide()],
    ) {
        prop_assume!(u != [0.0; 3]);
        check_3d(a, b, c, u)?;
    }

    #[test]
    fn orient3d_at_infinity_at_one_scale(
        a in point(), b in point(), c in point(), u in point(), s in scale(), t in scale(),
    ) {
        let m = |p: [f64; 3], s: f64| p.map(|x| x * s);
        check_3d(m(a, s), m(b, s), m(c, s), m(u, t))?;
    }

    /// `u` nearly in the plane of `a, b, c`: a rounded combination of two edges, then moved
    /// by a few ulps (or not at all), some components zeroed.
    #[test]
    fn orient3d_at_infinity_near_degenerate(
        a in point(), b in point(), c in point(),
        alpha in -3.0f64..3.0, beta in -3.0f64..3.0,
        nudge in [-3i32..=3, -3i32..=3, -3i32..=3], (s, t) in joint_scales(),
    ) {
        let (a, b, c) = (a.map(|x| x * s), b.map(|x| x * s), c.map(|x| x * s));
        let u: [f64; 3] = std::array::from_fn(|k| {
            ulps((alpha * (a[k] - c[k]) + beta * (b[k] - c[k])) * t, nudge[k])
        });
        prop_assume!(u != [0.0; 3]);
        check_3d(a, b, c, u)?;
        // c nearly on the plane through a, b parallel to u.
        let c2: [f64; 3] = std::array::from_fn(|k| {
            ulps(a[k] + alpha * (b[k] - a[k]) + beta * u[k] / t, nudge[(k + 1) % 3])
        });
        check_3d(a, b, c2, u)?;
    }

    /// Axis-aligned `u` (the fast path through orient2d) with `a, b, c` nearly collinear in
    /// the projection along `u`, and `u` with one zero component.
    #[test]
    fn orient3d_at_infinity_axis_aligned_near_degenerate(
        a in point(), b in point(), z in [coord(), coord(), coord()], lambda in -3.0f64..3.0,
        nudge in -2i32..=2, axis in 0usize..3, m in -10.0f64..10.0, (s, t) in joint_scales(),
    ) {
        let length = m * s * t;
        prop_assume!(length != 0.0);
        let (a, b) = (a.map(|x| x * s), b.map(|x| x * s));
        let mut c: [f64; 3] = std::array::from_fn(|k| ulps(a[k] + lambda * (b[k] - a[k]), nudge));
        c[axis] = z[0] * s;
        let mut u = [0.0; 3];
        u[axis] = length;
        check_3d(a, b, c, u)?;
        // The same with a second, tiny, nonzero component: no longer the fast path.
        u[(axis + 1) % 3] = length * 1e-3 * z[1].signum();
        check_3d(a, b, c, u)?;
    }

    /// Exactly degenerate: `u` an integer combination of `a - c` and `b - c` (all exact, the
    /// points and `u` scaled by independent powers of two) is parallel to the plane.
    #[test]
    fn orient3d_at_infinity_exactly_degenerate(
        a in int_point(), b in int_point(), c in int_point(),
        m in -50i32..50, n in -50i32..50, e in -300i32..300, f in -300i32..300,
    ) {
        let scale = 2f64.powi(e);
        let (a, b, c) = (a.map(|x| x * scale), b.map(|x| x * scale), c.map(|x| x * scale));
        let u: [f64; 3] = std::array::from_fn(|k| {
            (f64::from(m) * (a[k] - c[k]) + f64::from(n) * (b[k] - c[k])) / scale * 2f64.powi(f)
        });
        prop_assume!(u != [0.0; 3]);
        prop_assert_eq!(orient3d_at_infinity(&p3(a), &p3(b), &p3(c), &v3(u)), Ordering::Equal);
        check_3d(a, b, c, u)?;
    }

    /// The limit definition, exactly: with integer inputs and λ a power of two, `c + λu` is
    /// exact, and orient3d(a, b, c, c + λu) = -λ det[a - c, b - c, u] has the same sign for
    /// every λ > 0, degenerate or not.
    #[test]
    fn orient3d_at_infinity_is_the_limit_of_orient3d(
        a in int_point(), b in int_point(), c in int_point(), u in int_point(),
        log_lambda in 0i32..30, mask in 0u8..7,
    ) {
        let u = zeroed(u, mask);
        prop_assume!(u != [0.0; 3]);
        let lambda = 2f64.powi(log_lambda);
        let d: [f64; 3] = std::array::from_fn(|k| c[k] + lambda * u[k]);
        let at_infinity = orient3d_at_infinity(&p3(a), &p3(b), &p3(c), &v3(u));
        prop_assert_eq!(orient3d(&p3(a), &p3(b), &p3(c), &p3(d)), at_infinity);
        prop_assert_eq!(reference_orient3d(a, b, c, d), at_infinity);
    }

    /// For moderate floating-point inputs, `c + λu` is rounded; it still agrees whenever the
    /// determinant is clearly nonzero.
    #[test]
    fn orient3d_at_infinity_agrees_with_a_far_point(
        a in point(), b in point(), c in point(), u in point(),
    ) {
        let lambda = 2f64.powi(40);
        let d: [f64; 3] = std::array::from_fn(|k| c[k] + lambda * u[k]);
        let (qa, qb, qc, qu) = (qv(a), qv(b), qv(c), qv(u));
        let det = det3(&qsub(&qa, &qc), &qsub(&qb, &qc), &qu);
        let norm = |v: &[f64; 3]| v.iter().map(|x| x.abs()).sum::<f64>();
        let size = norm(&std::array::from_fn(|k| a[k] - c[k]))
            * norm(&std::array::from_fn(|k| b[k] - c[k])) * norm(&u);
        prop_assume!(det.abs() > q(1e-6 * size));
        prop_assert_eq!(
            orient3d(&p3(a), &p3(b), &p3(c), &p3(d)),
            orient3d_at_infinity(&p3(a), &p3(b), &p3(c), &v3(u))
        );
    }

    #[test]
    fn orient2d_at_infinity_on_random_inputs(
        a in [coord(), coord()], b in [coord(), coord()], u in [coord(), coord()], mask in 0u8..4,
    ) {
        let mut u = u;
        if mask & 1 != 0 { u[0] = 0.0; }
        if mask & 2 != 0 { u[1] = 0.0; }
        check_2d(a, b, u)?;
    }

    #[test]
    fn orient2d_at_infinity_on_huge_and_tiny_inputs(
        a in [wide(), wide()], b in [wide(), wide()], u in [wide(), wide()],
    ) {
        check_2d(a, b, u)?;
    }

    /// `u` nearly parallel to `a - b`, and `a` nearly on the line through `b` along `u`.
    #[test]
    fn orient2d_at_infinity_near_degenerate(
        a in [coord(), coord()], b in [coord(), coord()], alpha in -3.0f64..3.0,
        nudge in [-3i32..=3, -3i32..=3], (s, t) in joint_scales(),
    ) {
        let (a, b) = (a.map(|x| x * s), b.map(|x| x * s));
        let u: [f64; 2] = std::array::from_fn(|k| ulps(alpha * (a[k] - b[k]) * t, nudge[k]));
        check_2d(a, b, u)?;
        let a2: [f64; 2] = std::array::from_fn(|k| ulps(b[k] + alpha * u[k] / t, nudge[1 - k]));
        check_2d(a2, b, u)?;
    }

    /// Exactly degenerate: `u` an integer multiple of the exact difference `a - b`.
    #[test]
    fn orient2d_at_infinity_exactly_degenerate(
        a in [small_int(), small_int()], b in [small_int(), small_int()],
        m in -50i32..50, e in -300i32..300,
    ) {
        let scale = 2f64.powi(e);
        let (a, b) = (a.map(|x| x * scale), b.map(|x| x * scale));
        let u = [f64::from(m) * (a[0] - b[0]), f64::from(m) * (a[1] - b[1])];
        prop_assert_eq!(orient2d_at_infinity(a, b, u), Ordering::Equal);
        check_2d(a, b, u)?;
    }

    /// orient2d_at_infinity is the limit of orient2d(a, b, b + λu), exactly for integers.
    #[test]
    fn orient2d_at_infinity_is_the_limit_of_orient2d(
        a in [small_int(), small_int()], b in [small_int(), small_int()],
        u in [small_int(), small_int()], log_lambda in 0i32..30,
    ) {
        let lambda = 2f64.powi(log_lambda);
        let far = [b[0] + lambda * u[0], b[1] + lambda * u[1]];
        prop_assert_eq!(orient2d(a, b, far), orient2d_at_infinity(a, b, u));
    }
}

#[test]
fn hand_made_signs() {
    let o = Point3::origin();
    let (x, y) = (Point3::new(1.0, 0.0, 0.0), Point3::new(0.0, 1.0, 0.0));
    // (o, x, y) is counter-clockwise seen from +z: +z is above, so a direction pointing up is
    // Less (like orient3d of a point above), one pointing down Greater.
    assert_eq!(
        orient3d_at_infinity(&o, &x, &y, &Vector3::z()),
        Ordering::Less
    );
    assert_eq!(
        orient3d_at_infinity(&o, &x, &y, &-Vector3::z()),
        Ordering::Greater
    );
    assert_eq!(
        orient3d(&o, &x, &y, &Point3::new(5.0, -3.0, 1.0)),
        Ordering::Less
    );
    // In the plane: every direction with zero z.
    for u in [
        Vector3::x(),
        Vector3::y(),
        Vector3::new(3.0, -7.0, 0.0),
        Vector3::new(1e-300, 1e300, 0.0),
    ] {
        assert_eq!(orient3d_at_infinity(&o, &x, &y, &u), Ordering::Equal);
    }
    // The smallest nonzero z decides.
    let tiny = Vector3::new(1e300, 1e300, f64::from_bits(1));
    assert_eq!(orient3d_at_infinity(&o, &x, &y, &tiny), Ordering::Less);
    // A degenerate (collinear) triangle is parallel to every direction.
    let twice = Point3::new(2.0, 0.0, 0.0);
    assert_eq!(
        orient3d_at_infinity(&o, &x, &twice, &Vector3::new(1.0, 2.0, 3.0)),
        Ordering::Equal
    );
    // 2-D: from b looking along u = +x, a above is to the left: counter-clockwise.
    assert_eq!(
        orient2d_at_infinity([0.0, 1.0], [0.0, 0.0], [1.0, 0.0]),
        Ordering::Greater
    );
    assert_eq!(
        orient2d_at_infinity([0.0, 1.0], [0.0, 0.0], [0.0, 0.0]),
        Ordering::Equal
    );
    assert_eq!(
        orient2d_at_infinity([0.1, 0.2], [0.3, 0.6], [1.0, 2.0]),
        reference_2d([0.1, 0.2], [0.3, 0.6], [1.0, 2.0])
    );
}

/// 0.1 + 0.2 in doubles is not 0.3: nearly-planar cases whose floating-point determinant is
/// wrong or zero must still get the exact sign.
#[test]
fn rounding_traps() {
    type Case = ([f64; 3], [f64; 3], [f64; 3], [f64; 3]);
    let cases: [Case; 4] = [
        (
            [0.1, 0.2, 0.3],
            [0.4, 0.5, 0.6],
            [0.7, 0.8, 0.9],
            [1.0, 1.0, 1.0],
        ),
        (
            [0.1, 0.2, 0.3],
            [0.4, 0.5, 0.6],
            [0.7, 0.8, 0.9],
            [0.3, 0.3, 0.3],
        ),
        (
            [1e15, 1.0, 0.1],
            [1e15 + 2.0, 3.0, 0.1],
            [0.0, 0.0, 0.3],
            [1.0, 1.0, 0.0],
        ),
        (
            [1e-100, 3e-100, 0.0],
            [2e-100, 6e-100, 0.0],
            [0.0, 0.0, 1.0],
            [1.0, 3.0, 1e-100],
        ),
    ];
    for (a, b, c, u) in cases {
        check_3d(a, b, c, u).unwrap();
    }
}

// ---------------------------------------------------------------------------------------------
// The eye's perturbed orientation, exhaustively on a small lattice, against 128-bit integers.

/// Lattice inputs have integer coordinates below 8 in magnitude; with ε = 2⁻²⁰, scaling by
/// 2⁶⁰ turns p' = p + (ε, ε², ε³) into integers, and every orientation fits an i128 exactly.
/// Each orientation is linear in p' with integer coefficients below 2⁷ and an integer
/// constant, so its sign at this ε is the sign of the first nonzero coefficient of
/// (1, ε, ε², ε³): the symbolic answer.
const SHIFT: u32 = 60;

type I3 = [i128; 3];

fn cross_i(s: I3, t: I3) -> I3 {
    [
        s[1] * t[2] - s[2] * t[1],
        s[2] * t[0] - s[0] * t[2],
        s[0] * t[1] - s[1] * t[0],
    ]
}

fn scaled_i(p: I3) -> I3 {
    p.map(|x| x << SHIFT)
}

fn sub_i(a: I3, b: I3) -> I3 {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn perturbed(p: [i32; 3]) -> I3 {
    let s = scaled_i(p.map(i128::from));
    [s[0] + (1 << 40), s[1] + (1 << 20), s[2] + 1]
}

#[derive(Debug, Clone, Copy)]
enum LatticeEye {
    Point([i32; 3]),
    Infinity([i32; 3]),
}

impl LatticeEye {
    fn eye(self) -> Eye {
        match self {
            LatticeEye::Point(e) => Eye::Point(point_of(e)),
            LatticeEye::Infinity(u) => Eye::Infinity(Vector3::new(
                f64::from(u[0]),
                f64::from(u[1]),
                f64::from(u[2]),
            )),
        }
    }

    /// The sign of orient3d(p', a, b, eye) with p' perturbed: det[p' - e, a - e, b - e] =
    /// (p' - e)·((a - e) × (b - e)) for a point, -det[p' - b, a - b, u] =
    /// -(p' - b)·((a - b) × u) for a point at infinity. Only p' is scaled, so the products
    /// stay below 2⁷².
    fn reference(self, p: [i32; 3], a: [i32; 3], b: [i32; 3]) -> Ordering {
        let pp = perturbed(p);
        let (a, b) = (a.map(i128::from), b.map(i128::from));
        let dot = |x: I3, y: I3| x[0] * y[0] + x[1] * y[1] + x[2] * y[2];
        let d = match self {
            LatticeEye::Point(e) => {
                let e = e.map(i128::from);
                dot(sub_i(pp, scaled_i(e)), cross_i(sub_i(a, e), sub_i(b, e)))
            }
            LatticeEye::Infinity(u) => -dot(
                sub_i(pp, scaled_i(b)),
                cross_i(sub_i(a, b), u.map(i128::from)),
            ),
        };
        d.cmp(&0)
    }

    /// Whether `a`, `b` and the eye are collinear (for a point at infinity: `b - a` parallel
    /// to the direction, or zero).
    fn collinear(self, a: [i32; 3], b: [i32; 3]) -> bool {
        let ab = sub_i(b.map(i128::from), a.map(i128::from));
        let w = match self {
            LatticeEye::Point(e) => sub_i(e.map(i128::from), a.map(i128::from)),
            LatticeEye::Infinity(u) => u.map(i128::from),
        };
        ab[1] * w[2] == ab[2] * w[1] && ab[2] * w[0] == ab[0] * w[2] && ab[0] * w[1] == ab[1] * w[0]
    }
}

fn point_of(p: [i32; 3]) -> Point3 {
    Point3::new(f64::from(p[0]), f64::from(p[1]), f64::from(p[2]))
}

fn lattice(r: i32) -> Vec<[i32; 3]> {
    let mut out = Vec::new();
    for x in -r..=r {
        for y in -r..=r {
            for z in -r..=r {
                out.push([x, y, z]);
            }
        }
    }
    out
}

fn lattice_eyes() -> Vec<LatticeEye> {
    let mut eyes = Vec::new();
    for u in lattice(1) {
        if u != [0, 0, 0] {
            eyes.push(LatticeEye::Infinity(u));
        }
    }
    for u in [[0, 0, 2], [2, -1, 0], [1, 2, -2]] {
        eyes.push(LatticeEye::Infinity(u));
    }
    for e in [
        [0, 0, 0],
        [0, 0, 2],
        [1, 1, 1],
        [2, -1, 0],
        [-2, 2, 1],
        [1, 0, -2],
    ] {
        eyes.push(LatticeEye::Point(e));
    }
    eyes
}

/// Every (p, a, b) on the lattice [-1, 1]³ against every eye: the perturbed orientation is
/// the symbolic limit, antisymmetric in (a, b), exact when p is not degenerate, and `Equal`
/// exactly when a, b and the eye are collinear.
#[test]
fn perturbed_orient3d_on_a_lattice() {
    let points = lattice(1);
    let mut nonzero_by_perturbation = 0usize;
    for le in lattice_eyes() {
        let eye = le.eye();
        for &a in &points {
            for &b in &points {
                let collinear = le.collinear(a, b);
                for &p in &points {
                    let (pp, pa, pb) = (point_of(p), point_of(a), point_of(b));
                    let s = eye.perturbed_orient3d(&pp, &pa, &pb);
                    let what = (le, p, a, b);
                    assert_eq!(s, le.reference(p, a, b), "eye, p, a, b: {what:?}");
                    let swapped = eye.perturbed_orient3d(&pp, &pb, &pa);
                    assert_eq!(s, swapped.reverse(), "eye, p, a, b: {what:?}");
                    assert_eq!(s == Ordering::Equal, collinear, "eye, p, a, b: {what:?}");
                    let exact = eye.orient3d(&pp, &pa, &pb);
                    if exact != Ordering::Equal {
                        assert_eq!(s, exact, "eye, p, a, b: {what:?}");
                    } else if s != Ordering::Equal {
                        nonzero_by_perturbation += 1;
                    }
                }
            }
        }
    }
    // The lattice is full of degenerate lines of sight: the perturbation decides many.
    assert!(
        nonzero_by_perturbation > 10_000,
        "{nonzero_by_perturbation}"
    );
}

/// The perturbation's coefficients are the projected orientations the documentation names:
/// the coefficient of ε^(k+1) is orient2d of a, b and the eye with axis k dropped.
#[test]
fn perturbation_coefficients_are_projected_orientations() {
    let points = lattice(2);
    let mut checked = 0usize;
    for le in lattice_eyes() {
        let eye = le.eye();
        for (i, &a) in points.iter().enumerate().step_by(3) {
            for &b in points.iter().skip(i % 7).step_by(5) {
                if le.collinear(a, b) {
                    continue;
                }
                let (pa, pb) = (point_of(a), point_of(b));
                // p on the line of sight through a, beyond it: a + (a - e) or a - u, exactly.
                let p = match le {
                    LatticeEye::Point(e) => [2 * a[0] - e[0], 2 * a[1] - e[1], 2 * a[2] - e[2]],
                    LatticeEye::Infinity(u) => [a[0] - u[0], a[1] - u[1], a[2] - u[2]],
                };
                let pp = point_of(p);
                assert_eq!(eye.orient3d(&pp, &pa, &pb), Ordering::Equal);
                let first = (0..3)
                    .map(|k| match le {
                        LatticeEye::Point(e) => {
                            orient2d(project(&pa, k), project(&pb, k), project(&point_of(e), k))
                        }
                        LatticeEye::Infinity(u) => orient2d_at_infinity(
                            project(&pa, k),
                            project(&pb, k),
                            project(&point_of(u), k),
                        ),
                    })
                    .find(|&o| o != Ordering::Equal)
                    .expect("not collinear");
                let s = eye.perturbed_orient3d(&pp, &pa, &pb);
                assert_eq!(s, first, "eye {le:?}, p {p:?}, a {a:?}, b {b:?}");
                assert_eq!(
                    s,
                    le.reference(p, a, b),
                    "eye {le:?}, p {p:?}, a {a:?}, b {b:?}"
                );
                checked += 1;
            }
        }
    }
    assert!(checked > 1000, "{checked}");
}

/// With floating-point (not lattice) eyes and points, the perturbed orientation is still
/// antisymmetric, and equals the exact orientation where that is not zero.
#[test]
fn perturbed_orient3d_antisymmetric_on_floats() {
    let mut rng = 0x2545_f491_4f6c_dd1du64;
    let mut next = || {
        rng ^= rng << 13;
        rng ^= rng >> 7;
        rng ^= rng << 17;
        (rng >> 11) as f64 / (1u64 << 53) as f64 * 8.0 - 4.0
    };
    for i in 0..2_000 {
        let mut r = || Point3::new(next(), next(), next());
        let (a, b, e) = (r(), r(), r());
        // p near the line from the point eye through a (rounded), or exactly at b (degenerate).
        let p = if i % 2 == 0 { a + (a - e) * 0.5 } else { b };
        for eye in [Eye::Point(e), Eye::Infinity(e.coords)] {
            let s = eye.perturbed_orient3d(&p, &a, &b);
            assert_eq!(s, eye.perturbed_orient3d(&p, &b, &a).reverse());
            assert_ne!(s, Ordering::Equal, "{eye:?} {p:?} {a:?} {b:?}");
            let (qp, qa, qb) = (qv(arr(&p)), qv(arr(&a)), qv(arr(&b)));
            let exact = match eye {
                Eye::Point(e) => {
                    let qe = qv(arr(&e));
                    qsign(&det3(&qsub(&qp, &qe), &qsub(&qa, &qe), &qsub(&qb, &qe)))
                }
                Eye::Infinity(u) => qsign(&-det3(
                    &qsub(&qp, &qb),
                    &qsub(&qa, &qb),
                    &qv([u.x, u.y, u.z]),
                )),
            };
            if !exact.is_eq() {
                assert_eq!(s, exact);
            }
        }
    }
}
