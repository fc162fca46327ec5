//! The `kepler` command line.

use anyhow::Result;
use clap::{Args, Parser, Subcommand};
use geo::Line;
use kepler::geometry::{Point3, Vector3};
use kepler::grid::{intersecting_pairs, random_segments};
use kepler::io::points::{read_points, read_segments};
use kepler::queries::Counters;
use kepler::queries::include::{IncludeIndex, Inclusion};
use kepler::queries::visp::{Visibility, VisibilityIndex};
use kepler::scene::{Scene, file, report::BoundsReport};
use kepler::views::{View, ViewOptions};
use std::fmt::Write as _;
use std::io::Write;
use std::path::PathBuf;
use std::process::ExitCode;
use std::time::{Duration, Instant};

/// kepler: exact visibility for scenes of polyhedra.
#[derive(Parser)]
#[command(name = "kepler", version, about)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Print each object's faces, vertices, CBOX, INBOX, tribox and how tightly they fit.
    Bounds {
        /// A scene file (.toml) or a mesh file (.obj, .stl, .off).
        scene: PathBuf,
        /// Print JSON instead of a table.
        #[arg(long)]
        json: bool,
    },
    /// INCLUDE: print IN, OUT or ON for each point, in order (a summary goes to stderr).
    Include {
        /// A scene file (.toml) or a mesh file; every mesh must be closed.
        scene: PathBuf,
        /// The points: one `x y z` per line (commas or spaces; `#` comments and blank lines
        /// allowed); `-` reads standard input.
        #[arg(long)]
        points: PathBuf,
    },
    /// Franklin's uniform-grid segment intersection: print N, the number K of intersecting
    /// pairs, and the seconds taken (grid and pairs, not reading or generating).
    Segx {
        /// Generate this many random segments in the unit square (Franklin's experiment).
        #[arg(long, conflicts_with = "input", required_unless_present = "input")]
        n: Option<usize>,
        /// The length of the random segments (at most 1).
        #[arg(long, default_value_t = 0.01)]
        len: f64,
        /// The seed of the random segments.
        #[arg(long, default_value_t = 1)]
        seed: u64,
        /// Read the segments instead: one `x1 y1 x2 y2` per line; `-` reads standard input.
        #[arg(long)]
        input: Option<PathBuf>,
        /// List each intersecting pair `i j` (line numbers of the input, or 1-based indices of
        /// the random segments) on standard output; the summary then goes to standard error.
        #[arg(long)]
        pairs: bool,
    },
    /// VISP: print VISIBLE or HIDDEN for each point, in order (a summary goes to stderr).
    Visp {
        /// A scene file (.toml) or a mesh file.
        scene: PathBuf,
        /// The points: one `x y z` per line (commas or spaces; `#` comments and blank lines
        /// allowed); `-` reads standard input.
        #[arg(long)]
        points: PathBuf,
        #[command(flatten)]
        view: ViewArgs,
    },
}

/// The view options every command that takes a view accepts. Without them: the scene file's
/// camera, else an isometric view along (-1,-1,-1) with z up.
#[derive(Args)]
struct ViewArgs {
    /// Orthographic view along this direction (`0,0,-1` is Franklin's view from (0,0,+∞)).
    #[arg(long, value_name = "X,Y,Z", value_parser = parse_triple, allow_hyphen_values = true)]
    view_dir: Option<[f64; 3]>,
    /// The direction that appears upward in the picture.
    #[arg(long, value_name = "X,Y,Z", value_parser = parse_triple, allow_hyphen_values = true)]
    up: Option<[f64; 3]>,
    /// Perspective view from this eye point (with --target).
    #[arg(long, value_name = "X,Y,Z", value_parser = parse_triple, allow_hyphen_values = true)]
    eye: Option<[f64; 3]>,
    /// The point a perspective view looks at (with --eye).
    #[arg(long, value_name = "X,Y,Z", value_parser = parse_triple, allow_hyphen_values = true)]
    target: Option<[f64; 3]>,
    /// Vertical field of view of a perspective view, in degrees (default 40).
    #[arg(long, value_name = "DEGREES", allow_hyphen_values = true)]
    fov: Option<f64>,
}

impl ViewArgs {
    /// The view over the scene's camera.
    fn view(&self, scene: &Scene) -> kepler::Result<View> {
        let options = ViewOptions {
            view_dir: self.view_dir.map(Vector3::from),
            up: self.up.map(Vector3::from),
            eye: self.eye.map(Point3::from),
            target: self.target.map(Point3::from),
            fov: self.fov,
        };
        Ok(options.resolve(scene.camera())?)
    }
}

/// Parses `x,y,z` into three finite numbers.
fn parse_triple(text: &str) -> Result<[f64; 3], String> {
    let fields: Vec<&str> = text.split(',').map(str::trim).collect();
    if fields.len() != 3 {
        return Err(format!("expected x,y,z (three numbers), got '{text}'"));
    }
    let mut out = [0.0; 3];
    for (k, f) in fields.iter().enumerate() {
        out[k] = match f.parse::<f64>() {
            Ok(x) if x.is_finite() => x,
            _ => return Err(format!("'{f}' is not a finite number")),
        };
    }
    Ok(out)
}

fn run(cli: Cli) -> Result<()> {
    match cli.command {
        Command::Bounds { scene, json } => {
            let scene = file::load(&scene)?;
            let report = BoundsReport::of(&scene);
            let text = if json {
                serde_json::to_string_pretty(&report)? + "\n"
            } else {
                report.table()
            };
            emit(&text)?;
        }
        Command::Include { scene, points } => {
            let scene = file::load(&scene)?;
            let points = read_points(&points)?;
            answer_points(
                "include",
                &points,
                &[Inclusion::In, Inclusion::Out, Inclusion::On],
                || Ok(IncludeIndex::whole_scene(&scene)?),
                |index, points| index.include_all(points),
            )?;
        }
        Command::Segx {
            n,
            len,
            seed,
            input,
            pairs,
        } => {
            let (lines, segments): (Vec<usize>, Vec<Line<f64>>) = match (input, n) {
                (Some(path), _) => read_segments(&path)?.into_iter().unzip(),
                (None, Some(n)) => {
                    if !(0.0..=1.0).contains(&len) {
                        anyhow::bail!("--len must be between 0 and 1, not {len}");
                    }
                    ((1..=n).collect(), random_segments(n, len, seed))
                }
                (None, None) => anyhow::bail!("give --n N or --input FILE"),
            };
            let start = Instant::now();
            let found = intersecting_pairs(&segments);
            let seconds = start.elapsed().as_secs_f64();
            let summary = format!(
                "N {} K {} seconds {seconds:.6}",
                segments.len(),
                found.len()
            );
            if pairs {
                let mut text = String::with_capacity(found.len() * 12);
                for (i, j) in &found {
                    let _ = writeln!(text, "{} {}", lines[*i], lines[*j]);
                }
                emit(&text)?;
                eprintln!("{summary}");
            } else {
                emit(&(summary + "\n"))?;
            }
        }
        Command::Visp {
            scene,
            points,
            view,
        } => {
            let scene = file::load(&scene)?;
            let view = view.view(&scene)?;
            let points = read_points(&points)?;
            answer_points(
                "visp",
                &points,
                &[Visibility::Visible, Visibility::Hidden],
                || Ok(VisibilityIndex::whole_scene(&scene, view)),
                |index, points| index.visp_all(points),
            )?;
        }
    }
    Ok(())
}

/// Builds an index, answers every point with it, prints one answer per line, and a summary
/// on stderr with the count of each of `kinds` (in that order).
fn answer_points<I, T: std::fmt::Display + PartialEq>(
    command: &str,
    points: &[Point3],
    kinds: &[T],
    build: impl FnOnce() -> Result<I>,
    answer: impl FnOnce(&I, &[Point3]) -> (Vec<T>, Counters),
) -> Result<()> {
    let start = Instant::now();
    let index = build()?;
    let built = start.elapsed();
    let start = Instant::now();
    let (answers, counters) = answer(&index, points);
    let queried = start.elapsed();
    let mut text = String::with_capacity(answers.len() * 4);
    for a in &answers {
        let _ = writeln!(text, "{a}");
    }
    emit(&text)?;
    let tally = kinds
        .iter()
        .map(|kind| format!("{} {kind}", answers.iter().filter(|&a| a == kind).count()))
        .collect::<Vec<_>>()
        .join(", ");
    eprintln!("{}", summary(command, &tally, built, queried, &counters));
    Ok(())
}

/// The stderr summary: counts, speed, and what decided the answers.
fn summary(
    command: &str,
    tally: &str,
    built: Duration,
    queried: Duration,
    counters: &Counters,
) -> String {
    let n = counters.total();
    let seconds = queried.as_secs_f64();
    let rate = if seconds > 0.0 {
        format!("{:.2} M points/s", n as f64 / seconds / 1e6)
    } else {
        "instant".to_owned()
    };
    let share = counters
        .by_stage()
        .iter()
        .map(|(name, c)| {
            let percent = if n > 0 {
                100.0 * *c as f64 / n as f64
            } else {
                0.0
            };
            format!("{name} {c} ({percent:.1}%)")
        })
        .collect::<Vec<_>>()
        .join(", ");
    format!(
        "kepler {command}: {n} points: {tally}; {seconds:.3} s ({rate}) after building the index \
         in {:.3} s; decided by {share}",
        built.as_secs_f64()
    )
}

/// Writes to standard output; a reader that closed the pipe early (`| head`) is not an error.
fn emit(text: &str) -> Result<()> {
    match std::io::stdout().lock().write_all(text.as_bytes()) {
        Err(e) if e.kind() == std::io::ErrorKind::BrokenPipe => Ok(()),
        other => Ok(other?),
    }
}

fn main() -> ExitCode {
    match run(Cli::parse()) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::FAILURE
        }
    }
}
