//! What several commands write: standard output that tolerates a closed pipe, files (or
//! standard output for `-`), the answers to point queries with their summary, and a progress
//! bar.

use anyhow::Result;
use indicatif::{ProgressBar, ProgressStyle};
use kepler::geometry::Point3;
use kepler::io::FileError;
use kepler::queries::Counters;
use std::fmt::Write as _;
use std::io::{IsTerminal, Write};
use std::path::Path;
use std::time::{Duration, Instant};

/// Writes to standard output; a reader that closed the pipe early (`| head`) is not an error.
pub fn emit(text: &str) -> Result<()> {
    match std::io::stdout().lock().write_all(text.as_bytes()) {
        Err(e) if e.kind() == std::io::ErrorKind::BrokenPipe => Ok(()),
        other => Ok(other?),
    }
}

/// Writes a file (or standard output for `-`) with `write`, naming the file in errors.
pub fn write_file(
    path: &Path,
    write: impl FnOnce(&mut dyn Write) -> std::io::Result<()>,
) -> Result<()> {
    let name = path.display().to_string();
    if name == "-" {
        let mut out = std::io::BufWriter::new(std::io::stdout().lock());
        write(&mut out).and_then(|()| out.flush())?;
        return Ok(());
    }
    let file = std::fs::File::create(path).map_err(|e| FileError::io(&name, e))?;
    let mut out = std::io::BufWriter::new(file);
    write(&mut out)
        .and_then(|()| out.flush())
        .map_err(|e| FileError::io(&name, e))?;
    Ok(())
}

/// Writes `value` as one line of JSON to a file (or standard output for `-`).
pub fn write_json_file(path: &Path, value: &impl serde::Serialize) -> Result<()> {
    write_file(path, |out| {
        serde_json::to_writer(&mut *out, value).map_err(std::io::Error::other)?;
        writeln!(out)
    })
}

/// Builds an index, answers every point with it, prints one answer per line, and a summary
/// on stderr with the count of each of `kinds` (in that order).
pub fn answer_points<I, T: std::fmt::Display + PartialEq>(
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

/// A progress bar on stderr, or `None` when stderr is not a terminal.
pub fn progress_bar() -> Option<ProgressBar> {
    if !std::io::stderr().is_terminal() {
        return None;
    }
    let bar = ProgressBar::new(0);
    if let Ok(style) = ProgressStyle::with_template("visibility {bar:40} {pos}/{len} lines ({eta})")
    {
        bar.set_style(style);
    }
    Some(bar)
}
