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
use kepler::hidden::{Drawing, EdgeClass, EdgeSelection, Options, draw};
use kepler::mesh::Mesh;
use kepler::scene::Scene;
use kepler::views::{Picture, View};
use std::cmp::Ordering;

mod common;
use common::exact::{P2, RefEye, RefView, V, opposite, qdet, qlerp, qp, ulps2};
use common::{Q, Rng, qcross, qdot, qsub};
use num_traits::Zero;

/// A solid as input: vertices and polygon faces.
#[derive(Clone, Debug)]
struct Solid {
    vertices: Vec<Point3>,
    faces: Vec<Vec<u32>>,
}

impl Solid {
    fn mesh(&self) -> Mesh {
        Mesh::from_polygons(self.vertices.clone(), self.faces.clone()).unwrap()
    }

    fn map(&self, f: &impl Fn(&Point3) -> Point3) -> Solid {
        Solid {
            vertices: self.vertices.iter().map(f).collect(),
            faces: self.faces.clone(),
        }
    }

    /// Each face split into a fan of triangles.
    fn triangulated(&self) -> Solid {
        Solid {
            vertices: self.vertices.clone(),
            faces: self
                .faces
                .iter()
                .flat_map(|f| (1..f.len() - 1).map(move |i| vec![f[0], f[i], f[i + 1]]))
                .collect(),
        }
    }

    fn reversed(&self) -> Solid {
        Solid {
            vertices: self.vertices.clone(),
            faces: self
                .faces
                .iter()
                .map(|f| f.iter().rev().copied().collect())
                .collect(),
        }
    }
}

/// A view as input.
#[derive(Clone, Copy, Debug)]
enum ViewSpec {
    Orthographic {
        direction: Vector3,
        up: Vector3,
    },
    Perspective {
        eye: Point3,
        target: Point3,
        up: Vector3,
    },
}

impl ViewSpec {
    fn view(&self) -> Option<View> {
        match *self {
            ViewSpec::Orthographic { direction, up } => View::orthographic(direction, up).ok(),
            ViewSpec::Perspective { eye, target, up } => {
                View::perspective(eye, target, up, 40.0).ok()
            }
        }
    }

    fn is_perspective(&self) -> bool {
        matches!(self, ViewSpec::Perspective { .. })
    }
}

/// A transformation of scene and view.
#[derive(Clone, Copy, Debug)]
enum Transform {
    /// `x[axis] ↦ -x[axis]`.
    Mirror(usize),
    /// `x ↦ (x[p[0]], x[p[1]], x[p[2]])`.
    Permute([usize; 3]),
    /// `x ↦ 2^k·x`.
    Scale(i32),
    /// `x ↦ x + t` (points only).
    Translate([f64; 3]),
}

impl Transform {
    /// The linear part, on a vector.
    fn vector(&self, v: &Vector3) -> Vector3 {
        match *self {
            Transform::Mirror(a) => {
                let mut w = *v;
                w[a] = -w[a];
                w
            }
            Transform::Permute(p) => Vector3::new(v[p[0]], v[p[1]], v[p[2]]),
            Transform::Scale(_) | Transform::Translate(_) => *v,
        }
    }

    fn point(&self, x: &Point3) -> Point3 {
        match *self {
            Transform::Scale(k) => Point3::from(x.coords * 2f64.powi(k)),
            Transform::Translate(t) => {
                let y = Point3::new(x.x + t[0], x.y + t[1], x.z + t[2]);
                assert_eq!(y - Vector3::from(t), *x, "translation not exact");
                y
            }
            _ => Point3::from(self.vector(&x.coords)),
        }
    }

    fn view(&self, v: &ViewSpec) -> ViewSpec {
        match *v {
            ViewSpec::Orthographic { direction, up } => ViewSpec::Orthographic {
                direction: self.vector(&direction),
                up: self.vector(&up),
            },
            ViewSpec::Perspective { eye, target, up } => ViewSpec::Perspective {
                eye: self.point(&eye),
                target: self.point(&target),
                up: self.vector(&up),
            },
        }
    }

    /// How the picture is expected to change, from the two views' picture maps: `(sx, sy,
    /// c)` with `(x, y) ↦ (sx·c·x, sy·c·y)`, or `None` where the transformed view's frame is
    /// not exactly the transformed frame (its normalisation rounded differently).
    fn picture(&self, before: &View, after: &View) -> Option<(f64, f64, f64)> {
        let (r, _) = Picture::of(before).rows();
        let (s, _) = Picture::of(after).rows();
        let sign = |k: usize| {
            let t = self.vector(&r[k]);
            if s[k] == t {
                Some(1.0)
            } else if s[k] == -t {
                Some(-1.0)
            } else {
                None
            }
        };
        let (sx, sy, sz) = (sign(0)?, sign(1)?, sign(2)?);
        let perspective = before.is_perspective();
        if perspective && sz != 1.0 {
            return None;
        }
        let c = match *self {
            Transform::Scale(k) if !perspective => 2f64.powi(k),
            _ => 1.0,
        };
        Some((sx, sy, c))
    }
}

fn dyadic(rng: &mut Rng, lo: i32, hi: i32) -> f64 {
    rng.int(4 * lo, 4 * hi) / 4.0
}

fn box_solid(min: [f64; 3], max: [f64; 3]) -> Solid {
    let m = kepler::solids::box_between(min, max).unwrap();
    Solid {
        vertices: m.vertices().to_vec(),
        faces: m.faces().iter().map(|f| f.vertices().to_vec()).collect(),
    }
}

/// A solid of the given vertices and faces, turned outward.
fn outward(vertices: Vec<Point3>, faces: Vec<Vec<u32>>) -> Solid {
    let s = Solid { vertices, faces };
    if s.mesh().volume() < 0.0 {
        s.reversed()
    } else {
        s
    }
}

fn random_solid(rng: &mut Rng) -> Solid {
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
fn random_scene(rng: &mut Rng) -> Vec<Solid> {
    (0..2 + rng.below(2)).map(|_| random_solid(rng)).collect()
}

fn small_vector(rng: &mut Rng) -> Vector3 {
    loop {
        let v = Vector3::new(rng.int(-4, 4), rng.int(-4, 4), rng.int(-4, 4));
        if v != Vector3::zeros() {
            return v;
        }
    }
}

fn random_view(rng: &mut Rng, perspective: bool) -> ViewSpec {
    loop {
        let up = small_vector(rng);
        let spec = if perspective {
            let eye = Point3::from(small_vector(rng) * 8.0);
            if eye.coords.norm() < 24.0 {
                continue;
            }
            let target = Point3::new(dyadic(rng, -1, 1), dyadic(rng, -1, 1), dyadic(rng, -1, 1));
            ViewSpec::Perspective { eye, target, up }
        } else {
            ViewSpec::Orthographic {
                direction: small_vector(rng),
                up,
            }
        };
        if spec.view().is_some() {
            return spec;
        }
    }
}

fn options() -> Options {
    Options {
        edges: EdgeSelection::All,
        ..Options::default()
    }
}

fn drawing(solids: &[Solid], view: &View) -> Drawing {
    let mut scene = Scene::new();
    for (i, s) in solids.iter().enumerate() {
        scene.add_mesh(None, format!("s{i}"), s.mesh()).unwrap();
    }
    draw(&scene, view, &options()).unwrap()
}

type Segment = (EdgeClass, bool, [[u64; 2]; 2]);

/// The drawing's segments, sorted: each with its ends in order, `-0` read as `0`.
fn segments(d: &Drawing, map: impl Fn([f64; 2]) -> [f64; 2]) -> Vec<Segment> {
    let bits = |p: [f64; 2]| map(p).map(|x| if x == 0.0 { 0u64 } else { x.to_bits() });
    let mut out: Vec<Segment> = d
        .polylines
        .iter()
        .flat_map(|p| {
            p.points.windows(2).map(move |w| {
                let (a, b) = (bits(w[0]), bits(w[1]));
                (p.class, p.visible, if a <= b { [a, b] } else { [b, a] })
            })
        })
        .collect();
    out.sort_unstable_by_key(|x| (x.0 as u8, x.1, x.2));
    out
}

/// Where two segment lists differ, for the failure message.
fn difference(a: &[Segment], b: &[Segment]) -> String {
    let only = |x: &[Segment], y: &[Segment]| -> Vec<String> {
        x.iter()
            .filter(|s| !y.contains(s))
            .take(4)
            .map(|(c, v, e)| {
                let p = e.map(|p| p.map(f64::from_bits));
                format!("{c:?} {v} {p:?}")
            })
            .collect()
    };
    format!(
        "{} vs {} segments; only in the first: {:?}; only in the second: {:?}",
        a.len(),
        b.len(),
        only(a, b),
        only(b, a)
    )
}

fn intersections(d: &Drawing) -> usize {
    d.polylines
        .iter()
        .filter(|p| p.class == EdgeClass::Intersection)
        .count()
}

/// What a family of checks covered.
#[derive(Default, Debug)]
struct Tally {
    /// The scene's seed.
    seed: u64,
    compared: usize,
    skipped: usize,
    with_intersections: usize,
}

/// Draws the scene and its transformed copy (solids also passed through `solids`) and checks
/// that the second drawing is the first with the expected picture change.
fn check(
    tally: &mut Tally,
    name: &str,
    scene: &[Solid],
    spec: &ViewSpec,
    t: Option<Transform>,
    solids: impl Fn(&Solid) -> Solid,
) {
    let view = spec.view().unwrap();
    let changed = |s: &Solid| match t {
        Some(t) => solids(&s.map(&|p| t.point(p))),
        None => solids(s),
    };
    // A quad whose vertices, moved far, no longer pass the meshes' planarity check (done in
    // floating point) is split into triangles in both scenes.
    let scene: Vec<Solid> = scene
        .iter()
        .map(|s| {
            let c = changed(s);
            if Mesh::from_polygons(c.vertices, c.faces).is_ok() {
                s.clone()
            } else {
                s.triangulated()
            }
        })
        .collect();
    let scene = &scene[..];
    let spec2 = t.map_or(*spec, |t| t.view(spec));
    let scene2: Vec<Solid> = scene.iter().map(changed).collect();
    let Some(view2) = spec2.view() else {
        tally.skipped += 1;
        return;
    };
    let (sx, sy, c) = match t {
        Some(t) => match t.picture(&view, &view2) {
            Some(m) => m,
            None => {
                tally.skipped += 1;
                return;
            }
        },
        None => (1.0, 1.0, 1.0),
    };
    let d1 = drawing(scene, &view);
    let d2 = drawing(&scene2, &view2);
    let a = segments(&d1, |p| [sx * c * p[0], sy * c * p[1]]);
    let b = segments(&d2, |p| p);
    assert!(
        a == b,
        "{name}, seed {}: {t:?}, view {spec:?}: {}",
        tally.seed,
        difference(&a, &b)
    );
    tally.compared += 1;
    if intersections(&d1) > 0 {
        tally.with_intersections += 1;
    }
}

const SEEDS: u64 = 40;

/// Runs `family` over the random scenes, in both projections, and checks that it covered
/// scenes with intersection lines.
fn over_scenes(name: &str, family: impl Fn(&mut Tally, &mut Rng, &[Solid], &ViewSpec)) -> Tally {
    let mut tally = Tally::default();
    for seed in 0..SEEDS {
        let mut rng = Rng(0x1e14_0000 + seed);
        tally.seed = seed;
        let scene = random_scene(&mut rng);
        for perspective in [false, true] {
            let spec = random_view(&mut rng, perspective);
            family(&mut tally, &mut rng, &scene, &spec);
        }
    }
    assert!(
        tally.with_intersections >= tally.compared / 2 && tally.compared >= SEEDS as usize,
        "{name}: too few cases with intersection lines: {tally:?}"
    );
    eprintln!("{name}: {tally:?}");
    tally
}

#[test]
fn mirroring_mirrors_the_drawing() {
    over_scenes("mirror", |tally, rng, scene, spec| {
        let t = Transform::Mirror(rng.below(3));
        check(tally, "mirror", scene, spec, Some(t), Solid::clone);
        // Mirrored and reversed: solids turned outward again.
        check(
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
    over_scenes("reverse", |tally, rng, scene, spec| {
        check(tally, "reverse", scene, spec, None, Solid::reversed);
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
        check(tally, "reverse some", &some, spec, None, Solid::reversed);
    });
}

#[test]
fn permuting_axes_permutes_the_drawing() {
    const PERMUTATIONS: [[usize; 3]; 5] = [[1, 2, 0], [2, 0, 1], [1, 0, 2], [0, 2, 1], [2, 1, 0]];
    let tally = over_scenes("permute", |tally, _, scene, spec| {
        for p in PERMUTATIONS {
            check(
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
    over_scenes("scale", |tally, rng, scene, spec| {
        for k in [1, -1, 60, -60, rng.int(-59, 59) as i32] {
            check(
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
    over_scenes("translate", |tally, rng, scene, spec| {
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
            check(tally, "translate", scene, spec, t, Solid::clone);
        }
    });
}

#[test]
fn translating_along_an_orthographic_view_changes_nothing() {
    // Views along an axis, with any up direction across it: their frames have exact zeros
    // along the axis, so a translation along it leaves every exact picture unchanged.
    over_scenes("translate along", |tally, rng, scene, _| {
        let axis = rng.below(3);
        let mut direction = Vector3::zeros();
        direction[axis] = if rng.below(2) == 0 { 1.0 } else { -2.0 };
        let mut up = small_vector(rng);
        up[axis] = 0.0;
        if up == Vector3::zeros() {
            up[(axis + 1) % 3] = 1.0;
        }
        let spec = ViewSpec::Orthographic { direction, up };
        for offset in [2f64.powi(40), -(2f64.powi(50)), -1e8 - 0.25, 123_456_789.5] {
            let mut t = [0.0; 3];
            t[axis] = offset;
            let t = Some(Transform::Translate(t));
            check(tally, "translate along", scene, &spec, t, Solid::clone);
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
        let mut rng = Rng(0xe4ac_7000 + seed);
        let scene = random_scene(&mut rng);
        for perspective in [false, true] {
            let spec = random_view(&mut rng, perspective);
            let view = spec.view().unwrap();
            let d = drawing(&scene, &view);
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
    let mut rng = Rng(0x1e14_0000);
    let scene = random_scene(&mut rng);
    let spec = random_view(&mut rng, false);
    let d = drawing(&scene, &spec.view().unwrap());
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
