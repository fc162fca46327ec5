//! What `render` and `stitch` share: the options that finish a drawing (hidden lines,
//! overlaps, pen order) and write it (page, strokes, SVG or DXF, JSON), and the writing.

use crate::args::{PageArgs, parse_stroke};
use crate::output::write_file;
use anyhow::Result;
use kepler::hidden::{self, Drawing, EdgeClass, EdgeSelection, Overlaps};
use kepler::output::{
    DxfFormat, HatchLayer, SvgOptions, write_dxf, write_json, write_svg_with_hatches,
};
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

/// How a drawing is finished and written.
#[derive(clap::Args)]
pub struct FinishArgs {
    /// Hidden lines: `dashed` (their own grey dashed layers) or `omit`.
    #[arg(long, value_enum, default_value_t = Hidden::Dashed)]
    pub hidden: Hidden,
    #[command(flatten)]
    pub page: PageArgs,
    /// A stroke width in millimetres for one class, `CLASS=MM` (classes: silhouette,
    /// boundary, crease, intersection, smooth); repeat for several.
    #[arg(long, value_name = "CLASS=MM", value_parser = parse_stroke)]
    pub stroke: Vec<(EdgeClass, f64)>,
    /// Keep lines drawn twice: by default a stretch of line that several edges run along
    /// (touching objects, T-junctions, a line right behind a contour) is written once, as
    /// the one drawn on top (visible over hidden, then silhouette, boundary, intersection,
    /// crease, smooth).
    #[arg(long)]
    pub keep_overlaps: bool,
    /// Order and turn each layer's paths to shorten the pen's travel between them (greedy
    /// nearest end); `--stats` prints the travel before and after.
    #[arg(long)]
    pub order: bool,
    /// DXF encoding: `text` (ASCII, numbers to 12 decimal places) or `binary` (every double
    /// exact).
    #[arg(long, value_enum, default_value_t = DxfEncoding::Text)]
    pub dxf: DxfEncoding,
    /// Also write the polylines as JSON, in view coordinates, to this file.
    #[arg(long, value_name = "FILE")]
    pub json: Option<PathBuf>,
}

/// `--hidden`: the library keeps hidden lines or not (`hidden::Options::hidden`).
#[derive(Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum Hidden {
    Dashed,
    Omit,
}

/// `--dxf`: the DXF file's encoding (`output::DxfFormat`).
#[derive(Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum DxfEncoding {
    Text,
    Binary,
}

impl FinishArgs {
    /// The pass's options with these, for the edges `edges` and the `crease_angle`.
    pub fn options(&self, edges: EdgeSelection, crease_angle: f64) -> hidden::Options {
        hidden::Options {
            edges,
            crease_angle,
            hidden: self.hidden == Hidden::Dashed,
            overlaps: if self.keep_overlaps {
                Overlaps::Keep
            } else {
                Overlaps::Once
            },
        }
    }

    /// The SVG options of the page, with the stroke widths given.
    pub fn svg_options(&self) -> SvgOptions {
        let mut svg_options = self.page.svg_options();
        for &(class, width) in &self.stroke {
            match class {
                EdgeClass::Silhouette => svg_options.stroke.silhouette = width,
                EdgeClass::Boundary => svg_options.stroke.boundary = width,
                EdgeClass::Crease => svg_options.stroke.crease = width,
                EdgeClass::Intersection => svg_options.stroke.intersection = width,
                EdgeClass::Smooth => svg_options.stroke.smooth = width,
            }
        }
        svg_options
    }

    /// Writes the drawing (and its hatches) to `output` as SVG, or DXF when its name ends in
    /// `.dxf`, and as JSON when asked; the time that took.
    pub fn write(
        &self,
        output: &Path,
        drawing: &Drawing,
        hatches: &HatchLayer,
        svg_options: &SvgOptions,
    ) -> Result<Duration> {
        let clock = Instant::now();
        write_file(output, |mut out| {
            if is_dxf(output) {
                let format = match self.dxf {
                    DxfEncoding::Text => DxfFormat::Text,
                    DxfEncoding::Binary => DxfFormat::Binary,
                };
                write_dxf(drawing, svg_options, format, &mut out)
            } else {
                write_svg_with_hatches(drawing, hatches, svg_options, &mut out)
            }
        })?;
        if let Some(json) = &self.json {
            write_file(json, |mut out| write_json(drawing, &mut out))?;
        }
        Ok(clock.elapsed())
    }
}

/// Whether a drawing written to `output` is DXF (its name ends in `.dxf`).
pub fn is_dxf(output: &Path) -> bool {
    output
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("dxf"))
}
