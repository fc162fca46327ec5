//! Intersection lines, exactly (issue 14): each end of an intersection line and each point
//! where one is cut is constructed once from the input, and the order of points along the line
//! and the visibility between them are decided exactly. So the drawing of a scene of solids
//! that pierce each other (boxes, tetrahedra and parallelepipeds with dyadic coordinates) is
//! the same, bit for bit, under
//!
//! - mirroring scene and view (the picture's `x` negated),
//! - reversing every face (or some),
//! - permuting the axes of scene and view (where the view's frame, normalised in floating
//!   point, comes out exactly permuted: then the picture's `x` is negated for an odd
//!   permutation),
//! - scaling scene and view by `2^k` (the picture scaled by `2^k` in an orthographic view, the
//!   same in a perspective one),
//! - translating scene and eye together by `2^40` or by about `10^8` (exactly representable
//!   sums): in a perspective view any translation; in an orthographic one a translation along
//!   the view direction, for views along an axis (any other moves the picture by an amount
//!   that is not representable),
//!
//! in both projections. Drawings are compared as multisets of segments (class, visibility,
//! ends in either order, `-0` read as `0`): how pieces chain into polylines may legitimately
//! differ, nothing else.
//!
//! And the vertices of intersection lines are compared with exact rational references: every
//! vertex of an intersection polyline lies within 2 ulp of the picture of an edge's crossing
//! with another solid's face plane, of a point where three face planes meet, or of a point
//! where a line of two face planes meets a plane of sight through an edge.

use kepler::geometry::predicates::orient3d;
use kepler::geometry::{Point3, Vector3};
use kepler::hidden::{Drawing, EdgeClass, EdgeSelection, Options};
use std::cmp::Ordering;

use crate::common::exact::{P2, RefEye, RefView, V, opposite, qdet, qlerp, qp, ulps2};
use crate::common::invariance::{
    Setup, Solid, Transform, along_an_axis, box_solid, check, drawing, dyadic, outward,
    over_scenes, random_view, segments,
};
use crate::common::{Q, SplitMix64, qcross, qdot, qsub};
use num_traits::Zero;

fn random_solid(rng: &mut SplitMix64) -> Solid {
    match rng.below(3) {
        0 => {
            let c = [0; 3].map(|_| dyadic(rng, -2, 2));
            let h = [0; 3].map(|_| rng.int(2, 14) / 4.0);
            box_solid(
                [c[0] - h[0], c[1] - h[1], c[2] - h[2]],
                [c[0] + h[0], c[1] + h[1], c[2] + h[2]],
            )
        }
        1 => loop {
            let p: Vec<Point3> = (0..4)
                .map(|_| Point3::new(dyadic(rng, -4, 4), dyadic(rng, -4, 4), dyadic(rng, -4, 4)))
                .collect();
            if orient3d(&p[0], &p[1], &p[2], &p[3]) != Ordering::Equal {
                let faces = vec![vec![0, 1, 2], vec![0, 3, 1], vec![1, 3, 2], vec![0, 2, 3]];
                return outward(p, faces);
            }
        },
        _ => loop {
            let p0 = Vector3::new(dyadic(rng, -3, 0), dyadic(rng, -3, 0), dyadic(rng, -3, 0));
            let d = [0; 3].map(|_| Vector3::new(rng.int(-4, 4), rng.int(-4, 4), rng.int(-4, 4)));
            if d[0].cross(&d[1]).dot(&d[2]) == 0.0 {
                continue;
            }
            let corner = |i: usize| {
                let pick = |k: usize| {
                    if i & (1 << k) != 0 {
                        d[k]
                    } else {
                        Vector3::zeros()
                    }
                };
                Point3::from(p0 + pick(0) + pick(1) + pick(2))
            };
            let b = box_solid([0.0; 3], [1.0; 3]);
            return outward((0..8).map(corner).collect(), b.faces);
        },
    }
}

/// Two or three solids around the origin, most of them piercing each other.
fn random_scene(rng: &mut SplitMix64) -> Vec<Solid> {
    (0..2 + rng.below(2)).map(|_| random_solid(rng)).collect()
}

/// The families' setup: random scenes of solids that pierce each other, every edge drawn.
const SETUP: Setup = Setup {
    options: Options {
        edges: EdgeSelection::All,
        crease_angle: 30.0,
        hidden: true,
        overlaps: kepler::hidden::Overlaps::Keep,
    },
    seeds: 40,
    base: 0x1e14_0000,
    scene: random_scene,
    about: |d| intersections(d) > 0,
};

fn options() -> Options {
    Options {
        edges: EdgeSelection::All,
        ..Options::default()
    }
}

fn intersections(d: &Drawing) -> usize {
    d.polylines
        .iter()
        .filter(|p| p.class == EdgeClass::Intersection)
        .count()
}

#[test]
fn mirroring_mirrors_the_drawing() {
    over_scenes(&SETUP, "mirror", |tally, rng, scene, spec| {
        let t = Transform::Mirror(rng.below(3));
        check(&SETUP, tally, "mirror", scene, spec, Some(t), Solid::clone);
        // Mirrored and reversed: solids turned outward again.
        check(
            &SETUP,
            tally,
            "mirror+reverse",
            scene,
            spec,
            Some(t),
            Solid::reversed,
        );
    });
}

#[test]
fn reversing_faces_changes_nothing() {
    over_scenes(&SETUP, "reverse", |tally, rng, scene, spec| {
        check(&SETUP, tally, "reverse", scene, spec, None, Solid::reversed);
        // Some solids reversed, the others not.
        let pick = rng.next_u64();
        let some: Vec<Solid> = scene
            .iter()
            .enumerate()
            .map(|(i, s)| {
                if pick >> i & 1 == 1 {
                    s.reversed()
                } else {
                    s.clone()
                }
            })
            .collect();
        check(
            &SETUP,
            tally,
            "reverse some",
            &some,
            spec,
            None,
            Solid::reversed,
        );
    });
}

#[test]
fn permuting_axes_permutes_the_drawing() {
    const PERMUTATIONS: [[usize; 3]; 5] = [[1, 2, 0], [2, 0, 1], [1, 0, 2], [0, 2, 1], [2, 1, 0]];
    let tally = over_scenes(&SETUP, "permute", |tally, _, scene, spec| {
        for p in PERMUTATIONS {
            check(
                &SETUP,
                tally,
                "permute",
                scene,
                spec,
                Some(Transform::Permute(p)),
                Solid::clone,
            );
        }
    });
    // The view's frame is normalised by a length rounded once from the exact sum of squares,
    // so it permutes exactly with the axes: no case has a frame that rounds differently.
    assert_eq!(tally.skipped, 0, "{tally:?}");
}

#[test]
fn scaling_by_powers_of_two_scales_the_drawing() {
    over_scenes(&SETUP, "scale", |tally, rng, scene, spec| {
        for k in [1, -1, 60, -60, rng.int(-59, 59) as i32] {
            check(
                &SETUP,
                tally,
                "scale",
                scene,
                spec,
                Some(Transform::Scale(k)),
                Solid::clone,
            );
        }
    });
}

#[test]
fn translating_scene_and_eye_changes_nothing_in_perspective() {
    over_scenes(&SETUP, "translate", |tally, rng, scene, spec| {
        if !spec.is_perspective() {
            return;
        }
        // Coordinates are multiples of 1/4: exact after any of these moves (2^50 + 1/4 too).
        let offsets = [
            [2f64.powi(40), 0.0, 0.0],
            [-(2f64.powi(40)), 2f64.powi(40), 2f64.powi(39)],
            [2f64.powi(50), -(2f64.powi(50)), 2f64.powi(49)],
            [1e8, -123_456_789.25, 98_765_432.5],
            [0; 3].map(|_| rng.int(-(1 << 20), 1 << 20) * 128.0 + 0.75),
        ];
        for t in offsets {
            let t = Some(Transform::Translate(t));
            check(&SETUP, tally, "translate", scene, spec, t, Solid::clone);
        }
    });
}

#[test]
fn translating_along_an_orthographic_view_changes_nothing() {
    // Views along an axis, with any up direction across it: their frames have exact zeros
    // along the axis, so a translation along it leaves every exact picture unchanged.
    over_scenes(&SETUP, "translate along", |tally, rng, scene, _| {
        let (axis, spec) = along_an_axis(rng);
        for offset in [2f64.powi(40), -(2f64.powi(50)), -1e8 - 0.25, 123_456_789.5] {
            let mut t = [0.0; 3];
            t[axis] = offset;
            let t = Some(Transform::Translate(t));
            check(
                &SETUP,
                tally,
                "translate along",
                scene,
                &spec,
                t,
                Solid::clone,
            );
        }
    });
}

// ---------------------------------------------------------------------------------------------
// Exact references for the vertices of intersection lines.

/// A plane `n·x = h`, exactly.
struct Plane {
    n: V,
    h: Q,
}

impl Plane {
    fn through(a: &V, b: &V, c: &V) -> Plane {
        let n = qcross(&qsub(b, a), &qsub(c, a));
        let h = qdot(&n, a);
        Plane { n, h }
    }

    fn at(&self, x: &V) -> Q {
        qdot(&self.n, x) - &self.h
    }
}

/// The point where three planes meet, if they meet in one point.
fn meet3(p: &Plane, q: &Plane, r: &Plane) -> Option<V> {
    let d = qdet(&p.n, &q.n, &r.n);
    if d.is_zero() {
        return None;
    }
    // Cramer: x = (h_p (q×r) + h_q (r×p) + h_r (p×q)) / d.
    let (a, b, c) = (qcross(&q.n, &r.n), qcross(&r.n, &p.n), qcross(&p.n, &q.n));
    Some([0, 1, 2].map(|k| (&p.h * &a[k] + &q.h * &b[k] + &r.h * &c[k]) / &d))
}

/// The exact candidates for vertices of intersection lines, as pictures.
fn references(solids: &[Solid], rv: &RefView) -> Vec<P2> {
    let meshes: Vec<(Vec<V>, Vec<Vec<u32>>)> = solids
        .iter()
        .map(|s| (s.vertices.iter().map(qp).collect(), s.faces.clone()))
        .collect();
    let planes: Vec<(usize, Plane)> = meshes
        .iter()
        .enumerate()
        .flat_map(|(m, (v, faces))| {
            faces.iter().map(move |f| {
                let p = |i: usize| &v[f[i] as usize];
                (m, Plane::through(p(0), p(1), p(2)))
            })
        })
        .collect();
    let edges: Vec<(V, V)> = meshes
        .iter()
        .flat_map(|(v, faces)| {
            faces.iter().flat_map(move |f| {
                (0..f.len()).map(move |i| {
                    (
                        v[f[i] as usize].clone(),
                        v[f[(i + 1) % f.len()] as usize].clone(),
                    )
                })
            })
        })
        .collect();
    let mut points: Vec<V> = Vec::new();
    // Edges crossing the planes of other solids' faces.
    for (m, (v, faces)) in meshes.iter().enumerate() {
        for f in faces {
            for i in 0..f.len() {
                let (a, b) = (&v[f[i] as usize], &v[f[(i + 1) % f.len()] as usize]);
                for (_, plane) in planes.iter().filter(|(n, _)| *n != m) {
                    let (fa, fb) = (plane.at(a), plane.at(b));
                    if opposite(&fa, &fb) {
                        points.push(qlerp(a, b, &(&fa / (&fa - &fb))));
                    }
                }
            }
        }
    }
    // Lines of two faces of different solids, cut by a third face or a plane of sight.
    for (i, (m0, p0)) in planes.iter().enumerate() {
        for (j, (m1, p1)) in planes.iter().enumerate().skip(i + 1) {
            if m0 == m1 {
                continue;
            }
            for (_, p2) in planes.iter().skip(j + 1) {
                points.extend(meet3(p0, p1, p2));
            }
            for (c, d) in &edges {
                points.extend(meet3(p0, p1, &sight(&rv.eye, c, d)));
            }
        }
    }
    // Only points within the solids' box (others are no vertices, and may lie behind the eye).
    let all = meshes.iter().flat_map(|(v, _)| v.iter());
    let lo: V = [0, 1, 2].map(|k| all.clone().map(|p| p[k].clone()).min().unwrap());
    let hi: V = [0, 1, 2].map(|k| all.clone().map(|p| p[k].clone()).max().unwrap());
    points
        .iter()
        .filter(|x| (0..3).all(|k| lo[k] <= x[k] && x[k] <= hi[k]))
        .map(|x| rv.picture(x))
        .collect()
}

/// The plane through `c`, `d` and the eye.
fn sight(eye: &RefEye, c: &V, d: &V) -> Plane {
    match eye {
        RefEye::Point(e) => Plane::through(c, d, e),
        RefEye::Direction(u) => {
            let n = qcross(&qsub(d, c), u);
            let h = qdot(&n, c);
            Plane { n, h }
        }
    }
}

#[test]
fn intersection_line_vertices_are_within_two_ulps_of_exact_points() {
    let mut checked = 0usize;
    let mut worst = 0.0f64;
    for seed in 0..12 {
        let mut rng = SplitMix64(0xe4ac_7000 + seed);
        let scene = random_scene(&mut rng);
        for perspective in [false, true] {
            let spec = random_view(&mut rng, perspective);
            let view = spec.view().unwrap();
            let d = drawing(&scene, &view, &options());
            let rv = RefView::new(&view);
            let refs = references(&scene, &rv);
            let scale = d
                .polylines
                .iter()
                .flat_map(|p| p.points.iter())
                .fold(0.0f64, |m, p| m.max(p[0].abs()).max(p[1].abs()));
            for p in d
                .polylines
                .iter()
                .filter(|p| p.class == EdgeClass::Intersection)
            {
                for &x in &p.points {
                    let near = refs
                        .iter()
                        .map(|r| ulps2(x, r, scale))
                        .fold(f64::INFINITY, f64::min);
                    assert!(
                        near <= 2.0,
                        "seed {seed}, view {spec:?}: intersection vertex {x:?} is {near} ulp \
                         from every exact candidate"
                    );
                    worst = worst.max(near);
                    checked += 1;
                }
            }
        }
    }
    assert!(checked > 100, "only {checked} vertices checked");
    eprintln!("{checked} intersection vertices, worst {worst} ulp");
}

#[test]
fn the_checks_see_a_changed_drawing() {
    // A drawing compared with itself after a one-ulp change of one intersection vertex.
    let mut rng = SplitMix64(0x1e14_0000);
    let scene = random_scene(&mut rng);
    let spec = random_view(&mut rng, false);
    let d = drawing(&scene, &spec.view().unwrap(), &options());
    let mut changed = d.clone();
    let p = changed
        .polylines
        .iter_mut()
        .find(|p| p.class == EdgeClass::Intersection)
        .expect("an intersection line");
    p.points[0][0] = f64::from_bits(p.points[0][0].to_bits() + 1);
    assert_ne!(segments(&d, |p| p), segments(&changed, |p| p));
    // And the mirrored picture is not the picture.
    assert_ne!(segments(&d, |p| [-p[0], p[1]]), segments(&d, |p| p));
}
