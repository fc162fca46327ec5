//! The JSON form of a drawing (see [`crate::output`]).

use std::io::{self, Write};

use serde::Serialize;

use crate::hidden::{Drawing, Polyline};

/// The JSON document: the polylines alone, whatever else a [`Drawing`] holds.
#[derive(Serialize)]
struct Document<'a> {
    polylines: &'a [Polyline],
}

/// Writes `drawing` as `{"polylines":[{"class":…,"visible":…,"points":[[x,y],…]},…]}` followed
/// by a newline: the polylines in the drawing's order, in view coordinates, each number the
/// shortest decimal that reads back as the same `f64`.
///
/// Fails with [`io::ErrorKind::InvalidData`] if a coordinate is not finite (JSON has no `NaN` or
/// infinity), and with any error of `out`.
///
/// ```
/// use kepler::hidden::{Drawing, EdgeClass, Polyline};
/// let drawing = Drawing {
///     polylines: vec![Polyline { class: EdgeClass::Crease, visible: false, points: vec![[0.1, -2.0], [1.0 / 3.0, 5e-300]] }],
///     stages: Vec::new(),
/// };
/// let mut out = Vec::new();
/// kepler::output::write_json(&drawing, &mut out).unwrap();
/// let text = String::from_utf8(out).unwrap();
/// assert_eq!(
///     text,
///     "{\"polylines\":[{\"class\":\"crease\",\"visible\":false,\"points\":[[0.1,-2.0],[0.3333333333333333,5e-300]]}]}\n"
/// );
/// assert_eq!("0.3333333333333333".parse::<f64>(), Ok(1.0 / 3.0));
///
/// let bad = Drawing {
///     polylines: vec![Polyline { class: EdgeClass::Crease, visible: true, points: vec![[f64::NAN, 0.0], [1.0, 0.0]] }],
///     stages: Vec::new(),
/// };
/// assert!(kepler::output::write_json(&bad, &mut Vec::new()).is_err());
/// ```
pub fn write_json(drawing: &Drawing, out: &mut impl Write) -> io::Result<()> {
    super::check_finite(drawing)?;
    let mut out = io::BufWriter::new(out);
    serde_json::to_writer(
        &mut out,
        &Document {
            polylines: &drawing.polylines,
        },
    )?;
    out.write_all(b"\n")?;
    out.flush()
}
