//! `kepler render`: the exact hidden-line drawing of a scene, as SVG (and JSON).

use crate::args::{FaceArgs, ViewArgs, load_drawable, parse_area, parse_triple};
use crate::finish::{FinishArgs, Hidden, is_dxf};
use crate::output::{progress_bar, write_file};
use anyhow::Result;
use kepler::geometry::Vector3;
use kepler::geometry::polygon::bounding_box;
use kepler::hidden::ideographs::{Ideograph, ideographs};
use kepler::hidden::tiles::TileFile;
use kepler::hidden::verify::{Traced, draw_traced, verify};
use kepler::hidden::{self, Drawing, EdgeClass, EdgeSelection};
use kepler::output::{
    Finishing, HatchLayer, PageTransform, Shading, SvgOptions, finish, ordered_paths,
    page_transform,
};
use kepler::scene::Scene;
use kepler::surfaces::hatch::{Hatching, hatch_faces};
use kepler::surfaces::visible_surfaces;
use kepler::views::{Picture, View};
use std::fmt::Write as _;
use std::path::PathBuf;
use std::time::{Duration, Instant};

/// Draw the scene's visible (and hidden) lines exactly, as SVG (and JSON).
#[derive(clap::Args)]
pub struct Args {
    /// A scene file (.toml) or a mesh file (.obj, .stl, .off, .ply).
    scene: PathBuf,
    /// The file to write: SVG, or DXF when its name ends in `.dxf` (`-` writes SVG to
    /// standard output); with `--tile`, the tile file (`.kpt`) that `kepler stitch` reads.
    #[arg(short = 'o', long = "output", value_name = "FILE")]
    output: PathBuf,
    /// Which edges: `feature` (silhouette, boundary, crease, intersection), `all` (smooth
    /// edges too: a wireframe with hidden parts removed) or `mesh` (every edge of the input
    /// polygons, even between coplanar faces, with hidden parts removed).
    #[arg(long, value_enum, default_value_t = EdgeSelection::Feature)]
    edges: EdgeSelection,
    /// An edge whose faces bend by more than this many degrees is a crease.
    #[arg(long, value_name = "DEGREES", default_value_t = 30.0)]
    crease_angle: f64,
    #[command(flatten)]
    finish: FinishArgs,
    /// Print the degenerate faces dropped and the polygons split, what each stage computed
    /// and skipped, its time, and the visible and hidden length of each edge class (to
    /// stderr).
    #[arg(long)]
    stats: bool,
    /// Check the drawing independently (VISP at points of every piece, silhouettes by a sign
    /// test, the drawing against its pieces), print the checks and disagreements (to stderr),
    /// and fail on any disagreement. The files written are the same.
    #[arg(long)]
    verify: bool,
    #[command(flatten)]
    faces: FaceArgs,
    /// Franklin's ideographs: an object whose CBOX's picture is smaller than this many
    /// square millimetres on the page is drawn as its CBOX, or left out (`--ideograph`).
    #[arg(long, value_name = "MM2", value_parser = parse_area)]
    ideograph_below: Option<f64>,
    /// What a small object becomes: `bound` (its CBOX) or `omit`.
    #[arg(long, value_enum, default_value_t = Ideograph::Bound)]
    ideograph: Ideograph,
    /// Hatch the visible faces (SVG only): parallel lines, denser on darker faces (Lambert
    /// shading, `--light`), clipped exactly to each face's visible polygons, in their own
    /// layer `hatch` between the hidden and the visible lines. A face lit head-on gets none.
    #[arg(long)]
    hatch: bool,
    /// With `--hatch`: the direction towards the light, in scene coordinates (default: over
    /// the viewer's left shoulder: towards the eye, up and to the left in the picture).
    #[arg(long, value_name = "X,Y,Z", value_parser = parse_triple, allow_hyphen_values = true)]
    light: Option<[f64; 3]>,
    /// With `--hatch`: the angle of the hatch lines on the page, in degrees counter-clockwise
    /// from the horizontal.
    #[arg(
        long,
        value_name = "DEGREES",
        default_value_t = 45.0,
        allow_hyphen_values = true
    )]
    hatch_angle: f64,
    /// With `--hatch`: the spacing of hatch lines on the page in millimetres, `MIN,MAX`: the
    /// darkest faces get MIN; spacing grows as MIN / darkness, and a face that would get more
    /// than MAX gets none.
    #[arg(long, value_name = "MIN,MAX", value_parser = parse_spacing, default_value = "0.5,3")]
    hatch_spacing: [f64; 2],
    /// With `--hatch`: the hatch lines' stroke width in millimetres.
    #[arg(long, value_name = "MM", default_value_t = 0.1)]
    hatch_stroke: f64,
    /// Draw one tile of a grid of `COLUMNSxROWS` windows over the picture (with `--tile`):
    /// each tile can be drawn by another process or machine, and `kepler stitch` joins the
    /// tile files into this drawing, bit for bit.
    #[arg(long, value_name = "CxR", value_parser = parse_grid, requires = "tile")]
    tiles: Option<[usize; 2]>,
    /// With `--tiles`: the tile to draw, `COLUMN,ROW`, counted from 0 from the bottom left.
    #[arg(long, value_name = "I,J", value_parser = parse_tile, requires = "tiles")]
    tile: Option<[usize; 2]>,
    #[command(flatten)]
    view: ViewArgs,
}

/// Parses a grid `CxR` (columns and rows, at least 1 each).
fn parse_grid(text: &str) -> Result<[usize; 2], String> {
    match text
        .split_once(['x', 'X'])
        .map(|(c, r)| (c.trim().parse(), r.trim().parse()))
    {
        Some((Ok(c), Ok(r))) if c > 0 && r > 0 => Ok([c, r]),
        _ => Err(format!("expected COLUMNSxROWS (like 4x4), got '{text}'")),
    }
}

/// Parses a tile `I,J` (column and row, from 0).
fn parse_tile(text: &str) -> Result<[usize; 2], String> {
    match text
        .split_once(',')
        .map(|(i, j)| (i.trim().parse(), j.trim().parse()))
    {
        Some((Ok(i), Ok(j))) => Ok([i, j]),
        _ => Err(format!("expected COLUMN,ROW (like 2,3), got '{text}'")),
    }
}

/// Parses `MIN,MAX` (millimetres, `0 < MIN ≤ MAX`, finite).
fn parse_spacing(text: &str) -> Result<[f64; 2], String> {
    let fields: Vec<&str> = text.split(',').map(str::trim).collect();
    match fields[..] {
        [a, b] => match (a.parse::<f64>(), b.parse::<f64>()) {
            (Ok(a), Ok(b)) if a.is_finite() && b.is_finite() && a > 0.0 && a <= b => Ok([a, b]),
            _ => Err(format!("'{text}' is not two spacings 0 < MIN ≤ MAX in mm")),
        },
        _ => Err(format!("expected MIN,MAX in mm (like 0.5,3), got '{text}'")),
    }
}

/// Draws the scene and writes the drawing.
pub fn run(args: Args) -> Result<()> {
    checked(&args)?;
    let crease_angle = args.crease_angle;
    let started = Instant::now();
    let scene = load_drawable(&args.scene, args.faces.validation())?;
    let repairs = repairs(&scene);
    let svg_options = args.finish.svg_options();
    let view = args.view.view_on(&scene, svg_options.drawing_aspect())?;
    let options = args.finish.options(args.edges, crease_angle);
    let (scene, culled) = match args.ideograph_below {
        Some(mm2) => {
            let min_area = picture_area(&scene, &view, &svg_options, mm2);
            let small = ideographs(&scene, &view, min_area, args.ideograph)?;
            let counts = (small.culled, small.triangles_culled, small.triangles_added);
            (small.scene, Some(counts))
        }
        None => (scene, None),
    };
    let loaded = started.elapsed();
    if let (Some(grid), Some(at)) = (args.tiles, args.tile) {
        let tile = TileFile::draw(&scene, &view, &options, grid, at)?;
        let bytes = tile.to_bytes();
        return write_file(&args.output, |out| out.write_all(&bytes));
    }
    let traced = draw(&scene, &view, &options, args.verify)?;
    let finishing = Finishing {
        order: args.finish.order,
    };
    // `--verify` checks the drawing as the pass made it, and its pieces.
    let (finished, traced) = if args.verify {
        (finish(traced.drawing.clone(), &finishing), Some(traced))
    } else {
        (finish(traced.drawing, &finishing), None)
    };
    let drawing = &finished.drawing;
    let (hatches, hatch_stats) = if args.hatch {
        hatch(&scene, &view, drawing, &svg_options, &args)?
    } else {
        (HatchLayer::default(), String::new())
    };
    let written = args
        .finish
        .write(&args.output, drawing, &hatches, &svg_options)?;
    if args.stats {
        if let Some((objects, removed, added)) = culled {
            eprintln!(
                "ideographs: {objects} objects below {} mm² culled ({removed} triangles; \
                 {added} triangles of bounds drawn instead)",
                args.ideograph_below.unwrap_or(0.0)
            );
        }
        eprintln!("{repairs}");
        let plotter = finished.stats() + &hatch_stats;
        eprint!("{}", stats_report(drawing, loaded, &plotter, written));
    }
    if let Some(traced) = &traced {
        let report = verify(&scene, &view, &options, traced);
        eprint!("{report}");
        if report.disagreements > 0 {
            anyhow::bail!(
                "verify: the drawing disagrees with {} of {} checks",
                report.disagreements,
                report.checks()
            );
        }
    }
    Ok(())
}

/// The arguments' errors that clap does not catch.
fn checked(args: &Args) -> Result<()> {
    let crease_angle = args.crease_angle;
    if !(crease_angle.is_finite() && (0.0..=180.0).contains(&crease_angle)) {
        anyhow::bail!("--crease-angle must be between 0 and 180 degrees, not {crease_angle}");
    }
    if args.light == Some([0.0; 3]) {
        anyhow::bail!("--light 0,0,0 has no direction: give a nonzero vector towards the light");
    }
    if !(args.hatch_angle.is_finite() && args.hatch_stroke.is_finite() && args.hatch_stroke >= 0.0)
    {
        anyhow::bail!("--hatch-angle and --hatch-stroke must be finite (the stroke nonnegative)");
    }
    if is_dxf(&args.output) && args.hatch {
        anyhow::bail!("--hatch writes SVG only, not DXF");
    }
    if args.tile.is_some() {
        let finishing = [
            (args.hatch, "--hatch"),
            (args.verify, "--verify"),
            (args.stats, "--stats"),
            (args.finish.order, "--order"),
            (args.finish.keep_overlaps, "--keep-overlaps"),
            (args.finish.json.is_some(), "--json"),
            (args.finish.hidden == Hidden::Omit, "--hidden omit"),
        ];
        if let Some((_, option)) = finishing.iter().find(|(given, _)| *given) {
            anyhow::bail!(
                "{option} finishes a whole drawing, not a tile: give it to `kepler stitch`"
            );
        }
        if args.output.extension().is_none_or(|e| e != "kpt") {
            anyhow::bail!(
                "with --tile the output is a tile file, whose name ends in .kpt, not {}",
                args.output.display()
            );
        }
    }
    Ok(())
}

/// The hatch layer (`--hatch`): every face's visible polygons, shaded, hatched at the page
/// spacing (millimetres turned into view units by the drawing's page scale); and its
/// `--stats` line.
fn hatch(
    scene: &Scene,
    view: &View,
    drawing: &Drawing,
    svg_options: &SvgOptions,
    args: &Args,
) -> Result<(HatchLayer, String)> {
    let clock = Instant::now();
    let faces = visible_surfaces(scene, view)?;
    let shading = Shading {
        light: args.light.map(Vector3::from),
        outlines: false,
    };
    let shades = shading.shades(&faces, scene, view);
    let scale = page_transform(drawing, svg_options).scale;
    let hatching = Hatching {
        angle: args.hatch_angle,
        spacing: args.hatch_spacing.map(|mm| mm / scale),
    };
    let hatched = hatch_faces(&faces, &shades, &hatching)?;
    let polylines: Vec<Vec<[f64; 2]>> = hatched
        .iter()
        .flat_map(|f| f.hatch.runs.iter().map(|r| r.points.clone()))
        .collect();
    let polylines = if args.finish.order {
        ordered_paths(polylines)
    } else {
        polylines
    };
    let segments: usize = polylines.iter().map(|p| p.len() - 1).sum();
    let dropped: usize = hatched.iter().map(|f| f.hatch.dropped).sum();
    let stats = format!(
        "hatch          {:>7.4}  {} of {} faces hatched: {} lines, {segments} segments \
         ({dropped} dropped by the exact check)\n",
        clock.elapsed().as_secs_f64(),
        hatched.len(),
        faces.len(),
        polylines.len(),
    );
    Ok((
        HatchLayer {
            polylines,
            stroke: args.hatch_stroke,
        },
        stats,
    ))
}

/// What validation repaired in the scene's meshes: the `--stats` line.
fn repairs(scene: &Scene) -> String {
    let meshes = scene.mesh_objects(scene.roots());
    let sum = |count: fn(&kepler::mesh::Mesh) -> usize| {
        meshes.iter().map(|(_, m)| count(m)).sum::<usize>()
    };
    format!(
        "faces: {} degenerate faces dropped, {} polygons not exactly planar split into \
         triangles, {} sides matched at T-junctions (in {} meshes)",
        sum(kepler::mesh::Mesh::degenerate_faces),
        sum(kepler::mesh::Mesh::split_polygons),
        sum(kepler::mesh::Mesh::t_junctions),
        meshes.len()
    )
}

/// An area of `mm2` square millimetres on the page in picture units squared, at the page
/// scale of the whole scene (the ideographs' threshold).
fn picture_area(scene: &Scene, view: &View, svg_options: &SvgOptions, mm2: f64) -> f64 {
    let picture = Picture::of(view);
    let points = scene
        .mesh_objects(scene.roots())
        .into_iter()
        .flat_map(|(_, m)| m.vertices().iter().map(|v| picture.point(v)))
        .collect::<Vec<_>>();
    let [lo, hi] = bounding_box(points);
    let scale = PageTransform::fit(Some((lo, hi)), svg_options).scale;
    mm2 / (scale * scale)
}

/// The drawing, with a progress bar on a terminal, and its pieces traced to their lines when
/// they are to be verified (else none).
fn draw(scene: &Scene, view: &View, options: &hidden::Options, traced: bool) -> Result<Traced> {
    let bar = progress_bar();
    let progress = |done, total| {
        if let Some(bar) = &bar {
            bar.set_length(total);
            bar.set_position(done);
        }
    };
    let traced = if traced {
        draw_traced(scene, view, options, &progress)?
    } else {
        Traced {
            drawing: hidden::draw_with_progress(scene, view, options, &progress)?,
            pieces: Vec::new(),
            kept: None,
        }
    };
    if let Some(bar) = bar {
        bar.finish_and_clear();
    }
    Ok(traced)
}

/// The `--stats` report: each stage, then lengths per class.
fn stats_report(drawing: &Drawing, loaded: Duration, plotter: &str, written: Duration) -> String {
    let mut text = String::new();
    let _ = writeln!(text, "stage          seconds  computed / skipped");
    let _ = writeln!(
        text,
        "load           {:>7.4}  scene file and meshes",
        loaded.as_secs_f64()
    );
    for stage in &drawing.stages {
        let _ = writeln!(
            text,
            "{:<14} {:>7.4}  {}",
            stage.name, stage.seconds, stage.done
        );
        if let Some(skipped) = &stage.skipped {
            let _ = writeln!(text, "{:<14} {:>7}  skipped: {skipped}", "", "");
        }
    }
    text += plotter;
    let _ = writeln!(
        text,
        "write          {:>7.4}  output files",
        written.as_secs_f64()
    );
    let _ = writeln!(
        text,
        "class          visible length  hidden length  (view coordinates)"
    );
    for class in EdgeClass::ALL.into_iter().rev() {
        let _ = writeln!(
            text,
            "{:<14} {:>14.6} {:>14.6}",
            class.name(),
            drawing.length(class, true),
            drawing.length(class, false)
        );
    }
    text
}
