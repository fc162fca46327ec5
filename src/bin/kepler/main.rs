//! The `kepler` command line: one module per command, each with its options (`Args`) and its
//! `run`; `args` and `output` hold what several commands share.

mod args;
mod bounds;
mod boxtree;
mod cull;
mod finish;
mod r#gen;
mod include;
mod index;
mod output;
mod render;
mod report;
mod segx;
mod stitch;
mod surfaces;
mod triboxes;
mod visobj;
mod visp;

use clap::{Parser, Subcommand};
use std::process::ExitCode;

/// kepler: exact visibility for scenes of polyhedra.
#[derive(Parser)]
#[command(name = "kepler", version, about)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

// Each command's help is its `Args`' doc comment; `--help` lists them in this order.
#[derive(Subcommand)]
enum Command {
    Bounds(bounds::Args),
    Include(include::Args),
    Index(index::Args),
    Segx(segx::Args),
    Render(render::Args),
    Stitch(stitch::Args),
    Surfaces(surfaces::Args),
    Visobj(visobj::Args),
    Cull(cull::Args),
    Boxtree(boxtree::Args),
    Triboxes(triboxes::Args),
    Visp(visp::Args),
    Gen(r#gen::Args),
    Report(report::Args),
}

fn main() -> ExitCode {
    let result = match Cli::parse().command {
        Command::Bounds(args) => bounds::run(args),
        Command::Include(args) => include::run(args),
        Command::Index(args) => index::run(args),
        Command::Segx(args) => segx::run(args),
        Command::Render(args) => render::run(args),
        Command::Stitch(args) => stitch::run(args),
        Command::Surfaces(args) => surfaces::run(args),
        Command::Visobj(args) => visobj::run(args),
        Command::Cull(args) => cull::run(args),
        Command::Boxtree(args) => boxtree::run(args),
        Command::Triboxes(args) => triboxes::run(args),
        Command::Visp(args) => visp::run(args),
        Command::Gen(args) => r#gen::run(args),
        Command::Report(args) => report::run(args),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::FAILURE
        }
    }
}
