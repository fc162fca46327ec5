//! `kepler include`: INCLUDE for a list of points.

use crate::output::answer_points;
use anyhow::Result;
use kepler::io::points::read_points;
use kepler::queries::include::{IncludeIndex, Inclusion};
use kepler::scene::file;
use std::path::PathBuf;

/// INCLUDE: print IN, OUT or ON for each point, in order (a summary goes to stderr).
#[derive(clap::Args)]
pub struct Args {
    /// A scene file (.toml) or a mesh file; every mesh must be closed.
    scene: PathBuf,
    /// The points: one `x y z` per line (commas or spaces; `#` comments and blank lines
    /// allowed); `-` reads standard input.
    #[arg(long)]
    points: PathBuf,
}

/// Answers INCLUDE for every point.
pub fn run(args: Args) -> Result<()> {
    let scene = file::load(&args.scene)?;
    let points = read_points(&args.points)?;
    answer_points(
        "include",
        &points,
        &[Inclusion::In, Inclusion::Out, Inclusion::On],
        || Ok(IncludeIndex::whole_scene(&scene)?),
        |index, points| index.include_all(points),
    )
}
