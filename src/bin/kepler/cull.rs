//! `kepler cull`: the culling experiment for one view.

use crate::args::{ViewArgs, load_drawable};
use crate::output::{emit, write_json_file};
use anyhow::Result;
use kepler::lab::culling::{CullReport, cull};
use kepler::mesh::Validation;
use std::path::PathBuf;

/// Culling experiment: for one view, how many pairs of objects each bounding volume
/// (rstar on projected boxes, CBOX, TRIBOX, INBOX) proves not to interact, and the
/// triangle pairs that saves the hidden-line pass.
#[derive(clap::Args)]
pub struct Args {
    /// A scene file (.toml) or a mesh file.
    scene: PathBuf,
    /// Also write the table as JSON to this file.
    #[arg(long, value_name = "FILE")]
    json: Option<PathBuf>,
    #[command(flatten)]
    view: ViewArgs,
}

/// Prints the culling table of the view.
pub fn run(args: Args) -> Result<()> {
    let scene = load_drawable(&args.scene, Validation::Repair)?;
    let view = args.view.view(&scene)?;
    let report = cull(&scene, &view)?;
    emit(&cull_table(&report))?;
    if let Some(json) = &args.json {
        write_json_file(json, &report)?;
    }
    Ok(())
}

/// The culling table: one row per filter, then the pairs left to the hidden-line pass.
fn cull_table(r: &CullReport) -> String {
    let share = |x: u64, of: u64| {
        if of == 0 {
            0.0
        } else {
            100.0 * x as f64 / of as f64
        }
    };
    let mut out = format!(
        "{} objects, {} pairs, {} triangle pairs\n{:<8} {:>12} {:>8} {:>22} {:>8}\n",
        r.objects, r.pairs, r.triangle_pairs, "filter", "pairs", "%", "triangle pairs saved", "%"
    );
    for f in &r.filters {
        out += &format!(
            "{:<8} {:>12} {:>7.2}% {:>22} {:>7.2}%\n",
            f.name,
            f.decided,
            share(f.decided, r.pairs),
            f.triangle_pairs_saved,
            share(f.triangle_pairs_saved, r.triangle_pairs)
        );
    }
    out += &format!(
        "{:<8} {:>12} {:>7.2}% {:>22} {:>7.2}%\n",
        "left",
        r.undecided,
        share(r.undecided, r.pairs),
        r.undecided_triangle_pairs,
        share(r.undecided_triangle_pairs, r.triangle_pairs)
    );
    out
}
