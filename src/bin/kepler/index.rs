//! `kepler index`: a scene written as a scene index (`.kix`), which every command reads as
//! the scene itself.

use crate::args::FaceArgs;
use crate::output::write_file;
use anyhow::Result;
use kepler::scene::{file, index};
use std::path::PathBuf;

/// Write the scene as a scene index (`.kix`): compact binary, each mesh cut into spatial
/// chunks with their CBOXes in a table of contents; every command reads it as the same
/// scene, drawing for drawing bit for bit.
#[derive(clap::Args)]
pub struct Args {
    /// A scene file (.toml) or a mesh file (.obj, .stl, .off, .ply).
    scene: PathBuf,
    /// The index file to write (its name ends in `.kix`).
    #[arg(short = 'o', long = "output", value_name = "FILE")]
    output: PathBuf,
    #[command(flatten)]
    faces: FaceArgs,
}

/// Reads the scene and writes its index.
pub fn run(args: Args) -> Result<()> {
    if args.output.extension().is_none_or(|e| e != "kix") {
        anyhow::bail!(
            "a scene index's name ends in .kix, not {}",
            args.output.display()
        );
    }
    let scene = file::load_with(&args.scene, args.faces.validation())?;
    let bytes = index::to_bytes(&scene);
    write_file(&args.output, |out| out.write_all(&bytes))
}
