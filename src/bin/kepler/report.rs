//! `kepler report`: error against run time.

use anyhow::Result;
use indicatif::{ProgressBar, ProgressStyle};
use kepler::lab::report::{Report, Settings};
use std::io::IsTerminal;
use std::path::PathBuf;
use std::time::Duration;

/// Error against run time: draws stiff scenes (near-coplanar faces, slivers, far offsets,
/// extreme scales, edge-on faces, fans, nested, touching and near-tangent objects, inside-out
/// meshes) and the bundled ones with the exact engine and with cheaper variants (plain floats,
/// tolerances, f32, sampled edges, a z-buffer), and writes a table per family (index.md),
/// report.json and SVG charts.
#[derive(clap::Args)]
pub struct Args {
    /// The quick report (a few parameters per family, one seed; under a minute).
    #[arg(long)]
    quick: bool,
    /// The folder to write into.
    #[arg(short, long, default_value = "report")]
    out: PathBuf,
    /// The folder of the bundled scenes.
    #[arg(long, default_value = "scenes")]
    scenes: PathBuf,
    /// A run taking longer than this many seconds fails (default 60 quick, 300 full).
    #[arg(long, value_name = "SECONDS")]
    limit: Option<u64>,
}

/// Runs the report and writes it.
pub fn run(args: Args) -> Result<()> {
    let mut settings = if args.quick {
        Settings::quick(&args.scenes)
    } else {
        Settings::full(&args.scenes)
    };
    if let Some(limit) = args.limit {
        settings.limit = Duration::from_secs(limit);
    }
    let bar = std::io::stderr().is_terminal().then(|| {
        let bar = ProgressBar::new(0);
        if let Ok(style) =
            ProgressStyle::with_template("report {bar:40} {pos}/{len} cases {msg} ({eta})")
        {
            bar.set_style(style);
        }
        bar
    });
    let report = Report::run(&settings, &|done, total, name| {
        if let Some(bar) = &bar {
            bar.set_length(total as u64);
            bar.set_position(done as u64);
            bar.set_message(name.to_string());
        }
    })?;
    if let Some(bar) = &bar {
        bar.finish_and_clear();
    }
    for path in report.write(&args.out)? {
        println!("wrote {}", path.display());
    }
    if report.has_stuck_run() {
        // A run past the time limit still runs on its thread: end the process.
        eprintln!("kepler report: a run did not end within the limit (see the table)");
        std::process::exit(0);
    }
    Ok(())
}
