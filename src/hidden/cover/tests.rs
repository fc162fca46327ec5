//! The occluder grids leave out the triangles a solid turns away from the eye: VISP must
//! answer exactly as with every triangle listed, at points in general position and at the
//! degenerate ones (vertices, edges, silhouettes, axis-aligned faces seen edge-on), for
//! convex and non-convex solids, either orientation, orthographic and perspective views.

use super::*;
use crate::geometry::Vector3;
use crate::hidden::edges::triangle_turns;
use crate::sight::along::hides_at;
use crate::sight::own_solid::turned_away;
use crate::views::View;
use crate::{random::SplitMix64, solids};

/// VISP of each point against the mesh object `id` alone, its grid built with the side
/// `away` left out (or every triangle listed), and the number of triangles left out.
fn answers(
    scene: &Scene,
    id: ObjectId,
    view: &View,
    away: Option<Ordering>,
    points: &[Point3],
) -> (Vec<Visibility>, usize) {
    let mesh = scene[id].mesh().unwrap();
    let eye = *view.eye();
    let picture = Picture::of(view);
    let pictures: Vec<[f64; 2]> = mesh.vertices().iter().map(|v| picture.point(v)).collect();
    let turned: Vec<bool> = away
        .map(|side| {
            triangle_turns(mesh, &eye)
                .iter()
                .map(|&t| t == side)
                .collect()
        })
        .unwrap_or_default();
    let meshes = [(id, mesh, &pictures[..], &[][..], &turned[..])];
    // No INBOX: the grid decides every point.
    let occluders = Occluders::new(scene, (eye, Picture::of(view)), None, &meshes, 0, 1000);
    let seen = points
        .iter()
        .map(|p| {
            let hides = |o: ObjectId, t: usize| {
                scene[o]
                    .mesh()
                    .is_some_and(|m| hides_at(&eye, &m.triangle(t), |f| f.sign_at(&eye, p)))
            };
            occluders.visp((p, 0.0), hides, &mut Counters::default())
        })
        .collect();
    (seen, occluders.turned_away())
}

/// Points to ask about: the mesh's vertices, its edges' and faces' midpoints (rounded, so
/// on or beside them), points just off each vertex along the axes, and random points in and
/// round its box.
fn points(mesh: &crate::mesh::Mesh, seed: u64) -> Vec<Point3> {
    let v = mesh.vertices();
    let mut out: Vec<Point3> = v.to_vec();
    for t in mesh.triangles() {
        let [a, b, c] = t.map(|k| v[k as usize]);
        out.push(Point3::from((a.coords + b.coords) / 2.0));
        out.push(Point3::from((a.coords + b.coords + c.coords) / 3.0));
    }
    for p in v {
        for k in 0..3 {
            for d in [-1e-3, 1e-3] {
                let mut q = *p;
                q[k] += d;
                out.push(q);
            }
        }
    }
    let b = Aabb::from_points(v);
    let mut rng = SplitMix64(seed);
    for _ in 0..300 {
        out.push(Point3::from(
            [0, 1, 2].map(|k| rng.range(1.2 * b.min[k], 1.2 * b.max[k])),
        ));
    }
    out
}

#[test]
fn leaving_out_triangles_turned_away_changes_no_answer() {
    let reversed = |m: crate::mesh::Mesh| {
        let faces = m.polygons().into_iter().map(|mut f| {
            f.reverse();
            f
        });
        crate::mesh::Mesh::from_polygons(m.vertices().to_vec(), faces.collect()).unwrap()
    };
    let meshes = [
        ("cube", solids::cube(2.0).unwrap()),
        ("torus", solids::torus(2.0, 0.7, 16, 8).unwrap()),
        ("sphere", solids::uv_sphere(1.0, 10, 6).unwrap()),
        (
            "inside-out torus",
            reversed(solids::torus(2.0, 0.9, 12, 6).unwrap()),
        ),
    ];
    let views = [
        View::orthographic(Vector3::new(0.0, 0.0, -1.0), Vector3::y()).unwrap(),
        View::orthographic(Vector3::new(-1.0, -1.0, -1.0), Vector3::z()).unwrap(),
        View::orthographic(Vector3::new(1.0, 2.0, -3.0), Vector3::z()).unwrap(),
        View::perspective(
            Point3::new(3.0, -4.0, 2.0),
            Point3::origin(),
            Vector3::z(),
            60.0,
        )
        .unwrap(),
        View::perspective(
            Point3::new(0.0, 0.0, 6.0),
            Point3::origin(),
            Vector3::y(),
            60.0,
        )
        .unwrap(),
    ];
    for (s, (name, mesh)) in meshes.into_iter().enumerate() {
        let mut scene = Scene::new();
        let id = scene.add_mesh(None, name, mesh).unwrap();
        let asked = points(scene[id].mesh().unwrap(), s as u64);
        for (k, view) in views.iter().enumerate() {
            let side = turned_away(&scene, id, scene[id].mesh().unwrap(), view.eye());
            assert!(
                side.is_some(),
                "{name}, view {k}: a closed solid seen from outside"
            );
            let (all, none_left) = answers(&scene, id, view, None, &asked);
            let (fewer, left_out) = answers(&scene, id, view, side, &asked);
            assert_eq!(none_left, 0);
            assert!(left_out > 0, "{name}, view {k}");
            assert_eq!(all, fewer, "{name}, view {k}");
            // Both answers occur: the test asks about hidden and visible points alike.
            assert!(all.contains(&Visibility::Hidden) && all.contains(&Visibility::Visible));
        }
    }
}

/// The argument needs the side turned away: leaving out the other side instead changes
/// answers (so the comparison above can fail).
#[test]
fn leaving_out_the_side_turned_towards_the_eye_does_change_answers() {
    let mut scene = Scene::new();
    let id = scene
        .add_mesh(None, "torus", solids::torus(2.0, 0.7, 16, 8).unwrap())
        .unwrap();
    let view = View::orthographic(Vector3::new(1.0, 2.0, -3.0), Vector3::z()).unwrap();
    let side = turned_away(&scene, id, scene[id].mesh().unwrap(), view.eye()).unwrap();
    let asked = points(scene[id].mesh().unwrap(), 9);
    let (all, _) = answers(&scene, id, &view, None, &asked);
    let (wrong, _) = answers(&scene, id, &view, Some(side.reverse()), &asked);
    assert_ne!(all, wrong);
}
