//! A real scan with the defects scans have: the low-resolution Stanford bunny with zero-area
//! triangles added (a repeated vertex; an existing edge's ends repeated; slivers along
//! existing edges through a new vertex exactly on the edge) renders, and draws exactly the
//! bunny's drawing, in several views.

use kepler::geometry::predicates::collinear;
use kepler::geometry::{Point3, Vector3};
use kepler::hidden::{EdgeSelection, Options, draw};
use kepler::io::off;
use kepler::mesh::Mesh;
use kepler::scene::Scene;
use kepler::views::View;

fn bunny_text() -> String {
    std::fs::read_to_string("scenes/meshes/bunny.off").expect("the bundled bunny")
}

/// The OFF text's vertices and triangles.
fn parts(text: &str) -> (Vec<[f64; 3]>, Vec<[usize; 3]>) {
    let lines: Vec<&str> = text
        .lines()
        .filter(|l| !l.starts_with('#') && !l.trim().is_empty())
        .collect();
    let counts: Vec<usize> = lines[1]
        .split_whitespace()
        .map(|x| x.parse().unwrap())
        .collect();
    let vertices = lines[2..2 + counts[0]]
        .iter()
        .map(|l| {
            let v: Vec<f64> = l.split_whitespace().map(|x| x.parse().unwrap()).collect();
            [v[0], v[1], v[2]]
        })
        .collect();
    let faces = lines[2 + counts[0]..2 + counts[0] + counts[1]]
        .iter()
        .map(|l| {
            let f: Vec<usize> = l.split_whitespace().map(|x| x.parse().unwrap()).collect();
            [f[1], f[2], f[3]]
        })
        .collect();
    (vertices, faces)
}

fn off_text(vertices: &[[f64; 3]], faces: &[Vec<usize>]) -> String {
    let mut t = format!("OFF\n{} {} 0\n", vertices.len(), faces.len());
    for v in vertices {
        t += &format!("{:?} {:?} {:?}\n", v[0], v[1], v[2]);
    }
    for f in faces {
        t += &format!("{}", f.len());
        for i in f {
            t += &format!(" {i}");
        }
        t += "\n";
    }
    t
}

fn drawings(mesh: Mesh) -> Vec<Vec<kepler::hidden::Polyline>> {
    let mut scene = Scene::new();
    scene.add_mesh(None, "bunny", mesh).unwrap();
    let views = [
        View::orthographic(Vector3::new(-1.0, -1.0, -1.0), Vector3::z()).unwrap(),
        View::orthographic(Vector3::new(0.3, -1.0, 0.2), Vector3::z()).unwrap(),
        View::perspective(
            Point3::new(0.4, -0.9, 0.5),
            Point3::new(0.0, 0.1, 0.0),
            Vector3::y(),
            40.0,
        )
        .unwrap(),
    ];
    let mut out = Vec::new();
    for view in &views {
        for edges in [EdgeSelection::Feature, EdgeSelection::All] {
            let options = Options {
                edges,
                ..Options::default()
            };
            out.push(draw(&scene, view, &options).unwrap().polylines);
        }
    }
    out
}

#[test]
fn a_scan_with_degenerate_triangles_draws_as_the_clean_scan() {
    let text = bunny_text();
    let clean = off::parse(&text, "bunny.off").unwrap();
    let (mut vertices, faces) = parts(&text);
    let mut polygons: Vec<Vec<usize>> = faces.iter().map(|f| f.to_vec()).collect();
    // A repeated-vertex triangle and a triangle repeating an existing edge's ends.
    polygons.push(vec![faces[10][0], faces[10][0], faces[10][1]]);
    polygons.push(vec![faces[20][0], faces[20][1], faces[20][0]]);
    // Zero-area slivers along edges whose midpoint rounds exactly onto the edge (a new vertex
    // that no other face uses).
    let mut slivers = 0;
    for f in faces.iter().step_by(97) {
        let (a, b) = (f[0], f[1]);
        let (p, q) = (Point3::from(vertices[a]), Point3::from(vertices[b]));
        let m = Point3::from((p.coords + q.coords) / 2.0);
        if m != p && m != q && collinear(&p, &q, &m) {
            vertices.push(m.into());
            polygons.push(vec![a, vertices.len() - 1, b]);
            slivers += 1;
        }
    }
    assert!(slivers >= 3, "{slivers} slivers");
    let dirty = off::parse(&off_text(&vertices, &polygons), "dirty.off").unwrap();
    assert_eq!(dirty.degenerate_faces(), 2 + slivers);
    let (want, got) = (drawings(clean), drawings(dirty));
    for (k, (w, g)) in want.iter().zip(&got).enumerate() {
        assert!(w == g, "drawing {k} differs");
    }
}
