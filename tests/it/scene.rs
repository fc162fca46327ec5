//! The scene graph: Franklin's rule (subobjects or a mesh, never both), the bounds of groups
//! against independent references, instancing, the placement transform, flattening, the
//! depth-first walk, paths, and the invalidation of cached bounds.

use kepler::bounds::tribox::TriboxBounds;
use kepler::bounds::{Aabb, InboxMethod};
use kepler::geometry::{Point3, Vector3};
use kepler::mesh::Mesh;
use kepler::scene::{Content, ObjectId, Scene, Transform};
use kepler::solids::{self, Polyhedron};
use nalgebra::Matrix4;

// ---------------------------------------------------------------------------------------------
// Helpers.

fn place(scale: [f64; 3], rotate: [f64; 3], translate: [f64; 3]) -> Transform {
    Transform {
        scale,
        rotate,
        translate,
    }
}

fn moved(translate: [f64; 3]) -> Transform {
    Transform {
        translate,
        ..Transform::default()
    }
}

fn cube(edge: f64) -> Mesh {
    solids::cube(edge).unwrap()
}

fn cuboid(x: f64, y: f64, z: f64) -> Mesh {
    solids::cuboid(Vector3::new(x, y, z)).unwrap()
}

/// A box with its faces but one: open, so it bounds no solid.
fn open_box() -> Mesh {
    let c = cube(1.0);
    let faces = c.faces()[1..]
        .iter()
        .map(|f| f.vertices().to_vec())
        .collect();
    let m = Mesh::from_polygons(c.vertices().to_vec(), faces).unwrap();
    assert!(!m.is_solid());
    m
}

fn mesh_of(scene: &Scene, id: ObjectId) -> &Mesh {
    scene[id].mesh().expect("a mesh object")
}

fn assert_rel(actual: f64, expected: f64, tol: f64) {
    assert!(
        (actual - expected).abs() <= tol * expected.abs(),
        "{actual} differs from {expected} by more than {tol} relative"
    );
}

fn aabb(min: [f64; 3], max: [f64; 3]) -> Aabb {
    Aabb::new(Point3::from(min), Point3::from(max))
}

fn names(scene: &Scene, ids: &[ObjectId]) -> Vec<String> {
    ids.iter().map(|&i| scene[i].name().to_string()).collect()
}

/// Coordinates as bit patterns (with -0 taken as +0), for exact set comparisons.
fn key(p: &Point3) -> [u64; 3] {
    [p.x + 0.0, p.y + 0.0, p.z + 0.0].map(f64::to_bits)
}

// ---------------------------------------------------------------------------------------------
// Franklin's rule.

#[test]
fn a_mesh_object_cannot_take_subobjects() {
    let mut s = Scene::new();
    let city = s.add_group(None, "city").unwrap();
    let tower = s.add_mesh(Some(city), "tower", cube(1.0)).unwrap();

    let expected = "object 'tower': it has faces, so it cannot also have subobjects";
    let e = s.add_group(Some(tower), "floor").unwrap_err();
    assert_eq!(e.to_string(), expected);
    let e = s.add_mesh(Some(tower), "window", cube(0.1)).unwrap_err();
    assert_eq!(e.to_string(), expected);
    let e = s
        .instantiate(tower, Some(tower), "copy", &Transform::default())
        .unwrap_err();
    assert_eq!(e.to_string(), expected);

    // Nothing was added anywhere.
    assert_eq!(s.walk(), vec![(city, 0), (tower, 1)]);
    assert!(matches!(s[tower].content(), Content::Mesh(_)));
    assert!(s[tower].subobjects().is_empty());
    assert_eq!(s.face_count(city), 6);
}

#[test]
fn a_group_holds_only_subobjects() {
    let mut s = Scene::new();
    let g = s.add_group(None, "g").unwrap();
    let a = s.add_mesh(Some(g), "a", cube(1.0)).unwrap();
    let h = s.add_group(Some(g), "h").unwrap();
    assert!(s[g].mesh().is_none());
    assert!(matches!(s[g].content(), Content::Subobjects(v) if v == &[a, h]));
    assert_eq!(s[a].parent(), Some(g));
    assert_eq!(s[g].parent(), None);
    assert_eq!(s.roots(), &[g]);
}

// ---------------------------------------------------------------------------------------------
// Bounds of groups.

/// A group "g" of: a 1×2×4 box at (10, −5, 0), a cube of edge 2 at (−3, 0, 7), and a
/// subgroup "sub" holding a unit cube at (0, 0, −20).
fn three_children() -> (Scene, ObjectId, ObjectId) {
    let mut s = Scene::new();
    let g = s.add_group(None, "g").unwrap();
    let a = s.add_mesh(None, "a-src", cuboid(1.0, 2.0, 4.0)).unwrap();
    s.instantiate(a, Some(g), "a", &moved([10.0, -5.0, 0.0]))
        .unwrap();
    let b = s.add_mesh(None, "b-src", cube(2.0)).unwrap();
    s.instantiate(b, Some(g), "b", &moved([-3.0, 0.0, 7.0]))
        .unwrap();
    let sub = s.add_group(Some(g), "sub").unwrap();
    let c = s.add_mesh(None, "c-src", cube(1.0)).unwrap();
    s.instantiate(c, Some(sub), "c", &moved([0.0, 0.0, -20.0]))
        .unwrap();
    (s, g, sub)
}

#[test]
fn group_cbox_is_the_union_of_its_children() {
    let (s, g, sub) = three_children();
    // By hand: a spans [9.5, 10.5] × [−6, −4] × [−2, 2], b [−4, −2] × [−1, 1] × [6, 8],
    // c [−0.5, 0.5]² × [−20.5, −19.5].
    assert_eq!(s.cbox(g), aabb([-4.0, -6.0, -20.5], [10.5, 1.0, 8.0]));
    assert_eq!(s.cbox(sub), aabb([-0.5, -0.5, -20.5], [0.5, 0.5, -19.5]));
    // And against the box of all the subtree's vertices.
    let all: Vec<Point3> = s
        .meshes(g)
        .iter()
        .flat_map(|m| m.vertices().iter().copied())
        .collect();
    assert_eq!(all.len(), 24);
    assert_eq!(s.cbox(g), Aabb::from_points(&all));
    // An empty group has an empty CBOX.
    let mut s = Scene::new();
    let e = s.add_group(None, "empty").unwrap();
    assert!(s.cbox(e).is_empty());
}

#[test]
fn group_inbox_is_the_largest_child_inbox() {
    let mut s = Scene::new();
    let g = s.add_group(None, "g").unwrap();
    s.add_mesh(Some(g), "small", cube(1.0)).unwrap();
    let big_src = s.add_mesh(None, "big-src", cube(3.0)).unwrap();
    let big = s
        .instantiate(big_src, Some(g), "big", &moved([10.0, 0.0, 0.0]))
        .unwrap();
    let sub = s.add_group(Some(g), "sub").unwrap();
    let mid_src = s.add_mesh(None, "mid-src", cube(2.0)).unwrap();
    let mid = s
        .instantiate(mid_src, Some(sub), "mid", &moved([0.0, 10.0, 0.0]))
        .unwrap();
    s.add_mesh(Some(sub), "open", open_box()).unwrap();

    // A cube's inbox is the cube itself.
    let big_box = aabb([8.5, -1.5, -1.5], [11.5, 1.5, 1.5]);
    assert_eq!(s.inbox(big).unwrap().aabb, big_box);
    assert_eq!(
        s.inbox(mid).unwrap().aabb,
        aabb([-1.0, 9.0, -1.0], [1.0, 11.0, 1.0])
    );

    let gi = s.inbox(g).unwrap();
    assert_eq!(gi.aabb, big_box);
    assert_eq!(gi.method, InboxMethod::Subobject);
    // The subgroup: the open box has no inbox, so its cube's.
    let si = s.inbox(sub).unwrap();
    assert_eq!(si.aabb, aabb([-1.0, 9.0, -1.0], [1.0, 11.0, 1.0]));
    assert_eq!(si.method, InboxMethod::Subobject);

    // No interior anywhere: no inbox.
    let mut s = Scene::new();
    let g = s.add_group(None, "g").unwrap();
    let o = s.add_mesh(Some(g), "open", open_box()).unwrap();
    assert!(s.inbox(o).is_none());
    assert!(s.inbox(g).is_none());
    let e = s.add_group(None, "empty").unwrap();
    assert!(s.inbox(e).is_none());
}

#[test]
fn group_tribox_is_the_tribox_of_all_subtree_vertices() {
    // Coordinates whose diagonal sums round in f64.
    let mut s = Scene::new();
    let g = s.add_group(None, "g").unwrap();
    let ico = s
        .add_mesh(None, "ico", Polyhedron::Icosahedron.mesh(1.0).unwrap())
        .unwrap();
    s.instantiate(
        ico,
        Some(g),
        "ico",
        &place([1.0; 3], [30.0, 45.0, 10.0], [0.1, 0.7, -0.3]),
    )
    .unwrap();
    let sph = s
        .add_mesh(None, "sph", solids::uv_sphere(0.7, 7, 5).unwrap())
        .unwrap();
    s.instantiate(sph, Some(g), "sph", &moved([2.3, -1.1, 0.9]))
        .unwrap();
    let sub = s.add_group(Some(g), "sub").unwrap();
    let dod = s
        .add_mesh(None, "dod", Polyhedron::Dodecahedron.mesh(0.3).unwrap())
        .unwrap();
    s.instantiate(
        dod,
        Some(sub),
        "dod",
        &place([1.1, 0.9, 1.3], [-20.0, 5.0, 77.0], [-1.7, 0.2, 3.3]),
    )
    .unwrap();
    s.add_mesh(Some(sub), "open", open_box()).unwrap();

    for id in [g, sub] {
        let all: Vec<Point3> = s
            .meshes(id)
            .iter()
            .flat_map(|m| m.vertices().iter().copied())
            .collect();
        assert_eq!(
            s.tribox(id),
            TriboxBounds::from_points(&all),
            "{}",
            s.path(id)
        );
    }
    // The unit cube, exactly: min then max along x, y, z, x+y, x+z, y+z, x−z, y−x, z−y.
    let c = s.add_mesh(None, "unit", cube(1.0)).unwrap();
    assert_eq!(
        s.tribox(c).to_array18(),
        [
            -0.5, 0.5, -0.5, 0.5, -0.5, 0.5, -1.0, 1.0, -1.0, 1.0, -1.0, 1.0, -1.0, 1.0, -1.0, 1.0,
            -1.0, 1.0
        ]
    );
    let e = s.add_group(None, "empty").unwrap();
    assert!(s.tribox(e).is_empty());
}

#[test]
fn group_counts_volume_and_area_sum_over_the_subtree() {
    let (s, g, sub) = three_children();
    assert_eq!(s.face_count(g), 18);
    assert_eq!(s.vertex_count(g), 24);
    assert_eq!(s.face_count(sub), 6);
    assert!(s.is_solid(g));
    // 8 + 8 + 1, areas 28 + 24 + 6.
    assert_eq!(s.volume(g), Some(17.0));
    assert_eq!(s.surface_area(g), 58.0);

    let mut s = Scene::new();
    let g = s.add_group(None, "g").unwrap();
    s.add_mesh(Some(g), "cube", cube(1.0)).unwrap();
    s.add_mesh(Some(g), "open", open_box()).unwrap();
    assert!(!s.is_solid(g));
    assert_eq!(s.volume(g), None);
    let e = s.add_group(None, "empty").unwrap();
    assert!(!s.is_solid(e));
    assert_eq!(s.volume(e), None);
}

// ---------------------------------------------------------------------------------------------
// Instancing.

/// A chiral, convex source with irrational coordinates: the snub cube.
fn snub() -> Mesh {
    Polyhedron::SnubCube.mesh(1.0).unwrap()
}

fn transforms() -> Vec<(&'static str, Transform)> {
    vec![
        ("translate", moved([1.5, -2.0, 3.25])),
        ("rotate", place([1.0; 3], [30.0, -45.0, 60.0], [0.0; 3])),
        ("scale", place([2.0, 0.5, 3.0], [0.0; 3], [0.0; 3])),
        ("mirror-x", place([-1.0, 1.0, 1.0], [0.0; 3], [0.0; 3])),
        ("mirror-y", place([1.0, -2.0, 1.0], [0.0; 3], [0.0; 3])),
        ("point-reflection", place([-1.0; 3], [0.0; 3], [0.0; 3])),
        (
            "everything",
            place([-2.0, 3.0, 0.5], [10.0, 20.0, 30.0], [-7.0, 0.1, 4.0]),
        ),
    ]
}

#[test]
fn instance_vertices_are_the_matrix_applied_once() {
    for (what, t) in transforms() {
        let mut s = Scene::new();
        let src = s.add_mesh(None, "src", snub()).unwrap();
        let b = s.instantiate(src, None, "b", &t).unwrap();
        let m = t.matrix();
        let (from, to) = (mesh_of(&s, src), mesh_of(&s, b));
        assert_eq!(to.vertices().len(), from.vertices().len(), "{what}");
        // A rotation can leave polygons not exactly planar: split, they are still polygons.
        assert_eq!(to.polygons().len(), from.polygons().len(), "{what}");
        for (i, (p, q)) in from.vertices().iter().zip(to.vertices()).enumerate() {
            assert_eq!(*q, m.transform_point(p), "{what}: vertex {i}");
        }
        // The same through instantiate_matrix.
        let c = s.instantiate_matrix(src, None, "c".into(), &m).unwrap();
        assert_eq!(mesh_of(&s, c), mesh_of(&s, b), "{what}");
        // The source is untouched.
        assert_eq!(mesh_of(&s, src), &snub());
    }
}

#[test]
fn mirrored_instances_still_point_outward() {
    let source = snub();
    let v0 = source.volume();
    assert!(v0 > 0.0);
    for (what, t) in transforms() {
        let mut s = Scene::new();
        let src = s.add_mesh(None, "src", source.clone()).unwrap();
        let b = s.instantiate(src, None, "b", &t).unwrap();
        let det = t.scale.iter().product::<f64>();
        let mesh = mesh_of(&s, b);
        assert!(mesh.is_solid(), "{what}");
        assert!(mesh.volume() > 0.0, "{what}: volume {}", mesh.volume());
        assert_rel(mesh.volume(), det.abs() * v0, 1e-12);
        assert_rel(s.volume(b).unwrap(), det.abs() * v0, 1e-12);
        // Convex: every vertex is behind (or on) every face's outward plane; the centroid
        // strictly behind.
        let n = mesh.vertices().len() as f64;
        let centroid = Point3::from(
            mesh.vertices()
                .iter()
                .fold(Vector3::zeros(), |a, p| a + p.coords)
                / n,
        );
        let size = s.cbox(b).size().iter().fold(0.0f64, |a, &b| a.max(b));
        for (fi, f) in mesh.faces().iter().enumerate() {
            assert!(
                f.plane().evaluate(&centroid) < -1e-3 * size,
                "{what}: face {fi} points inward"
            );
            for p in mesh.vertices() {
                assert!(f.plane().evaluate(p) <= 1e-12 * size, "{what}: face {fi}");
            }
        }
    }
}

#[test]
fn mirroring_reverses_each_face() {
    let mut s = Scene::new();
    let src = s.add_mesh(None, "src", cuboid(1.0, 2.0, 4.0)).unwrap();
    let b = s
        .instantiate(src, None, "b", &place([-1.0, 1.0, 1.0], [0.0; 3], [0.0; 3]))
        .unwrap();
    let (from, to) = (mesh_of(&s, src), mesh_of(&s, b));
    for (f, g) in from.faces().iter().zip(to.faces()) {
        // Same vertex cycle, run backwards (up to the starting vertex).
        let mut back: Vec<u32> = f.vertices().to_vec();
        back.reverse();
        let n = back.len();
        let rotations: Vec<Vec<u32>> = (0..n)
            .map(|k| (0..n).map(|i| back[(i + k) % n]).collect())
            .collect();
        assert!(rotations.contains(&g.vertices().to_vec()), "{f:?} vs {g:?}");
    }
}

#[test]
fn instancing_copies_whole_subtrees_with_names() {
    let mut s = Scene::new();
    let house = s.add_group(None, "house").unwrap();
    let walls = s
        .add_mesh(Some(house), "walls", cuboid(4.0, 3.0, 2.0))
        .unwrap();
    let roof = s.add_group(Some(house), "roof").unwrap();
    let tile = s
        .add_mesh(
            Some(roof),
            "tile",
            Polyhedron::Octahedron.mesh(0.5).unwrap(),
        )
        .unwrap();
    let t = place([1.0, 2.0, 0.5], [0.0, 0.0, 33.0], [100.0, 0.1, -3.0]);
    let copy = s.instantiate(house, None, "house-2", &t).unwrap();

    assert_eq!(s.roots(), &[house, copy]);
    assert_eq!(s[copy].name(), "house-2");
    assert_eq!(s[copy].instance_of(), Some("house"));
    assert_eq!(s[house].instance_of(), None);
    let kids = s[copy].subobjects().to_vec();
    assert_eq!(names(&s, &kids), ["walls", "roof"]);
    assert!(!kids.contains(&walls) && !kids.contains(&roof));
    assert_eq!(s[kids[0]].instance_of(), Some("walls"));
    assert_eq!(s[kids[1]].instance_of(), Some("roof"));
    assert_eq!(s[kids[0]].parent(), Some(copy));
    let grandkids = s[kids[1]].subobjects().to_vec();
    assert_eq!(names(&s, &grandkids), ["tile"]);
    assert_eq!(s[grandkids[0]].instance_of(), Some("tile"));
    assert_eq!(s.path(grandkids[0]), "house-2/roof/tile");
    // The source keeps its own children.
    assert_eq!(s[house].subobjects(), &[walls, roof]);
    assert_eq!(s[roof].subobjects(), &[tile]);

    // Each vertex transformed once, at every depth.
    let m = t.matrix();
    for (src, dst) in [(walls, kids[0]), (tile, grandkids[0])] {
        let (from, to) = (mesh_of(&s, src), mesh_of(&s, dst));
        assert_eq!(from.vertices().len(), to.vertices().len());
        for (p, q) in from.vertices().iter().zip(to.vertices()) {
            assert_eq!(*q, m.transform_point(p));
        }
    }
    assert_eq!(s.face_count(copy), 6 + 8);

    // An instance of an instance: the second matrix applied to the first copy's vertices.
    let t2 = place([1.0; 3], [90.0, 0.0, 0.0], [0.0, 0.0, 50.0]);
    let copy2 = s.instantiate(copy, None, "house-3", &t2).unwrap();
    assert_eq!(s[copy2].instance_of(), Some("house-2"));
    let tile3 = s.find("house-3/roof/tile").unwrap();
    assert_eq!(s[tile3].instance_of(), Some("tile"));
    let m2 = t2.matrix();
    for (p, q) in mesh_of(&s, grandkids[0])
        .vertices()
        .iter()
        .zip(mesh_of(&s, tile3).vertices())
    {
        assert_eq!(*q, m2.transform_point(p));
    }
}

#[test]
fn instancing_a_group_into_itself_copies_its_children_once() {
    let mut s = Scene::new();
    let g = s.add_group(None, "g").unwrap();
    let a = s.add_mesh(Some(g), "a", cube(1.0)).unwrap();
    let copy = s
        .instantiate(g, Some(g), "copy", &moved([2.0, 0.0, 0.0]))
        .unwrap();
    assert_eq!(s[g].subobjects(), &[a, copy]);
    assert_eq!(names(&s, s[copy].subobjects()), ["a"]);
    assert_eq!(s.face_count(g), 12);
    assert_eq!(s.cbox(g), aabb([-0.5; 3], [2.5, 0.5, 0.5]));
}

#[test]
fn a_singular_instance_transform_is_an_error_naming_the_object() {
    let mut s = Scene::new();
    let a = s.add_mesh(None, "a", cube(1.0)).unwrap();
    let flat = place([1.0, 0.0, 1.0], [0.0; 3], [0.0; 3]);
    let e = s.instantiate(a, None, "squashed", &flat).unwrap_err();
    assert_eq!(
        e.to_string(),
        "object 'squashed': the transform is singular or not finite"
    );
    let e = s
        .instantiate(a, None, "nan", &moved([f64::NAN, 0.0, 0.0]))
        .unwrap_err();
    assert!(e.to_string().starts_with("object 'nan': "), "{e}");
    assert_eq!(s.walk().len(), 1);
}

#[test]
fn a_failed_group_instance_leaves_the_scene_unchanged() {
    let mut s = Scene::new();
    let g = s.add_group(None, "g").unwrap();
    s.add_mesh(Some(g), "a", cube(1.0)).unwrap();
    let flat = place([1.0, 0.0, 1.0], [0.0; 3], [0.0; 3]);
    let e = s.instantiate(g, None, "squashed", &flat).unwrap_err();
    assert!(e.to_string().contains("singular"), "{e}");
    // The error must not leave a half-built copy behind.
    assert_eq!(s.roots(), &[g], "a partial copy was left in the scene");
    assert_eq!(s.walk().len(), 2);
}

// ---------------------------------------------------------------------------------------------
// The placement transform.

/// Rotation of (x, y, z) by `deg` (a multiple of 90) about `axis`, by hand: the two other
/// coordinates (a, b), in right-handed order, go to (−b, a) per quarter turn.
fn quarter_turn(p: [f64; 3], axis: usize, deg: i32) -> [f64; 3] {
    let (i, j) = [(1, 2), (2, 0), (0, 1)][axis];
    let mut q = p;
    for _ in 0..(deg / 90).rem_euclid(4) {
        let (a, b) = (q[i], q[j]);
        q[i] = -b;
        q[j] = a;
    }
    q
}

#[test]
fn quarter_turns_are_exact() {
    for axis in 0..3 {
        for deg in [90, 180, 270, -90, -180, -270, 360, 450] {
            let mut rotate = [0.0; 3];
            rotate[axis] = f64::from(deg);
            let t = Transform {
                rotate,
                ..Transform::default()
            };
            let mut s = Scene::new();
            let src = s.add_mesh(None, "src", cuboid(1.0, 2.0, 4.0)).unwrap();
            let b = s.instantiate(src, None, "b", &t).unwrap();
            for (p, q) in mesh_of(&s, src)
                .vertices()
                .iter()
                .zip(mesh_of(&s, b).vertices())
            {
                let want = quarter_turn([p.x, p.y, p.z], axis, deg);
                assert_eq!([q.x, q.y, q.z], want, "axis {axis}, {deg}°");
            }
            // The matrix itself holds only 0 and ±1.
            let m = t.matrix();
            assert!(m.iter().all(|&x| x == 0.0 || x.abs() == 1.0), "{m}");
            // Still an axis-aligned box with the sizes permuted.
            let half = quarter_turn([0.5, 1.0, 2.0], axis, deg).map(f64::abs);
            assert_eq!(
                s.cbox(b),
                aabb(half.map(|h| -h), half),
                "axis {axis}, {deg}°"
            );
        }
    }
}

#[test]
fn quarter_turn_matrices_by_hand() {
    let rz = Transform {
        rotate: [0.0, 0.0, 90.0],
        ..Transform::default()
    };
    #[rustfmt::skip]
    let want = Matrix4::new(
        0.0, -1.0, 0.0, 0.0,
        1.0, 0.0, 0.0, 0.0,
        0.0, 0.0, 1.0, 0.0,
        0.0, 0.0, 0.0, 1.0,
    );
    assert_eq!(rz.matrix(), want);
    let rx = Transform {
        rotate: [-90.0, 0.0, 0.0],
        ..Transform::default()
    };
    #[rustfmt::skip]
    let want = Matrix4::new(
        1.0, 0.0, 0.0, 0.0,
        0.0, 0.0, 1.0, 0.0,
        0.0, -1.0, 0.0, 0.0,
        0.0, 0.0, 0.0, 1.0,
    );
    assert_eq!(rx.matrix(), want);
}

#[test]
fn composition_order_is_scale_then_rotate_x_y_z_then_translate() {
    let t = place([2.0, 3.0, 4.0], [90.0, 90.0, 90.0], [10.0, 20.0, 30.0]);
    // By hand, for (1, 1, 1): scale (2, 3, 4); about x by 90°: (x, −z, y) = (2, −4, 3);
    // about y: (z, y, −x) = (3, −4, −2); about z: (−y, x, z) = (4, 3, −2); translate
    // (14, 23, 28). (Rotating z, y, x instead would give (14, 17, 32).)
    let p = t.matrix().transform_point(&Point3::new(1.0, 1.0, 1.0));
    assert_eq!(p, Point3::new(14.0, 23.0, 28.0));
    // The whole matrix: columns are the images of the axes, then the translation.
    #[rustfmt::skip]
    let want = Matrix4::new(
        0.0, 0.0, 4.0, 10.0,
        0.0, 3.0, 0.0, 20.0,
        -2.0, 0.0, 0.0, 30.0,
        0.0, 0.0, 0.0, 1.0,
    );
    assert_eq!(t.matrix(), want);

    // A general angle: (1, 0, 0) about z by 30° is (cos 30°, sin 30°, 0).
    let t = Transform {
        rotate: [0.0, 0.0, 30.0],
        ..Transform::default()
    };
    let p = t.matrix().transform_point(&Point3::new(1.0, 0.0, 0.0));
    assert!((p.x - 3f64.sqrt() / 2.0).abs() < 1e-15 && (p.y - 0.5).abs() < 1e-15 && p.z == 0.0);
}

#[test]
fn the_default_transform_is_the_identity() {
    let t = Transform::default();
    assert!(t.is_identity());
    assert_eq!(t.matrix(), Matrix4::identity());
    assert!(!moved([0.0, 0.0, 1.0]).is_identity());
    let mut s = Scene::new();
    let a = s.add_mesh(None, "a", snub()).unwrap();
    let b = s.instantiate(a, None, "b", &t).unwrap();
    assert_eq!(mesh_of(&s, a), mesh_of(&s, b));
}

// ---------------------------------------------------------------------------------------------
// Flattening.

fn assert_no_duplicate_vertices(m: &Mesh) {
    let mut keys: Vec<[u64; 3]> = m.vertices().iter().map(key).collect();
    keys.sort_unstable();
    let n = keys.len();
    keys.dedup();
    assert_eq!(keys.len(), n, "duplicate vertex coordinates");
}

#[test]
fn flattening_two_cubes_sharing_a_face_merges_four_vertices() {
    let mut s = Scene::new();
    let g = s.add_group(None, "pair").unwrap();
    let a = s.add_mesh(Some(g), "a", cube(1.0)).unwrap();
    s.instantiate(a, Some(g), "b", &moved([1.0, 0.0, 0.0]))
        .unwrap();
    assert_eq!(s.vertex_count(g), 16);
    let flat = s.flatten(g).unwrap();
    assert_eq!(flat.vertices().len(), 12);
    assert_eq!(flat.faces().len(), 12);
    assert_eq!(flat.merged_vertices(), 4);
    assert_no_duplicate_vertices(&flat);
    assert_rel(flat.volume(), 2.0, 1e-12);
}

#[test]
fn flattening_a_2x2x2_block_of_cubes_merges_to_27_vertices() {
    let mut s = Scene::new();
    let g = s.add_group(None, "block").unwrap();
    let unit = s.add_mesh(None, "unit", cube(1.0)).unwrap();
    for k in 0..8 {
        let t = moved([f64::from(k & 1), f64::from((k >> 1) & 1), f64::from(k >> 2)]);
        s.instantiate(unit, Some(g), format!("c{k}"), &t).unwrap();
    }
    assert_eq!(s.vertex_count(g), 64);
    assert_eq!(s.face_count(g), 48);
    let flat = s.flatten(g).unwrap();
    assert_eq!(flat.vertices().len(), 27);
    assert_eq!(flat.faces().len(), 48);
    assert_no_duplicate_vertices(&flat);
    // The vertices are exactly the grid {−0.5, 0.5, 1.5}³.
    let mut got: Vec<[u64; 3]> = flat.vertices().iter().map(key).collect();
    let mut want: Vec<[u64; 3]> = (0..27)
        .map(|i| {
            let c = |d: i32| f64::from(d) - 0.5;
            key(&Point3::new(c(i % 3), c(i / 3 % 3), c(i / 9)))
        })
        .collect();
    got.sort_unstable();
    want.sort_unstable();
    assert_eq!(got, want);
    assert_rel(flat.volume(), 8.0, 1e-12);
    assert_eq!(s.volume(g), Some(8.0));

    // The result is a leaf: it goes into a scene as a mesh object.
    let mut t = Scene::new();
    let f = t.add_mesh(None, "flat", flat).unwrap();
    assert!(t[f].subobjects().is_empty());
    assert_eq!(t.walk(), vec![(f, 0)]);
}

#[test]
fn flattening_keeps_every_face_and_the_volume() {
    let mut s = Scene::new();
    let g = s.add_group(None, "g").unwrap();
    let sub = s.add_group(Some(g), "sub").unwrap();
    let deeper = s.add_group(Some(sub), "deeper").unwrap();
    let mut x = 10.0;
    for (i, p) in Polyhedron::ALL.iter().enumerate() {
        let src = s.add_mesh(None, p.name(), p.mesh(1.0).unwrap()).unwrap();
        let parent = [g, sub, deeper][i % 3];
        let t = place(
            [1.0, 1.5, 0.75],
            [10.0 * i as f64, 7.0, -3.0],
            [x, 0.3, -0.1],
        );
        s.instantiate(src, Some(parent), format!("p{i}"), &t)
            .unwrap();
        x += 10.0;
    }
    s.add_mesh(Some(deeper), "ball", solids::uv_sphere(1.0, 12, 6).unwrap())
        .unwrap();
    let flat = s.flatten(g).unwrap();
    assert_eq!(flat.faces().len(), s.face_count(g));
    // Polygons that rounding left not exactly planar are split into triangle faces.
    assert_eq!(flat.polygons().len(), 502 + 72);
    // The solids are apart: no vertex is shared.
    assert_eq!(flat.vertices().len(), s.vertex_count(g));
    assert_no_duplicate_vertices(&flat);
    assert_rel(flat.volume(), s.volume(g).unwrap(), 1e-12);
    assert_rel(flat.surface_area(), s.surface_area(g), 1e-12);
    assert!(flat.is_solid());
}

#[test]
fn flattening_a_single_mesh_gives_the_same_mesh() {
    let mut s = Scene::new();
    for mesh in [
        cube(1.0),
        snub(),
        solids::uv_sphere(1.0, 9, 5).unwrap(),
        open_box(),
    ] {
        let id = s.add_mesh(None, "m", mesh.clone()).unwrap();
        assert_eq!(s.flatten(id).unwrap(), mesh);
        // A group around it changes nothing either.
        let g = s.add_group(None, "g").unwrap();
        s.instantiate(id, Some(g), "m", &Transform::default())
            .unwrap();
        assert_eq!(s.flatten(g).unwrap(), mesh);
    }
}

// ---------------------------------------------------------------------------------------------
// Walk, paths, names.

/// a ─┬─ a1 ── x
///    └─ a2
/// b ─── a2
fn small_tree() -> (Scene, [ObjectId; 6]) {
    let mut s = Scene::new();
    let a = s.add_group(None, "a").unwrap();
    let a1 = s.add_group(Some(a), "a1").unwrap();
    let x = s.add_mesh(Some(a1), "x", cube(1.0)).unwrap();
    let a2 = s.add_mesh(Some(a), "a2", snub()).unwrap();
    let b = s.add_group(None, "b").unwrap();
    let b2 = s.add_mesh(Some(b), "a2", cube(2.0)).unwrap();
    (s, [a, a1, x, a2, b, b2])
}

#[test]
fn walk_is_depth_first_with_depths() {
    let (s, [a, a1, x, a2, b, b2]) = small_tree();
    assert_eq!(
        s.walk(),
        vec![(a, 0), (a1, 1), (x, 2), (a2, 1), (b, 0), (b2, 1)]
    );
    assert_eq!(s.roots(), &[a, b]);
    let meshes = s.meshes(a);
    assert_eq!(meshes.len(), 2);
    assert_eq!(meshes[0], mesh_of(&s, x));
    assert_eq!(meshes[1], mesh_of(&s, a2));
    assert_eq!(s.meshes(x), vec![mesh_of(&s, x)]);
    assert_eq!(s.face_count(a), 6 + 38);
    assert_eq!(s.vertex_count(a), 8 + 24);
}

#[test]
fn paths_and_find_by_name_and_by_path() {
    let (s, [a, a1, x, a2, b, b2]) = small_tree();
    assert_eq!(s.path(a), "a");
    assert_eq!(s.path(x), "a/a1/x");
    assert_eq!(s.path(b2), "b/a2");
    assert_eq!(s.find("a/a1/x"), Some(x));
    assert_eq!(s.find("x"), Some(x));
    assert_eq!(s.find("a1"), Some(a1));
    assert_eq!(s.find("b"), Some(b));
    // A name used twice: the first depth-first, unless the path says which.
    assert_eq!(s.find("a2"), Some(a2));
    assert_eq!(s.find("a/a2"), Some(a2));
    assert_eq!(s.find("b/a2"), Some(b2));
    assert_eq!(s.find("nope"), None);
    assert_eq!(s.find("a1/x"), None);
    assert_eq!(s.find(""), None);
    assert_eq!(s.get(x).map(|o| o.name()), Some("x"));
}

// ---------------------------------------------------------------------------------------------
// Cached bounds.

#[test]
fn adding_a_child_invalidates_the_cached_bounds_of_all_ancestors() {
    let mut s = Scene::new();
    let top = s.add_group(None, "top").unwrap();
    let mid = s.add_group(Some(top), "mid").unwrap();
    s.add_mesh(Some(mid), "a", cube(1.0)).unwrap();
    let small = aabb([-0.5; 3], [0.5; 3]);
    assert_eq!(s.cbox(top), small);
    assert_eq!(s.cbox(mid), small);
    assert_eq!(s.inbox(top).unwrap().aabb, small);
    let t0 = s.tribox(top);

    // A larger cube far away, under the middle group.
    let src = s.add_mesh(None, "src", cube(4.0)).unwrap();
    s.instantiate(src, Some(mid), "far", &moved([10.0, 0.0, 0.0]))
        .unwrap();
    let far = aabb([8.0, -2.0, -2.0], [12.0, 2.0, 2.0]);
    let both = aabb([-0.5, -2.0, -2.0], [12.0, 2.0, 2.0]);
    assert_eq!(s.cbox(mid), both);
    assert_eq!(s.cbox(top), both);
    assert_eq!(s.inbox(top).unwrap().aabb, far);
    assert_eq!(s.inbox(mid).unwrap().aabb, far);
    assert_ne!(s.tribox(top), t0);
    assert_eq!(s.tribox(top).max()[0], 12.0);
    assert_eq!(s.face_count(top), 12);

    // add_mesh and add_group too.
    s.add_mesh(Some(top), "low", cuboid(1.0, 1.0, 2.0)).unwrap();
    assert_eq!(s.cbox(top).min, [-0.5, -2.0, -2.0]);
    let g = s.add_group(Some(mid), "deep").unwrap();
    s.add_mesh(Some(g), "high", cuboid(1.0, 1.0, 50.0)).unwrap();
    assert_eq!(s.cbox(top), aabb([-0.5, -2.0, -25.0], [12.0, 2.0, 25.0]));
    assert_eq!(s.cbox(mid), aabb([-0.5, -2.0, -25.0], [12.0, 2.0, 25.0]));
    assert_eq!(s.tribox(top).max()[2], 25.0);
}
