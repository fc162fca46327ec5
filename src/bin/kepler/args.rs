//! What several commands take: the view and page options, the parsers of option values, and
//! the scene and objects named on the command line.

use anyhow::Result;
use kepler::geometry::{Point3, Vector3};
use kepler::hidden::EdgeClass;
use kepler::mesh::Validation;
use kepler::output::SvgOptions;
use kepler::scene::{ObjectId, Scene, file};
use kepler::views::{View, ViewOptions};
use std::path::Path;

/// The view options every command that takes a view accepts. Without them: the scene file's
/// camera, else an isometric view along (-1,-1,-1) with z up.
#[derive(clap::Args)]
pub struct ViewArgs {
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
    /// `render` and `surfaces`: the near clipping distance of a perspective view whose eye is
    /// inside the scene (default 1/1024 of the distance to the target); lines and faces are
    /// clipped to the page's field of view too.
    #[arg(long, value_name = "DIST", allow_hyphen_values = true)]
    near: Option<f64>,
}

impl ViewArgs {
    /// The view over the scene's camera.
    pub fn view(&self, scene: &Scene) -> kepler::Result<View> {
        self.view_on(scene, 1.0)
    }

    /// The view over the scene's camera, clipping (when its eye is inside the scene) to a
    /// picture `aspect` times as wide as high.
    pub fn view_on(&self, scene: &Scene, aspect: f64) -> kepler::Result<View> {
        let options = ViewOptions {
            view_dir: self.view_dir.map(Vector3::from),
            up: self.up.map(Vector3::from),
            eye: self.eye.map(Point3::from),
            target: self.target.map(Point3::from),
            fov: self.fov,
        };
        let view = options.resolve(scene.camera())?;
        if !view.is_perspective() {
            return Ok(view);
        }
        Ok(match self.near {
            Some(near) => view.with_clipping(near, aspect)?,
            None => view.with_aspect(aspect)?,
        })
    }
}

/// The page options of the commands that write SVG.
#[derive(clap::Args)]
pub struct PageArgs {
    /// Page size in millimetres, `WIDTHxHEIGHT` (default A4 landscape).
    #[arg(long, value_name = "WxH", value_parser = parse_page, default_value = "297x210")]
    page: [f64; 2],
    /// Page margin in millimetres.
    #[arg(long, value_name = "MM", default_value_t = 10.0)]
    margin: f64,
}

impl PageArgs {
    /// The SVG options with this page and margin.
    pub fn svg_options(&self) -> SvgOptions {
        SvgOptions {
            page: self.page,
            margin: self.margin,
            ..SvgOptions::default()
        }
    }
}

/// What the commands that read meshes do with faces that are valid input but not faces as
/// they are.
#[derive(clap::Args)]
pub struct FaceArgs {
    /// Refuse degenerate faces (zero area, a repeated vertex) and polygons that are not exactly
    /// planar, naming the file and line, instead of dropping the first and splitting the
    /// second into triangles.
    #[arg(long)]
    strict: bool,
}

impl FaceArgs {
    /// The validation asked for.
    pub fn validation(&self) -> Validation {
        if self.strict {
            Validation::Strict
        } else {
            Validation::Repair
        }
    }
}

/// Loads a scene to draw, its mesh files validated as asked: an error naming the file if it
/// holds no mesh.
pub fn load_drawable(path: &Path, validation: Validation) -> Result<Scene> {
    let scene = file::load_with(path, validation)?;
    if scene.mesh_objects(scene.roots()).is_empty() {
        anyhow::bail!("{}: the scene has no objects to draw", path.display());
    }
    Ok(scene)
}

/// The object of the scene loaded from `path` named `name` (its path, like `block/tower-west`):
/// an error naming the file if there is none.
pub fn find_object(scene: &Scene, path: &Path, name: &str) -> Result<ObjectId> {
    scene
        .find(name)
        .ok_or_else(|| anyhow::anyhow!("{}: no object named '{name}'", path.display()))
}

/// A nonnegative finite area.
pub fn parse_area(s: &str) -> Result<f64, String> {
    match s.trim().parse::<f64>() {
        Ok(a) if a.is_finite() && a >= 0.0 => Ok(a),
        _ => Err(format!("'{s}' is not a nonnegative area in mm²")),
    }
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
pub fn parse_stroke(text: &str) -> Result<(EdgeClass, f64), String> {
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
pub fn parse_triple(text: &str) -> Result<[f64; 3], String> {
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
