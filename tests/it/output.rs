//! The SVG and JSON writers: structure, exact round trip of coordinates, page layout and
//! degenerate drawings.

use std::io::ErrorKind;

use kepler::hidden::{Drawing, EdgeClass, Polyline};
use kepler::output::{
    PageTransform, StrokeWidths, SvgOptions, page_transform, write_json, write_svg,
};

const SVG_NS: &str = "http://www.w3.org/2000/svg";
const INKSCAPE_NS: &str = "http://www.inkscape.org/namespaces/inkscape";

fn line(class: EdgeClass, visible: bool, points: &[[f64; 2]]) -> Polyline {
    Polyline {
        class,
        visible,
        points: points.to_vec(),
    }
}

fn drawing(polylines: Vec<Polyline>) -> Drawing {
    Drawing {
        polylines,
        stages: Vec::new(),
    }
}

/// Several classes, visible and hidden, a closed polyline and awkward coordinates.
fn awkward() -> Drawing {
    use EdgeClass::*;
    let third = 1.0 / 3.0;
    drawing(vec![
        line(
            Smooth,
            false,
            &[[0.1 + 0.2, third], [-third, 1e-300], [2.0 / 3.0, -0.0]],
        ),
        line(
            Crease,
            true,
            &[[-1e17, 0.1], [1e17, -0.7], [0.1 + 0.2, 1e-300]],
        ),
        line(Crease, true, &[[1.0, 1.0], [7e-310, 1e16 + 1.0]]),
        line(
            Crease,
            false,
            &[[third, third], [1e-7, 123456789.0 + 0.123456789]],
        ),
        line(
            Boundary,
            true,
            &[[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0], [0.0, 0.0]],
        ),
        line(Silhouette, true, &[[-2.5, 3.0], [4.0, 1e-300], [-2.5, 3.0]]),
        line(
            Silhouette,
            false,
            &[[0.3, -0.1], [f64::EPSILON, 1.0 - f64::EPSILON]],
        ),
        line(Silhouette, true, &[[5.0, 5.0], [6.0, 6.0]]),
    ])
}

/// A plain drawing, wider than the page's aspect.
fn plain() -> Drawing {
    use EdgeClass::*;
    drawing(vec![
        line(Intersection, true, &[[-3.0, 1.0], [5.0, 2.0]]),
        line(Smooth, false, &[[0.0, 0.5], [1.0, 2.5], [0.0, 0.5]]),
    ])
}

fn svg_text(d: &Drawing, options: &SvgOptions) -> String {
    let mut out = Vec::new();
    write_svg(d, options, &mut out).expect("write_svg");
    String::from_utf8(out).expect("UTF-8")
}

fn json_text(d: &Drawing) -> String {
    let mut out = Vec::new();
    write_json(d, &mut out).expect("write_json");
    String::from_utf8(out).expect("UTF-8")
}

fn number(s: &str) -> f64 {
    s.parse()
        .unwrap_or_else(|e| panic!("{s:?} is not a number: {e}"))
}

/// The `d` attribute of a path as points: `M x y L x y L x y …`.
fn path_points(d: &str) -> Vec<[f64; 2]> {
    let tokens: Vec<&str> = d.split_ascii_whitespace().collect();
    assert_eq!(tokens.len() % 3, 0, "path {d:?}");
    tokens
        .chunks(3)
        .enumerate()
        .map(|(i, t)| {
            assert_eq!(t[0], if i == 0 { "M" } else { "L" }, "path {d:?}");
            [number(t[1]), number(t[2])]
        })
        .collect()
}

/// Every number of a JSON text, in order, read with Rust's correctly rounded parser (serde_json
/// parses floats only to within an ulp without its `float_roundtrip` feature).
fn json_numbers(text: &str) -> Vec<f64> {
    let mut numbers = Vec::new();
    let mut chars = text.chars().peekable();
    while let Some(c) = chars.next() {
        match c {
            '"' => {
                while let Some(c) = chars.next() {
                    match c {
                        '\\' => {
                            chars.next();
                        }
                        '"' => break,
                        _ => {}
                    }
                }
            }
            '-' | '0'..='9' => {
                let mut s = c.to_string();
                while let Some(&c) = chars.peek() {
                    if c.is_ascii_digit() || "+-.eE".contains(c) {
                        s.push(c);
                        chars.next();
                    } else {
                        break;
                    }
                }
                numbers.push(number(&s));
            }
            _ => {}
        }
    }
    numbers
}

/// The JSON output read back: its polylines, with coordinates exact.
fn json_polylines(text: &str) -> Vec<Polyline> {
    let value: serde_json::Value = serde_json::from_str(text).expect("valid JSON");
    let top = value.as_object().expect("an object");
    assert_eq!(top.keys().collect::<Vec<_>>(), ["polylines"]);
    let mut numbers = json_numbers(text).into_iter();
    let polylines = top["polylines"]
        .as_array()
        .expect("an array")
        .iter()
        .map(|p| {
            let p = p.as_object().expect("a polyline object");
            let mut keys: Vec<&String> = p.keys().collect();
            keys.sort();
            assert_eq!(keys, ["class", "points", "visible"]);
            let class = p["class"].as_str().expect("a class name");
            let class = EdgeClass::ALL
                .into_iter()
                .find(|c| c.name() == class)
                .unwrap_or_else(|| panic!("unknown class {class}"));
            let points = p["points"]
                .as_array()
                .expect("points")
                .iter()
                .map(|q| {
                    let q = q.as_array().expect("a point");
                    assert_eq!(q.len(), 2);
                    let x = numbers.next().expect("x");
                    let y = numbers.next().expect("y");
                    // serde_json's value is within an ulp of the exact one.
                    for (read, exact) in [(&q[0], x), (&q[1], y)] {
                        let read = read.as_f64().expect("a number");
                        let tolerance = (exact.abs() * 1e-15).max(1e-300);
                        assert!((read - exact).abs() <= tolerance, "{read} vs {exact}");
                    }
                    [x, y]
                })
                .collect();
            Polyline {
                class,
                visible: p["visible"].as_bool().expect("visible"),
                points,
            }
        })
        .collect();
    assert_eq!(numbers.next(), None, "numbers outside the points");
    polylines
}

/// Exact equality, telling `-0` from `0`.
fn same_points(a: &[[f64; 2]], b: &[[f64; 2]]) -> bool {
    a.len() == b.len()
        && a.iter()
            .zip(b)
            .all(|(p, q)| p[0].to_bits() == q[0].to_bits() && p[1].to_bits() == q[1].to_bits())
}

fn layer_id(class: EdgeClass, visible: bool) -> String {
    format!(
        "{}-{}",
        if visible { "visible" } else { "hidden" },
        class.name()
    )
}

fn element_children<'a, 'i>(node: roxmltree::Node<'a, 'i>) -> Vec<roxmltree::Node<'a, 'i>> {
    node.children().filter(|n| n.is_element()).collect()
}

/// `matrix(a b c d e f)` as its six numbers.
fn matrix(transform: &str) -> [f64; 6] {
    let inner = transform
        .strip_prefix("matrix(")
        .and_then(|t| t.strip_suffix(')'))
        .unwrap_or_else(|| panic!("transform {transform:?}"));
    let v: Vec<f64> = inner.split_ascii_whitespace().map(number).collect();
    v.try_into().expect("six numbers")
}

fn no_nan_or_inf(text: &str) {
    let lower = text.to_ascii_lowercase();
    assert!(!lower.contains("nan"), "NaN in {text}");
    assert!(!lower.contains("inf"), "inf in {text}");
}

/// What the SVG says: its page transform, and its layers' ids, attributes and polylines.
struct Svg {
    /// The layers' page transform (the same in each), if there are layers.
    matrix: Option<[f64; 6]>,
    layers: Vec<Layer>,
}

struct Layer {
    id: String,
    stroke_width: f64,
    dasharray: Option<Vec<f64>>,
    paths: Vec<Vec<[f64; 2]>>,
}

/// Parses and checks the document's structure.
fn read_svg(text: &str, options: &SvgOptions) -> Svg {
    no_nan_or_inf(text);
    let doc = roxmltree::Document::parse(text).expect("well-formed XML");
    let root = doc.root_element();
    assert_eq!(root.tag_name().name(), "svg");
    assert_eq!(root.tag_name().namespace(), Some(SVG_NS));
    let [w, h] = options.page;
    assert_eq!(root.attribute("width"), Some(format!("{w}mm").as_str()));
    assert_eq!(root.attribute("height"), Some(format!("{h}mm").as_str()));
    assert_eq!(
        root.attribute("viewBox"),
        Some(format!("0 0 {w} {h}").as_str())
    );

    // The layers are the root's children, each an Inkscape layer with the same transform.
    let groups = element_children(root);
    let mut matrices = Vec::new();
    let layers = groups
        .into_iter()
        .map(|g| {
            assert_eq!(g.tag_name().name(), "g");
            assert_eq!(g.tag_name().namespace(), Some(SVG_NS));
            assert_eq!(g.attribute("fill"), Some("none"));
            assert_eq!(g.attribute("stroke-linecap"), Some("round"));
            assert_eq!(g.attribute("stroke-linejoin"), Some("round"));
            let id = g.attribute("id").expect("a layer id").to_string();
            assert_eq!(g.attribute((INKSCAPE_NS, "groupmode")), Some("layer"));
            assert_eq!(
                g.attribute((INKSCAPE_NS, "label")),
                Some(id.replacen('-', " ", 1).as_str())
            );
            matrices.push(matrix(g.attribute("transform").expect("a transform")));
            let paths = element_children(g)
                .into_iter()
                .map(|p| {
                    assert_eq!(p.tag_name().name(), "path", "only paths in a layer");
                    assert!(element_children(p).is_empty());
                    path_points(p.attribute("d").expect("d"))
                })
                .collect();
            Layer {
                id,
                stroke_width: number(g.attribute("stroke-width").expect("a stroke width")),
                dasharray: g
                    .attribute("stroke-dasharray")
                    .map(|d| d.split_ascii_whitespace().map(number).collect()),
                paths,
            }
        })
        .collect();
    let matrix = matrices.first().copied();
    assert!(
        matrices.iter().all(|m| Some(*m) == matrix),
        "one page transform"
    );
    Svg { matrix, layers }
}

/// The SVG's layers hold exactly the JSON's polylines (non-empty ones), in the expected layer
/// order, each layer's paths in the drawing's order, all coordinates exact.
fn check_round_trip(d: &Drawing, options: &SvgOptions) -> Svg {
    let svg = read_svg(&svg_text(d, options), options);
    let json = json_polylines(&json_text(d));

    // The JSON is the drawing, exactly.
    assert_eq!(json.len(), d.polylines.len());
    for (j, p) in json.iter().zip(&d.polylines) {
        assert_eq!((j.class, j.visible), (p.class, p.visible));
        assert!(
            same_points(&j.points, &p.points),
            "{:?} vs {:?}",
            j.points,
            p.points
        );
    }

    let mut expected_ids = Vec::new();
    for visible in [false, true] {
        for class in EdgeClass::ALL {
            let from_json: Vec<&Polyline> = json
                .iter()
                .filter(|p| p.class == class && p.visible == visible && !p.points.is_empty())
                .collect();
            if from_json.is_empty() {
                continue;
            }
            let id = layer_id(class, visible);
            let layer = svg
                .layers
                .iter()
                .find(|l| l.id == id)
                .unwrap_or_else(|| panic!("no layer {id}"));
            assert_eq!(layer.paths.len(), from_json.len(), "layer {id}");
            for (path, p) in layer.paths.iter().zip(&from_json) {
                assert!(
                    same_points(path, &p.points),
                    "{id}: {path:?} vs {:?}",
                    p.points
                );
            }
            expected_ids.push(id);
        }
    }
    let ids: Vec<&str> = svg.layers.iter().map(|l| l.id.as_str()).collect();
    assert_eq!(ids, expected_ids, "layers and their order");
    svg
}

#[test]
fn awkward_coordinates_round_trip_through_svg_and_json() {
    let d = awkward();
    let svg = check_round_trip(&d, &SvgOptions::default());
    let ids: Vec<&str> = svg.layers.iter().map(|l| l.id.as_str()).collect();
    assert_eq!(
        ids,
        [
            "hidden-smooth",
            "hidden-crease",
            "hidden-silhouette",
            "visible-crease",
            "visible-boundary",
            "visible-silhouette",
        ]
    );
    // The closed polylines keep their repeated last point.
    let boundary = &svg.layers[4].paths[0];
    assert_eq!(boundary.len(), 5);
    assert_eq!(boundary[0], boundary[4]);
}

#[test]
fn every_class_and_visibility_gets_its_layer() {
    let mut polylines = Vec::new();
    for (i, class) in EdgeClass::ALL.into_iter().enumerate() {
        for visible in [true, false] {
            let y = i as f64 + if visible { 0.5 } else { 0.0 };
            polylines.push(line(class, visible, &[[0.0, y], [1.0, y + 0.25]]));
            polylines.push(line(class, visible, &[[2.0, y], [3.0, y], [2.5, y + 0.1]]));
        }
    }
    let d = drawing(polylines);
    let options = SvgOptions::default();
    let svg = check_round_trip(&d, &options);
    let ids: Vec<String> = svg.layers.iter().map(|l| l.id.clone()).collect();
    let expected: Vec<String> = [false, true]
        .into_iter()
        .flat_map(|v| EdgeClass::ALL.into_iter().map(move |c| layer_id(c, v)))
        .collect();
    assert_eq!(ids, expected);
    assert_eq!(
        &ids[5..],
        [
            "visible-smooth",
            "visible-crease",
            "visible-intersection",
            "visible-boundary",
            "visible-silhouette"
        ]
    );
}

#[test]
fn stroke_widths_and_dashes_are_millimetres_on_the_page() {
    let options = SvgOptions {
        stroke: StrokeWidths {
            silhouette: 0.7,
            boundary: 0.6,
            crease: 0.4,
            intersection: 0.3,
            smooth: 0.1,
        },
        hidden_dash: [2.0, 0.75],
        ..SvgOptions::default()
    };
    for d in [awkward(), plain()] {
        let svg = check_round_trip(&d, &options);
        let s = svg.matrix.expect("layers")[0];
        for layer in &svg.layers {
            let class = EdgeClass::ALL
                .into_iter()
                .find(|c| layer.id.ends_with(c.name()))
                .expect("a class");
            let mm = layer.stroke_width * s;
            assert!(
                (mm - options.stroke.get(class)).abs() < 1e-12,
                "{}: {mm} mm",
                layer.id
            );
            if layer.id.starts_with("hidden-") {
                let dash = layer.dasharray.as_ref().expect("hidden layers are dashed");
                assert_eq!(dash.len(), 2);
                assert!((dash[0] * s - 2.0).abs() < 1e-12);
                assert!((dash[1] * s - 0.75).abs() < 1e-12);
            } else {
                assert!(layer.id.starts_with("visible-"));
                assert!(layer.dasharray.is_none(), "{} is dashed", layer.id);
            }
        }
    }
}

#[test]
fn hidden_lines_are_lighter_than_visible_ones() {
    let text = svg_text(&plain(), &SvgOptions::default());
    let doc = roxmltree::Document::parse(&text).expect("XML");
    let colour = |id: &str| {
        doc.descendants()
            .find(|n| n.attribute("id") == Some(id))
            .and_then(|n| n.attribute("stroke"))
            .map(str::to_string)
    };
    let visible = colour("visible-intersection").expect("a visible colour");
    let hidden = colour("hidden-smooth").expect("a hidden colour");
    let grey = |c: &str| -> u32 {
        let c = c.strip_prefix('#').expect("#rrggbb");
        (0..3)
            .map(|i| u32::from_str_radix(&c[2 * i..2 * i + 2], 16).expect("hex"))
            .sum()
    };
    assert!(grey(&hidden) > grey(&visible), "{hidden} vs {visible}");
}

/// The drawing's bounds, mapped by the SVG's matrix, lie inside the page less the margins,
/// touch them on both sides along one axis, and are centred.
fn check_layout(d: &Drawing, options: &SvgOptions) {
    let svg = read_svg(&svg_text(d, options), options);
    let [a, b, c, dd, e, f] = svg.matrix.expect("layers");
    assert_eq!((b, c), (0.0, 0.0));
    assert_eq!(dd, -a, "uniform scale with y flipped");
    assert!(a > 0.0 && a.is_finite());
    let t = page_transform(d, options);
    assert_eq!(
        t,
        PageTransform {
            scale: a,
            tx: e,
            ty: f
        }
    );

    let (lo, hi) = d.bounds().expect("a non-empty drawing");
    let map = |p: [f64; 2]| [a * p[0] + c * p[1] + e, b * p[0] + dd * p[1] + f];
    let m = options.margin;
    let [w, h] = options.page;
    let eps = 1e-9;
    for corner in [lo, hi, [lo[0], hi[1]], [hi[0], lo[1]]] {
        let q = map(corner);
        assert_eq!(q, t.to_page(corner));
        assert!(q[0] >= m - eps && q[0] <= w - m + eps, "{corner:?} ↦ {q:?}");
        assert!(q[1] >= m - eps && q[1] <= h - m + eps, "{corner:?} ↦ {q:?}");
    }
    let (plo, phi) = (map(lo), map(hi));
    // y is flipped: the bottom of the drawing is lower on the page.
    assert!(plo[1] >= phi[1]);
    assert!(plo[0] <= phi[0]);
    // Centred.
    assert!(((plo[0] + phi[0]) / 2.0 - w / 2.0).abs() < eps);
    assert!(((plo[1] + phi[1]) / 2.0 - h / 2.0).abs() < eps);
    // Tight along one axis.
    let fills_x = (plo[0] - m).abs() < eps && (phi[0] - (w - m)).abs() < eps;
    let fills_y = (phi[1] - m).abs() < eps && (plo[1] - (h - m)).abs() < eps;
    assert!(fills_x || fills_y, "{plo:?} {phi:?} do not fill the page");
    // Aspect preserved: the mapped box has the drawing's proportions.
    let (dw, dh) = (hi[0] - lo[0], hi[1] - lo[1]);
    let (pw, ph) = (phi[0] - plo[0], plo[1] - phi[1]);
    assert!((pw * dh - ph * dw).abs() <= 1e-9 * (pw * dh).abs().max((ph * dw).abs()));
}

#[test]
fn the_page_transform_fits_the_drawing_inside_the_margins() {
    let a4 = SvgOptions::default();
    let portrait = SvgOptions {
        page: [210.0, 297.0],
        margin: 25.0,
        ..SvgOptions::default()
    };
    let no_margin = SvgOptions {
        page: [100.0, 100.0],
        margin: 0.0,
        ..SvgOptions::default()
    };
    let tall = drawing(vec![line(
        EdgeClass::Crease,
        true,
        &[[10.0, -40.0], [11.0, 60.0], [10.5, 0.0]],
    )]);
    let vertical = drawing(vec![line(
        EdgeClass::Crease,
        false,
        &[[1.0, 1.0], [1.0, 3.0]],
    )]);
    let horizontal = drawing(vec![line(
        EdgeClass::Smooth,
        true,
        &[[-1.0, 7.0], [4.0, 7.0]],
    )]);
    for options in [a4, portrait, no_margin] {
        for d in [
            awkward(),
            plain(),
            tall.clone(),
            vertical.clone(),
            horizontal.clone(),
        ] {
            check_layout(&d, &options);
        }
    }
    // A known case: 8 wide and 2 high on A4 landscape, scale 277 / 8.
    let t = page_transform(&plain(), &a4);
    assert_eq!(t.scale, 277.0 / 8.0);
    assert_eq!(t.to_page([-3.0, 2.5]), [10.0, 105.0 - 277.0 / 8.0]);
}

#[test]
fn degenerate_drawings_give_valid_svg() {
    let options = SvgOptions::default();
    let empty = drawing(Vec::new());
    let text = svg_text(&empty, &options);
    let svg = read_svg(&text, &options);
    assert!(svg.layers.is_empty());
    assert_eq!(svg.matrix, None);
    let t = page_transform(&empty, &options);
    assert_eq!((t.scale, t.tx, t.ty), (1.0, 148.5, 105.0));
    assert_eq!(json_text(&empty), "{\"polylines\":[]}\n");

    let point = drawing(vec![
        line(EdgeClass::Silhouette, true, &[[3.0, -4.0], [3.0, -4.0]]),
        line(EdgeClass::Boundary, false, &[[3.0, -4.0]]),
    ]);
    let svg = check_round_trip(&point, &options);
    assert_eq!(svg.layers.len(), 2);
    let t = page_transform(&point, &options);
    assert_eq!(t.to_page([3.0, -4.0]), [148.5, 105.0]);
    assert_eq!(t.scale, 1.0);
}

#[test]
fn extreme_extents_stay_finite() {
    let options = SvgOptions::default();
    let cases = [
        vec![[0.0, 0.0], [5e-324, 0.0]],
        vec![[0.0, 0.0], [1e-310, 1e-310]],
        vec![[-f64::MAX, 0.0], [f64::MAX, 1.0]],
        vec![[-f64::MAX, -f64::MAX], [f64::MAX, f64::MAX]],
        vec![[1e300, 1e300], [1e300, 1e300]],
    ];
    for points in cases {
        let d = drawing(vec![
            line(EdgeClass::Silhouette, true, &points),
            line(EdgeClass::Smooth, false, &points),
        ]);
        let svg = check_round_trip(&d, &options);
        let matrix = svg.matrix.expect("layers");
        assert!(matrix.iter().all(|v| v.is_finite()), "{points:?}");
        assert!(matrix[0] > 0.0);
        for layer in &svg.layers {
            assert!(layer.stroke_width.is_finite());
        }
        no_nan_or_inf(&json_text(&d));
    }
}

#[test]
fn empty_polylines_are_left_out_of_the_svg() {
    let d = drawing(vec![
        line(EdgeClass::Crease, true, &[]),
        line(EdgeClass::Boundary, true, &[[0.0, 0.0], [1.0, 1.0]]),
        line(EdgeClass::Boundary, true, &[]),
    ]);
    let svg = check_round_trip(&d, &SvgOptions::default());
    let ids: Vec<&str> = svg.layers.iter().map(|l| l.id.as_str()).collect();
    assert_eq!(ids, ["visible-boundary"]);
    assert_eq!(svg.layers[0].paths.len(), 1);
    assert_eq!(json_polylines(&json_text(&d)).len(), 3);
}

#[test]
fn bad_input_is_an_error_not_nan() {
    for bad in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
        let d = drawing(vec![line(
            EdgeClass::Smooth,
            true,
            &[[0.0, 0.0], [1.0, bad]],
        )]);
        let mut out = Vec::new();
        let err = write_svg(&d, &SvgOptions::default(), &mut out).expect_err("svg");
        assert_eq!(err.kind(), ErrorKind::InvalidData);
        let err = write_json(&d, &mut out).expect_err("json");
        assert_eq!(err.kind(), ErrorKind::InvalidData);
    }
    let d = plain();
    let default = SvgOptions::default();
    let bad_options = [
        SvgOptions {
            page: [0.0, 210.0],
            ..default
        },
        SvgOptions {
            page: [297.0, f64::NAN],
            ..default
        },
        SvgOptions {
            page: [-297.0, 210.0],
            ..default
        },
        SvgOptions {
            margin: -1.0,
            ..default
        },
        SvgOptions {
            margin: 105.0,
            ..default
        },
        SvgOptions {
            margin: f64::INFINITY,
            ..default
        },
        SvgOptions {
            hidden_dash: [0.0, 1.0],
            ..default
        },
        SvgOptions {
            hidden_dash: [1.0, f64::NAN],
            ..default
        },
        SvgOptions {
            stroke: StrokeWidths {
                crease: -0.1,
                ..StrokeWidths::default()
            },
            ..default
        },
        SvgOptions {
            stroke: StrokeWidths {
                smooth: f64::INFINITY,
                ..StrokeWidths::default()
            },
            ..default
        },
    ];
    for options in bad_options {
        let mut out = Vec::new();
        let err = write_svg(&d, &options, &mut out).expect_err("bad options");
        assert_eq!(err.kind(), ErrorKind::InvalidInput, "{options:?}");
        assert!(out.is_empty(), "nothing written for {options:?}");
    }
    // A stroke too wide to express in view units at a tiny scale.
    let huge = drawing(vec![line(
        EdgeClass::Smooth,
        true,
        &[[-f64::MAX, 0.0], [f64::MAX, 0.0]],
    )]);
    let wide = SvgOptions {
        stroke: StrokeWidths {
            smooth: 1e10,
            ..StrokeWidths::default()
        },
        ..default
    };
    let err = write_svg(&huge, &wide, &mut Vec::new()).expect_err("overflow");
    assert_eq!(err.kind(), ErrorKind::InvalidInput);
}
