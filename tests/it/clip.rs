//! Polygon clipping (`kepler::clip`) against exact rational references (`BigRational`): every
//! output vertex is an input vertex or the exact crossing of two input edges to within the
//! documented error (measured in ulps of the largest input coordinate), and areas add up;
//! against geo's `BooleanOps` as an oracle for areas, with the vertex error of both printed;
//! and degenerate inputs: shared edges, collinear overlaps, touching vertices, identical,
//! nested and disjoint polygons, coordinates far from the origin or tiny, self-crossing rings,
//! empty and non-finite inputs.

use geo::{Area, BooleanOps, Coord, LineString, MultiPolygon, Polygon};
use kepler::clip::{self, ClipError};
use kepler::geometry::polygon::is_simple;
use kepler::geometry::predicates::orient2d;
use num_traits::{Signed, ToPrimitive, Zero};
use std::cmp::Ordering;
use std::time::Instant;

use crate::common::{Q, SplitMix64, q};

// ---------------------------------------------------------------------------------------------
// Building polygons.

fn ring(points: &[[f64; 2]]) -> LineString<f64> {
    points.iter().map(|&[x, y]| Coord { x, y }).collect()
}

fn poly(points: &[[f64; 2]]) -> MultiPolygon<f64> {
    Polygon::new(ring(points), vec![]).into()
}

fn poly_with_holes(outer: &[[f64; 2]], holes: &[&[[f64; 2]]]) -> MultiPolygon<f64> {
    Polygon::new(ring(outer), holes.iter().map(|h| ring(h)).collect()).into()
}

fn rect(x0: f64, y0: f64, x1: f64, y1: f64) -> MultiPolygon<f64> {
    poly(&[[x0, y0], [x1, y0], [x1, y1], [x0, y1]])
}

fn empty() -> MultiPolygon<f64> {
    MultiPolygon::new(vec![])
}

/// A polygon star-shaped about a random centre: `n ≥ 4` vertices at increasing angles (no
/// gap of π or more, for `n ≥ 5`) and random radii in `[r_min, r]`. Simple; convex when
/// `r_min == r`.
fn star(rng: &mut SplitMix64, n: usize, r_min: f64, r: f64) -> Vec<[f64; 2]> {
    let (cx, cy) = (rng.range(-1.0, 1.0), rng.range(-1.0, 1.0));
    let gaps: Vec<f64> = (0..n).map(|_| rng.range(1.0, 2.0)).collect();
    let unit = std::f64::consts::TAU / gaps.iter().sum::<f64>();
    let start = rng.range(0.0, std::f64::consts::TAU);
    let mut angle = start;
    gaps.iter()
        .map(|g| {
            angle += g * unit;
            let rho = rng.range(r_min, r);
            [cx + rho * angle.cos(), cy + rho * angle.sin()]
        })
        .collect()
}

/// A random triangle, convex quadrilateral or simple polygon of 5 to 12 vertices, at a random
/// place and size, counter-clockwise or clockwise.
fn random_polygon(rng: &mut SplitMix64) -> Vec<[f64; 2]> {
    let r = rng.range(0.3, 1.5);
    let mut points = match rng.below(3) {
        0 => (0..3)
            .map(|_| [rng.range(-1.5, 1.5), rng.range(-1.5, 1.5)])
            .collect(),
        1 => star(rng, 4, r, r),
        _ => {
            let n = 5 + rng.below(8);
            star(rng, n, 0.2 * r, r)
        }
    };
    if rng.below(2) == 0 {
        points.reverse();
    }
    assert!(is_simple(&points), "not simple: {points:?}");
    points
}

// ---------------------------------------------------------------------------------------------
// Exact references.

type Q2 = [Q; 2];

fn q2(p: [f64; 2]) -> Q2 {
    p.map(q)
}

fn qcross(a: &Q2, b: &Q2) -> Q {
    &a[0] * &b[1] - &a[1] * &b[0]
}

fn qsub(a: &Q2, b: &Q2) -> Q2 {
    [&a[0] - &b[0], &a[1] - &b[1]]
}

/// The exact meeting point of two segments that cross or touch at one point.
fn crossing(p0: [f64; 2], p1: [f64; 2], s0: [f64; 2], s1: [f64; 2]) -> Option<Q2> {
    let overlap = |a: f64, b: f64, c: f64, d: f64| a.min(b) <= c.max(d) && c.min(d) <= a.max(b);
    if !overlap(p0[0], p1[0], s0[0], s1[0]) || !overlap(p0[1], p1[1], s0[1], s1[1]) {
        return None;
    }
    let (p, s) = (q2(p0), q2(s0));
    let r = qsub(&q2(p1), &p);
    let v = qsub(&q2(s1), &s);
    let den = qcross(&r, &v);
    if den.is_zero() {
        return None;
    }
    let w = qsub(&s, &p);
    let t = qcross(&w, &v) / &den;
    let u = qcross(&w, &r) / &den;
    let unit = |x: &Q| !x.is_negative() && *x <= Q::from_integer(1.into());
    (unit(&t) && unit(&u)).then(|| [&p[0] + &t * &r[0], &p[1] + &t * &r[1]])
}

fn edges(polygons: &MultiPolygon<f64>) -> Vec<([f64; 2], [f64; 2])> {
    polygons
        .iter()
        .flat_map(|p| std::iter::once(p.exterior()).chain(p.interiors()))
        .flat_map(|r| {
            r.lines()
                .map(|l| ([l.start.x, l.start.y], [l.end.x, l.end.y]))
        })
        .collect()
}

fn vertices(polygons: &MultiPolygon<f64>) -> Vec<[f64; 2]> {
    polygons
        .iter()
        .flat_map(|p| std::iter::once(p.exterior()).chain(p.interiors()))
        .flat_map(|r| r.coords().map(|c| [c.x, c.y]))
        .collect()
}

/// The largest coordinate magnitude of the inputs.
fn max_magnitude(a: &MultiPolygon<f64>, b: &MultiPolygon<f64>) -> f64 {
    vertices(a)
        .iter()
        .chain(&vertices(b))
        .flatten()
        .fold(0.0, |m, x| m.max(x.abs()))
}

/// The spacing of `f64` values at `m` (a normal, positive number).
fn ulp(m: f64) -> f64 {
    f64::from_bits(m.to_bits() & (0x7ff << 52)) * f64::EPSILON
}

/// Where an output vertex may come from: the input vertices (exactly) and the exact crossings
/// of an edge of `a` with an edge of `b`. Each with its nearest `f64` for a quick search.
struct Candidates {
    exact: Vec<Q2>,
    approx: Vec<[f64; 2]>,
    /// How many of the first candidates are input vertices.
    inputs: usize,
}

impl Candidates {
    fn new(a: &MultiPolygon<f64>, b: &MultiPolygon<f64>) -> Candidates {
        let mut exact: Vec<Q2> = vertices(a).into_iter().chain(vertices(b)).map(q2).collect();
        let inputs = exact.len();
        let eb = edges(b);
        for (p0, p1) in edges(a) {
            exact.extend(eb.iter().filter_map(|&(s0, s1)| crossing(p0, p1, s0, s1)));
        }
        let approx = exact
            .iter()
            .map(|c| c.clone().map(|x| x.to_f64().expect("finite")))
            .collect();
        Candidates {
            exact,
            approx,
            inputs,
        }
    }

    /// The exact distance (largest of |dx|, |dy|) from `v` to the nearest candidate, rounded
    /// to `f64`, whether that candidate is an input vertex, and the distance to the nearest
    /// crossing candidate.
    fn error(&self, v: [f64; 2]) -> (f64, bool, f64) {
        let approx_dist = |c: &[f64; 2]| (v[0] - c[0]).abs().max((v[1] - c[1]).abs());
        let nearest = self
            .approx
            .iter()
            .map(approx_dist)
            .fold(f64::INFINITY, f64::min);
        let qv = q2(v);
        let mut best = (f64::INFINITY, false);
        let mut crossing = f64::INFINITY;
        for (i, c) in self.approx.iter().enumerate() {
            // Exact distances only for the candidates that can be nearest.
            if approx_dist(c) <= 2.0 * nearest + f64::MIN_POSITIVE {
                let e = qsub(&qv, &self.exact[i]);
                let d = e[0].abs().max(e[1].abs()).to_f64().expect("finite");
                if d < best.0 || (d == best.0 && i < self.inputs) {
                    best = (d, i < self.inputs);
                }
                if i >= self.inputs {
                    crossing = crossing.min(d);
                }
            }
        }
        (best.0, best.1, crossing)
    }
}

/// Largest vertex error of `result` in ulps of `m`; also the largest error among vertices
/// whose nearest candidate is an input vertex, and how many of those are bit-identical.
fn vertex_errors(result: &MultiPolygon<f64>, c: &Candidates, m: f64) -> (f64, f64, usize, usize) {
    let (mut worst, mut worst_input, mut identical, mut inputs) = (0.0_f64, 0.0_f64, 0, 0);
    for v in vertices(result) {
        let (d, nearest_is_input, crossing) = c.error(v);
        worst = worst.max(d / ulp(m));
        // A vertex off its nearest input vertex may be a crossing rounded (and snapped) next
        // to it: within an ulp of M, an input and a crossing can be that close.
        let is_input = nearest_is_input && (d == 0.0 || crossing > ulp(m));
        if is_input {
            inputs += 1;
            identical += usize::from(d == 0.0);
            worst_input = worst_input.max(d / ulp(m));
        }
    }
    (worst, worst_input, identical, inputs)
}

/// geo's conventions, as the module promises: rings closed, exteriors counter-clockwise,
/// holes clockwise, no repeated vertex, no vertex between two collinear edges (exactly).
fn check_conventions(result: &MultiPolygon<f64>) {
    // Scaled by a power of two, exactly, so that the products in orient2d do not underflow.
    let m = vertices(result)
        .iter()
        .flatten()
        .fold(0.0_f64, |m, x| m.max(x.abs()));
    let s = 1.0 / f64::from_bits(m.to_bits() & (0x7ff << 52));
    for polygon in result {
        let rings = std::iter::once((polygon.exterior(), Ordering::Greater))
            .chain(polygon.interiors().iter().map(|r| (r, Ordering::Less)));
        for (r, turn) in rings {
            let p: Vec<[f64; 2]> = r.coords().map(|c| [c.x * s, c.y * s]).collect();
            assert!(p.len() >= 4, "ring too short: {p:?}");
            assert_eq!(p.first(), p.last(), "ring not closed: {p:?}");
            let n = p.len() - 1;
            let corner = |i: usize| orient2d(p[(i + n - 1) % n], p[i], p[(i + 1) % n]);
            for i in 0..n {
                assert_ne!(p[i], p[i + 1], "repeated vertex in {p:?}");
                assert_ne!(corner(i), Ordering::Equal, "collinear vertex {i} in {p:?}");
            }
            // The turn at the lowest-leftmost vertex is the ring's orientation.
            let low = (0..n)
                .min_by(|&i, &j| {
                    p[i][0]
                        .total_cmp(&p[j][0])
                        .then(p[i][1].total_cmp(&p[j][1]))
                })
                .expect("a vertex");
            assert_eq!(corner(low), turn, "ring orientation: {p:?}");
        }
    }
}

/// The polygons with each ring starting at its lowest-leftmost vertex, the polygons sorted:
/// equal for equal point sets with the same conventions.
fn canonical(m: &MultiPolygon<f64>) -> Vec<Vec<Vec<(u64, u64)>>> {
    let ring = |r: &LineString<f64>| {
        let mut v: Vec<(u64, u64)> = r.coords().map(|c| (c.x.to_bits(), c.y.to_bits())).collect();
        v.pop();
        let low = (0..v.len())
            .min_by(|&i, &j| {
                let (a, b) = (r.0[i], r.0[j]);
                a.x.total_cmp(&b.x).then(a.y.total_cmp(&b.y))
            })
            .unwrap_or(0);
        v.rotate_left(low);
        v
    };
    let mut polygons: Vec<Vec<Vec<(u64, u64)>>> = m
        .iter()
        .map(|p| {
            let mut holes: Vec<_> = p.interiors().iter().map(ring).collect();
            holes.sort();
            std::iter::once(ring(p.exterior())).chain(holes).collect()
        })
        .collect();
    polygons.sort();
    polygons
}

fn assert_same(a: &MultiPolygon<f64>, b: &MultiPolygon<f64>) {
    assert_eq!(canonical(a), canonical(b), "{a:?} != {b:?}");
}

fn area(m: &MultiPolygon<f64>) -> f64 {
    m.unsigned_area()
}

fn ops(a: &MultiPolygon<f64>, b: &MultiPolygon<f64>) -> [MultiPolygon<f64>; 3] {
    [
        clip::intersection(a, b).expect("finite input"),
        clip::difference(a, b).expect("finite input"),
        clip::union(a, b).expect("finite input"),
    ]
}

fn xy_set(m: &MultiPolygon<f64>) -> Vec<(u64, u64)> {
    let mut v: Vec<(u64, u64)> = vertices(m)
        .iter()
        .map(|p| (p[0].to_bits(), p[1].to_bits()))
        .collect();
    v.sort_unstable();
    v.dedup();
    v
}

// ---------------------------------------------------------------------------------------------
// Random inputs against exact references.

const PAIRS: usize = 300;

#[test]
fn vertices_are_input_vertices_or_exact_crossings_to_half_an_ulp() {
    let mut rng = SplitMix64(0x5eed_c11b);
    let (mut worst, mut worst_input, mut identical, mut inputs, mut total) = (0.0, 0.0, 0, 0, 0);
    for trial in 0..PAIRS {
        let (pa, pb) = (random_polygon(&mut rng), random_polygon(&mut rng));
        let (a, b) = (poly(&pa), poly(&pb));
        let m = max_magnitude(&a, &b);
        let c = Candidates::new(&a, &b);
        for result in ops(&a, &b) {
            check_conventions(&result);
            let (w, wi, id, n) = vertex_errors(&result, &c, m);
            assert!(
                w <= 1.0,
                "trial {trial}: vertex off by {w} ulps; a = {pa:?}, b = {pb:?}"
            );
            // An input vertex moves only when it is finer than the grid, by ulp(m)/512 at most.
            assert!(
                wi <= 1.0 / 512.0,
                "trial {trial}: input vertex moved by {wi} ulps"
            );
            worst = f64::max(worst, w);
            worst_input = f64::max(worst_input, wi);
            identical += id;
            inputs += n;
            total += vertices(&result).len();
        }
    }
    eprintln!(
        "clip (i_overlay 9, i64): {total} vertices over {PAIRS} pairs x 3 operations; \
         max error {worst:.3} ulp of the largest coordinate; input vertices bit-identical \
         {identical}/{inputs} (max move {worst_input:.2e} ulp)"
    );
}

#[test]
fn areas_add_up() {
    let mut rng = SplitMix64(0xa4ea);
    for trial in 0..PAIRS {
        let (a, b) = (
            poly(&random_polygon(&mut rng)),
            poly(&random_polygon(&mut rng)),
        );
        let [both, only_a, either] = ops(&a, &b);
        let (aa, ab) = (area(&a), area(&b));
        let scale = aa + ab;
        let split = area(&both) + area(&only_a) - aa;
        assert!(
            split.abs() <= 1e-12 * scale,
            "trial {trial}: A∩B + A\\B - A = {split}"
        );
        let incl = area(&either) - (aa + ab - area(&both));
        assert!(
            incl.abs() <= 1e-12 * scale,
            "trial {trial}: A∪B - (A + B - A∩B) = {incl}"
        );
        assert!(area(&both) <= aa.min(ab) * (1.0 + 1e-12));
    }
}

#[test]
fn geo_boolean_ops_agrees_on_areas_and_moves_vertices_more() {
    let mut rng = SplitMix64(0x6e0);
    let (mut ours, mut theirs, mut area_dev) = (0.0_f64, 0.0_f64, 0.0_f64);
    for trial in 0..PAIRS / 2 {
        let (a, b) = (
            poly(&random_polygon(&mut rng)),
            poly(&random_polygon(&mut rng)),
        );
        let m = max_magnitude(&a, &b);
        let c = Candidates::new(&a, &b);
        let geo = [a.intersection(&b), a.difference(&b), a.union(&b)];
        for (k, (mine, other)) in ops(&a, &b).iter().zip(&geo).enumerate() {
            // geo moves vertices by about 5e-9 of the largest coordinate, hence 1e-8.
            let dev = (area(mine) - area(other)).abs() / (area(&a) + area(&b));
            assert!(
                dev <= 1e-8,
                "trial {trial}, operation {k}: areas differ by {dev:e}"
            );
            area_dev = area_dev.max(dev);
            ours = ours.max(vertex_errors(mine, &c, m).0);
            theirs = theirs.max(vertex_errors(other, &c, m).0);
        }
    }
    eprintln!(
        "max vertex error from the exact reference, in ulps of the largest coordinate M: \
         kepler::clip {ours:.3} ulp, geo BooleanOps {theirs:.3e} ulp (about {:.1e} M); \
         max area difference {area_dev:.2e} of area(A) + area(B)",
        theirs * f64::EPSILON
    );
    assert!(
        ours <= 1.0 && theirs > ours,
        "kepler::clip {ours} ulp, geo {theirs} ulp"
    );
}

#[test]
fn a_typical_clip_of_two_100_vertex_polygons_is_fast() {
    let mut rng = SplitMix64(0x100);
    let pairs: Vec<_> = (0..50)
        .map(|_| {
            (
                poly(&star(&mut rng, 100, 0.5, 1.0)),
                poly(&star(&mut rng, 100, 0.5, 1.0)),
            )
        })
        .collect();
    // The fastest of 5 rounds over the 50 pairs, per clip.
    let fastest = |clip: &dyn Fn(&MultiPolygon<f64>, &MultiPolygon<f64>) -> usize| {
        let mut best = f64::INFINITY;
        let mut count = 0;
        for _ in 0..5 {
            let start = Instant::now();
            count = pairs.iter().map(|(a, b)| clip(a, b)).sum::<usize>();
            best = best.min(start.elapsed().as_secs_f64() / pairs.len() as f64);
        }
        (best, count)
    };
    let (ours, vertex_count) =
        fastest(&|a, b| vertices(&clip::intersection(a, b).expect("finite")).len());
    let (geo, _) = fastest(&|a, b| vertices(&a.intersection(b)).len());
    eprintln!(
        "intersection of two 100-vertex star polygons ({} output vertices on average): \
         kepler::clip {:.1} µs, geo BooleanOps {:.1} µs",
        vertex_count / pairs.len(),
        ours * 1e6,
        geo * 1e6
    );
    assert!(vertex_count > 0);
}

/// A random polygon with its coordinates rounded to multiples of `step`, some then nudged by
/// an ulp or two: shared vertices, collinear overlapping edges, vertices on edges, and
/// crossings next to vertices.
fn near_degenerate_polygon(rng: &mut SplitMix64, step: f64) -> Vec<[f64; 2]> {
    loop {
        let mut points: Vec<[f64; 2]> = random_polygon(rng)
            .iter()
            .map(|p| p.map(|x| (x / step).round() * step))
            .collect();
        for x in points.iter_mut().flatten() {
            // Zero is not nudged: its neighbours in bits are subnormals or NaN.
            if rng.below(4) == 0 && *x != 0.0 {
                let nudge = rng.pick(&[-2_i64, -1, 1, 2]);
                *x = f64::from_bits(x.to_bits().wrapping_add_signed(nudge));
            }
        }
        let turn = |i: usize| {
            let n = points.len();
            orient2d(points[(i + n - 1) % n], points[i], points[(i + 1) % n])
        };
        if is_simple(&points) && (0..points.len()).all(|i| turn(i) != Ordering::Equal) {
            return points;
        }
    }
}

#[test]
fn near_degenerate_inputs_stay_exact() {
    let mut rng = SplitMix64(0xde9e);
    let mut worst = 0.0_f64;
    for trial in 0..PAIRS {
        let step = rng.pick(&[0.25, 0.5]);
        let (pa, pb) = (
            near_degenerate_polygon(&mut rng, step),
            near_degenerate_polygon(&mut rng, step),
        );
        let (a, b) = (poly(&pa), poly(&pb));
        let (m, c) = (max_magnitude(&a, &b), Candidates::new(&a, &b));
        let results = ops(&a, &b);
        for r in &results {
            check_conventions(r);
            let (w, wi, _, _) = vertex_errors(r, &c, m);
            assert!(
                w <= 1.0 && wi <= 1.0 / 512.0,
                "trial {trial}: {w} ulps; {pa:?} {pb:?}"
            );
            worst = worst.max(w);
        }
        let [both, only_a, either] = &results;
        let sum = area(&a) + area(&b);
        let split = area(both) + area(only_a) - area(&a);
        let incl = area(either) - (sum - area(both));
        // Relative to m² too: nudged vertices make slivers of area about ulp(m)·m.
        let tolerance = 1e-12 * sum.max(m * m);
        assert!(
            split.abs().max(incl.abs()) <= tolerance,
            "trial {trial}: {split}, {incl}; areas {} {}; {pa:?} {pb:?}",
            area(&a),
            area(&b)
        );
    }
    eprintln!("near-degenerate inputs: max vertex error {worst:.3} ulp of the largest coordinate");
}

// ---------------------------------------------------------------------------------------------
// Degenerate inputs.

#[test]
fn shared_edge() {
    let (a, b) = (rect(0.0, 0.0, 1.0, 1.0), rect(1.0, 0.0, 2.0, 1.0));
    let [both, only_a, either] = ops(&a, &b);
    assert!(both.0.is_empty(), "{both:?}");
    assert_same(&only_a, &a);
    // One rectangle, without the vertices (1, 0) and (1, 1) of the shared edge.
    assert_eq!(either.0.len(), 1);
    assert_eq!(xy_set(&either), xy_set(&rect(0.0, 0.0, 2.0, 1.0)));
    check_conventions(&either);
}

#[test]
fn collinear_overlapping_edges() {
    let (a, b) = (rect(0.0, 0.0, 2.0, 2.0), rect(1.0, 0.0, 3.0, 1.0));
    let [both, only_a, either] = ops(&a, &b);
    assert_eq!(xy_set(&both), xy_set(&rect(1.0, 0.0, 2.0, 1.0)));
    assert_eq!(area(&only_a), 3.0);
    assert_eq!(
        xy_set(&only_a),
        xy_set(&poly(&[
            [0.0, 0.0],
            [1.0, 0.0],
            [1.0, 1.0],
            [2.0, 1.0],
            [2.0, 2.0],
            [0.0, 2.0]
        ]))
    );
    assert_eq!(area(&either), 5.0);
    for r in [&both, &only_a, &either] {
        check_conventions(r);
    }
}

#[test]
fn polygons_touching_at_a_vertex() {
    let (a, b) = (rect(0.0, 0.0, 1.0, 1.0), rect(1.0, 1.0, 2.0, 2.0));
    let [both, only_a, either] = ops(&a, &b);
    assert!(both.0.is_empty(), "{both:?}");
    assert_same(&only_a, &a);
    assert_eq!(area(&either), 2.0);
    assert_eq!(
        xy_set(&either),
        xy_set(&MultiPolygon::new(vec![a.0[0].clone(), b.0[0].clone()]))
    );
    // A triangle whose apex touches the square's side.
    let t = poly(&[[1.0, 0.5], [2.0, 0.0], [2.0, 1.0]]);
    assert!(clip::intersection(&a, &t).expect("finite").0.is_empty());
    assert_eq!(area(&clip::union(&a, &t).expect("finite")), 1.5);
}

#[test]
fn identical_polygons() {
    let mut rng = SplitMix64(7);
    for _ in 0..20 {
        let a = poly(&random_polygon(&mut rng));
        let [both, only_a, either] = ops(&a, &a);
        assert!(only_a.0.is_empty(), "{only_a:?}");
        assert_eq!(xy_set(&both), xy_set(&a));
        assert_eq!(xy_set(&either), xy_set(&a));
        assert!((area(&both) - area(&a)).abs() <= 1e-15 * area(&a));
    }
}

#[test]
fn nested_polygons_make_holes() {
    let outer = rect(0.0, 0.0, 4.0, 4.0);
    let inner = poly(&[[1.0, 1.0], [3.0, 1.5], [2.0, 3.0]]);
    let [both, ring_of, either] = ops(&outer, &inner);
    assert_eq!(xy_set(&both), xy_set(&inner));
    assert_eq!(xy_set(&either), xy_set(&outer));
    assert_eq!(ring_of.0.len(), 1);
    assert_eq!(ring_of.0[0].interiors().len(), 1);
    assert_eq!(area(&ring_of), 16.0 - area(&inner));
    check_conventions(&ring_of);
    assert!(
        clip::difference(&inner, &outer)
            .expect("finite")
            .0
            .is_empty()
    );
    // Filling the hole again, and cutting a polygon that straddles the hole's boundary.
    let filled = clip::union(&ring_of, &inner).expect("finite");
    assert_eq!(xy_set(&filled), xy_set(&outer));
    let straddle = rect(2.0, 0.5, 5.0, 2.0);
    let cut = clip::intersection(&ring_of, &straddle).expect("finite");
    let expected = area(&clip::intersection(&outer, &straddle).expect("finite"))
        - area(&clip::intersection(&inner, &straddle).expect("finite"));
    assert!((area(&cut) - expected).abs() < 1e-15);
    check_conventions(&cut);
    // A polygon with a hole as input, and an island inside the hole.
    let holed = poly_with_holes(
        &[[0.0, 0.0], [4.0, 0.0], [4.0, 4.0], [0.0, 4.0]],
        &[&[[1.0, 1.0], [3.0, 1.0], [3.0, 3.0], [1.0, 3.0]]],
    );
    let island = rect(1.5, 1.5, 2.5, 2.5);
    let both = clip::union(&holed, &island).expect("finite");
    assert_eq!(both.0.len(), 2);
    assert_eq!(area(&both), 13.0);
    assert!(
        clip::intersection(&holed, &island)
            .expect("finite")
            .0
            .is_empty()
    );
    check_conventions(&both);
}

#[test]
fn disjoint_polygons() {
    let (a, b) = (
        rect(0.0, 0.0, 1.0, 1.0),
        poly(&[[3.0, 3.0], [4.0, 3.0], [3.5, 4.0]]),
    );
    let [both, only_a, either] = ops(&a, &b);
    assert!(both.0.is_empty());
    assert_same(&only_a, &a);
    assert_eq!(either.0.len(), 2);
    assert_eq!(area(&either), 1.5);
}

#[test]
fn orientation_and_closing_vertex_do_not_matter() {
    let a = rect(0.0, 0.0, 2.0, 2.0);
    let b = poly(&[[1.0, 1.0], [3.0, 0.5], [2.5, 3.0]]);
    let clockwise = poly(&[[1.0, 1.0], [2.5, 3.0], [3.0, 0.5]]);
    assert_eq!(ops(&a, &b), ops(&a, &clockwise));
    // A collinear vertex in an input is not kept.
    let a_mid = poly(&[[0.0, 0.0], [1.0, 0.0], [2.0, 0.0], [2.0, 2.0], [0.0, 2.0]]);
    assert_eq!(ops(&a, &b), ops(&a_mid, &b));
}

#[test]
fn far_from_the_origin() {
    let x0 = 1e6;
    let e = 1e-3;
    let a = rect(x0, x0, x0 + 3.0 * e, x0 + 2.0 * e);
    let b = rect(x0 + e, x0 + e, x0 + 5.0 * e, x0 + 4.0 * e);
    let [both, only_a, either] = ops(&a, &b);
    // Axis-parallel edges: every output coordinate is an input coordinate, bit for bit.
    assert_eq!(
        xy_set(&both),
        xy_set(&rect(x0 + e, x0 + e, x0 + 3.0 * e, x0 + 2.0 * e))
    );
    let inputs = xy_set(&MultiPolygon::new(vec![a.0[0].clone(), b.0[0].clone()]));
    let xs: Vec<u64> = inputs.iter().flat_map(|&(x, y)| [x, y]).collect();
    for r in [&only_a, &either] {
        for (x, y) in xy_set(r) {
            assert!(xs.contains(&x) && xs.contains(&y));
        }
        check_conventions(r);
    }
    // Crossing edges: within half an ulp of 1e6 + 0.01 of the exact crossings.
    let mut rng = SplitMix64(0xfa4);
    for _ in 0..50 {
        let shift = |p: Vec<[f64; 2]>| -> Vec<[f64; 2]> {
            p.iter()
                .map(|&[x, y]| [x0 + 1e-3 * x, x0 + 1e-3 * y])
                .collect()
        };
        let (a, b) = (
            poly(&shift(random_polygon(&mut rng))),
            poly(&shift(random_polygon(&mut rng))),
        );
        let (m, c) = (max_magnitude(&a, &b), Candidates::new(&a, &b));
        for r in ops(&a, &b) {
            let (w, wi, _, _) = vertex_errors(&r, &c, m);
            assert!(
                w <= 1.0 && wi == 0.0,
                "error {w} ulps, input vertex moved {wi} ulps"
            );
        }
    }
}

#[test]
fn tiny_coordinates() {
    for s in [1e-12, 1e-150, 1e-280] {
        let a = rect(0.0, 0.0, 3.0 * s, 2.0 * s);
        let b = poly(&[[s, s], [4.0 * s, s], [s, 4.0 * s]]);
        let (m, c) = (max_magnitude(&a, &b), Candidates::new(&a, &b));
        for r in ops(&a, &b) {
            assert!(!r.0.is_empty());
            let (w, wi, id, n) = vertex_errors(&r, &c, m);
            assert!(w <= 1.0 && wi == 0.0 && id == n, "scale {s:e}: {w} ulps");
            check_conventions(&r);
        }
    }
    // Below the adapter's range the grid is 2^-1023: subnormal polygons vanish, no panic.
    let sub = rect(0.0, 0.0, 4.0 * f64::from_bits(1), 4.0 * f64::from_bits(1));
    for r in ops(&sub, &sub) {
        assert!(area(&r) <= 1e-320);
    }
}

#[test]
fn self_crossing_rings_use_even_odd() {
    // A bow tie: both lobes are inside, whatever their turning sense.
    let bow = poly(&[[0.0, 0.0], [2.0, 2.0], [2.0, 0.0], [0.0, 2.0]]);
    let big = rect(-1.0, -1.0, 3.0, 3.0);
    let both = clip::intersection(&bow, &big).expect("finite");
    assert_eq!(area(&both), 2.0);
    assert_eq!(both.0.len(), 2);
    check_conventions(&both);
    // Two overlapping members of one operand cancel where they overlap.
    let overlapping = MultiPolygon::new(vec![
        rect(0.0, 0.0, 2.0, 2.0).0[0].clone(),
        rect(1.0, 0.0, 3.0, 2.0).0[0].clone(),
    ]);
    assert_eq!(
        area(&clip::union(&overlapping, &empty()).expect("finite")),
        4.0
    );
}

#[test]
fn empty_inputs() {
    let a = poly(&[[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]]);
    for (x, y) in [(&a, &empty()), (&empty(), &a), (&empty(), &empty())] {
        assert!(clip::intersection(x, y).expect("finite").0.is_empty());
    }
    assert_same(&clip::union(&a, &empty()).expect("finite"), &a);
    assert_same(&clip::union(&empty(), &a).expect("finite"), &a);
    assert_same(&clip::difference(&a, &empty()).expect("finite"), &a);
    assert!(clip::difference(&empty(), &a).expect("finite").0.is_empty());
    assert!(
        clip::union(&empty(), &empty())
            .expect("finite")
            .0
            .is_empty()
    );
    // Rings with fewer than three distinct vertices, or no area.
    let flat = poly(&[[0.0, 0.0], [1.0, 1.0], [2.0, 2.0]]);
    let point = poly(&[[0.5, 0.5]]);
    let nothing = Polygon::new(LineString::new(vec![]), vec![]).into();
    for d in [&flat, &point, &nothing] {
        assert!(clip::intersection(&a, d).expect("finite").0.is_empty());
        assert_same(&clip::union(&a, d).expect("finite"), &a);
    }
}

#[test]
fn non_finite_and_huge_coordinates_are_errors() {
    let a = rect(0.0, 0.0, 1.0, 1.0);
    for bad in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
        let b = poly(&[[0.0, 0.0], [bad, 0.0], [0.0, 1.0]]);
        for (x, y) in [(&a, &b), (&b, &a)] {
            assert_eq!(clip::intersection(x, y), Err(ClipError::NotFinite));
            assert_eq!(clip::difference(x, y), Err(ClipError::NotFinite));
            assert_eq!(clip::union(x, y), Err(ClipError::NotFinite));
        }
    }
    let limit = 2f64.powi(500);
    let huge = rect(0.0, 0.0, limit, limit);
    assert_eq!(
        area(&clip::union(&a, &huge).expect("at the limit")),
        limit * limit
    );
    let beyond = rect(0.0, 0.0, 1e151, 1.0);
    assert_eq!(clip::union(&a, &beyond), Err(ClipError::TooLarge));
    assert_eq!(clip::intersection(&beyond, &a), Err(ClipError::TooLarge));
}
