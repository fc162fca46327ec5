//! Point files for the point queries: one point per line, `x y z`, the coordinates separated
//! by commas or by white space.
//!
//! Blank lines and `#` comments are allowed and produce no point (so answers correspond to the
//! points in order, not to line numbers). Any other line must hold exactly three finite
//! numbers of magnitude at most [`MAX_COORDINATE`]; anything else is an error naming the file
//! and line. Nothing is skipped silently.
//!
//! ```
//! use kepler::io::points::parse_points;
//! let points = parse_points("# x y z\n1 2 3\n\n4.5, -1, 0\n", "p.txt").unwrap();
//! assert_eq!(points.len(), 2);
//! assert_eq!(points[1].x, 4.5);
//! let err = parse_points("1 2 3\n1 2\n", "p.txt").unwrap_err();
//! assert_eq!(err.to_string(), "p.txt:2: expected 3 coordinates (x y z), found 2");
//! ```

use super::{finite, strip_bom, strip_comment};
use crate::error::{Error, Result};
use crate::geometry::Point3;
use crate::geometry::predicates::MAX_COORDINATE;
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
    let mut points = Vec::new();
    for (i, raw) in strip_bom(text).lines().enumerate() {
        let line = strip_comment(raw).trim();
        if line.is_empty() {
            continue;
        }
        let fields: Vec<&str> = if line.contains(',') {
            line.split(',').map(str::trim).collect()
        } else {
            line.split_whitespace().collect()
        };
        let at = |message: String| Error::at_line(name, i + 1, message);
        if fields.iter().any(|f| f.is_empty()) {
            return Err(at("empty coordinate between commas".into()));
        }
        if fields.len() != 3 {
            return Err(at(format!(
                "expected 3 coordinates (x y z), found {}",
                fields.len()
            )));
        }
        let mut c = [0.0; 3];
        for (k, field) in fields.iter().enumerate() {
            c[k] = finite(field, "coordinate").map_err(at)?;
            if c[k].abs() > MAX_COORDINATE {
                return Err(at(format!(
                    "coordinate {field} is larger in magnitude than {MAX_COORDINATE:e}"
                )));
            }
        }
        points.push(Point3::from(c));
    }
    Ok(points)
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
    let name = path.display().to_string();
    let mut bytes = Vec::new();
    if name == "-" {
        std::io::stdin()
            .lock()
            .read_to_end(&mut bytes)
            .map_err(|e| Error::io("standard input", e))?;
    } else {
        bytes = std::fs::read(path).map_err(|e| Error::io(&name, e))?;
    }
    let text = String::from_utf8(bytes).map_err(|e| {
        let line = 1 + e.as_bytes()[..e.utf8_error().valid_up_to()]
            .iter()
            .filter(|&&b| b == b'\n')
            .count();
        let shown = if name == "-" { "standard input" } else { &name };
        Error::at_line(shown, line, "the text is not UTF-8")
    })?;
    parse_points(&text, if name == "-" { "standard input" } else { &name })
}
