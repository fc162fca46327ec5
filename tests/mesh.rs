//! Mesh validation, Franklin's texture coordinate systems, topology, exact containment.

use kepler::geometry::{Point3, Vector3};
use kepler::mesh::{
    Containment, Mesh, MeshError, TriangleTree, Validation, classify_point,
    classify_point_brute_force,
};
use nalgebra::Matrix4;

fn p(x: f64, y: f64, z: f64) -> Point3 {
    Point3::new(x, y, z)
}

fn unit_square_pyramid() -> (Vec<Point3>, Vec<Vec<u32>>) {
    let v = vec![
        p(0., 0., 0.),
        p(1., 0., 0.),
        p(1., 1., 0.),
        p(0., 1., 0.),
        p(0.5, 0.5, 1.),
    ];
    let f = vec![
        vec![0, 3, 2, 1],
        vec![0, 1, 4],
        vec![1, 2, 4],
        vec![2, 3, 4],
        vec![3, 0, 4],
    ];
    (v, f)
}

#[test]
fn valid_pyramid_is_a_solid_with_exact_measures() {
    let (v, f) = unit_square_pyramid();
    let m = Mesh::from_polygons(v, f).unwrap();
    assert!(m.is_solid());
    assert_eq!(m.topology().edges, 8);
    assert!((m.volume() - 1.0 / 3.0).abs() < 1e-15);
    assert_eq!(m.triangles().len(), 6);
}

#[test]
fn each_bad_input_is_named() {
    let (v, f) = unit_square_pyramid();
    let mut nan = v.clone();
    nan[3].y = f64::NAN;
    assert_eq!(
        Mesh::from_polygons(nan, f.clone()),
        Err(MeshError::NonFinite { vertex: 3 })
    );
    let mut inf = v.clone();
    inf[1].z = f64::INFINITY;
    assert_eq!(
        Mesh::from_polygons(inf, f.clone()),
        Err(MeshError::NonFinite { vertex: 1 })
    );
    // Every finite coordinate is accepted.
    let mut huge = v.clone();
    huge[4].x = 1e300;
    assert!(Mesh::from_polygons(huge, f.clone()).unwrap().is_solid());
    let mut short = f.clone();
    short[2] = vec![1, 2];
    assert_eq!(
        Mesh::from_polygons(v.clone(), short),
        Err(MeshError::TooFewVertices { face: 2, count: 2 })
    );
    let mut far = f.clone();
    far[1] = vec![0, 1, 9];
    let e = Mesh::from_polygons(v.clone(), far).unwrap_err();
    assert_eq!(
        e,
        MeshError::IndexOutOfRange {
            face: 1,
            index: 9,
            vertex_count: 5
        }
    );
    assert_eq!(
        e.to_string(),
        "face 2 refers to vertex 10 but there are only 5 vertices"
    );
    let strict =
        |v: Vec<Point3>, f: Vec<Vec<u32>>| Mesh::from_polygons_with(v, f, Validation::Strict);
    let mut twice = f.clone();
    twice[1] = vec![0, 1, 0, 4];
    assert!(matches!(
        strict(v.clone(), twice.clone()),
        Err(MeshError::RepeatedVertex { face: 1, .. })
    ));
    // Repaired: the face is dropped, and the pyramid has a hole where it was.
    let m = Mesh::from_polygons(v.clone(), twice).unwrap();
    assert_eq!((m.faces().len(), m.degenerate_faces()), (4, 1));
    assert_eq!(m.topology().boundary_edges, 3);
    // Two vertices with equal coordinates merge; a face using both then repeats a point.
    let mut dup = v.clone();
    dup.push(p(1., 0., 0.));
    let mut dupf = f.clone();
    dupf[1] = vec![0, 1, 5, 4];
    let e = strict(dup.clone(), dupf.clone()).unwrap_err();
    assert_eq!(e.to_string(), "face 2 visits the point (1, 0, 0) twice");
    // Repaired: a point repeated in a row is a zero-length side, so the face is the triangle.
    let m = Mesh::from_polygons(dup, dupf).unwrap();
    assert_eq!((m.faces().len(), m.degenerate_faces()), (5, 0));
    assert!(m.is_solid());
    let line = vec![p(0., 0., 0.), p(1., 1., 1.), p(2., 2., 2.)];
    assert_eq!(
        strict(line.clone(), vec![vec![0, 1, 2]]),
        Err(MeshError::ZeroArea { face: 0 })
    );
    let m = Mesh::from_polygons(line, vec![vec![0, 1, 2]]).unwrap();
    assert_eq!((m.faces().len(), m.degenerate_faces()), (0, 1));
    let bent = vec![p(0., 0., 0.), p(1., 0., 0.), p(1., 1., 0.1), p(0., 1., 0.)];
    let e = strict(bent.clone(), vec![vec![0, 1, 2, 3]]).unwrap_err();
    assert_eq!(e, MeshError::NonPlanar { face: 0, corner: 3 });
    assert_eq!(
        e.to_string(),
        "face 1 is not planar: its corner 4 is off the plane of its first corners"
    );
    let m = Mesh::from_polygons(bent, vec![vec![0, 1, 2, 3]]).unwrap();
    assert_eq!((m.faces().len(), m.split_polygons()), (2, 1));
    let star: Vec<Point3> = (0..5)
        .map(|i| {
            let a = std::f64::consts::TAU * (2 * i) as f64 / 5.0;
            p(a.cos(), a.sin(), 0.0)
        })
        .collect();
    assert_eq!(
        Mesh::from_polygons(star, vec![vec![0, 1, 2, 3, 4]]),
        Err(MeshError::NotSimple { face: 0 })
    );
}

#[test]
fn duplicates_merge_including_signed_zero() {
    let v = vec![
        p(0., 0., 0.),
        p(1., 0., 0.),
        p(0., 1., 0.),
        p(-0.0, 0.0, -0.0),
        p(0., 1., 0.),
        p(-1., 0., 0.),
    ];
    let m = Mesh::from_polygons(v, vec![vec![0, 1, 2], vec![3, 4, 5]]).unwrap();
    assert_eq!(m.vertices().len(), 4);
    assert_eq!(m.merged_vertices(), 2);
    assert_eq!(m.faces()[1].vertices(), &[0, 2, 3]);
}

#[test]
fn open_and_inconsistent_meshes_load_and_say_so() {
    let (v, mut f) = unit_square_pyramid();
    f.remove(0);
    let open = Mesh::from_polygons(v.clone(), f).unwrap();
    assert!(!open.topology().closed && open.topology().consistently_oriented);
    assert_eq!(open.topology().boundary_edges, 4);
    let (v, mut f) = unit_square_pyramid();
    f[1].reverse();
    let flipped = Mesh::from_polygons(v, f).unwrap();
    assert!(flipped.topology().closed && !flipped.topology().consistently_oriented);
    assert_eq!(flipped.topology().misoriented_edges, 3);
    assert!(!flipped.is_solid());
}

#[test]
fn mirrored_instances_keep_outward_faces() {
    let cube = kepler::solids::cube(1.0).unwrap();
    let m = cube
        .transformed(&Matrix4::new_nonuniform_scaling(&Vector3::new(
            -1.0, 2.0, 3.0,
        )))
        .unwrap();
    assert!(m.is_solid());
    assert!((m.volume() - 6.0).abs() < 1e-12);
    assert!(
        cube.transformed(&Matrix4::new_nonuniform_scaling(&Vector3::new(
            1.0, 0.0, 1.0
        )))
        .is_err()
    );
}

/// Franklin: origin = the point of the face plane closest to the 3-D origin; unit x-vector in
/// the plane with no z component; y-vector with positive z; horizontal faces (1,0,0), (0,1,0).
#[test]
fn texture_systems_follow_the_paper() {
    let check = |m: &Mesh| {
        for (i, f) in m.faces().iter().enumerate() {
            let t = f.texture();
            let (x, y, n) = (t.x_axis(), t.y_axis(), f.plane().normal);
            let horizontal = m
                .face_points(i)
                .all(|q| q.z == m.face_points(i).next().unwrap().z);
            if horizontal {
                assert_eq!(x, Vector3::x());
                assert_eq!(y, Vector3::y());
            } else {
                assert_eq!(x.z, 0.0, "x-vector has no z component");
                assert!(y.z > 0.0, "y-vector points up");
                assert!(
                    (x.cross(&y) - n).norm() < 1e-12,
                    "x × y is the outward normal"
                );
            }
            assert!(
                (x.norm() - 1.0).abs() < 1e-15
                    && (y.norm() - 1.0).abs() < 1e-15
                    && x.dot(&y).abs() < 1e-15
            );
            // The origin is on the plane and is its point closest to the origin.
            let o = t.origin();
            assert!(f.plane().evaluate(&o).abs() < 1e-12);
            assert!(o.coords.cross(&n).norm() < 1e-12);
            // Global → texture → global, and every vertex has w = 0.
            for v in m.face_points(i) {
                let tv = t.to_texture(&v);
                assert!(tv.z.abs() < 1e-12);
                assert!((t.to_global(&tv) - v).norm() < 1e-12);
            }
        }
    };
    // Horizontal top and bottom, vertical walls, and slanted faces.
    check(&kepler::solids::cube(2.0).unwrap());
    check(&kepler::solids::octahedron(1.5).unwrap());
    check(
        &kepler::solids::Polyhedron::SnubDodecahedron
            .mesh(1.0)
            .unwrap(),
    );
    // A wall facing -y at y = 3: x-vector (1, 0, 0), y-vector (0, 0, 1), origin (0, 3, 0).
    let cube = kepler::solids::cube(6.0).unwrap();
    let wall = cube
        .faces()
        .iter()
        .find(|f| f.plane().normal.y < -0.5)
        .unwrap();
    assert_eq!(wall.texture().x_axis(), Vector3::x());
    assert!((wall.texture().y_axis() - Vector3::z()).norm() < 1e-15);
    assert!((wall.texture().origin() - p(0., -3., 0.)).norm() < 1e-15);
}

/// The L-shaped prism, probed on a half-unit grid that puts points exactly on its vertices,
/// edges and faces and sends vertical rays through vertices and edges; the exact answer is
/// known in closed form.
#[test]
fn containment_is_exact_on_grid_aligned_degeneracies() {
    let outline = geo::Polygon::new(
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
    let l = kepler::solids::prism(&outline, 3.0).unwrap();
    let tree = TriangleTree::new(&l);
    let closed_l = |x: f64, y: f64| {
        (0. ..=6.).contains(&x) && (0. ..=1.).contains(&y)
            || (0. ..=1.).contains(&x) && (0. ..=4.).contains(&y)
    };
    let open_l = |x: f64, y: f64| {
        (0. < x && x < 6. && 0. < y && y < 1.) || (0. < x && x < 1. && 0. < y && y < 4.)
    };
    let mut counts = [0usize; 3];
    for i in -1..=13 {
        for j in -1..=9 {
            for k in -1..=7 {
                let (x, y, z) = (i as f64 / 2.0, j as f64 / 2.0, k as f64 / 2.0);
                let expected = if 0. < z && z < 3. && open_l(x, y) {
                    Containment::Inside
                } else if (0. ..=3.).contains(&z) && closed_l(x, y) {
                    Containment::Boundary
                } else {
                    Containment::Outside
                };
                let q = p(x, y, z);
                assert_eq!(classify_point(&tree, &q), expected, "at {q:?}");
                assert_eq!(classify_point_brute_force(&l, &q), expected, "at {q:?}");
                counts[expected as usize] += 1;
            }
        }
    }
    assert!(counts.iter().all(|&c| c > 50), "{counts:?}");
}
