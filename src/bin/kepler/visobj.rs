//! `kepler visobj`: whether one object hides another.

use crate::args::{ViewArgs, find_object};
use crate::output::emit;
use anyhow::Result;
use kepler::scene::file;
use kepler::surfaces::visobj;
use std::path::PathBuf;

/// VISOBJ: print VISIBLE, HIDDEN or MIXED as object A hides nothing, all or part of
/// object B (objects named by their paths, like `block/tower-west`).
#[derive(clap::Args)]
pub struct Args {
    /// A scene file (.toml).
    scene: PathBuf,
    /// The object that may hide.
    a: String,
    /// The object that may be hidden.
    b: String,
    #[command(flatten)]
    view: ViewArgs,
}

/// Prints whether A hides B.
pub fn run(args: Args) -> Result<()> {
    let scene = file::load(&args.scene)?;
    let a = find_object(&scene, &args.scene, &args.a)?;
    let b = find_object(&scene, &args.scene, &args.b)?;
    let view = args.view.view(&scene)?;
    let answer = visobj(&scene, a, b, &view)?;
    emit(&format!("{}\n", format!("{answer:?}").to_uppercase()))
}
