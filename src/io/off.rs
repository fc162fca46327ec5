//! Object File Format (OFF), as written by Geomview, MeshLab and CGAL.
//!
//! Written by hand (no crate reads OFF with line numbers in its errors and `f64` coordinates).
//!
//! Layout: an optional header `OFF`, the counts `vertices faces edges` (on the header's line or
//! the next), then one vertex per line, then one face per line: `n i1 .. in` with 0-based
//! vertex indices. The edge count is not checked (many writers put 0). `#` starts a comment
//! that runs to the end of the line; blank lines may appear anywhere. A face may end with a
//! colour (1 colour-map index, or 3 or 4 components); colour is not geometry, so it is
//! checked to be numbers and otherwise ignored.
//!
//! The header variants `COFF` (each vertex followed by a colour of 3 or 4 numbers), `NOFF`
//! (followed by a normal of 3 numbers) and `CNOFF` (a normal, then a colour) are read the
//! same way, their extra values checked to be numbers and ignored. Other variants (`STOFF`,
//! `4OFF`, `nOFF`, binary OFF) are errors. Fewer or more records than the counts announce
//! are errors at the line where the difference shows.
//!
//! ```
//! let text = "OFF 3 1 3\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2 255 0 0\n";
//! let mesh = kepler::io::off::parse(text, "tri.off").unwrap();
//! assert_eq!(mesh.faces().len(), 1);
//! ```

use super::{FileError, Result};
use super::{finite, last_line, located_at_lines, quoted, strip_bom, strip_comment};
use crate::geometry::Point3;
use crate::mesh::{Loop, Mesh, Validation};

/// Parses the text of an OFF file; `path` names the file in error messages.
///
/// ```
/// use kepler::io::off;
/// let text = "# a tetrahedron\nOFF\n4 4 6\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n\
///             3 0 2 1\n3 0 1 3\n3 1 2 3\n3 0 3 2\n";
/// let tet = off::parse(text, "tet.off").unwrap();
/// assert!(tet.is_solid());
///
/// let short = text.replace("3 0 3 2\n", "");
/// let err = off::parse(&short, "tet.off").unwrap_err();
/// assert_eq!(
///     err.to_string(),
///     "tet.off:10: unexpected end of file: line 3 announces 4 faces, found 3"
/// );
/// ```
pub fn parse(text: &str, path: &str) -> Result<Mesh> {
    parse_with(text, path, Validation::Repair)
}

/// [`parse`] with the given treatment of degenerate faces and polygons that are not exactly
/// planar.
///
/// ```
/// use kepler::{io::off, mesh::Validation};
/// let text = "OFF\n4 2 0\n0 0 0\n1 0 0\n0 1 0\n2 0 0\n3 0 1 2\n3 0 1 3\n";
/// assert_eq!(off::parse(text, "t.off").unwrap().degenerate_faces(), 1);
/// let err = off::parse_with(text, "t.off", Validation::Strict).unwrap_err();
/// assert_eq!(err.to_string(), "t.off:8: face 2 has zero area");
/// ```
pub fn parse_with(text: &str, path: &str, validation: Validation) -> Result<Mesh> {
    let text = strip_bom(text);
    let mut records = text
        .lines()
        .enumerate()
        .map(|(i, line)| {
            (
                i + 1,
                strip_comment(line).split_whitespace().collect::<Vec<_>>(),
            )
        })
        .filter(|(_, tokens)| !tokens.is_empty());
    let end = |message: String| FileError::at_line(path, last_line(text), message);

    let Some((header_line, header)) = records.next() else {
        return Err(end(
            "empty file: expected the header 'OFF' or the counts".into()
        ));
    };
    let at_header = |message: String| FileError::at_line(path, header_line, message);
    let (variant, counts_on_header) = match header.split_first() {
        Some((keyword, rest)) if keyword.parse::<f64>().is_err() => {
            (Variant::of(keyword).map_err(at_header)?, rest.to_vec())
        }
        _ => (Variant::Plain, header),
    };
    let (counts_line, counts) = if counts_on_header.is_empty() {
        records
            .next()
            .ok_or_else(|| end("unexpected end of file: expected the counts".into()))?
    } else {
        (header_line, counts_on_header)
    };
    let (nv, nf) = parse_counts(&counts).map_err(|m| FileError::at_line(path, counts_line, m))?;

    let mut vertices = Vec::new();
    let mut vertex_lines = Vec::new();
    for _ in 0..nv {
        let Some((line, tokens)) = records.next() else {
            return Err(end(format!(
                "unexpected end of file: line {counts_line} announces {nv} vertices, found {}",
                vertices.len()
            )));
        };
        let p = variant.vertex(&tokens).map_err(|m| {
            let k = vertices.len() + 1;
            FileError::at_line(
                path,
                line,
                format!("{m} (vertex {k} of the {nv} announced on line {counts_line})"),
            )
        })?;
        vertices.push(p);
        vertex_lines.push(line);
    }
    let mut faces = Vec::new();
    let mut face_lines = Vec::new();
    for _ in 0..nf {
        let Some((line, tokens)) = records.next() else {
            return Err(end(format!(
                "unexpected end of file: line {counts_line} announces {nf} faces, found {}",
                faces.len()
            )));
        };
        faces.push(face(&tokens, nv).map_err(|m| FileError::at_line(path, line, m))?);
        face_lines.push(line);
    }
    if let Some((line, _)) = records.next() {
        return Err(FileError::at_line(
            path,
            line,
            format!(
                "unexpected data after the {nv} vertices and {nf} faces announced on line {counts_line}"
            ),
        ));
    }
    Mesh::from_loops_with(vertices, faces, validation)
        .map_err(|e| located_at_lines(path, e, &vertex_lines, &face_lines))
}

/// The header variants read: which values follow a vertex's coordinates.
#[derive(Clone, Copy)]
enum Variant {
    /// `OFF`: nothing.
    Plain,
    /// `COFF`: a colour of 3 or 4 numbers.
    Colour,
    /// `NOFF`: a normal of 3 numbers.
    Normal,
    /// `CNOFF`: a normal, then a colour.
    NormalColour,
}

impl Variant {
    fn of(keyword: &str) -> Result<Variant, String> {
        match keyword {
            "OFF" => Ok(Variant::Plain),
            "COFF" => Ok(Variant::Colour),
            "NOFF" => Ok(Variant::Normal),
            "CNOFF" => Ok(Variant::NormalColour),
            k if k.ends_with("OFF") => Err(format!(
                "unsupported OFF variant {}: only OFF, COFF, NOFF and CNOFF are read",
                quoted(k)
            )),
            k => Err(format!(
                "expected the header 'OFF' or the counts 'vertices faces edges', found {}",
                quoted(k)
            )),
        }
    }

    /// The point of a vertex line, checking the extra values of the variant.
    fn vertex(self, tokens: &[&str]) -> Result<Point3, String> {
        let (expected, extras): (&str, &[usize]) = match self {
            Variant::Plain => ("3 coordinates x y z", &[0]),
            Variant::Colour => ("3 coordinates x y z and a colour of 3 or 4 values", &[3, 4]),
            Variant::Normal => ("3 coordinates x y z and a normal of 3 values", &[3]),
            Variant::NormalColour => (
                "3 coordinates x y z, a normal of 3 values and a colour of 3 or 4 values",
                &[6, 7],
            ),
        };
        let [x, y, z, rest @ ..] = tokens else {
            return Err(format!(
                "expected {expected}, found {} values",
                tokens.len()
            ));
        };
        if !extras.contains(&rest.len()) {
            return Err(format!(
                "expected {expected}, found {} values",
                tokens.len()
            ));
        }
        let p = Point3::new(
            finite(x, "x coordinate")?,
            finite(y, "y coordinate")?,
            finite(z, "z coordinate")?,
        );
        for value in rest {
            finite(value, "normal or colour value")?;
        }
        Ok(p)
    }
}

/// The numbers of vertices and faces from the counts `vertices faces edges`.
fn parse_counts(tokens: &[&str]) -> Result<(usize, usize), String> {
    if tokens.first() == Some(&"BINARY") {
        return Err("binary OFF is not supported".into());
    }
    let count = |t: &str| t.parse::<usize>().ok();
    match *tokens {
        [v, f, e] => match (count(v), count(f), count(e)) {
            (Some(v), Some(f), Some(_)) => Ok((v, f)),
            _ => Err(format!(
                "the counts {} are not 3 non-negative integers",
                quoted(&tokens.join(" "))
            )),
        },
        _ => Err(format!(
            "expected the counts 'vertices faces edges', found {}",
            quoted(&tokens.join(" "))
        )),
    }
}

/// The 0-based vertex indices of a face line `n i1 .. in [colour]`, given the vertex count.
fn face(tokens: &[&str], vertex_count: usize) -> Result<Loop, String> {
    let Some((n, rest)) = tokens.split_first() else {
        return Err("expected a face".into());
    };
    let n: usize = n.parse().map_err(|_| {
        format!(
            "the face's vertex count {} is not a non-negative integer",
            quoted(n)
        )
    })?;
    let Some((indices, colour)) = rest.split_at_checked(n) else {
        return Err(format!(
            "the face announces {n} vertices but lists {}",
            rest.len()
        ));
    };
    if ![0, 1, 3, 4].contains(&colour.len()) {
        return Err(format!(
            "expected a colour of 1, 3 or 4 values (or none) after the {n} vertex indices, found {} values",
            colour.len()
        ));
    }
    for value in colour {
        finite(value, "colour value")?;
    }
    indices
        .iter()
        .map(|i| {
            let k: usize = i
                .parse()
                .map_err(|_| {
                    format!("vertex index {} is not a non-negative integer", quoted(i))
                })?;
            if k >= vertex_count {
                return Err(format!(
                    "vertex index {k} is out of range: the file has {vertex_count} vertices, numbered from 0"
                ));
            }
            u32::try_from(k)
                .map_err(|_| format!("vertex index {k} is beyond the 2^32 vertices kepler supports"))
        })
        .collect()
}
