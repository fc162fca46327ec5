//! The `kepler` command line.

use anyhow::Result;
use clap::{Args, Parser, Subcommand};
use geo::Line;
use indicatif::{ProgressBar, ProgressStyle};
use kepler::bounds::tribox::Tribox;
use kepler::geometry::polygon::bounding_box;
use kepler::geometry::{Point3, Vector3};
use kepler::grid::{intersecting_pairs, random_segments};
use kepler::hidden::ideographs::{Ideograph, ideographs};
use kepler::hidden::{self, Drawing, EdgeClass, EdgeSelection};
use kepler::io::points::{read_points, read_segments};
use kepler::lab::boxtree::spheres::{DEFAULT_GAP, PAPER_FACETS};
use kepler::lab::boxtree::{Merge, sphere_experiment};
use kepler::lab::culling::{CullReport, cull};
use kepler::lab::tribox_hierarchy::{
    Hierarchy, HierarchyOptions as TriboxOptions, Level, SplitRule, TriboxesError, tribox_mesh,
};
use kepler::mesh::Mesh;
use kepler::output::{
    PageTransform, Shading, SvgOptions, write_json, write_surfaces_json, write_surfaces_svg,
    write_svg,
};
use kepler::queries::Counters;
use kepler::queries::include::{IncludeIndex, Inclusion};
use kepler::queries::visp::{Visibility, VisibilityIndex};
use kepler::scene::{Scene, file, report::BoundsReport};
use kepler::surfaces::{visible_surfaces, visobj};
use kepler::views::{Picture, View, ViewOptions};
use std::fmt::Write as _;
use std::io::IsTerminal;
use std::io::Write;
use std::path::PathBuf;
use std::process::ExitCode;
use std::time::{Duration, Instant};

/// kepler: exact visibility for scenes of polyhedra.
#[derive(Parser)]
#[command(name = "kepler", version, about)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Print each object's faces, vertices, CBOX, INBOX, tribox and how tightly they fit.
    Bounds {
        /// A scene file (.toml) or a mesh file (.obj, .stl, .off).
        scene: PathBuf,
        /// Print JSON instead of a table.
        #[arg(long)]
        json: bool,
    },
    /// INCLUDE: print IN, OUT or ON for each point, in order (a summary goes to stderr).
    Include {
        /// A scene file (.toml) or a mesh file; every mesh must be closed.
        scene: PathBuf,
        /// The points: one `x y z` per line (commas or spaces; `#` comments and blank lines
        /// allowed); `-` reads standard input.
        #[arg(long)]
        points: PathBuf,
    },
    /// Franklin's uniform-grid segment intersection: print N, the number K of intersecting
    /// pairs, and the seconds taken (grid and pairs, not reading or generating).
    Segx {
        /// Generate this many random segments in the unit square (Franklin's experiment).
        #[arg(long, conflicts_with = "input", required_unless_present = "input")]
        n: Option<usize>,
        /// The length of the random segments (at most 1).
        #[arg(long, default_value_t = 0.01)]
        len: f64,
        /// The seed of the random segments.
        #[arg(long, default_value_t = 1)]
        seed: u64,
        /// Read the segments instead: one `x1 y1 x2 y2` per line; `-` reads standard input.
        #[arg(long)]
        input: Option<PathBuf>,
        /// List each intersecting pair `i j` (line numbers of the input, or 1-based indices of
        /// the random segments) on standard output; the summary then goes to standard error.
        #[arg(long)]
        pairs: bool,
    },
    /// Draw the scene's visible (and hidden) lines exactly, as SVG (and JSON).
    Render {
        /// A scene file (.toml) or a mesh file (.obj, .stl, .off).
        scene: PathBuf,
        /// The SVG file to write (`-` writes standard output).
        #[arg(short = 'o', long = "output", value_name = "FILE")]
        output: PathBuf,
        /// Which edges: `feature` (silhouette, boundary, crease, intersection) or `all` (smooth
        /// edges too: a wireframe with hidden parts removed).
        #[arg(long, value_enum, default_value_t = Edges::Feature)]
        edges: Edges,
        /// An edge whose faces bend by more than this many degrees is a crease.
        #[arg(long, value_name = "DEGREES", default_value_t = 30.0)]
        crease_angle: f64,
        /// Hidden lines: `dashed` (their own grey dashed layers) or `omit`.
        #[arg(long, value_enum, default_value_t = Hidden::Dashed)]
        hidden: Hidden,
        #[command(flatten)]
        page: PageArgs,
        /// A stroke width in millimetres for one class, `CLASS=MM` (classes: silhouette,
        /// boundary, crease, intersection, smooth); repeat for several.
        #[arg(long, value_name = "CLASS=MM", value_parser = parse_stroke)]
        stroke: Vec<(EdgeClass, f64)>,
        /// Also write the polylines as JSON, in view coordinates, to this file.
        #[arg(long, value_name = "FILE")]
        json: Option<PathBuf>,
        /// Print what each stage computed and skipped, its time, and the visible and hidden
        /// length of each edge class (to stderr).
        #[arg(long)]
        stats: bool,
        /// Franklin's ideographs: an object whose CBOX's picture is smaller than this many
        /// square millimetres on the page is drawn as its CBOX, or left out (`--ideograph`).
        #[arg(long, value_name = "MM2", value_parser = parse_area)]
        ideograph_below: Option<f64>,
        /// What a small object becomes: `bound` (its CBOX) or `omit`.
        #[arg(long, value_enum, default_value_t = IdeographMode::Bound)]
        ideograph: IdeographMode,
        #[command(flatten)]
        view: ViewArgs,
    },
    /// Visible surfaces: every face's visible polygons (Franklin's VISFAC), as a shaded SVG
    /// (and JSON).
    Surfaces {
        /// A scene file (.toml) or a mesh file (.obj, .stl, .off).
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
        page: PageArgs,
        #[command(flatten)]
        view: ViewArgs,
    },
    /// VISOBJ: print VISIBLE, HIDDEN or MIXED as object A hides nothing, all or part of
    /// object B (objects named by their paths, like `block/tower-west`).
    Visobj {
        /// A scene file (.toml).
        scene: PathBuf,
        /// The object that may hide.
        a: String,
        /// The object that may be hidden.
        b: String,
        #[command(flatten)]
        view: ViewArgs,
    },
    /// Culling experiment: for one view, how many pairs of objects each bounding volume
    /// (rstar on projected boxes, CBOX, TRIBOX, INBOX) proves not to interact, and the
    /// triangle pairs that saves the hidden-line pass.
    Cull {
        /// A scene file (.toml) or a mesh file.
        scene: PathBuf,
        /// Also write the table as JSON to this file.
        #[arg(long, value_name = "FILE")]
        json: Option<PathBuf>,
        #[command(flatten)]
        view: ViewArgs,
    },
    /// BOXTREE experiments (Barequet et al. 1996): `--experiment spheres` counts the
    /// collision tests between pairs of concentric random spheres (556, 1,996 and 9,996
    /// facets) for every node shape, beside the paper's Table 1.
    Boxtree {
        /// The experiment to run.
        #[arg(long, value_enum)]
        experiment: Experiment,
        /// The merge rule: smallest parent `volume` (the paper's Table 1) or `area`.
        #[arg(long, value_enum, default_value_t = MergeRule::Volume)]
        merge: MergeRule,
        /// Also write the rows as JSON to this file.
        #[arg(long, value_name = "FILE")]
        json: Option<PathBuf>,
    },
    /// Hierarchical triboxes (Crosnier and Rossignac 1999, §4): split a closed object by
    /// planes across the tribox's 9 directions while the triboxes' total area drops, and print
    /// each level of detail (triboxes, faces M, compression N/M, volume and area excess,
    /// Hausdorff distance bounds).
    Triboxes {
        /// A scene file (.toml) or a mesh file.
        scene: PathBuf,
        /// The object (its path, e.g. `round/ring`); default: all objects together.
        #[arg(long, value_name = "PATH")]
        object: Option<String>,
        /// How many levels to report (depths 0 to K−1).
        #[arg(long, value_name = "K", default_value_t = 4)]
        levels: usize,
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
        #[arg(long, value_enum, default_value_t = SplitArg::Bisectors)]
        split: SplitArg,
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
    },
    /// VISP: print VISIBLE or HIDDEN for each point, in order (a summary goes to stderr).
    Visp {
        /// A scene file (.toml) or a mesh file.
        scene: PathBuf,
        /// The points: one `x y z` per line (commas or spaces; `#` comments and blank lines
        /// allowed); `-` reads standard input.
        #[arg(long)]
        points: PathBuf,
        #[command(flatten)]
        view: ViewArgs,
    },
}

/// The view options every command that takes a view accepts. Without them: the scene file's
/// camera, else an isometric view along (-1,-1,-1) with z up.
#[derive(Args)]
struct ViewArgs {
    /// Orthographic view along this direction (`0,0,-1` is Franklin's view from (0,0,+∞)).
    #[arg(long, value_name = "X,Y,Z", value_parser = parse_triple, allow_hyphen_values = true)]
    view_dir: Option<[f64; 3]>,
    /// The direction that appears upward in the picture.
    #[arg(long, value_name = "X,Y,Z", value_parser = parse_triple, allow_hyphen_values = true)]
    up: Option<[f64; 3]>,
    /// Perspective view from this eye point (with --target).
    #[arg(long, value_name = "X,Y,Z", value_parser = parse_triple, allow_hyphen_values = true)]
    eye: Option<[f64; 3]>,
    /// The point a perspective view looks at (with --eye).
    #[arg(long, value_name = "X,Y,Z", value_parser = parse_triple, allow_hyphen_values = true)]
    target: Option<[f64; 3]>,
    /// Vertical field of view of a perspective view, in degrees (default 40).
    #[arg(long, value_name = "DEGREES", allow_hyphen_values = true)]
    fov: Option<f64>,
}

impl ViewArgs {
    /// The view over the scene's camera.
    fn view(&self, scene: &Scene) -> kepler::Result<View> {
        let options = ViewOptions {
            view_dir: self.view_dir.map(Vector3::from),
            up: self.up.map(Vector3::from),
            eye: self.eye.map(Point3::from),
            target: self.target.map(Point3::from),
            fov: self.fov,
        };
        Ok(options.resolve(scene.camera())?)
    }
}

/// The page options of the commands that write SVG.
#[derive(Args)]
struct PageArgs {
    /// Page size in millimetres, `WIDTHxHEIGHT` (default A4 landscape).
    #[arg(long, value_name = "WxH", value_parser = parse_page, default_value = "297x210")]
    page: [f64; 2],
    /// Page margin in millimetres.
    #[arg(long, value_name = "MM", default_value_t = 10.0)]
    margin: f64,
}

impl PageArgs {
    /// The SVG options with this page and margin.
    fn svg_options(&self) -> SvgOptions {
        SvgOptions {
            page: self.page,
            margin: self.margin,
            ..SvgOptions::default()
        }
    }
}

/// Loads a scene to draw: an error naming the file if it holds no mesh.
fn load_drawable(path: &std::path::Path) -> Result<Scene> {
    let scene = file::load(path)?;
    if scene.mesh_objects(scene.roots()).is_empty() {
        anyhow::bail!("{}: the scene has no objects to draw", path.display());
    }
    Ok(scene)
}

/// `--split`.
#[derive(Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
enum SplitArg {
    Thickest,
    Bisectors,
    Features,
}

/// `--experiment`.
#[derive(Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
enum Experiment {
    /// Concentric random spheres (the paper's Table 1 setting).
    Spheres,
}

/// `--merge`.
#[derive(Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
enum MergeRule {
    Volume,
    Area,
}

/// `--ideograph`.
#[derive(Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
enum IdeographMode {
    Bound,
    Omit,
}

/// A nonnegative finite area.
fn parse_area(s: &str) -> std::result::Result<f64, String> {
    match s.trim().parse::<f64>() {
        Ok(a) if a.is_finite() && a >= 0.0 => Ok(a),
        _ => Err(format!("'{s}' is not a nonnegative area in mm²")),
    }
}

/// `--edges`.
#[derive(Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
enum Edges {
    Feature,
    All,
}

/// `--hidden`.
#[derive(Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
enum Hidden {
    Dashed,
    Omit,
}

/// Parses `WIDTHxHEIGHT` (millimetres, positive).
fn parse_page(text: &str) -> Result<[f64; 2], String> {
    let fields: Vec<&str> = text.split(['x', 'X']).map(str::trim).collect();
    match fields[..] {
        [w, h] => match (w.parse::<f64>(), h.parse::<f64>()) {
            (Ok(w), Ok(h)) if w.is_finite() && h.is_finite() && w > 0.0 && h > 0.0 => Ok([w, h]),
            _ => Err(format!("'{text}' is not two positive sizes in mm")),
        },
        _ => Err(format!(
            "expected WIDTHxHEIGHT in mm (like 297x210), got '{text}'"
        )),
    }
}

/// Parses `CLASS=MM`.
fn parse_stroke(text: &str) -> Result<(EdgeClass, f64), String> {
    let (name, width) = text
        .split_once('=')
        .ok_or_else(|| format!("expected CLASS=MM, got '{text}'"))?;
    let class = EdgeClass::ALL
        .into_iter()
        .find(|c| c.name() == name.trim())
        .ok_or_else(|| {
            format!(
                "'{name}' is not an edge class (silhouette, boundary, crease, intersection, smooth)"
            )
        })?;
    match width.trim().parse::<f64>() {
        Ok(w) if w.is_finite() && w >= 0.0 => Ok((class, w)),
        _ => Err(format!("'{width}' is not a stroke width in mm")),
    }
}

/// Parses `x,y,z` into three finite numbers.
fn parse_triple(text: &str) -> Result<[f64; 3], String> {
    let fields: Vec<&str> = text.split(',').map(str::trim).collect();
    if fields.len() != 3 {
        return Err(format!("expected x,y,z (three numbers), got '{text}'"));
    }
    let mut out = [0.0; 3];
    for (k, f) in fields.iter().enumerate() {
        out[k] = match f.parse::<f64>() {
            Ok(x) if x.is_finite() => x,
            _ => return Err(format!("'{f}' is not a finite number")),
        };
    }
    Ok(out)
}

fn run(cli: Cli) -> Result<()> {
    match cli.command {
        Command::Bounds { scene, json } => {
            let scene = file::load(&scene)?;
            let report = BoundsReport::of(&scene);
            let text = if json {
                serde_json::to_string_pretty(&report)? + "\n"
            } else {
                report.table()
            };
            emit(&text)?;
        }
        Command::Include { scene, points } => {
            let scene = file::load(&scene)?;
            let points = read_points(&points)?;
            answer_points(
                "include",
                &points,
                &[Inclusion::In, Inclusion::Out, Inclusion::On],
                || Ok(IncludeIndex::whole_scene(&scene)?),
                |index, points| index.include_all(points),
            )?;
        }
        Command::Segx {
            n,
            len,
            seed,
            input,
            pairs,
        } => {
            let (lines, segments): (Vec<usize>, Vec<Line<f64>>) = match (input, n) {
                (Some(path), _) => read_segments(&path)?.into_iter().unzip(),
                (None, Some(n)) => {
                    if !(0.0..=1.0).contains(&len) {
                        anyhow::bail!("--len must be between 0 and 1, not {len}");
                    }
                    ((1..=n).collect(), random_segments(n, len, seed))
                }
                (None, None) => anyhow::bail!("give --n N or --input FILE"),
            };
            let start = Instant::now();
            let found = intersecting_pairs(&segments);
            let seconds = start.elapsed().as_secs_f64();
            let summary = format!(
                "N {} K {} seconds {seconds:.6}",
                segments.len(),
                found.len()
            );
            if pairs {
                let mut text = String::with_capacity(found.len() * 12);
                for (i, j) in &found {
                    let _ = writeln!(text, "{} {}", lines[*i], lines[*j]);
                }
                emit(&text)?;
                eprintln!("{summary}");
            } else {
                emit(&(summary + "\n"))?;
            }
        }
        Command::Render {
            scene: path,
            output,
            edges,
            crease_angle,
            hidden,
            page,
            stroke,
            json,
            stats,
            ideograph_below,
            ideograph,
            view,
        } => {
            if !(crease_angle.is_finite() && (0.0..=180.0).contains(&crease_angle)) {
                anyhow::bail!(
                    "--crease-angle must be between 0 and 180 degrees, not {crease_angle}"
                );
            }
            let started = Instant::now();
            let scene = load_drawable(&path)?;
            let view = view.view(&scene)?;
            let options = hidden::Options {
                edges: match edges {
                    Edges::Feature => EdgeSelection::Feature,
                    Edges::All => EdgeSelection::All,
                },
                crease_angle,
                hidden: hidden == Hidden::Dashed,
            };
            let mut svg_options = page.svg_options();
            for (class, width) in stroke {
                match class {
                    EdgeClass::Silhouette => svg_options.stroke.silhouette = width,
                    EdgeClass::Boundary => svg_options.stroke.boundary = width,
                    EdgeClass::Crease => svg_options.stroke.crease = width,
                    EdgeClass::Intersection => svg_options.stroke.intersection = width,
                    EdgeClass::Smooth => svg_options.stroke.smooth = width,
                }
            }
            // The ideographs' threshold, at the page scale of the whole scene.
            let culled = match ideograph_below {
                Some(mm2) => {
                    let picture = Picture::of(&view);
                    let points = scene
                        .mesh_objects(scene.roots())
                        .into_iter()
                        .flat_map(|(_, m)| m.vertices().iter().map(|v| picture.point(v)))
                        .collect::<Vec<_>>();
                    let [lo, hi] = bounding_box(points);
                    let scale = PageTransform::fit(Some((lo, hi)), &svg_options).scale;
                    let mode = match ideograph {
                        IdeographMode::Bound => Ideograph::Bound,
                        IdeographMode::Omit => Ideograph::Omit,
                    };
                    Some(ideographs(&scene, &view, mm2 / (scale * scale), mode)?)
                }
                None => None,
            };
            let (scene, culled) = match culled {
                Some(c) => (
                    c.scene,
                    Some((c.culled, c.triangles_culled, c.triangles_added)),
                ),
                None => (scene, None),
            };
            let loaded = started.elapsed();
            let bar = progress_bar();
            let drawing = hidden::draw_with_progress(&scene, &view, &options, &|done, total| {
                if let Some(bar) = &bar {
                    bar.set_length(total);
                    bar.set_position(done);
                }
            })?;
            if let Some(bar) = bar {
                bar.finish_and_clear();
            }
            let clock = Instant::now();
            write_file(&output, |mut out| {
                write_svg(&drawing, &svg_options, &mut out)
            })?;
            if let Some(json) = &json {
                write_file(json, |mut out| write_json(&drawing, &mut out))?;
            }
            let written = clock.elapsed();
            if stats {
                if let Some((objects, removed, added)) = culled {
                    eprintln!(
                        "ideographs: {objects} objects below {} mm² culled ({removed} triangles; \
                         {added} triangles of bounds drawn instead)",
                        ideograph_below.unwrap_or(0.0)
                    );
                }
                eprint!("{}", stats_report(&drawing, loaded, written));
            }
        }
        Command::Surfaces {
            scene: path,
            output,
            json,
            light,
            outlines,
            page,
            view,
        } => {
            if light == Some([0.0; 3]) {
                anyhow::bail!(
                    "--light 0,0,0 has no direction: give a nonzero vector towards the light"
                );
            }
            let scene = load_drawable(&path)?;
            let view = view.view(&scene)?;
            let faces = visible_surfaces(&scene, &view)?;
            let options = page.svg_options();
            let shading = Shading {
                light: light.map(Vector3::from),
                outlines,
            };
            write_file(&output, |mut out| {
                write_surfaces_svg(&faces, &scene, &view, &options, &shading, &mut out)
            })?;
            if let Some(json) = &json {
                write_file(json, |mut out| {
                    write_surfaces_json(&faces, &scene, &mut out)
                })?;
            }
        }
        Command::Visobj {
            scene: path,
            a,
            b,
            view,
        } => {
            let scene = file::load(&path)?;
            let find = |name: &str| {
                scene
                    .find(name)
                    .ok_or_else(|| anyhow::anyhow!("{}: no object named '{name}'", path.display()))
            };
            let (a, b) = (find(&a)?, find(&b)?);
            let view = view.view(&scene)?;
            let answer = visobj(&scene, a, b, &view)?;
            emit(&format!("{}\n", format!("{answer:?}").to_uppercase()))?;
        }
        Command::Boxtree {
            experiment: Experiment::Spheres,
            merge,
            json,
        } => {
            let merge = match merge {
                MergeRule::Volume => Merge::Volume,
                MergeRule::Area => Merge::Area,
            };
            let rows = sphere_experiment(&PAPER_FACETS, DEFAULT_GAP, 1, merge)?;
            let mut table = format!(
                "{:>7}  {:<8} {:>12} {:>12}\n",
                "facets", "shape", "tests", "paper"
            );
            for r in &rows {
                let paper = r.paper.map_or("-".to_string(), |p| p.to_string());
                table += &format!(
                    "{:>7}  {:<8} {:>12} {:>12}\n",
                    r.facets,
                    r.shape.to_string(),
                    r.tests,
                    paper
                );
            }
            emit(&table)?;
            if let Some(json) = &json {
                write_file(json, |out| {
                    serde_json::to_writer(&mut *out, &rows).map_err(std::io::Error::other)?;
                    writeln!(out)
                })?;
            }
        }
        Command::Cull { scene, json, view } => {
            let scene = load_drawable(&scene)?;
            let view = view.view(&scene)?;
            let report = cull(&scene, &view)?;
            emit(&cull_table(&report))?;
            if let Some(json) = &json {
                write_file(json, |out| {
                    serde_json::to_writer(&mut *out, &report).map_err(std::io::Error::other)?;
                    writeln!(out)
                })?;
            }
        }
        Command::Triboxes {
            scene: path,
            object,
            levels,
            gain,
            max_depth,
            split,
            output,
            json,
            page,
            view,
        } => {
            let scene = load_drawable(&path)?;
            let (name, mesh) = match &object {
                Some(name) => {
                    let Some(id) = scene.find(name) else {
                        anyhow::bail!("{}: no object named '{name}'", path.display());
                    };
                    (scene.path(id), scene.flatten(id)?)
                }
                None => {
                    // Name the first object that cannot bound a solid, not only the file.
                    let roots = scene.mesh_objects(scene.roots());
                    if let Some((id, _)) = roots.iter().find(|(_, m)| !m.is_solid()) {
                        anyhow::bail!("object '{}': {}", scene.path(*id), TriboxesError::NotSolid);
                    }
                    (
                        path.display().to_string(),
                        scene
                            .flatten_all()
                            .map_err(|e| anyhow::anyhow!("{}: {e}", path.display()))?,
                    )
                }
            };
            let options = TriboxOptions {
                gain,
                max_depth,
                split: match split {
                    SplitArg::Thickest => SplitRule::Thickest,
                    SplitArg::Bisectors => SplitRule::Bisectors,
                    SplitArg::Features => SplitRule::Features,
                },
                ..TriboxOptions::default()
            };
            let hierarchy = Hierarchy::build(&mesh, &options).map_err(|e| match e {
                // The command sets no option but the gain that the library checks.
                TriboxesError::Option(message) => anyhow::anyhow!("--gain: {message}"),
                e => anyhow::anyhow!("object '{name}': {e}"),
            })?;
            let report = hierarchy.levels(levels);
            emit(&tribox_table(&name, mesh.faces().len(), &report))?;
            if let Some(json) = &json {
                let value = serde_json::json!({
                    "object": name,
                    "faces": mesh.faces().len(),
                    "volume": mesh.volume(),
                    "area": mesh.surface_area(),
                    "levels": report,
                    "nodes": hierarchy.nodes(),
                });
                write_file(json, |out| {
                    serde_json::to_writer(&mut *out, &value).map_err(std::io::Error::other)?;
                    writeln!(out)
                })?;
            }
            if let Some(output) = &output {
                let view = view.view(&scene)?;
                let panels = tribox_panels(&mesh, &hierarchy, report.len(), &view)?;
                let drawing = hidden::draw(&panels, &view, &hidden::Options::default())?;
                write_file(output, |mut out| {
                    write_svg(&drawing, &page.svg_options(), &mut out)
                })?;
            }
        }
        Command::Visp {
            scene,
            points,
            view,
        } => {
            let scene = file::load(&scene)?;
            let view = view.view(&scene)?;
            let points = read_points(&points)?;
            answer_points(
                "visp",
                &points,
                &[Visibility::Visible, Visibility::Hidden],
                || Ok(VisibilityIndex::whole_scene(&scene, view)),
                |index, points| index.visp_all(points),
            )?;
        }
    }
    Ok(())
}

/// Builds an index, answers every point with it, prints one answer per line, and a summary
/// on stderr with the count of each of `kinds` (in that order).
fn answer_points<I, T: std::fmt::Display + PartialEq>(
    command: &str,
    points: &[Point3],
    kinds: &[T],
    build: impl FnOnce() -> Result<I>,
    answer: impl FnOnce(&I, &[Point3]) -> (Vec<T>, Counters),
) -> Result<()> {
    let start = Instant::now();
    let index = build()?;
    let built = start.elapsed();
    let start = Instant::now();
    let (answers, counters) = answer(&index, points);
    let queried = start.elapsed();
    let mut text = String::with_capacity(answers.len() * 4);
    for a in &answers {
        let _ = writeln!(text, "{a}");
    }
    emit(&text)?;
    let tally = kinds
        .iter()
        .map(|kind| format!("{} {kind}", answers.iter().filter(|&a| a == kind).count()))
        .collect::<Vec<_>>()
        .join(", ");
    eprintln!("{}", summary(command, &tally, built, queried, &counters));
    Ok(())
}

/// The stderr summary: counts, speed, and what decided the answers.
fn summary(
    command: &str,
    tally: &str,
    built: Duration,
    queried: Duration,
    counters: &Counters,
) -> String {
    let n = counters.total();
    let seconds = queried.as_secs_f64();
    let rate = if seconds > 0.0 {
        format!("{:.2} M points/s", n as f64 / seconds / 1e6)
    } else {
        "instant".to_owned()
    };
    let share = counters
        .by_stage()
        .iter()
        .map(|(name, c)| {
            let percent = if n > 0 {
                100.0 * *c as f64 / n as f64
            } else {
                0.0
            };
            format!("{name} {c} ({percent:.1}%)")
        })
        .collect::<Vec<_>>()
        .join(", ");
    format!(
        "kepler {command}: {n} points: {tally}; {seconds:.3} s ({rate}) after building the index \
         in {:.3} s; decided by {share}",
        built.as_secs_f64()
    )
}

/// A progress bar on stderr, or `None` when stderr is not a terminal.
fn progress_bar() -> Option<ProgressBar> {
    if !std::io::stderr().is_terminal() {
        return None;
    }
    let bar = ProgressBar::new(0);
    if let Ok(style) = ProgressStyle::with_template("visibility {bar:40} {pos}/{len} lines ({eta})")
    {
        bar.set_style(style);
    }
    Some(bar)
}

/// Writes a file (or standard output for `-`) with `write`, naming the file in errors.
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

fn write_file(
    path: &std::path::Path,
    write: impl FnOnce(&mut dyn Write) -> std::io::Result<()>,
) -> Result<()> {
    let name = path.display().to_string();
    if name == "-" {
        let mut out = std::io::BufWriter::new(std::io::stdout().lock());
        write(&mut out).and_then(|()| out.flush())?;
        return Ok(());
    }
    let file = std::fs::File::create(path).map_err(|e| kepler::io::FileError::io(&name, e))?;
    let mut out = std::io::BufWriter::new(file);
    write(&mut out)
        .and_then(|()| out.flush())
        .map_err(|e| kepler::io::FileError::io(&name, e))?;
    Ok(())
}

/// The `--stats` report: each stage, then lengths per class.
fn stats_report(drawing: &Drawing, loaded: Duration, written: Duration) -> String {
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

/// The table of `kepler triboxes`.
fn tribox_table(name: &str, faces: usize, levels: &[Level]) -> String {
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
            "{:>5} {:>8} {:>7} {:>11.2} {:>12.2}% {:>10.2}%  {:.6} ({:.6})\n",
            l.depth,
            l.triboxes,
            l.faces,
            l.compression,
            100.0 * l.volume_excess,
            100.0 * l.area_excess,
            l.hausdorff,
            l.hausdorff_lower
        );
    }
    t
}

/// The object and the levels of detail side by side: each panel moved along the picture's
/// horizontal by the object's width and a gap.
fn tribox_panels(mesh: &Mesh, h: &Hierarchy, levels: usize, view: &View) -> Result<Scene> {
    let (right, _) = view.right_up();
    let root = Tribox::new(&h.nodes()[0].tribox).cleaned();
    let along = root.vertices().iter().map(|v| v.coords.dot(&right));
    let (lo, hi) = along.fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), x| {
        (lo.min(x), hi.max(x))
    });
    let pitch = 1.25 * (hi - lo);
    let shifted = |m: &Mesh, k: usize| {
        m.transformed(&nalgebra::Matrix4::new_translation(
            &(right * (pitch * k as f64)),
        ))
    };
    let mut scene = Scene::new();
    scene.add_mesh(None, "object", shifted(mesh, 0)?)?;
    for depth in 0..levels {
        let group = scene.add_group(None, format!("level-{depth}"))?;
        for (i, node) in h.cut(depth).into_iter().enumerate() {
            let m = tribox_mesh(&h.nodes()[node].tribox, h.simplify_tolerance())?;
            scene.add_mesh(Some(group), format!("tribox-{i}"), shifted(&m, depth + 1)?)?;
        }
    }
    Ok(scene)
}

/// Writes to standard output; a reader that closed the pipe early (`| head`) is not an error.
fn emit(text: &str) -> Result<()> {
    match std::io::stdout().lock().write_all(text.as_bytes()) {
        Err(e) if e.kind() == std::io::ErrorKind::BrokenPipe => Ok(()),
        other => Ok(other?),
    }
}

fn main() -> ExitCode {
    match run(Cli::parse()) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::FAILURE
        }
    }
}
