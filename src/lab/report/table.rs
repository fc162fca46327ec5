//! The report as Markdown tables, JSON and charts: everything here is computed from the
//! [`Report`]'s data alone, so the table rebuilt from `report.json` is the same table.

use super::chart::{self, ChartError, Series};
use super::{CaseReport, Report, VariantRun};
use std::collections::BTreeMap;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

/// Why the report could not be written.
#[derive(Debug, thiserror::Error)]
pub enum WriteError {
    /// A file could not be written.
    #[error("cannot write {path}: {source}")]
    Io {
        /// The file.
        path: PathBuf,
        /// Why.
        source: std::io::Error,
    },
    /// A chart could not be drawn.
    #[error("cannot draw a chart: {0}")]
    Chart(#[from] ChartError),
}

/// The relative error a failed run counts as in charts: the whole drawing wrong.
const FAILED: f64 = 1.0;

/// Writes `index.md`, `report.json`, `error-vs-time.svg` and one `stiffness-FAMILY.svg` per
/// stiff family into `dir`.
pub(super) fn write(report: &Report, dir: &Path) -> Result<Vec<PathBuf>, WriteError> {
    let io = |path: &Path| {
        let path = path.to_path_buf();
        move |source| WriteError::Io { path, source }
    };
    std::fs::create_dir_all(dir).map_err(io(dir))?;
    let mut written = Vec::new();
    for (name, text) in [
        ("index.md", markdown(report)),
        ("report.json", report.json()),
    ] {
        let path = dir.join(name);
        std::fs::write(&path, text).map_err(io(&path))?;
        written.push(path);
    }
    let path = dir.join("error-vs-time.svg");
    chart::log_log(
        &path,
        "Error against run time (all cases)",
        "total time of the variant over all cases (s)",
        "mean share of the drawing wrong",
        &time_series(report),
    )?;
    written.push(path);
    for (family, cases) in families(report) {
        if cases.iter().all(|c| c.parameter.is_none()) {
            continue;
        }
        let path = dir.join(format!("stiffness-{family}.svg"));
        chart::semi_log(
            &path,
            &format!("Error against stiffness: {family}"),
            "stiffness parameter k",
            "largest share of the drawing wrong over seeds",
            &stiffness_series(&cases),
        )?;
        written.push(path);
    }
    Ok(written)
}

/// The cases by family, in the order of first appearance.
fn families(report: &Report) -> Vec<(String, Vec<&CaseReport>)> {
    let mut order: Vec<(String, Vec<&CaseReport>)> = Vec::new();
    for case in &report.cases {
        match order.iter_mut().find(|(f, _)| *f == case.family) {
            Some((_, cases)) => cases.push(case),
            None => order.push((case.family.clone(), vec![case])),
        }
    }
    order
}

/// The variants' names in the order they ran.
fn variant_names(cases: &[&CaseReport]) -> Vec<(String, String)> {
    let mut names: Vec<(String, String)> = Vec::new();
    for run in cases.iter().flat_map(|c| &c.runs) {
        if !names.iter().any(|(n, _)| *n == run.variant) {
            names.push((run.variant.clone(), run.kind.clone()));
        }
    }
    names
}

/// A run's error as a number for charts (a failure counts as the whole drawing), or none for
/// an exact run without a reference.
fn error_of(run: &VariantRun) -> Option<f64> {
    if run.failure.is_some() {
        return Some(FAILED);
    }
    run.figures.map(|f| f.relative)
}

/// Whether a run went wrong; the exact variant when the engine's checks disagree or its
/// lengths differ from the rational reference's.
fn is_wrong(case: &CaseReport, run: &VariantRun) -> bool {
    if run.kind == "exact" {
        return run.failure.is_some()
            || case.disagreements > 0
            || run.figures.is_some_and(|f| f.relative > 0.0);
    }
    run.failure.is_some() || run.figures.is_some_and(|f| f.is_wrong())
}

/// The median of some numbers (NaN for none).
fn median(mut xs: Vec<f64>) -> f64 {
    xs.sort_by(f64::total_cmp);
    xs.get(xs.len() / 2).copied().unwrap_or(f64::NAN)
}

/// One point per variant: its total time and its mean error over the cases, grouped by kind.
fn time_series(report: &Report) -> Vec<Series> {
    let cases: Vec<&CaseReport> = report.cases.iter().collect();
    let mut series: Vec<Series> = Vec::new();
    for (name, kind) in variant_names(&cases) {
        let runs: Vec<&VariantRun> = cases
            .iter()
            .flat_map(|c| &c.runs)
            .filter(|r| r.variant == name)
            .collect();
        let time: f64 = runs.iter().filter_map(|r| r.seconds).sum();
        let errors: Vec<f64> = runs.iter().filter_map(|r| error_of(r)).collect();
        if errors.is_empty() || time <= 0.0 {
            continue;
        }
        let error = errors.iter().sum::<f64>() / errors.len() as f64;
        match series.iter_mut().find(|s| s.name == kind) {
            Some(s) => s.points.push((time, error)),
            None => series.push(Series {
                name: kind,
                points: vec![(time, error)],
            }),
        }
    }
    series
}

/// One series per variant: its largest error over seeds at each parameter.
fn stiffness_series(cases: &[&CaseReport]) -> Vec<Series> {
    variant_names(cases)
        .into_iter()
        .map(|(name, _)| {
            let mut by_k: BTreeMap<i32, f64> = BTreeMap::new();
            for case in cases {
                let (Some(k), Some(run)) =
                    (case.parameter, case.runs.iter().find(|r| r.variant == name))
                else {
                    continue;
                };
                if let Some(e) = error_of(run) {
                    let worst = by_k.entry(k).or_insert(0.0);
                    *worst = worst.max(e);
                }
            }
            Series {
                name,
                points: by_k.into_iter().map(|(k, e)| (f64::from(k), e)).collect(),
            }
        })
        .collect()
}

/// A share as the tables print it.
fn share(x: f64) -> String {
    if x == 0.0 {
        "0".to_string()
    } else {
        format!("{x:.1e}")
    }
}

/// The report as Markdown.
pub(super) fn markdown(report: &Report) -> String {
    let mut out = String::new();
    let runs = report.cases.first().map_or(0, |c| c.runs.len());
    let _ = writeln!(out, "# Error against run time\n");
    let _ = writeln!(
        out,
        "The {} report: {} cases, {} variants each. Rebuild with `cargo run --release -- report{}`.\n",
        if report.quick { "quick" } else { "full" },
        report.cases.len(),
        runs,
        if report.quick { " --quick" } else { "" },
    );
    let _ = writeln!(
        out,
        "Each cell is the share of the exact drawing's length that the variant draws wrong \
         (with the wrong visibility, missing, or extra; lines within 2^-40 of the drawing's size \
         of each other count as the same), the largest over seeds; `fail` when a run panicked, \
         refused the scene or ran out of time; `*` marks runs whose lengths are right but whose \
         run ends or vertices are misplaced (more than 4 ulps; `f32` is compared within 16 of \
         its own ulps, so that its rounding alone shows only in the vertex distance). For \
         `exact`, the error is against the rational reference where the scene is small enough \
         (`–` where it is not), judged by length, and `*` marks a disagreement of the engine's \
         own checks. *First wrong* is the first parameter at which \
         the variant goes wrong; *time* is the median over the family's cases of its time over \
         the exact engine's.\n"
    );
    let _ = writeln!(out, "![error against run time](error-vs-time.svg)\n");
    for (family, cases) in families(report) {
        family_table(&mut out, &family, &cases);
    }
    cost_table(&mut out, report);
    out
}

/// The table of one family.
fn family_table(out: &mut String, family: &str, cases: &[&CaseReport]) {
    let _ = writeln!(out, "## {family}\n");
    // Columns: the parameters in order of appearance (bundled scenes: their names).
    let mut columns: Vec<(String, Option<i32>)> = Vec::new();
    for case in cases {
        let column = match case.parameter {
            Some(k) => (format!("k={k}"), Some(k)),
            None => (case.name.clone(), None),
        };
        if !columns.contains(&column) {
            columns.push(column);
        }
    }
    let in_column = |case: &CaseReport, column: &(String, Option<i32>)| match column.1 {
        Some(k) => case.parameter == Some(k),
        None => case.name == column.0,
    };
    let _ = write!(out, "| variant |");
    for (name, _) in &columns {
        let _ = write!(out, " {name} |");
    }
    let _ = writeln!(out, " first wrong | time |");
    let _ = writeln!(out, "|---|{}---|---|", "---|".repeat(columns.len()));
    for (name, _) in variant_names(cases) {
        let _ = write!(out, "| {name} |");
        let mut first_wrong = None;
        for column in &columns {
            let mut cell_error: Option<f64> = None;
            let (mut failed, mut marked) = (false, false);
            for case in cases.iter().filter(|c| in_column(c, column)) {
                let Some(run) = case.runs.iter().find(|r| r.variant == name) else {
                    continue;
                };
                failed |= run.failure.is_some();
                if let Some(f) = run.figures {
                    cell_error = Some(cell_error.unwrap_or(0.0).max(f.relative));
                }
                marked |= is_wrong(case, run) && run.failure.is_none();
                if is_wrong(case, run) && first_wrong.is_none() {
                    first_wrong = Some(column.0.clone());
                }
            }
            let text = if failed {
                "fail".to_string()
            } else {
                let value = cell_error.map_or("–".to_string(), share);
                let exact_value = cell_error.is_some_and(|e| e == 0.0);
                if marked && exact_value {
                    format!("{value}*")
                } else {
                    value
                }
            };
            let _ = write!(out, " {text} |");
        }
        let ratios: Vec<f64> = cases
            .iter()
            .filter_map(|c| {
                let run = c.runs.iter().find(|r| r.variant == name)?;
                Some(run.seconds? / c.exact_seconds()?)
            })
            .filter(|r| r.is_finite())
            .collect();
        let time = if ratios.is_empty() {
            "–".to_string()
        } else {
            format!("{:.2}", median(ratios))
        };
        let _ = writeln!(
            out,
            " {} | {time} |",
            first_wrong.unwrap_or_else(|| "–".to_string())
        );
    }
    let _ = writeln!(out);
    if cases.iter().any(|c| c.parameter.is_some()) {
        let _ = writeln!(out, "![{family}](stiffness-{family}.svg)\n");
    }
}

/// The cost of exactness and the checks of the exact drawings, per family.
fn cost_table(out: &mut String, report: &Report) {
    let _ = writeln!(
        out,
        "## The cost of exactness, and the checks of the exact drawings\n"
    );
    let _ = writeln!(
        out,
        "Filter calls are the kernel's sign decisions; *exact path* counts those whose rounded \
         value could not certify the sign, so that exact arithmetic ran. *Checks* are the \
         engine's independent checks of its exact drawing (`render --verify`); *reference* \
         counts the cases also drawn by the rational brute-force reference, with the largest \
         share of the exact drawing that differs from it and the largest vertex distance.\n"
    );
    let _ = writeln!(
        out,
        "| family | cases | filter calls | exact path | share | exact time (ms, median) | checks | disagreements | reference | wrong vs reference | drift (ulps) |"
    );
    let _ = writeln!(out, "|---|---|---|---|---|---|---|---|---|---|---|");
    for (family, cases) in families(report) {
        let calls: u64 = cases.iter().map(|c| c.filter_calls).sum();
        let slow: u64 = cases.iter().map(|c| c.exact_path).sum();
        let times: Vec<f64> = cases.iter().filter_map(|c| c.exact_seconds()).collect();
        let checks: usize = cases.iter().map(|c| c.checks).sum();
        let disagreements: usize = cases.iter().map(|c| c.disagreements).sum();
        let referenced: Vec<_> = cases
            .iter()
            .filter_map(|c| c.runs.iter().find(|r| r.kind == "exact")?.figures)
            .collect();
        let wrong = referenced.iter().map(|f| f.relative).fold(0.0, f64::max);
        let drift = referenced
            .iter()
            .map(|f| f.hausdorff_ulps.unwrap_or(f64::INFINITY))
            .fold(0.0, f64::max);
        let _ = writeln!(
            out,
            "| {family} | {} | {calls} | {slow} | {} | {:.2} | {checks} | {disagreements} | {} | {} | {:.1} |",
            cases.len(),
            share(if calls == 0 {
                0.0
            } else {
                slow as f64 / calls as f64
            }),
            median(times) * 1e3,
            referenced.len(),
            share(wrong),
            drift,
        );
    }
    let _ = writeln!(out);
}
