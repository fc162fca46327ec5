//! The error measures on small drawings and on drawings of the engine.

use super::*;
use crate::geometry::{Point3, Vector3};
use crate::hidden::{EdgeClass, EdgeSelection, Options, Polyline, draw};
use crate::views::View;

fn line(visible: bool, points: &[[f64; 2]]) -> Polyline {
    Polyline {
        class: EdgeClass::Crease,
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

fn all_zero(e: &ErrorFigures) {
    assert!(e.is_exact(), "{e:?}");
    assert_eq!(
        (e.misclassified(), e.wrong_length(), e.relative()),
        (0.0, 0.0, 0.0),
        "{e:?}"
    );
    assert_eq!(e.hausdorff_ulps, 0.0, "{e:?}");
}

#[test]
fn half_hidden() {
    let exact = drawing(vec![line(true, &[[0.0, 0.0], [10.0, 0.0]])]);
    let variant = drawing(vec![
        line(true, &[[0.0, 0.0], [5.0, 0.0]]),
        line(false, &[[5.0, 0.0], [10.0, 0.0]]),
    ]);
    let e = compare(&exact, &variant, 0.0);
    assert_eq!(e.exact_length, 10.0);
    assert_eq!((e.visible_as_hidden, e.hidden_as_visible), (5.0, 0.0));
    assert_eq!((e.missing, e.extra), (0.0, 0.0));
    // The variant's vertex at (5, 0), where its visibility changes, is 5 from the nearest
    // exact vertex.
    assert_eq!(e.hausdorff, 5.0);
    assert_eq!(e.relative(), 0.5);
    // Unmatched: the variant's visible end at (5, 0) and its hidden ends at (5, 0) and
    // (10, 0); the exact visible end at (10, 0).
    assert_eq!((e.wrong_ends, e.runs), (4, [1, 2]));
    // With a tolerance r, the visible run's capsule reaches r past (5, 0): that much of
    // the hidden half counts as covered by both, so as not misclassified.
    let r = 0.25;
    let e = compare(&exact, &variant, r);
    assert!((e.visible_as_hidden - (5.0 - r)).abs() < 1e-12, "{e:?}");
    // Back: the hidden half of an exact hidden line drawn visible.
    let exact = drawing(vec![line(false, &[[0.0, 0.0], [10.0, 0.0]])]);
    let e = compare(&exact, &variant, 0.0);
    assert_eq!((e.visible_as_hidden, e.hidden_as_visible), (0.0, 5.0));
}

#[test]
fn missing_and_extra_segments() {
    let one = drawing(vec![line(true, &[[0.0, 0.0], [10.0, 0.0]])]);
    let two = drawing(vec![
        line(true, &[[0.0, 0.0], [10.0, 0.0]]),
        line(false, &[[0.0, 5.0], [3.0, 9.0]]),
    ]);
    let e = compare(&two, &one, 0.5);
    assert_eq!((e.exact_length, e.missing, e.extra), (15.0, 5.0, 0.0));
    assert_eq!((e.misclassified(), e.wrong_ends), (0.0, 2));
    assert!((e.hausdorff - 90f64.sqrt()).abs() < 1e-12, "{e:?}");
    assert_eq!(e.relative(), 5.0 / 15.0);
    let e = compare(&one, &two, 0.5);
    assert_eq!((e.exact_length, e.missing, e.extra), (10.0, 0.0, 5.0));
    assert_eq!((e.misclassified(), e.wrong_ends), (0.0, 2));
    assert_eq!(e.relative(), 0.5);
}

#[test]
fn shifted_segment() {
    let exact = drawing(vec![line(true, &[[0.0, 0.0], [10.0, 0.0]])]);
    let variant = drawing(vec![line(true, &[[0.0, 3.0], [10.0, 3.0]])]);
    let e = compare(&exact, &variant, 0.5);
    assert_eq!((e.missing, e.extra, e.misclassified()), (10.0, 10.0, 0.0));
    assert_eq!((e.hausdorff, e.wrong_ends), (3.0, 4));
    // The largest exact coordinate is 10, whose ulp is 2^-49.
    assert_eq!(e.hausdorff_ulps, 3.0 * 2f64.powi(49));
}

#[test]
fn shift_below_tolerance() {
    let exact = drawing(vec![
        line(true, &[[0.0, 0.0], [10.0, 0.0], [10.0, 10.0]]),
        line(false, &[[10.0, 10.0], [0.0, 0.0]]),
    ]);
    let shift = [3e-6, -4e-6];
    let variant = drawing(
        exact
            .polylines
            .iter()
            .map(|p| Polyline {
                points: p
                    .points
                    .iter()
                    .map(|q| [q[0] + shift[0], q[1] + shift[1]])
                    .collect(),
                ..p.clone()
            })
            .collect(),
    );
    let e = compare(&exact, &variant, 1e-5);
    assert_eq!((e.visible_as_hidden, e.hidden_as_visible), (0.0, 0.0));
    assert_eq!((e.missing, e.extra, e.wrong_ends), (0.0, 0.0, 0));
    assert!((e.hausdorff - 5e-6).abs() < 1e-15, "{e:?}");
    assert!(e.hausdorff_ulps > 0.0 && !e.is_exact());
}

#[test]
fn split_run() {
    let exact = drawing(vec![line(true, &[[0.0, 0.0], [10.0, 0.0]])]);
    let variant = drawing(vec![
        line(true, &[[0.0, 0.0], [5.0, 0.0]]),
        line(true, &[[5.0, 0.0], [10.0, 0.0]]),
    ]);
    let e = compare(&exact, &variant, default_tolerance(&exact));
    assert_eq!(e.wrong_length(), 0.0);
    assert_eq!((e.hausdorff, e.wrong_ends, e.runs), (5.0, 2, [1, 2]));
}

#[test]
fn chaining_does_not_count() {
    // Two edges meeting at (5, 0), chained into one polyline or drawn apart.
    let exact = drawing(vec![line(true, &[[0.0, 0.0], [5.0, 0.0], [5.0, 4.0]])]);
    let variant = drawing(vec![
        line(true, &[[5.0, 4.0], [5.0, 0.0]]),
        line(true, &[[0.0, 0.0], [5.0, 0.0]]),
    ]);
    all_zero(&compare(&exact, &variant, default_tolerance(&exact)));
}

#[test]
fn crossing_segments_do_not_cover() {
    let exact = drawing(vec![line(true, &[[0.0, 0.0], [16.0, 0.0]])]);
    let variant = drawing(vec![line(true, &[[8.0, -8.0], [8.0, 8.0]])]);
    // Each covers the other on [7.75, 8.25], within 0.25 of the crossing.
    let e = compare(&exact, &variant, 0.25);
    assert_eq!((e.missing, e.extra, e.misclassified()), (15.5, 15.5, 0.0));
    assert_eq!(e.wrong_ends, 4);
}

#[test]
fn reversed_and_reordered() {
    let exact = drawing(vec![
        line(true, &[[0.1, 0.3], [10.7, 0.2], [10.0, 10.9], [0.1, 0.3]]),
        line(false, &[[0.3, 0.7], [5.1, -3.3]]),
        line(true, &[[0.3, 0.7], [-2.9, 1.0 / 3.0], [7.0, 1e-3]]),
    ]);
    let mut variant = exact.clone();
    variant.polylines.reverse();
    for p in &mut variant.polylines {
        p.points.reverse();
    }
    for tolerance in [0.0, 1e-12, default_tolerance(&exact), 0.5] {
        all_zero(&compare(&exact, &variant, tolerance));
        all_zero(&compare(&variant, &exact, tolerance));
    }
}

#[test]
fn closed_runs_have_no_ends() {
    let square = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0], [0.0, 0.0]];
    let rotated = [[1.0, 1.0], [0.0, 1.0], [0.0, 0.0], [1.0, 0.0], [1.0, 1.0]];
    let e = compare(
        &drawing(vec![line(true, &square)]),
        &drawing(vec![line(true, &rotated)]),
        0.0,
    );
    all_zero(&e);
}

#[test]
fn empty_and_degenerate() {
    let empty = drawing(Vec::new());
    let one = drawing(vec![line(false, &[[1.0, 2.0], [1.0, 2.0], [4.0, 6.0]])]);
    let e = compare(&empty, &one, 0.0);
    assert_eq!(
        (e.extra, e.hausdorff, e.hausdorff_ulps),
        (5.0, f64::INFINITY, f64::INFINITY)
    );
    assert_eq!(e.relative(), f64::INFINITY);
    let e = compare(&one, &empty, 0.0);
    assert_eq!(
        (e.exact_length, e.missing, e.hausdorff),
        (5.0, 5.0, f64::INFINITY)
    );
    all_zero(&compare(&one, &one, f64::NAN));
    all_zero(&compare(&one, &one, -1.0));
    let broken = drawing(vec![line(true, &[[0.0, 0.0], [f64::NAN, 1.0]])]);
    let e = compare(&one, &broken, 0.1);
    assert_eq!((e.extra, e.hausdorff), (f64::INFINITY, f64::INFINITY));
    assert_eq!((e.misclassified(), e.missing), (0.0, 5.0));
    let e = compare(&broken, &one, 0.1);
    assert_eq!((e.exact_length, e.missing), (f64::INFINITY, f64::INFINITY));
    assert_eq!((e.misclassified(), e.extra), (0.0, 5.0));
    assert_eq!(default_tolerance(&empty), 16.0 * f64::from_bits(1));
    let point = drawing(vec![line(true, &[[1.0, 1.0], [1.0, 1.0]])]);
    assert_eq!(default_tolerance(&point), 16.0 * 2f64.powi(-52));
    assert_eq!(default_tolerance(&one), 5.0 * 2f64.powi(-40));
}

/// A real drawing against itself and against its reversal: every figure exactly 0.
#[test]
fn self_comparison_of_drawings() {
    let options = Options {
        edges: EdgeSelection::All,
        ..Default::default()
    };
    let orthographic = |x, y, z| View::orthographic(Vector3::new(x, y, z), Vector3::z());
    let cases = [
        ("polyhedra", orthographic(1.0, 2.0, -3.0)),
        ("polyhedra", orthographic(-1.0, -2.0, -1.5)),
        ("polyhedra", orthographic(0.3, -0.7, 0.2)),
        (
            "polyhedra",
            View::perspective(
                Point3::new(20.0, -15.0, 10.0),
                Point3::new(20.0, 5.0, 0.0),
                Vector3::z(),
                60.0,
            ),
        ),
        ("solids", orthographic(-1.0, -2.0, -3.0)),
    ];
    for (name, view) in cases {
        let path = format!("scenes/{name}.toml");
        let scene = crate::scene::file::load(path.as_ref()).unwrap();
        let exact = draw(&scene, &view.unwrap(), &options).unwrap();
        assert!(exact.polylines.iter().any(|p| p.visible));
        assert!(exact.polylines.iter().any(|p| !p.visible));
        let tolerance = default_tolerance(&exact);
        let e = compare(&exact, &exact, tolerance);
        all_zero(&e);
        assert!(e.exact_length > 0.0);
        assert_eq!(e.runs[0], exact.polylines.len());
        let mut reversed = exact.clone();
        reversed.polylines.reverse();
        for p in &mut reversed.polylines {
            p.points.reverse();
        }
        all_zero(&compare(&exact, &reversed, tolerance));
        // Hiding one visible run shows as exactly its length drawn hidden.
        let mut one_hidden = exact.clone();
        let k = one_hidden.polylines.iter().position(|p| p.visible).unwrap();
        one_hidden.polylines[k].visible = false;
        let e = compare(&exact, &one_hidden, tolerance);
        let length = exact.polylines[k].length();
        assert!(e.visible_as_hidden <= length, "{e:?}");
        assert!(e.visible_as_hidden > 0.5 * length, "{e:?}");
        assert_eq!((e.hidden_as_visible, e.missing, e.extra), (0.0, 0.0, 0.0));
    }
}
