//! Hand-checked hidden-line drawings against exact references.
//!
//! Every expected point is computed here in rational arithmetic (`BigRational`), from the
//! scene's input coordinates and the view's rows taken as exact, independently of the
//! library's expansions:
//!
//! - the picture of a world point `p`: with `(rows, origin) = Picture::of(&view).rows()`,
//!   orthographic `x = rows[0]·p`, `y = rows[1]·p`; perspective
//!   `x = rows[0]·(p - origin) / rows[2]·(p - origin)`, `y` likewise;
//! - a crossing cut of edge `ab` by the contour `cd`: `X = a + t(b - a)` with
//!   `t = O(a) / (O(a) - O(b))`, `O(x) = det[c - e, d - e, x - e]` for a perspective eye `e`
//!   and `O(x) = det[c - x, d - x, u]` for an orthographic eye at infinity in direction `u`;
//! - an intersection-line end, or the cut where an edge pierces a face: `X = a + t(b - a)`
//!   with `t = P(a) / (P(a) - P(b))`, `P(x) = det[q - p, r - p, x - p]` for the other face's
//!   triangle `pqr`.
//!
//! The drawn vertex must be within [`MAX_ULPS`] units in the last place of the exact picture
//! of its reference point, per coordinate: `|computed - exact| <= 4 ulp(exact)`, with
//! `ulp(x) = 2^(e - 52)` for `2^e <= |x| < 2^(e + 1)` (exactly, on the rational). When the
//! exact coordinate is 0 (it has no ulp), the unit is the ulp of the drawing's largest
//! coordinate magnitude instead.
//!
//! For scenes of convex solids the expected drawing itself is computed here independently:
//! edges are classified from exact face normals, each edge is cut at every exact crossing
//! with a contour's picture and every piercing of another solid's face plane, and each piece
//! is decided at its exact midpoint by whether the ray towards the eye enters the interior of
//! a solid (exact slab tests). Merged runs of equal visibility must equal the library's
//! pieces one to one (class, visibility, both ends within 4 ulps).

use kepler::geometry::{Point3, Vector3};
use kepler::hidden::{Drawing, EdgeClass, EdgeSelection, Options, draw};
use kepler::mesh::Mesh;
use kepler::scene::Scene;
use kepler::solids;
use kepler::views::View;
use num_bigint::BigInt;
use num_traits::{One, Signed, ToPrimitive, Zero};
use std::cmp::Ordering;
use std::collections::BTreeMap;

use crate::common::exact::{
    P2, RefView, V, cuboid_at, f2, opposite, parallelepiped, qadd, qdet, qlerp, qp, qscale, ulps,
    ulps2,
};
use crate::common::{Q, q, qcross, qdot, qsign, qsub, qv, scene_of};

/// The largest error allowed for a drawn vertex, in units in the last place per coordinate.
const MAX_ULPS: f64 = 4.0;

/// The largest coordinate magnitude of a drawing (for exact zeros, see the module docs).
fn scale_of(d: &Drawing) -> f64 {
    d.polylines
        .iter()
        .flat_map(|p| p.points.iter())
        .fold(0.0f64, |m, p| m.max(p[0].abs()).max(p[1].abs()))
}

// ---------------------------------------------------------------------------------------------
// Convex solids, exactly: classification and visibility by rays.

struct Solid {
    v: Vec<V>,
    faces: Vec<Vec<usize>>,
    /// Outward normals (not normalized) and offsets: the interior is `n·x < h` for all faces.
    normals: Vec<V>,
    offsets: Vec<Q>,
}

impl Solid {
    /// The exact solid of a convex mesh (any face orientation: normals point away from the
    /// centroid).
    fn of(mesh: &Mesh) -> Solid {
        let v: Vec<V> = mesh.vertices().iter().map(qp).collect();
        let count = Q::from_integer(BigInt::from(v.len()));
        let centroid = v
            .iter()
            .fold([Q::zero(), Q::zero(), Q::zero()], |s, p| qadd(&s, p))
            .map(|c| c / &count);
        let faces: Vec<Vec<usize>> = mesh
            .faces()
            .iter()
            .map(|f| f.vertices().iter().map(|&i| i as usize).collect())
            .collect();
        let mut normals = Vec::new();
        let mut offsets = Vec::new();
        for f in &faces {
            let (p0, p1, p2) = (&v[f[0]], &v[f[1]], &v[f[2]]);
            let mut n = qcross(&qsub(p1, p0), &qsub(p2, p0));
            assert!(n.iter().any(|c| !c.is_zero()));
            if qdot(&n, &qsub(&centroid, p0)).is_positive() {
                n = n.map(|c| -c);
            }
            offsets.push(qdot(&n, p0));
            normals.push(n);
        }
        Solid {
            v,
            faces,
            normals,
            offsets,
        }
    }

    /// Whether the open ray `x + s·w`, `0 < s < smax`, meets the interior.
    fn ray_enters(&self, x: &V, w: &V, smax: &Option<Q>) -> bool {
        let mut lo = Q::zero();
        let mut hi = smax.clone();
        for (n, h) in self.normals.iter().zip(&self.offsets) {
            let k = qdot(n, w);
            let r = h - qdot(n, x);
            match qsign(&k) {
                Ordering::Equal => {
                    if !r.is_positive() {
                        return false;
                    }
                }
                Ordering::Greater => {
                    let s = r / k;
                    if hi.as_ref().is_none_or(|m| s < *m) {
                        hi = Some(s);
                    }
                }
                Ordering::Less => {
                    let s = r / k;
                    if s > lo {
                        lo = s;
                    }
                }
            }
        }
        hi.is_none_or(|m| lo < m)
    }
}

/// An edge of a solid, with its class in the view.
struct RefEdge {
    solid: usize,
    ends: [V; 2],
    class: EdgeClass,
}

/// A piece of the expected drawing: a 3-D segment and its exact picture.
#[derive(Clone)]
struct RefSeg {
    class: EdgeClass,
    visible: bool,
    ends: [V; 2],
    pictures: [P2; 2],
}

/// The edges of convex solids, classified exactly: faces turned differently make a
/// silhouette, coplanar neighbours no edge, others a crease (checked to bend more than 30°).
fn ref_edges(solids: &[Solid], rv: &RefView) -> Vec<RefEdge> {
    let mut out = Vec::new();
    for (s, solid) in solids.iter().enumerate() {
        let mut sides: BTreeMap<(usize, usize), Vec<usize>> = BTreeMap::new();
        for (f, face) in solid.faces.iter().enumerate() {
            for i in 0..face.len() {
                let (a, b) = (face[i], face[(i + 1) % face.len()]);
                sides.entry((a.min(b), a.max(b))).or_default().push(f);
            }
        }
        for ((a, b), faces) in sides {
            assert_eq!(faces.len(), 2, "a closed solid");
            let (n, m) = (&solid.normals[faces[0]], &solid.normals[faces[1]]);
            if qcross(n, m).iter().all(Zero::is_zero) {
                assert!(qdot(n, m).is_positive());
                continue; // coplanar neighbours
            }
            let fa = rv.facing(n, &solid.v[solid.faces[faces[0]][0]]);
            let fb = rv.facing(m, &solid.v[solid.faces[faces[1]][0]]);
            assert!(
                fa != Ordering::Equal && fb != Ordering::Equal,
                "a face seen edge-on"
            );
            let class = if fa != fb {
                EdgeClass::Silhouette
            } else {
                let (nf, mf) = (
                    n.clone().map(|c| c.to_f64().unwrap()),
                    m.clone().map(|c| c.to_f64().unwrap()),
                );
                let dot = nf[0] * mf[0] + nf[1] * mf[1] + nf[2] * mf[2];
                let norms = (nf.iter().map(|c| c * c).sum::<f64>()
                    * mf.iter().map(|c| c * c).sum::<f64>())
                .sqrt();
                assert!(dot / norms < 0.8, "a crease bends well over 30 degrees");
                EdgeClass::Crease
            };
            out.push(RefEdge {
                solid: s,
                ends: [solid.v[a].clone(), solid.v[b].clone()],
                class,
            });
        }
    }
    out
}

/// Whether the point `x` is hidden: the ray towards the eye enters some solid's interior.
fn hidden(solids: &[Solid], rv: &RefView, x: &V) -> bool {
    let (w, smax) = rv.ray(x);
    solids.iter().any(|s| s.ray_enters(x, &w, &smax))
}

/// The expected runs of every edge: cut at crossings with contours' pictures and at
/// piercings of other solids' face planes, decided at each piece's midpoint, merged.
fn expected_runs(solids: &[Solid], edges: &[RefEdge], rv: &RefView) -> Vec<RefSeg> {
    let mut out = Vec::new();
    for (i, e) in edges.iter().enumerate() {
        let [a, b] = &e.ends;
        let mut ts = vec![Q::zero(), Q::one()];
        for (j, c) in edges.iter().enumerate() {
            if j == i || c.class != EdgeClass::Silhouette {
                continue;
            }
            let [cc, cd] = &c.ends;
            let (oa, ob) = (rv.sight(cc, cd, a), rv.sight(cc, cd, b));
            if opposite(&oa, &ob) {
                let (oc, od) = (rv.sight(a, b, cc), rv.sight(a, b, cd));
                if qsign(&oc) != qsign(&od) || oc.is_zero() {
                    ts.push(&oa / (&oa - &ob));
                }
            }
        }
        for (s, solid) in solids.iter().enumerate() {
            if s == e.solid {
                continue;
            }
            for (n, h) in solid.normals.iter().zip(&solid.offsets) {
                let (pa, pb) = (qdot(n, a) - h, qdot(n, b) - h);
                if opposite(&pa, &pb) {
                    ts.push(&pa / (&pa - &pb));
                }
            }
        }
        ts.sort();
        ts.dedup();
        let mut runs: Vec<(Q, Q, bool)> = Vec::new();
        for w in ts.windows(2) {
            let mid = (&w[0] + &w[1]) / Q::from_integer(BigInt::from(2));
            let visible = !hidden(solids, rv, &qlerp(a, b, &mid));
            match runs.last_mut() {
                Some(last) if last.2 == visible => last.1 = w[1].clone(),
                _ => runs.push((w[0].clone(), w[1].clone(), visible)),
            }
        }
        for (t0, t1, visible) in runs {
            let ends = [qlerp(a, b, &t0), qlerp(a, b, &t1)];
            let pictures = [rv.picture(&ends[0]), rv.picture(&ends[1])];
            out.push(RefSeg {
                class: e.class,
                visible,
                ends,
                pictures,
            });
        }
    }
    out
}

// ---------------------------------------------------------------------------------------------
// The library's drawing, as pieces.

type Seg = (EdgeClass, bool, [[f64; 2]; 2]);

/// The pieces of a drawing: consecutive vertices of its polylines.
fn lib_segments(d: &Drawing) -> Vec<Seg> {
    d.segments().collect()
}

/// The pieces as bit patterns, each with its ends in order, sorted: equal drawings give
/// equal lists.
fn bit_segments(d: &Drawing) -> Vec<(EdgeClass, bool, [[u64; 2]; 2])> {
    let mut out: Vec<_> = lib_segments(d)
        .into_iter()
        .map(|(c, v, [p, q])| {
            let key = |p: [f64; 2]| p.map(|x| (x + 0.0).to_bits());
            let (mut x, mut y) = (key(p), key(q));
            if x > y {
                std::mem::swap(&mut x, &mut y);
            }
            (c, v, [x, y])
        })
        .collect();
    out.sort();
    out
}

/// How many pieces of each (class, visibility).
fn counts(segs: &[Seg]) -> BTreeMap<(EdgeClass, bool), usize> {
    let mut m = BTreeMap::new();
    for s in segs {
        *m.entry((s.0, s.1)).or_insert(0) += 1;
    }
    m
}

/// The exact length of the pictures of reference pieces of one class and visibility (the
/// differences of exact pictures rounded once, then `hypot`).
fn ref_length(segs: &[RefSeg], class: EdgeClass, visible: bool) -> f64 {
    segs.iter()
        .filter(|s| s.class == class && s.visible == visible)
        .map(|s| {
            let [p, r] = &s.pictures;
            let dx = (&r[0] - &p[0]).to_f64().unwrap();
            let dy = (&r[1] - &p[1]).to_f64().unwrap();
            dx.hypot(dy)
        })
        .sum()
}

fn assert_length(d: &Drawing, want: &[RefSeg], class: EdgeClass, visible: bool) {
    let (got, exact) = (d.length(class, visible), ref_length(want, class, visible));
    assert!(
        (got - exact).abs() <= 1e-12 * exact,
        "{class:?} visible={visible}: length {got} against exact {exact}"
    );
}

/// Matches the library's pieces of edges (intersection lines aside) one to one with the
/// reference's (same class and visibility, both ends within [`MAX_ULPS`]); returns the
/// largest error in ulps.
fn match_segments(name: &str, d: &Drawing, want: &[RefSeg]) -> f64 {
    // Intersection lines are checked on their own (see `box_piercing_another`).
    let got: Vec<Seg> = lib_segments(d)
        .into_iter()
        .filter(|s| s.0 != EdgeClass::Intersection)
        .collect();
    let scale = scale_of(d);
    // A piece whose exact ends round to one point has no length to draw.
    let want: Vec<&RefSeg> = want
        .iter()
        .filter(|w| f2(&w.pictures[0]) != f2(&w.pictures[1]))
        .collect();
    let mut used = vec![false; want.len()];
    let mut worst = 0.0f64;
    let mut missing = Vec::new();
    for g in &got {
        let (class, visible, [p, r]) = *g;
        let mut best: Option<(usize, f64)> = None;
        for (k, w) in want.iter().enumerate() {
            if used[k] || w.class != class || w.visible != visible {
                continue;
            }
            let e1 = ulps2(p, &w.pictures[0], scale).max(ulps2(r, &w.pictures[1], scale));
            let e2 = ulps2(p, &w.pictures[1], scale).max(ulps2(r, &w.pictures[0], scale));
            let e = e1.min(e2);
            if e <= MAX_ULPS && best.is_none_or(|(_, b)| e < b) {
                best = Some((k, e));
            }
        }
        match best {
            Some((k, e)) => {
                used[k] = true;
                worst = worst.max(e);
            }
            None => missing.push(g),
        }
    }
    let unmatched: Vec<_> = want
        .iter()
        .zip(&used)
        .filter(|(_, u)| !**u)
        .map(|(w, _)| (w.class, w.visible, w.pictures.clone().map(|p| f2(&p))))
        .collect();
    assert!(
        missing.is_empty() && unmatched.is_empty(),
        "{name}: drawn pieces without an exact counterpart within {MAX_ULPS} ulps: {missing:?}\n\
         expected pieces not drawn: {unmatched:?}\nall drawn: {got:?}"
    );
    println!(
        "{name}: {} pieces, largest vertex error {worst:.3} ulps",
        got.len()
    );
    worst
}

// ---------------------------------------------------------------------------------------------
// Scenes.

fn options() -> Options {
    Options::default()
}

/// The mesh with every face's loop reversed (inside out).
fn inside_out(mesh: &Mesh) -> Mesh {
    let faces = mesh
        .faces()
        .iter()
        .map(|f| f.vertices().iter().rev().copied().collect())
        .collect();
    Mesh::from_polygons(mesh.vertices().to_vec(), faces).unwrap()
}

/// The mesh with every (convex) face split into a fan of triangles, each a face of its own.
fn triangulated(mesh: &Mesh) -> Mesh {
    let faces = mesh
        .faces()
        .iter()
        .flat_map(|f| {
            let v = f.vertices().to_vec();
            (1..v.len() - 1).map(move |i| vec![v[0], v[i], v[i + 1]])
        })
        .collect();
    Mesh::from_polygons(mesh.vertices().to_vec(), faces).unwrap()
}

/// Draws convex solids and checks the drawing against the exact reference; returns the
/// reference pieces and the largest error.
fn check_convex(name: &str, meshes: &[Mesh], view: &View) -> (Drawing, Vec<RefSeg>, f64) {
    let d = draw(&scene_of(meshes), view, &options()).unwrap();
    let rv = RefView::new(view);
    let solids: Vec<Solid> = meshes.iter().map(Solid::of).collect();
    let edges = ref_edges(&solids, &rv);
    let want = expected_runs(&solids, &edges, &rv);
    let worst = match_segments(name, &d, &want);
    for class in [EdgeClass::Silhouette, EdgeClass::Crease] {
        for visible in [true, false] {
            assert_length(&d, &want, class, visible);
        }
    }
    (d, want, worst)
}

/// Hand-expected pieces of a single axis-aligned cube (half-edge `h`, centre `c`) whose
/// visible faces are the ones on the `near` side of each axis (+1 or -1): creases at the near
/// corner visible, at the far corner hidden, the six other edges a visible silhouette.
fn hand_cube(h: f64, c: [f64; 3], near: [i32; 3], rv: &RefView) -> Vec<RefSeg> {
    let corner = |s: [i32; 3]| -> V { qv([0, 1, 2].map(|k| c[k] + f64::from(s[k]) * h)) };
    let far = near.map(|s| -s);
    let mut out = Vec::new();
    for bits in 0..8u32 {
        let s: [i32; 3] = [0, 1, 2].map(|k| if bits & (1 << k) != 0 { 1 } else { -1 });
        for k in 0..3 {
            if s[k] != -1 {
                continue;
            }
            let mut t = s;
            t[k] = 1;
            let (class, visible) = if s == near || t == near {
                (EdgeClass::Crease, true)
            } else if s == far || t == far {
                (EdgeClass::Crease, false)
            } else {
                (EdgeClass::Silhouette, true)
            };
            let ends = [corner(s), corner(t)];
            let pictures = [rv.picture(&ends[0]), rv.picture(&ends[1])];
            out.push(RefSeg {
                class,
                visible,
                ends,
                pictures,
            });
        }
    }
    out
}

/// Whether two lists of reference pieces are equal as sets (exactly).
fn same_pieces(a: &[RefSeg], b: &[RefSeg]) -> bool {
    let key = |s: &RefSeg| {
        let mut e = s.ends.clone();
        if e[0] > e[1] {
            e.swap(0, 1);
        }
        (s.class, s.visible, e)
    };
    let mut x: Vec<_> = a.iter().map(key).collect();
    let mut y: Vec<_> = b.iter().map(key).collect();
    x.sort();
    y.sort();
    x == y
}

fn expect_counts(d: &Drawing, want: &[((EdgeClass, bool), usize)]) {
    let got = counts(&lib_segments(d));
    let want: BTreeMap<_, _> = want.iter().copied().filter(|&(_, n)| n > 0).collect();
    assert_eq!(got, want);
}

// ---------------------------------------------------------------------------------------------
// 1. A cube from general directions.

#[test]
fn cube_from_general_directions() {
    let cube = solids::cube(2.0).unwrap();
    for (direction, up) in [
        (Vector3::new(-1.0, -2.0, -3.0), Vector3::z()),
        (Vector3::new(2.0, -1.0, -0.5), Vector3::z()),
        (Vector3::new(0.3, 0.7, -1.9), Vector3::new(0.1, 1.0, 0.2)),
    ] {
        let view = View::orthographic(direction, up).unwrap();
        let rv = RefView::new(&view);
        // The corner nearest the eye: the signs of the eye direction (minus the view's).
        let near = [0, 1, 2].map(|k| if direction[k] < 0.0 { 1 } else { -1 });
        let hand = hand_cube(1.0, [0.0; 3], near, &rv);
        let name = format!("cube {direction:?}");
        let (d, want, _) = check_convex(&name, std::slice::from_ref(&cube), &view);
        assert!(
            same_pieces(&hand, &want),
            "{name}: the reference differs from the hand count"
        );
        // Matched against the hand-made list too: every piece ends at two cube vertices.
        match_segments(&format!("{name} (by hand)"), &d, &hand);
        expect_counts(
            &d,
            &[
                ((EdgeClass::Silhouette, true), 6),
                ((EdgeClass::Crease, true), 3),
                ((EdgeClass::Crease, false), 3),
            ],
        );
        // The outline is one closed hexagon; the creases meet three at a corner, so each is
        // its own polyline.
        let outline: Vec<_> = d
            .polylines
            .iter()
            .filter(|p| p.class == EdgeClass::Silhouette)
            .collect();
        assert_eq!(outline.len(), 1);
        assert_eq!(outline[0].points.len(), 7);
        assert_eq!(outline[0].points[0], outline[0].points[6]);
        assert_eq!(
            d.polylines
                .iter()
                .filter(|p| p.class == EdgeClass::Crease)
                .count(),
            6
        );
    }
}

/// Whether the line of sight from `x` (direction `towards(x)`, forwards) meets an edge of the
/// box `[lo, hi]`: two coordinates on the box's bounds, the third within them.
fn sight_meets_box_edge(x: &V, towards: impl Fn(&V) -> V, lo: [f64; 3], hi: [f64; 3]) -> bool {
    let w = towards(x);
    let (lo, hi) = (qv(lo), qv(hi));
    (0..3).any(|k| {
        [&lo[k], &hi[k]].iter().any(|&side| {
            if w[k].is_zero() {
                return false;
            }
            let s = (side - &x[k]) / &w[k];
            let y = qadd(x, &qscale(&w, &s));
            let inside = (0..3).all(|i| lo[i] <= y[i] && y[i] <= hi[i]);
            let on = (0..3).filter(|&i| y[i] == lo[i] || y[i] == hi[i]).count();
            s.is_positive() && inside && on == 2
        })
    })
}

/// Whether the line of sight from `x` meets an edge of the cube `[-1, 1]^3`.
fn sight_meets_cube_edge(x: &V, towards: impl Fn(&V) -> V) -> bool {
    sight_meets_box_edge(x, towards, [-1.0; 3], [1.0; 3])
}

/// The reference's cuts: the ends of its pieces that are no input vertex, sorted, each once.
fn reference_cuts(meshes: &[&Mesh], want: &[RefSeg]) -> Vec<V> {
    let inputs: Vec<V> = meshes
        .iter()
        .flat_map(|m| m.vertices().iter().map(qp))
        .collect();
    let mut cuts: Vec<V> = want
        .iter()
        .flat_map(|s| s.ends.iter().cloned())
        .filter(|x| !inputs.contains(x))
        .collect();
    cuts.sort();
    cuts.dedup();
    cuts
}

/// Checks that the reference's cuts (piece ends that are no input vertex) are exactly
/// `hand`, and that each is drawn: some vertex of the drawing within [`MAX_ULPS`] of its
/// exact picture.
fn assert_cuts(d: &Drawing, want: &[RefSeg], meshes: &[&Mesh], view: &View, hand: &[V]) {
    let cuts = reference_cuts(meshes, want);
    let mut hand = hand.to_vec();
    hand.sort();
    assert_eq!(cuts, hand, "the reference's cuts are the hand-checked ones");
    let rv = RefView::new(view);
    let scale = scale_of(d);
    for x in &hand {
        let p = rv.picture(x);
        let e = d
            .polylines
            .iter()
            .flat_map(|l| l.points.iter())
            .map(|&v| ulps2(v, &p, scale))
            .fold(f64::INFINITY, f64::min);
        assert!(
            e <= MAX_ULPS,
            "cut {:?}: nearest vertex {e} ulps away",
            f2(&p)
        );
    }
}

// ---------------------------------------------------------------------------------------------
// 2. A box partly behind another.

/// The front cube, the box behind it and the view of case 2.
fn two_boxes() -> (Mesh, Mesh, View) {
    // x in [-3.75, -0.75], y in [-1.75, -0.25], z in [-4.75, -2.25].
    let back = cuboid_at([3.0, 1.5, 2.5], [-2.25, -1.0, -3.5]);
    let view = View::orthographic(Vector3::new(-1.0, -2.0, -3.0), Vector3::z()).unwrap();
    (solids::cube(2.0).unwrap(), back, view)
}

/// The four cuts of `two_boxes`, by hand: each is the point X of a back-box edge whose line of
/// sight X + s(1, 2, 3) meets a silhouette edge of the cube (at the s shown).
fn two_boxes_cuts() -> Vec<V> {
    vec![
        // Edge x = -0.75, z = -4.75 at y = -1.5; s = 5/4 gives (0.5, 1, -1): edge y = 1, z = -1.
        qv([-0.75, -1.5, -4.75]),
        // Edge x = -0.75, y = -0.25 at z = -2.875; s = 5/8 gives (-0.125, 1, -1): same edge.
        qv([-0.75, -0.25, -2.875]),
        // Edge y = -1.75, z = -2.25 at x = -25/12; s = 13/12 gives (-1, 5/12, 1): x = -1, z = 1.
        [
            Q::new(BigInt::from(-25), BigInt::from(12)),
            q(-1.75),
            q(-2.25),
        ],
        // Edge y = -0.25, z = -2.25 at x = -1.625; s = 5/8 gives (-1, 1, -0.375): x = -1, y = 1.
        qv([-1.625, -0.25, -2.25]),
    ]
}

#[test]
fn box_partly_behind_another() {
    let (front, back, view) = two_boxes();
    let (d, want, worst) = check_convex("two boxes", &[front.clone(), back.clone()], &view);
    // The front cube draws whole: 6 + 3 visible, 3 hidden. The back box (seen from the
    // eye direction (1, 2, 3) too) has its far corner's 3 creases hidden; of its 6 silhouette
    // edges 3 are visible, 1 hidden and 2 cut (visible and hidden); of its near corner's 3
    // creases 1 is hidden and 2 cut.
    expect_counts(
        &d,
        &[
            ((EdgeClass::Silhouette, true), 6 + 3 + 2),
            ((EdgeClass::Silhouette, false), 1 + 2),
            ((EdgeClass::Crease, true), 3 + 2),
            ((EdgeClass::Crease, false), 3 + 3 + 1 + 2),
        ],
    );
    let hand_cuts = two_boxes_cuts();
    let u = qv([1.0, 2.0, 3.0]);
    assert!(
        hand_cuts
            .iter()
            .all(|x| sight_meets_cube_edge(x, |_| u.clone()))
    );
    assert_cuts(&d, &want, &[&front, &back], &view, &hand_cuts);
    println!("two boxes: 4 cuts, largest vertex error {worst:.3} ulps");

    // The same scene with the back box triangulated and the front one inside out draws the
    // same pieces, bit for bit.
    let other = draw(
        &scene_of(&[inside_out(&front), triangulated(&back)]),
        &view,
        &options(),
    )
    .unwrap();
    assert_eq!(bit_segments(&other), bit_segments(&d));
}

// ---------------------------------------------------------------------------------------------
// 3. A box piercing another.

/// Where the boundary of the convex polygon `face` meets the plane `n·x = h`.
fn section(face: &[V], n: &V, h: &Q) -> Vec<V> {
    let mut out: Vec<V> = Vec::new();
    for i in 0..face.len() {
        let (a, b) = (&face[i], &face[(i + 1) % face.len()]);
        let (pa, pb) = (qdot(n, a) - h, qdot(n, b) - h);
        if pa.is_zero() {
            out.push(a.clone());
        } else if opposite(&pa, &pb) {
            out.push(qlerp(a, b, &(&pa / (&pa - &pb))));
        }
    }
    out
}

/// The segment where face `f` of `s1` and face `g` of `s2` pierce each other, exactly.
fn face_pair_segment(s1: &Solid, f: usize, s2: &Solid, g: usize) -> Option<[V; 2]> {
    let dir = qcross(&s1.normals[f], &s2.normals[g]);
    if dir.iter().all(Zero::is_zero) {
        return None;
    }
    let pf: Vec<V> = s1.faces[f].iter().map(|&i| s1.v[i].clone()).collect();
    let pg: Vec<V> = s2.faces[g].iter().map(|&i| s2.v[i].clone()).collect();
    let (a, b) = (
        section(&pf, &s2.normals[g], &s2.offsets[g]),
        section(&pg, &s1.normals[f], &s1.offsets[f]),
    );
    if a.len() != 2 || b.len() != 2 {
        return None;
    }
    let along = |x: &V| qdot(&dir, x);
    let sorted = |mut s: Vec<V>| {
        if along(&s[0]) > along(&s[1]) {
            s.swap(0, 1);
        }
        s
    };
    let (a, b) = (sorted(a), sorted(b));
    let start = if along(&a[0]) >= along(&b[0]) {
        a[0].clone()
    } else {
        b[0].clone()
    };
    let end = if along(&a[1]) <= along(&b[1]) {
        a[1].clone()
    } else {
        b[1].clone()
    };
    (along(&start) < along(&end)).then_some([start, end])
}

/// The exact pictures of every point where a triangle edge of one mesh crosses the plane of
/// a triangle of the other (`P(x) = det[q - p, r - p, x - p]`): the candidates for the
/// vertices of intersection lines, triangulation diagonals included.
fn triangle_crossings(m0: &Mesh, m1: &Mesh, rv: &RefView) -> Vec<P2> {
    let mut out = Vec::new();
    for (x, y) in [(m0, m1), (m1, m0)] {
        for i in 0..x.triangles().len() {
            let t = x.triangle(i).map(|p| qp(&p));
            for e in 0..3 {
                let (a, b) = (&t[e], &t[(e + 1) % 3]);
                for j in 0..y.triangles().len() {
                    let [p, r, s] = y.triangle(j).map(|p| qp(&p));
                    let (qp_, rp) = (qsub(&r, &p), qsub(&s, &p));
                    let (pa, pb) = (qdet(&qp_, &rp, &qsub(a, &p)), qdet(&qp_, &rp, &qsub(b, &p)));
                    if opposite(&pa, &pb) {
                        out.push(rv.picture(&qlerp(a, b, &(&pa / (&pa - &pb)))));
                    }
                }
            }
        }
    }
    out
}

#[test]
fn box_piercing_another() {
    let cube = solids::cube(2.0).unwrap();
    // A rod along (5, 0.5, 0.25) from x = -2.5 to 2.5 through the cube's faces x = -1 and
    // x = 1 (its cross-section stays well inside |y|, |z| < 1 there); its long edges cross
    // those planes at t = 0.3 and 0.7 (plus offsets), not dyadic.
    let rod = parallelepiped(
        [-2.5, -0.375, -0.25],
        [5.0, 0.5, 0.25],
        [0.125, 0.5, 0.0625],
        [-0.0625, 0.125, 0.5],
    );
    let view = View::orthographic(Vector3::new(-1.0, -2.0, -3.0), Vector3::z()).unwrap();
    let meshes = [cube.clone(), rod.clone()];
    let (d, edge_pieces, worst) = check_convex("rod through cube", &meshes, &view);
    // By hand, edges: the cube as alone, but its silhouette edge x = 1, z = -1 passes behind
    // the rod's end (visible, hidden, visible). The rod: its far long edge and far end's
    // two creases hidden, its near end's edges visible; its two long silhouette edges and
    // its near long crease visible outside the cube, hidden from where they pass behind the
    // cube's outline (x = -1 side) to where they pierce the face x = 1.
    let mut edge_counts = counts(&lib_segments(&d));
    edge_counts.retain(|k, _| k.0 != EdgeClass::Intersection);
    let want_counts: BTreeMap<_, _> = [
        ((EdgeClass::Silhouette, true), (5 + 2) + (2 + 2 + 2 * 2)),
        ((EdgeClass::Silhouette, false), 1 + 2),
        ((EdgeClass::Crease, true), 3 + (2 + 2)),
        ((EdgeClass::Crease, false), 3 + (1 + 2 + 1)),
    ]
    .into_iter()
    .collect();
    assert_eq!(edge_counts, want_counts);
    // The three piercings of the face x = 1 by those long edges, by hand: the edge from
    // `a` along d = (5, 0.5, 0.25) meets x = 1 at t = (1 - a.x)/5.
    let d_rod = qv([5.0, 0.5, 0.25]);
    let piercings: Vec<V> = [
        [-2.375, 0.125, -0.1875],
        [-2.5625, -0.25, 0.25],
        [-2.4375, 0.25, 0.3125],
    ]
    .into_iter()
    .map(|a| {
        let a = qv(a);
        let t = (Q::one() - &a[0]) / &d_rod[0];
        qlerp(&a, &qadd(&a, &d_rod), &t)
    })
    .collect();
    let cuts = reference_cuts(&meshes.iter().collect::<Vec<_>>(), &edge_pieces);
    // Those three, two where the cube's edge passes behind the rod's outline, three where
    // the rod's edges pass behind the cube's.
    assert_eq!(cuts.len(), 8);
    assert!(piercings.iter().all(|x| cuts.contains(x)));

    // The intersection lines: two loops of four segments, on the cube's faces x = ±1.
    let rv = RefView::new(&view);
    let solids: Vec<Solid> = meshes.iter().map(Solid::of).collect();
    let mut want = Vec::new();
    for f in 0..6 {
        for g in 0..6 {
            if let Some(ends) = face_pair_segment(&solids[0], f, &solids[1], g) {
                let mid = qscale(
                    &qadd(&ends[0], &ends[1]),
                    &Q::new(BigInt::one(), BigInt::from(2)),
                );
                let visible = !hidden(&solids, &rv, &mid);
                let pictures = [rv.picture(&ends[0]), rv.picture(&ends[1])];
                want.push(RefSeg {
                    class: EdgeClass::Intersection,
                    visible,
                    ends,
                    pictures,
                });
            }
        }
    }
    // By hand: on x = 1 (turned towards the eye) the segments on the rod's two faces turned
    // towards the eye are visible, the other two hidden by the rod itself; the loop on
    // x = -1 lies on a face turned away, hidden by the cube.
    let sides = 2..6; // faces 0 and 1 are the rod's ends
    let facing_rod_sides = sides
        .filter(|&g| {
            let p = &solids[1].v[solids[1].faces[g][0]];
            rv.facing(&solids[1].normals[g], p) == Ordering::Greater
        })
        .count();
    assert_eq!(facing_rod_sides, 2);
    assert_eq!(want.len(), 8);
    assert_eq!(want.iter().filter(|s| s.visible).count(), 2);
    assert!(
        want.iter()
            .filter(|s| s.visible)
            .all(|s| s.ends[0][0] == Q::one() && s.ends[1][0] == Q::one())
    );
    for visible in [true, false] {
        assert_length(&d, &want, EdgeClass::Intersection, visible);
    }

    // Every vertex of an intersection line within MAX_ULPS of an exact edge-plane crossing
    // (the loops' corners, or where a triangulation diagonal crosses the other face), and
    // every corner drawn.
    let candidates = triangle_crossings(&cube, &rod, &rv);
    let scale = scale_of(&d);
    let mut worst_int = 0.0f64;
    let lines: Vec<_> = d
        .polylines
        .iter()
        .filter(|p| p.class == EdgeClass::Intersection)
        .collect();
    for p in lines.iter().flat_map(|l| l.points.iter()) {
        let e = candidates
            .iter()
            .map(|c| ulps2(*p, c, scale))
            .fold(f64::INFINITY, f64::min);
        assert!(
            e <= MAX_ULPS,
            "intersection vertex {p:?}: nearest exact crossing {e} ulps away"
        );
        worst_int = worst_int.max(e);
    }
    for s in &want {
        for c in &s.pictures {
            let e = lines
                .iter()
                .filter(|l| l.visible == s.visible)
                .flat_map(|l| l.points.iter())
                .map(|&p| ulps2(p, c, scale))
                .fold(f64::INFINITY, f64::min);
            assert!(e <= MAX_ULPS, "corner {:?} not drawn ({e} ulps)", f2(c));
        }
    }
    // Chained: the visible pair is one polyline, the hidden pair on x = 1 another, and the
    // loop on x = -1 a closed one.
    let count = |v: bool| lines.iter().filter(|l| l.visible == v).count();
    assert_eq!((count(true), count(false)), (1, 2));
    assert!(
        lines
            .iter()
            .any(|l| !l.visible && l.points.first() == l.points.last())
    );
    println!(
        "rod through cube: largest error {worst:.3} ulps (edges), {worst_int:.3} ulps (intersection lines, {} vertices)",
        lines.iter().map(|l| l.points.len()).sum::<usize>()
    );
}

// ---------------------------------------------------------------------------------------------
// 4. A torus hiding parts of itself.

/// Distance from `p` to the segment `ab`, in floating point.
fn distance_to_segment(p: [f64; 2], a: [f64; 2], b: [f64; 2]) -> f64 {
    let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
    let n = dx * dx + dy * dy;
    let t = if n > 0.0 {
        (((p[0] - a[0]) * dx + (p[1] - a[1]) * dy) / n).clamp(0.0, 1.0)
    } else {
        0.0
    };
    (p[0] - a[0] - t * dx).hypot(p[1] - a[1] - t * dy)
}

/// Checks that every vertex of the drawing lies within MAX_ULPS of some exact reference: an
/// input vertex's picture, or the crossing (by the definition) of two edges whose pictures
/// pass within 1e-9 of it. Returns the largest error and how many vertices are crossings.
fn check_vertices_near_references(
    name: &str,
    d: &Drawing,
    meshes: &[Mesh],
    rv: &RefView,
) -> (f64, usize) {
    let mut vertices: Vec<(P2, [f64; 2])> = Vec::new();
    let mut edges: Vec<([V; 2], [[f64; 2]; 2])> = Vec::new();
    for mesh in meshes {
        let v: Vec<V> = mesh.vertices().iter().map(qp).collect();
        let pictures: Vec<P2> = v.iter().map(|x| rv.picture(x)).collect();
        let mut sides = std::collections::BTreeSet::new();
        for f in mesh.faces() {
            let l = f.vertices();
            for i in 0..l.len() {
                let (a, b) = (l[i] as usize, l[(i + 1) % l.len()] as usize);
                sides.insert((a.min(b), a.max(b)));
            }
        }
        for (a, b) in sides {
            edges.push((
                [v[a].clone(), v[b].clone()],
                [f2(&pictures[a]), f2(&pictures[b])],
            ));
        }
        vertices.extend(pictures.iter().map(|p| (p.clone(), f2(p))));
    }
    let mut points: Vec<[f64; 2]> = d
        .polylines
        .iter()
        .flat_map(|p| p.points.iter().copied())
        .collect();
    points.sort_by(|x, y| x.partial_cmp(y).unwrap());
    points.dedup();
    let scale = scale_of(d);
    let (mut worst, mut crossings) = (0.0f64, 0usize);
    for p in points {
        let near = |c: [f64; 2]| (c[0] - p[0]).hypot(c[1] - p[1]) <= 1e-9;
        let at_vertex = vertices
            .iter()
            .filter(|(_, f)| near(*f))
            .map(|(x, _)| ulps2(p, x, scale))
            .fold(f64::INFINITY, f64::min);
        let close: Vec<_> = edges
            .iter()
            .filter(|(_, [a, b])| distance_to_segment(p, *a, *b) <= 1e-9)
            .collect();
        let mut at_crossing = f64::INFINITY;
        if at_vertex > MAX_ULPS {
            // Both ways round: the exact picture of the point cut on one edge lies on the
            // other's picture only up to the rows' rounding (they are not exactly orthogonal
            // to the eye direction), so the two differ in the last bits.
            for i in 0..close.len() {
                for j in 0..close.len() {
                    if i == j {
                        continue;
                    }
                    let ([a, b], [c, e]) = (&close[i].0, &close[j].0);
                    if let Some(x) = rv.crossing(a, b, c, e) {
                        at_crossing = at_crossing.min(ulps2(p, &rv.picture(&x), scale));
                    }
                }
            }
        }
        let e = at_vertex.min(at_crossing);
        assert!(
            e <= MAX_ULPS,
            "{name}: vertex {p:?} is {e} ulps from the nearest exact reference ({} edges near it)",
            close.len()
        );
        if at_vertex > MAX_ULPS {
            crossings += 1;
        }
        worst = worst.max(e);
    }
    (worst, crossings)
}

/// Whether the triangle `t` hides `x` (exactly, the library's rule): `x` lies strictly behind
/// the triangle's plane as seen from the eye, and the line of sight through `x` meets the
/// closed triangle.
fn triangle_hides(rv: &RefView, t: &[V; 3], x: &V) -> bool {
    let n = qcross(&qsub(&t[1], &t[0]), &qsub(&t[2], &t[0]));
    let eye_side = rv.facing(&n, &t[0]);
    if eye_side == Ordering::Equal || qsign(&qdot(&n, &qsub(x, &t[0]))) != eye_side.reverse() {
        return false;
    }
    let signs: Vec<Ordering> = (0..3)
        .map(|i| qsign(&rv.sight(&t[i], &t[(i + 1) % 3], x)))
        .collect();
    !(signs.contains(&Ordering::Greater) && signs.contains(&Ordering::Less))
}

/// Checks the visibility of every piece of the drawing of `mesh` independently: the piece is
/// matched to the edge whose picture holds both its ends, a point of that edge near the
/// piece's middle is taken exactly, and it is hidden when some triangle of the mesh hides
/// it. Returns how many pieces were checked.
fn check_visibility_by_rays(name: &str, d: &Drawing, mesh: &Mesh, rv: &RefView) -> usize {
    let v: Vec<V> = mesh.vertices().iter().map(qp).collect();
    let pictures: Vec<[f64; 2]> = v.iter().map(|x| f2(&rv.picture(x))).collect();
    let mut sides = std::collections::BTreeSet::new();
    for f in mesh.faces() {
        let l = f.vertices();
        for i in 0..l.len() {
            let (a, b) = (l[i] as usize, l[(i + 1) % l.len()] as usize);
            sides.insert((a.min(b), a.max(b)));
        }
    }
    let triangles: Vec<([V; 3], [[f64; 2]; 2])> = mesh
        .triangles()
        .iter()
        .map(|t| {
            let pics = t.map(|i| pictures[i as usize]);
            let lo = [0, 1].map(|k| pics.iter().map(|p| p[k]).fold(f64::INFINITY, f64::min) - 1e-9);
            let hi =
                [0, 1].map(|k| pics.iter().map(|p| p[k]).fold(f64::NEG_INFINITY, f64::max) + 1e-9);
            (t.map(|i| v[i as usize].clone()), [lo, hi])
        })
        .collect();
    let segments = lib_segments(d);
    for (class, visible, [p, r]) in &segments {
        let on: Vec<&(usize, usize)> = sides
            .iter()
            .filter(|&&(a, b)| {
                distance_to_segment(*p, pictures[a], pictures[b]) <= 1e-9
                    && distance_to_segment(*r, pictures[a], pictures[b]) <= 1e-9
            })
            .collect();
        assert_eq!(
            on.len(),
            1,
            "{name}: piece {p:?} {r:?} on {} edges",
            on.len()
        );
        let (a, b) = *on[0];
        let (pa, pb) = (pictures[a], pictures[b]);
        let m = [(p[0] + r[0]) / 2.0, (p[1] + r[1]) / 2.0];
        let (dx, dy) = (pb[0] - pa[0], pb[1] - pa[1]);
        // The parameter of the middle along the edge's picture (affine in an orthographic
        // view; any point well inside the piece will do).
        let t = ((m[0] - pa[0]) * dx + (m[1] - pa[1]) * dy) / (dx * dx + dy * dy);
        let x = qlerp(&v[a], &v[b], &q(t));
        let hidden = triangles.iter().any(|(tri, [lo, hi])| {
            (lo[0]..=hi[0]).contains(&m[0])
                && (lo[1]..=hi[1]).contains(&m[1])
                && triangle_hides(rv, tri, &x)
        });
        assert_eq!(
            !hidden, *visible,
            "{name}: {class:?} piece {p:?} {r:?} drawn visible={visible}"
        );
    }
    segments.len()
}

#[test]
fn torus_hides_parts_of_itself() {
    let torus = solids::torus(2.0, 0.75, 16, 8).unwrap();
    let all = Options {
        edges: EdgeSelection::All,
        ..Options::default()
    };
    for direction in [
        Vector3::new(0.3, -1.0, -0.45),
        Vector3::new(-0.6, -1.0, -0.25),
    ] {
        let view = View::orthographic(direction, Vector3::z()).unwrap();
        for (label, opts) in [("feature", options()), ("all", all)] {
            let name = format!("torus {direction:?} ({label} edges)");
            let d = draw(&scene_of(std::slice::from_ref(&torus)), &view, &opts).unwrap();
            // Seen from above at a low angle, the near half of the ring hides part of the
            // far half: parts of the silhouette are hidden, and pieces end at cuts.
            assert!(d.length(EdgeClass::Silhouette, true) > 0.0);
            assert!(
                d.length(EdgeClass::Silhouette, false) > 0.0,
                "{name}: no hidden silhouette"
            );
            let rv = RefView::new(&view);
            let (worst, crossings) =
                check_vertices_near_references(&name, &d, std::slice::from_ref(&torus), &rv);
            assert!(crossings >= 2, "{name}: only {crossings} cut vertices");
            let pieces = check_visibility_by_rays(&name, &d, &torus, &rv);
            println!(
                "{name}: {pieces} pieces, {crossings} cut vertices, largest vertex error {worst:.3} ulps"
            );
        }
    }
}

// ---------------------------------------------------------------------------------------------
// 5. Nested objects.

#[test]
fn nested_groups_draw_as_flat() {
    let (front, back, view) = two_boxes();
    // In front of the cube (towards the eye), hiding part of it.
    let small = cuboid_at([0.5, 0.75, 0.5], [1.5, 1.5, 2.25]);
    let mut nested = Scene::new();
    let outer = nested.add_group(None, "outer").unwrap();
    let inner = nested.add_group(Some(outer), "inner").unwrap();
    let innermost = nested.add_group(Some(inner), "innermost").unwrap();
    nested
        .add_mesh(Some(innermost), "front", front.clone())
        .unwrap();
    nested.add_mesh(Some(inner), "back", back.clone()).unwrap();
    nested
        .add_mesh(Some(outer), "small", small.clone())
        .unwrap();
    let meshes = [front, back, small];
    let d_nested = draw(&nested, &view, &options()).unwrap();
    let (d_flat, want, worst) = check_convex("three boxes (flat)", &meshes, &view);
    assert_eq!(bit_segments(&d_nested), bit_segments(&d_flat));
    assert_eq!(d_nested.polylines.len(), d_flat.polylines.len());
    match_segments("three boxes (nested)", &d_nested, &want);
    // By hand: the small box hides the cube's near corner (1, 1, 1), cutting each of its
    // three visible creases once; with the four cuts of `box_partly_behind_another`:
    expect_counts(
        &d_flat,
        &[
            ((EdgeClass::Silhouette, true), 6 + 5 + 6),
            ((EdgeClass::Silhouette, false), 3),
            ((EdgeClass::Crease, true), 3 + 2 + 3),
            ((EdgeClass::Crease, false), (3 + 3) + 6 + 3),
        ],
    );
    let corner_cuts = [
        qv([0.8125, 1.0, 1.0]),
        qv([1.0, 1.0, 0.6875]),
        qv([1.0, 0.125, 1.0]),
    ];
    // Seen along (1, 2, 3) from each: at s = 7/16, (1.25, 1.875, 2.3125) on the small box's
    // edge x = 1.25, y = 1.875; at s = 7/16, (1.4375, 1.875, 2) on y = 1.875, z = 2; at
    // s = 1/2, (1.5, 1.125, 2.5) on y = 1.125, z = 2.5.
    let u = qv([1.0, 2.0, 3.0]);
    let (lo, hi) = ([1.25, 1.125, 2.0], [1.75, 1.875, 2.5]);
    assert!(
        corner_cuts
            .iter()
            .all(|x| sight_meets_box_edge(x, |_| u.clone(), lo, hi))
    );
    let mut all_cuts = corner_cuts.to_vec();
    all_cuts.extend(two_boxes_cuts());
    assert_cuts(
        &d_nested,
        &want,
        &meshes.iter().collect::<Vec<_>>(),
        &view,
        &all_cuts,
    );
    println!(
        "nested: {} polylines, largest vertex error {worst:.3} ulps",
        d_nested.polylines.len()
    );
}

// ---------------------------------------------------------------------------------------------
// 6. A cube in perspective.

fn perspective_view() -> View {
    View::perspective(
        Point3::new(4.0, -5.0, 3.0),
        Point3::origin(),
        Vector3::z(),
        40.0,
    )
    .unwrap()
}

#[test]
fn cube_in_perspective() {
    let cube = solids::cube(2.0).unwrap();
    let view = perspective_view();
    let rv = RefView::new(&view);
    let (d, want, worst) = check_convex("cube in perspective", std::slice::from_ref(&cube), &view);
    // The eye (4, -5, 3) sees the faces x = 1, y = -1 and z = 1: the corner (1, -1, 1) is
    // nearest.
    let hand = hand_cube(1.0, [0.0; 3], [1, -1, 1], &rv);
    assert!(same_pieces(&hand, &want));
    match_segments("cube in perspective (by hand)", &d, &hand);
    expect_counts(
        &d,
        &[
            ((EdgeClass::Silhouette, true), 6),
            ((EdgeClass::Crease, true), 3),
            ((EdgeClass::Crease, false), 3),
        ],
    );
    assert!(
        worst <= 2.0,
        "the library claims 2 ulps for perspective vertices: {worst}"
    );
    // A box behind it in perspective: cuts by the perspective crossing definition.
    let back = cuboid_at([1.0, 3.0, 1.5], [-0.5, 3.0, -1.5]);
    let (d2, want2, worst2) = check_convex(
        "two boxes in perspective",
        &[cube.clone(), back.clone()],
        &view,
    );
    // The cube draws as above; the box behind it (x in [-1, 0], y in [1.5, 4.5], z in
    // [-2.25, -0.75]) shows only its far end: 3 of its silhouette edges visible (2 of them
    // cut), 5 hidden pieces; of its creases 1 cut (a visible piece), the others hidden.
    expect_counts(
        &d2,
        &[
            ((EdgeClass::Silhouette, true), 6 + 3),
            ((EdgeClass::Silhouette, false), 5),
            ((EdgeClass::Crease, true), 3 + 1),
            ((EdgeClass::Crease, false), 3 + 6),
        ],
    );
    // The cuts, by hand: the line from each towards the eye meets the cube's silhouette edge
    // x = 1, y = 1: from (0, 3, z) at s = 1/4, from (-0.75, 4.5, -0.75) at s = 7/19.
    let hand_cuts = [
        qv([0.0, 3.0, -2.25]),
        qv([0.0, 3.0, -0.75]),
        qv([-0.75, 4.5, -0.75]),
    ];
    let e = qv([4.0, -5.0, 3.0]);
    assert!(
        hand_cuts
            .iter()
            .all(|x| sight_meets_cube_edge(x, |x| qsub(&e, x)))
    );
    assert_cuts(&d2, &want2, &[&cube, &back], &view, &hand_cuts);
    assert!(
        worst2 <= 2.0,
        "the library claims 2 ulps for perspective vertices: {worst2}"
    );
    println!("cube in perspective: {worst:.3} ulps; two boxes: {worst2:.3} ulps");
}

// ---------------------------------------------------------------------------------------------
// Orientation independence and coplanar neighbours.

#[test]
fn inside_out_cube_draws_the_same() {
    let cube = solids::cube(2.0).unwrap();
    let reversed = inside_out(&cube);
    assert_ne!(reversed.faces()[0].vertices(), cube.faces()[0].vertices());
    for view in [
        View::orthographic(Vector3::new(-1.0, -2.0, -3.0), Vector3::z()).unwrap(),
        View::orthographic(Vector3::new(2.0, -1.0, -0.5), Vector3::z()).unwrap(),
        perspective_view(),
    ] {
        let a = draw(&scene_of(std::slice::from_ref(&cube)), &view, &options()).unwrap();
        let b = draw(
            &scene_of(std::slice::from_ref(&reversed)),
            &view,
            &options(),
        )
        .unwrap();
        assert_eq!(bit_segments(&a), bit_segments(&b));
        assert_eq!(lib_segments(&a).len(), 12);
        check_convex("inside-out cube", std::slice::from_ref(&reversed), &view);
    }
}

#[test]
fn triangulated_cube_draws_the_same() {
    let cube = solids::cube(2.0).unwrap();
    let split = triangulated(&cube);
    assert_eq!(split.faces().len(), 12);
    for view in [
        View::orthographic(Vector3::new(-1.0, -2.0, -3.0), Vector3::z()).unwrap(),
        View::orthographic(Vector3::new(2.0, -1.0, -0.5), Vector3::z()).unwrap(),
        perspective_view(),
    ] {
        let a = draw(&scene_of(std::slice::from_ref(&cube)), &view, &options()).unwrap();
        let b = draw(&scene_of(std::slice::from_ref(&split)), &view, &options()).unwrap();
        // No edge between coplanar triangles: the same 12 pieces.
        assert_eq!(bit_segments(&a), bit_segments(&b));
        assert_eq!(lib_segments(&b).len(), 12);
        check_convex("triangulated cube", std::slice::from_ref(&split), &view);
    }
}

// ---------------------------------------------------------------------------------------------
// The checks themselves can fail.

#[test]
fn the_checks_reject_wrong_drawings() {
    let one = q(1.0);
    let mut x = 1.0f64;
    for _ in 0..5 {
        x = x.next_up();
    }
    assert_eq!(ulps(x, &one, 1.0), 5.0);
    assert_eq!(ulps(1.0f64.next_down(), &one, 1.0), 0.5);
    assert_eq!(ulps(1e-300, &Q::zero(), 1.0), 1e-300 / f64::EPSILON);

    let cube = solids::cube(2.0).unwrap();
    let view = View::orthographic(Vector3::new(-1.0, -2.0, -3.0), Vector3::z()).unwrap();
    let (d, want, _) = check_convex("cube", std::slice::from_ref(&cube), &view);
    let crease = d
        .polylines
        .iter()
        .position(|p| p.class == EdgeClass::Crease)
        .unwrap();
    let moved = |ulps: usize| {
        let mut e = d.clone();
        let p = &mut e.polylines[crease].points[0];
        for _ in 0..ulps {
            p[0] = if p[0] > 0.0 {
                p[0].next_up()
            } else {
                p[0].next_down()
            };
        }
        e
    };
    let accepts = |e: &Drawing| {
        std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
            match_segments("probe", e, &want)
        }))
        .is_ok()
    };
    assert!(accepts(&moved(3)));
    assert!(!accepts(&moved(5)));
    let mut flipped = d.clone();
    flipped.polylines[crease].visible = !flipped.polylines[crease].visible;
    assert!(!accepts(&flipped));
    let mut fewer = d.clone();
    fewer.polylines.remove(crease);
    assert!(!accepts(&fewer));
}

/// Boxes touching: one resting on another, one beside it sharing a face. Faces that only
/// touch make no intersection line, and every edge matches the exact reference (an edge lying
/// on another box's face is on it, not behind it), from three views including the axis-aligned
/// ones where whole faces are seen edge-on.
#[test]
fn touching_boxes_make_no_intersection_lines() {
    let meshes = [
        cuboid_at([4.0, 4.0, 1.0], [0.0, 0.0, 0.5]),
        cuboid_at([2.0, 2.0, 1.0], [0.0, 0.0, 1.5]),
        cuboid_at([1.0, 4.0, 1.0], [2.5, 0.0, 0.5]),
    ];
    let views = [
        View::orthographic(Vector3::new(-1.0, -2.0, -3.0), Vector3::z()).unwrap(),
        View::orthographic(Vector3::new(0.3, -1.0, -0.7), Vector3::z()).unwrap(),
        View::perspective(
            Point3::new(7.0, -9.0, 6.0),
            Point3::origin(),
            Vector3::z(),
            40.0,
        )
        .unwrap(),
    ];
    for (k, view) in views.iter().enumerate() {
        let (d, _, worst) = check_convex(&format!("touching boxes, view {k}"), &meshes, view);
        assert!(worst <= MAX_ULPS, "view {k}: {worst} ulps");
        assert!(
            d.polylines
                .iter()
                .all(|p| p.class != EdgeClass::Intersection),
            "view {k}: touching faces drew an intersection line"
        );
        // The top box's bottom edges lie on the base's top face: the near ones are visible.
        assert!(d.length(EdgeClass::Crease, true) > 0.0);
    }
}

// ---------------------------------------------------------------------------------------------
// 7. Degenerate faces and polygon edges (issue 14).

/// The unit cube's corners (index `x + 2y + 4z`), the midpoint of its edge from corner 0 to
/// corner 1 (index 8), and its quads turned outward.
fn cube_with_midpoint() -> (Vec<Point3>, Vec<Vec<u32>>) {
    let cube = solids::box_between([0.0; 3], [1.0; 3]).unwrap();
    let mut v = cube.vertices().to_vec();
    v.push(Point3::new(0.5, 0.0, 0.0));
    (v, cube.polygons())
}

/// Orthographic and perspective views from every side of the unit cube.
fn views_around_the_cube() -> Vec<View> {
    let mut views = Vec::new();
    for (i, d) in [
        [-1.0, -2.0, -3.0],
        [1.0, 2.0, -3.0],
        [-2.0, 1.0, 3.0],
        [3.0, -1.0, 2.0],
        [0.0, 1.0, 0.0],
        [0.0, -1.0, 1.0],
    ]
    .into_iter()
    .enumerate()
    {
        let d = Vector3::from(d);
        let up = if d.x == 0.0 && d.y == 0.0 {
            Vector3::x()
        } else {
            Vector3::z()
        };
        views.push(View::orthographic(d, up).unwrap());
        let eye = Point3::new(0.5, 0.5, 0.5) - d * (2.0 + i as f64);
        views.push(View::perspective(eye, Point3::new(0.5, 0.5, 0.5), up, 50.0).unwrap());
    }
    views
}

fn drawing_of(
    vertices: Vec<Point3>,
    faces: Vec<Vec<u32>>,
    view: &View,
    edges: EdgeSelection,
) -> Drawing {
    let mut scene = Scene::new();
    scene
        .add_mesh(None, "m", Mesh::from_polygons(vertices, faces).unwrap())
        .unwrap();
    let options = Options {
        edges,
        hidden: true,
        ..Options::default()
    };
    draw(&scene, view, &options).unwrap()
}

/// Visibility, class and points of each polyline, in order.
fn lines(d: &Drawing) -> Vec<(EdgeClass, bool, Vec<[f64; 2]>)> {
    d.polylines
        .iter()
        .map(|p| (p.class, p.visible, p.points.clone()))
        .collect()
}

/// A cube with a zero-area sliver triangle along an edge draws exactly as the cube: the
/// sliver alone, the sliver with the edge's midpoint also in one neighbouring face (a
/// T-junction once the sliver is dropped), and faces repeating a vertex.
#[test]
fn a_cube_with_a_sliver_along_an_edge_draws_as_the_cube() {
    let (v, cube) = cube_with_midpoint();
    let mut sliver = cube.clone();
    sliver.push(vec![0, 8, 1]);
    let mut junction = cube.clone();
    junction[2] = vec![0, 8, 1, 5, 4];
    junction.push(vec![1, 8, 0]);
    let mut repeated = junction.clone();
    repeated.push(vec![4, 5, 4]);
    repeated.push(vec![3, 7, 7, 3]);
    let variants = [
        ("sliver", sliver),
        ("junction", junction),
        ("repeated", repeated),
    ];
    for (name, faces) in &variants {
        let m = Mesh::from_polygons(v.clone(), faces.clone()).unwrap();
        assert!(m.is_solid(), "{name}");
        assert_eq!(m.topology().boundary_edges, 0, "{name}");
        assert!(m.degenerate_faces() >= 1, "{name}");
    }
    let corners = v[..8].to_vec();
    for (i, view) in views_around_the_cube().iter().enumerate() {
        for edges in [
            EdgeSelection::Feature,
            EdgeSelection::All,
            EdgeSelection::Mesh,
        ] {
            let want = lines(&drawing_of(corners.clone(), cube.clone(), view, edges));
            assert!(!want.is_empty());
            for (name, faces) in &variants {
                let got = lines(&drawing_of(v.clone(), faces.clone(), view, edges));
                assert_eq!(got, want, "{name}, view {i}, {edges:?}");
            }
        }
    }
}

/// `--edges mesh` draws every polygon edge, even between coplanar faces: a cube whose quads
/// are given as two triangles each draws as the quad cube with `feature` and `all` (the
/// diagonals join coplanar faces), and with `mesh` adds the six diagonals as smooth edges,
/// the visible ones exactly on the pictures of the front faces' diagonals.
#[test]
fn edges_mesh_draws_the_edges_between_coplanar_polygons() {
    let (v, cube) = cube_with_midpoint();
    let triangles: Vec<Vec<u32>> = cube
        .iter()
        .flat_map(|q| [vec![q[0], q[1], q[2]], vec![q[0], q[2], q[3]]])
        .collect();
    let view = View::orthographic(Vector3::new(-1.0, -2.0, -3.0), Vector3::z()).unwrap();
    let rv = RefView::new(&view);
    for edges in [EdgeSelection::Feature, EdgeSelection::All] {
        assert_eq!(
            lines(&drawing_of(v.clone(), triangles.clone(), &view, edges)),
            lines(&drawing_of(v.clone(), cube.clone(), &view, edges)),
            "{edges:?}"
        );
    }
    let quads = lines(&drawing_of(
        v.clone(),
        cube.clone(),
        &view,
        EdgeSelection::Mesh,
    ));
    assert_eq!(
        quads,
        lines(&drawing_of(
            v.clone(),
            cube.clone(),
            &view,
            EdgeSelection::All
        ))
    );
    let d = lines(&drawing_of(
        v.clone(),
        triangles,
        &view,
        EdgeSelection::Mesh,
    ));
    let (smooth, rest): (Vec<_>, Vec<_>) = d.into_iter().partition(|l| l.0 == EdgeClass::Smooth);
    assert_eq!(rest, quads);
    // Looking along (-1, -2, -3), the eye sees the faces x = 1, y = 1 and z = 1: faces 1, 3
    // and 5, whose diagonals run from corner q[0] to corner q[2].
    let picture = |i: u32| f2(&rv.picture(&qp(&v[i as usize])));
    let mut want: Vec<[[f64; 2]; 2]> = [1, 3, 5]
        .iter()
        .map(|&f| [picture(cube[f][0]), picture(cube[f][2])])
        .collect();
    let mut visible: Vec<[[f64; 2]; 2]> = smooth
        .iter()
        .filter(|l| l.1)
        .flat_map(|l| l.2.windows(2).map(|w| [w[0], w[1]]).collect::<Vec<_>>())
        .collect();
    for s in want.iter_mut().chain(visible.iter_mut()) {
        s.sort_by(|a, b| a.partial_cmp(b).unwrap());
    }
    want.sort_by(|a, b| a.partial_cmp(b).unwrap());
    visible.sort_by(|a, b| a.partial_cmp(b).unwrap());
    for (got, want) in visible.iter().zip(&want) {
        for k in 0..2 {
            for c in 0..2 {
                assert!(
                    (got[k][c] - want[k][c]).abs() <= 1e-15,
                    "{got:?} vs {want:?}"
                );
            }
        }
    }
    assert_eq!(visible.len(), 3, "{visible:?}");
    assert!(
        smooth.iter().any(|l| !l.1),
        "the back diagonals are drawn hidden"
    );
}

/// Cuts closer together than a long edge's parameter can tell apart: a box 2⁶⁰ long whose far
/// end lies behind small boxes in front of it. Every crossing of a small box's silhouette with
/// a long edge within 2⁷ of its far end has a parameter that rounds to 1, and the two
/// crossings of one small box often round to one double: the cuts are ordered exactly, and
/// each piece is decided at a point strictly inside it (where no double lies between its cuts,
/// a point between the two exact cut points with positive weights). Before, a cut whose parameter rounded to 1 was dropped, and the hidden
/// piece under the small box was drawn visible.
#[test]
fn cuts_closer_than_the_edge_parameter_resolves() {
    let long = solids::box_between([-(2f64.powi(60)), 0.0, 0.0], [1.0, 1.0, 1.0]).unwrap();
    let fronts = [
        (-3.0, 0.5),
        (-100.0, -50.0),
        (-10.0, -5.0),
        (0.25, 0.75),
        (-0.5, 3.0),
    ];
    let views: Vec<View> = [[-1.0, -2.0, -3.0], [1.25, -2.0, -3.0], [-2.0, 1.0, -5.0]]
        .iter()
        .map(|d| View::orthographic(Vector3::from(*d), Vector3::z()).unwrap())
        .collect();
    for (x0, x1) in fronts {
        let front = solids::box_between([x0, -1.0, 2.0], [x1, 2.0, 3.0]).unwrap();
        for (k, view) in views.iter().enumerate() {
            let name = format!("long box behind [{x0}, {x1}], view {k}");
            let (d, _, _) = check_convex(&name, &[long.clone(), front.clone()], view);
            // Some long edge is hidden near its far end.
            assert!(d.length(EdgeClass::Silhouette, false) > 0.0, "{name}");
        }
    }
}
