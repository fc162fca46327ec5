//! `kepler surfaces`: every face's visible polygons, as a shaded SVG (and JSON).

use crate::args::{FaceArgs, PageArgs, ViewArgs, load_drawable, parse_triple};
use crate::output::write_file;
use anyhow::Result;
use kepler::geometry::Vector3;
use kepler::output::{Shading, write_surfaces_json, write_surfaces_svg};
use kepler::surfaces::visible_surfaces;
use std::path::PathBuf;

/// Visible surfaces: every face's visible polygons (Franklin's VISFAC), as a shaded SVG
/// (and JSON).
#[derive(clap::Args)]
pub struct Args {
    /// A scene file (.toml) or a mesh file (.obj, .stl, .off, .ply).
    scene: PathBuf,
    /// The SVG file to write (`-` writes standard output).
    #[arg(short = 'o', long = "output", value_name = "FILE")]
    output: PathBuf,
    /// Also write each face's status and polygons as JSON to this file.
    #[arg(long, value_name = "FILE")]
    json: Option<PathBuf>,
    /// The direction towards the light (default: over the viewer's left shoulder).
    #[arg(long, value_name = "X,Y,Z", value_parser = parse_triple, allow_hyphen_values = true)]
    light: Option<[f64; 3]>,
    /// Outline the visible polygons.
    #[arg(long)]
    outlines: bool,
    #[command(flatten)]
    faces: FaceArgs,
    #[command(flatten)]
    page: PageArgs,
    #[command(flatten)]
    view: ViewArgs,
}

/// Computes the visible surfaces and writes them.
pub fn run(args: Args) -> Result<()> {
    if args.light == Some([0.0; 3]) {
        anyhow::bail!("--light 0,0,0 has no direction: give a nonzero vector towards the light");
    }
    let scene = load_drawable(&args.scene, args.faces.validation())?;
    let options = args.page.svg_options();
    let view = args.view.view_on(&scene, options.drawing_aspect())?;
    let faces = visible_surfaces(&scene, &view)?;
    let shading = Shading {
        light: args.light.map(Vector3::from),
        outlines: args.outlines,
    };
    write_file(&args.output, |mut out| {
        write_surfaces_svg(&faces, &scene, &view, &options, &shading, &mut out)
    })?;
    if let Some(json) = &args.json {
        write_file(json, |mut out| {
            write_surfaces_json(&faces, &scene, &mut out)
        })?;
    }
    Ok(())
}
