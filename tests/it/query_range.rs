//! The point queries at every scale: INCLUDE and VISP of a scene scaled by `2^k`, at points
//! scaled by `2^k`, give the answers of the unscaled scene, for `k` from the bottom of the
//! normal range to the top (the answers are signs, exact for every finite input).

use crate::common::SplitMix64;
use kepler::geometry::exact::ldexp;
use kepler::geometry::{Point3, Vector3};
use kepler::queries::include::IncludeIndex;
use kepler::queries::visp::VisibilityIndex;
use kepler::scene::Scene;
use kepler::views::View;

fn scaled(p: &Point3, k: i32) -> Point3 {
    p.map(|c| ldexp(c, k))
}

/// Two boxes and a tetrahedron, one box hollowed by nothing, all with small integer
/// coordinates; points on a half-integer lattice and on faces, edges and vertices.
fn scene_and_points(rng: &mut SplitMix64) -> (Scene, Vec<Point3>) {
    let mut scene = Scene::new();
    for i in 0..2 {
        let lo = [rng.int(-4, 2), rng.int(-4, 2), rng.int(-4, 2)];
        let hi = lo.map(|c| c + rng.int(1, 4));
        let mesh = kepler::solids::box_between(lo, hi).unwrap();
        scene.add_mesh(None, format!("box{i}"), mesh).unwrap();
    }
    let v = (0..4)
        .map(|_| Point3::new(rng.int(-4, 4), rng.int(-4, 4), rng.int(-4, 4)))
        .collect();
    let faces = vec![vec![0, 2, 1], vec![0, 1, 3], vec![1, 2, 3], vec![0, 3, 2]];
    if let Ok(mesh) = kepler::mesh::Mesh::from_polygons(v, faces) {
        scene.add_mesh(None, "tetrahedron", mesh).unwrap();
    }
    let points = (0..200)
        .map(|_| {
            let mut c = || rng.int(-10, 10) / 2.0;
            Point3::new(c(), c(), c())
        })
        .collect();
    (scene, points)
}

#[test]
fn include_and_visp_answer_the_same_at_every_scale() {
    let mut rng = SplitMix64(0x9e7);
    for case in 0..8 {
        let (scene, points) = scene_and_points(&mut rng);
        let views = [
            View::orthographic(Vector3::new(-1.0, -2.0, -3.0), Vector3::z()).unwrap(),
            View::perspective(
                Point3::new(20.0, -30.0, 25.0),
                Point3::origin(),
                Vector3::z(),
                40.0,
            )
            .unwrap(),
        ];
        let include = IncludeIndex::whole_scene(&scene).unwrap();
        let (inside, _) = include.include_all(&points);
        let visible: Vec<_> = views
            .iter()
            .map(|v| {
                VisibilityIndex::whole_scene(&scene, v.clone())
                    .visp_all(&points)
                    .0
            })
            .collect();
        for k in [-1000, -700, -300, -61, 61, 150, 300, 700, 1015] {
            let big = scene.scaled(k).unwrap();
            let moved: Vec<Point3> = points.iter().map(|p| scaled(p, k)).collect();
            let include = IncludeIndex::whole_scene(&big).unwrap();
            assert_eq!(include.include_all(&moved).0, inside, "case {case}, 2^{k}");
            for (view, expected) in views.iter().zip(&visible) {
                let index = VisibilityIndex::whole_scene(&big, view.scaled(k));
                assert_eq!(&index.visp_all(&moved).0, expected, "case {case}, 2^{k}");
            }
        }
    }
}

/// A points file takes every finite double; a segments file keeps its limit (Franklin's grid
/// computes cells in floating point).
#[test]
fn point_files_take_every_finite_coordinate() {
    use kepler::io::points::{parse_points, parse_segments};
    let p = parse_points("1e300 -1e-300 5e-324\n-1.7e308, 0, 1\n", "p.txt").unwrap();
    assert_eq!(p[0], Point3::new(1e300, -1e-300, 5e-324));
    assert_eq!(p[1].x, -1.7e308);
    assert!(parse_points("1e309 0 0\n", "p.txt").is_err());
    let e = parse_segments("0 0 1e200 1\n", "s.txt").unwrap_err();
    assert!(e.to_string().starts_with("s.txt:1: coordinate"), "{e}");
}
