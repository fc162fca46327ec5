//! `kepler segx`: Franklin's uniform-grid segment intersection, on random or given segments.

use crate::output::emit;
use anyhow::Result;
use geo::Line;
use kepler::grid::{intersecting_pairs, random_segments};
use kepler::io::points::read_segments;
use std::fmt::Write as _;
use std::path::PathBuf;
use std::time::Instant;

/// Franklin's uniform-grid segment intersection: print N, the number K of intersecting
/// pairs, and the seconds taken (grid and pairs, not reading or generating).
#[derive(clap::Args)]
pub struct Args {
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
}

/// Finds the intersecting pairs and prints them, or their count.
pub fn run(args: Args) -> Result<()> {
    let (lines, segments) = segments(&args)?;
    let start = Instant::now();
    let found = intersecting_pairs(&segments);
    let seconds = start.elapsed().as_secs_f64();
    let summary = format!(
        "N {} K {} seconds {seconds:.6}",
        segments.len(),
        found.len()
    );
    if args.pairs {
        let mut text = String::with_capacity(found.len() * 12);
        for (i, j) in &found {
            let _ = writeln!(text, "{} {}", lines[*i], lines[*j]);
        }
        emit(&text)?;
        eprintln!("{summary}");
        Ok(())
    } else {
        emit(&(summary + "\n"))
    }
}

/// The segments read or generated, each with the number that names it in `--pairs`.
fn segments(args: &Args) -> Result<(Vec<usize>, Vec<Line<f64>>)> {
    Ok(match (&args.input, args.n) {
        (Some(path), _) => read_segments(path)?.into_iter().unzip(),
        (None, Some(n)) => {
            if !(0.0..=1.0).contains(&args.len) {
                anyhow::bail!("--len must be between 0 and 1, not {}", args.len);
            }
            ((1..=n).collect(), random_segments(n, args.len, args.seed))
        }
        (None, None) => anyhow::bail!("give --n N or --input FILE"),
    })
}
