//! The SVG form of a drawing (see [`crate::output`]).

use std::io::{self, Write};

use crate::hidden::{Drawing, EdgeClass};

/// The stroke colour of visible lines.
const VISIBLE_COLOUR: &str = "#000000";
/// The stroke colour of hidden lines.
const HIDDEN_COLOUR: &str = "#909090";

/// Stroke widths per edge class, in millimetres on the page.
///
/// ```
/// use kepler::hidden::EdgeClass;
/// use kepler::output::StrokeWidths;
/// let widths = StrokeWidths { smooth: 0.1, ..StrokeWidths::default() };
/// assert_eq!(widths.get(EdgeClass::Smooth), 0.1);
/// assert_eq!(widths.get(EdgeClass::Silhouette), 0.5);
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StrokeWidths {
    /// Silhouette edges (default 0.5 mm).
    pub silhouette: f64,
    /// Boundary edges (default 0.5 mm).
    pub boundary: f64,
    /// Crease edges (default 0.35 mm).
    pub crease: f64,
    /// Intersection lines (default 0.35 mm).
    pub intersection: f64,
    /// Smooth edges (default 0.18 mm).
    pub smooth: f64,
}

impl StrokeWidths {
    /// The width for `class`, in millimetres.
    ///
    /// ```
    /// use kepler::hidden::EdgeClass;
    /// assert_eq!(kepler::output::StrokeWidths::default().get(EdgeClass::Crease), 0.35);
    /// ```
    pub fn get(&self, class: EdgeClass) -> f64 {
        match class {
            EdgeClass::Silhouette => self.silhouette,
            EdgeClass::Boundary => self.boundary,
            EdgeClass::Crease => self.crease,
            EdgeClass::Intersection => self.intersection,
            EdgeClass::Smooth => self.smooth,
        }
    }
}

impl Default for StrokeWidths {
    fn default() -> Self {
        StrokeWidths {
            silhouette: 0.5,
            boundary: 0.5,
            crease: 0.35,
            intersection: 0.35,
            smooth: 0.18,
        }
    }
}

/// How [`write_svg`] lays a drawing out on the page. All lengths are in millimetres.
///
/// [`write_svg`] refuses options with a page size that is not finite and positive, a margin
/// that is negative or leaves no room on the page, a stroke width that is negative or not
/// finite, or a dash or gap length that is not finite and positive.
///
/// ```
/// use kepler::output::SvgOptions;
/// let a3_portrait = SvgOptions { page: [297.0, 420.0], margin: 15.0, ..SvgOptions::default() };
/// assert_eq!(a3_portrait.stroke.silhouette, 0.5);
/// assert_eq!(SvgOptions::default().page, [297.0, 210.0]);
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SvgOptions {
    /// The page's width and height (default A4 landscape, 297 × 210).
    pub page: [f64; 2],
    /// The blank margin kept on every side of the page (default 10).
    pub margin: f64,
    /// The stroke width of each class, for visible and hidden lines alike.
    pub stroke: StrokeWidths,
    /// The dash and gap lengths of hidden lines (default 1.5 and 1).
    pub hidden_dash: [f64; 2],
}

impl Default for SvgOptions {
    fn default() -> Self {
        SvgOptions {
            page: [297.0, 210.0],
            margin: 10.0,
            stroke: StrokeWidths::default(),
            hidden_dash: [1.5, 1.0],
        }
    }
}

impl SvgOptions {
    /// The width of the page's drawing area (the page less its margins) over its height: the
    /// aspect a perspective view is framed to. 1 when the page is refused (the writer reports
    /// it).
    ///
    /// ```
    /// let a4 = kepler::output::SvgOptions::default();
    /// assert_eq!(a4.drawing_aspect(), (297.0 - 20.0) / (210.0 - 20.0));
    /// ```
    pub fn drawing_aspect(&self) -> f64 {
        let room = self.page.map(|side| side - 2.0 * self.margin);
        Some(room[0] / room[1])
            .filter(|a| a.is_finite() && *a > 0.0)
            .unwrap_or(1.0)
    }

    /// An error if the options are out of range (see [`SvgOptions`]).
    pub(crate) fn check(&self) -> io::Result<()> {
        let [width, height] = self.page;
        let bad = |what: String| Err(io::Error::new(io::ErrorKind::InvalidInput, what));
        if !(width.is_finite() && width > 0.0 && height.is_finite() && height > 0.0) {
            return bad(format!("page size {width} × {height} mm is not positive"));
        }
        if !(self.margin.is_finite() && self.margin >= 0.0) {
            return bad(format!("margin {} mm is negative", self.margin));
        }
        if 2.0 * self.margin >= width.min(height) {
            return bad(format!(
                "margin {} mm leaves no room on a {width} × {height} mm page",
                self.margin
            ));
        }
        for class in EdgeClass::ALL {
            let w = self.stroke.get(class);
            if !(w.is_finite() && w >= 0.0) {
                return bad(format!("{} stroke width {w} mm is negative", class.name()));
            }
        }
        let [dash, gap] = self.hidden_dash;
        if !(dash.is_finite() && dash > 0.0 && gap.is_finite() && gap > 0.0) {
            return bad(format!(
                "hidden dash {dash} mm, gap {gap} mm are not positive"
            ));
        }
        Ok(())
    }
}

/// The map from view coordinates (`y` up) to page millimetres (`y` down):
/// `(x, y) ↦ (scale·x + tx, ty − scale·y)`, the SVG `matrix(scale 0 0 -scale tx ty)`.
///
/// ```
/// use kepler::output::PageTransform;
/// let t = PageTransform { scale: 2.0, tx: 10.0, ty: 100.0 };
/// assert_eq!(t.to_page([1.0, 3.0]), [12.0, 94.0]);
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PageTransform {
    /// Millimetres per view unit (finite and positive).
    pub scale: f64,
    /// The page `x` of the view origin.
    pub tx: f64,
    /// The page `y` of the view origin.
    pub ty: f64,
}

impl PageTransform {
    /// The page position, in millimetres from the top left corner, of the view point `p`.
    ///
    /// ```
    /// use kepler::output::PageTransform;
    /// let t = PageTransform { scale: 0.5, tx: 0.0, ty: 210.0 };
    /// assert_eq!(t.to_page([0.0, 0.0]), [0.0, 210.0]);
    /// assert_eq!(t.to_page([4.0, 4.0]), [2.0, 208.0]);
    /// ```
    pub fn to_page(&self, p: [f64; 2]) -> [f64; 2] {
        [self.scale * p[0] + self.tx, self.ty - self.scale * p[1]]
    }
}

/// The transform [`write_svg`] uses: one uniform scale fitting the drawing's bounds
/// ([`Drawing::bounds`]) inside the page less the margins, aspect preserved, the bounds'
/// centre at the page's centre.
///
/// A drawing without extent (empty, or all its points equal) is drawn at scale 1, centred; a
/// drawing so small or so large that the fitting scale leaves the range of `f64` gets the
/// nearest finite positive scale. The options are assumed valid (as [`write_svg`] checks).
///
/// ```
/// use kepler::hidden::{Drawing, EdgeClass, Polyline};
/// use kepler::output::{page_transform, SvgOptions};
/// let drawing = Drawing {
///     polylines: vec![Polyline { class: EdgeClass::Boundary, visible: true, points: vec![[-1.0, -1.0], [1.0, 0.0]] }],
///     stages: Vec::new(),
/// };
/// let t = page_transform(&drawing, &SvgOptions::default());
/// // The width (2) fills the 277 mm between the margins; the height (1) is centred.
/// assert_eq!(t.scale, 138.5);
/// assert_eq!(t.to_page([-1.0, -1.0]), [10.0, 174.25]);
/// assert_eq!(t.to_page([1.0, 0.0]), [287.0, 35.75]);
/// ```
pub fn page_transform(drawing: &Drawing, options: &SvgOptions) -> PageTransform {
    PageTransform::fit(drawing.bounds(), options)
}

impl PageTransform {
    /// The transform that fits the box `(min, max)` (or nothing) to the page, as
    /// [`page_transform`] does for a drawing's bounds.
    ///
    /// ```
    /// use kepler::output::{PageTransform, SvgOptions};
    /// let t = PageTransform::fit(Some(([-1.0, -1.0], [1.0, 0.0])), &SvgOptions::default());
    /// assert_eq!(t.scale, 138.5);
    /// ```
    pub fn fit(bounds: Option<([f64; 2], [f64; 2])>, options: &SvgOptions) -> PageTransform {
        fit(bounds, options)
    }
}

/// [`PageTransform::fit`].
fn fit(bounds: Option<([f64; 2], [f64; 2])>, options: &SvgOptions) -> PageTransform {
    let [width, height] = options.page;
    let (centre, scale) = match bounds {
        None => ([0.0, 0.0], 1.0),
        Some((lo, hi)) => {
            // Halves, so that neither the extent nor the centre can overflow.
            let half = [hi[0] / 2.0 - lo[0] / 2.0, hi[1] / 2.0 - lo[1] / 2.0];
            let room = [
                (width / 2.0 - options.margin).max(0.0),
                (height / 2.0 - options.margin).max(0.0),
            ];
            let scale = (0..2)
                .filter(|&i| half[i] > 0.0)
                .map(|i| room[i] / half[i])
                .reduce(f64::min)
                .map_or(1.0, |s| s.clamp(f64::MIN_POSITIVE, f64::MAX));
            (
                [lo[0] / 2.0 + hi[0] / 2.0, lo[1] / 2.0 + hi[1] / 2.0],
                scale,
            )
        }
    };
    PageTransform {
        scale,
        tx: width / 2.0 - scale * centre[0],
        ty: height / 2.0 + scale * centre[1],
    }
}

/// Writes `drawing` as an SVG document laid out by `options` (the format is described in
/// [`crate::output`]). Path coordinates are the drawing's view coordinates, printed so that they
/// read back as the same `f64`; a polyline without points is left out.
///
/// Fails with [`io::ErrorKind::InvalidInput`] if the options are out of range (see
/// [`SvgOptions`]) or the stroke widths or dashes cannot be expressed in view units at the
/// drawing's scale, with [`io::ErrorKind::InvalidData`] if a coordinate is not finite, and with
/// any error of `out`.
///
/// ```
/// use kepler::hidden::{Drawing, EdgeClass, Polyline};
/// use kepler::output::{write_svg, SvgOptions};
/// let drawing = Drawing {
///     polylines: vec![
///         Polyline { class: EdgeClass::Crease, visible: true, points: vec![[0.0, 0.0], [2.0, 1.0]] },
///         Polyline { class: EdgeClass::Crease, visible: false, points: vec![[0.0, 1.0], [2.0, 0.0]] },
///     ],
///     stages: Vec::new(),
/// };
/// let mut out = Vec::new();
/// write_svg(&drawing, &SvgOptions::default(), &mut out).unwrap();
/// let svg = String::from_utf8(out).unwrap();
/// assert!(svg.contains(r#"width="297mm" height="210mm" viewBox="0 0 297 210""#));
/// assert!(svg.contains(r#"transform="matrix(138.5 0 0 -138.5 10 174.25)""#));
/// let hidden = svg.find(r#"id="hidden-crease""#).unwrap();
/// let visible = svg.find(r#"id="visible-crease""#).unwrap();
/// assert!(hidden < visible);
/// assert!(!svg.contains("visible-silhouette"));
///
/// let cramped = SvgOptions { margin: 200.0, ..SvgOptions::default() };
/// assert!(write_svg(&drawing, &cramped, &mut Vec::new()).is_err());
/// ```
pub fn write_svg(drawing: &Drawing, options: &SvgOptions, out: &mut impl Write) -> io::Result<()> {
    write_layers(drawing, None, options, out)
}

/// Hatch lines to draw with a drawing ([`write_svg_with_hatches`]): polylines in view
/// coordinates and their stroke width in millimetres on the page.
///
/// ```
/// let h = kepler::output::HatchLayer { polylines: vec![vec![[0.0, 0.0], [1.0, 0.0]]], stroke: 0.1 };
/// assert_eq!(h.polylines.len(), 1);
/// ```
#[derive(Debug, Clone, Default, PartialEq)]
pub struct HatchLayer {
    /// The hatch polylines (see [`crate::surfaces::hatch`]), in view coordinates.
    pub polylines: Vec<Vec<[f64; 2]>>,
    /// Their stroke width in millimetres.
    pub stroke: f64,
}

/// [`write_svg`] with a layer of hatch lines: `id="hatch"`, labelled `hatch`, black, solid,
/// `hatches.stroke` wide, between the hidden layers and the visible ones (so that the
/// outlines are drawn over the hatches' ends), left out when empty. The page transform is the
/// drawing's, as [`write_svg`]'s: hatches of visible faces lie inside the drawing's bounds.
///
/// Fails as [`write_svg`] does, and with [`io::ErrorKind::InvalidInput`] for a negative or
/// non-finite hatch stroke, [`io::ErrorKind::InvalidData`] for a hatch point not finite.
///
/// ```
/// use kepler::hidden::{Drawing, EdgeClass, Polyline};
/// use kepler::output::{HatchLayer, SvgOptions, write_svg_with_hatches};
/// let drawing = Drawing {
///     polylines: vec![Polyline { class: EdgeClass::Silhouette, visible: true, points: vec![[0.0, 0.0], [1.0, 1.0]] }],
///     stages: Vec::new(),
/// };
/// let hatches = HatchLayer { polylines: vec![vec![[0.0, 0.5], [0.5, 0.5]]], stroke: 0.1 };
/// let mut out = Vec::new();
/// write_svg_with_hatches(&drawing, &hatches, &SvgOptions::default(), &mut out).unwrap();
/// let svg = String::from_utf8(out).unwrap();
/// let hatch = svg.find(r#"<g id="hatch" inkscape:groupmode="layer" inkscape:label="hatch""#).unwrap();
/// assert!(hatch < svg.find(r#"id="visible-silhouette""#).unwrap());
/// assert!(svg.contains(r#"d="M 0 0.5 L 0.5 0.5""#));
/// ```
pub fn write_svg_with_hatches(
    drawing: &Drawing,
    hatches: &HatchLayer,
    options: &SvgOptions,
    out: &mut impl Write,
) -> io::Result<()> {
    if !(hatches.stroke.is_finite() && hatches.stroke >= 0.0) {
        return Err(io::Error::new(
            io::ErrorKind::InvalidInput,
            format!("hatch stroke width {} mm is negative", hatches.stroke),
        ));
    }
    if hatches
        .polylines
        .iter()
        .flatten()
        .any(|p| !(p[0].is_finite() && p[1].is_finite()))
    {
        return Err(io::Error::new(
            io::ErrorKind::InvalidData,
            "a hatch has a point that is not finite",
        ));
    }
    write_layers(drawing, Some(hatches), options, out)
}

/// [`write_svg`], with the hatch layer if any.
fn write_layers(
    drawing: &Drawing,
    hatches: Option<&HatchLayer>,
    options: &SvgOptions,
    out: &mut impl Write,
) -> io::Result<()> {
    options.check()?;
    super::check_finite(drawing)?;
    let t = page_transform(drawing, options);
    let in_view = |mm: f64, what: &str| in_view(&t, mm, what);
    let dash = [
        in_view(options.hidden_dash[0], "the hidden dash")?,
        in_view(options.hidden_dash[1], "the hidden gap")?,
    ];
    let mut widths = [0.0; EdgeClass::ALL.len()];
    for (width, class) in widths.iter_mut().zip(EdgeClass::ALL) {
        *width = in_view(options.stroke.get(class), "a stroke width")?;
    }
    if !(t.tx.is_finite() && t.ty.is_finite()) {
        return Err(io::Error::new(
            io::ErrorKind::InvalidInput,
            "the drawing cannot be placed on the page",
        ));
    }

    let [width, height] = options.page;
    let mut out = io::BufWriter::new(out);
    writeln!(out, r#"<?xml version="1.0" encoding="UTF-8"?>"#)?;
    writeln!(
        out,
        r#"<svg xmlns="http://www.w3.org/2000/svg" xmlns:inkscape="{INKSCAPE_NS}" version="1.1" width="{width}mm" height="{height}mm" viewBox="0 0 {width} {height}">"#
    )?;
    // Each layer a top-level group with the page transform, so that Inkscape and `vpype
    // read` see one layer per class and visibility (a layer nested in a group is not one).
    let placed = format!(
        r#"transform="matrix({s} 0 0 -{s} {tx} {ty})" fill="none" stroke-linecap="round" stroke-linejoin="round""#,
        s = t.scale,
        tx = t.tx,
        ty = t.ty,
    );
    for visible in [false, true] {
        if let Some(h) = hatches.filter(|h| visible && !h.polylines.is_empty()) {
            let paths: Vec<&[[f64; 2]]> = h.polylines.iter().map(Vec::as_slice).collect();
            writeln!(
                out,
                r#"<g id="hatch" inkscape:groupmode="layer" inkscape:label="hatch" {placed} stroke="{VISIBLE_COLOUR}" stroke-width="{}">"#,
                in_view(h.stroke, "the hatch stroke width")?
            )?;
            write_paths(&paths, &mut out)?;
            writeln!(out, "</g>")?;
        }
        for (class, stroke_width) in EdgeClass::ALL.into_iter().zip(widths) {
            let layer = Layer {
                class,
                visible,
                stroke_width,
                dash,
                placed: &placed,
            };
            write_class_layer(drawing, &layer, &mut out)?;
        }
    }
    writeln!(out, "</svg>")?;
    out.flush()
}

/// A length of `mm` millimetres on the page in drawing units under the transform `t`, or an
/// error naming `what` when it is out of range.
fn in_view(t: &PageTransform, mm: f64, what: &str) -> io::Result<f64> {
    let v = mm / t.scale;
    if v.is_finite() {
        Ok(v)
    } else {
        Err(io::Error::new(
            io::ErrorKind::InvalidInput,
            format!(
                "{what} of {mm} mm is out of range at a scale of {} mm per unit",
                t.scale
            ),
        ))
    }
}

/// The layer of one class and visibility: its stroke width and hidden dash in drawing units,
/// and the attributes of the page transform.
struct Layer<'a> {
    class: EdgeClass,
    visible: bool,
    stroke_width: f64,
    dash: [f64; 2],
    placed: &'a str,
}

/// Writes the layer of the drawing's polylines of `layer.class` and `layer.visible` (visible
/// layers solid, hidden ones dashed), left out when it has none.
fn write_class_layer(drawing: &Drawing, layer: &Layer, out: &mut impl Write) -> io::Result<()> {
    let Layer {
        class,
        visible,
        stroke_width,
        dash,
        placed,
    } = *layer;
    let paths: Vec<&[[f64; 2]]> = drawing
        .polylines
        .iter()
        .filter(|p| p.class == class && p.visible == visible && !p.points.is_empty())
        .map(|p| p.points.as_slice())
        .collect();
    if paths.is_empty() {
        return Ok(());
    }
    let name = class.name();
    let layer = |id: &str| {
        format!(r#"id="{id}-{name}" inkscape:groupmode="layer" inkscape:label="{id} {name}""#)
    };
    if visible {
        writeln!(
            out,
            r#"<g {} {placed} stroke="{VISIBLE_COLOUR}" stroke-width="{stroke_width}">"#,
            layer("visible")
        )?;
    } else {
        writeln!(
            out,
            r#"<g {} {placed} stroke="{HIDDEN_COLOUR}" stroke-width="{stroke_width}" stroke-dasharray="{} {}">"#,
            layer("hidden"),
            dash[0],
            dash[1]
        )?;
    }
    write_paths(&paths, out)?;
    writeln!(out, "</g>")
}

/// Inkscape's namespace, for its layer attributes.
const INKSCAPE_NS: &str = "http://www.inkscape.org/namespaces/inkscape";

/// Writes one `<path>` per polyline, in order. Formatting the numbers (shortest round trip)
/// is most of the work of a large drawing: windows of polylines are formatted in parallel
/// pieces and written in order, so the bytes are those of writing them one by one, and the
/// memory held is one window's text.
fn write_paths(paths: &[&[[f64; 2]]], out: &mut impl Write) -> io::Result<()> {
    use rayon::prelude::*;
    const WINDOW: usize = 1 << 16;
    const PIECE: usize = 1 << 11;
    for window in paths.chunks(WINDOW) {
        let pieces: Vec<Vec<u8>> = window
            .par_chunks(PIECE)
            .map(|piece| {
                let mut text = Vec::new();
                for polyline in piece {
                    text.extend_from_slice(b"<path d=\"");
                    for (i, [x, y]) in polyline.iter().enumerate() {
                        let command = if i == 0 { "M" } else { " L" };
                        // Writing into a vector cannot fail.
                        let _ = write!(text, "{command} {x} {y}");
                    }
                    text.extend_from_slice(b"\"/>\n");
                }
                text
            })
            .collect();
        for text in pieces {
            out.write_all(&text)?;
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::hidden::Polyline;

    /// Many polylines (several windows and pieces) are written as one by one, in order.
    #[test]
    fn paths_formatted_in_parallel_are_written_in_order() {
        let polylines: Vec<Polyline> = (0..150_000u32)
            .map(|i| Polyline {
                class: EdgeClass::Smooth,
                visible: true,
                points: (0..1 + i % 4)
                    .map(|k| [f64::from(i) / 7.0, -f64::from(k) * 1e-300])
                    .collect(),
            })
            .collect();
        let refs: Vec<&[[f64; 2]]> = polylines.iter().map(|p| p.points.as_slice()).collect();
        let mut parallel = Vec::new();
        write_paths(&refs, &mut parallel).unwrap();
        let mut one_by_one = String::new();
        for p in &polylines {
            one_by_one += "<path d=\"";
            for (i, [x, y]) in p.points.iter().enumerate() {
                one_by_one += &format!("{} {x} {y}", if i == 0 { "M" } else { " L" });
            }
            one_by_one += "\"/>\n";
        }
        assert_eq!(String::from_utf8(parallel).unwrap(), one_by_one);
    }
}
