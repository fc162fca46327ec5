//! `kepler bounds`: each object's bounds, as a table or JSON.

use crate::args::FaceArgs;
use crate::output::emit;
use anyhow::Result;
use kepler::scene::{file, report::BoundsReport};
use std::path::PathBuf;

/// Print each object's faces, vertices, CBOX, INBOX, tribox and how tightly they fit.
#[derive(clap::Args)]
pub struct Args {
    /// A scene file (.toml) or a mesh file (.obj, .stl, .off, .ply).
    scene: PathBuf,
    /// Print JSON instead of a table.
    #[arg(long)]
    json: bool,
    #[command(flatten)]
    faces: FaceArgs,
}

/// Prints the bounds report of the scene.
pub fn run(args: Args) -> Result<()> {
    let scene = file::load_with(&args.scene, args.faces.validation())?;
    let report = BoundsReport::of(&scene);
    let text = if args.json {
        serde_json::to_string_pretty(&report)? + "\n"
    } else {
        report.table()
    };
    emit(&text)
}
