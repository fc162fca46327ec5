//! The lab's stiff scenes (issue 15): every family at its quick parameters and three seeds
//! generates, draws with visible and hidden lines (and intersection lines where its solids
//! pierce each other) and passes `hidden::verify`; each is as stiff as its parameter says;
//! seeds give different scenes, the same seed the same one; `write` and `scene::file::load`
//! round-trip to the same meshes, camera and drawing.

use kepler::geometry::{Point3, Vector3};
use kepler::hidden::verify::{Traced, draw_traced, verify};
use kepler::hidden::{EdgeClass, EdgeSelection, Options, draw};
use kepler::lab::stiff::{Family, StiffError, StiffScene, generate, write};
use kepler::mesh::Mesh;
use kepler::scene::{Scene, file};
use kepler::views::View;
use std::cmp::Ordering;

const SEEDS: [u64; 3] = [0, 1, 2];

/// Every edge: a wireframe with its hidden parts.
fn options() -> Options {
    Options {
        edges: EdgeSelection::All,
        ..Options::default()
    }
}

fn scene(family: Family, k: i32, seed: u64) -> StiffScene {
    generate(family, k, seed).unwrap_or_else(|e| panic!("{family} k={k} seed={seed}: {e}"))
}

fn traced(s: &StiffScene) -> Traced {
    draw_traced(&s.scene, &s.view, &options(), &|_, _| {})
        .unwrap_or_else(|e| panic!("{}: {e}", s.name()))
}

/// The meshes by name, in order.
fn meshes(scene: &Scene) -> Vec<(String, Mesh)> {
    scene
        .mesh_objects(scene.roots())
        .into_iter()
        .map(|(id, m)| (scene[id].name().to_string(), m.clone()))
        .collect()
}

fn mesh<'a>(s: &'a StiffScene, name: &str) -> &'a Mesh {
    let id = s
        .scene
        .find(name)
        .unwrap_or_else(|| panic!("{}: no {name}", s.name()));
    s.scene[id].mesh().expect("a mesh object")
}

/// Whether the solids of the scene must pierce each other: everywhere but where they only
/// touch (the touching family, and the tilt's exactly coplanar end).
fn pierces(s: &StiffScene) -> bool {
    !(s.family == Family::Touching || s.family == Family::Tilt && s.parameter == 16)
}

/// Where `verify` is known to be wrong: the scale family beyond 2^200 (see
/// `verify_checks_intersection_lines_of_scenes_of_extreme_scale`).
fn verify_overflows(s: &StiffScene) -> bool {
    s.family == Family::Scale && s.parameter > 200
}

#[test]
fn every_family_draws_and_verifies_at_its_quick_parameters_and_three_seeds() {
    for family in Family::ALL {
        for k in family.parameters(true) {
            for seed in SEEDS {
                let s = scene(family, k, seed);
                let name = s.name();
                for (object, m) in meshes(&s.scene) {
                    // Built exactly: every quad planar, nothing degenerate or merged.
                    let repairs = (
                        m.split_polygons(),
                        m.degenerate_faces(),
                        m.merged_vertices(),
                    );
                    assert_eq!(repairs, (0, 0, 0), "{name}: {object}");
                    assert!(m.topology().closed || object == "cone", "{name}: {object}");
                }
                let drawn =
                    draw(&s.scene, &s.view, &options()).unwrap_or_else(|e| panic!("{name}: {e}"));
                let t = traced(&s);
                assert_eq!(t.drawing.polylines, drawn.polylines, "{name}");
                let lines = &drawn.polylines;
                assert!(lines.iter().any(|l| l.visible), "{name}: nothing visible");
                assert!(lines.iter().any(|l| !l.visible), "{name}: nothing hidden");
                let meets = lines.iter().any(|l| l.class == EdgeClass::Intersection);
                assert!(meets || !pierces(&s), "{name}: no intersection line");
                let report = verify(&s.scene, &s.view, &options(), &t);
                assert!(report.checks() > 0, "{name}: nothing checked");
                if verify_overflows(&s) {
                    // The drawing is still right: the unscaled scene's, piece by piece.
                    let unscaled = traced(&scene(family, 0, seed));
                    let key = |t: &Traced| -> Vec<_> {
                        t.pieces.iter().map(|p| (p.t, p.visible, p.class)).collect()
                    };
                    assert_eq!(key(&t), key(&unscaled), "{name}");
                } else {
                    assert_eq!(report.disagreements, 0, "{name}:\n{report}");
                }
            }
        }
    }
}

/// The scale family at 2^±280, also seen along an axis: `verify` once sampled intersection
/// lines at the input's scale instead of in the working range the drawing is made in, and
/// found pieces visible in the unscaled scene (and drawn visible, rightly) hidden; it now
/// checks in the working range.
#[test]
fn verify_checks_intersection_lines_of_scenes_of_extreme_scale() {
    let down = View::orthographic(Vector3::new(0.0, 0.0, -1.0), Vector3::y()).unwrap();
    for seed in [0, 1] {
        let s = scene(Family::Scale, 280, seed);
        let report = verify(&s.scene, &s.view, &options(), &traced(&s));
        assert_eq!(report.disagreements, 0, "{}:\n{report}", s.name());
        let s = scene(Family::Scale, -280, seed);
        let t = draw_traced(&s.scene, &down, &options(), &|_, _| {}).unwrap();
        let report = verify(&s.scene, &down, &options(), &t);
        assert_eq!(
            report.disagreements,
            0,
            "{}, from above:\n{report}",
            s.name()
        );
    }
}

#[test]
fn the_parameters_are_in_range_and_outside_it_is_an_error() {
    for family in Family::ALL {
        let quick = family.parameters(true);
        let full = family.parameters(false);
        assert_eq!(quick.len(), 3, "{family}");
        assert!((6..=10).contains(&full.len()), "{family}");
        let range = family.range();
        for k in quick.iter().chain(&full) {
            assert!(range.contains(k), "{family}: {k}");
        }
        assert!(full.windows(2).all(|w| w[0] < w[1]), "{family}");
        assert_eq!(full[0], *range.start(), "{family}");
        // The report's fan stops one short of the largest fan `gen` makes (2^12 triangles
        // take 13 s to draw).
        let last = if family == Family::Fan {
            range.end() - 1
        } else {
            *range.end()
        };
        assert_eq!(full.last(), Some(&last), "{family}");
        assert_eq!(Family::from_name(family.name()), Some(family));
        let past = range.end() + 1;
        assert!(matches!(
            generate(family, past, 0),
            Err(StiffError::Parameter { parameter, .. }) if parameter == past
        ));
    }
    assert_eq!(Family::from_name("Tilt"), None);
}

#[test]
fn seeds_give_different_scenes_and_the_same_seed_the_same_one() {
    for family in Family::ALL {
        let k = family.parameters(true)[1];
        let scenes: Vec<_> = SEEDS.iter().map(|&seed| scene(family, k, seed)).collect();
        for (i, a) in scenes.iter().enumerate() {
            for b in &scenes[i + 1..] {
                assert_ne!(
                    meshes(&a.scene),
                    meshes(&b.scene),
                    "{} {}",
                    a.name(),
                    b.name()
                );
            }
            let again = scene(family, k, a.seed);
            assert_eq!(meshes(&a.scene), meshes(&again.scene), "{}", a.name());
            assert_eq!(a.view, again.view, "{}", a.name());
        }
    }
}

/// Each family's stiffness is what its parameter says, exactly.
#[test]
fn each_family_is_as_stiff_as_it_says() {
    let near = |x: f64, k: i32| (0.25..=4.0).contains(&(x / 10f64.powi(k)));
    for seed in SEEDS {
        // Tilt: the plate's top is 10^-k (times its half width, 1 or 2) off the base's top
        // at its ends; at k = 16 it is in it.
        for k in Family::Tilt.range() {
            let s = scene(Family::Tilt, k, seed);
            let top = bounds(mesh(&s, "base")).1.z;
            let off = mesh(&s, "plate")
                .vertices()
                .iter()
                .map(|p| (p.z - top).abs())
                .filter(|d| *d < 0.5)
                .fold(0.0, f64::max);
            assert!(
                if k == 16 { off == 0.0 } else { near(off, -k) },
                "{k}: {off}"
            );
        }
        // Sliver: the needle's sides have an aspect of about 10^k.
        for k in Family::Sliver.range() {
            let s = scene(Family::Sliver, k, seed);
            let lengths = edge_lengths(mesh(&s, "needle"));
            let aspect = lengths.iter().fold(0.0, |m: f64, l| m.max(*l))
                / lengths.iter().fold(f64::MAX, |m, l| m.min(*l));
            assert!(near(aspect, k), "{k}: {aspect}");
        }
        // Offset: every coordinate is 10^k (or −10^k) plus a multiple of 1/8 (of 2 at k = 16).
        for k in Family::Offset.range() {
            let s = scene(Family::Offset, k, seed);
            let origin = bounds(mesh(&s, "block")).0;
            let unit = if k == 16 { 2.0 } else { 0.125 };
            assert_eq!(
                origin.map(f64::abs),
                Point3::new(1.0, 1.0, 1.0) * 10f64.powi(k)
            );
            for (_, m) in meshes(&s.scene) {
                for p in m.vertices() {
                    for i in 0..3 {
                        let steps = (p[i] - origin[i]) / unit;
                        assert!(steps == steps.round() && steps.abs() < 128.0, "{k}: {p}");
                    }
                }
            }
        }
        // Edge-on: the prism has four faces edge-on, the slab two, the tilted slab none.
        for k in Family::EdgeOn.parameters(false) {
            let s = scene(Family::EdgeOn, k, seed);
            let edge_on = |name: &str| {
                let m = mesh(&s, name);
                (0..m.faces().len())
                    .filter(|&f| {
                        let t = m.triangle(m.faces()[f].triangle_range().start);
                        s.view.eye().orient3d(&t[0], &t[1], &t[2]) == Ordering::Equal
                    })
                    .count()
            };
            assert_eq!(
                [edge_on("prism"), edge_on("slab"), edge_on("tilted")],
                [4, 2, 0]
            );
        }
        // Fan: 2^k triangles meet at the apex.
        for k in Family::Fan.parameters(true) {
            let s = scene(Family::Fan, k, seed);
            let cone = mesh(&s, "cone");
            let top = bounds(cone).1.z;
            let apex = cone.vertices().iter().position(|p| p.z == top).unwrap() as u32;
            let at_apex = cone
                .triangles()
                .iter()
                .filter(|t| t.contains(&apex))
                .count();
            assert_eq!(at_apex, 1 << k);
        }
        // Inside-out: the inverted meshes, and only they, are turned inward.
        let s = scene(Family::InsideOut, 9, seed);
        for (name, m) in meshes(&s.scene) {
            let inward = m.orientation() == Ordering::Less;
            assert_eq!(inward, name.starts_with("inverted"), "{name}");
        }
    }
}

/// The smallest and largest corner of a mesh's vertices.
fn bounds(m: &Mesh) -> (Point3, Point3) {
    let v = m.vertices();
    v.iter()
        .fold((v[0], v[0]), |(lo, hi), p| (lo.inf(p), hi.sup(p)))
}

fn edge_lengths(m: &Mesh) -> Vec<f64> {
    m.triangles()
        .iter()
        .flat_map(|t| {
            let p = t.map(|i| m.vertices()[i as usize]);
            [
                (p[1] - p[0]).norm(),
                (p[2] - p[1]).norm(),
                (p[0] - p[2]).norm(),
            ]
        })
        .collect()
}

#[test]
fn write_and_load_round_trip_to_the_same_scene_and_drawing() {
    let dir = std::env::temp_dir().join(format!("kepler-stiff-{}", std::process::id()));
    for family in Family::ALL {
        let quick = family.parameters(true);
        for (k, seed) in [(quick[0], 1), (quick[2], 2)] {
            let s = scene(family, k, seed);
            let path = write(&s, &dir).unwrap();
            let loaded = file::load(&path).unwrap_or_else(|e| panic!("{}: {e}", s.name()));
            assert_eq!(meshes(&loaded), meshes(&s.scene), "{}", s.name());
            assert_eq!(loaded.camera(), s.scene.camera(), "{}", s.name());
            let view = View::from_camera(loaded.camera().unwrap()).unwrap();
            assert_eq!(view, s.view, "{}", s.name());
            if matches!(family, Family::Tilt | Family::Scale | Family::EdgeOn) {
                let [a, b] = [&s.scene, &loaded]
                    .map(|scene| draw(scene, &view, &options()).unwrap().polylines);
                assert_eq!(a, b, "{}", s.name());
            }
        }
    }
    std::fs::remove_dir_all(&dir).unwrap();
}
