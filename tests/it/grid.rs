//! Franklin's uniform grid for segment intersection (`kepler::grid`) against a brute force
//! over all pairs with exact rational arithmetic (`BigRational`), and against geo's sweep as a
//! second oracle: random segments of mixed lengths, Franklin's experiment, lattice inputs full
//! of shared endpoints, collinear overlaps and horizontal and vertical segments, stars of
//! segments through one point, segments lying along the grid's cell boundaries, coordinates
//! far from the origin or tiny, and duplicated segments. `meeting` against the exact meeting
//! point or overlap.

use geo::algorithm::sweep::{Cross, Intersections};
use geo::{Coord, Line};
use kepler::geometry::polygon::segments_meet;
use kepler::grid::{
    Meeting, SegmentGrid, intersecting_pairs, intersections, meeting, random_segments,
};
use num_traits::Zero;
use proptest::prelude::*;
use std::cmp::Ordering;

use crate::common::{Q, SplitMix64, q, qsign};

// ---------------------------------------------------------------------------------------------
// Exact references.

fn seg(x1: f64, y1: f64, x2: f64, y2: f64) -> Line<f64> {
    Line::new(Coord { x: x1, y: y1 }, Coord { x: x2, y: y2 })
}

fn ends(s: &Line<f64>) -> [[f64; 2]; 2] {
    [[s.start.x, s.start.y], [s.end.x, s.end.y]]
}

fn xy(p: [f64; 2]) -> Coord<f64> {
    Coord { x: p[0], y: p[1] }
}

type Q2 = [Q; 2];

fn q2(p: [f64; 2]) -> Q2 {
    p.map(q)
}

fn q2sub(a: &Q2, b: &Q2) -> Q2 {
    [&a[0] - &b[0], &a[1] - &b[1]]
}

fn q2cross(u: &Q2, v: &Q2) -> Q {
    &u[0] * &v[1] - &u[1] * &v[0]
}

fn q2dot(u: &Q2, v: &Q2) -> Q {
    &u[0] * &v[0] + &u[1] * &v[1]
}

/// The exact sign of (b - a) x (c - a): `Greater` when `c` is left of `ab`. Rationals decide
/// unless a floating-point evaluation is provably right (see [`orient_float`]).
fn orient(a: [f64; 2], b: [f64; 2], c: [f64; 2]) -> Ordering {
    orient_float(a, b, c).unwrap_or_else(|| {
        let (a, b, c) = (q2(a), q2(b), q2(c));
        qsign(&q2cross(&q2sub(&b, &a), &q2sub(&c, &a)))
    })
}

/// A speed-up of the rational reference (which is slow for the brute force): the sign of the
/// floating-point determinant when it is certain, either because it is far from zero (an
/// error bound a hundred times Shewchuk's) or because every operation was exact (checked with
/// error-free transformations). `None` otherwise.
fn orient_float(a: [f64; 2], b: [f64; 2], c: [f64; 2]) -> Option<Ordering> {
    let two_sum = |x: f64, y: f64| {
        let s = x + y;
        let yy = s - x;
        (s, (x - (s - yy)) + (y - yy))
    };
    let (u0, e0) = two_sum(b[0], -a[0]);
    let (u1, e1) = two_sum(b[1], -a[1]);
    let (v0, e2) = two_sum(c[0], -a[0]);
    let (v1, e3) = two_sum(c[1], -a[1]);
    let (l, r) = (u0 * v1, u1 * v0);
    let det = l - r;
    let sum = l.abs() + r.abs();
    if !sum.is_finite() {
        return None;
    }
    if sum > 1e-250 && det.abs() > 1e-14 * sum {
        return det.partial_cmp(&0.0);
    }
    let product_exact = |x: f64, y: f64, p: f64| {
        x == 0.0 || y == 0.0 || (p.abs() > 1e-290 && x.mul_add(y, -p) == 0.0)
    };
    let exact = [e0, e1, e2, e3].iter().all(|&e| e == 0.0)
        && product_exact(u0, v1, l)
        && product_exact(u1, v0, r)
        && two_sum(l, -r).1 == 0.0;
    if exact { det.partial_cmp(&0.0) } else { None }
}

/// Whether the closed bounding boxes of `s` and `t` meet (exact in floating point).
fn boxes_meet(s: &[[f64; 2]; 2], t: &[[f64; 2]; 2]) -> bool {
    (0..2).all(|k| {
        s[0][k].min(s[1][k]) <= t[0][k].max(t[1][k]) && t[0][k].min(t[1][k]) <= s[0][k].max(s[1][k])
    })
}

/// Where two closed segments meet, exactly.
#[derive(Debug, Clone, PartialEq)]
enum Exact {
    /// A proper crossing at this rational point (interior to both segments).
    Crossing(Q2),
    /// One point, an input endpoint.
    Touch([f64; 2]),
    /// A collinear overlap of positive length between these input points, in the direction
    /// of the first segment.
    Overlap([f64; 2], [f64; 2]),
}

/// The exact reference for `meeting`: exact orientation signs, then the collinear case by
/// projection onto the common line in rationals, or the crossing point in rationals.
fn exact_meeting(s: &[[f64; 2]; 2], t: &[[f64; 2]; 2]) -> Option<Exact> {
    let pts = [s[0], s[1], t[0], t[1]];
    let o = [
        orient(s[0], s[1], t[0]),
        orient(s[0], s[1], t[1]),
        orient(t[0], t[1], s[0]),
        orient(t[0], t[1], s[1]),
    ];
    let zero = Ordering::Equal;
    if o.iter().all(|&x| x == zero) {
        // Collinear (or degenerate): project on the common line.
        if s[0] == s[1] && t[0] == t[1] {
            return (s[0] == t[0]).then_some(Exact::Touch(s[0]));
        }
        let [a, b, c, d] = pts.map(q2);
        let v = if s[0] != s[1] {
            q2sub(&b, &a)
        } else {
            q2sub(&d, &c)
        };
        let along: Vec<Q> = [&a, &b, &c, &d]
            .iter()
            .map(|p| q2dot(&q2sub(p, &a), &v))
            .collect();
        let (s_lo, s_hi) = minmax(&along[0], &along[1]);
        let (t_lo, t_hi) = minmax(&along[2], &along[3]);
        let lo = if s_lo >= t_lo { s_lo } else { t_lo };
        let hi = if s_hi <= t_hi { s_hi } else { t_hi };
        let at = |x: &Q| pts[along.iter().position(|y| y == x).expect("an input point")];
        return match lo.cmp(hi) {
            Ordering::Less => Some(Exact::Overlap(at(lo), at(hi))),
            Ordering::Equal => Some(Exact::Touch(at(lo))),
            Ordering::Greater => None,
        };
    }
    let straddles = |x: Ordering, y: Ordering| x != y || x == zero;
    if !(straddles(o[0], o[1]) && straddles(o[2], o[3])) {
        return None;
    }
    // Not all collinear and they meet: both segments are proper and their lines distinct, so
    // an endpoint on the other's line is the meeting point.
    if let Some(k) = o.iter().position(|&x| x == zero) {
        return Some(Exact::Touch([t[0], t[1], s[0], s[1]][k]));
    }
    let [a, b, c, d] = pts.map(q2);
    // a + u (b - a) with u = (a - c) x (d - c) / ((d - c) x (b - a)).
    let dc = q2sub(&d, &c);
    let ba = q2sub(&b, &a);
    let u = q2cross(&q2sub(&a, &c), &dc) / q2cross(&dc, &ba);
    Some(Exact::Crossing([&a[0] + &u * &ba[0], &a[1] + &u * &ba[1]]))
}

fn minmax<'a>(x: &'a Q, y: &'a Q) -> (&'a Q, &'a Q) {
    if x <= y { (x, y) } else { (y, x) }
}

/// Whether two closed segments share a point, exactly: exact orientation signs, the collinear
/// case by the (exact) bounding boxes.
fn exact_meets(s: &[[f64; 2]; 2], t: &[[f64; 2]; 2]) -> bool {
    if !boxes_meet(s, t) {
        return false;
    }
    let o = [
        orient(s[0], s[1], t[0]),
        orient(s[0], s[1], t[1]),
        orient(t[0], t[1], s[0]),
        orient(t[0], t[1], s[1]),
    ];
    let zero = Ordering::Equal;
    if o.iter().all(|&x| x == zero) {
        // Collinear points: the segments meet exactly when their boxes do.
        return true;
    }
    let straddles = |x: Ordering, y: Ordering| x != y || x == zero;
    straddles(o[0], o[1]) && straddles(o[2], o[3])
}

/// Every pair `i < j` that meets, by brute force with exact arithmetic.
fn brute(segments: &[Line<f64>]) -> Vec<(usize, usize)> {
    let e: Vec<[[f64; 2]; 2]> = segments.iter().map(ends).collect();
    let mut pairs = Vec::new();
    for i in 0..e.len() {
        for j in i + 1..e.len() {
            if exact_meets(&e[i], &e[j]) {
                pairs.push((i, j));
            }
        }
    }
    pairs
}

/// A segment tagged with its index, for geo's sweep.
#[derive(Debug, Clone)]
struct Tagged(usize, Line<f64>);

impl Cross for Tagged {
    type Scalar = f64;

    fn line(&self) -> Line<f64> {
        self.1
    }
}

/// The pairs geo's sweep finds (each must come once).
fn geo_pairs(segments: &[Line<f64>]) -> Vec<(usize, usize)> {
    let mut pairs: Vec<(usize, usize)> =
        Intersections::from_iter(segments.iter().enumerate().map(|(i, &s)| Tagged(i, s)))
            .map(|(a, b, _)| (a.0.min(b.0), a.0.max(b.0)))
            .collect();
    pairs.sort_unstable();
    let n = pairs.len();
    pairs.dedup();
    assert_eq!(pairs.len(), n, "geo's sweep reported a pair twice");
    pairs
}

/// The grid's pairs, through both entry points, checked against the brute force; returns them.
fn check(segments: &[Line<f64>], what: &str) -> Vec<(usize, usize)> {
    let expected = brute(segments);
    check_against(segments, &expected, what);
    expected
}

/// The grid's pairs, through both entry points, checked against `expected`.
fn check_against(segments: &[Line<f64>], expected: &[(usize, usize)], what: &str) {
    let found = intersecting_pairs(segments);
    if found != expected {
        let missed: Vec<_> = expected.iter().filter(|p| !found.contains(p)).collect();
        let extra: Vec<_> = found.iter().filter(|p| !expected.contains(p)).collect();
        panic!(
            "{what}: {} pairs found, {} expected; missed {:?}, extra {:?}",
            found.len(),
            expected.len(),
            &missed[..missed.len().min(10)],
            &extra[..extra.len().min(10)],
        );
    }
    let grid = SegmentGrid::new(segments);
    assert_eq!(grid.pairs(), expected, "{what}: SegmentGrid::pairs");
    let [cx, cy] = grid.shape();
    assert!(cx >= 1 && cy >= 1, "{what}: shape {:?}", grid.shape());
    assert!(
        (cx * cy) as f64 <= 4.0 * segments.len().max(1) as f64 + 1.0,
        "{what}: {cx}x{cy} cells for {} segments",
        segments.len()
    );
    if !segments.is_empty() {
        assert!(
            grid.cells_per_segment() >= 1.0,
            "{what}: every segment has a cell"
        );
    }
}

/// `meeting` for one pair, in both orders, against the exact reference and against
/// `segments_meet`.
fn check_meeting(s: &Line<f64>, t: &Line<f64>) {
    check_meeting_in_order(s, t);
    check_meeting_in_order(t, s);
}

fn check_meeting_in_order(s: &Line<f64>, t: &Line<f64>) {
    let (e, f) = (ends(s), ends(t));
    let got = meeting(s, t);
    let want = exact_meeting(&e, &f);
    assert_eq!(
        got.is_some(),
        segments_meet(e[0], e[1], f[0], f[1]),
        "meeting and segments_meet disagree for {s:?}, {t:?}: {got:?}"
    );
    let scale = e
        .iter()
        .chain(&f)
        .flatten()
        .fold(0.0f64, |m, v| m.max(v.abs()));
    match (&want, got) {
        (None, None) => {}
        (Some(Exact::Crossing(x)), Some(Meeting::Point(p))) => {
            let tolerance = q(4.0 * f64::EPSILON * scale);
            for (k, v) in [p.x, p.y].into_iter().enumerate() {
                let error = q(v) - &x[k];
                let error = if error < Q::zero() { -error } else { error };
                assert!(
                    error <= tolerance,
                    "crossing of {s:?} and {t:?}: {p:?} is more than 4 ulps from the exact point"
                );
            }
        }
        (Some(Exact::Touch(r)), Some(Meeting::Point(p))) => {
            assert_eq!(p, xy(*r), "touching {s:?} and {t:?}");
        }
        (Some(Exact::Overlap(a, b)), Some(Meeting::Overlap(c, d))) => {
            assert_eq!((c, d), (xy(*a), xy(*b)), "overlap of {s:?} and {t:?}");
        }
        _ => panic!("{s:?} and {t:?}: meeting gave {got:?}, expected {want:?}"),
    }
}

/// `meeting` on every pair of a (small) input, and `intersections` on the whole input.
fn check_meetings(segments: &[Line<f64>]) {
    for i in 0..segments.len() {
        for j in i + 1..segments.len() {
            check_meeting(&segments[i], &segments[j]);
        }
    }
    check_intersections(segments);
}

/// `intersections` gives the pairs of `intersecting_pairs`, each with its `meeting`.
fn check_intersections(segments: &[Line<f64>]) {
    let all = intersections(segments);
    let pairs: Vec<(usize, usize)> = all.iter().map(|&(i, j, _)| (i, j)).collect();
    assert_eq!(pairs, intersecting_pairs(segments));
    for (i, j, m) in all {
        assert_eq!(Some(m), meeting(&segments[i], &segments[j]), "pair {i} {j}");
    }
}

// ---------------------------------------------------------------------------------------------
// Inputs.

/// Random segments in the unit square of mixed kinds: points, short and medium segments,
/// horizontal and vertical ones, and a few long ones spanning the whole square.
fn mixed(rng: &mut SplitMix64, n: usize) -> Vec<Line<f64>> {
    (0..n)
        .map(|_| match rng.below(12) {
            0 => {
                let (x, y) = (rng.unit(), rng.unit());
                seg(x, y, x, y)
            }
            1 => {
                // Across the whole square, side to side.
                if rng.below(2) == 0 {
                    seg(
                        rng.range(0.0, 0.05),
                        rng.unit(),
                        rng.range(0.95, 1.0),
                        rng.unit(),
                    )
                } else {
                    seg(
                        rng.unit(),
                        rng.range(0.0, 0.05),
                        rng.unit(),
                        rng.range(0.95, 1.0),
                    )
                }
            }
            2 => {
                let (x, y) = (rng.unit(), rng.unit());
                seg(x, y, x + rng.range(-0.1, 0.1), y)
            }
            3 => {
                let (x, y) = (rng.unit(), rng.unit());
                seg(x, y, x, y + rng.range(-0.1, 0.1))
            }
            _ => {
                let len = rng.pick(&[0.001, 0.01, 0.03, 0.1, 0.3]);
                let (x, y) = (rng.unit(), rng.unit());
                let angle = rng.range(0.0, std::f64::consts::TAU);
                seg(x, y, x + len * angle.cos(), y + len * angle.sin())
            }
        })
        .collect()
}

/// Segments with endpoints on the lattice `step * [0, k]²`: points, lattice edges
/// (horizontal, vertical, diagonal), longer axis-parallel segments, and general ones.
fn lattice(rng: &mut SplitMix64, n: usize, k: i32, step: f64) -> Vec<Line<f64>> {
    (0..n)
        .map(|_| {
            let (x, y) = (rng.int(0, k), rng.int(0, k));
            let (x2, y2) = match rng.below(8) {
                0 => (x, y),
                1 => (rng.int(0, k), y),
                2 => (x, rng.int(0, k)),
                3 | 4 => {
                    let (dx, dy) = rng.pick(&[(1.0, 0.0), (0.0, 1.0), (1.0, 1.0), (1.0, -1.0)]);
                    let m = rng.int(1, 3);
                    (x + m * dx, y + m * dy)
                }
                _ => (rng.int(0, k), rng.int(0, k)),
            };
            seg(x * step, y * step, x2 * step, y2 * step)
        })
        .collect()
}

fn shifted(segments: &[Line<f64>], dx: f64, dy: f64) -> Vec<Line<f64>> {
    segments
        .iter()
        .map(|s| seg(s.start.x + dx, s.start.y + dy, s.end.x + dx, s.end.y + dy))
        .collect()
}

fn scaled(segments: &[Line<f64>], f: f64) -> Vec<Line<f64>> {
    segments
        .iter()
        .map(|s| seg(s.start.x * f, s.start.y * f, s.end.x * f, s.end.y * f))
        .collect()
}

/// Every unit edge of the integer lattice in `[0, k]²`.
fn lattice_edges(k: i32) -> Vec<Line<f64>> {
    let mut edges = Vec::new();
    for i in 0..=k {
        for j in 0..k {
            let (i, j) = (f64::from(i), f64::from(j));
            edges.push(seg(i, j, i, j + 1.0));
            edges.push(seg(j, i, j + 1.0, i));
        }
    }
    edges
}

// ---------------------------------------------------------------------------------------------
// Small cases.

#[test]
fn empty_single_and_point_inputs() {
    assert_eq!(intersecting_pairs(&[]), vec![]);
    assert_eq!(intersections(&[]), vec![]);
    assert_eq!(SegmentGrid::new(&[]).shape(), [1, 1]);
    let one = [seg(0.0, 0.0, 1.0, 1.0)];
    assert_eq!(intersecting_pairs(&one), vec![]);
    // Points: equal ones meet, distinct ones do not; a point on a segment meets it.
    let points = [
        seg(0.5, 0.5, 0.5, 0.5),
        seg(0.5, 0.5, 0.5, 0.5),
        seg(0.25, 0.5, 0.25, 0.5),
        seg(0.0, 0.0, 1.0, 1.0),
        seg(0.0, 0.5, 0.2, 0.5),
    ];
    assert_eq!(check(&points, "points"), vec![(0, 1), (0, 3), (1, 3)]);
    check_meetings(&points);
    // All the same point: a zero extent.
    let same = vec![seg(3.0, -2.0, 3.0, -2.0); 5];
    assert_eq!(SegmentGrid::new(&same).shape(), [1, 1]);
    assert_eq!(check(&same, "same point").len(), 10);
}

#[test]
fn meeting_in_each_case() {
    let point = |x, y| Some(Meeting::Point(Coord { x, y }));
    let overlap = |x1, y1, x2, y2| {
        Some(Meeting::Overlap(
            Coord { x: x1, y: y1 },
            Coord { x: x2, y: y2 },
        ))
    };
    let a = seg(0.0, 0.0, 4.0, 0.0);
    // A proper crossing.
    assert_eq!(meeting(&a, &seg(1.0, -1.0, 1.0, 3.0)), point(1.0, 0.0));
    // A T: the touching endpoint, exactly.
    assert_eq!(meeting(&a, &seg(3.0, 0.0, 3.0, 5.0)), point(3.0, 0.0));
    assert_eq!(meeting(&seg(3.0, 0.0, 3.0, 5.0), &a), point(3.0, 0.0));
    // Shared endpoints.
    assert_eq!(meeting(&a, &seg(4.0, 0.0, 7.0, 1.0)), point(4.0, 0.0));
    // End to end on one line: one point.
    assert_eq!(meeting(&a, &seg(4.0, 0.0, 9.0, 0.0)), point(4.0, 0.0));
    assert_eq!(meeting(&a, &seg(-2.0, 0.0, 0.0, 0.0)), point(0.0, 0.0));
    // Overlaps in the first segment's direction.
    assert_eq!(
        meeting(&a, &seg(9.0, 0.0, 1.0, 0.0)),
        overlap(1.0, 0.0, 4.0, 0.0)
    );
    let reversed = seg(4.0, 0.0, 0.0, 0.0);
    assert_eq!(
        meeting(&reversed, &seg(1.0, 0.0, 9.0, 0.0)),
        overlap(4.0, 0.0, 1.0, 0.0)
    );
    // Containment: the inner segment's points, in the outer's direction.
    assert_eq!(
        meeting(&reversed, &seg(1.0, 0.0, 2.0, 0.0)),
        overlap(2.0, 0.0, 1.0, 0.0)
    );
    assert_eq!(
        meeting(&seg(2.0, 0.0, 1.0, 0.0), &a),
        overlap(2.0, 0.0, 1.0, 0.0)
    );
    // Identical segments, and vertical and diagonal overlaps.
    assert_eq!(meeting(&a, &a), overlap(0.0, 0.0, 4.0, 0.0));
    assert_eq!(
        meeting(&seg(1.0, 5.0, 1.0, -5.0), &seg(1.0, 0.0, 1.0, 9.0)),
        overlap(1.0, 5.0, 1.0, 0.0)
    );
    assert_eq!(
        meeting(&seg(0.0, 0.0, 3.0, 3.0), &seg(4.0, 4.0, 1.0, 1.0)),
        overlap(1.0, 1.0, 3.0, 3.0)
    );
    // Disjoint: parallel, collinear with a gap, and lines crossing outside the segments.
    assert_eq!(meeting(&a, &seg(0.0, 1.0, 4.0, 1.0)), None);
    assert_eq!(meeting(&a, &seg(5.0, 0.0, 9.0, 0.0)), None);
    assert_eq!(meeting(&a, &seg(5.0, -1.0, 6.0, 1.0)), None);
    assert_eq!(meeting(&a, &seg(2.0, 1.0, 3.0, 0.5)), None);
    // Points.
    assert_eq!(meeting(&a, &seg(2.0, 0.0, 2.0, 0.0)), point(2.0, 0.0));
    assert_eq!(meeting(&seg(2.0, 0.0, 2.0, 0.0), &a), point(2.0, 0.0));
    assert_eq!(meeting(&a, &seg(2.0, 1e-300, 2.0, 1e-300)), None);
    assert_eq!(
        meeting(&seg(1.0, 1.0, 1.0, 1.0), &seg(1.0, 1.0, 1.0, 1.0)),
        point(1.0, 1.0)
    );
    assert_eq!(
        meeting(&seg(1.0, 1.0, 1.0, 1.0), &seg(1.0, 2.0, 1.0, 2.0)),
        None
    );
    // A crossing that is not representable: within a few ulps of 1/3.
    let Some(Meeting::Point(p)) = meeting(&seg(0.0, 0.0, 1.0, 0.0), &seg(0.0, -1.0, 0.5, 0.5))
    else {
        panic!("they cross")
    };
    assert!(
        (p.x - 1.0 / 3.0).abs() <= 4.0 * f64::EPSILON && p.y == 0.0,
        "{p:?}"
    );
    for (s, t) in [
        (a, seg(1.0, -1.0, 1.0, 3.0)),
        (a, seg(9.0, 0.0, 1.0, 0.0)),
        (reversed, seg(1.0, 0.0, 2.0, 0.0)),
        (seg(0.0, 0.0, 1.0, 0.0), seg(0.0, -1.0, 0.5, 0.5)),
        (seg(0.1, 0.2, 0.7, 0.9), seg(0.3, 0.8, 0.6, 0.1)),
    ] {
        check_meeting(&s, &t);
    }
}

#[test]
fn crossings_are_within_four_ulps_of_the_exact_point() {
    // Random crossings, nearly parallel long segments (the hardest for the construction),
    // nearly perpendicular diagonals, and crossings far from the origin.
    let mut rng = SplitMix64(81);
    let mut crossings = 0;
    for i in 0..4000 {
        let mut p = |lo: f64, hi: f64| [rng.range(lo, hi), rng.range(lo, hi)];
        let [a, b, c, d] = match i % 4 {
            0 => [p(0.0, 1.0), p(0.0, 1.0), p(0.0, 1.0), p(0.0, 1.0)],
            1 => {
                let (a, c) = (p(-1.0, -0.999), p(-1.0, -0.999));
                let (b, d) = (p(0.999, 1.0), p(0.999, 1.0));
                [a, [b[0], -b[1]], c, [d[0], -d[1]]]
            }
            2 => {
                let e = p(0.0, 1e-9);
                [
                    [-1.0 + e[0], -1.0],
                    [1.0, 1.0 - e[1]],
                    [-1.0, 1.0 - e[0]],
                    [1.0, -1.0 + e[1]],
                ]
            }
            _ => [
                p(1e6, 1e6 + 1.0),
                p(1e6, 1e6 + 1.0),
                p(1e6, 1e6 + 1.0),
                p(1e6, 1e6 + 1.0),
            ],
        };
        let (s, t) = (seg(a[0], a[1], b[0], b[1]), seg(c[0], c[1], d[0], d[1]));
        if matches!(
            exact_meeting(&ends(&s), &ends(&t)),
            Some(Exact::Crossing(_))
        ) {
            crossings += 1;
        }
        check_meeting(&s, &t);
    }
    assert!(crossings > 1000, "{crossings}");
}

// ---------------------------------------------------------------------------------------------
// Random inputs.

#[test]
fn random_segments_of_mixed_lengths_equal_brute_force_and_geo() {
    for seed in 0..6 {
        let mut rng = SplitMix64(seed);
        let segments = mixed(&mut rng, 400);
        let expected = check(&segments, &format!("mixed, seed {seed}"));
        assert_eq!(geo_pairs(&segments), expected, "geo, seed {seed}");
        assert!(expected.len() > 100, "{}", expected.len());
    }
}

#[test]
fn a_few_long_segments_among_many_short_ones() {
    // Long segments cross most of the grid's cells.
    let mut rng = SplitMix64(11);
    let mut segments = random_segments(1500, 0.005, 5);
    for _ in 0..20 {
        let (x, y) = (rng.unit(), rng.unit());
        segments.insert(
            rng.below(segments.len()),
            seg(x, 0.0, 1.0 - x, 1.0 - y * 0.01),
        );
    }
    segments.push(seg(0.0, 0.0, 1.0, 1.0));
    segments.push(seg(0.0, 1.0, 1.0, 0.0));
    segments.push(seg(0.0, 0.5, 1.0, 0.5));
    segments.push(seg(0.5, 0.0, 0.5, 1.0));
    let expected = check(&segments, "long among short");
    assert_eq!(geo_pairs(&segments), expected);
    check_intersections(&segments);
}

#[test]
fn franklin_random_segments_equal_brute_force_and_geo() {
    for (n, len, seed) in [
        (3000, 0.05, 1),
        (3000, 0.02, 2),
        (500, 0.3, 3),
        (200, 1.0, 4),
    ] {
        let segments = random_segments(n, len, seed);
        let what = format!("random_segments({n}, {len}, {seed})");
        let expected = check(&segments, &what);
        assert_eq!(geo_pairs(&segments), expected, "geo: {what}");
        check_intersections(&segments);
    }
}

#[test]
fn franklin_expected_number_of_intersections() {
    // n segments of length len in the unit square: about n² len² / π intersecting pairs.
    let (n, len) = (50_000, 0.01);
    let segments = random_segments(n, len, 1);
    let k = intersecting_pairs(&segments).len();
    let expected = (n * n) as f64 * len * len / std::f64::consts::PI;
    assert!(
        (k as f64 - expected).abs() < 0.04 * expected,
        "K = {k}, expected about {expected:.0}"
    );
    assert_eq!(k, 80_894, "the count for seed 1");
    // A few cells per segment, as Franklin's analysis needs.
    let grid = SegmentGrid::new(&segments);
    assert!(
        grid.cells_per_segment() < 4.0,
        "{}",
        grid.cells_per_segment()
    );
}

#[test]
fn random_segments_have_their_length_stay_in_the_square_and_reproduce() {
    for (n, len, seed) in [
        (2000, 0.01, 1),
        (2000, 0.5, 2),
        (500, 1.0, 3),
        (100, 0.0, 4),
    ] {
        let s = random_segments(n, len, seed);
        assert_eq!(s.len(), n);
        for l in &s {
            let length = l.dx().hypot(l.dy());
            assert!(
                (length - len).abs() <= 4.0 * f64::EPSILON,
                "{l:?} has length {length}, not {len}"
            );
            for p in [l.start, l.end] {
                assert!(
                    (0.0..=1.0).contains(&p.x) && (0.0..=1.0).contains(&p.y),
                    "{p:?} outside the unit square"
                );
            }
        }
        assert_eq!(random_segments(n, len, seed), s, "seed {seed} reproduces");
        if len > 0.0 {
            assert_ne!(random_segments(n, len, seed + 100), s);
        }
    }
    assert!(random_segments(0, 0.1, 1).is_empty());
    // The midpoints and directions are spread out: each quadrant gets about a quarter.
    let s = random_segments(4000, 0.01, 9);
    let left = s.iter().filter(|l| l.start.x + l.end.x < 1.0).count();
    let low = s.iter().filter(|l| l.start.y + l.end.y < 1.0).count();
    let rightward = s.iter().filter(|l| l.dx() > 0.0).count();
    for c in [left, low, rightward] {
        assert!((1800..2200).contains(&c), "{c} of 4000");
    }
}

// ---------------------------------------------------------------------------------------------
// Degenerate inputs.

#[test]
fn lattice_inputs_equal_brute_force() {
    // Shared endpoints, T-junctions, collinear overlaps, horizontal and vertical segments.
    for seed in 0..8 {
        let mut rng = SplitMix64(100 + seed);
        let (k, step) = if seed % 2 == 0 { (6, 1.0) } else { (12, 0.5) };
        let segments = lattice(&mut rng, 250, k, step);
        let what = format!("lattice, seed {seed}");
        let expected = check(&segments, &what);
        assert!(
            expected.len() > segments.len(),
            "{what}: {}",
            expected.len()
        );
        // geo's sweep too (its segments carry their indices, so duplicates are fine).
        assert_eq!(geo_pairs(&segments), expected, "geo: {what}");
        check_intersections(&segments);
    }
    let mut rng = SplitMix64(7);
    check_meetings(&lattice(&mut rng, 80, 4, 1.0));
}

#[test]
fn horizontal_and_vertical_segments() {
    let mut rng = SplitMix64(21);
    // Random positions, axis-parallel only.
    let segments: Vec<Line<f64>> = (0..600)
        .map(|_| {
            let (x, y, d) = (rng.unit(), rng.unit(), rng.range(-0.1, 0.1));
            if rng.below(2) == 0 {
                seg(x, y, x + d, y)
            } else {
                seg(x, y, x, y + d)
            }
        })
        .collect();
    check(&segments, "axis-parallel");
    assert_eq!(geo_pairs(&segments), brute(&segments));
    // All on one horizontal line, and all on one vertical line: a grid one cell thick.
    let on_line: Vec<Line<f64>> = (0..200)
        .map(|_| {
            let x = rng.unit();
            seg(x, 0.375, x + rng.range(-0.02, 0.02), 0.375)
        })
        .collect();
    let grid = SegmentGrid::new(&on_line);
    assert_eq!(grid.shape()[1], 1);
    assert!(grid.shape()[0] > 1);
    check(&on_line, "one horizontal line");
    let vertical: Vec<Line<f64>> = on_line
        .iter()
        .map(|s| seg(-2.5, s.start.x, -2.5, s.end.x))
        .collect();
    assert_eq!(SegmentGrid::new(&vertical).shape()[0], 1);
    check(&vertical, "one vertical line");
    check_meetings(&on_line[..60]);
    check_meetings(&vertical[..60]);
}

#[test]
fn many_segments_through_one_point() {
    let mut rng = SplitMix64(31);
    // Sharing an endpoint (not a lattice point), among other segments.
    let centre = (0.3, 0.7);
    let mut segments = random_segments(300, 0.03, 8);
    for _ in 0..150 {
        let (x, y) = (rng.unit(), rng.unit());
        segments.insert(rng.below(segments.len()), seg(centre.0, centre.1, x, y));
    }
    let expected = check(&segments, "star with a shared endpoint");
    assert_eq!(geo_pairs(&segments), expected);
    let star: Vec<usize> = (0..segments.len())
        .filter(|&i| segments[i].start == Coord::from(centre))
        .collect();
    for (n, &i) in star.iter().enumerate() {
        for &j in &star[n + 1..] {
            assert!(expected.contains(&(i, j)));
            assert_eq!(
                meeting(&segments[i], &segments[j]),
                Some(Meeting::Point(centre.into()))
            );
        }
    }
    // Crossing at an interior point: symmetric lattice segments through (20, 20), with
    // repeated directions (collinear overlaps).
    let through: Vec<Line<f64>> = (0..200)
        .map(|_| {
            let (dx, dy) = (rng.int(-5, 5), rng.int(-5, 5));
            let (dx, dy) = if dx == 0.0 && dy == 0.0 {
                (1.0, 0.0)
            } else {
                (dx, dy)
            };
            let (s, t) = (rng.int(1, 3), rng.int(1, 3));
            seg(20.0 - s * dx, 20.0 - s * dy, 20.0 + t * dx, 20.0 + t * dy)
        })
        .collect();
    let all: Vec<(usize, usize)> = (0..200)
        .flat_map(|i| (i + 1..200).map(move |j| (i, j)))
        .collect();
    assert_eq!(check(&through, "star through (20, 20)"), all);
    check_meetings(&through[..50]);
    // A thousand from one point, all in the same few cells: every pair (not checked by brute
    // force).
    let m = 1000;
    let many: Vec<Line<f64>> = (0..m)
        .map(|i| {
            let a = std::f64::consts::TAU * i as f64 / m as f64;
            let (r, s) = (rng.range(0.1, 1.0), rng.range(0.1, 1.0));
            let (c, d) = (a.cos(), a.sin());
            if i % 2 == 0 {
                seg(0.5, 0.5, 0.5 + r * c, 0.5 + r * d)
            } else {
                seg(0.5 + s * c, 0.5 + s * d, 0.5, 0.5)
            }
        })
        .collect();
    let all: Vec<(usize, usize)> = (0..m)
        .flat_map(|i| (i + 1..m).map(move |j| (i, j)))
        .collect();
    check_against(&many, &all, "1000 segments from one point");
}

#[test]
fn segments_along_grid_lines() {
    // All unit edges of the lattice in [0, 10]²: the cells have side 1, and every segment lies
    // on cell boundaries. Edges meet exactly when they share a lattice point: the sum over
    // points of C(degree, 2) = 4 corners x 1 + 36 side points x 3 + 81 inner points x 6.
    let edges = lattice_edges(10);
    assert_eq!(edges.len(), 220);
    assert_eq!(SegmentGrid::new(&edges).shape(), [10, 10]);
    assert_eq!(check(&edges, "lattice edges").len(), 4 + 36 * 3 + 81 * 6);
    assert_eq!(geo_pairs(&edges), brute(&edges));
    check_intersections(&edges);
    // Shifted far away, exactly (cell boundaries at 1e6 + k), and scaled by a power of two.
    for (what, moved) in [
        ("edges + 1e6", shifted(&edges, 1e6, -1e6)),
        ("edges + 3", shifted(&edges, 3.0, 7.0)),
        ("edges / 2^20", scaled(&edges, 1.0 / (1u64 << 20) as f64)),
        ("edges * 0.1", scaled(&edges, 0.1)),
    ] {
        assert_eq!(SegmentGrid::new(&moved).shape(), [10, 10], "{what}");
        assert_eq!(check(&moved, what).len(), 598, "{what}");
    }
    // Random unit edges (duplicates included) and random half-unit edges: still cell side
    // one (the extent is pinned by the frame's corners).
    for (seed, step) in [(1, 1.0), (2, 0.5), (3, 1.0), (4, 0.5)] {
        let mut rng = SplitMix64(seed);
        let k = (10.0 / step) as i32;
        let mut segments = vec![seg(0.0, 0.0, step, 0.0), seg(10.0 - step, 10.0, 10.0, 10.0)];
        for _ in 0..400 {
            let (x, y) = (rng.int(0, k - 1) * step, rng.int(0, k - 1) * step);
            segments.push(match rng.below(4) {
                0 => seg(x, y, x + step, y),
                1 => seg(x, y, x, y + step),
                2 => seg(x + step, y, x, y),
                _ => seg(x, y + step, x, y),
            });
        }
        let shape = SegmentGrid::new(&segments).shape();
        assert_eq!(shape, [k as usize, k as usize]);
        check(&segments, &format!("unit edges, seed {seed}"));
    }
    // Whole grid lines crossing every cell, with the unit edges and points at lattice points.
    let mut segments = edges.clone();
    for i in 0..=10 {
        let i = f64::from(i);
        segments.push(seg(i, 0.0, i, 10.0));
        segments.push(seg(10.0, i, 0.0, i));
        segments.push(seg(i, i, i, i));
        segments.push(seg(i, 10.0 - i, i, 10.0 - i));
    }
    segments.push(seg(0.0, 0.0, 10.0, 10.0));
    segments.push(seg(0.0, 10.0, 10.0, 0.0));
    check(&segments, "grid lines");
}

#[test]
fn coordinates_far_from_the_origin_and_tiny_ones() {
    let mut rng = SplitMix64(41);
    let base = mixed(&mut rng, 300);
    let lattice_base = lattice(&mut rng, 200, 8, 1.0);
    for (what, segments) in [
        ("mixed + 1e6", shifted(&base, 1e6, 1e6)),
        ("mixed - 1e6", shifted(&base, -1e6, 3e6)),
        ("mixed * 1e-6", scaled(&base, 1e-6)),
        ("mixed * 1e6", scaled(&base, 1e6)),
        ("lattice + 1e6", shifted(&lattice_base, 1e6, -1e6)),
        ("lattice * 2^-40", scaled(&lattice_base, (-40f64).exp2())),
        ("lattice * 1e-6", scaled(&lattice_base, 1e-6)),
    ] {
        let expected = check(&segments, what);
        assert_eq!(geo_pairs(&segments), expected, "geo: {what}");
        check_meetings(&segments[..40]);
        check_intersections(&segments);
    }
    // Correct (if slow, see segments_far_from_the_origin_are_listed_in_few_cells) when the
    // data's extent is small next to its distance from the origin.
    let far = shifted(&scaled(&random_segments(300, 0.05, 3), 1e-3), 1e6, -1e6);
    let expected = check(&far, "tiny and far");
    assert_eq!(expected, intersecting_pairs(&random_segments(300, 0.05, 3)));
}

#[test]
fn duplicated_segments() {
    let mut rng = SplitMix64(51);
    let base = mixed(&mut rng, 200);
    let mut segments = Vec::new();
    for s in &base {
        for _ in 0..rng.int(1, 3) as usize {
            segments.push(if rng.below(2) == 0 {
                *s
            } else {
                seg(s.end.x, s.end.y, s.start.x, s.start.y)
            });
        }
    }
    let expected = check(&segments, "duplicated");
    assert_eq!(geo_pairs(&segments), expected, "geo");
    // Copies of one segment always meet.
    for i in 0..segments.len() {
        for j in i + 1..segments.len() {
            let (a, b) = (ends(&segments[i]), ends(&segments[j]));
            if a == b || a == [b[1], b[0]] {
                assert!(expected.binary_search(&(i, j)).is_ok(), "{i} {j}");
            }
        }
    }
    check_meetings(&segments[..80]);
    // Every copy of a lattice edge many times over.
    let copies: Vec<Line<f64>> = lattice_edges(3)
        .into_iter()
        .flat_map(|s| [s, s, s])
        .collect();
    check(&copies, "lattice edges three times");
}

#[test]
fn nearly_vertical_and_nearly_horizontal_segments() {
    // Steep segments one ulp or so from vertical (and flat ones), crossed by many others.
    let mut rng = SplitMix64(71);
    let mut segments = Vec::new();
    for i in 0..40 {
        let x = rng.unit();
        let dx = rng.pick(&[f64::EPSILON, 1e-15, 1e-12, -1e-14, 1e-300]) * f64::from(i % 3);
        segments.push(seg(x, 0.0, x + dx, 1.0));
        segments.push(seg(0.0, x, 1.0, x - dx));
    }
    for _ in 0..200 {
        segments.push(seg(rng.unit(), rng.unit(), rng.unit(), rng.unit()));
    }
    let expected = check(&segments, "nearly axis-parallel");
    assert_eq!(geo_pairs(&segments), expected);
    check_meetings(&segments[..80]);
}

#[test]
fn a_nearly_vertical_segment_whose_slope_overflows() {
    // The walk's slope (b.y - a.y) / (b.x - a.x) overflows to infinity when dx is tiny (here
    // 3e-308 for dy = 8, and 2e-300 for dy = 1e9); such a segment must still be listed in all
    // the rows it spans (it once was not: 3 of these 17 crossings were found).
    for (x, up) in [(3e-308, true), (3e-308, false), (2e-300, true)] {
        let dy = if x < 1e-300 { 8.0 } else { 1e9 };
        let mut segments = vec![if up {
            seg(0.0, 0.0, x, dy)
        } else {
            seg(0.0, dy, x, 0.0)
        }];
        for i in 0..=16 {
            let y = f64::from(i) * dy / 16.0;
            segments.push(seg(-1.0, y, 1.0, y));
            segments.push(seg(7.0, y, 8.0, y + 0.25));
        }
        let expected = check(&segments, &format!("nearly vertical, dx {x:e}, up {up}"));
        let crossed = (1..=17)
            .filter(|&j| expected.contains(&(0, 2 * j - 1)))
            .count();
        assert_eq!(crossed, 17);
    }
}

#[test]
fn segments_far_from_the_origin_are_listed_in_few_cells() {
    // The walk's margin is relative to the largest coordinate: it must stay far below the
    // cell side for data far from the origin, or every segment is listed in every cell
    // (quadratic time and memory). Here 500 segments of length 2e-5 at 1e6 + [0, 1e-3]²
    // (about 170,000 ulps long); with a margin of 2^-30 they were listed in all 529 cells.
    let base = random_segments(500, 0.02, 1);
    let near = SegmentGrid::new(&base).cells_per_segment();
    let far = shifted(&scaled(&base, 1e-3), 1e6, 1e6);
    let grid = SegmentGrid::new(&far);
    assert_eq!(grid.shape(), SegmentGrid::new(&base).shape());
    assert_eq!(grid.pairs(), intersecting_pairs(&base));
    assert!(
        grid.cells_per_segment() < 2.0 * near,
        "{} cells per segment far from the origin, {near} at the origin",
        grid.cells_per_segment()
    );
}

// ---------------------------------------------------------------------------------------------
// Properties.

/// A segment from four lattice coordinates on the half-integer lattice in [0, 4]².
fn lattice_segment() -> impl Strategy<Value = Line<f64>> {
    (0i32..9, 0i32..9, 0i32..9, 0i32..9).prop_map(|(a, b, c, d)| {
        let h = |v: i32| f64::from(v) * 0.5;
        seg(h(a), h(b), h(c), h(d))
    })
}

/// Floating-point segments sharing endpoints from a small pool of points, and free ones.
fn pooled_segments() -> impl Strategy<Value = Vec<Line<f64>>> {
    let point = (-1.0..1.0f64, -1.0..1.0f64);
    (
        prop::collection::vec(point.clone(), 1..8),
        prop::collection::vec((0usize..8, 0usize..8, point.clone(), point, 0u8..3), 0..40),
    )
        .prop_map(|(pool, picks)| {
            picks
                .into_iter()
                .map(|(i, j, p, r, kind)| {
                    let (a, b) = (pool[i % pool.len()], pool[j % pool.len()]);
                    match kind {
                        0 => seg(a.0, a.1, b.0, b.1),
                        1 => seg(a.0, a.1, p.0, p.1),
                        _ => seg(p.0, p.1, r.0, r.1),
                    }
                })
                .collect()
        })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    #[test]
    fn lattice_segments_equal_brute_force(
        segments in prop::collection::vec(lattice_segment(), 0..50),
    ) {
        check(&segments, "proptest lattice");
        check_meetings(&segments);
    }

    #[test]
    fn pooled_segments_equal_brute_force(segments in pooled_segments()) {
        let expected = check(&segments, "proptest pooled");
        check_meetings(&segments);
        prop_assert_eq!(geo_pairs(&segments), expected);
    }

    #[test]
    fn random_segments_equal_brute_force(
        n in 0usize..300,
        len in 0.0..0.5f64,
        seed in any::<u64>(),
        offset in prop::sample::select(vec![0.0, 1e6, -1e3]),
    ) {
        let segments = shifted(&random_segments(n, len, seed), offset, offset);
        let expected = check(&segments, "proptest random_segments");
        prop_assert_eq!(geo_pairs(&segments), expected);
    }
}

#[test]
fn the_floating_point_speed_up_of_the_reference_is_right() {
    // orient_float, where it answers, agrees with rationals: random, lattice, tiny, far and
    // nearly collinear triples.
    let mut rng = SplitMix64(61);
    let mut answered = 0;
    for i in 0..20_000 {
        let scale = rng.pick(&[1.0, 1e-6, 1e6, 1e-150, 1e90]);
        let offset = rng.pick(&[0.0, 1e6, -3.5]);
        let p = |rng: &mut SplitMix64| match i % 3 {
            0 => [rng.unit(), rng.unit()],
            1 => [rng.int(-3, 3), rng.int(-3, 3)],
            _ => [rng.range(-1.0, 1.0), rng.range(-1.0, 1.0)],
        };
        let (a, b) = (p(&mut rng), p(&mut rng));
        let c = if i % 3 == 2 {
            // On the line through a and b, up to rounding.
            let t = rng.range(-2.0, 2.0);
            [a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1])]
        } else {
            p(&mut rng)
        };
        let [a, b, c] = [a, b, c].map(|v| v.map(|x| x * scale + offset));
        let exact = qsign(&q2cross(&q2sub(&q2(b), &q2(a)), &q2sub(&q2(c), &q2(a))));
        if let Some(o) = orient_float(a, b, c) {
            answered += 1;
            assert_eq!(o, exact, "{a:?} {b:?} {c:?}");
        }
        assert_eq!(orient(a, b, c), exact);
    }
    assert!(answered > 10_000, "{answered}");
}

// ---------------------------------------------------------------------------------------------
// Candidates with keys (stage 3's pairs with a contour), crowded cells split.

/// Checks `SegmentGrid::candidates` with the keys `key` against the brute force: every pair
/// with a key whose exact segments meet is listed, every listed pair has a key, passes `keep`
/// and has bounding boxes that meet within 2⁻⁴⁰ of the largest coordinate, each once in
/// increasing order. Returns how many were listed.
fn check_candidates(segments: &[Line<f64>], key: &[bool], what: &str) -> usize {
    let grid = SegmentGrid::new(segments);
    let keep = |i: usize, j: usize| (i + j) % 7 != 3;
    let found = grid.candidates(|i| key[i], keep);
    assert!(
        found.windows(2).all(|w| w[0] < w[1]),
        "{what}: not increasing"
    );
    let e: Vec<[[f64; 2]; 2]> = segments.iter().map(ends).collect();
    let scale = e
        .iter()
        .flatten()
        .flatten()
        .fold(0.0f64, |m, v| m.max(v.abs()));
    let slack = scale / (1u64 << 40) as f64;
    let near = |s: &[[f64; 2]; 2], t: &[[f64; 2]; 2]| {
        (0..2).all(|k| {
            s[0][k].min(s[1][k]) - slack <= t[0][k].max(t[1][k])
                && t[0][k].min(t[1][k]) - slack <= s[0][k].max(s[1][k])
        })
    };
    for &(i, j) in &found {
        assert!(
            i < j && (key[i] || key[j]) && keep(i, j),
            "{what}: ({i}, {j}) listed"
        );
        assert!(near(&e[i], &e[j]), "{what}: ({i}, {j}) listed, boxes apart");
    }
    for (i, j) in brute(segments) {
        if (key[i] || key[j]) && keep(i, j) {
            assert!(
                found.binary_search(&(i, j)).is_ok(),
                "{what}: ({i}, {j}) missed"
            );
        }
    }
    found.len()
}

/// A cone's edges seen head-on: `n` spokes from `centre` to a circle of radius `r`, and the
/// circle's `n` short sides; the sides are the keys (contours), the spokes not.
fn cone(n: usize, centre: [f64; 2], r: f64) -> (Vec<Line<f64>>, Vec<bool>) {
    let rim = |i: usize| {
        let a = std::f64::consts::TAU * (i % n) as f64 / n as f64;
        [centre[0] + r * a.cos(), centre[1] + r * a.sin()]
    };
    let mut segments = Vec::new();
    let mut key = Vec::new();
    for i in 0..n {
        let (p, q) = (rim(i), rim(i + 1));
        segments.push(seg(centre[0], centre[1], p[0], p[1]));
        key.push(false);
        segments.push(seg(p[0], p[1], q[0], q[1]));
        key.push(true);
    }
    (segments, key)
}

#[test]
fn candidates_with_keys_equal_brute_force_on_random_and_lattice_inputs() {
    for seed in 0..12 {
        let mut rng = SplitMix64(1000 + seed);
        let n = rng.pick(&[20, 80, 300, 700]);
        let segments = if seed % 2 == 0 {
            mixed(&mut rng, n)
        } else {
            let (k, step) = (rng.pick(&[3, 8, 20]), rng.pick(&[1.0, 0.125, 3.0]));
            lattice(&mut rng, n, k, step)
        };
        let share = rng.pick(&[0, 1, 2, 8]);
        let key: Vec<bool> = (0..n).map(|_| share > 0 && rng.below(share) == 0).collect();
        check_candidates(&segments, &key, &format!("seed {seed}"));
        // Far from the origin and tiny: the same pairs.
        let far = shifted(&segments, 1e8, -3e8);
        check_candidates(&far, &key, &format!("seed {seed}, far"));
        check_candidates(
            &scaled(&segments, 1e-300),
            &key,
            &format!("seed {seed}, tiny"),
        );
    }
}

#[test]
fn candidates_in_a_cone_seen_head_on_equal_brute_force_through_split_cells() {
    for (n, centre, r) in [
        (500, [0.0, 0.0], 1.0),
        (2000, [0.3, -7.0], 0.5),
        (1500, [1e8, 1e8], 3.0),
    ] {
        let (segments, key) = cone(n, centre, r);
        let found = check_candidates(&segments, &key, &format!("cone of {n}"));
        // Each side meets its two neighbours and its two spokes (3 n pairs, all listed, as
        // checked). The cells round the rim are crowded with sides, and split.
        assert!(found <= 12 * n, "cone of {n}: {found} pairs");
    }
    // All segments keys, through one point: every pair meets, and every pair is listed.
    let (mut segments, _) = cone(300, [0.5, 0.5], 1.0);
    segments.retain(|s| s.start == Coord { x: 0.5, y: 0.5 });
    let key = vec![true; segments.len()];
    let m = segments.len();
    assert_eq!(
        check_candidates(&segments, &key, "spokes"),
        m * (m - 1) / 2
            - (0..m)
                .flat_map(|i| (i + 1..m).map(move |j| (i, j)))
                .filter(|&(i, j)| (i + j) % 7 == 3)
                .count()
    );
}
