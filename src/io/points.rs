//! Point files for the point queries: one point per line, `x y z`, the coordinates separated
//! by commas or by white space; and segment files, `x1 y1 x2 y2` per line, the same way.
//!
//! Blank lines and `#` comments are allowed and produce no point (so answers correspond to the
//! points in order, not to line numbers). Any other line must hold exactly three finite
//! numbers (any finite double: the point queries are exact at every scale), or four of
//! magnitude at most [`MAX_COORDINATE`] for a segment (Franklin's grid computes cells in
//! floating point); anything else is an error naming the file and line. Nothing is skipped
//! silently.
//!
//! ```
//! use kepler::io::points::parse_points;
//! let points = parse_points("# x y z\n1 2 3\n\n4.5, -1, 0\n", "p.txt").unwrap();
//! assert_eq!(points.len(), 2);
//! assert_eq!(points[1].x, 4.5);
//! let err = parse_points("1 2 3\n1 2\n", "p.txt").unwrap_err();
//! assert_eq!(err.to_string(), "p.txt:2: expected 3 coordinates (x y z), found 2");
//! ```

use super::{FileError, Result};
use super::{finite, quoted, strip_bom, strip_comment};
use crate::geometry::Point3;
use crate::geometry::predicates::MAX_COORDINATE;
use geo::{Coord, Line};
use std::io::Read;
use std::path::Path;

/// Parses the text of a point file; `name` names it in errors.
///
/// ```
/// use kepler::io::points::parse_points;
/// assert!(parse_points("1,,2,3", "p").unwrap_err().to_string().contains("empty coordinate"));
/// assert!(parse_points("1 2 nan", "p").unwrap_err().to_string().contains("not a finite number"));
/// ```
pub fn parse_points(text: &str, name: &str) -> Result<Vec<Point3>> {
    let rows = parse_rows::<3>(text, name, "x y z", f64::MAX)?;
    Ok(rows.into_iter().map(|(_, c)| Point3::from(c)).collect())
}

/// Parses the text of a segment file, one segment `x1 y1 x2 y2` per line (same rules as point
/// files), with the 1-based line of each segment.
///
/// ```
/// use kepler::io::points::parse_segments;
/// let s = parse_segments("# two\n0 0 1 1\n\n0,1,1,0\n", "s.txt").unwrap();
/// assert_eq!(s.iter().map(|(line, _)| *line).collect::<Vec<_>>(), vec![2, 4]);
/// assert_eq!(s[1].1.end.x, 1.0);
/// let err = parse_segments("0 0 1\n", "s.txt").unwrap_err();
/// assert_eq!(err.to_string(), "s.txt:1: expected 4 coordinates (x1 y1 x2 y2), found 3");
/// ```
pub fn parse_segments(text: &str, name: &str) -> Result<Vec<(usize, Line<f64>)>> {
    let rows = parse_rows::<4>(text, name, "x1 y1 x2 y2", MAX_COORDINATE)?;
    Ok(rows
        .into_iter()
        .map(|(line, [x1, y1, x2, y2])| {
            (
                line,
                Line::new(Coord { x: x1, y: y1 }, Coord { x: x2, y: y2 }),
            )
        })
        .collect())
}

/// The rows of `N` numbers of a text, each at most `limit` in magnitude, with their 1-based
/// line numbers; `fields` names the numbers in errors.
fn parse_rows<const N: usize>(
    text: &str,
    name: &str,
    fields: &str,
    limit: f64,
) -> Result<Vec<(usize, [f64; N])>> {
    let mut rows = Vec::new();
    for (i, raw) in strip_bom(text).lines().enumerate() {
        let line = strip_comment(raw).trim();
        if line.is_empty() {
            continue;
        }
        let found: Vec<&str> = if line.contains(',') {
            line.split(',').map(str::trim).collect()
        } else {
            line.split_whitespace().collect()
        };
        let at = |message: String| FileError::at_line(name, i + 1, message);
        if found.iter().any(|f| f.is_empty()) {
            return Err(at("empty coordinate between commas".into()));
        }
        if found.len() != N {
            return Err(at(format!(
                "expected {N} coordinates ({fields}), found {}",
                found.len()
            )));
        }
        let mut c = [0.0; N];
        for (k, field) in found.iter().enumerate() {
            c[k] = finite(field, "coordinate").map_err(at)?;
            if c[k].abs() > limit {
                return Err(at(format!(
                    "coordinate {} is larger in magnitude than {limit:e}",
                    quoted(field)
                )));
            }
        }
        rows.push((i + 1, c));
    }
    Ok(rows)
}

/// Reads a point file, or standard input when `path` is `-`.
///
/// ```
/// let path = std::env::temp_dir().join(format!("kepler-points-{}.txt", std::process::id()));
/// std::fs::write(&path, "0 0 0\n1 1 1\n")?;
/// assert_eq!(kepler::io::points::read_points(&path)?.len(), 2);
/// std::fs::remove_file(&path)?;
/// let missing = kepler::io::points::read_points(std::path::Path::new("no/such/file"));
/// assert!(missing.unwrap_err().to_string().starts_with("no/such/file: "));
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn read_points(path: &Path) -> Result<Vec<Point3>> {
    let (text, name) = read_text(path)?;
    parse_points(&text, &name)
}

/// Reads a segment file (see [`parse_segments`]), or standard input when `path` is `-`.
///
/// ```
/// let missing = kepler::io::points::read_segments(std::path::Path::new("no/such/file"));
/// assert!(missing.unwrap_err().to_string().starts_with("no/such/file: "));
/// ```
pub fn read_segments(path: &Path) -> Result<Vec<(usize, Line<f64>)>> {
    let (text, name) = read_text(path)?;
    parse_segments(&text, &name)
}

/// The text of a file, or of standard input for `-`, and the name errors should give.
fn read_text(path: &Path) -> Result<(String, String)> {
    let stdin = path.as_os_str() == "-";
    let name = if stdin {
        "standard input".to_owned()
    } else {
        path.display().to_string()
    };
    let mut bytes = Vec::new();
    if stdin {
        std::io::stdin()
            .lock()
            .read_to_end(&mut bytes)
            .map_err(|e| FileError::io(&name, e))?;
    } else {
        bytes = std::fs::read(path).map_err(|e| FileError::io(&name, e))?;
    }
    let text = String::from_utf8(bytes).map_err(|e| {
        let valid = &e.as_bytes()[..e.utf8_error().valid_up_to()];
        let line = 1 + valid.iter().filter(|&&b| b == b'\n').count();
        FileError::at_line(&name, line, "the text is not UTF-8")
    })?;
    Ok((text, name))
}
