//! The scene index (`kepler index`, `scene::index`): read back, it is the same scene (tree,
//! names, instances, camera, every mesh face for face and bit for bit, with its counts of
//! repairs), so every drawing of it is the original's; damaged indexes are errors, not
//! panics.

use kepler::geometry::{Point3, Vector3};
use kepler::hidden::{Options, draw};
use kepler::mesh::Mesh;
use kepler::random::SplitMix64;
use kepler::scene::{ObjectId, Scene, file, index};
use kepler::views::View;

/// An object as its name, its parent's position in tree order, its mesh and the instance
/// it copies.
type Shape = (String, Option<usize>, Option<Mesh>, Option<String>);

/// Every object, in tree order.
fn shape(scene: &Scene) -> Vec<Shape> {
    let order: Vec<ObjectId> = scene
        .roots()
        .iter()
        .flat_map(|&r| scene.subtree(r))
        .collect();
    order
        .iter()
        .map(|&id| {
            let o = &scene[id];
            let parent = o
                .parent()
                .map(|p| order.iter().position(|&q| q == p).unwrap());
            let (name, mesh) = (o.name().to_string(), o.mesh().cloned());
            (name, parent, mesh, o.instance_of().map(str::to_string))
        })
        .collect()
}

fn round_trip(scene: &Scene) -> Scene {
    index::read(&index::to_bytes(scene), "t.kix").unwrap()
}

/// A drawing as comparable bits.
fn bits(scene: &Scene, view: &View) -> Vec<(u8, bool, Vec<u64>)> {
    let options = Options {
        edges: kepler::hidden::EdgeSelection::All,
        ..Options::default()
    };
    draw(scene, view, &options)
        .unwrap()
        .polylines
        .iter()
        .map(|p| {
            let points = p.points.iter().flatten().map(|c| c.to_bits()).collect();
            (p.class as u8, p.visible, points)
        })
        .collect()
}

#[test]
fn every_bundled_scene_reads_back_the_same() {
    for name in [
        "cube",
        "city",
        "polyhedra",
        "solids",
        "meshes",
        "bunny",
        "torus",
    ] {
        let scene = file::load(format!("scenes/{name}.toml").as_ref()).unwrap();
        let back = round_trip(&scene);
        assert!(shape(&back) == shape(&scene), "{name}");
        assert_eq!(back.camera(), scene.camera(), "{name}");
        let view = View::orthographic(Vector3::new(-1.0, -2.0, -3.0), Vector3::z()).unwrap();
        assert!(bits(&back, &view) == bits(&scene, &view), "{name}");
        // Copies still share their mesh: the index holds it once.
        let counts = |s: &Scene| {
            let meshes = s.mesh_objects(s.roots());
            let shared = meshes
                .windows(2)
                .filter(|w| std::ptr::eq(w[0].1, w[1].1))
                .count();
            (meshes.len(), shared)
        };
        assert_eq!(counts(&back), counts(&scene), "{name}");
    }
}

/// A random mesh over a small grid of points: quads that are not all planar (split), faces
/// with repeated or collinear vertices (dropped), duplicate vertices (merged), T-junctions.
fn random_mesh(rng: &mut SplitMix64) -> Option<Mesh> {
    let n = 3 + rng.below(4);
    let mut vertices = Vec::new();
    for i in 0..n {
        for j in 0..n {
            let z = if rng.below(3) == 0 {
                rng.below(5) as f64 / 8.0
            } else {
                0.0
            };
            vertices.push(Point3::new(i as f64, j as f64, z));
        }
    }
    vertices.push(vertices[0]); // a duplicate, merged
    let at = |i: usize, j: usize| (i * n + j) as u32;
    let mut faces = Vec::new();
    for i in 0..n - 1 {
        for j in 0..n - 1 {
            match rng.below(6) {
                0 => faces.push(vec![at(i, j), at(i + 1, j), at(i + 1, j + 1)]),
                1 => faces.push(vec![at(i, j), at(i, j), at(i + 1, j + 1)]),
                2 if i + 2 < n => faces.push(vec![at(i, j), at(i + 1, j), at(i + 2, j)]),
                _ => faces.push(vec![at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)]),
            }
        }
    }
    faces.push(vec![(n * n) as u32, at(0, 1), at(1, 1)]);
    Mesh::from_polygons(vertices, faces).ok()
}

#[test]
fn random_scenes_read_back_the_same() {
    let mut rng = SplitMix64(30);
    for case in 0..60 {
        let mut scene = Scene::new();
        let group = scene.add_group(None, "g").unwrap();
        for k in 0..1 + rng.below(4) {
            let parent = if rng.below(2) == 0 { Some(group) } else { None };
            if let Some(mesh) = random_mesh(&mut rng) {
                scene.add_mesh(parent, format!("m{k}"), mesh).unwrap();
            }
        }
        let back = round_trip(&scene);
        assert!(shape(&back) == shape(&scene), "case {case}");
        let counts = |s: &Scene| -> Vec<[usize; 3]> {
            s.mesh_objects(s.roots())
                .iter()
                .map(|(_, m)| {
                    [
                        m.merged_vertices(),
                        m.degenerate_faces(),
                        m.split_polygons(),
                    ]
                })
                .collect()
        };
        assert_eq!(counts(&back), counts(&scene), "case {case}");
        if !scene.mesh_objects(scene.roots()).is_empty() {
            let view = View::orthographic(Vector3::new(-1.0, -2.0, -3.0), Vector3::z()).unwrap();
            assert!(bits(&back, &view) == bits(&scene, &view), "case {case}");
        }
    }
}

#[test]
fn damaged_indexes_are_errors() {
    let scene = file::load("scenes/polyhedra.toml".as_ref()).unwrap();
    let bytes = index::to_bytes(&scene);
    for len in (0..bytes.len()).step_by(7).chain([bytes.len() - 1]) {
        let err = index::read(&bytes[..len], "p.kix").unwrap_err().to_string();
        assert!(err.starts_with("p.kix:"), "{len}: {err}");
    }
    let mut rng = SplitMix64(3);
    for _ in 0..300 {
        let mut damaged = bytes.clone();
        let k = rng.below(damaged.len());
        damaged[k] ^= 1 << rng.below(8);
        // Either an error or a scene (a flipped coordinate bit is still a scene): no panic.
        let _ = index::read(&damaged, "p.kix");
    }
    let err = index::read(b"KINDEX\x00\x02", "v.kix")
        .unwrap_err()
        .to_string();
    assert_eq!(
        err,
        "v.kix:header: not a kepler scene index, or a damaged one"
    );
}
