//! The quick error report (issue 15), run whole: the exact engine has no error on any case
//! (against the rational reference where the scene is small, and by its own checks), every
//! other variant runs and has finite figures, some of them go wrong (the measures have
//! teeth), and the table, the JSON and the files written agree.

use kepler::lab::report::{Report, Settings};
use std::collections::BTreeMap;

/// Run in the same process as every other test of the crate, on threads beside theirs: the
/// report's cheaper arithmetic runs on threads of its own (`kepler::geometry::arithmetic`), so
/// the exact tests running meanwhile stay exact (before issue 28 it switched the arithmetic of
/// the whole process, and 14 tests beside it failed).
#[test]
fn the_quick_report_measures_every_variant() {
    let settings = Settings::quick(concat!(env!("CARGO_MANIFEST_DIR"), "/scenes"));
    let report = Report::run(&settings, &|_, _, _| {}).unwrap();
    assert!(report.cases.len() >= 30, "{} cases", report.cases.len());
    let mut referenced = 0;
    let mut wrong_kinds = BTreeMap::new();
    for case in &report.cases {
        let exact = &case.runs[0];
        assert_eq!(exact.kind, "exact", "{}", case.name);
        assert_eq!(exact.failure, None, "{}", case.name);
        assert_eq!(
            case.disagreements, 0,
            "{}: the engine's checks disagree",
            case.name
        );
        assert!(case.checks > 0, "{}: nothing checked", case.name);
        assert!(case.filter_calls >= case.exact_path, "{}", case.name);
        if let Some(f) = exact.figures {
            referenced += 1;
            assert_eq!(
                f.relative, 0.0,
                "{}: exact against the rational reference: {f:?}",
                case.name
            );
        }
        for run in &case.runs[1..] {
            match (&run.failure, run.figures) {
                (Some(_), _) => {
                    *wrong_kinds.entry(run.kind.clone()).or_insert(0) += 1;
                }
                (None, Some(f)) => {
                    let seconds = run.seconds.unwrap_or(f64::NAN);
                    assert!(
                        seconds.is_finite() && seconds >= 0.0,
                        "{} {}",
                        case.name,
                        run.variant
                    );
                    for x in [f.relative, f.misclassified, f.missing, f.extra] {
                        assert!(
                            x.is_finite() && x >= 0.0,
                            "{} {}: {f:?}",
                            case.name,
                            run.variant
                        );
                    }
                    if f.is_wrong() {
                        *wrong_kinds.entry(run.kind.clone()).or_insert(0) += 1;
                    }
                }
                (None, None) => panic!("{} {}: no figures", case.name, run.variant),
            }
        }
    }
    assert!(
        referenced >= 20,
        "only {referenced} cases checked against the reference"
    );
    // The cheap variants are measured, not assumed right: each kind goes wrong somewhere.
    for kind in ["float", "epsilon", "f32", "sampled", "raster"] {
        assert!(
            wrong_kinds.get(kind).is_some_and(|&n| n > 0),
            "{kind} never wrong: {wrong_kinds:?}"
        );
    }

    // The JSON holds the whole report, and the table is rebuilt from it.
    let back = Report::from_json(&report.json()).unwrap();
    assert_eq!(back, report);
    let table = report.markdown();
    assert_eq!(back.markdown(), table);
    // Each family's "first wrong" column, recomputed here from the data.
    for family in ["tilt", "offset", "scale"] {
        let cases: Vec<_> = report.cases.iter().filter(|c| c.family == family).collect();
        let row = |variant: &str| -> Vec<String> {
            let section = table.split(&format!("## {family}\n")).nth(1).unwrap();
            let line = section
                .lines()
                .find(|l| l.starts_with(&format!("| {variant} |")))
                .unwrap();
            line.split('|').map(|c| c.trim().to_string()).collect()
        };
        let first_wrong = |variant: &str| {
            cases
                .iter()
                .find(|c| {
                    c.runs.iter().any(|r| {
                        r.variant == variant
                            && (r.failure.is_some()
                                || if r.kind == "exact" {
                                    c.disagreements > 0
                                        || r.figures.is_some_and(|f| f.relative > 0.0)
                                } else {
                                    r.figures.is_some_and(|f| f.is_wrong())
                                })
                    })
                })
                .map_or("–".to_string(), |c| format!("k={}", c.parameter.unwrap()))
        };
        for variant in ["exact", "float", "epsilon 1e-6", "f32"] {
            let cells = row(variant);
            assert_eq!(
                cells[cells.len() - 3],
                first_wrong(variant),
                "{family} {variant}"
            );
        }
    }

    // The files.
    let dir = std::env::temp_dir().join(format!("kepler-report-{}", std::process::id()));
    let written = report.write(&dir).unwrap();
    assert_eq!(
        std::fs::read_to_string(dir.join("index.md")).unwrap(),
        table
    );
    let json = std::fs::read_to_string(dir.join("report.json")).unwrap();
    assert_eq!(Report::from_json(&json).unwrap(), report);
    let charts: Vec<_> = written
        .iter()
        .filter(|p| p.extension().is_some_and(|e| e == "svg"))
        .collect();
    assert!(charts.len() >= 10, "{written:?}");
    for chart in charts {
        let svg = std::fs::read_to_string(chart).unwrap();
        roxmltree::Document::parse(&svg).unwrap_or_else(|e| panic!("{}: {e}", chart.display()));
        assert!(
            table.contains(chart.file_name().unwrap().to_str().unwrap()),
            "{}",
            chart.display()
        );
    }
    std::fs::remove_dir_all(&dir).unwrap();
}
