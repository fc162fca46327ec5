//! The crowded cases of issue 16, whose speed changed how the pass finds its pairs: many
//! edges through one point (fans, cones, the poles of UV spheres), arrays of many separate
//! objects, and exact copies stacked in one place. Each drawing passes `hidden::verify`
//! (VISP at points of every piece, independently of the pass), and copies draw exactly what
//! one of them draws.

use kepler::geometry::Vector3;
use kepler::hidden::verify::{draw_traced, verify};
use kepler::hidden::{EdgeSelection, Options, draw};
use kepler::mesh::Mesh;
use kepler::scene::{Scene, Transform};
use kepler::solids;
use kepler::views::View;
use nalgebra::{Matrix4, Rotation3};

fn passes(name: &str, scene: &Scene, view: &View, options: &Options) -> usize {
    let traced = draw_traced(scene, view, options, &|_, _| {}).expect("the scene draws");
    let report = verify(scene, view, options, &traced);
    assert_eq!(report.disagreements, 0, "{name}:\n{report}");
    assert!(report.checks() > 0, "{name}: nothing checked");
    report.checks()
}

fn views() -> Vec<View> {
    vec![
        View::orthographic(Vector3::new(-1.0, -1.0, -1.0), Vector3::z()).unwrap(),
        View::orthographic(Vector3::new(0.3, -1.0, 0.05), Vector3::z()).unwrap(),
        View::perspective(
            [3.0, -4.0, 2.0].into(),
            [0.0, 0.0, 0.0].into(),
            Vector3::z(),
            40.0,
        )
        .unwrap(),
    ]
}

fn placed(mesh: &Mesh, m: Matrix4<f64>) -> Mesh {
    mesh.transformed(&m).unwrap()
}

#[test]
fn fans_of_many_slivers_draw_correctly() {
    for segments in [150, 700] {
        // Two cones base to base, and a cone piercing the first one's side near its apex.
        let fan = solids::uv_sphere(1.0, segments, 2).unwrap();
        let mut scene = Scene::new();
        scene.add_mesh(None, "fan", fan.clone()).unwrap();
        let turned = Rotation3::from_euler_angles(0.4, 0.3, 0.0).to_homogeneous();
        let other = placed(
            &fan,
            Matrix4::new_translation(&Vector3::new(0.2, 0.1, 0.6)) * turned,
        );
        scene.add_mesh(None, "other", other).unwrap();
        // Also head-on, down the first fan's axis, and just off it: the points asked about lie
        // all round the apexes' pictures (found by angle round them, see `hidden/hubs.rs`).
        let mut all_views = views();
        all_views.push(View::orthographic(Vector3::new(0.0, 0.0, -1.0), Vector3::y()).unwrap());
        all_views.push(View::orthographic(Vector3::new(1e-3, -2e-3, -1.0), Vector3::y()).unwrap());
        for (k, view) in all_views.iter().enumerate() {
            for edges in [EdgeSelection::Feature, EdgeSelection::All] {
                let options = Options {
                    edges,
                    ..Options::default()
                };
                passes(&format!("fan {segments}, view {k}"), &scene, view, &options);
            }
        }
    }
}

#[test]
fn an_array_of_cubes_draws_correctly() {
    let mut scene = Scene::new();
    let group = scene.add_group(None, "array").unwrap();
    let cube = solids::cube(1.0).unwrap();
    for i in 0..12 {
        for j in 0..12 {
            // Some touching, some apart, one row sunk into its neighbours.
            let at = Vector3::new(
                1.0 * i as f64,
                1.5 * j as f64,
                if j == 3 { 0.5 } else { 0.0 },
            );
            let m = placed(&cube, Matrix4::new_translation(&at));
            scene.add_mesh(Some(group), format!("c{i}-{j}"), m).unwrap();
        }
    }
    for (k, view) in views().iter().enumerate() {
        passes(
            &format!("array, view {k}"),
            &scene,
            view,
            &Options::default(),
        );
    }
}

#[test]
fn copies_in_one_place_draw_what_one_draws() {
    let cube = solids::cube(1.0).unwrap();
    let sphere = solids::uv_sphere(0.7, 16, 8).unwrap();
    let shifted = placed(
        &sphere,
        Matrix4::new_translation(&Vector3::new(0.4, 0.3, 0.2)),
    );
    let mut one = Scene::new();
    one.add_mesh(None, "cube", cube.clone()).unwrap();
    one.add_mesh(None, "sphere", shifted.clone()).unwrap();
    let mut many = Scene::new();
    for k in 0..5 {
        many.add_mesh(None, format!("cube{k}"), cube.clone())
            .unwrap();
        many.add_mesh(None, format!("sphere{k}"), shifted.clone())
            .unwrap();
    }
    // A copy placed by a transform that moves nothing is a copy too.
    let id = many.add_mesh(None, "cube-again", cube.clone()).unwrap();
    many.instantiate(id, None, "identity", &Transform::default())
        .unwrap();
    for (k, view) in views().iter().enumerate() {
        let options = Options::default();
        let a = draw(&one, view, &options).unwrap();
        let b = draw(&many, view, &options).unwrap();
        assert_eq!(a.polylines, b.polylines, "view {k}");
        passes(&format!("copies, view {k}"), &many, view, &options);
    }
    // A copy moved by the smallest step is not a copy: both are drawn.
    let mut two = Scene::new();
    two.add_mesh(None, "cube", cube.clone()).unwrap();
    let nudged = placed(
        &cube,
        Matrix4::new_translation(&Vector3::new(0.0, 0.0, 1e-9)),
    );
    two.add_mesh(None, "nudged", nudged).unwrap();
    let view = &views()[0];
    let mut lone = Scene::new();
    lone.add_mesh(None, "cube", cube).unwrap();
    let single = draw(&lone, view, &Options::default()).unwrap();
    let both = draw(&two, view, &Options::default()).unwrap();
    assert!(both.polylines.len() > single.polylines.len());
    passes("nudged copy", &two, view, &Options::default());
}
