//! A line crossing the plane of a perspective eye inside the scene whose picture runs along a
//! contour's (issue 27, item 5), against a rational reference.
//!
//! The eye is inside a room; a rail's edge `l` runs through the plane of the eye (one end
//! behind it), in the horizontal plane through the eye, and a box's top face lies in that
//! plane too (seen edge-on, so its edges are silhouettes whose pictures run along `l`'s, on
//! the horizon). The box is nearer than `l` (then `l` is hidden behind it between the lines of
//! sight through two of its top corners), farther (then `l` is seen whole), or nearer and
//! itself reaching behind the eye (a wide contour). `l` is either a short rail whose picture
//! (a ray) is clipped to the window before the uniform grid, or a very long one whose front
//! end's picture lies 2³¹ times the window away, so that it is tested against every other
//! line ("untamed"); the scene has fewer than 64 lines (every pair tested) or more (the
//! grid).
//!
//! The reference cuts `l` wherever anything could change along it (the frustum's planes,
//! every triangle's plane, every triangle side's plane of sight, the lines of sight through
//! every vertex in the plane of `l` and the eye), decides each piece at its exact midpoint
//! (inside the frustum by the five planes' exact signs; hidden when a triangle not edge-on has
//! the point strictly behind its plane and the closed triangle on its line of sight, the
//! drawing's rule), and merges runs. `l`'s traced pieces must be those runs one to one (both
//! ends within 4 units in the last place of the exact pictures), and the drawing must pass
//! `verify`.

use crate::common::exact::{P2, RefView, V, parallelepiped, qdet, qlerp, qp, ulps2};
use crate::common::{Q, q, qcross, qdot, qsign, qsub, qv};
use kepler::geometry::{Point3, Vector3};
use kepler::hidden::verify::{draw_traced, verify};
use kepler::hidden::{EdgeClass, Options};
use kepler::mesh::Mesh;
use kepler::scene::Scene;
use kepler::solids::box_between;
use kepler::views::View;
use num_traits::{One, Zero};
use std::cmp::Ordering;

/// The largest error allowed for a piece's end, in units in the last place per coordinate.
const MAX_ULPS: f64 = 4.0;

/// The eye (dyadic).
const EYE: [f64; 3] = [0.5, 0.25, 1.5];

/// `EYE + d`, exactly for the dyadic offsets used here.
fn at(d: [f64; 3]) -> [f64; 3] {
    let p = std::array::from_fn(|k| EYE[k] + d[k]);
    assert!((0..3).all(|k| p[k] - EYE[k] == d[k]), "inexact point");
    p
}

/// Where the box with the contours lies.
#[derive(Debug, Clone, Copy)]
enum Contour {
    /// Between the eye and `l`.
    Nearer,
    /// Beyond `l`.
    Farther,
    /// Between the eye and `l`, reaching behind the eye (its side's top edge is wide).
    NearerWide,
}

/// The rail whose top edge is `l`: short (its picture a ray clipped to the window) or long
/// (its front end's picture far outside the window).
#[derive(Debug, Clone, Copy)]
enum Rail {
    Short,
    Long,
}

/// The scene and `l`'s ends.
fn scene(rail: Rail, contour: Contour, crowd: bool) -> (Scene, [Point3; 2]) {
    let mut scene = Scene::new();
    let mut add = |name: &str, mesh: Mesh| {
        scene.add_mesh(None, name, mesh).unwrap();
    };
    let (l, rail_mesh, room) = match rail {
        Rail::Short => {
            let (a, b) = (at([1.0, -4.0, 0.0]), at([1.0, 16.0, 0.0]));
            let mesh = box_between(at([1.0, -4.0, -0.25]), at([1.25, 16.0, 0.0])).unwrap();
            ([a, b], mesh, (at([-8.0, -8.0, -4.0]), at([8.0, 24.0, 4.0])))
        }
        Rail::Long => {
            // From far right of the picture, just in front of the eye, to far left behind it:
            // its picture passes through the window near the point (0.5, 1) from the eye.
            let (b, a) = (
                at([2f64.powi(32), 2.0, 0.0]),
                at([1.5 - 2f64.powi(33), -1.0, 0.0]),
            );
            let d = std::array::from_fn(|k| b[k] - a[k]);
            let mesh = parallelepiped(a, d, [0.0, 0.0, -0.25], [0.0, 0.25, 0.0]);
            (
                [a, b],
                mesh,
                (
                    at([-(2f64.powi(34)), -8.0, -4.0]),
                    at([2f64.powi(34), 8.0, 4.0]),
                ),
            )
        }
    };
    let l = l.map(Point3::from);
    assert!(
        rail_mesh.vertices().contains(&l[0]) && rail_mesh.vertices().contains(&l[1]),
        "the rail's vertices are not exact"
    );
    add("room", box_between(room.0, room.1).unwrap());
    add("rail", rail_mesh);
    let (lo, hi) = match (rail, contour) {
        (_, Contour::Nearer) => ([0.125, 0.375, -0.5], [0.25, 0.5, 0.0]),
        (_, Contour::NearerWide) => ([0.125, -1.0, -0.5], [0.25, 0.5, 0.0]),
        (Rail::Short, Contour::Farther) => ([1.5, 4.0, -0.5], [2.0, 6.0, 0.0]),
        (Rail::Long, Contour::Farther) => ([0.5, 2.0, -0.5], [1.0, 2.5, 0.0]),
    };
    add("box", box_between(at(lo), at(hi)).unwrap());
    if crowd {
        // Crates to the left, below the horizon: more than 64 lines, so the uniform grid.
        for i in 0..4 {
            let x = -7.0 + f64::from(i);
            let mesh = box_between(at([x, 6.0, -4.0]), at([x + 0.5, 6.5, -3.0])).unwrap();
            add(&format!("crate{i}"), mesh);
        }
    }
    (scene, l)
}

/// The view: from the eye along +y, a field of view of 90°.
fn view() -> View {
    View::perspective(
        Point3::from(EYE),
        Point3::from(at([0.0, 1.0, 0.0])),
        Vector3::z(),
        90.0,
    )
    .unwrap()
}

/// A run of the reference: `None` outside the frustum, else whether it is visible; its ends'
/// parameters along `l`.
type Run = (Option<bool>, [Q; 2]);

/// Whether the triangle `t` hides `x` (the drawing's rule: the eye not in its plane, `x`
/// strictly behind it, the line of sight through `x` meeting the closed triangle).
fn hides(rv: &RefView, eye: &V, t: &[V; 3], x: &V) -> bool {
    let normal = qcross(&qsub(&t[1], &t[0]), &qsub(&t[2], &t[0]));
    let (eye_side, x_side) = (
        qsign(&qdot(&normal, &qsub(eye, &t[0]))),
        qsign(&qdot(&normal, &qsub(x, &t[0]))),
    );
    if eye_side == Ordering::Equal || x_side != eye_side.reverse() {
        return false;
    }
    let sides: Vec<Ordering> = (0..3)
        .map(|i| qsign(&rv.sight(&t[i], &t[(i + 1) % 3], x)))
        .collect();
    !(sides.contains(&Ordering::Greater) && sides.contains(&Ordering::Less))
}

/// The parameter in `(0, 1)` where the affine function with values `f0`, `f1` at `l`'s ends
/// vanishes, if it changes sign strictly inside.
fn zero(f0: Q, f1: Q) -> Option<Q> {
    let (s0, s1) = (qsign(&f0), qsign(&f1));
    (s0 != Ordering::Equal && s1 == s0.reverse()).then(|| &f0 / (&f0 - &f1))
}

/// The reference runs of `l` (see the module documentation).
fn reference(scene: &Scene, view: &View, l: [V; 2]) -> Vec<Run> {
    let rv = RefView::new(view);
    let eye = qv(EYE);
    let frustum: Vec<(V, V, Q)> = view
        .frustum()
        .unwrap()
        .planes
        .iter()
        .map(|(e, n, d)| (qp(e), qv([n.x, n.y, n.z]), q(*d)))
        .collect();
    let inside = |x: &V| {
        frustum
            .iter()
            .all(|(e, n, d)| qsign(&(qdot(n, &qsub(x, e)) - d)) == Ordering::Greater)
    };
    let triangles: Vec<[V; 3]> = scene
        .mesh_objects(scene.roots())
        .iter()
        .flat_map(|(_, m)| (0..m.triangles().len()).map(|t| m.triangle(t).map(|p| qp(&p))))
        .collect();
    let [a, b] = &l;
    let mut cuts: Vec<Q> = Vec::new();
    for (e, n, d) in &frustum {
        let f = |x: &V| qdot(n, &qsub(x, e)) - d;
        cuts.extend(zero(f(a), f(b)));
    }
    for t in &triangles {
        let f = |x: &V| qdet(&qsub(&t[1], &t[0]), &qsub(&t[2], &t[0]), &qsub(x, &t[0]));
        cuts.extend(zero(f(a), f(b)));
        for i in 0..3 {
            let (p, r) = (&t[i], &t[(i + 1) % 3]);
            cuts.extend(zero(rv.sight(p, r, a), rv.sight(p, r, b)));
            // A vertex in the plane of `l` and the eye: where its line of sight meets `l`.
            if qsign(&rv.sight(a, b, p)) == Ordering::Equal {
                let w = qsub(p, &eye);
                let c = |x: &V| qcross(&qsub(x, &eye), &w);
                let (ca, cb) = (c(a), c(b));
                if let Some(k) = (0..3).find(|&k| ca[k] != cb[k]) {
                    let s = &ca[k] / (&ca[k] - &cb[k]);
                    let x = qlerp(a, b, &s);
                    assert!(c(&x).iter().all(|v| v.is_zero()));
                    if s > Q::zero() && s < Q::one() {
                        cuts.push(s);
                    }
                }
            }
        }
    }
    cuts.sort();
    cuts.dedup();
    let bounds: Vec<Q> = std::iter::once(Q::zero())
        .chain(cuts)
        .chain(std::iter::once(Q::one()))
        .collect();
    let mut runs: Vec<Run> = Vec::new();
    for w in bounds.windows(2) {
        let x = qlerp(a, b, &((&w[0] + &w[1]) / Q::from_integer(2.into())));
        let state = inside(&x).then(|| !triangles.iter().any(|t| hides(&rv, &eye, t, &x)));
        match runs.last_mut() {
            Some((s, ends)) if *s == state => ends[1] = w[1].clone(),
            _ => runs.push((state, [w[0].clone(), w[1].clone()])),
        }
    }
    runs
}

/// Draws the scene, checks it with `verify` and `l`'s pieces against the reference; returns
/// `l`'s drawn pieces' visibilities and the lines' count stage.
fn check(rail: Rail, contour: Contour, crowd: bool) -> (Vec<bool>, String) {
    let name = format!("{rail:?} rail, {contour:?} contour, crowd {crowd}");
    let (scene, l) = scene(rail, contour, crowd);
    let view = view();
    let options = Options::default();
    let traced = draw_traced(&scene, &view, &options, &|_, _| {}).unwrap();
    let report = verify(&scene, &view, &options, &traced);
    assert_eq!(report.disagreements, 0, "{name}:\n{report}");
    let rv = RefView::new(&view);
    let lq = l.map(|p| qp(&p));
    let want: Vec<(bool, [P2; 2])> = reference(&scene, &view, lq.clone())
        .into_iter()
        .filter_map(|(state, [s, t])| {
            let picture = |u: &Q| rv.picture(&qlerp(&lq[0], &lq[1], u));
            state.map(|visible| (visible, [picture(&s), picture(&t)]))
        })
        .collect();
    let mut got: Vec<(EdgeClass, bool, [[f64; 2]; 2])> = traced
        .pieces
        .iter()
        .filter(|p| p.line == l || p.line == [l[1], l[0]])
        .map(|p| (p.class, p.visible, p.ends))
        .collect();
    if traced.pieces.iter().any(|p| p.line == [l[1], l[0]]) {
        got.reverse();
        for (_, _, e) in &mut got {
            e.reverse();
        }
    }
    let shown: Vec<String> = want
        .iter()
        .map(|(v, e)| {
            format!(
                "{v} {:?}..{:?}",
                crate::common::exact::f2(&e[0]),
                crate::common::exact::f2(&e[1])
            )
        })
        .collect();
    assert_eq!(got.len(), want.len(), "{name}: got {got:?}, want {shown:?}");
    for ((class, visible, ends), (v, e)) in got.iter().zip(&want) {
        assert_eq!(*class, EdgeClass::Silhouette, "{name}");
        assert_eq!(visible, v, "{name}: got {got:?}, want {shown:?}");
        for k in 0..2 {
            let error = ulps2(ends[k], &e[k], 1.0);
            assert!(
                error <= MAX_ULPS,
                "{name}: {error} ulps; got {got:?}, want {shown:?}"
            );
        }
    }
    let cuts = traced
        .drawing
        .stages
        .iter()
        .find(|s| s.name == "cuts")
        .map(|s| s.done.clone())
        .unwrap_or_default();
    (got.iter().map(|g| g.1).collect(), cuts)
}

/// Issue 27, item 5: a line crossing the plane of the eye is cut at the lines of sight through
/// the ends of a contour whose picture runs along its own, for every placement of the contour
/// and through every path of the cuts stage (see the module documentation): behind a nearer
/// box, `l` is hidden exactly between the lines of sight through the box's corners; in front
/// of a farther one it is seen whole. `crossing`'s collinear branch cuts `l` at each end's
/// line of sight (the zero on `l` of the plane through the eye, the end and a point off the
/// common plane, decided and built in 3-D; on a wide line it may lie behind the eye, where no
/// piece is drawn). Before commit 6607617 that branch skipped wide lines, yet the cut was made
/// all the same by the contour edge leaving the common plane at that end (the general case):
/// the test fails with both cuts removed, not with either one alone.
#[test]
fn wide_lines_are_cut_at_collinear_contours_ends() {
    let mut untamed = Vec::new();
    for rail in [Rail::Short, Rail::Long] {
        for contour in [Contour::Nearer, Contour::Farther, Contour::NearerWide] {
            for crowd in [false, true] {
                let (visible, cuts) = check(rail, contour, crowd);
                let hidden = visible.iter().filter(|v| !**v).count();
                match contour {
                    Contour::Farther => assert_eq!(visible, [true], "{rail:?} {contour:?}"),
                    _ => assert_eq!(hidden, 1, "{rail:?} {contour:?}: {visible:?}"),
                }
                // Every path of the cuts stage: all pairs, the grid with `l` gridded by its
                // clipped ray, and the grid with `l` too far out to clip.
                assert_eq!(cuts.contains("every pair"), !crowd, "{cuts}");
                if crowd {
                    let far = cuts
                        .split(" too far out to clip")
                        .next()
                        .and_then(|s| s.rsplit(' ').next())
                        .and_then(|n| n.parse::<usize>().ok());
                    untamed.push((rail as usize, far));
                }
            }
        }
    }
    for (rail, far) in untamed {
        match rail {
            0 => assert_eq!(far, Some(0)),
            _ => assert!(far.is_some_and(|n| n > 0), "{far:?}"),
        }
    }
}
