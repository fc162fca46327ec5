//! `kepler boxtree`: BOXTREE experiments.

use crate::output::{emit, write_json_file};
use anyhow::Result;
use kepler::lab::boxtree::spheres::{DEFAULT_GAP, PAPER_FACETS, Row};
use kepler::lab::boxtree::{Merge, sphere_experiment};
use std::path::PathBuf;

/// BOXTREE experiments (Barequet et al. 1996): `--experiment spheres` counts the
/// collision tests between pairs of concentric random spheres (556, 1,996 and 9,996
/// facets) for every node shape, beside the paper's Table 1.
#[derive(clap::Args)]
pub struct Args {
    /// The experiment to run.
    #[arg(long, value_enum)]
    experiment: Experiment,
    /// The merge rule: smallest parent `volume` (the paper's Table 1) or `area`.
    #[arg(long, value_enum, default_value_t = Merge::Volume)]
    merge: Merge,
    /// Also write the rows as JSON to this file.
    #[arg(long, value_name = "FILE")]
    json: Option<PathBuf>,
}

/// `--experiment`.
#[derive(Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
enum Experiment {
    /// Concentric random spheres (the paper's Table 1 setting).
    Spheres,
}

/// Runs the experiment and prints its table.
pub fn run(args: Args) -> Result<()> {
    let rows = match args.experiment {
        Experiment::Spheres => sphere_experiment(&PAPER_FACETS, DEFAULT_GAP, 1, args.merge)?,
    };
    emit(&table(&rows))?;
    if let Some(json) = &args.json {
        write_json_file(json, &rows)?;
    }
    Ok(())
}

/// The table: one row per sphere size and node shape, beside the paper's count.
fn table(rows: &[Row]) -> String {
    let mut table = format!(
        "{:>7}  {:<8} {:>12} {:>12}\n",
        "facets", "shape", "tests", "paper"
    );
    for r in rows {
        let paper = r.paper.map_or("-".to_string(), |p| p.to_string());
        table += &format!(
            "{:>7}  {:<8} {:>12} {:>12}\n",
            r.facets,
            r.shape.to_string(),
            r.tests,
            paper
        );
    }
    table
}
