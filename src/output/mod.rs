//! Writing a hidden-line [`Drawing`](crate::hidden::Drawing) as SVG or JSON.
//!
//! Both formats carry the drawing's polylines in **view coordinates** (`x` to the right, `y`
//! up), each number printed with the shortest decimal that reads back as the very same `f64`.
//! Non-finite coordinates are refused with an error, so neither file ever holds `NaN` or `inf`.
//!
//! ## SVG ([`write_svg`])
//!
//! The root `<svg>` has `width` and `height` in millimetres and a matching `viewBox`, so one user
//! unit is one millimetre of the page ([`SvgOptions::page`], A4 landscape by default). Its
//! children are the layers, one `<g>` per class and visibility, each an Inkscape layer
//! (`inkscape:groupmode="layer"`, labelled like `visible silhouette`) so that Inkscape and
//! `vpype read` keep them apart, and each with the transform `matrix(s 0 0 -s tx ty)` that maps
//! view coordinates to the page: one uniform scale `s` fits the drawing's bounds inside the
//! page less [`SvgOptions::margin`], centred, and the `-s` flips `y` to point down the page
//! (see [`page_transform`]). The layers' ids:
//!
//! - `hidden-smooth`, `hidden-crease`, `hidden-intersection`, `hidden-boundary`,
//!   `hidden-silhouette`: hidden lines, grey and dashed (`stroke-dasharray`);
//! - `visible-smooth`, `visible-crease`, `visible-intersection`, `visible-boundary`,
//!   `visible-silhouette`: visible lines, black and solid.
//!
//! With [`write_svg_with_hatches`], one more layer, `hatch` (black, solid, thin): the hatch
//! lines of the visible faces (see [`crate::surfaces::hatch`]), between the hidden layers and
//! the visible ones, so that outlines are drawn over the hatches' ends.
//!
//! Hidden layers come first and visible ones are drawn over them, each in
//! [`EdgeClass::ALL`](crate::hidden::EdgeClass::ALL) order; a layer without polylines is left
//! out. Every polyline is one `<path d="M x y L x y L x y …"/>` listing all its points in view
//! coordinates (a closed polyline repeats its first point at the end). Stroke widths
//! ([`SvgOptions::stroke`]) and dash lengths ([`SvgOptions::hidden_dash`]) are given in
//! millimetres and written divided by `s`, so they come out at their size on the page without
//! `vector-effect`, which plotter software does not all honour. Paths have `fill="none"` and
//! round caps and joins.
//!
//! ## JSON ([`write_json`])
//!
//! ```text
//! {"polylines":[{"class":"silhouette","visible":true,"points":[[x,y],[x,y],…]},…]}
//! ```
//!
//! The polylines in the drawing's order; `class` is one of `silhouette`, `boundary`, `crease`,
//! `intersection`, `smooth`; points are in view coordinates, before any page scaling.
//!
//! ```
//! use kepler::hidden::{Drawing, EdgeClass, Polyline};
//! use kepler::output::{write_json, write_svg, SvgOptions};
//! let drawing = Drawing {
//!     polylines: vec![Polyline {
//!         class: EdgeClass::Silhouette,
//!         visible: true,
//!         points: vec![[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 0.0]],
//!     }],
//!     stages: Vec::new(),
//! };
//! let mut svg = Vec::new();
//! write_svg(&drawing, &SvgOptions::default(), &mut svg).unwrap();
//! let svg = String::from_utf8(svg).unwrap();
//! assert!(svg.contains(r#"<g id="visible-silhouette""#));
//! assert!(svg.contains(r#"d="M 0 0 L 1 0 L 1 1 L 0 0""#));
//! let mut json = Vec::new();
//! write_json(&drawing, &mut json).unwrap();
//! assert_eq!(
//!     String::from_utf8(json).unwrap().trim_end(),
//!     r#"{"polylines":[{"class":"silhouette","visible":true,"points":[[0.0,0.0],[1.0,0.0],[1.0,1.0],[0.0,0.0]]}]}"#
//! );
//! ```

mod dxf;
mod finish;
mod json;
mod order;
mod surfaces;
mod svg;

pub use self::dxf::{DxfFormat, layer_name, write_dxf};
pub use finish::{Finished, Finishing, finish};
pub use json::write_json;
pub use order::{ordered, ordered_paths, pen_order, pen_travel};
pub use surfaces::{Shading, write_surfaces_json, write_surfaces_svg};
pub use svg::{
    HatchLayer, PageTransform, StrokeWidths, SvgOptions, page_transform, write_svg,
    write_svg_with_hatches,
};

/// An [`std::io::ErrorKind::InvalidData`] error if a point of `drawing` is not finite.
fn check_finite(drawing: &crate::hidden::Drawing) -> std::io::Result<()> {
    match drawing
        .polylines
        .iter()
        .flat_map(|p| p.points.iter())
        .find(|p| !(p[0].is_finite() && p[1].is_finite()))
    {
        Some(p) => Err(std::io::Error::new(
            std::io::ErrorKind::InvalidData,
            format!(
                "the drawing has a point ({}, {}) that is not finite",
                p[0], p[1]
            ),
        )),
        None => Ok(()),
    }
}
