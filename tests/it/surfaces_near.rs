//! Visible surfaces from a perspective eye inside the scene: the view clips to its frustum.
//! An eye inside a closed room with boxes (deterministic seeds): every visible polygon lies in
//! the picture's window, points inside visible polygons are visible by VISP, faces reported
//! HIDDEN or VISIBLE agree with VISP at sample points inside the frustum (also with bars
//! through the plane of the eye hiding boxes in front), a box wholly behind the eye changes no
//! bit of what a scene in front of it shows, and VISOBJ follows.

use crate::common::SplitMix64;
use crate::common::exact::cuboid_at;
use geo::{InteriorPoint, MultiPolygon};
use kepler::geometry::{Point3, Vector3};
use kepler::queries::visp::{Visibility, VisibilityIndex};
use kepler::scene::{ObjectId, Scene};
use kepler::surfaces::{FaceReport, Status, visible_surfaces, visobj};
use kepler::views::{Picture, View};

/// The aspect of the pictures.
const ASPECT: f64 = 1.5;

/// A perspective view from `eye` towards `target`, clipping at `ASPECT`.
fn view(eye: Point3, target: Point3) -> View {
    View::perspective(eye, target, Vector3::z(), 60.0)
        .unwrap()
        .with_clipping(0.25, ASPECT)
        .unwrap()
}

/// A room (a closed cube of edge 16 about the origin), an eye inside it and boxes that miss
/// the eye and the walls.
fn room(seed: u64) -> (Scene, View) {
    let mut rng = SplitMix64(seed);
    let mut scene = Scene::new();
    scene
        .add_mesh(None, "room", kepler::solids::cube(16.0).unwrap())
        .unwrap();
    let eye = Point3::from(rng.vector(4.0));
    let target = eye + rng.vector(1.0) + Vector3::new(0.0, 0.0, 0.01);
    let mut added = 0;
    while added < 12 {
        let size = [0; 3].map(|_| rng.range(0.5, 3.0));
        let at = [0; 3].map(|_| rng.range(-6.0, 6.0));
        let clear = (0..3).any(|k| (eye[k] - at[k]).abs() > size[k] / 2.0 + 0.5);
        if clear {
            scene
                .add_mesh(None, format!("box{added}"), cuboid_at(size, at))
                .unwrap();
            added += 1;
        }
    }
    (scene, view(eye, target))
}

/// The point of face `report`'s plane whose picture is `p`, moved towards the eye by 2⁻³⁰ of
/// the way (so that the face itself does not hide it, whatever the rounding).
fn on_face(scene: &Scene, view: &View, report: &FaceReport, p: [f64; 2]) -> Option<Point3> {
    let mesh = scene[report.object].mesh().unwrap();
    let plane = mesh.faces()[report.face].plane();
    let x = Picture::of(view).unproject(p, &plane.normal, plane.d)?;
    let kepler::views::Eye::Point(eye) = *view.eye() else {
        unreachable!()
    };
    Some(x + (eye - x) * 2f64.powi(-30))
}

/// Whether `x` lies inside the frustum, its picture inside the window by a margin.
fn well_inside(view: &View, x: &Point3) -> bool {
    let picture = Picture::of(view);
    view.frustum().unwrap().contains(x) && picture.in_front(x) && {
        let [px, py] = picture.point(x);
        px.abs() < ASPECT * 0.999 && py.abs() < 0.999
    }
}

/// Sample points of a face (on its triangles, barycentric).
fn samples(scene: &Scene, report: &FaceReport, rng: &mut SplitMix64) -> Vec<Point3> {
    let mesh = scene[report.object].mesh().unwrap();
    let range = mesh.faces()[report.face].triangle_range();
    range
        .flat_map(|t| {
            let [a, b, c] = mesh.triangle(t);
            (0..8)
                .map(|_| {
                    let (mut s, mut u) = (rng.unit(), rng.unit());
                    if s + u > 1.0 {
                        (s, u) = (1.0 - s, 1.0 - u);
                    }
                    a + (b - a) * s + (c - a) * u
                })
                .collect::<Vec<_>>()
        })
        .collect()
}

/// Checks the visible surfaces of `scene` from `view` against VISP; the number of faces of
/// each status, and of sample points checked.
fn check(scene: &Scene, view: &View, seed: u64) -> ([usize; 3], usize) {
    let faces = visible_surfaces(scene, view).unwrap();
    let index = VisibilityIndex::whole_scene(scene, view.clone());
    let kepler::views::Eye::Point(eye) = *view.eye() else {
        unreachable!()
    };
    let mut rng = SplitMix64(seed ^ 0x5eed);
    let mut counts = [0; 3];
    // Points checked inside visible polygons, and sample points of VISIBLE or HIDDEN faces.
    let mut checked = [0; 2];
    for report in &faces {
        let polygons: &MultiPolygon<f64> = &report.visible.polygons;
        for polygon in polygons {
            let rings = std::iter::once(polygon.exterior()).chain(polygon.interiors());
            for c in rings.flat_map(|r| r.coords()) {
                let slack = 1e-15;
                assert!(
                    c.x.abs() <= ASPECT * (1.0 + slack) && c.y.abs() <= 1.0 + slack,
                    "seed {seed}: face {} vertex {c:?} outside the window",
                    report.face
                );
            }
            // A point well inside each visible polygon is visible.
            if let Some(p) = polygon.interior_point()
                && let Some(x) = on_face(scene, view, report, [p.x(), p.y()])
            {
                assert_eq!(
                    index.visp(&x).0,
                    Visibility::Visible,
                    "seed {seed}: face {} of {}: {x:?} in its visible polygons is hidden",
                    report.face,
                    scene.path(report.object)
                );
                checked[0] += 1;
            }
        }
        // Sample points of the face well inside the frustum, moved a little towards the eye:
        // all visible for a VISIBLE face, none for a HIDDEN one.
        let expected = match report.visible.status {
            Status::Visible => Some(Visibility::Visible),
            Status::Hidden => Some(Visibility::Hidden),
            Status::Mixed => None,
        };
        counts[report.visible.status as usize] += 1;
        if report.visible.edge_on {
            continue;
        }
        for x in samples(scene, report, &mut rng) {
            let x = x + (eye - x) * 2f64.powi(-30);
            if let Some(e) = expected
                && well_inside(view, &x)
            {
                checked[1] += 1;
                assert_eq!(
                    index.visp(&x).0,
                    e,
                    "seed {seed}: face {} of {:?} ({:?}) at {x:?}",
                    report.face,
                    scene.path(report.object),
                    report.visible.status
                );
            }
        }
        if report.visible.status == Status::Visible {
            let mesh = scene[report.object].mesh().unwrap();
            for v in mesh.face_points(report.face) {
                assert!(view.frustum().unwrap().contains(&v), "seed {seed}");
            }
        }
    }
    assert!(checked[0] > 0, "seed {seed}: no visible polygon checked");
    (counts, checked[1])
}

#[test]
fn an_eye_inside_a_room_sees_only_its_frustum() {
    let (mut totals, mut samples) = ([0; 3], 0);
    for seed in 0..64 {
        let (scene, view) = room(seed);
        let (counts, checked) = check(&scene, &view, seed);
        for k in 0..3 {
            totals[k] += counts[k];
        }
        samples += checked;
    }
    // Every status occurs, and many faces were sampled.
    assert!(totals.iter().all(|&n| n > 0), "{totals:?}");
    assert!(samples > 1000, "{samples}");
}

/// Boxes wholly inside the frustum of a view, and the view.
fn in_front(seed: u64) -> (Scene, View, Vec<ObjectId>) {
    let mut rng = SplitMix64(seed);
    let view = view(Point3::new(0.0, -20.0, 1.0), Point3::new(0.0, 0.0, 0.0));
    let frustum = view.frustum().unwrap();
    let mut scene = Scene::new();
    let mut ids = Vec::new();
    while ids.len() < 5 {
        let size = [0; 3].map(|_| rng.range(0.5, 3.0));
        let at = [0; 3].map(|_| rng.range(-4.0, 4.0));
        let mesh = cuboid_at(size, at);
        if mesh.vertices().iter().all(|v| frustum.contains(v)) {
            let name = format!("box{}", ids.len());
            ids.push(scene.add_mesh(None, name, mesh).unwrap());
        }
    }
    (scene, view, ids)
}

#[test]
fn a_box_behind_the_eye_changes_nothing_in_front() {
    for seed in 0..16 {
        let (mut scene, view, _) = in_front(seed);
        let before = visible_surfaces(&scene, &view).unwrap();
        // Wholly behind the eye (y = −20), and one across the plane of the eye.
        let behind = scene
            .add_mesh(
                None,
                "behind",
                cuboid_at([4.0, 2.0, 4.0], [1.0, -24.0, 0.5]),
            )
            .unwrap();
        let across = scene
            .add_mesh(
                None,
                "across",
                cuboid_at([1.0, 4.0, 1.0], [30.0, -20.0, 0.0]),
            )
            .unwrap();
        let after = visible_surfaces(&scene, &view).unwrap();
        let kept: Vec<&FaceReport> = after
            .iter()
            .filter(|r| r.object != behind && r.object != across)
            .collect();
        assert_eq!(kept.len(), before.len());
        for (a, b) in kept.iter().zip(&before) {
            assert_eq!((a.object, a.face), (b.object, b.face));
            assert_eq!(a.visible.status, b.visible.status, "seed {seed}");
            assert_eq!(a.visible.polygons, b.visible.polygons, "seed {seed}");
            assert_eq!(a.texture, b.texture, "seed {seed}");
        }
        let extra = after
            .iter()
            .filter(|r| r.object == behind || r.object == across);
        assert!(extra.clone().count() == 12);
        assert!(extra.clone().all(|r| r.visible.status == Status::Hidden));
        assert_eq!(
            visobj(&scene, behind, across, &view).unwrap(),
            Status::Hidden
        );
    }
}

#[test]
fn occluders_across_the_plane_of_the_eye_hide_what_is_in_front() {
    // Long bars through the plane of the eye, by it, hide parts of boxes wholly in the frustum.
    let mut totals = [0; 3];
    for seed in 0..48 {
        let (mut scene, view, _) = in_front(seed);
        let mut rng = SplitMix64(seed ^ 0xba5);
        let mut bars = 0;
        while bars < 3 {
            let size = [
                rng.range(0.2, 1.0),
                rng.range(6.0, 12.0),
                rng.range(0.2, 1.0),
            ];
            let at = [
                rng.range(-1.5, 1.5),
                rng.range(-22.0, -18.0),
                rng.range(-0.5, 2.5),
            ];
            let clear = [0, 2]
                .iter()
                .any(|&k| (at[k] - [0.0, 0.0, 1.0][k]).abs() > size[k] / 2.0);
            if clear {
                scene
                    .add_mesh(None, format!("bar{bars}"), cuboid_at(size, at))
                    .unwrap();
                bars += 1;
            }
        }
        let (counts, _) = check(&scene, &view, seed);
        for k in 0..3 {
            totals[k] += counts[k];
        }
    }
    assert!(totals.iter().all(|&n| n > 0), "{totals:?}");
}

#[test]
fn visobj_from_inside_a_room() {
    // The eye in a room looks at a box wholly in view; another box lies behind the eye.
    let mut scene = Scene::new();
    let room = scene
        .add_mesh(None, "room", kepler::solids::cube(16.0).unwrap())
        .unwrap();
    let front = scene
        .add_mesh(None, "front", cuboid_at([1.0; 3], [0.0, 4.0, 0.0]))
        .unwrap();
    let back = scene
        .add_mesh(None, "back", cuboid_at([1.0; 3], [0.0, -4.0, 0.0]))
        .unwrap();
    let view = view(Point3::new(0.0, 0.0, 0.5), Point3::new(0.0, 4.0, 0.0));
    assert_eq!(visobj(&scene, room, front, &view).unwrap(), Status::Visible);
    assert_eq!(visobj(&scene, room, back, &view).unwrap(), Status::Hidden);
    // The box in front hides part of the far wall, the room part of its own faces (those
    // turned away from the eye, which face the wall behind them).
    assert_eq!(visobj(&scene, front, room, &view).unwrap(), Status::Mixed);
}
