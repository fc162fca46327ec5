//! `kepler visp`: VISP for a list of points.

use crate::args::ViewArgs;
use crate::output::answer_points;
use anyhow::Result;
use kepler::io::points::read_points;
use kepler::queries::visp::{Visibility, VisibilityIndex};
use kepler::scene::file;
use std::path::PathBuf;

/// VISP: print VISIBLE or HIDDEN for each point, in order (a summary goes to stderr).
#[derive(clap::Args)]
pub struct Args {
    /// A scene file (.toml) or a mesh file.
    scene: PathBuf,
    /// The points: one `x y z` per line (commas or spaces; `#` comments and blank lines
    /// allowed); `-` reads standard input.
    #[arg(long)]
    points: PathBuf,
    #[command(flatten)]
    view: ViewArgs,
}

/// Answers VISP for every point.
pub fn run(args: Args) -> Result<()> {
    let scene = file::load(&args.scene)?;
    let view = args.view.view(&scene)?;
    let points = read_points(&args.points)?;
    answer_points(
        "visp",
        &points,
        &[Visibility::Visible, Visibility::Hidden],
        || Ok(VisibilityIndex::whole_scene(&scene, view)),
        |index, points| index.visp_all(points),
    )
}
