//! Charts of the report (SVG, with plotters).
//!
//! The report's figures plot error against cost: the error figures of
//! [`measure`](super::measure) for each variant against its run time, or against a stiffness
//! parameter of the scene. Errors span many decades (a rounding error of `1e-15` of the picture
//! beside a z-buffer's `1e-3`), so the error axis is logarithmic: [`log_log`] when the other
//! axis spans decades too (time, size), [`semi_log`] when it is a parameter stepped linearly.
//!
//! The exact engine's error is 0, and a variant may be exact on some scenes: the cases the
//! report is about, which a logarithmic axis cannot place. Values at or below 0 on a
//! logarithmic axis are drawn on a *floor line* one decade below the decade of the smallest
//! positive value on that axis (at `10^(⌊log10 m⌋ - 1)` for the smallest positive value `m`),
//! and the floor's tick is labelled `0`. Non-finite values (a variant that failed) are left
//! out: the point is skipped and the series' line joins its neighbours.
//!
//! Logarithmic axes are drawn as linear axes over `log10` of the values, with a tick at every
//! decade (every few decades when there are many), labelled `0.01`, `1`, `1000` or `1e-9`. So
//! the ticks and the floor are exact decades whatever the range, down to subnormal values.
//!
//! Each series gets its own colour (the ten colours of the Tableau palette, then hues a golden
//! angle apart) and a marker (ten shapes, filled and hollow, in turn), and a line in the legend.
//!
//! Only plotters' SVG backend is built, without a font library: plotters lays out text with a
//! rough estimate of its width, and the SVG holds `<text>` elements (`sans-serif`) that the
//! viewer sets in its own fonts. So charts render the same on a machine with no fonts at all.
//!
//! ```
//! use kepler::lab::report::chart::{Series, log_log};
//! let path = std::env::temp_dir().join(format!("kepler-chart-doc-{}.svg", std::process::id()));
//! let series = [
//!     Series { name: "exact".into(), points: vec![(2.0, 0.0), (40.0, 0.0)] },
//!     Series { name: "f32".into(), points: vec![(0.5, 1e-4), (9.0, 3e-3)] },
//! ];
//! log_log(&path, "Error against time", "seconds", "relative error", &series).unwrap();
//! let svg = std::fs::read_to_string(&path).unwrap();
//! assert!(svg.contains("<svg") && svg.contains("f32"));
//! std::fs::remove_file(&path).unwrap();
//! ```

use plotters::coord::ranged1d::{DefaultFormatting, KeyPointHint};
use plotters::coord::types::RangedCoordf64;
use plotters::element::{Drawable, PointCollection};
use plotters::prelude::*;
use plotters_backend::{BackendCoord, DrawingErrorKind};
use std::ops::Range;
use std::path::{Path, PathBuf};

/// One line of a chart: a variant, or a variant with one setting of its parameter.
///
/// ```
/// let s = kepler::lab::report::chart::Series { name: "tolerance 1e-9".into(), points: vec![(1.0, 2e-7)] };
/// assert_eq!(s.points.len(), 1);
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct Series {
    /// The name in the legend.
    pub name: String,
    /// The points `(x, y)`, joined in this order.
    pub points: Vec<(f64, f64)>,
}

/// Why a chart could not be made.
///
/// ```
/// use kepler::lab::report::chart::{ChartError, semi_log};
/// let path = std::env::temp_dir().join("kepler-no-such-directory").join("chart.svg");
/// let e = semi_log(&path, "t", "k", "error", &[]).unwrap_err();
/// assert!(matches!(e, ChartError::Write { .. }));
/// ```
#[derive(Debug, thiserror::Error)]
pub enum ChartError {
    /// Plotters failed to draw the chart.
    #[error("cannot draw the chart {path}")]
    Draw {
        /// The chart's file.
        path: PathBuf,
        /// Plotters' error.
        #[source]
        source: Box<dyn std::error::Error + Send + Sync>,
    },
    /// The SVG file could not be written.
    #[error("cannot write the chart {path}")]
    Write {
        /// The chart's file.
        path: PathBuf,
        /// The error writing it.
        #[source]
        source: std::io::Error,
    },
}

/// Writes an SVG chart of `series` with both axes logarithmic (values ≤ 0 on the floor line
/// labelled `0`, non-finite values skipped: see the [module documentation](self)).
///
/// ```
/// use kepler::lab::report::chart::{Series, log_log};
/// let path = std::env::temp_dir().join(format!("kepler-log-log-doc-{}.svg", std::process::id()));
/// let s = Series { name: "plain floats".into(), points: vec![(1e-3, 1e-12), (1e-2, 1e-9), (f64::NAN, 1.0)] };
/// log_log(&path, "Error and time", "seconds", "wrong length / length", &[s]).unwrap();
/// assert!(std::fs::read_to_string(&path).unwrap().contains("plain floats"));
/// std::fs::remove_file(&path).unwrap();
/// ```
pub fn log_log(
    path: &Path,
    title: &str,
    x_label: &str,
    y_label: &str,
    series: &[Series],
) -> Result<(), ChartError> {
    chart(path, title, [x_label, y_label], true, series)
}

/// Writes an SVG chart of `series` with a linear `x` axis (a stiffness parameter, say) and a
/// logarithmic `y` axis (values ≤ 0 on the floor line labelled `0`, non-finite values
/// skipped: see the [module documentation](self)).
///
/// ```
/// use kepler::lab::report::chart::{Series, semi_log};
/// let path = std::env::temp_dir().join(format!("kepler-semi-log-doc-{}.svg", std::process::id()));
/// let s = Series { name: "exact".into(), points: (0..8).map(|k| (k as f64, 0.0)).collect() };
/// let t = Series { name: "tolerance".into(), points: (0..8).map(|k| (k as f64, 10f64.powi(k - 12))).collect() };
/// semi_log(&path, "Error against stiffness", "k", "Hausdorff distance", &[s, t]).unwrap();
/// assert!(std::fs::read_to_string(&path).unwrap().contains("tolerance"));
/// std::fs::remove_file(&path).unwrap();
/// ```
pub fn semi_log(
    path: &Path,
    title: &str,
    x_label: &str,
    y_label: &str,
    series: &[Series],
) -> Result<(), ChartError> {
    chart(path, title, [x_label, y_label], false, series)
}

/// The chart's size in pixels.
const SIZE: (u32, u32) = (800, 560);

fn chart(
    path: &Path,
    title: &str,
    labels: [&str; 2],
    log_x: bool,
    series: &[Series],
) -> Result<(), ChartError> {
    let finite = || {
        series
            .iter()
            .flat_map(|s| s.points.iter())
            .filter(|(x, y)| x.is_finite() && y.is_finite())
    };
    let x = Axis::new(log_x, finite().map(|p| p.0));
    let y = Axis::new(true, finite().map(|p| p.1));
    let mut svg = String::new();
    render(&mut svg, title, labels, [&x, &y], series).map_err(|e| ChartError::Draw {
        path: path.to_path_buf(),
        source: Box::new(e),
    })?;
    std::fs::write(path, svg).map_err(|source| ChartError::Write {
        path: path.to_path_buf(),
        source,
    })
}

fn render(
    svg: &mut String,
    title: &str,
    [x_label, y_label]: [&str; 2],
    [x, y]: [&Axis; 2],
    series: &[Series],
) -> Result<(), DrawingAreaErrorKind<std::io::Error>> {
    let root = SVGBackend::with_string(svg, SIZE).into_drawing_area();
    root.fill(&WHITE)?;
    let mut chart = ChartBuilder::on(&root)
        .caption(title, ("sans-serif", 22))
        .margin(16)
        .x_label_area_size(48)
        .y_label_area_size(72)
        .build_cartesian_2d(x.clone(), y.clone())?;
    chart
        .configure_mesh()
        .x_desc(x_label)
        .y_desc(y_label)
        .x_label_formatter(&|v| x.label(*v))
        .y_label_formatter(&|v| y.label(*v))
        .bold_line_style(BLACK.mix(0.12))
        .draw()?;
    let floor_style = BLACK.stroke_width(1);
    if let Some(f) = y.floor {
        let line = vec![(x.range.start, f), (x.range.end, f)];
        chart.draw_series(std::iter::once(PathElement::new(line, floor_style)))?;
    }
    if let Some(f) = x.floor {
        let line = vec![(f, y.range.start), (f, y.range.end)];
        chart.draw_series(std::iter::once(PathElement::new(line, floor_style)))?;
    }
    for (i, s) in series.iter().enumerate() {
        let style = Style::of(i);
        let points: Vec<(f64, f64)> = s
            .points
            .iter()
            .filter_map(|&(a, b)| Some((x.place(a)?, y.place(b)?)))
            .collect();
        chart.draw_series(std::iter::once(PathElement::new(
            points.clone(),
            style.color.stroke_width(2),
        )))?;
        chart
            .draw_series(points.into_iter().map(|at| Mark {
                at,
                style,
                key: false,
            }))?
            .label(s.name.as_str())
            .legend(move |at| Mark {
                at,
                style,
                key: true,
            });
    }
    if !series.is_empty() {
        chart
            .configure_series_labels()
            .background_style(WHITE.mix(0.85))
            .border_style(BLACK)
            .position(SeriesLabelPosition::UpperRight)
            .draw()?;
    }
    root.present()
}

/// One axis: where values go on it (`log10` of them on a logarithmic axis), its range and
/// its ticks.
#[derive(Debug, Clone)]
struct Axis {
    log: bool,
    /// On a logarithmic axis with values ≤ 0: the decade they are drawn at.
    floor: Option<f64>,
    range: Range<f64>,
    ticks: Vec<f64>,
    /// On a linear axis: the decimals of the tick labels.
    decimals: usize,
}

impl Axis {
    /// The axis for `values` (all finite).
    fn new(log: bool, values: impl Iterator<Item = f64>) -> Axis {
        let values: Vec<f64> = values.collect();
        if log {
            Axis::logarithmic(&values)
        } else {
            Axis::linear(&values)
        }
    }

    fn logarithmic(values: &[f64]) -> Axis {
        let (lo, hi) = values
            .iter()
            .filter(|&&v| v > 0.0)
            .map(|v| v.log10())
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| {
                (lo.min(v), hi.max(v))
            });
        let (lo, hi) = if lo <= hi {
            (lo.floor(), hi.ceil())
        } else {
            (0.0, 1.0)
        };
        let hi = if hi > lo { hi } else { lo + 1.0 };
        let floor = values.iter().any(|&v| v <= 0.0).then_some(lo - 1.0);
        let step = ((hi - lo) / 10.0).ceil().max(1.0);
        let first = (lo / step).ceil() as i64;
        let last = (hi / step).floor() as i64;
        let ticks = floor
            .into_iter()
            .chain((first..=last).map(|k| k as f64 * step))
            .collect();
        let bottom = floor.unwrap_or(lo);
        let pad = 0.04 * (hi - bottom);
        Axis {
            log: true,
            floor,
            range: bottom - pad..hi + pad,
            ticks,
            decimals: 0,
        }
    }

    fn linear(values: &[f64]) -> Axis {
        let (lo, hi) = values
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &v| {
                (lo.min(v), hi.max(v))
            });
        let (lo, hi) = if lo < hi {
            (lo, hi)
        } else if lo == hi {
            let half = 0.5 * lo.abs().max(1.0);
            (lo - half, hi + half)
        } else {
            (0.0, 1.0)
        };
        // Halved first, so that the span of values near the largest f64 does not overflow.
        let half_span = 0.5 * hi - 0.5 * lo;
        let raw = half_span / 4.0;
        let magnitude = 10f64.powf(raw.log10().floor());
        let step = [1.0, 2.0, 5.0, 10.0]
            .into_iter()
            .map(|f| f * magnitude)
            .find(|&s| s >= raw)
            .unwrap_or(10.0 * magnitude);
        let ticks = if step > 0.0 && step.is_finite() {
            let (first, last) = ((lo / step).ceil() as i64, (hi / step).floor() as i64);
            (first..=last).map(|k| k as f64 * step).collect()
        } else {
            vec![lo, hi]
        };
        let pad = 0.08 * half_span;
        Axis {
            log: false,
            floor: None,
            range: lo - pad..hi + pad,
            ticks,
            decimals: (-step.log10().floor()).clamp(0.0, 17.0) as usize,
        }
    }

    /// Where a value goes on the axis (`None` if it is not finite).
    fn place(&self, v: f64) -> Option<f64> {
        match (v.is_finite(), self.log) {
            (false, _) => None,
            (true, false) => Some(v),
            (true, true) if v > 0.0 => Some(v.log10()),
            (true, true) => self.floor,
        }
    }

    /// The label of a tick.
    fn label(&self, v: f64) -> String {
        if self.floor == Some(v) {
            "0".into()
        } else if self.log {
            decade(v.round() as i32)
        } else if v == 0.0 {
            // Also for -0.0.
            "0".into()
        } else {
            format!("{v:.*}", self.decimals)
        }
    }
}

/// The axis as plotters' coordinate: linear over the range, its ticks as key points (no
/// light mesh lines).
impl Ranged for Axis {
    type FormatOption = DefaultFormatting;
    type ValueType = f64;

    fn map(&self, value: &f64, limit: (i32, i32)) -> i32 {
        RangedCoordf64::from(self.range.clone()).map(value, limit)
    }

    fn key_points<Hint: KeyPointHint>(&self, hint: Hint) -> Vec<f64> {
        if hint.weight().allow_light_points() {
            Vec::new()
        } else {
            self.ticks.clone()
        }
    }

    fn range(&self) -> Range<f64> {
        self.range.clone()
    }
}

/// The label of `10^k`.
fn decade(k: i32) -> String {
    match k {
        0..=3 => format!("1{}", "0".repeat(k.unsigned_abs() as usize)),
        -3..=-1 => format!("0.{}1", "0".repeat((k.unsigned_abs() - 1) as usize)),
        _ => format!("1e{k}"),
    }
}

/// A series' marker shapes.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Shape {
    Circle,
    Square,
    Triangle,
    Diamond,
    Cross,
    Plus,
}

/// The markers, in turn: the closed shapes filled and hollow, the crosses.
const MARKERS: [(Shape, bool); 10] = [
    (Shape::Circle, true),
    (Shape::Square, false),
    (Shape::Triangle, true),
    (Shape::Cross, false),
    (Shape::Diamond, true),
    (Shape::Circle, false),
    (Shape::Square, true),
    (Shape::Triangle, false),
    (Shape::Plus, false),
    (Shape::Diamond, false),
];

/// The Tableau 10 palette.
const PALETTE: [(u8, u8, u8); 10] = [
    (31, 119, 180),
    (255, 127, 14),
    (44, 160, 44),
    (214, 39, 40),
    (148, 103, 189),
    (140, 86, 75),
    (227, 119, 194),
    (127, 127, 127),
    (188, 189, 34),
    (23, 190, 207),
];

/// How series `i` is drawn.
#[derive(Debug, Clone, Copy)]
struct Style {
    color: RGBAColor,
    shape: Shape,
    filled: bool,
}

impl Style {
    fn of(i: usize) -> Style {
        let color = match PALETTE.get(i) {
            Some(&(r, g, b)) => RGBColor(r, g, b).to_rgba(),
            // Hues a golden angle apart: never the same twice.
            None => HSLColor((i as f64 * 0.618_033_988_749_895).fract(), 0.65, 0.45).to_rgba(),
        };
        let (shape, filled) = MARKERS[i % MARKERS.len()];
        Style {
            color,
            shape,
            filled,
        }
    }
}

/// A series' marker at a point, or (`key`) its key in the legend: a short line through the
/// marker, starting at the point.
struct Mark<C> {
    at: C,
    style: Style,
    key: bool,
}

impl<'a, C: 'a> PointCollection<'a, C> for &'a Mark<C> {
    type Point = &'a C;
    type IntoIter = std::iter::Once<&'a C>;

    fn point_iter(self) -> Self::IntoIter {
        std::iter::once(&self.at)
    }
}

impl<C, DB: DrawingBackend> Drawable<DB> for Mark<C> {
    fn draw<I: Iterator<Item = BackendCoord>>(
        &self,
        pos: I,
        backend: &mut DB,
        _: (u32, u32),
    ) -> Result<(), DrawingErrorKind<DB::ErrorType>> {
        for (x, y) in pos {
            if self.key {
                backend.draw_line((x, y), (x + 24, y), &self.style.color.stroke_width(2))?;
                self.style.mark(backend, (x + 12, y))?;
            } else {
                self.style.mark(backend, (x, y))?;
            }
        }
        Ok(())
    }
}

impl Style {
    /// Draws the marker centred at `(x, y)`: outlined in the series' colour, filled with it or
    /// (a hollow marker) with white, hiding the series' line under it.
    fn mark<DB: DrawingBackend>(
        &self,
        backend: &mut DB,
        (x, y): BackendCoord,
    ) -> Result<(), DrawingErrorKind<DB::ErrorType>> {
        const R: i32 = 4;
        let stroke = self.color.stroke_width(2);
        let fill = if self.filled {
            self.color.filled()
        } else {
            WHITE.filled()
        };
        let polygon = match self.shape {
            Shape::Circle => {
                backend.draw_circle((x, y), R as u32, &fill, true)?;
                return backend.draw_circle((x, y), R as u32, &stroke, false);
            }
            Shape::Square => {
                let corners = ((x - R, y - R), (x + R, y + R));
                backend.draw_rect(corners.0, corners.1, &fill, true)?;
                return backend.draw_rect(corners.0, corners.1, &stroke, false);
            }
            Shape::Cross => {
                backend.draw_line((x - R, y - R), (x + R, y + R), &stroke)?;
                return backend.draw_line((x - R, y + R), (x + R, y - R), &stroke);
            }
            Shape::Plus => {
                backend.draw_line((x - R - 1, y), (x + R + 1, y), &stroke)?;
                return backend.draw_line((x, y - R - 1), (x, y + R + 1), &stroke);
            }
            Shape::Triangle => vec![(x, y - R - 1), (x + R + 1, y + R), (x - R - 1, y + R)],
            Shape::Diamond => vec![
                (x, y - R - 1),
                (x + R + 1, y),
                (x, y + R + 1),
                (x - R - 1, y),
            ],
        };
        backend.fill_polygon(polygon.iter().copied(), &fill)?;
        backend.draw_path(polygon.iter().chain(polygon.first()).copied(), &stroke)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn temp(name: &str) -> PathBuf {
        let unique = format!("kepler-chart-{}-{name}.svg", std::process::id());
        std::env::temp_dir().join(unique)
    }

    /// The chart at `path` parses as XML; returns its texts, and removes it.
    fn texts(path: &Path) -> Vec<String> {
        let svg = std::fs::read_to_string(path).unwrap();
        std::fs::remove_file(path).unwrap();
        let doc = roxmltree::Document::parse(&svg).unwrap();
        assert_eq!(doc.root_element().tag_name().name(), "svg");
        doc.descendants()
            .filter(|n| n.has_tag_name("text"))
            .map(|n| n.text().unwrap_or("").trim().to_string())
            .collect()
    }

    fn series() -> Vec<Series> {
        let names = [
            "exact",
            "plain floats",
            "tolerance 1e-9 & <more>",
            "f32",
            "sampled edges",
            "z-buffer",
        ];
        names
            .iter()
            .enumerate()
            .map(|(i, name)| Series {
                name: name.to_string(),
                points: (1..6)
                    .map(|k| {
                        let x = k as f64 * 0.7;
                        let y = if i == 0 {
                            0.0
                        } else {
                            10f64.powi(-(i as i32) * 3) * x
                        };
                        (x, y)
                    })
                    .chain([(f64::NAN, 1.0), (2.0, f64::INFINITY)])
                    .collect(),
            })
            .collect()
    }

    #[test]
    fn log_log_chart_is_xml_with_every_name() {
        let path = temp("log-log");
        let s = series();
        log_log(&path, "Error against time", "seconds", "relative error", &s).unwrap();
        let texts = texts(&path);
        for name in s.iter().map(|s| &s.name) {
            assert!(texts.contains(name), "{name} not in {texts:?}");
        }
        for label in [
            "Error against time",
            "seconds",
            "relative error",
            "0",
            "1e-14",
        ] {
            assert!(texts.iter().any(|t| t == label), "{label} not in {texts:?}");
        }
    }

    #[test]
    fn semi_log_chart_is_xml_with_every_name() {
        let path = temp("semi-log");
        let s = series();
        semi_log(&path, "Error against stiffness", "k", "error", &s).unwrap();
        let texts = texts(&path);
        for name in s.iter().map(|s| &s.name) {
            assert!(texts.contains(name), "{name} not in {texts:?}");
        }
        assert!(texts.iter().any(|t| t == "0"), "{texts:?}");
    }

    #[test]
    fn degenerate_charts() {
        let empty = temp("empty");
        log_log(&empty, "Nothing", "x", "y", &[]).unwrap();
        assert!(texts(&empty).contains(&"Nothing".to_string()));
        let lone = temp("lone");
        let s = Series {
            name: "lone".into(),
            points: vec![(3.0, 0.0), (f64::NAN, f64::NAN)],
        };
        semi_log(&lone, "One point", "k", "error", &[s]).unwrap();
        assert!(texts(&lone).contains(&"lone".to_string()));
        let tiny = temp("tiny");
        let s = Series {
            name: "tiny".into(),
            points: vec![(f64::from_bits(1), 1e300), (f64::MAX, -0.0)],
        };
        log_log(&tiny, "Extremes", "x", "y", &[s]).unwrap();
        let texts = texts(&tiny);
        for label in ["0", "1e300"] {
            assert!(texts.iter().any(|t| t == label), "{label} not in {texts:?}");
        }
    }

    #[test]
    fn axes() {
        let y = Axis::new(true, [0.0, 3e-5, 0.2].into_iter());
        assert_eq!(y.floor, Some(-6.0));
        assert_eq!(y.ticks, vec![-6.0, -5.0, -4.0, -3.0, -2.0, -1.0, 0.0]);
        let labels: Vec<String> = y.ticks.iter().map(|&v| y.label(v)).collect();
        assert_eq!(labels, ["0", "1e-5", "1e-4", "0.001", "0.01", "0.1", "1"]);
        assert_eq!(
            (y.place(-2.0), y.place(f64::NAN), y.place(100.0)),
            (Some(-6.0), None, Some(2.0))
        );
        let x = Axis::new(false, [0.0, 1.0, 7.0].into_iter());
        assert_eq!(x.ticks, vec![0.0, 1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0]);
        assert_eq!(x.label(3.0), "3");
        assert_eq!(decade(3), "1000");
        assert_eq!(decade(-300), "1e-300");
        let many = Axis::new(true, [1e-300, 1e300].into_iter());
        assert!(many.ticks.len() <= 12 && many.floor.is_none());
        // Distinct colours beyond the palette.
        let colours: Vec<_> = (0..40)
            .map(|i| Style::of(i).color)
            .map(|c| (c.0, c.1, c.2))
            .collect();
        for (i, c) in colours.iter().enumerate() {
            assert!(!colours[..i].contains(c), "colour {i} repeats");
        }
    }
}
