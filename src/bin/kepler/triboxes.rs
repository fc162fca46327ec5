//! `kepler triboxes`: hierarchical triboxes, their levels of detail as a table (and JSON, and a
//! drawing).

use crate::args::{PageArgs, ViewArgs, find_object, load_drawable};
use crate::output::{emit, write_file, write_json_file};
use anyhow::Result;
use kepler::hidden;
use kepler::lab::tribox_hierarchy::{
    Hierarchy, HierarchyOptions, Level, SplitRule, Stop, TriboxesError,
};
use kepler::mesh::Mesh;
use kepler::mesh::Validation;
use kepler::output::write_svg;
use kepler::scene::Scene;
use std::path::{Path, PathBuf};

/// The levels reported without `--levels`.
const LEVELS: usize = 4;

/// Hierarchical triboxes (Crosnier and Rossignac 1999, §4): split a closed object by
/// planes across the tribox's 9 directions while the triboxes' total area drops, and print
/// each level of detail (triboxes, faces M, compression N/M, volume and area excess,
/// Hausdorff distance bounds).
#[derive(clap::Args)]
pub struct Args {
    /// A scene file (.toml) or a mesh file.
    scene: PathBuf,
    /// The object (its path, e.g. `round/ring`); default: all objects together.
    #[arg(long, value_name = "PATH")]
    object: Option<String>,
    /// How many levels to report (depths 0 to K−1; default 4, as deep as `--gain` splits).
    /// Given, all K are made (within --max-depth): a level that the gain would not split is
    /// split regardless, and marked `*`.
    #[arg(long, value_name = "K")]
    levels: Option<usize>,
    /// Split a cell only when the total tribox area drops by this fraction (negative:
    /// may rise by that fraction, to build deeper levels).
    #[arg(
        long,
        value_name = "FRACTION",
        default_value_t = 0.05,
        allow_hyphen_values = true
    )]
    gain: f64,
    /// Split no cell deeper than this.
    #[arg(long, value_name = "DEPTH", default_value_t = 8)]
    max_depth: usize,
    /// The candidate splitting planes: the paper's `thickest` slab's bisector, the nine
    /// `bisectors`, or also planes through the object's vertices (`features`); of those
    /// that lower the total tribox area enough (`--gain`), the least total volume wins.
    #[arg(long, value_enum, default_value_t = SplitRule::Bisectors)]
    split: SplitRule,
    /// Draw the object and the levels side by side (hidden lines removed) to this SVG file.
    #[arg(short = 'o', long = "output", value_name = "FILE")]
    output: Option<PathBuf>,
    /// Also write the levels and the nodes as JSON to this file.
    #[arg(long, value_name = "FILE")]
    json: Option<PathBuf>,
    #[command(flatten)]
    page: PageArgs,
    #[command(flatten)]
    view: ViewArgs,
}

/// Builds the hierarchy, prints its levels and writes the JSON and the drawing.
pub fn run(args: Args) -> Result<()> {
    let scene = load_drawable(&args.scene, Validation::Repair)?;
    let (name, mesh) = object(&scene, &args.scene, args.object.as_deref())?;
    let options = HierarchyOptions {
        gain: args.gain,
        max_depth: args.max_depth,
        split: args.split,
        levels: args.levels,
        ..HierarchyOptions::default()
    };
    let hierarchy = Hierarchy::build(&mesh, &options).map_err(|e| match e {
        // The command sets no option but the gain that the library checks.
        TriboxesError::Option(message) => anyhow::anyhow!("--gain: {message}"),
        e => anyhow::anyhow!("object '{name}': {e}"),
    })?;
    let wanted = args.levels.unwrap_or(LEVELS);
    let report = hierarchy.levels(wanted);
    emit(&table(&name, mesh.faces().len(), &report, args.gain))?;
    if let Some(json) = &args.json {
        let value = serde_json::json!({
            "object": name,
            "faces": mesh.faces().len(),
            "volume": mesh.volume(),
            "area": mesh.surface_area(),
            "levels": report,
            "nodes": hierarchy.nodes(),
        });
        write_json_file(json, &value)?;
    }
    if let Some(output) = &args.output {
        let view = args.view.view(&scene)?;
        let panels = hierarchy.panels(&mesh, report.len(), &view)?;
        let drawing = hidden::draw(&panels, &view, &hidden::Options::default())?;
        write_file(output, |mut out| {
            write_svg(&drawing, &args.page.svg_options(), &mut out)
        })?;
    }
    if report.len() < wanted {
        eprintln!("{}", stop_note(&hierarchy, wanted, args.gain));
    }
    Ok(())
}

/// The object's name and mesh: the one named, or all objects together.
fn object(scene: &Scene, path: &Path, object: Option<&str>) -> Result<(String, Mesh)> {
    if let Some(name) = object {
        let id = find_object(scene, path, name)?;
        return Ok((scene.path(id), scene.flatten(id)?));
    }
    // Name the first object that cannot bound a solid, not only the file.
    let roots = scene.mesh_objects(scene.roots());
    if let Some((id, _)) = roots.iter().find(|(_, m)| !m.is_solid()) {
        anyhow::bail!("object '{}': {}", scene.path(*id), TriboxesError::NotSolid);
    }
    let mesh = scene
        .flatten_all()
        .map_err(|e| anyhow::anyhow!("{}: {e}", path.display()))?;
    Ok((path.display().to_string(), mesh))
}

/// The table of `kepler triboxes`: a row per level, a level split below the gain marked `*`
/// and explained under the table.
fn table(name: &str, faces: usize, levels: &[Level], gain: f64) -> String {
    let mut t = format!("{name}: N = {faces} faces\n");
    t += &format!(
        "{:>5} {:>8} {:>7} {:>11} {:>13} {:>11}  {}\n",
        "depth",
        "triboxes",
        "faces M",
        "compression",
        "volume excess",
        "area excess",
        "hausdorff (lower bound)"
    );
    for l in levels {
        t += &format!(
            "{:>5} {:>8} {:>7} {:>11.2} {:>12.2}% {:>10.2}%  {:.6} ({:.6}){}\n",
            l.depth,
            l.triboxes,
            l.faces,
            l.compression,
            100.0 * l.volume_excess,
            100.0 * l.area_excess,
            l.hausdorff,
            l.hausdorff_lower,
            if l.below_gain { "  *" } else { "" }
        );
    }
    if levels.iter().any(|l| l.below_gain) {
        t += &format!(
            "* below the gain of {}: split for --levels, although no split lowers a cell's \
             tribox area by the gain\n",
            gain
        );
    }
    t
}

/// Why the hierarchy has fewer levels than `wanted`, and what would make more.
fn stop_note(hierarchy: &Hierarchy, wanted: usize, gain: f64) -> String {
    let depth = hierarchy.depth();
    let why = match hierarchy.stop() {
        Stop::MaxDepth => format!("its cells are at --max-depth {depth}"),
        Stop::Gain { best_gain } => format!(
            "no split lowers a cell's tribox area by the gain of {}; --gain {} admits the best \
             one, --levels {wanted} splits regardless",
            gain,
            rounded_down(best_gain)
        ),
        Stop::NoPlane => "no plane splits its cells further".to_string(),
    };
    format!(
        "note: the hierarchy stops at depth {depth} ({} of {wanted} levels): {why}",
        depth + 1
    )
}

/// A gain at most `gain` in thousandths, to print: any gain at most `gain` admits what it does.
fn rounded_down(gain: f64) -> f64 {
    let thousandths = (gain * 1000.0).floor();
    if thousandths / 1000.0 <= gain {
        thousandths / 1000.0
    } else {
        (thousandths - 1.0) / 1000.0
    }
}
