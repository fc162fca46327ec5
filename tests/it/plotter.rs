//! Plotter-clean drawings (issue 17): [`Overlaps::Once`] on real drawings of touching and
//! stacked boxes with dyadic coordinates, seen along the axes (where every point of the
//! drawing is exact, so that rational arithmetic on the drawing's points is the truth), checked
//! against the drawing that keeps overlaps: no two segments of the result overlap along a
//! length (every pair), and every stretch of the drawing is still drawn by a segment of its
//! class and visibility or of one drawn over it. Oblique and perspective views (whose points
//! are rounded) are checked for what rounding cannot blur: nothing is drawn longer.

use crate::common::exact::cuboid_at;
use crate::common::{Q, q};
use kepler::geometry::Vector3;
use kepler::hidden::{Drawing, EdgeClass, Options, Overlaps, draw};
use kepler::scene::Scene;
use kepler::views::View;
use num_traits::Zero;

type P = [Q; 2];

/// The segments of a drawing, exact, with their rank (what is drawn over what).
fn segments(d: &Drawing) -> Vec<(usize, [P; 2])> {
    d.segments()
        .map(|(class, visible, [a, b])| {
            let rank =
                usize::from(visible) * 5 + EdgeClass::ALL.iter().position(|&c| c == class).unwrap();
            (rank, [[q(a[0]), q(a[1])], [q(b[0]), q(b[1])]])
        })
        .collect()
}

fn cross(a: &P, b: &P, c: &P) -> Q {
    (&b[0] - &a[0]) * (&c[1] - &a[1]) - (&b[1] - &a[1]) * (&c[0] - &a[0])
}

/// The parameters of `t`'s ends along `s` (`s(u) = s0 + u·(s1 − s0)`), if `t` lies on `s`'s
/// line; sorted.
fn along(s: &[P; 2], t: &[P; 2]) -> Option<(Q, Q)> {
    if !cross(&s[0], &s[1], &t[0]).is_zero() || !cross(&s[0], &s[1], &t[1]).is_zero() {
        return None;
    }
    let d = [&s[1][0] - &s[0][0], &s[1][1] - &s[0][1]];
    let dd = &d[0] * &d[0] + &d[1] * &d[1];
    let u = |p: &P| ((&p[0] - &s[0][0]) * &d[0] + (&p[1] - &s[0][1]) * &d[1]) / &dd;
    let (a, b) = (u(&t[0]), u(&t[1]));
    Some(if a <= b { (a, b) } else { (b, a) })
}

/// Checks the cleaned drawing against the drawing (both of points that are exact); returns
/// how many pairs of the drawing's segments overlapped.
fn check_clean(name: &str, drawing: &Drawing, clean: &Drawing) -> usize {
    let after = segments(clean);
    for (i, (_, s)) in after.iter().enumerate() {
        for (_, t) in &after[i + 1..] {
            if let Some((a, b)) = along(s, t) {
                let (lo, hi) = (a.max(Q::zero()), b.min(q(1.0)));
                assert!(
                    lo >= hi,
                    "{name}: two segments of the result overlap: {s:?} {t:?}"
                );
            }
        }
    }
    let before = segments(drawing);
    let mut overlapping = 0;
    for (i, (rank, s)) in before.iter().enumerate() {
        overlapping += before[i + 1..]
            .iter()
            .filter(|(_, t)| along(s, t).is_some_and(|(a, b)| a.max(Q::zero()) < b.min(q(1.0))))
            .count();
        // [0, 1] of s covered by result segments of its rank or above.
        let mut cover: Vec<(Q, Q)> = after
            .iter()
            .filter(|(r, _)| r >= rank)
            .filter_map(|(_, t)| along(s, t))
            .collect();
        cover.sort();
        let mut reached = Q::zero();
        for (a, b) in cover {
            if a <= reached && b > reached {
                reached = b;
            }
        }
        assert!(reached >= q(1.0), "{name}: {s:?} is not drawn whole");
    }
    assert!(
        clean
            .polylines
            .iter()
            .all(|p| p.points.windows(2).all(|w| w[0] != w[1]))
    );
    shorter(name, drawing, clean);
    overlapping
}

/// What is left is never longer than what was drawn, class by class.
fn shorter(name: &str, drawing: &Drawing, clean: &Drawing) {
    for class in EdgeClass::ALL {
        for visible in [false, true] {
            assert!(
                clean.length(class, visible) <= drawing.length(class, visible) * (1.0 + 1e-12),
                "{name}: {class:?} longer"
            );
        }
    }
}

/// Views along the axes (exact pictures), then oblique and perspective ones.
fn views() -> Vec<View> {
    vec![
        View::orthographic(Vector3::new(0.0, -1.0, 0.0), Vector3::z()).unwrap(),
        View::orthographic(Vector3::new(1.0, 0.0, 0.0), Vector3::z()).unwrap(),
        View::orthographic(Vector3::new(0.0, 0.0, -1.0), Vector3::y()).unwrap(),
        View::orthographic(Vector3::new(-1.0, -2.0, -1.5), Vector3::z()).unwrap(),
        View::perspective(
            [5.0, -7.0, 4.0].into(),
            [1.0, 0.0, 0.5].into(),
            Vector3::z(),
            40.0,
        )
        .unwrap(),
    ]
}

#[test]
fn touching_and_stacked_boxes_are_drawn_once() {
    let mut overlapping = 0;
    for offset in [0.0, 1e8] {
        let mut scene = Scene::new();
        let at = |x: f64, y: f64, z: f64| [x + offset, y, z];
        // A row of boxes face to face, one on top sharing an edge, a smaller one standing on
        // a face (T-junctions), one sunk into its neighbour.
        scene
            .add_mesh(None, "a", cuboid_at([1.0, 1.0, 1.0], at(0.0, 0.0, 0.0)))
            .unwrap();
        scene
            .add_mesh(None, "b", cuboid_at([1.0, 1.0, 1.0], at(1.0, 0.0, 0.0)))
            .unwrap();
        scene
            .add_mesh(None, "c", cuboid_at([1.0, 1.0, 1.0], at(1.0, 0.0, 1.0)))
            .unwrap();
        scene
            .add_mesh(None, "d", cuboid_at([0.5, 1.0, 0.5], at(2.25, 0.0, 0.75)))
            .unwrap();
        scene
            .add_mesh(None, "e", cuboid_at([1.0, 1.0, 1.0], at(2.75, 0.0, 0.0)))
            .unwrap();
        scene
            .add_mesh(None, "f", cuboid_at([2.0, 0.5, 0.25], at(0.5, 0.25, 1.625)))
            .unwrap();
        for (k, view) in views().iter().enumerate() {
            for hidden in [false, true] {
                let options = Options {
                    hidden,
                    ..Options::default()
                };
                let drawing = draw(&scene, view, &options).unwrap();
                let once = Options {
                    overlaps: Overlaps::Once,
                    ..options
                };
                let clean = draw(&scene, view, &once).unwrap();
                let name = format!("boxes at {offset}, view {k}");
                if k < 3 {
                    overlapping += check_clean(&name, &drawing, &clean);
                } else {
                    shorter(&name, &drawing, &clean);
                }
            }
        }
    }
    assert!(
        overlapping > 20,
        "only {overlapping} overlapping pairs: the test tests little"
    );
}

// ---------------------------------------------------------------------------------------------
// Invariance: the same stretches removed wherever the scene is placed (issue 27).

use crate::common::SplitMix64;
use crate::common::invariance::{
    Setup, Solid, Transform, along_an_axis, box_solid, check, dyadic, over_scenes, overlaps_removed,
};
use kepler::geometry::Point3;
use kepler::hidden::EdgeSelection;

/// Boxes on a quarter lattice, each touching the last along a face (beside it, on top of it,
/// or sunk into it by a quarter), and tetrahedra on lattice points, some standing on a box's
/// face: many stretches of line drawn twice, and intersection lines.
fn touching_scene(rng: &mut SplitMix64) -> Vec<Solid> {
    let mut solids = Vec::new();
    let mut lo = [0; 3].map(|_| dyadic(rng, -2, 0));
    for _ in 0..2 + rng.below(3) {
        let size = [0; 3].map(|_| rng.int(2, 8) / 4.0);
        let hi = [0, 1, 2].map(|k| lo[k] + size[k]);
        solids.push(box_solid(lo, hi));
        let axis = rng.below(3);
        let sunk = if rng.below(3) == 0 { 0.25 } else { 0.0 };
        lo[axis] = hi[axis] - sunk;
        let across = (axis + 1 + rng.below(2)) % 3;
        lo[across] += rng.int(-2, 2) / 4.0;
    }
    for _ in 0..rng.below(3) {
        let p: Vec<Point3> = (0..4)
            .map(|_| Point3::new(dyadic(rng, -2, 2), dyadic(rng, -2, 2), dyadic(rng, -2, 2)))
            .collect();
        if kepler::geometry::predicates::orient3d(&p[0], &p[1], &p[2], &p[3])
            != std::cmp::Ordering::Equal
        {
            let faces = vec![vec![0, 1, 2], vec![0, 3, 1], vec![1, 3, 2], vec![0, 2, 3]];
            solids.push(crate::common::invariance::outward(p, faces));
        }
    }
    solids
}

const fn once(edges: EdgeSelection) -> Options {
    Options {
        edges,
        crease_angle: 30.0,
        hidden: true,
        overlaps: Overlaps::Once,
    }
}

const FEATURE: Setup = Setup {
    options: once(EdgeSelection::Feature),
    seeds: 24,
    base: 0x2700_0000,
    scene: touching_scene,
    about: |d| !overlaps_removed(d).starts_with("0 groups"),
};

const ALL: Setup = Setup {
    options: once(EdgeSelection::All),
    seeds: 16,
    base: 0x2701_0000,
    scene: touching_scene,
    about: |d| !overlaps_removed(d).starts_with("0 groups"),
};

#[test]
fn overlaps_removed_the_same_when_mirrored_reversed_or_permuted() {
    for setup in [&FEATURE, &ALL] {
        over_scenes(
            setup,
            "mirror, reverse, permute",
            |tally, rng, scene, spec| {
                let mirror = Transform::Mirror(rng.below(3));
                check(
                    setup,
                    tally,
                    "mirror",
                    scene,
                    spec,
                    Some(mirror),
                    Solid::clone,
                );
                check(
                    setup,
                    tally,
                    "mirror+reverse",
                    scene,
                    spec,
                    Some(mirror),
                    Solid::reversed,
                );
                check(setup, tally, "reverse", scene, spec, None, Solid::reversed);
                let p = [[1, 2, 0], [2, 0, 1], [1, 0, 2]][rng.below(3)];
                check(
                    setup,
                    tally,
                    "permute",
                    scene,
                    spec,
                    Some(Transform::Permute(p)),
                    Solid::clone,
                );
            },
        );
    }
}

#[test]
fn overlaps_removed_the_same_when_scaled_or_translated() {
    for setup in [&FEATURE, &ALL] {
        over_scenes(setup, "scale, translate", |tally, rng, scene, spec| {
            for k in [1, -60, 60, rng.int(-59, 59) as i32] {
                let t = Some(Transform::Scale(k));
                check(setup, tally, "scale", scene, spec, t, Solid::clone);
            }
            // Coordinates are multiples of 1/4: exact after any of these moves.
            let offsets = [1e8, 2f64.powi(40), -(2f64.powi(50))];
            if spec.is_perspective() {
                for o in offsets {
                    let t = Some(Transform::Translate([o, -o / 2.0, o / 4.0]));
                    check(setup, tally, "translate", scene, spec, t, Solid::clone);
                }
            } else {
                // Along an axis of view: the picture does not move.
                let (axis, along) = along_an_axis(rng);
                for o in offsets {
                    let mut t = [0.0; 3];
                    t[axis] = o;
                    let t = Some(Transform::Translate(t));
                    check(
                        setup,
                        tally,
                        "translate along",
                        scene,
                        &along,
                        t,
                        Solid::clone,
                    );
                }
            }
        });
    }
}
