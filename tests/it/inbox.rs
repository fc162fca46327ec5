//! INBOX: it must never poke out of its object, and should be as large as is practical.

use kepler::bounds::{InboxMethod, cbox, inbox};
use kepler::geometry::exact::ldexp;
use kepler::geometry::predicates::triangle_meets_open_box;
use kepler::geometry::{Aabb, Point3, Vector3};
use kepler::mesh::{Containment, Mesh, classify_point_brute_force};
use kepler::scene::Scene;
use kepler::solids::{self, Polyhedron};
use nalgebra::{Matrix4, Rotation3};
use proptest::prelude::*;

/// The exact certificate: every corner of the box is inside or on the object, the centre is
/// strictly inside, and no triangle of the object meets the box's open interior.
fn assert_inside(mesh: &Mesh, b: &Aabb, what: &str) {
    // Each side, not the volume, which underflows for tiny boxes.
    assert!((0..3).all(|k| b.min[k] < b.max[k]), "{what}: empty inbox");
    for c in b.corners() {
        let at = classify_point_brute_force(mesh, &c);
        assert_ne!(at, Containment::Outside, "{what}: corner {c:?} is outside");
    }
    let centre = nalgebra::center(&b.min_point(), &b.max_point());
    assert_eq!(
        classify_point_brute_force(mesh, &centre),
        Containment::Inside,
        "{what}: centre"
    );
    for t in 0..mesh.triangles().len() {
        assert!(
            !triangle_meets_open_box(&mesh.triangle(t), b),
            "{what}: triangle {t} crosses the inbox"
        );
    }
}

#[test]
fn every_built_in_solid_has_an_inbox_inside_it() {
    let outline =
        |pts: &[(f64, f64)]| geo::Polygon::new(geo::LineString::from(pts.to_vec()), vec![]);
    let mut meshes: Vec<(String, Mesh)> = Polyhedron::ALL
        .iter()
        .map(|p| (p.name().to_string(), p.mesh(1.3).unwrap()))
        .collect();
    meshes.push(("sphere".into(), solids::uv_sphere(2.0, 24, 12).unwrap()));
    meshes.push(("torus".into(), solids::torus(3.0, 1.0, 24, 12).unwrap()));
    meshes.push(("cylinder".into(), solids::cylinder(1.0, 5.0, 20).unwrap()));
    meshes.push((
        "box".into(),
        solids::cuboid(Vector3::new(1.0, 2.0, 3.0)).unwrap(),
    ));
    let l = outline(&[(0., 0.), (6., 0.), (6., 1.), (1., 1.), (1., 4.), (0., 4.)]);
    meshes.push(("l-prism".into(), solids::prism(&l, 3.0).unwrap()));
    let star: Vec<(f64, f64)> = (0..10)
        .map(|i| {
            let (r, a) = (
                if i % 2 == 0 { 3.0 } else { 1.2 },
                std::f64::consts::TAU * i as f64 / 10.0,
            );
            (r * a.cos(), r * a.sin())
        })
        .collect();
    meshes.push((
        "star-prism".into(),
        solids::prism(&outline(&star), 1.5).unwrap(),
    ));
    for (name, m) in &meshes {
        let i = inbox(m).unwrap_or_else(|| panic!("{name} has no inbox"));
        assert_inside(m, &i.aabb, name);
        assert!(
            i.aabb.volume() >= 0.02 * m.volume(),
            "{name}: inbox only {}",
            i.aabb.volume() / m.volume()
        );
    }
}

#[test]
fn a_box_is_its_own_inbox_exactly() {
    let cube = solids::cube(1.0).unwrap();
    assert_eq!(inbox(&cube).unwrap().aabb, cbox(&cube));
    // Also off the origin, with coordinates whose sums are not representable.
    let t = Matrix4::new_translation(&Vector3::new(0.1, 0.7, -1e-3));
    let b = solids::cuboid(Vector3::new(0.3, 1.7, 2.9))
        .unwrap()
        .transformed(&t)
        .unwrap();
    assert_eq!(inbox(&b).unwrap().aabb, cbox(&b));
}

#[test]
fn the_house_inbox_is_its_walls() {
    let house = kepler::io::read_mesh("scenes/meshes/house.obj".as_ref()).unwrap();
    let i = inbox(&house).unwrap();
    assert_eq!((i.aabb.min, i.aabb.max), ([0.0; 3], [4.0, 3.0, 2.0]));
}

#[test]
fn a_sphere_inbox_nearly_fills_the_inscribed_cube() {
    for (segments, rings) in [(32, 16), (64, 32)] {
        let r = 1.7;
        let s = solids::uv_sphere(r, segments, rings).unwrap();
        let i = inbox(&s).unwrap();
        assert_eq!(i.method, InboxMethod::Kernel);
        let inscribed_cube = (2.0 * r / 3f64.sqrt()).powi(3);
        assert!(
            i.aabb.volume() >= 0.95 * inscribed_cube,
            "{segments}x{rings}: {}",
            i.aabb.volume() / inscribed_cube
        );
        assert_inside(&s, &i.aabb, "sphere");
    }
}

#[test]
fn the_l_prism_inbox_fills_an_arm() {
    let l = geo::Polygon::new(
        geo::LineString::from(vec![
            (0., 0.),
            (6., 0.),
            (6., 1.),
            (1., 1.),
            (1., 4.),
            (0., 4.),
        ]),
        vec![],
    );
    let m = solids::prism(&l, 3.0).unwrap();
    let i = inbox(&m).unwrap();
    // The arms are 6 x 1 x 3 and 1 x 4 x 3; growth must reach at least the smaller one.
    assert!(i.aabb.volume() >= 12.0 - 1e-9, "{:?}", i.aabb);
}

#[test]
fn objects_without_interior_have_no_inbox() {
    let tent = kepler::io::read_mesh("scenes/meshes/tent.stl".as_ref()).unwrap();
    assert!(inbox(&tent).is_none());
    let square = Mesh::from_polygons(
        vec![
            Point3::new(0., 0., 0.),
            Point3::new(1., 0., 0.),
            Point3::new(1., 1., 0.),
            Point3::new(0., 1., 0.),
        ],
        vec![vec![0, 1, 2, 3], vec![0, 3, 2, 1]],
    )
    .unwrap();
    // Closed and consistently oriented, but flat: no interior.
    assert!(square.is_solid());
    assert!(inbox(&square).is_none());
}

#[test]
fn an_inside_out_solid_still_gets_a_correct_inbox() {
    let m = kepler::io::read_mesh("scenes/meshes/inside_out.off".as_ref()).unwrap();
    assert!(m.volume() < 0.0);
    assert_eq!(inbox(&m).unwrap().aabb, cbox(&m));
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]

    /// Random convex polytopes: a built-in polyhedron under a random rotation, non-uniform
    /// scale and translation. The inbox must pass the exact certificate and, the polytope
    /// being convex, come from the convex program.
    #[test]
    fn random_convex_polytopes(
        which in 0usize..18, angles in prop::array::uniform3(-3.2f64..3.2),
        scale in prop::array::uniform3(0.3f64..3.0), shift in prop::array::uniform3(-10.0f64..10.0)
    ) {
        let rot = Rotation3::from_euler_angles(angles[0], angles[1], angles[2]).to_homogeneous();
        let m = Matrix4::new_translation(&Vector3::from(shift))
            * Matrix4::new_nonuniform_scaling(&Vector3::from(scale))
            * rot;
        let mesh = Polyhedron::ALL[which].mesh(1.0).unwrap().transformed(&m).unwrap();
        let i = inbox(&mesh).unwrap();
        prop_assert_eq!(i.method, InboxMethod::Kernel);
        assert_inside(&mesh, &i.aabb, Polyhedron::ALL[which].name());
    }
}

/// Building the INBOX of a valid mesh scaled by any power of two does not panic (near 1e77 the
/// R-tree's nearest-neighbour search met infinite distances), and the box is certified inside
/// the scaled mesh, at both ends of the range of normal coordinates.
#[test]
fn the_inbox_exists_at_every_power_of_two() {
    let shapes: Vec<(&str, Mesh)> = vec![
        (
            "box",
            solids::box_between([0.0; 3], [1.0, 1.5, 0.7]).unwrap(),
        ),
        ("octahedron", solids::octahedron(1.3).unwrap()),
        ("sphere", solids::uv_sphere(0.9, 12, 6).unwrap()),
        (
            "L prism",
            solids::prism(
                &geo::Polygon::new(
                    geo::LineString::from(vec![
                        (0.0, 0.0),
                        (6.0, 0.0),
                        (6.0, 1.0),
                        (1.0, 1.0),
                        (1.0, 4.0),
                        (0.0, 4.0),
                    ]),
                    vec![],
                ),
                3.0,
            )
            .unwrap(),
        ),
    ];
    for (name, mesh) in &shapes {
        // 1e77 is about 2^256; coordinates stay below 2^1023 and above 2^-1022 (the smallest
        // nonzero coordinates of these solids are above 2^-4).
        for k in [
            -1010, -1000, -700, -256, -151, -150, 150, 151, 250, 256, 257, 500, 1000, 1017,
        ] {
            let scaled = crate::common::scaled_mesh(mesh, k).unwrap();
            let what = format!("{name} scaled by 2^{k}");
            let b = inbox(&scaled).unwrap_or_else(|| panic!("{what}: no inbox"));
            assert_inside(&scaled, &b.aabb, &what);
            // At least a tenth of the unscaled inbox, scaled.
            let unit = inbox(mesh).unwrap().aabb;
            let ratio = (0..3)
                .map(|i| (b.aabb.max[i] - b.aabb.min[i]) / ldexp(unit.max[i] - unit.min[i], k))
                .product::<f64>();
            assert!(ratio > 0.1, "{what}: inbox {:?} vs {unit:?}", b.aabb);
        }
    }
}

/// The bounds report at every scale: a cube (and one turned inside out) scaled by `2^k` from
/// the bottom of the normal range to the top reports ratios of exactly 1, 6 tribox faces, an
/// INBOX, the right orientation, and volumes and areas that are the unscaled ones scaled (or
/// infinite where the true value exceeds the doubles), never NaN. Before, volumes overflowed
/// from 2^342 (NaN ratios), the tribox of a cube at 2^1022 had 18 faces, a tiny inside-out
/// cube was reported as `yes`, and a cube of side 5e-324 had no INBOX. Objects of very
/// different scales in one scene are each measured at their own.
#[test]
fn the_bounds_report_holds_at_every_scale() {
    use kepler::scene::report::BoundsReport;
    let unit = kepler::solids::box_between([0.0; 3], [1.0; 3]).unwrap();
    let reversed = |m: &Mesh| {
        let faces = m
            .faces()
            .iter()
            .map(|f| f.vertices().iter().rev().copied().collect())
            .collect();
        Mesh::from_polygons(m.vertices().to_vec(), faces).unwrap()
    };
    let mut scene = Scene::new();
    let ks = [
        -1074, -1070, -900, -359, -150, 0, 150, 341, 342, 600, 1000, 1022,
    ];
    for &k in &ks {
        let cube = crate::common::scaled_mesh(&unit, k).unwrap();
        scene
            .add_mesh(None, format!("cube{k}"), cube.clone())
            .unwrap();
        scene
            .add_mesh(None, format!("inverted{k}"), reversed(&cube))
            .unwrap();
    }
    let report = BoundsReport::of(&scene);
    assert_eq!(report.objects.len(), 2 * ks.len());
    for (o, k) in report.objects.iter().zip(ks.iter().flat_map(|k| [k, k])) {
        let name = &o.name;
        assert_eq!(o.inside_out, name.starts_with("inverted"), "{name}");
        assert_eq!(o.tribox.faces, 6, "{name}");
        for ratio in [o.inbox_ratio, o.tribox_ratio, o.cbox_ratio] {
            assert_eq!(ratio, Some(1.0), "{name}");
        }
        let side = ldexp(1.0, *k);
        assert_eq!(o.cbox.max, [side; 3], "{name}");
        assert_eq!(o.inbox.map(|b| b.max), Some([side; 3]), "{name}");
        let (volume, area) = (ldexp(1.0, 3 * k), ldexp(6.0, 2 * k));
        assert_eq!(o.volume, Some(volume), "{name}");
        assert_eq!(o.cbox.volume, volume, "{name}");
        assert_eq!(o.surface_area, area, "{name}");
        assert_eq!(o.tribox.surface_area, area, "{name}");
        assert!(!o.tribox.volume.is_nan(), "{name}");
    }
    // A flat box of finite volume whose sides span 2^-333 to 2^664.
    let flat = Mesh::from_polygons(
        unit.vertices()
            .iter()
            .map(|p| Point3::new(p.x * 1e200, p.y * 1e200, p.z * 1e-100))
            .collect(),
        unit.faces().iter().map(|f| f.vertices().to_vec()).collect(),
    )
    .unwrap();
    let mut scene = Scene::new();
    scene.add_mesh(None, "flat", flat).unwrap();
    let o = &BoundsReport::of(&scene).objects[0];
    assert_eq!(o.cbox_ratio, Some(1.0));
    assert_eq!(o.inbox_ratio, Some(1.0));
    assert!((o.cbox.volume / (1e200 * (1e200 * 1e-100)) - 1.0).abs() < 1e-15);
}
