//! Error against run time: what exactness costs, and what the shortcuts lose.
//!
//! Why not decide visibility with plain floats, or with a tolerance as most CAD and plotting
//! engines do, or in single precision as a GPU does, or by sampling each edge (the `ln`
//! family) or with a z-buffer? This module answers with measurements, on scenes chosen to be
//! hard ([`super::stiff`]) and on the bundled ones:
//!
//! 1. Every case is drawn by the exact engine; that drawing is checked twice: by the engine's
//!    own independent checks ([`crate::hidden::verify`]), and, on small scenes, against a
//!    brute-force drawing in rational arithmetic ([`reference`]). So "exact" is measured, not
//!    claimed.
//! 2. Every [`Variant`](variants::Variant) draws the same case. The arithmetic variants run
//!    the engine's own code with only the kernel's arithmetic switched
//!    ([`crate::geometry::kernel::Arithmetic`]); the sampled and z-buffer variants decide the
//!    engine's own lines by samples. A variant that panics, refuses the scene or runs past the
//!    time limit is recorded as a failure.
//! 3. Each drawing is compared with the exact one ([`measure`]): lengths drawn with the wrong
//!    visibility, missing and extra, the Hausdorff distance of the vertices, and ends of
//!    visible or hidden runs that are not where they should be.
//! 4. The exact engine's own cost of exactness: how many of its filter calls could not decide
//!    a sign from the rounded value and went down the exact path
//!    ([`crate::geometry::kernel::count_filters`]).
//!
//! The [`Report`] is written as a table per family (`index.md`), as JSON (`report.json`,
//! from which the table is rebuilt exactly) and as charts ([`chart`]): error against run
//! time, and error against each family's stiffness parameter.
//!
//! ```no_run
//! use kepler::lab::report::{Report, Settings};
//! let report = Report::run(&Settings::quick("scenes"), &|_, _, _| {}).unwrap();
//! report.write("report".as_ref()).unwrap();
//! ```

pub mod chart;
pub mod measure;
pub mod reference;
mod table;

pub use table::WriteError;
pub mod variants;

use crate::Error;
use crate::geometry::kernel::count_filters;
use crate::hidden::verify::{draw_traced, verify};
use crate::hidden::{Drawing, EdgeSelection, Options};
use crate::lab::stiff::{Family, StiffError, generate};
use crate::scene::{Scene, file};
use crate::views::View;
use measure::{ErrorFigures, compare, default_tolerance};
use serde::{Deserialize, Serialize};
use std::panic::{AssertUnwindSafe, catch_unwind};
use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::sync::mpsc;
use std::time::{Duration, Instant};
use variants::Variant;

/// Why a report could not be made or written.
///
/// ```
/// use kepler::lab::report::ReportError;
/// let e = ReportError::from(kepler::Error::from(kepler::views::ViewError::EyeAtTarget));
/// assert!(e.to_string().starts_with("invalid view"));
/// ```
#[derive(Debug, thiserror::Error)]
pub enum ReportError {
    /// A stiff scene could not be generated.
    #[error(transparent)]
    Stiff(#[from] StiffError),
    /// A bundled scene could not be loaded or viewed.
    #[error(transparent)]
    Engine(#[from] Error),
    /// The report could not be written.
    #[error(transparent)]
    Write(#[from] table::WriteError),
}

/// Scenes with at most this many triangles are also drawn by the rational [`reference`].
pub const REFERENCE_LIMIT: usize = 150;

/// What a report runs.
///
/// ```
/// let s = kepler::lab::report::Settings::quick("scenes");
/// assert_eq!((s.quick, s.repeats, s.seeds), (true, 1, 1));
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct Settings {
    /// The quick report (a few parameters per family, two resolutions, one seed, one timing
    /// run), else the full one.
    pub quick: bool,
    /// Seeds per family and parameter.
    pub seeds: u64,
    /// Timed runs per variant and case (the median is reported; a run of a second or more
    /// is timed once).
    pub repeats: usize,
    /// A run that takes longer fails.
    pub limit: Duration,
    /// The folder of the bundled scenes.
    pub scenes: PathBuf,
}

impl Settings {
    /// The quick report: under a minute, for the test suite and CI.
    pub fn quick(scenes: impl Into<PathBuf>) -> Settings {
        Settings {
            quick: true,
            seeds: 1,
            repeats: 1,
            limit: Duration::from_secs(60),
            scenes: scenes.into(),
        }
    }

    /// The full report: every parameter, three seeds, three timing runs.
    ///
    /// ```
    /// assert_eq!(kepler::lab::report::Settings::full("scenes").repeats, 3);
    /// ```
    pub fn full(scenes: impl Into<PathBuf>) -> Settings {
        Settings {
            quick: false,
            seeds: 3,
            repeats: 3,
            limit: Duration::from_secs(300),
            scenes: scenes.into(),
        }
    }
}

/// A scene and view to draw every way.
struct Case {
    family: String,
    parameter: Option<i32>,
    name: String,
    scene: Scene,
    view: View,
    options: Options,
}

/// The bundled scenes in the report: (file, view direction); the full report adds the
/// larger ones.
const BUNDLED: [(&str, [f64; 3], bool); 6] = [
    ("cube.toml", [-1.0, -2.0, -3.0], true),
    ("polyhedra.toml", [1.0, 2.0, -3.0], true),
    ("meshes.toml", [1.0, 2.0, -3.0], true),
    ("solids.toml", [1.0, 2.0, -3.0], false),
    ("bunny.toml", [1.0, 2.0, -3.0], false),
    ("city.toml", [1.0, 2.0, -3.0], false),
];

/// The cases of a report: each stiff family at its parameters and seeds, then the bundled
/// scenes.
fn cases(settings: &Settings) -> Result<Vec<Case>, ReportError> {
    let options = Options {
        edges: EdgeSelection::All,
        ..Options::default()
    };
    let mut cases = Vec::new();
    for family in Family::ALL {
        for k in family.parameters(settings.quick) {
            for seed in 1..=settings.seeds {
                let stiff = generate(family, k, seed)?;
                cases.push(Case {
                    family: family.name().to_string(),
                    parameter: Some(k),
                    name: stiff.name(),
                    scene: stiff.scene,
                    view: stiff.view,
                    options,
                });
            }
        }
    }
    for (file, direction, quick) in BUNDLED {
        if settings.quick && !quick {
            continue;
        }
        let scene = file::load(&settings.scenes.join(file)).map_err(Error::from)?;
        let view =
            View::orthographic(direction.into(), nalgebra::Vector3::z()).map_err(Error::from)?;
        cases.push(Case {
            family: "bundled".to_string(),
            parameter: None,
            name: file.trim_end_matches(".toml").to_string(),
            scene,
            view,
            options,
        });
    }
    Ok(cases)
}

/// A drawing's error figures as the report keeps them (JSON has no infinity: an infinite or
/// NaN distance is `None`).
///
/// ```
/// use kepler::lab::report::{Figures, measure::ErrorFigures};
/// let f = Figures::from(&ErrorFigures::default());
/// assert_eq!((f.relative, f.wrong_ends, f.hausdorff), (0.0, 0, Some(0.0)));
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Figures {
    /// Wrong length over the exact drawing's length.
    pub relative: f64,
    /// Length drawn with the wrong visibility.
    pub misclassified: f64,
    /// Length of the exact drawing missing.
    pub missing: f64,
    /// Length drawn that the exact drawing does not have.
    pub extra: f64,
    /// Hausdorff distance of the vertices, in picture units.
    pub hausdorff: Option<f64>,
    /// The same in units in the last place of the drawing's largest coordinate.
    pub hausdorff_ulps: Option<f64>,
    /// Ends of runs with no counterpart.
    pub wrong_ends: usize,
}

impl Figures {
    /// Whether the drawing has anything wrong: length, ends or a misplaced vertex (more than
    /// four units in the last place away). (The exact engine against the rational reference
    /// is judged by its lengths only: the reference rounds the ends of intersection lines,
    /// see [`reference`].)
    ///
    /// ```
    /// use kepler::lab::report::{Figures, measure::ErrorFigures};
    /// assert!(!Figures::from(&ErrorFigures::default()).is_wrong());
    /// ```
    pub fn is_wrong(&self) -> bool {
        self.relative > 0.0 || self.wrong_ends > 0 || self.hausdorff_ulps.is_none_or(|u| u > 4.0)
    }
}

impl From<&ErrorFigures> for Figures {
    fn from(e: &ErrorFigures) -> Figures {
        let finite = |x: f64| x.is_finite().then_some(x);
        Figures {
            relative: e.relative(),
            misclassified: e.misclassified(),
            missing: e.missing,
            extra: e.extra,
            hausdorff: finite(e.hausdorff),
            hausdorff_ulps: finite(e.hausdorff_ulps),
            wrong_ends: e.wrong_ends,
        }
    }
}

/// One variant on one case.
///
/// ```
/// let r = kepler::lab::report::VariantRun { variant: "float".into(), kind: "float".into(), seconds: Some(0.5), figures: None, failure: Some("panicked".into()) };
/// assert!(r.failure.is_some());
/// ```
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct VariantRun {
    /// The variant's name ([`Variant::name`]).
    pub variant: String,
    /// Its kind ([`Variant::kind`]).
    pub kind: String,
    /// The median time of its drawing, in seconds (none when it failed).
    pub seconds: Option<f64>,
    /// Its errors against the exact drawing (for the exact variant: against the rational
    /// reference when the case is small enough, else none).
    pub figures: Option<Figures>,
    /// Why it failed: a panic, an error, the time limit.
    pub failure: Option<String>,
}

/// One case of the report with every variant's run.
///
/// ```
/// let c = kepler::lab::report::CaseReport { name: "tilt k=3 seed=1".into(), family: "tilt".into(), parameter: Some(3), triangles: 36, filter_calls: 1000, exact_path: 4, checks: 900, disagreements: 0, runs: vec![] };
/// assert_eq!(c.exact_share(), 0.004);
/// ```
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct CaseReport {
    /// The case: a stiff scene with its parameter and seed, or a bundled scene's name.
    pub name: String,
    /// Its family (`bundled` for the bundled scenes).
    pub family: String,
    /// The family's stiffness parameter.
    pub parameter: Option<i32>,
    /// Triangles in the scene.
    pub triangles: usize,
    /// Filter calls of the exact drawing.
    pub filter_calls: u64,
    /// Of those, the calls that went down the exact path.
    pub exact_path: u64,
    /// The independent checks of the exact drawing ([`verify`]).
    pub checks: usize,
    /// And their disagreements.
    pub disagreements: usize,
    /// Every variant's run, the exact one first.
    pub runs: Vec<VariantRun>,
}

impl CaseReport {
    /// The share of filter calls that needed the exact path.
    pub fn exact_share(&self) -> f64 {
        if self.filter_calls == 0 {
            0.0
        } else {
            self.exact_path as f64 / self.filter_calls as f64
        }
    }

    /// The exact variant's time, in seconds.
    ///
    /// ```
    /// use kepler::lab::report::{CaseReport, VariantRun};
    /// let run = VariantRun { variant: "exact".into(), kind: "exact".into(), seconds: Some(0.25), figures: None, failure: None };
    /// let c = CaseReport { name: "c".into(), family: "f".into(), parameter: None, triangles: 1, filter_calls: 0, exact_path: 0, checks: 0, disagreements: 0, runs: vec![run] };
    /// assert_eq!(c.exact_seconds(), Some(0.25));
    /// ```
    pub fn exact_seconds(&self) -> Option<f64> {
        self.runs.iter().find(|r| r.kind == "exact")?.seconds
    }
}

/// A report: every case with every variant's run.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Report {
    /// Whether this is the quick report.
    pub quick: bool,
    /// The cases, in the order run.
    pub cases: Vec<CaseReport>,
}

/// Why a run did not give a drawing.
enum Failure {
    /// It panicked, with this message.
    Panicked(String),
    /// It returned an error.
    Refused(String),
    /// It did not end within the limit (it goes on in the background).
    TimedOut,
}

impl Failure {
    fn describe(&self, limit: Duration) -> String {
        match self {
            Failure::Panicked(m) => format!("panicked: {m}"),
            Failure::Refused(m) => format!("error: {m}"),
            Failure::TimedOut => format!("no answer within {} s", limit.as_secs()),
        }
    }
}

/// Runs `work` on its own thread, with panics caught, waiting at most `limit`; the time it
/// took.
fn bounded<T: Send + 'static>(
    limit: Duration,
    work: impl FnOnce() -> Result<T, Error> + Send + 'static,
) -> Result<(T, f64), Failure> {
    let (send, receive) = mpsc::channel();
    std::thread::spawn(move || {
        let clock = Instant::now();
        let result = catch_unwind(AssertUnwindSafe(work));
        let seconds = clock.elapsed().as_secs_f64();
        // The report may have stopped waiting.
        let _ = send.send((result, seconds));
    });
    match receive.recv_timeout(limit) {
        Ok((Ok(Ok(value)), seconds)) => Ok((value, seconds)),
        Ok((Ok(Err(e)), _)) => Err(Failure::Refused(e.to_string())),
        Ok((Err(payload), _)) => Err(Failure::Panicked(
            payload
                .downcast_ref::<&str>()
                .map(|s| s.to_string())
                .or_else(|| payload.downcast_ref::<String>().cloned())
                .unwrap_or_else(|| "no message".to_string()),
        )),
        Err(_) => Err(Failure::TimedOut),
    }
}

/// The tolerance within which a variant's lines count as the exact ones: the default one
/// ([`default_tolerance`]), or for `f32` sixteen of its units in the last place of the
/// drawing's largest coordinate, so that its rounding alone is not counted as lines missing
/// (it shows in the Hausdorff distance) and what is counted is visibility and topology.
fn variant_tolerance(exact: &Drawing, variant: Variant) -> f64 {
    let tolerance = default_tolerance(exact);
    if variant != Variant::Single {
        return tolerance;
    }
    let largest = exact
        .polylines
        .iter()
        .flat_map(|p| &p.points)
        .flat_map(|q| q.iter())
        .filter(|x| x.is_finite())
        .fold(0.0f64, |m, x| m.max(x.abs()));
    tolerance.max(16.0 * f64::from(f32::EPSILON) / 2.0 * largest)
}

/// The median of some times.
fn median(mut times: Vec<f64>) -> f64 {
    times.sort_by(f64::total_cmp);
    times.get(times.len() / 2).copied().unwrap_or(f64::NAN)
}

impl Report {
    /// Runs every variant on every case of `settings`, calling `progress(done, total, case)`
    /// before each case. While it runs, panics print nothing (they are recorded). A run past
    /// the time limit stops the report: the remaining runs are recorded as not run, since the
    /// stuck run still holds the kernel's arithmetic.
    pub fn run(
        settings: &Settings,
        progress: &dyn Fn(usize, usize, &str),
    ) -> Result<Report, ReportError> {
        let cases = cases(settings)?;
        let total = cases.len();
        let hook = std::panic::take_hook();
        std::panic::set_hook(Box::new(|_| {}));
        let mut stuck = false;
        let mut reports = Vec::with_capacity(total);
        for (i, case) in cases.into_iter().enumerate() {
            progress(i, total, &case.name);
            reports.push(run_case(Arc::new(case), settings, &mut stuck));
        }
        std::panic::set_hook(hook);
        Ok(Report {
            quick: settings.quick,
            cases: reports,
        })
    }

    /// Whether some run did not end within the limit (its thread still runs: a program
    /// should exit once the report is written).
    ///
    /// ```
    /// let r = kepler::lab::report::Report { quick: true, cases: vec![] };
    /// assert!(!r.has_stuck_run());
    /// ```
    pub fn has_stuck_run(&self) -> bool {
        self.cases.iter().flat_map(|c| &c.runs).any(|r| {
            r.failure
                .as_deref()
                .is_some_and(|f| f.starts_with("no answer"))
        })
    }

    /// Writes `index.md`, `report.json` and the charts into `dir` (created if needed); the
    /// files written.
    pub fn write(&self, dir: &Path) -> Result<Vec<PathBuf>, ReportError> {
        Ok(table::write(self, dir)?)
    }

    /// The report as JSON.
    ///
    /// ```
    /// use kepler::lab::report::Report;
    /// let r = Report { quick: true, cases: vec![] };
    /// assert_eq!(Report::from_json(&r.json()).unwrap(), r);
    /// ```
    pub fn json(&self) -> String {
        serde_json::to_string_pretty(self).unwrap_or_default()
    }

    /// A report read back from its JSON.
    pub fn from_json(text: &str) -> Result<Report, serde_json::Error> {
        serde_json::from_str(text)
    }

    /// The report as Markdown tables: one per family, the cost of exactness, the checks of
    /// the exact drawings.
    ///
    /// ```
    /// let r = kepler::lab::report::Report { quick: true, cases: vec![] };
    /// assert!(r.markdown().starts_with("# Error against run time"));
    /// ```
    pub fn markdown(&self) -> String {
        table::markdown(self)
    }
}

/// A run of `variant` that was not made, and why.
fn not_run(variant: &Variant, why: &str) -> VariantRun {
    VariantRun {
        variant: variant.name(),
        kind: variant.kind().to_string(),
        seconds: None,
        figures: None,
        failure: Some(why.to_string()),
    }
}

/// `variant` drawing the case up to `settings.repeats` times (once when a run takes a second
/// or more): the times of the runs, the last drawing, and the failure that ended them, if any
/// (a run that timed out sets `stuck`).
fn timed_runs(
    case: &Arc<Case>,
    variant: Variant,
    settings: &Settings,
    stuck: &mut bool,
) -> (Vec<f64>, Option<Drawing>, Option<String>) {
    let mut times = Vec::new();
    let mut drawing = None;
    let mut failure = None;
    for _ in 0..settings.repeats.max(1) {
        let case = case.clone();
        match bounded(settings.limit, move || {
            variant.draw(&case.scene, &case.view, &case.options)
        }) {
            Ok((d, seconds)) => {
                times.push(seconds);
                drawing = Some(d);
                // A run of a second or more is timed once: its noise is small.
                if seconds >= 1.0 {
                    break;
                }
            }
            Err(f) => {
                *stuck |= matches!(f, Failure::TimedOut);
                failure = Some(f.describe(settings.limit));
                break;
            }
        }
    }
    (times, drawing, failure)
}

/// The error figures of a variant's drawing: the exact drawing (kept in `exact`) against the
/// rational reference, for a case of at most [`REFERENCE_LIMIT`] triangles; any other against
/// the exact drawing, once there is one.
fn figures_of(
    case: &Arc<Case>,
    settings: &Settings,
    triangles: usize,
    variant: Variant,
    drawing: &Option<Drawing>,
    exact: &mut Option<Arc<Drawing>>,
) -> Option<Figures> {
    match (drawing, variant, &*exact) {
        (Some(d), Variant::Exact, _) => {
            let d = Arc::new(d.clone());
            *exact = Some(d.clone());
            (triangles <= REFERENCE_LIMIT)
                .then(|| {
                    let case = case.clone();
                    bounded(settings.limit, move || {
                        reference::reference(&case.scene, &case.view, &case.options)
                    })
                    .ok()
                    .map(|(r, _)| Figures::from(&compare(&r, &d, default_tolerance(&r))))
                })
                .flatten()
        }
        (Some(d), _, Some(e)) => Some(Figures::from(&compare(e, d, variant_tolerance(e, variant)))),
        _ => None,
    }
}

/// Every variant on one case.
fn run_case(case: Arc<Case>, settings: &Settings, stuck: &mut bool) -> CaseReport {
    let triangles = case
        .scene
        .mesh_objects(case.scene.roots())
        .iter()
        .map(|(_, m)| m.triangles().len())
        .sum();
    let mut report = CaseReport {
        name: case.name.clone(),
        family: case.family.clone(),
        parameter: case.parameter,
        triangles,
        filter_calls: 0,
        exact_path: 0,
        checks: 0,
        disagreements: 0,
        runs: Vec::new(),
    };
    let variants = Variant::all(settings.quick);
    if *stuck {
        report.runs = variants
            .iter()
            .map(|v| not_run(v, "not run: an earlier run did not end"))
            .collect();
        return report;
    }
    // The exact drawing, its checks and its cost.
    let checked = {
        let case = case.clone();
        bounded(settings.limit, move || {
            let (traced, counts) =
                count_filters(|| draw_traced(&case.scene, &case.view, &case.options, &|_, _| {}));
            let verification = verify(&case.scene, &case.view, &case.options, &traced?);
            Ok((verification, counts))
        })
    };
    match checked {
        Ok(((verification, counts), _)) => {
            report.checks = verification.checks();
            report.disagreements = verification.disagreements;
            report.filter_calls = counts.calls;
            report.exact_path = counts.misses;
        }
        Err(failure) => {
            *stuck |= matches!(failure, Failure::TimedOut);
            let why = failure.describe(settings.limit);
            report.runs = variants.iter().map(|v| not_run(v, &why)).collect();
            return report;
        }
    }
    let mut exact: Option<Arc<Drawing>> = None;
    for variant in variants {
        if *stuck {
            report
                .runs
                .push(not_run(&variant, "not run: an earlier run did not end"));
            continue;
        }
        let (times, drawing, failure) = timed_runs(&case, variant, settings, stuck);
        let figures = figures_of(&case, settings, triangles, variant, &drawing, &mut exact);
        report.runs.push(VariantRun {
            variant: variant.name(),
            kind: variant.kind().to_string(),
            seconds: failure.is_none().then(|| median(times)),
            figures,
            failure,
        });
    }
    report
}
