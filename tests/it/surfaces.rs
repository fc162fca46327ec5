//! VISFAC (Franklin 1981, algorithm D) on hand-made scenes with exact answers: squares in
//! front of, beside and half over another, two faces crossing in depth, an INBOX that hides a
//! face at once, and a cube's own faces from orthographic and perspective views.

use geo::{Area, BoundingRect, MultiPolygon};
use kepler::geometry::{Point3, Vector3};
use kepler::mesh::Mesh;
use kepler::random::SplitMix64;
use kepler::scene::{ObjectId, Scene};
use kepler::solids;
use kepler::surfaces::{Status, visfac};
use kepler::views::View;
use nalgebra::Matrix4;

/// A single square face (an open mesh) with corners `(x0, y0)`, `(x1, y1)` at height `z`,
/// counter-clockwise from above.
fn square(x: [f64; 2], y: [f64; 2], z: f64) -> Mesh {
    let v = vec![
        Point3::new(x[0], y[0], z),
        Point3::new(x[1], y[0], z),
        Point3::new(x[1], y[1], z),
        Point3::new(x[0], y[1], z),
    ];
    Mesh::from_polygons(v, vec![vec![0, 1, 2, 3]]).unwrap()
}

/// The scene of a back square `[0, 2]²` at z = 0 and a front mesh; their ids.
fn over(front: Mesh) -> (Scene, ObjectId, ObjectId) {
    let mut scene = Scene::new();
    let back = scene
        .add_mesh(None, "back", square([0.0, 2.0], [0.0, 2.0], 0.0))
        .unwrap();
    let front = scene.add_mesh(None, "front", front).unwrap();
    (scene, back, front)
}

/// The bounding box of a drawing's polygons: `[x0, y0, x1, y1]`.
fn bounds(p: &MultiPolygon<f64>) -> [f64; 4] {
    let r = p.bounding_rect().expect("not empty");
    [r.min().x, r.min().y, r.max().x, r.max().y]
}

#[test]
fn a_square_in_front_beside_and_half_over_another() {
    let view = View::standard();
    // Fully in front: HIDDEN, nothing left.
    let (scene, back, front) = over(square([-1.0, 3.0], [-1.0, 3.0], 1.0));
    let f = visfac(&scene, front, &view, back, 0).unwrap();
    assert_eq!(f.status, Status::Hidden);
    assert!(f.polygons.0.is_empty());
    // Beside: VISIBLE, the whole square.
    let (scene, back, front) = over(square([3.0, 5.0], [0.0, 2.0], 1.0));
    let f = visfac(&scene, front, &view, back, 0).unwrap();
    assert_eq!(f.status, Status::Visible);
    assert_eq!(f.polygons.unsigned_area(), 4.0);
    // Half over: MIXED, exactly [0, 1] × [0, 2] left.
    let (scene, back, front) = over(square([1.0, 3.0], [-1.0, 3.0], 1.0));
    let f = visfac(&scene, front, &view, back, 0).unwrap();
    assert_eq!(f.status, Status::Mixed);
    assert_eq!(f.polygons.0.len(), 1);
    assert_eq!(f.polygons.unsigned_area(), 2.0);
    assert_eq!(bounds(&f.polygons), [0.0, 0.0, 1.0, 2.0]);
    // Behind instead of in front: it hides nothing.
    let (scene, back, front) = over(square([-1.0, 3.0], [-1.0, 3.0], -1.0));
    assert_eq!(
        visfac(&scene, front, &view, back, 0).unwrap().status,
        Status::Visible
    );
}

#[test]
fn two_faces_crossing_in_depth_are_cut_along_their_intersection_line() {
    // A square tilted from z = -1 at x = 0 to z = 1 at x = 2 crosses the flat square z = 0
    // along x = 1. Seen from above, each hides the other's half beyond that line.
    let tilted = Mesh::from_polygons(
        vec![
            Point3::new(0.0, 0.0, -1.0),
            Point3::new(2.0, 0.0, 1.0),
            Point3::new(2.0, 2.0, 1.0),
            Point3::new(0.0, 2.0, -1.0),
        ],
        vec![vec![0, 1, 2, 3]],
    )
    .unwrap();
    let (scene, back, front) = over(tilted);
    let view = View::standard();
    let flat = visfac(&scene, front, &view, back, 0).unwrap();
    assert_eq!(flat.status, Status::Mixed);
    assert_eq!(bounds(&flat.polygons), [0.0, 0.0, 1.0, 2.0]);
    assert_eq!(flat.polygons.unsigned_area(), 2.0);
    let slope = visfac(&scene, back, &view, front, 0).unwrap();
    assert_eq!(slope.status, Status::Mixed);
    assert_eq!(bounds(&slope.polygons), [1.0, 0.0, 2.0, 2.0]);
    // From below, the other halves.
    let below = View::orthographic(Vector3::z(), Vector3::y()).unwrap();
    let flat = visfac(&scene, front, &below, back, 0).unwrap();
    assert_eq!(flat.status, Status::Mixed);
    assert_eq!(flat.polygons.unsigned_area(), 2.0);
}

#[test]
fn an_inbox_hides_a_face_at_once() {
    let mut scene = Scene::new();
    let back = scene
        .add_mesh(None, "back", square([0.0, 1.0], [0.0, 1.0], 0.0))
        .unwrap();
    let group = scene.add_group(None, "block").unwrap();
    let cube = solids::cube(4.0)
        .unwrap()
        .transformed(&Matrix4::new_translation(&nalgebra::Vector3::new(
            0.5, 0.5, 3.0,
        )))
        .unwrap();
    scene.add_mesh(Some(group), "cube", cube).unwrap();
    let f = visfac(&scene, group, &View::standard(), back, 0).unwrap();
    assert_eq!(f.status, Status::Hidden);
    assert_eq!(f.exits.inbox_hid, 1);
    assert_eq!(f.exits.faces_tested, 0, "no face was needed");
    // Beside the block: its INBOX decides nothing, and nothing hides the square.
    let side = scene
        .add_mesh(None, "side", square([10.0, 11.0], [0.0, 1.0], 0.0))
        .unwrap();
    let s = visfac(&scene, group, &View::standard(), side, 0).unwrap();
    assert_eq!(s.status, Status::Visible);
    assert_eq!(s.exits.inbox_hid, 0);
}

#[test]
fn a_cube_hides_its_own_far_faces() {
    let mut scene = Scene::new();
    let cube = scene
        .add_mesh(None, "cube", solids::cube(2.0).unwrap())
        .unwrap();
    let views = [
        View::orthographic(Vector3::new(-1.0, -2.0, -3.0), Vector3::z()).unwrap(),
        View::orthographic(Vector3::new(2.0, -1.0, -0.5), Vector3::z()).unwrap(),
        View::perspective(
            Point3::new(4.0, -5.0, 3.0),
            Point3::origin(),
            Vector3::z(),
            40.0,
        )
        .unwrap(),
    ];
    for view in &views {
        let statuses: Vec<Status> = (0..6)
            .map(|f| visfac(&scene, cube, view, cube, f).unwrap().status)
            .collect();
        let count = |s: Status| statuses.iter().filter(|&&x| x == s).count();
        assert_eq!(
            (count(Status::Visible), count(Status::Hidden)),
            (3, 3),
            "{view:?}"
        );
    }
    // Straight down: the top is visible, the bottom hidden, the sides seen edge-on (VISIBLE:
    // nothing to hide; no polygons).
    let down: Vec<_> = (0..6)
        .map(|f| visfac(&scene, cube, &View::standard(), cube, f).unwrap())
        .collect();
    let count = |s: Status| down.iter().filter(|v| v.status == s).count();
    assert_eq!((count(Status::Visible), count(Status::Hidden)), (5, 1));
    assert_eq!(down.iter().filter(|v| v.edge_on).count(), 4);
    assert_eq!(down.iter().filter(|v| !v.polygons.0.is_empty()).count(), 1);
}

/// A one-face mesh through the given corners.
fn polygon(corners: &[[f64; 3]]) -> Mesh {
    let v = corners
        .iter()
        .map(|c| Point3::new(c[0], c[1], c[2]))
        .collect();
    Mesh::from_polygons(v, vec![(0..corners.len() as u32).collect()]).unwrap()
}

/// VISFAC of face 0 of `back` behind the one face of `front`.
fn status_of(back: &Mesh, front: &Mesh, view: &View) -> kepler::surfaces::VisibleFace {
    let mut scene = Scene::new();
    let b = scene.add_mesh(None, "back", back.clone()).unwrap();
    let f = scene.add_mesh(None, "front", front.clone()).unwrap();
    visfac(&scene, f, view, b, 0).unwrap()
}

/// Pictures that coincide or touch exactly (the front square is the back one moved along the
/// line of sight, then sideways by a whole side) are decided exactly, although the rounded
/// pictures of the two squares' corners differ: the moved square hides all of the back one
/// (at once, by the single-face exit), and one moved sideways hides nothing (no piece counted).
#[test]
fn statuses_are_exact_where_pictures_coincide_or_touch() {
    let back = square([0.0, 1.0], [0.0, 1.0], 0.0);
    for d in [[-1.0, -1.0, -1.0], [-1.0, -2.0, -3.0], [-3.0, -1.0, -7.0]] {
        let view = View::orthographic(Vector3::new(d[0], d[1], d[2]), Vector3::y()).unwrap();
        for (side, expect) in [
            ([0.0, 0.0], Status::Hidden),
            ([1.0, 0.0], Status::Visible),
            ([0.0, 1.0], Status::Visible),
            ([1.0, 1.0], Status::Visible),
            ([-1.0, 0.0], Status::Visible),
        ] {
            let [x, y, z] = [side[0] - d[0], side[1] - d[1], -d[2]];
            let front = polygon(&[
                [x, y, z],
                [x + 1.0, y, z],
                [x + 1.0, y + 1.0, z],
                [x, y + 1.0, z],
            ]);
            let f = status_of(&back, &front, &view);
            assert_eq!(f.status, expect, "{d:?} {side:?}");
            match expect {
                Status::Hidden => {
                    assert_eq!(f.exits.face_hid, 1);
                    assert!(f.polygons.0.is_empty());
                }
                _ => {
                    assert_eq!(f.exits.faces_in_front, 0, "{d:?} {side:?}");
                    assert_eq!(f.polygons.unsigned_area(), back_area(&view));
                }
            }
        }
    }
}

/// The area of the picture of the unit square at z = 0.
fn back_area(view: &View) -> f64 {
    let p = kepler::views::Picture::of(view);
    let c = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]]
        .map(|[x, y]| p.point(&Point3::new(x, y, 0.0)));
    geo::Polygon::new(
        geo::LineString::from(c.iter().map(|&[x, y]| (x, y)).collect::<Vec<_>>()),
        vec![],
    )
    .unsigned_area()
}

/// A triangle crossing the back square's plane whose part in front of it touches the square's
/// picture exactly along the square's edge: its vertices there are a corner and a point where
/// an edge crosses the plane (built, not input), and the exact test still finds no overlap.
/// A wall through the edge of a slab hides all of the slab's top from behind the wall.
#[test]
fn touching_along_a_cut_and_covering_through_an_edge_are_exact() {
    let back = square([0.0, 2.0], [0.0, 2.0], 0.0);
    let front = polygon(&[[1.0, 2.5, -0.5], [2.0, 1.5, 0.5], [2.0, 3.0, 0.5]]);
    for d in [[0.0, 1.0, -1.0], [0.0, 3.0, -3.0]] {
        let view = View::orthographic(Vector3::new(d[0], d[1], d[2]), Vector3::y()).unwrap();
        let f = status_of(&back, &front, &view);
        assert_eq!((f.status, f.exits.faces_in_front), (Status::Visible, 0));
        // Seen more steeply, the triangle's front part does cover some of the square.
        let steep = View::orthographic(Vector3::new(0.0, -1.0, -1.0), Vector3::y()).unwrap();
        assert_eq!(status_of(&back, &front, &steep).status, Status::Mixed);
    }
    let slab_top = square([0.0, 1.0], [0.0, 1.0], 1.0);
    let wall = polygon(&[
        [1.0, -0.37, -1.0],
        [1.0, 1.73, -1.0],
        [1.0, 1.73, 2.0],
        [1.0, -0.37, 2.0],
    ]);
    let view = View::perspective(
        Point3::new(5.0, 0.7, 3.0),
        Point3::new(0.5, 0.5, 0.5),
        Vector3::z(),
        40.0,
    )
    .unwrap();
    let f = status_of(&slab_top, &wall, &view);
    assert_eq!((f.status, f.exits.face_hid), (Status::Hidden, 1));
}

#[test]
fn bad_faces_are_errors() {
    let mut scene = Scene::new();
    let cube = scene
        .add_mesh(None, "cube", solids::cube(2.0).unwrap())
        .unwrap();
    let group = scene.add_group(None, "g").unwrap();
    assert!(visfac(&scene, cube, &View::standard(), cube, 6).is_err());
    assert!(visfac(&scene, cube, &View::standard(), group, 0).is_err());
}

/// Whether the point `p` lies inside the polygons, and its distance to their boundaries.
fn locate(polygons: &MultiPolygon<f64>, p: [f64; 2]) -> (bool, f64) {
    use geo::{Contains, Distance, Euclidean};
    let point = geo::Point::new(p[0], p[1]);
    let inside = polygons.contains(&point);
    let distance = polygons
        .iter()
        .flat_map(|poly| std::iter::once(poly.exterior()).chain(poly.interiors()))
        .flat_map(|ring| ring.lines())
        .map(|line| Euclidean.distance(&line, &point))
        .fold(f64::INFINITY, f64::min);
    (inside, distance)
}

/// On random scenes of boxes, the visible polygons of every face agree with VISP: points of a
/// face's picture well inside its visible polygons are visible, and points well outside them
/// (but inside the face) are hidden. The 3-D point is found on the face's plane along the line
/// of sight and moved a hair towards the eye, so that its own face cannot hide it.
#[test]
fn visible_polygons_agree_with_visp() {
    use kepler::queries::visp::{Visibility, VisibilityIndex};
    use kepler::views::Picture;
    let mut rng = SplitMix64(0x5eed);
    let mut unit = move || rng.unit();
    let (mut checked, mut hidden) = (0usize, 0usize);
    for case in 0..12 {
        let mut scene = Scene::new();
        for i in 0..3 {
            let size = Vector3::new(0.5 + 2.0 * unit(), 0.5 + 2.0 * unit(), 0.5 + 2.0 * unit());
            let axis = nalgebra::Unit::new_normalize(Vector3::new(
                unit() - 0.5,
                unit() - 0.5,
                unit() - 0.5,
            ));
            let rotation = nalgebra::Rotation3::from_axis_angle(&axis, 6.0 * unit());
            let shift =
                nalgebra::Vector3::new(2.0 * unit() - 1.0, 2.0 * unit() - 1.0, 2.0 * unit() - 1.0);
            let m = Matrix4::new_translation(&shift) * rotation.to_homogeneous();
            let mesh = solids::cuboid(size).unwrap().transformed(&m).unwrap();
            scene.add_mesh(None, format!("box{i}"), mesh).unwrap();
        }
        let dir = Vector3::new(unit() - 0.5, unit() - 0.5, -1.0 - unit());
        let view = View::orthographic(dir, Vector3::y()).unwrap();
        let picture = Picture::of(&view);
        let (right, up) = view.right_up();
        let toward_eye = -view.forward();
        let index = VisibilityIndex::whole_scene(&scene, view.clone());
        let objects: Vec<ObjectId> = scene.roots().to_vec();
        for &id in &objects {
            let mesh = scene[id].mesh().unwrap().clone();
            for f in 0..mesh.faces().len() {
                let seen = kepler::surfaces::visfac_scene(&scene, &view, id, f).unwrap();
                let corners: Vec<Point3> = mesh.face_points(f).collect();
                let whole: Vec<[f64; 2]> = corners.iter().map(|c| picture.point(c)).collect();
                let plane = mesh.faces()[f].plane();
                for _ in 0..60 {
                    // A random point of the face: a random convex combination of its corners.
                    let w: Vec<f64> = corners.iter().map(|_| unit()).collect();
                    let total: f64 = w.iter().sum();
                    let x = corners
                        .iter()
                        .zip(&w)
                        .fold(Vector3::zeros(), |acc, (c, wi)| {
                            acc + c.coords * (wi / total)
                        });
                    let on_face = Point3::from(x);
                    let p = [right.dot(&on_face.coords), up.dot(&on_face.coords)];
                    let (in_visible, to_visible) = locate(&seen.polygons, p);
                    let (_, to_face) = locate(&kepler_face(&whole), p);
                    if to_visible < 1e-6 || to_face < 1e-6 {
                        continue;
                    }
                    // Off the face's plane by a hair, on the eye's side.
                    let lift = if plane.normal.dot(&toward_eye) > 0.0 {
                        1e-9
                    } else {
                        -1e-9
                    };
                    let probe = on_face + plane.normal * lift;
                    let visible = index.visp(&probe).0 == Visibility::Visible;
                    assert_eq!(
                        visible, in_visible,
                        "case {case}, object {id:?} face {f} ({:?}): point {p:?}",
                        seen.status
                    );
                    checked += 1;
                    hidden += usize::from(!visible);
                }
            }
        }
    }
    assert!(
        checked > 2_000 && hidden > 500 && checked - hidden > 500,
        "{checked} {hidden}"
    );
}

/// A face's picture as polygons (for distances to its outline).
fn kepler_face(points: &[[f64; 2]]) -> MultiPolygon<f64> {
    let ring: Vec<geo::Coord<f64>> = points.iter().map(|&[x, y]| geo::Coord { x, y }).collect();
    MultiPolygon::new(vec![geo::Polygon::new(
        geo::LineString::new(ring),
        Vec::new(),
    )])
}

/// Random scenes of three rotated boxes (seeded).
fn random_boxes(seed: u64) -> Scene {
    let mut rng = SplitMix64(seed);
    let mut unit = move || rng.unit();
    let mut scene = Scene::new();
    for i in 0..3 {
        let size = Vector3::new(0.5 + 2.0 * unit(), 0.5 + 2.0 * unit(), 0.5 + 2.0 * unit());
        let axis =
            nalgebra::Unit::new_normalize(Vector3::new(unit() - 0.5, unit() - 0.5, unit() - 0.5));
        let rotation = nalgebra::Rotation3::from_axis_angle(&axis, 6.0 * unit());
        let shift =
            nalgebra::Vector3::new(2.0 * unit() - 1.0, 2.0 * unit() - 1.0, 2.0 * unit() - 1.0);
        let m = Matrix4::new_translation(&shift) * rotation.to_homogeneous();
        let mesh = solids::cuboid(size).unwrap().transformed(&m).unwrap();
        scene.add_mesh(None, format!("box{i}"), mesh).unwrap();
    }
    scene
}

/// Area conservation: the visible polygons of all faces sum to the area of the union of all
/// faces' pictures (computed independently, by uniting the pictures), and no two visible
/// polygons overlap. (The union by `kepler::clip`, which comes with the `lab` feature.)
#[cfg(feature = "lab")]
#[test]
fn visible_areas_sum_to_the_area_of_the_picture() {
    use kepler::surfaces::visible_surfaces;
    use kepler::views::Picture;
    for seed in 1..=10u64 {
        let scene = random_boxes(0x9e37_79b9 * seed);
        let view = View::orthographic(
            Vector3::new(-1.0, -2.0, -3.0 + 0.1 * seed as f64),
            Vector3::z(),
        )
        .unwrap();
        let picture = Picture::of(&view);
        let faces = visible_surfaces(&scene, &view).unwrap();
        let visible: f64 = faces
            .iter()
            .map(|f| f.visible.polygons.unsigned_area())
            .sum();
        let mut union = MultiPolygon::new(Vec::new());
        for &id in scene.roots() {
            let mesh = scene[id].mesh().unwrap();
            for f in 0..mesh.faces().len() {
                let ring: Vec<[f64; 2]> = mesh.face_points(f).map(|v| picture.point(&v)).collect();
                union = kepler::clip::union(&union, &kepler_face(&ring)).unwrap();
            }
        }
        let total = union.unsigned_area();
        assert!(
            (visible - total).abs() <= 1e-9 * total,
            "seed {seed}: visible {visible} against the picture's {total}"
        );
        let pieces: Vec<&MultiPolygon<f64>> = faces
            .iter()
            .map(|f| &f.visible.polygons)
            .filter(|p| !p.0.is_empty())
            .collect();
        for i in 0..pieces.len() {
            for j in i + 1..pieces.len() {
                let overlap = kepler::clip::intersection(pieces[i], pieces[j])
                    .unwrap()
                    .unsigned_area();
                assert!(
                    overlap <= 1e-12 * total,
                    "seed {seed}: pieces {i} and {j} overlap by {overlap}"
                );
            }
        }
        // The texture polygons are the visible polygons on the face's plane: in an orthographic
        // view, picture areas are texture areas foreshortened by |normal · forward|.
        for f in &faces {
            let face = &scene[f.object].mesh().unwrap().faces()[f.face];
            let cos = face.plane().normal.dot(&view.forward()).abs();
            let (texture, seen) = (
                f.texture.unsigned_area(),
                f.visible.polygons.unsigned_area(),
            );
            assert!(
                (texture * cos - seen).abs() <= 1e-9 * face.area(),
                "seed {seed}: face {} texture area {texture} × {cos} against {seen}",
                f.face
            );
            assert!(texture <= face.area() * (1.0 + 1e-9));
        }
    }
}

/// The hidden-line drawing and the visible polygons agree: every visible piece of a line lies
/// on the boundary of some face's visible polygons, and no hidden piece does.
#[test]
fn hidden_lines_lie_on_visible_polygon_boundaries() {
    use geo::{Distance, Euclidean};
    use kepler::hidden::{EdgeSelection, Options, draw};
    use kepler::surfaces::visible_surfaces;
    let (mut on, mut off) = (0usize, 0usize);
    for seed in 1..=8u64 {
        let scene = random_boxes(0x51ed_270b * seed);
        let view = View::orthographic(
            Vector3::new(0.5, -1.0 - 0.1 * seed as f64, -2.0),
            Vector3::z(),
        )
        .unwrap();
        let drawing = draw(
            &scene,
            &view,
            &Options {
                edges: EdgeSelection::All,
                ..Default::default()
            },
        )
        .unwrap();
        let faces = visible_surfaces(&scene, &view).unwrap();
        let boundaries: Vec<geo::Line<f64>> = faces
            .iter()
            .flat_map(|f| f.visible.polygons.iter())
            .flat_map(|p| std::iter::once(p.exterior()).chain(p.interiors()))
            .flat_map(|r| r.lines())
            .collect();
        let (lo, hi) = drawing.bounds().expect("a drawing");
        let tolerance = 1e-9 * (hi[0] - lo[0]).max(hi[1] - lo[1]);
        for polyline in &drawing.polylines {
            for w in polyline.points.windows(2) {
                let length = (w[1][0] - w[0][0]).hypot(w[1][1] - w[0][1]);
                if length < 1e3 * tolerance {
                    continue;
                }
                for u in [0.25, 0.5, 0.75] {
                    let p = geo::Point::new(
                        w[0][0] + u * (w[1][0] - w[0][0]),
                        w[0][1] + u * (w[1][1] - w[0][1]),
                    );
                    let d = boundaries
                        .iter()
                        .map(|l| Euclidean.distance(l, &p))
                        .fold(f64::INFINITY, f64::min);
                    if polyline.visible {
                        assert!(
                            d <= tolerance,
                            "seed {seed}: visible {:?} at {p:?} is {d} off",
                            polyline.class
                        );
                        on += 1;
                    } else {
                        assert!(
                            d > tolerance,
                            "seed {seed}: hidden {:?} at {p:?} is on a boundary",
                            polyline.class
                        );
                        off += 1;
                    }
                }
            }
        }
    }
    assert!(on > 500 && off > 200, "{on} {off}");
}

/// The city block (Franklin's motivating scene) from its camera: the ground hides nothing of
/// the buildings standing on it (their walls only touch its plane), the buildings hide part of
/// the ground, a tower hides all of its own back windows, and INBOXes hide faces at once.
#[test]
fn the_city_block() {
    use kepler::surfaces::{visible_surfaces, visobj};
    let scene = kepler::scene::file::load(std::path::Path::new("scenes/city.toml")).unwrap();
    let view = View::from_camera(scene.camera().unwrap()).unwrap();
    let id = |name: &str| scene.find(name).unwrap();
    assert_eq!(
        visobj(&scene, id("ground"), id("block"), &view).unwrap(),
        Status::Visible
    );
    assert_eq!(
        visobj(&scene, id("block"), id("ground"), &view).unwrap(),
        Status::Mixed
    );
    let back = id("block/tower-west/back-windows");
    assert_eq!(
        visobj(&scene, id("block"), back, &view).unwrap(),
        Status::Hidden
    );
    assert_eq!(
        visobj(&scene, id("ground"), back, &view).unwrap(),
        Status::Visible
    );
    let faces = visible_surfaces(&scene, &view).unwrap();
    let inbox: u64 = faces.iter().map(|f| f.visible.exits.inbox_hid).sum();
    assert!(inbox > 100, "INBOXes hid {inbox} faces at once");
    // Every face of the tower's back windows is hidden in the whole-scene pass too.
    assert!(
        faces
            .iter()
            .filter(|f| scene
                .path(f.object)
                .starts_with("block/tower-west/back-windows"))
            .all(|f| f.visible.status == Status::Hidden || f.visible.edge_on)
    );
}

/// The whole-scene pass decides faces in an order near in space, not face order: its reports
/// still come object by object, face by face, each the answer of VISFAC against the whole
/// scene for that face alone, on a mesh whose faces are listed in a shuffled order.
#[test]
fn whole_scene_reports_come_in_face_order() {
    use kepler::surfaces::{visfac_scene, visible_surfaces};
    let mut scene = random_boxes(11);
    let sphere = solids::uv_sphere(1.2, 16, 9).unwrap();
    let mut faces = sphere.polygons();
    let mut rng = SplitMix64(3);
    for k in (1..faces.len()).rev() {
        faces.swap(k, (rng.next_u64() % (k as u64 + 1)) as usize);
    }
    let shuffled = Mesh::from_polygons(sphere.vertices().to_vec(), faces).unwrap();
    scene.add_mesh(None, "shuffled", shuffled).unwrap();
    let view = View::orthographic(Vector3::new(-1.0, -2.0, -3.0), Vector3::z()).unwrap();
    let reports = visible_surfaces(&scene, &view).unwrap();
    let expected: Vec<(ObjectId, usize)> = scene
        .roots()
        .iter()
        .flat_map(|&id| (0..scene[id].mesh().unwrap().faces().len()).map(move |f| (id, f)))
        .collect();
    let got: Vec<(ObjectId, usize)> = reports.iter().map(|r| (r.object, r.face)).collect();
    assert_eq!(got, expected);
    for r in &reports {
        let alone = visfac_scene(&scene, &view, r.object, r.face).unwrap();
        assert_eq!(r.visible.status, alone.status);
        assert_eq!(r.visible.polygons, alone.polygons);
    }
    assert!(reports.iter().any(|r| r.visible.status == Status::Mixed));
}
