//! The `kepler` command line.

use anyhow::Result;
use clap::{Parser, Subcommand};
use kepler::scene::{file, report::BoundsReport};
use std::io::Write;
use std::path::PathBuf;
use std::process::ExitCode;

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
    }
    Ok(())
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
