//! Hatching (`surfaces::hatch`) against an exact reference.
//!
//! For every hatch line `n·x = c` (`n` and `c = k·s` the doubles the library uses), the
//! reference computes in rationals, independently of the library's sweep: the exact points
//! where the polygons' edges meet the line (vertices on it, crossings), sorted along it; for
//! each stretch between two consecutive ones, whether the polygons (even-odd over all rings)
//! cover both sides of it, by the crossing number of a horizontal ray from points pushed off
//! the stretch's midpoint by a rational distance smaller than that to every edge. The library
//! must return one segment per covered stretch, in order, each end within `1e-12` of the scale
//! of the exact end, with its midpoint inside or on the polygons and crossing no edge properly
//! (both decided in rationals), and drop nothing.
//!
//! The polygons are random rings (self-crossing ones included, several per set, with holes in
//! the even-odd sense) with vertices on a lattice the lines pass through (vertices on lines,
//! edges along lines, zero-area slivers), and random ones at general angles; at scales `2^±300`
//! (where the hatch must be the unscaled one scaled, bit for bit) and `1e8` from the origin.

use crate::common::{Q, SplitMix64, q, qsign};
use geo::{Coord, LineString, MultiPolygon, Polygon};
use kepler::geometry::exact::ldexp;
use kepler::surfaces::hatch::{Hatch, Hatching, direction, hatch_faces, hatch_polygons};
use num_traits::{Signed, Zero};
use std::cmp::Ordering;

type P = [Q; 2];

fn qp(p: [f64; 2]) -> P {
    p.map(q)
}

fn sub(a: &P, b: &P) -> P {
    [&a[0] - &b[0], &a[1] - &b[1]]
}

fn dot(a: &P, b: &P) -> Q {
    &a[0] * &b[0] + &a[1] * &b[1]
}

fn cross(a: &P, b: &P) -> Q {
    &a[0] * &b[1] - &a[1] * &b[0]
}

/// `orient2d(a, b, c)` in rationals.
fn orient(a: &P, b: &P, c: &P) -> Ordering {
    qsign(&cross(&sub(b, a), &sub(c, a)))
}

fn l1(a: &P) -> Q {
    a[0].abs() + a[1].abs()
}

/// The rings of a multipolygon as open lists of exact points (as the library reads them:
/// consecutive repeats and the closing point left out, rings of fewer than 3 points dropped).
fn exact_rings(m: &MultiPolygon<f64>) -> Vec<Vec<P>> {
    m.iter()
        .flat_map(|p| std::iter::once(p.exterior()).chain(p.interiors()))
        .map(|r| {
            let mut v: Vec<[f64; 2]> = r.coords().map(|c| [c.x, c.y]).collect();
            v.dedup();
            while v.len() > 1 && v.first() == v.last() {
                v.pop();
            }
            v.into_iter().map(qp).collect::<Vec<P>>()
        })
        .filter(|r| r.len() >= 3)
        .collect()
}

fn edges(rings: &[Vec<P>]) -> Vec<(P, P)> {
    rings
        .iter()
        .flat_map(|r| (0..r.len()).map(move |i| (r[i].clone(), r[(i + 1) % r.len()].clone())))
        .collect()
}

/// Whether `x` lies on the closed segment `p q`.
fn on_segment(p: &P, q: &P, x: &P) -> bool {
    orient(p, q, x) == Ordering::Equal
        && (0..2).all(|k| {
            let (lo, hi) = if p[k] <= q[k] {
                (&p[k], &q[k])
            } else {
                (&q[k], &p[k])
            };
            lo <= &x[k] && &x[k] <= hi
        })
}

/// The even-odd crossing number of a horizontal ray from `x` to the right (half-open at
/// vertices): odd inside. `x` must not lie on an edge.
fn odd(edges: &[(P, P)], x: &P) -> bool {
    let mut odd = false;
    for (p, q) in edges {
        if (p[1] > x[1]) != (q[1] > x[1]) {
            // The crossing's abscissa exceeds x's: orient(p, q, x) has the sign of q.y − p.y.
            let o = orient(p, q, x);
            let up = if q[1] > p[1] {
                Ordering::Greater
            } else {
                Ordering::Less
            };
            if o == up {
                odd = !odd;
            }
        }
    }
    odd
}

fn inside_or_on(edges: &[(P, P)], x: &P) -> bool {
    edges.iter().any(|(p, q)| on_segment(p, q, x)) || odd(edges, x)
}

fn properly_crosses(a: &P, b: &P, p: &P, q: &P) -> bool {
    let opposite = |s: Ordering, t: Ordering| s != Ordering::Equal && s == t.reverse();
    opposite(orient(a, b, p), orient(a, b, q)) && opposite(orient(p, q, a), orient(p, q, b))
}

/// Whether the segment `a b` (on the line `n·x = c`) crosses the edge `p q` properly, other
/// than where the edge meets the line at a point another edge holds too: a hatch runs on
/// through a point of the line where two pieces share an edge, or two edges cross (the outline
/// pinched to a point), and may cross those edges within rounding there.
fn crosses_outline(edges: &[(P, P)], a: &P, b: &P, p: &P, q: &P, n: &P, c: &Q) -> bool {
    if !properly_crosses(a, b, p, q) {
        return false;
    }
    let (sp, sq) = (dot(n, p) - c, dot(n, q) - c);
    if sp.is_zero() || sq.is_zero() || sp.is_positive() == sq.is_positive() {
        return true;
    }
    let t = &sp / (&sp - &sq);
    let x = [&p[0] + (&q[0] - &p[0]) * &t, &p[1] + (&q[1] - &p[1]) * &t];
    edges.iter().filter(|(e, f)| on_segment(e, f, &x)).count() < 2
}

/// The reference: the covered stretches of line `n·x = c` as pairs of exact points, in order
/// along `d`.
fn reference(edges: &[(P, P)], d: &P, c: &Q) -> Vec<(P, P)> {
    let n: P = [-d[1].clone(), d[0].clone()];
    let dd = dot(d, d);
    let side = |x: &P| dot(&n, x) - c;
    let mut positions: Vec<Q> = Vec::new();
    for (p, q) in edges {
        let (a, b) = (side(p), side(q));
        if a.is_zero() {
            positions.push(dot(d, p));
        } else if !b.is_zero() && (a.is_positive() != b.is_positive()) {
            let t = &a / (&a - &b);
            let x = [&p[0] + (&q[0] - &p[0]) * &t, &p[1] + (&q[1] - &p[1]) * &t];
            positions.push(dot(d, &x));
        }
    }
    positions.sort();
    positions.dedup();
    let at = |t: &Q| -> P { [(c * &n[0] + t * &d[0]) / &dd, (c * &n[1] + t * &d[1]) / &dd] };
    let two = Q::from_integer(2.into());
    let mut out = Vec::new();
    for w in positions.windows(2) {
        let m = at(&((&w[0] + &w[1]) / &two));
        // A distance to every edge not through m, over |n|₁.
        let mut eps: Option<Q> = None;
        let mut keep = |e: Q| {
            if e.is_positive() && eps.as_ref().is_none_or(|x| &e < x) {
                eps = Some(e);
            }
        };
        for (p, q) in edges {
            let area = cross(&sub(q, p), &sub(&m, p)).abs();
            if area.is_positive() {
                keep(area / l1(&sub(q, p)));
            } else if !on_segment(p, q, &m) {
                for end in [p, q] {
                    let g = sub(&m, end);
                    keep(if g[0].abs() > g[1].abs() {
                        g[0].abs()
                    } else {
                        g[1].abs()
                    });
                }
            }
        }
        let eps = eps.expect("some edge off the line") / (l1(&n) * &two);
        let off = |sign: &Q| [&m[0] + &n[0] * &eps * sign, &m[1] + &n[1] * &eps * sign];
        let one = Q::from_integer(1.into());
        if odd(edges, &off(&one)) && odd(edges, &off(&-one.clone())) {
            out.push((at(&w[0]), at(&w[1])));
        }
    }
    out
}

/// Checks the library's hatch of `polygons` against the reference and the exact containment
/// tests; returns the number of segments.
fn check(polygons: &MultiPolygon<f64>, angle: f64, spacing: f64) -> usize {
    let hatch = hatch_polygons(polygons, angle, spacing).expect("hatch");
    assert_eq!(hatch.dropped, 0, "dropped segments at angle {angle}");
    let rings = exact_rings(polygons);
    let edges = edges(&rings);
    let scale = polygons
        .iter()
        .flat_map(|p| std::iter::once(p.exterior()).chain(p.interiors()))
        .flat_map(|r| r.coords())
        .fold(0.0f64, |m, c| m.max(c.x.abs()).max(c.y.abs()));
    let tolerance = q(scale * 1e-12);
    let d = direction(angle).expect("finite angle");
    let qd = qp(d);
    let qn: P = [-qd[1].clone(), qd[0].clone()];
    let two = Q::from_integer(2.into());
    let mut segments = 0;
    // Lines in order, as the library lists them.
    let mut lines: Vec<i64> = hatch.runs.iter().map(|r| r.line).collect();
    lines.dedup();
    let u = |x: [f64; 2]| -d[1] * x[0] + d[0] * x[1];
    let (lo, hi) = polygons
        .iter()
        .flat_map(|p| std::iter::once(p.exterior()).chain(p.interiors()))
        .flat_map(|r| r.coords())
        .map(|c| u([c.x, c.y]))
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| {
            (a.min(v), b.max(v))
        });
    let first = (lo / spacing).floor() as i64 - 1;
    let last = (hi / spacing).ceil() as i64 + 1;
    for k in first..=last {
        let c = q(k as f64 * spacing);
        let expected = reference(&edges, &qd, &c);
        let got: Vec<[[f64; 2]; 2]> = hatch
            .runs
            .iter()
            .filter(|r| r.line == k)
            .flat_map(|r| r.segments().collect::<Vec<_>>())
            .collect();
        assert_eq!(
            got.len(),
            expected.len(),
            "line {k} at angle {angle}: {got:?} against {} stretches",
            expected.len()
        );
        for (s, (ea, eb)) in got.iter().zip(&expected) {
            let (a, b) = (qp(s[0]), qp(s[1]));
            for (x, e) in [(&a, ea), (&b, eb)] {
                let far = sub(x, e);
                assert!(
                    far[0].abs() <= tolerance && far[1].abs() <= tolerance,
                    "line {k}: end {x:?} far from the exact {e:?}"
                );
            }
            let m = [(&a[0] + &b[0]) / &two, (&a[1] + &b[1]) / &two];
            assert!(inside_or_on(&edges, &m), "line {k}: segment {s:?} outside");
            for (p, q) in &edges {
                assert!(
                    !crosses_outline(&edges, &a, &b, p, q, &qn, &c),
                    "line {k}: segment {s:?} crosses the edge {p:?} {q:?}"
                );
            }
            segments += 1;
        }
    }
    assert!(lines.iter().all(|k| (first..=last).contains(k)));
    segments
}

fn polygon(rings: Vec<Vec<[f64; 2]>>) -> MultiPolygon<f64> {
    let ls =
        |r: Vec<[f64; 2]>| LineString::new(r.into_iter().map(|[x, y]| Coord { x, y }).collect());
    let mut rings = rings.into_iter();
    let outer = rings
        .next()
        .map(ls)
        .unwrap_or_else(|| LineString::new(vec![]));
    MultiPolygon::new(vec![Polygon::new(outer, rings.map(ls).collect())])
}

/// A random ring of `n` points from `point`.
fn ring(
    rng: &mut SplitMix64,
    n: usize,
    point: &mut impl FnMut(&mut SplitMix64) -> [f64; 2],
) -> Vec<[f64; 2]> {
    (0..n).map(|_| point(rng)).collect()
}

/// Random sets of rings on the lattice of quarter units (spacing 1/2 or 1: many vertices on
/// lines and edges along them), with a zero-area sliver now and then.
fn lattice_sets(rng: &mut SplitMix64, count: usize) -> Vec<MultiPolygon<f64>> {
    (0..count)
        .map(|_| {
            let mut point = |r: &mut SplitMix64| [r.int(-12, 12) / 4.0, r.int(-12, 12) / 4.0];
            let rings = rng.below(3) + 1;
            let mut set: Vec<Vec<[f64; 2]>> = (0..rings)
                .map(|_| {
                    let n = 3 + rng.below(6);
                    ring(rng, n, &mut point)
                })
                .collect();
            if rng.below(3) == 0 {
                // A sliver: three points on one lattice line.
                let y = rng.int(-12, 12) / 4.0;
                set.push(vec![[-2.0, y], [1.0, y], [3.0, y]]);
            }
            polygon(set)
        })
        .collect()
}

fn scaled(m: &MultiPolygon<f64>, k: i32) -> MultiPolygon<f64> {
    use geo::MapCoords;
    m.map_coords(|c| Coord {
        x: ldexp(c.x, k),
        y: ldexp(c.y, k),
    })
}

fn scaled_hatch(h: &Hatch, k: i32) -> Hatch {
    let mut h = h.clone();
    for r in &mut h.runs {
        for p in &mut r.points {
            *p = p.map(|c| ldexp(c, k));
        }
    }
    h
}

/// Lines through lattice vertices and along lattice edges, at 0°, 90°, 180° and 45° (whose
/// line through the origin holds the diagonal's vertices), against the reference.
#[test]
fn lattice_rings_are_clipped_exactly() {
    let mut rng = SplitMix64(17);
    let mut segments = 0;
    for set in &lattice_sets(&mut rng, 30) {
        for (angle, spacing) in [(0.0, 0.5), (90.0, 0.25), (180.0, 1.0), (45.0, 0.75)] {
            segments += check(set, angle, spacing);
        }
    }
    assert!(segments > 300, "{segments} segments");
}

/// Random rings of random doubles at general angles.
#[test]
fn random_rings_at_general_angles_are_clipped_exactly() {
    let mut rng = SplitMix64(5);
    let mut segments = 0;
    for _ in 0..8 {
        let mut point = |r: &mut SplitMix64| [r.range(-3.0, 3.0), r.range(-3.0, 3.0)];
        let rings: Vec<Vec<[f64; 2]>> = (0..1 + rng.below(3))
            .map(|_| {
                let n = 3 + rng.below(8);
                ring(&mut rng, n, &mut point)
            })
            .collect();
        let set = polygon(rings);
        for angle in [30.0, 117.5, -10.0] {
            segments += check(&set, angle, 0.3);
        }
    }
    assert!(segments > 100, "{segments} segments");
}

/// At `2^±300` the hatch is the unscaled one scaled, bit for bit, and still exact; `1e8` from
/// the origin, lattice degeneracies stay exact.
#[test]
fn extreme_scales_and_far_offsets() {
    let mut rng = SplitMix64(99);
    for set in lattice_sets(&mut rng, 6) {
        for (angle, spacing) in [(0.0, 0.5), (45.0, 0.75), (30.0, 0.4)] {
            let plain = hatch_polygons(&set, angle, spacing).expect("hatch");
            for k in [300, -300] {
                let big = scaled(&set, k);
                let got = hatch_polygons(&big, angle, ldexp(spacing, k)).expect("hatch");
                assert_eq!(got, scaled_hatch(&plain, k), "angle {angle}, scale 2^{k}");
                check(&big, angle, ldexp(spacing, k));
            }
        }
        use geo::MapCoords;
        let far = set.map_coords(|c| Coord {
            x: c.x + 1e8,
            y: c.y - 1e8,
        });
        for (angle, spacing) in [(0.0, 0.25), (90.0, 0.5), (30.0, 0.4)] {
            check(&far, angle, spacing);
        }
    }
}

/// A line along an edge of the outline is not hatched; one along an edge two pieces share is,
/// through it; a hole splits the hatch.
#[test]
fn outline_edges_shared_edges_and_holes() {
    let square = |x: f64, y: f64, s: f64| {
        Polygon::new(
            LineString::from(vec![(x, y), (x + s, y), (x + s, y + s), (x, y + s)]),
            vec![],
        )
    };
    // Two unit squares, one on top of the other: the line y = 1 runs along their shared edge.
    let stacked = MultiPolygon::new(vec![square(0.0, 0.0, 1.0), square(0.0, 1.0, 1.0)]);
    let hatch = hatch_polygons(&stacked, 0.0, 1.0).unwrap();
    let lines: Vec<(i64, Vec<[f64; 2]>)> = hatch
        .runs
        .iter()
        .map(|r| (r.line, r.points.clone()))
        .collect();
    assert_eq!(lines, vec![(1, vec![[0.0, 1.0], [1.0, 1.0]])]);
    check(&stacked, 0.0, 1.0);
    // Side by side: the line y = 0.5 passes the shared vertical edge, split there.
    let side = MultiPolygon::new(vec![square(0.0, 0.0, 1.0), square(1.0, 0.0, 1.0)]);
    let hatch = hatch_polygons(&side, 0.0, 0.5).unwrap();
    assert_eq!(hatch.runs.len(), 1);
    assert_eq!(hatch.runs[0].points.len(), 3, "{:?}", hatch.runs);
    check(&side, 0.0, 0.5);
}

/// Degenerate input hatches nothing and never panics; bad spacings and angles are errors.
#[test]
fn degenerate_input() {
    let empty = MultiPolygon::<f64>::new(vec![]);
    assert_eq!(hatch_polygons(&empty, 0.0, 1.0).unwrap(), Hatch::default());
    let flat = polygon(vec![vec![[0.0, 0.0], [1.0, 1.0], [2.0, 2.0]]]);
    assert!(hatch_polygons(&flat, 10.0, 0.1).unwrap().runs.is_empty());
    let nan = polygon(vec![vec![[0.0, 0.0], [f64::NAN, 1.0], [2.0, 0.0]]]);
    assert!(hatch_polygons(&nan, 10.0, 0.1).unwrap().runs.is_empty());
    let square = polygon(vec![vec![[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]]]);
    assert!(hatch_polygons(&square, 0.0, 0.0).is_err());
    assert!(hatch_polygons(&square, f64::INFINITY, 1.0).is_err());
    assert!(
        hatch_polygons(&square, 0.0, 1e-12).is_err(),
        "too many lines"
    );
    let tiny = scaled(&square, -1070);
    let _ = hatch_polygons(&tiny, 30.0, ldexp(0.1, -1070));
    let huge = polygon(vec![vec![[0.0, 0.0], [1e308, 0.0], [0.0, 1e308]]]);
    let _ = hatch_polygons(&huge, 30.0, 1e306);
    assert!(
        Hatching {
            angle: 0.0,
            spacing: [1.0, 0.5]
        }
        .check()
        .is_err()
    );
    assert!(
        hatch_faces(
            &[],
            &[0.5],
            &Hatching {
                angle: 0.0,
                spacing: [1.0, 2.0]
            }
        )
        .is_err()
    );
}

/// A cube and a sphere, shaded and hatched: every segment lies in its face's visible polygons
/// (midpoint inside or on, no outline edge crossed, in rationals), darker faces get denser
/// lines, and a face's hatch length over its visible area is about one over its spacing.
#[test]
fn a_rendered_scene_is_hatched_inside_its_visible_faces() {
    use geo::Area;
    use kepler::geometry::Vector3;
    use kepler::output::Shading;
    use kepler::scene::Scene;
    use kepler::surfaces::visible_surfaces;
    use kepler::views::View;
    use nalgebra::{Matrix4, Vector3 as V};
    let mut scene = Scene::new();
    let cube = kepler::solids::cube(2.0).expect("cube");
    scene.add_mesh(None, "cube", cube).expect("add");
    let ball = kepler::solids::uv_sphere(1.2, 24, 12)
        .expect("sphere")
        .transformed(&Matrix4::new_translation(&V::new(0.5, -2.0, 0.8)))
        .expect("moved");
    scene.add_mesh(None, "ball", ball).expect("add");
    let view = View::orthographic(Vector3::new(-1.0, -2.0, -1.2), Vector3::z()).expect("view");
    let faces = visible_surfaces(&scene, &view).expect("surfaces");
    let shades = Shading::default().shades(&faces, &scene, &view);
    let hatching = Hatching {
        angle: 45.0,
        spacing: [0.02, 0.2],
    };
    let hatched = hatch_faces(&faces, &shades, &hatching).expect("hatch");
    assert!(hatched.len() > 20, "{} faces hatched", hatched.len());
    let d = direction(hatching.angle).expect("angle");
    let qn: P = [q(-d[1]), q(d[0])];
    let two = Q::from_integer(2.into());
    let mut segments = 0;
    for h in &hatched {
        assert_eq!(h.hatch.dropped, 0);
        let f = faces
            .iter()
            .position(|f| (f.object, f.face) == (h.object, h.face))
            .expect("the face");
        let polygons = &faces[f].visible.polygons;
        let edges = edges(&exact_rings(polygons));
        let mut length = 0.0;
        for run in &h.hatch.runs {
            let c = q(run.line as f64 * h.spacing);
            for s in run.segments() {
                let (a, b) = (qp(s[0]), qp(s[1]));
                let m = [(&a[0] + &b[0]) / &two, (&a[1] + &b[1]) / &two];
                assert!(inside_or_on(&edges, &m), "segment {s:?} outside");
                for (p, q) in &edges {
                    assert!(!crosses_outline(&edges, &a, &b, p, q, &qn, &c));
                }
                length += (s[1][0] - s[0][0]).hypot(s[1][1] - s[0][1]);
                segments += 1;
            }
        }
        let area = polygons.unsigned_area();
        if area > 400.0 * h.spacing * h.spacing {
            let density = length / area * h.spacing;
            assert!((0.8..1.25).contains(&density), "density {density}");
        }
    }
    assert!(segments > 500, "{segments} segments");
    // Darker faces never get sparser lines.
    let mut by_shade: Vec<(f64, f64)> = hatched
        .iter()
        .map(|h| {
            let f = faces
                .iter()
                .position(|f| (f.object, f.face) == (h.object, h.face))
                .expect("the face");
            (shades[f], h.spacing)
        })
        .collect();
    by_shade.sort_by(|a, b| a.0.total_cmp(&b.0));
    assert!(by_shade.windows(2).all(|w| w[0].1 <= w[1].1));
    assert!(by_shade.first().expect("some").1 < by_shade.last().expect("some").1);
}
