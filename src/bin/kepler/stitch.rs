//! `kepler stitch`: the drawing of a grid's tile files (`render --tiles … --tile …`),
//! finished and written as `render` writes the whole drawing.

use crate::finish::FinishArgs;
use anyhow::{Result, anyhow};
use kepler::hidden::EdgeSelection;
use kepler::hidden::tiles::{TileFile, TileSet};
use kepler::output::{Finishing, HatchLayer, finish};
use std::path::PathBuf;

/// Join the tile files of a grid (`render --tiles CxR --tile I,J`) into the whole drawing,
/// bit for bit `render`'s: give every tile once, in any order, and the finishing options
/// (`--hidden`, `--keep-overlaps`, `--order`, the page, DXF, JSON) as `render` takes them.
#[derive(clap::Args)]
pub struct Args {
    /// The tile files (`.kpt`), every tile of one grid once.
    #[arg(required = true)]
    tiles: Vec<PathBuf>,
    /// The file to write: SVG, or DXF when its name ends in `.dxf` (`-` writes SVG to
    /// standard output).
    #[arg(short = 'o', long = "output", value_name = "FILE")]
    output: PathBuf,
    #[command(flatten)]
    finish: FinishArgs,
}

/// Reads the tiles, checks that they make one grid, stitches and writes the drawing.
pub fn run(args: Args) -> Result<()> {
    // One file at a time: each tile is let go once added.
    let mut set = TileSet::default();
    for path in &args.tiles {
        let name = path.display().to_string();
        let bytes = std::fs::read(path).map_err(|e| anyhow!("cannot read {name}: {e}"))?;
        let file = TileFile::from_bytes(&bytes).map_err(|e| anyhow!("{name}: {e}"))?;
        set.add(&name, file)?;
    }
    // The pass's options that the tiles were drawn with are in their fingerprint; these
    // only finish the drawing.
    let options = args.finish.options(EdgeSelection::Feature, 0.0);
    let drawing = set.finish(&options)?;
    let finishing = Finishing {
        order: args.finish.order,
    };
    let finished = finish(drawing, &finishing);
    let svg_options = args.finish.svg_options();
    args.finish.write(
        &args.output,
        &finished.drawing,
        &HatchLayer::default(),
        &svg_options,
    )?;
    Ok(())
}
