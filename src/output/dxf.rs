//! DXF: a hidden-line drawing for CAD, written with the `dxf` crate.
//!
//! One layer per class and visibility, named as the SVG's (`visible-silhouette`,
//! `hidden-crease`, …); every polyline is an `LWPOLYLINE` on its layer, closed chains flagged
//! closed (their repeated last point left out). Visible layers are colour 7 (black on paper,
//! white on a dark screen) with the `CONTINUOUS` linetype; hidden layers are colour 8 (grey)
//! with a `DASHED` linetype whose dash and gap are the SVG's, in the drawing's units at the
//! page scale the SVG would use. Coordinates are view coordinates (`x` right, `y` up; scene
//! units for an orthographic view), unscaled, in an AutoCAD 2000 file.
//!
//! [`DxfFormat::Text`] is the usual ASCII DXF; the `dxf` crate writes its numbers with 12
//! decimal places, so a coordinate is exact to 5e-13 of a unit, not to the bit.
//! [`DxfFormat::Binary`] (binary DXF, which AutoCAD, ezdxf and the `dxf` crate read) keeps
//! every double as computed.
//!
//! ```
//! use kepler::hidden::{Drawing, EdgeClass, Polyline};
//! use kepler::output::{DxfFormat, SvgOptions, write_dxf};
//! let drawing = Drawing {
//!     polylines: vec![Polyline {
//!         class: EdgeClass::Silhouette,
//!         visible: true,
//!         points: vec![[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 0.0]],
//!     }],
//!     stages: Vec::new(),
//! };
//! let mut bytes = Vec::new();
//! write_dxf(&drawing, &SvgOptions::default(), DxfFormat::Text, &mut bytes).unwrap();
//! let back = dxf::Drawing::load(&mut bytes.as_slice()).unwrap();
//! assert_eq!(back.entities().count(), 1);
//! assert!(back.layers().any(|l| l.name == "visible-silhouette"));
//! ```

use super::{SvgOptions, check_finite, page_transform};
use crate::hidden::{Drawing, EdgeClass};
use dxf::entities::{Entity, EntityType, LwPolyline};
use dxf::enums::AcadVersion;
use dxf::tables::{Layer, LineType};
use dxf::{Color, LwPolylineVertex};
use std::io::{self, Write};

/// How a DXF file is encoded.
///
/// ```
/// assert_ne!(kepler::output::DxfFormat::Text, kepler::output::DxfFormat::Binary);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum DxfFormat {
    /// ASCII DXF, numbers with 12 decimal places.
    Text,
    /// Binary DXF: every double exact.
    Binary,
}

/// The name of the layer of a class and visibility (the SVG's layer id).
///
/// ```
/// use kepler::hidden::EdgeClass;
/// assert_eq!(kepler::output::layer_name(EdgeClass::Crease, false), "hidden-crease");
/// ```
pub fn layer_name(class: EdgeClass, visible: bool) -> String {
    format!(
        "{}-{}",
        if visible { "visible" } else { "hidden" },
        class.name()
    )
}

/// Writes `drawing` as DXF to `out` (see the module documentation); `options` gives the
/// hidden lines' dash and gap in millimetres on the page the SVG would fill.
pub fn write_dxf(
    drawing: &Drawing,
    options: &SvgOptions,
    format: DxfFormat,
    out: &mut impl Write,
) -> io::Result<()> {
    options.check()?;
    check_finite(drawing)?;
    let t = page_transform(drawing, options);
    let [dash, gap] = options.hidden_dash.map(|mm| mm / t.scale);
    let mut dxf = dxf::Drawing::new();
    dxf.header.version = AcadVersion::R2000;
    // The GUIDs that would be drawn at random, from the drawing, and the dates that would be
    // now, DXF's epoch (1900-01-01, Julian day 2415021 in every time zone): the same file
    // every run.
    let guid = content_guid(drawing, options);
    dxf.header.fingerprint_guid = guid;
    dxf.header.version_guid = guid;
    use chrono::TimeZone;
    if let (Some(local), Some(utc)) = (
        chrono::Local.with_ymd_and_hms(1900, 1, 1, 0, 0, 0).single(),
        chrono::Utc.with_ymd_and_hms(1900, 1, 1, 0, 0, 0).single(),
    ) {
        (dxf.header.creation_date, dxf.header.update_date) = (local, local);
        (
            dxf.header.creation_date_universal,
            dxf.header.update_date_universal,
        ) = (utc, utc);
    }
    let pattern = if dash.is_finite() && gap.is_finite() {
        vec![dash, -gap]
    } else {
        Vec::new()
    };
    dxf.add_line_type(LineType {
        name: "DASHED".to_string(),
        description: "Dashed __ __ __".to_string(),
        element_count: pattern.len() as i32,
        total_pattern_length: pattern.iter().map(|x| x.abs()).sum(),
        dash_dot_space_lengths: pattern,
        ..Default::default()
    });
    for visible in [false, true] {
        for class in EdgeClass::ALL {
            if !drawing
                .polylines
                .iter()
                .any(|p| p.class == class && p.visible == visible)
            {
                continue;
            }
            dxf.add_layer(Layer {
                name: layer_name(class, visible),
                color: Color::from_index(if visible { 7 } else { 8 }),
                line_type_name: if visible { "CONTINUOUS" } else { "DASHED" }.to_string(),
                ..Default::default()
            });
        }
    }
    for p in drawing.polylines.iter().filter(|p| p.points.len() >= 2) {
        let closed = p.points.len() > 2 && p.points[0] == p.points[p.points.len() - 1];
        let points = if closed {
            &p.points[..p.points.len() - 1]
        } else {
            &p.points[..]
        };
        let mut polyline = LwPolyline::default();
        polyline.set_is_closed(closed);
        polyline.vertices = points
            .iter()
            .map(|q| LwPolylineVertex {
                x: q[0],
                y: q[1],
                ..Default::default()
            })
            .collect();
        let mut entity = Entity::new(EntityType::LwPolyline(polyline));
        entity.common.layer = layer_name(p.class, p.visible);
        dxf.add_entity(entity);
    }
    let mut out = io::BufWriter::new(out);
    let written = match format {
        DxfFormat::Text => dxf.save(&mut out),
        DxfFormat::Binary => dxf.save_binary(&mut out),
    };
    written.map_err(|e| io::Error::other(e.to_string()))?;
    out.flush()
}

/// A GUID for the drawing written with `options`: a hash (the same in every build) of every
/// point's bits, class and visibility, and of the page.
fn content_guid(drawing: &Drawing, options: &SvgOptions) -> uuid::Uuid {
    let half = |seed: u64| {
        let mut h = crate::fnv::Fnv::new(seed);
        for p in &drawing.polylines {
            h.word((p.class as u64) << 1 | u64::from(p.visible));
            h.word(p.points.len() as u64);
            p.points.iter().flatten().for_each(|c| h.word(c.to_bits()));
        }
        let page = options
            .page
            .iter()
            .chain([&options.margin])
            .chain(&options.hidden_dash);
        page.for_each(|c| h.word(c.to_bits()));
        h.finish()
    };
    uuid::Uuid::from_u128(u128::from(half(1)) << 64 | u128::from(half(2)))
}
