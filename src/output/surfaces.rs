//! Writing visible surfaces (see [`crate::surfaces`]) as a shaded SVG or as JSON.

use super::svg::{PageTransform, SvgOptions};
use crate::geometry::Vector3;
use crate::geometry::polygon::bounding_box;
use crate::scene::Scene;
use crate::surfaces::{FaceReport, Status};
use crate::views::View;
use geo::{MultiPolygon, Polygon};
use serde::Serialize;
use std::io::{self, Write};

/// How [`write_surfaces_svg`] shades and outlines the faces.
///
/// ```
/// let s = kepler::output::Shading::default();
/// assert!(s.light.is_none() && !s.outlines);
/// ```
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Shading {
    /// The direction towards the light, in world coordinates; `None` for a light over the
    /// viewer's left shoulder (which a zero or non-finite vector also gives; the command line
    /// rejects those).
    pub light: Option<Vector3>,
    /// Whether to stroke the visible polygons' outlines (0.1 mm, black).
    pub outlines: bool,
}

impl Shading {
    /// The unit direction towards the light in `view`: [`Shading::light`], or over the
    /// viewer's left shoulder (towards the eye, up 0.6 and left 0.4 of the picture).
    ///
    /// ```
    /// use kepler::{geometry::Vector3, output::Shading, views::View};
    /// let view = View::orthographic(Vector3::new(0.0, 0.0, -1.0), Vector3::y()).unwrap();
    /// let l = Shading::default().light_direction(&view);
    /// assert!((l.norm() - 1.0).abs() < 1e-12 && l.z > 0.0 && l.y > 0.0);
    /// let given = Shading { light: Some(Vector3::new(0.0, 0.0, 2.0)), ..Shading::default() };
    /// assert_eq!(given.light_direction(&view), Vector3::z());
    /// ```
    pub fn light_direction(&self, view: &View) -> Vector3 {
        let toward_eye = -view.forward();
        let (right, up) = view.right_up();
        self.light
            .filter(|l| l.norm() > 0.0 && l.iter().all(|c| c.is_finite()))
            .unwrap_or(toward_eye + up * 0.6 - right * 0.4)
            .normalize()
    }

    /// Each face's shade in `[0, 1]` (Lambert): `max(0, n·l)` with the face's unit normal `n`
    /// turned towards the eye and the light direction `l` ([`Shading::light_direction`]); 0
    /// for a face turned away from the light (darkest), 1 for one facing it.
    ///
    /// ```
    /// use kepler::{geometry::Vector3, output::Shading, scene::Scene, views::View};
    /// use kepler::surfaces::visible_surfaces;
    /// let mut scene = Scene::new();
    /// scene.add_mesh(None, "cube", kepler::solids::cube(2.0).unwrap()).unwrap();
    /// let view = View::orthographic(Vector3::new(0.0, 0.0, -1.0), Vector3::y()).unwrap();
    /// let faces = visible_surfaces(&scene, &view).unwrap();
    /// let light = Shading { light: Some(Vector3::z()), ..Shading::default() };
    /// let shades = light.shades(&faces, &scene, &view);
    /// let top = faces.iter().position(|f| !f.visible.polygons.0.is_empty()).unwrap();
    /// assert_eq!(shades[top], 1.0);
    /// ```
    pub fn shades(&self, faces: &[FaceReport], scene: &Scene, view: &View) -> Vec<f64> {
        let toward_eye = -view.forward();
        let light = self.light_direction(view);
        faces
            .iter()
            .map(|f| {
                let normal = scene[f.object]
                    .mesh()
                    .map_or(toward_eye, |m| m.faces()[f.face].plane().normal);
                let facing = if normal.dot(&toward_eye) < 0.0 {
                    -normal
                } else {
                    normal
                };
                facing.dot(&light).clamp(0.0, 1.0)
            })
            .collect()
    }
}

/// Writes the visible polygons of `faces` as an SVG page: each face's polygons one `<path>`
/// (holes by the even-odd rule) filled with a grey from flat shading, `ambient + diffuse ·
/// max(0, n·l)` with the face's normal `n` turned towards the eye and the light direction `l`.
/// Path coordinates are view coordinates in one outer `matrix(s 0 0 -s tx ty)` group, as in
/// [`super::write_svg`]; each path carries `data-object` and `data-face`.
///
/// ```
/// use kepler::{geometry::Vector3, scene::Scene, views::View, surfaces::visible_surfaces};
/// use kepler::output::{Shading, SvgOptions, write_surfaces_svg};
/// let mut scene = Scene::new();
/// scene.add_mesh(None, "cube", kepler::solids::cube(2.0).unwrap()).unwrap();
/// let view = View::orthographic(Vector3::new(-1.0, -2.0, -3.0), Vector3::z()).unwrap();
/// let faces = visible_surfaces(&scene, &view).unwrap();
/// let mut out = Vec::new();
/// write_surfaces_svg(&faces, &scene, &view, &SvgOptions::default(), &Shading::default(), &mut out).unwrap();
/// let svg = String::from_utf8(out).unwrap();
/// assert_eq!(svg.matches("<path").count(), 3);
/// ```
pub fn write_surfaces_svg(
    faces: &[FaceReport],
    scene: &Scene,
    view: &View,
    options: &SvgOptions,
    shading: &Shading,
    out: &mut impl Write,
) -> io::Result<()> {
    options.check()?;
    let points: Vec<[f64; 2]> = faces
        .iter()
        .flat_map(|f| f.visible.polygons.iter())
        .flat_map(|p| p.exterior().coords().map(|c| [c.x, c.y]))
        .collect();
    if points
        .iter()
        .any(|c| !(c[0].is_finite() && c[1].is_finite()))
    {
        return Err(io::Error::new(
            io::ErrorKind::InvalidData,
            "a visible polygon has a point that is not finite",
        ));
    }
    let bounds = (!points.is_empty()).then(|| {
        let [lo, hi] = bounding_box(points.iter().copied());
        (lo, hi)
    });
    let t = PageTransform::fit(bounds, options);
    let [width, height] = options.page;
    writeln!(out, r#"<?xml version="1.0" encoding="UTF-8"?>"#)?;
    writeln!(
        out,
        r#"<svg xmlns="http://www.w3.org/2000/svg" version="1.1" width="{width}mm" height="{height}mm" viewBox="0 0 {width} {height}">"#
    )?;
    let outline = if shading.outlines {
        format!(
            r#" stroke="black" stroke-width="{}" stroke-linejoin="round""#,
            0.1 / t.scale
        )
    } else {
        String::new()
    };
    writeln!(
        out,
        r#"<g id="surfaces" transform="matrix({} 0 0 {} {} {})" fill-rule="evenodd"{outline}>"#,
        t.scale, -t.scale, t.tx, t.ty
    )?;
    for (f, shade) in faces
        .iter()
        .zip(shading.shades(faces, scene, view))
        .filter(|(f, _)| !f.visible.polygons.0.is_empty())
    {
        let grey = (255.0 * (0.25 + 0.7 * shade)).round() as u8;
        let mut d = String::new();
        for p in f.visible.polygons.iter() {
            for ring in std::iter::once(p.exterior()).chain(p.interiors()) {
                let n = ring.0.len().saturating_sub(1);
                for (k, c) in ring.0.iter().take(n).enumerate() {
                    d.push_str(if k == 0 { "M " } else { " L " });
                    d.push_str(&format!("{} {}", c.x, c.y));
                }
                d.push_str(" Z ");
            }
        }
        writeln!(
            out,
            r#"<path data-object="{}" data-face="{}" fill="rgb({grey},{grey},{grey})" d="{}"/>"#,
            xml_escape(&scene.path(f.object)),
            f.face,
            d.trim_end()
        )?;
    }
    writeln!(out, "</g>")?;
    writeln!(out, "</svg>")
}

/// The characters of `s` that XML needs escaped in an attribute, escaped.
fn xml_escape(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('"', "&quot;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
}

/// One polygon in the JSON: its outer ring and holes, each as open rings of points.
#[derive(Serialize)]
struct JsonPolygon {
    outer: Vec<[f64; 2]>,
    holes: Vec<Vec<[f64; 2]>>,
}

/// One face in the JSON.
#[derive(Serialize)]
struct JsonFace {
    object: String,
    face: usize,
    status: Status,
    polygons: Vec<JsonPolygon>,
    texture_polygons: Vec<JsonPolygon>,
}

/// The polygons as JSON polygons (rings without their closing point).
fn json_polygons(m: &MultiPolygon<f64>) -> Vec<JsonPolygon> {
    let open = |ring: &geo::LineString<f64>| -> Vec<[f64; 2]> {
        let n = ring.0.len().saturating_sub(1);
        ring.0.iter().take(n).map(|c| [c.x, c.y]).collect()
    };
    m.iter()
        .map(|p: &Polygon<f64>| JsonPolygon {
            outer: open(p.exterior()),
            holes: p.interiors().iter().map(open).collect(),
        })
        .collect()
}

/// Writes every face's visible polygons as JSON:
/// `{"faces": [{"object", "face", "status", "polygons": [{"outer", "holes"}],
/// "texture_polygons": [...]}]}`, picture coordinates in view units as in
/// [`super::write_json`], texture coordinates in the face's texture system; rings are open
/// (the first point is not repeated) and every number reads back as the same `f64`.
///
/// ```
/// use kepler::{scene::Scene, views::View, surfaces::visible_surfaces, output::write_surfaces_json};
/// let mut scene = Scene::new();
/// scene.add_mesh(None, "cube", kepler::solids::cube(2.0).unwrap()).unwrap();
/// let faces = visible_surfaces(&scene, &View::standard()).unwrap();
/// let mut out = Vec::new();
/// write_surfaces_json(&faces, &scene, &mut out).unwrap();
/// let json: serde_json::Value = serde_json::from_slice(&out).unwrap();
/// assert_eq!(json["faces"].as_array().unwrap().len(), 6);
/// ```
pub fn write_surfaces_json(
    faces: &[FaceReport],
    scene: &Scene,
    out: &mut impl Write,
) -> io::Result<()> {
    #[derive(Serialize)]
    struct Document {
        faces: Vec<JsonFace>,
    }
    let document = Document {
        faces: faces
            .iter()
            .map(|f| JsonFace {
                object: scene.path(f.object),
                face: f.face,
                status: f.visible.status,
                polygons: json_polygons(&f.visible.polygons),
                texture_polygons: json_polygons(&f.texture),
            })
            .collect(),
    };
    serde_json::to_writer(&mut *out, &document).map_err(io::Error::other)?;
    writeln!(out)
}
