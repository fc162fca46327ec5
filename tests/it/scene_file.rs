//! The TOML scene file: solids, arrays, defines and instances, placement, mesh files, the
//! camera, every error (file, line and message), and the bundled scenes.

use kepler::bounds::Aabb;
use kepler::geometry::Point3;
use kepler::scene::file::{load, parse};
use kepler::scene::{Camera, ObjectId, Projection, Scene};
use std::path::{Path, PathBuf};

// ---------------------------------------------------------------------------------------------
// Helpers.

fn scene(text: &str) -> Scene {
    parse(text, Path::new("t.toml")).unwrap_or_else(|e| panic!("{e}\n--- in:\n{text}"))
}

/// The error for `text` (named `t.toml`), which must start with `t.toml:LINE: ` and contain
/// `phrase`.
#[track_caller]
fn assert_error(text: &str, line: usize, phrase: &str) -> String {
    assert_error_in("t.toml", text, line, phrase)
}

#[track_caller]
fn assert_error_in(path: &str, text: &str, line: usize, phrase: &str) -> String {
    let e = match parse(text, Path::new(path)) {
        Ok(_) => panic!("no error for:\n{text}"),
        Err(e) => e.to_string(),
    };
    let prefix = format!("{path}:{line}: ");
    assert!(e.starts_with(&prefix), "expected `{prefix}...`, got `{e}`");
    assert!(e.contains(phrase), "expected `{phrase}` in `{e}`");
    e
}

fn root(s: &Scene, name: &str) -> ObjectId {
    s.find(name).unwrap_or_else(|| panic!("no object {name}"))
}

fn aabb(min: [f64; 3], max: [f64; 3]) -> Aabb {
    Aabb::new(Point3::from(min), Point3::from(max))
}

fn names(s: &Scene, ids: &[ObjectId]) -> Vec<String> {
    ids.iter().map(|&i| s[i].name().to_string()).collect()
}

/// The input polygons of an object's meshes: a polygon that rounding left not exactly planar
/// is split into triangle faces, and counts once.
fn polygons(s: &Scene, id: ObjectId) -> usize {
    s.flatten(id).unwrap().polygons().len()
}

/// The input polygons of every object.
fn total_faces(s: &Scene) -> usize {
    s.roots().iter().map(|&r| polygons(s, r)).sum()
}

fn manifest() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

fn assert_rel(actual: f64, expected: f64, tol: f64) {
    assert!(
        (actual - expected).abs() <= tol * expected.abs(),
        "{actual} differs from {expected} by more than {tol} relative"
    );
}

/// The 18 solids with their face counts (Platonic and Archimedean solids, from the
/// literature).
const FACES: [(&str, usize); 18] = [
    ("tetrahedron", 4),
    ("cube", 6),
    ("octahedron", 8),
    ("dodecahedron", 12),
    ("icosahedron", 20),
    ("truncated-tetrahedron", 8),
    ("cuboctahedron", 14),
    ("truncated-cube", 14),
    ("truncated-octahedron", 14),
    ("rhombicuboctahedron", 26),
    ("truncated-cuboctahedron", 26),
    ("snub-cube", 38),
    ("icosidodecahedron", 32),
    ("truncated-dodecahedron", 32),
    ("truncated-icosahedron", 32),
    ("rhombicosidodecahedron", 62),
    ("truncated-icosidodecahedron", 62),
    ("snub-dodecahedron", 92),
];

// ---------------------------------------------------------------------------------------------
// Solids, arrays, defines, placement.

#[test]
fn a_cube_with_edge_2() {
    let s = scene("[[object]]\nname = \"c\"\nsolid = \"cube\"\nedge = 2\n");
    assert_eq!(s.roots().len(), 1);
    let c = s.roots()[0];
    assert_eq!(s[c].name(), "c");
    assert_eq!(s.volume(c), Some(8.0));
    assert_eq!(s.cbox(c), aabb([-1.0; 3], [1.0; 3]));
    assert_eq!((polygons(&s, c), s.vertex_count(c)), (6, 8));
    assert_eq!(s[c].instance_of(), None);
    assert!(s.camera().is_none());
    // `size = 2` says the same.
    let s = scene("[[object]]\nname = \"c\"\nsolid = \"cube\"\nsize = 2\n");
    assert_eq!(s.cbox(s.roots()[0]), aabb([-1.0; 3], [1.0; 3]));
}

#[test]
fn an_array_makes_a_group_of_numbered_copies() {
    let s = scene(
        r#"
[[object]]
name = "row"
solid = "box"
size = [1, 2, 3]
translate = [100, 0, 0]
array = { count = [3, 2, 1], step = [10, 20, 30] }
"#,
    );
    let row = root(&s, "row");
    assert_eq!(s.roots(), &[row]);
    assert!(s[row].mesh().is_none());
    let kids = s[row].subobjects().to_vec();
    assert_eq!(
        names(&s, &kids),
        ["row-1", "row-2", "row-3", "row-4", "row-5", "row-6"]
    );
    // x varies fastest, then y (then z); each copy is the placed box, moved by the step.
    for (k, &id) in kids.iter().enumerate() {
        let (i, j) = ((k % 3) as f64, (k / 3) as f64);
        let want = aabb(
            [99.5 + 10.0 * i, -1.0 + 20.0 * j, -1.5],
            [100.5 + 10.0 * i, 1.0 + 20.0 * j, 1.5],
        );
        assert_eq!(s.cbox(id), want, "{}", s[id].name());
        assert_eq!(s.volume(id), Some(6.0));
        assert!(s[id].mesh().is_some());
    }
    assert_eq!(s.cbox(row), aabb([99.5, -1.0, -1.5], [120.5, 21.0, 1.5]));
    assert_eq!(polygons(&s, row), 36);

    // Along z, and a single copy is still a group.
    let s = scene(
        "[[object]]\nsolid = \"cube\"\narray = { count = [1, 1, 2], step = [0, 0, 5] }\n\
         [[object]]\nname = \"one\"\nsolid = \"cube\"\narray = { count = [1, 1, 1], step = [9, 9, 9] }\n",
    );
    let col = s.roots()[0];
    assert_eq!(s[col].name(), "cube");
    assert_eq!(names(&s, s[col].subobjects()), ["cube-1", "cube-2"]);
    assert_eq!(
        s.cbox(s[col].subobjects()[1]),
        aabb([-0.5, -0.5, 4.5], [0.5, 0.5, 5.5])
    );
    let one = root(&s, "one");
    assert_eq!(names(&s, s[one].subobjects()), ["one-1"]);
    assert_eq!(s.cbox(one), aabb([-0.5; 3], [0.5; 3]));
}

#[test]
fn defines_instances_and_instances_of_instances() {
    let s = scene(
        r#"
[define.pane]
solid = "box"
size = [1, 0.5, 2]

[define.window]
[[define.window.object]]
name = "glass"
instance = "pane"
translate = [0, 0, 1]
[[define.window.object]]
name = "sill"
solid = "box"
size = [1.5, 1, 0.25]

[define.big-window]
instance = "window"
scale = 2

[[object]]
name = "w1"
instance = "window"
translate = [10, 0, 0]

[[object]]
name = "w2"
instance = "big-window"
translate = [0, 10, 0]

[[object]]
instance = "pane"
"#,
    );
    assert_eq!(names(&s, s.roots()), ["w1", "w2", "pane"]);
    // A define is not placed by itself.
    assert_eq!(s.walk().len(), 3 + 2 + 2);

    let w1 = root(&s, "w1");
    assert_eq!(s[w1].instance_of(), Some("window"));
    let kids = s[w1].subobjects().to_vec();
    assert_eq!(names(&s, &kids), ["glass", "sill"]);
    assert_eq!(s[kids[0]].instance_of(), Some("pane"));
    assert_eq!(s[kids[1]].instance_of(), None);
    assert_eq!(s.cbox(kids[0]), aabb([9.5, -0.25, 0.0], [10.5, 0.25, 2.0]));
    assert_eq!(
        s.cbox(kids[1]),
        aabb([9.25, -0.5, -0.125], [10.75, 0.5, 0.125])
    );

    // The instance of an instance: the window scaled by 2, then moved.
    let w2 = root(&s, "w2");
    assert_eq!(s[w2].instance_of(), Some("big-window"));
    let kids = s[w2].subobjects().to_vec();
    assert_eq!(names(&s, &kids), ["glass", "sill"]);
    assert_eq!(s[kids[0]].instance_of(), Some("pane"));
    assert_eq!(s.cbox(kids[0]), aabb([-1.0, 9.5, 0.0], [1.0, 10.5, 4.0]));
    assert_eq!(s.cbox(kids[1]), aabb([-1.5, 9.0, -0.25], [1.5, 11.0, 0.25]));
    assert_eq!(s.volume(w2), Some(8.0 * (1.0 + 0.375)));
    assert_eq!(s.path(kids[1]), "w2/sill");

    // Without a name, an instance is named after its define.
    let p = root(&s, "pane");
    assert_eq!(s[p].instance_of(), Some("pane"));
    assert_eq!(s.cbox(p), aabb([-0.5, -0.25, -1.0], [0.5, 0.25, 1.0]));
}

#[test]
fn placement_composes_with_the_enclosing_objects() {
    let s = scene(
        r#"
[[object]]
name = "parent"
rotate = [0, 0, 90]
translate = [10, 0, 0]
[[object.object]]
name = "mid"
scale = [1, 1, 2]
translate = [0, 0, 1]
[[object.object.object]]
name = "leaf"
solid = "box"
size = [2, 4, 6]
rotate = [90, 0, 0]
translate = [5, 0, 0]
"#,
    );
    let leaf = root(&s, "parent/mid/leaf");
    assert_eq!(s.walk().iter().map(|w| w.1).collect::<Vec<_>>(), [0, 1, 2]);
    // By hand: the leaf takes (x, y, z) to (x + 5, −z, y), mid that to (x, y, 2z + 1), the
    // parent to (10 − y, x, z): overall (z + 10, x + 5, 2y + 1).
    let local = kepler::solids::cuboid([2.0, 4.0, 6.0].into()).unwrap();
    let world = s[leaf].mesh().unwrap();
    assert_eq!(world.vertices().len(), 8);
    for (p, q) in local.vertices().iter().zip(world.vertices()) {
        assert_eq!(*q, Point3::new(p.z + 10.0, p.x + 5.0, 2.0 * p.y + 1.0));
    }
    assert_eq!(s.cbox(leaf), aabb([7.0, 4.0, -3.0], [13.0, 6.0, 5.0]));
    assert_eq!(s.volume(leaf), Some(96.0));
}

#[test]
fn mirrored_placements_keep_faces_outward() {
    let l = "solid = \"prism\"\noutline = [[0, 0], [2, 0], [2, 1], [1, 1], [1, 2], [0, 2]]\nheight = 2\n";
    let local = scene(&format!("[[object]]\n{l}"));
    let s = scene(&format!(
        "[[object]]\nname = \"m\"\nscale = [-1, 1, 1]\n[[object.object]]\nname = \"l\"\n{l}rotate = [0, 0, 90]\n"
    ));
    let id = root(&s, "m/l");
    let mesh = s[id].mesh().unwrap();
    // A quarter turn about z, (x, y) → (−y, x), then x → −x: overall x and y swap.
    let from = local[local.roots()[0]].mesh().unwrap();
    for (p, q) in from.vertices().iter().zip(mesh.vertices()) {
        assert_eq!(*q, Point3::new(p.y, p.x, p.z));
    }
    assert!(s.is_solid(id));
    assert!(mesh.volume() > 0.0, "turned inside out: {}", mesh.volume());
    assert_rel(mesh.volume(), 6.0, 1e-12);
    assert_eq!(s.cbox(id), aabb([0.0; 3], [2.0; 3]));
    // A uniform negative scale is a point reflection: outward too.
    let s = scene(&format!("[[object]]\nname = \"r\"\n{l}scale = -1\n"));
    let r = root(&s, "r");
    assert!(s[r].mesh().unwrap().volume() > 0.0);
    assert_eq!(s.cbox(r), aabb([-2.0; 3], [0.0; 3]));
}

#[test]
fn an_array_of_instances_records_the_define() {
    let s = scene(
        "[define.pane]\nsolid = \"box\"\nsize = [1, 0.5, 2]\n\
         [[object]]\nname = \"panes\"\ninstance = \"pane\"\narray = { count = [2, 1, 1], step = [3, 0, 0] }\n",
    );
    let panes = root(&s, "panes");
    assert_eq!(s[panes].instance_of(), None);
    let kids = s[panes].subobjects().to_vec();
    assert_eq!(names(&s, &kids), ["panes-1", "panes-2"]);
    for k in kids {
        assert_eq!(s[k].instance_of(), Some("pane"));
    }
}

#[test]
fn every_solid_kind_with_its_defaults_and_parameters() {
    let s = scene(
        r#"
[[object]]
solid = "box"
size = [1, 2, 4]
[[object]]
name = "box-uniform"
solid = "box"
size = 3
[[object]]
solid = "cube"
[[object]]
solid = "prism"
outline = [[0, 0], [2, 0], [2, 1], [1, 1], [1, 2], [0, 2]]
height = 2
[[object]]
name = "prism-cw"
solid = "prism"
outline = [[0, 0], [0, 1], [3, 1], [3, 0]]
height = 0.5
[[object]]
solid = "sphere"
[[object]]
name = "small-sphere"
solid = "uv-sphere"
radius = 2
segments = 8
rings = 4
[[object]]
solid = "torus"
major-radius = 3
minor-radius = 1
[[object]]
name = "small-torus"
solid = "torus"
major-radius = 2
minor-radius = 0.5
segments = 6
sides = 4
[[object]]
solid = "cylinder"
height = 2
[[object]]
name = "square-cylinder"
solid = "cylinder"
radius = 2
height = 3
segments = 4
"#,
    );
    let get = |n: &str| root(&s, n);
    let b = get("box");
    assert_eq!((polygons(&s, b), s.volume(b)), (6, Some(8.0)));
    assert_eq!(s.cbox(b), aabb([-0.5, -1.0, -2.0], [0.5, 1.0, 2.0]));
    assert_eq!(s.cbox(get("box-uniform")), aabb([-1.5; 3], [1.5; 3]));
    let c = get("cube");
    assert_eq!(s.cbox(c), aabb([-0.5; 3], [0.5; 3]));

    let p = get("prism");
    assert_eq!((polygons(&s, p), s.vertex_count(p)), (8, 12));
    assert_eq!(s.cbox(p), aabb([0.0; 3], [2.0; 3]));
    assert_rel(s.volume(p).unwrap(), 6.0, 1e-12);
    let p = get("prism-cw");
    assert!(s.is_solid(p));
    assert_rel(s.volume(p).unwrap(), 1.5, 1e-12);
    assert_eq!(s.cbox(p), aabb([0.0; 3], [3.0, 1.0, 0.5]));

    // Sphere: radius 1, 32 segments, 16 rings by default.
    let sp = get("sphere");
    assert_eq!(
        (polygons(&s, sp), s.vertex_count(sp)),
        (32 * 16, 32 * 15 + 2)
    );
    assert_eq!((s.cbox(sp).min[2], s.cbox(sp).max[2]), (-1.0, 1.0));
    let sp = get("small-sphere");
    assert_eq!((polygons(&s, sp), s.vertex_count(sp)), (32, 26));
    assert_eq!((s.cbox(sp).min[2], s.cbox(sp).max[2]), (-2.0, 2.0));

    // Torus: 48 segments, 24 sides by default.
    let t = get("torus");
    assert_eq!((polygons(&s, t), s.vertex_count(t)), (48 * 24, 48 * 24));
    assert_rel(s.cbox(t).max[0], 4.0, 1e-15);
    let t = get("small-torus");
    assert_eq!((polygons(&s, t), s.vertex_count(t)), (24, 24));
    assert_rel(s.cbox(t).max[0], 2.5, 1e-15);
    assert!(s.is_solid(t));

    // Cylinder: radius 1, 32 segments by default.
    let cy = get("cylinder");
    assert_eq!((polygons(&s, cy), s.vertex_count(cy)), (34, 64));
    assert_eq!((s.cbox(cy).min[2], s.cbox(cy).max[2]), (-1.0, 1.0));
    assert_eq!(s.cbox(cy).max[0], 1.0);
    let cy = get("square-cylinder");
    assert_eq!(polygons(&s, cy), 6);
    // A square of diagonal 4 (area 8), 3 high.
    assert_rel(s.volume(cy).unwrap(), 24.0, 1e-12);
}

#[test]
fn every_polyhedron_by_every_name_form() {
    let mut text = String::new();
    for (name, _) in FACES {
        text += &format!("[[object]]\nsolid = \"{name}\"\nedge = 2\n");
    }
    let s = scene(&text);
    assert_eq!(s.roots().len(), 18);
    for (&id, (name, faces)) in s.roots().iter().zip(FACES) {
        assert_eq!(s[id].name(), name);
        assert_eq!(polygons(&s, id), faces, "{name}");
        assert!(s.is_solid(id), "{name}");
    }
    // Default edge 1; names in words, snake_case, capitals.
    let s = scene(
        r#"
[[object]]
name = "a"
solid = "Truncated Cube"
[[object]]
name = "b"
solid = "truncated_cube"
edge = 2
[[object]]
name = "c"
solid = "TRUNCATED-CUBE"
[[object]]
name = "d"
solid = "snub dodecahedron"
[[object]]
name = "e"
solid = "Icosahedron"
[[object]]
solid = "Snub_Cube"
"#,
    );
    let v1 = (21.0 + 14.0 * 2f64.sqrt()) / 3.0;
    for (n, edge) in [("a", 1.0), ("b", 2.0), ("c", 1.0)] {
        let id = root(&s, n);
        assert_eq!((polygons(&s, id), s.vertex_count(id)), (14, 24), "{n}");
        assert_rel(s.volume(id).unwrap(), v1 * f64::powi(edge, 3), 1e-12);
    }
    assert_eq!(polygons(&s, root(&s, "d")), 92);
    let e = root(&s, "e");
    assert_rel(
        s.volume(e).unwrap(),
        5.0 * (3.0 + 5f64.sqrt()) / 12.0,
        1e-12,
    );
    // Unnamed: named after the solid, in kebab-case.
    let snub = s.roots()[5];
    assert_eq!(s[snub].name(), "snub-cube");
    assert_eq!(polygons(&s, snub), 38);
}

#[test]
fn mesh_files_are_found_relative_to_the_scene_file() {
    let path = manifest().join("tests/data/scenes/meshes.toml");
    let s = load(&path).unwrap();
    assert_eq!(
        names(&s, s.roots()),
        ["cube", "off-cube", "stl-cube", "again"]
    );
    let [obj, off, stl, again] = [0, 1, 2, 3].map(|i| s.roots()[i]);
    assert_eq!((polygons(&s, obj), s.vertex_count(obj)), (6, 8));
    assert_eq!(s.cbox(obj), aabb([0.0; 3], [1.0; 3]));
    assert_eq!(s.volume(obj), Some(1.0));
    assert_eq!(s.cbox(off), aabb([2.0, 0.0, 0.0], [3.0, 1.0, 1.0]));
    assert_eq!(polygons(&s, off), 6);
    assert_eq!(polygons(&s, stl), 12);
    assert_eq!(s.cbox(stl), aabb([0.0, 0.0, 5.0], [2.0, 2.0, 7.0]));
    assert_eq!(s.volume(stl), Some(8.0));
    // The same file placed again, turned a quarter about z: (x, y) → (−y, x).
    assert_eq!(s.cbox(again), aabb([-1.0, 0.0, 0.0], [0.0, 1.0, 1.0]));
    assert!(s.is_solid(again));

    // parse anchors relative paths at the directory of the path it is given.
    let dir = manifest().join("tests/data/scenes");
    let s = parse(
        "[[object]]\nmesh = \"../cube.off\"\n",
        &dir.join("virtual.toml"),
    )
    .unwrap();
    assert_eq!(polygons(&s, s.roots()[0]), 6);

    // A mesh file given directly is a scene of one object named after the file.
    let s = load(&manifest().join("tests/data/cube.off")).unwrap();
    assert_eq!(names(&s, s.roots()), ["cube"]);
    assert_eq!(s.volume(s.roots()[0]), Some(1.0));
}

#[test]
fn camera_variants() {
    let cam = |text: &str| {
        *scene(&format!("{text}\n[[object]]\nsolid = \"cube\"\n"))
            .camera()
            .unwrap()
    };
    assert_eq!(
        cam("[camera]\nview-dir = [-1, -2, -1]"),
        Camera {
            projection: Projection::Orthographic {
                direction: [-1.0, -2.0, -1.0]
            },
            up: [0.0, 0.0, 1.0],
        }
    );
    assert_eq!(
        cam("[camera]\nprojection = \"orthographic\"\nview-dir = [0, 0, -1]\nup = [0, 1, 0]"),
        Camera {
            projection: Projection::Orthographic {
                direction: [0.0, 0.0, -1.0]
            },
            up: [0.0, 1.0, 0.0],
        }
    );
    // Orthographic from an eye and a target: the direction from one to the other.
    assert_eq!(
        cam("[camera]\nprojection = \"orthographic\"\neye = [1, 2, 3]\ntarget = [0, 0, 1]"),
        Camera {
            projection: Projection::Orthographic {
                direction: [-1.0, -2.0, -2.0]
            },
            up: [0.0, 0.0, 1.0],
        }
    );
    assert_eq!(
        cam(
            "[camera]\nprojection = \"perspective\"\neye = [4, -9, 5]\ntarget = [0, 0, 1.5]\nfov = 35"
        ),
        Camera {
            projection: Projection::Perspective {
                eye: [4.0, -9.0, 5.0],
                target: [0.0, 0.0, 1.5],
                fov: 35.0
            },
            up: [0.0, 0.0, 1.0],
        }
    );
    // An eye and a target without a projection: perspective, 40° by default.
    assert_eq!(
        cam("[camera]\neye = [0, -10, 0]\ntarget = [0, 0, 0]\nup = [0, 0, -1]"),
        Camera {
            projection: Projection::Perspective {
                eye: [0.0, -10.0, 0.0],
                target: [0.0; 3],
                fov: 40.0
            },
            up: [0.0, 0.0, -1.0],
        }
    );
    // No camera at all.
    assert!(scene("[[object]]\nsolid = \"cube\"\n").camera().is_none());
}

#[test]
fn an_empty_file_is_an_empty_scene() {
    let s = scene("# nothing\n");
    assert!(s.roots().is_empty());
    assert!(s.camera().is_none());
}

// ---------------------------------------------------------------------------------------------
// Errors: each names the file and the line.

#[test]
fn error_toml_syntax() {
    assert_error(
        "# a scene\n[[object]]\nname = \"a\"\nsolid = \"cube\nedge = 1\n",
        4,
        "string",
    );
    assert_error(
        "[[object]]\nname = \"a\"\nname = \"b\"\n",
        3,
        "duplicate key",
    );
}

#[test]
fn error_unknown_key() {
    let e = assert_error(
        "# a scene\n[[object]]\nname = \"a\"\nsolid = \"cube\"\ncolour = \"red\"\n",
        5,
        "unknown field `colour`",
    );
    // It says what is allowed.
    assert!(e.contains("`translate`"), "{e}");
    assert_error(
        "[[object]]\nsolid = \"cube\"\n[camera]\nview-dir = [0, 0, -1]\nfocal = 3\n",
        5,
        "unknown field `focal`",
    );
    assert_error("title = \"x\"\n", 1, "unknown field `title`");
}

#[test]
fn error_unknown_solid() {
    assert_error(
        "# a scene\n\n[[object]]\nname = \"a\"\nsolid = \"dodecagon\"\n",
        3,
        "unknown solid `dodecagon`",
    );
}

#[test]
fn error_box_without_size() {
    assert_error(
        "[[object]]\nsolid = \"cube\"\n\n[[object]]\nname = \"a\"\nsolid = \"box\"\n",
        4,
        "solid `box` needs `size`",
    );
    assert_error(
        "[[object]]\nsolid = \"torus\"\nmajor-radius = 2\n",
        1,
        "solid `torus` needs `minor-radius`",
    );
    assert_error(
        "[[object]]\nsolid = \"prism\"\noutline = [[0, 0], [1, 0], [0, 1]]\n",
        1,
        "solid `prism` needs `height`",
    );
    assert_error(
        "[[object]]\nsolid = \"cylinder\"\n",
        1,
        "solid `cylinder` needs `height`",
    );
}

#[test]
fn error_parameter_that_does_not_apply() {
    assert_error(
        "[[object]]\nsolid = \"cube\"\n[[object]]\nname = \"a\"\nsolid = \"box\"\nsize = 1\nradius = 2\n",
        3,
        "`radius` does not apply to solid `box`",
    );
    assert_error(
        "[[object]]\nsolid = \"sphere\"\nheight = 2\n",
        1,
        "`height` does not apply to solid `sphere`",
    );
    assert_error(
        "[[object]]\nsolid = \"cube\"\nsize = [1, 2, 3]\n",
        1,
        "solid `cube` takes one number",
    );
    // Solid parameters on a mesh, an instance or a group.
    assert_error(
        "[[object]]\nname = \"g\"\nedge = 2\n[[object.object]]\nsolid = \"cube\"\n",
        1,
        "`edge` applies only to a built-in solid",
    );
}

#[test]
fn error_two_kinds_of_content() {
    assert_error(
        "# x\n[[object]]\nname = \"a\"\nsolid = \"box\"\nsize = 1\nmesh = \"x.obj\"\n",
        2,
        "an object has only one of `solid`, `mesh`, `instance` or subobjects",
    );
    assert_error(
        "[define.d]\nsolid = \"cube\"\n[[object]]\ninstance = \"d\"\n[[object.object]]\nsolid = \"cube\"\n",
        3,
        "an object has only one of",
    );
}

#[test]
fn error_no_content() {
    assert_error(
        "[[object]]\nsolid = \"cube\"\n[[object]]\nname = \"a\"\ntranslate = [1, 2, 3]\n",
        3,
        "an object needs one of `solid`, `mesh`, `instance` or subobjects",
    );
    // In a subobject: its own line.
    assert_error(
        "[[object]]\nname = \"g\"\n[[object.object]]\nsolid = \"cube\"\n[[object.object]]\nname = \"empty\"\n",
        5,
        "an object needs one of",
    );
}

#[test]
fn error_undefined_instance() {
    assert_error(
        "[define.ghosts]\nsolid = \"cube\"\n\n[[object]]\nname = \"a\"\ninstance = \"ghost\"\n",
        4,
        "no `[define.ghost]` for this instance",
    );
}

#[test]
fn error_define_in_terms_of_itself() {
    assert_error(
        "[define.a]\ninstance = \"a\"\n\n[[object]]\nname = \"x\"\ninstance = \"a\"\n",
        1,
        "`a` is defined in terms of itself (a → a)",
    );
    assert_error(
        "[define.a]\ninstance = \"b\"\n[define.b]\ninstance = \"a\"\n\n[[object]]\nname = \"x\"\ninstance = \"a\"\n",
        3,
        "`a` is defined in terms of itself (a → b → a)",
    );
    // Through a subobject of the define.
    assert_error(
        "[define.a]\n[[define.a.object]]\nsolid = \"cube\"\n[[define.a.object]]\ninstance = \"a\"\n\n[[object]]\ninstance = \"a\"\n",
        4,
        "defined in terms of itself",
    );
}

#[test]
fn error_bad_array_count() {
    assert_error(
        "# x\n[[object]]\nsolid = \"cube\"\narray = { count = [3, 0, 1], step = [1, 1, 1] }\n",
        2,
        "array count must give 1 to 1,000,000 copies, got 0",
    );
    assert_error(
        "[[object]]\nsolid = \"cube\"\narray = { count = [1000, 1000, 2], step = [1, 1, 1] }\n",
        1,
        "got 2000000",
    );
    assert_error(
        "[[object]]\nsolid = \"cube\"\n\narray = { count = [-1, 1, 1], step = [1, 1, 1] }\n",
        4,
        "-1",
    );
    assert_error(
        "[[object]]\nsolid = \"cube\"\narray = { count = [2, 1, 1], step = [inf, 0, 0] }\n",
        1,
        "array step must be finite",
    );
}

#[test]
fn error_non_finite_or_zero_scale() {
    for scale in ["nan", "inf", "[1, -inf, 1]"] {
        assert_error(
            &format!("# x\n[[object]]\nsolid = \"cube\"\nscale = {scale}\n"),
            2,
            "scale, rotate and translate must be finite",
        );
    }
    assert_error(
        "[[object]]\nsolid = \"cube\"\ntranslate = [0, nan, 0]\n",
        1,
        "must be finite",
    );
    for scale in ["0", "[1, 0, 1]", "-0.0"] {
        assert_error(
            &format!("# x\n[[object]]\nsolid = \"cube\"\nscale = {scale}\n"),
            2,
            "a scale factor of 0 flattens the object",
        );
    }
}

#[test]
fn error_missing_mesh_file_names_the_mesh() {
    let e = assert_error_in(
        "somewhere/t.toml",
        "[[object]]\nsolid = \"cube\"\n[[object]]\nname = \"m\"\nmesh = \"sub/missing.obj\"\n",
        3,
        "somewhere/sub/missing.obj",
    );
    assert!(e.to_lowercase().contains("no such file"), "{e}");
}

#[test]
fn error_malformed_mesh_file_names_the_mesh_and_its_line() {
    let scene_path = manifest().join("tests/data/scenes/broken_mesh.toml");
    let e = load(&scene_path).unwrap_err().to_string();
    let mesh_path = manifest().join("tests/data/scenes/broken.obj");
    let want = format!(
        "{}:7: {}:7: vertex index 9 is out of range",
        scene_path.display(),
        mesh_path.display()
    );
    assert!(e.starts_with(&want), "expected `{want}...`, got `{e}`");
}

#[test]
fn error_bad_camera() {
    let obj = "\n[[object]]\nsolid = \"cube\"\n";
    let cam = |body: &str| format!("# x\n[camera]\n{body}{obj}");
    assert_error(
        &cam("projection = \"fisheye\"\neye = [0, 0, 5]\ntarget = [0, 0, 0]\n"),
        2,
        "unknown projection `fisheye`",
    );
    assert_error(
        &cam("view-dir = [0, 0, -2]\n"),
        2,
        "the up vector is zero or parallel to the view direction",
    );
    assert_error(
        &cam("eye = [0, 0, 5]\ntarget = [0, 0, 0]\nup = [0, 0, 3]\n"),
        2,
        "parallel to the view direction",
    );
    assert_error(
        &cam("view-dir = [0, 0, 0]\n"),
        2,
        "the view direction is zero",
    );
    assert_error(
        &cam("eye = [1, 1, 1]\ntarget = [1, 1, 1]\n"),
        2,
        "the view direction is zero",
    );
    assert_error(
        &cam("view-dir = [0, 1, 0]\nup = [0, 0, inf]\n"),
        2,
        "camera up must be finite",
    );
    for fov in ["0", "180", "-10", "nan", "400"] {
        assert_error(
            &cam(&format!(
                "eye = [0, -5, 0]\ntarget = [0, 0, 0]\nfov = {fov}\n"
            )),
            2,
            "fov must be between 0 and 180 degrees",
        );
    }
    assert_error(
        &cam("view-dir = [0, 1, 0]\nfov = 30\n"),
        2,
        "fov applies only to a perspective camera",
    );
    assert_error(
        &cam("projection = \"perspective\"\ntarget = [0, 0, 0]\n"),
        2,
        "a perspective camera needs eye and target",
    );
    assert_error(
        &cam("projection = \"perspective\"\nview-dir = [0, 1, 0]\n"),
        2,
        "a perspective camera needs eye and target",
    );
    assert_error(
        &cam(""),
        2,
        "an orthographic camera needs view-dir, or eye and target",
    );
}

#[test]
fn error_solid_parameter_out_of_range() {
    assert_error(
        "# x\n[[object]]\nsolid = \"sphere\"\nsegments = 2\n",
        2,
        "sphere: segments must be at least 3, got 2",
    );
    assert_error(
        "[[object]]\nsolid = \"torus\"\nmajor-radius = 1\nminor-radius = 2\n",
        1,
        "torus: minor radius must be less than the major radius",
    );
    assert_error(
        "[[object]]\nsolid = \"icosahedron\"\nedge = -1\n",
        1,
        "icosahedron: edge must be a finite number greater than 0, got -1",
    );
    assert_error(
        "[[object]]\nsolid = \"prism\"\noutline = [[0, 0], [1, 1], [1, 0], [0, 1]]\nheight = 1\n",
        1,
        "prism: the outline is not simple",
    );
}

#[test]
fn error_in_a_define_names_the_define() {
    assert_error(
        "[[object]]\nname = \"x\"\ninstance = \"d\"\n\n[define.d]\nsolid = \"box\"\n",
        5,
        "solid `box` needs `size`",
    );
    assert_error(
        "[[object]]\nname = \"g\"\n[[object.object]]\nsolid = \"cube\"\n[[object.object]]\nsolid = \"blob\"\n",
        5,
        "unknown solid `blob`",
    );
}

#[test]
fn a_missing_scene_file_is_an_error_naming_it() {
    let path = manifest().join("tests/data/scenes/no-such-scene.toml");
    let e = load(&path).unwrap_err().to_string();
    assert!(e.starts_with(&format!("{}: ", path.display())), "{e}");
}

// ---------------------------------------------------------------------------------------------
// The bundled scenes.

fn bundled(name: &str) -> Scene {
    let path = manifest().join("scenes").join(name);
    load(&path).unwrap_or_else(|e| panic!("{e}"))
}

#[test]
fn every_bundled_scene_loads() {
    let mut found = Vec::new();
    for entry in std::fs::read_dir(manifest().join("scenes")).unwrap() {
        let path = entry.unwrap().path();
        if path.extension().is_some_and(|e| e == "toml") {
            let s = load(&path).unwrap_or_else(|e| panic!("{e}"));
            assert!(total_faces(&s) > 0, "{}", path.display());
            found.push(path.file_name().unwrap().to_string_lossy().into_owned());
        }
    }
    found.sort();
    for want in ["city.toml", "cube.toml", "meshes.toml", "polyhedra.toml"] {
        assert!(found.iter().any(|f| f == want), "{want} missing: {found:?}");
    }
}

#[test]
fn bundled_cube() {
    let s = bundled("cube.toml");
    assert_eq!(total_faces(&s), 6);
    let c = root(&s, "cube");
    assert_eq!(s.volume(c), Some(1.0));
    assert_eq!(s.cbox(c), aabb([-0.5; 3], [0.5; 3]));
}

#[test]
fn bundled_polyhedra() {
    let s = bundled("polyhedra.toml");
    assert_eq!(s.roots().len(), 18);
    for (name, faces) in FACES {
        assert_eq!(polygons(&s, root(&s, name)), faces, "{name}");
    }
    // 4 + 6 + 8 + 12 + 20 + 8 + 14 + 14 + 14 + 26 + 26 + 38 + 32 + 32 + 32 + 62 + 62 + 92.
    assert_eq!(total_faces(&s), 502);
    // Placed on the grid: the cube at (8, 0, 0).
    assert_eq!(
        s.cbox(root(&s, "cube")),
        aabb([7.5, -0.5, -0.5], [8.5, 0.5, 0.5])
    );
}

#[test]
fn bundled_city() {
    let s = bundled("city.toml");
    // A tower: body, 4 × 7 windows front and back, 3 × 7 on each side, 2 + 2 ledges = 103
    // boxes; a shop: body, 4 display windows, a cornice = 6 boxes. Three towers, three shops
    // and the ground: (3 × 103 + 3 × 6 + 1) boxes of 6 faces.
    assert_eq!(total_faces(&s), (3 * 103 + 3 * 6 + 1) * 6);
    assert_eq!(total_faces(&s), 1968);
    let block = root(&s, "block");
    assert_eq!(
        names(&s, s[block].subobjects()),
        ["tower-west", "tower-east", "tower-tall", "shops"]
    );
    let east = root(&s, "block/tower-east");
    assert_eq!(s[east].instance_of(), Some("tower"));
    assert_eq!(polygons(&s, east), 618);
    let shops = root(&s, "block/shops");
    assert_eq!(
        names(&s, s[shops].subobjects()),
        ["shops-1", "shops-2", "shops-3"]
    );
    // The tall tower's body: 10 × 8 × 24 scaled by 1.5 in z, at (0, 12, 0).
    let body = root(&s, "block/tower-tall/body");
    assert_eq!(s.cbox(body), aabb([-5.0, 8.0, 0.0], [5.0, 16.0, 36.0]));
    // The east tower is turned a quarter: its body spans 8 along x and 10 along y.
    let body = root(&s, "block/tower-east/body");
    assert_eq!(s.cbox(body), aabb([14.0, 5.0, 0.0], [22.0, 15.0, 24.0]));
    assert!(matches!(
        s.camera().unwrap().projection,
        Projection::Perspective { fov, .. } if fov == 35.0
    ));
}

#[test]
fn bundled_metropolis() {
    let s = bundled("metropolis.toml");
    let faces = total_faces(&s);
    assert!(faces >= 100_000, "{faces}");
    // Per block: a pavement box and six towers of a body box, 98 window boxes and a
    // truncated-octahedron roof (14 faces).
    assert_eq!(faces, 36 * (6 + 6 * (6 + 98 * 6 + 14)));
    let city = root(&s, "city");
    assert_eq!(s[city].subobjects().len(), 36);
}

#[test]
fn bundled_other_scenes() {
    // The house (7), the open tent (4) and the inside-out cube (6).
    let s = bundled("meshes.toml");
    assert_eq!(total_faces(&s), 17);
    assert_eq!(s.volume(root(&s, "house")), Some(30.0));
    assert!(!s.is_solid(root(&s, "tent")));
    // Prisms of 6 and 10 sides, a 48 × 24 sphere, a 48 × 24 torus, a 40-sided cylinder.
    let s = bundled("solids.toml");
    assert_eq!(total_faces(&s), 8 + 12 + 48 * 24 + 48 * 24 + 42);
    // A 64-sided cylinder and the bunny's 3674 triangles.
    let s = bundled("bunny.toml");
    assert_eq!(total_faces(&s), 66 + 3674);
}

#[test]
fn error_in_a_define_nothing_instances() {
    assert_error(
        "[[object]]\nsolid = \"cube\"\n\n[define.typo]\nsolid = \"blob\"\n",
        4,
        "unknown solid `blob`",
    );
}

#[test]
fn error_nested_arrays_beyond_the_object_limit() {
    let text = "[define.row]\nsolid = \"cube\"\narray = { count = [100, 100, 1], step = [2, 2, 0] }\n\n\
                [[object]]\ninstance = \"row\"\narray = { count = [1000, 1, 1], step = [0, 0, 2] }\n";
    assert_error(text, 5, "would place more than 10000000 objects");
}

#[test]
fn error_camera_with_view_dir_and_eye() {
    let text = "[camera]\nview-dir = [0, 0, -1]\neye = [0, 0, 5]\ntarget = [0, 0, 0]\n";
    assert_error(text, 1, "either view-dir or eye and target, not both");
}
