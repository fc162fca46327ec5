//! DXF output (issue 17), read back with the `dxf` crate: one LWPOLYLINE per polyline on its
//! class-and-visibility layer, hidden layers dashed, closed chains closed, and every
//! coordinate as written: bit for bit in binary DXF, to 12 decimal places in ASCII DXF.

use kepler::geometry::Vector3;
use kepler::hidden::{Drawing, EdgeClass, Options, Polyline, draw};
use kepler::output::{DxfFormat, SvgOptions, layer_name, write_dxf};
use kepler::scene::Scene;
use kepler::views::View;

fn read(drawing: &Drawing, format: DxfFormat) -> dxf::Drawing {
    let mut bytes = Vec::new();
    write_dxf(drawing, &SvgOptions::default(), format, &mut bytes).unwrap();
    dxf::Drawing::load(&mut bytes.as_slice()).expect("a DXF reader reads it")
}

/// The polylines read back: layer, closed, points (a closed one's first point repeated).
fn polylines(d: &dxf::Drawing) -> Vec<(String, Vec<[f64; 2]>)> {
    d.entities()
        .map(|e| {
            let dxf::entities::EntityType::LwPolyline(p) = &e.specific else {
                panic!("only LWPOLYLINEs, not {:?}", e.specific);
            };
            let mut points: Vec<[f64; 2]> = p.vertices.iter().map(|v| [v.x, v.y]).collect();
            if p.is_closed() {
                points.push(points[0]);
            }
            (e.common.layer.clone(), points)
        })
        .collect()
}

fn check(drawing: &Drawing, format: DxfFormat) {
    let back = read(drawing, format);
    let got = polylines(&back);
    assert_eq!(got.len(), drawing.polylines.len());
    for ((layer, points), p) in got.iter().zip(&drawing.polylines) {
        assert_eq!(*layer, layer_name(p.class, p.visible));
        assert_eq!(points.len(), p.points.len());
        for (a, b) in points.iter().zip(&p.points) {
            for k in 0..2 {
                match format {
                    DxfFormat::Binary => assert_eq!(a[k].to_bits(), b[k].to_bits()),
                    DxfFormat::Text => {
                        assert!(
                            (a[k] - b[k]).abs() <= 5e-13 + 4e-16 * b[k].abs().max(1.0),
                            "{} for {}",
                            a[k],
                            b[k]
                        )
                    }
                }
            }
        }
    }
    for p in &drawing.polylines {
        let name = layer_name(p.class, p.visible);
        let layer = back.layers().find(|l| l.name == name).expect("its layer");
        let dashed = if p.visible { "CONTINUOUS" } else { "DASHED" };
        assert_eq!(layer.line_type_name, dashed);
    }
    let dashed = back
        .line_types()
        .find(|l| l.name == "DASHED")
        .expect("DASHED");
    assert_eq!(dashed.dash_dot_space_lengths.len(), 2);
    assert!(dashed.dash_dot_space_lengths[0] > 0.0 && dashed.dash_dot_space_lengths[1] < 0.0);
}

#[test]
fn polylines_come_back_on_their_layers() {
    let line = |class, visible, points: &[[f64; 2]]| Polyline {
        class,
        visible,
        points: points.to_vec(),
    };
    let drawing = Drawing {
        polylines: vec![
            line(
                EdgeClass::Silhouette,
                true,
                &[[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 0.0]],
            ),
            line(
                EdgeClass::Crease,
                false,
                &[[0.1, 0.2], [0.30000000000000004, -7.5]],
            ),
            line(
                EdgeClass::Intersection,
                true,
                &[[1e8 + 0.5, 3.0], [1e8, 2.0], [1e8, 3.0]],
            ),
            line(EdgeClass::Smooth, false, &[[1e-3, 1e-3], [2.5e-3, 1.75e-3]]),
            line(
                EdgeClass::Boundary,
                true,
                &[[-123456.789, 9.0], [98765.4321, 0.0]],
            ),
        ],
        stages: Vec::new(),
    };
    check(&drawing, DxfFormat::Binary);
    check(&drawing, DxfFormat::Text);
    // Tiny and huge coordinates: exact in binary.
    let extreme = Drawing {
        polylines: vec![
            line(
                EdgeClass::Silhouette,
                true,
                &[[3e-300, 1e-310], [7e-300, 2e-300]],
            ),
            line(EdgeClass::Crease, true, &[[-1e90, 1e90], [1e90, 3e89]]),
        ],
        stages: Vec::new(),
    };
    check(&extreme, DxfFormat::Binary);
}

#[test]
fn a_rendered_scene_comes_back_whole() {
    let mut scene = Scene::new();
    scene
        .add_mesh(None, "cube", kepler::solids::cube(2.0).unwrap())
        .unwrap();
    scene
        .add_mesh(
            None,
            "ball",
            kepler::solids::uv_sphere(0.9, 12, 6)
                .unwrap()
                .transformed(&nalgebra::Matrix4::new_translation(&Vector3::new(
                    1.2, 0.7, 0.4,
                )))
                .unwrap(),
        )
        .unwrap();
    let view = View::orthographic(Vector3::new(-1.0, -2.0, -1.5), Vector3::z()).unwrap();
    let drawing = draw(&scene, &view, &Options::default()).unwrap();
    assert!(drawing.polylines.iter().any(|p| !p.visible));
    check(&drawing, DxfFormat::Binary);
    check(&drawing, DxfFormat::Text);
}

/// The same drawing writes the same bytes every time (the GUIDs come from the drawing, the
/// dates are DXF's epoch), and another drawing gets another GUID.
#[test]
fn the_same_drawing_writes_the_same_bytes() {
    let mut scene = Scene::new();
    scene
        .add_mesh(None, "cube", kepler::solids::cube(2.0).unwrap())
        .unwrap();
    let view = View::orthographic(Vector3::new(-1.0, -2.0, -3.0), Vector3::z()).unwrap();
    let drawing = draw(&scene, &view, &Options::default()).unwrap();
    let bytes = |d: &Drawing, format: DxfFormat| {
        let mut out = Vec::new();
        write_dxf(d, &SvgOptions::default(), format, &mut out).unwrap();
        out
    };
    for format in [DxfFormat::Text, DxfFormat::Binary] {
        let first = bytes(&drawing, format);
        std::thread::sleep(std::time::Duration::from_millis(1100));
        assert!(
            first == bytes(&drawing, format),
            "written twice, differently"
        );
    }
    let read = |d: &Drawing| dxf::Drawing::load(&mut bytes(d, DxfFormat::Text).as_slice()).unwrap();
    let mut other = drawing.clone();
    other.polylines.pop();
    let (a, b) = (read(&drawing), read(&other));
    assert_ne!(a.header.fingerprint_guid, b.header.fingerprint_guid);
    assert_eq!(
        a.header.creation_date_universal,
        b.header.creation_date_universal
    );
}
