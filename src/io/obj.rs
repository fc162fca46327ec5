//! Wavefront OBJ: the polygonal subset.
//!
//! Written by hand rather than with `tobj`, whose errors carry no line numbers and which
//! parses coordinates as `f32` by default.
//!
//! Read: `v x y z [w]` (w, if present, must be exactly 1: kepler does not rescale
//! coordinates), and `f` with corners `v`, `v/vt`, `v/vt/vn` or `v//vn`, with indices counting
//! from 1 or, when negative, back from the last element defined before the line. Faces are
//! kept as the polygons they are, not triangulated. `vt` and `vn` lines are accepted and only
//! counted, so that the indices referring to them can be checked; `o`, `g`, `s`, `usemtl` and
//! `mtllib` are accepted and ignored, as are comments (`#` to the end of the line) and blank
//! lines. A line ending with `\` continues on the next one.
//!
//! Everything else is an error naming the line: elements kepler cannot represent (points
//! `p`, lines `l`, free-form curves and surfaces), unknown keywords, malformed or non-finite
//! numbers, and indices that are 0, not integers, or refer to elements not defined before
//! their line.
//!
//! ```
//! let square = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n";
//! let mesh = kepler::io::obj::parse(square, "square.obj").unwrap();
//! assert_eq!(mesh.faces().len(), 1);
//! assert_eq!(mesh.face_points(0).count(), 4);
//! ```

use super::{FileError, Result};
use super::{finite, located_at_lines, quoted, strip_bom, strip_comment};
use crate::geometry::Point3;
use crate::mesh::{Mesh, Validation};
use std::borrow::Cow;

/// Parses the text of an OBJ file; `path` names the file in error messages.
///
/// ```
/// use kepler::io::obj;
/// let text = "\
///     v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nvt 0 0\nvt 1 0\nvt 0 1\nvn 0 -1 0\n\
///     f -4 -2 -3\nf 1/1/1 2/2/1 4/3/1\nf 2//1 3//1 4//1\nf 1/1 4/2 3/3\n";
/// let tet = obj::parse(text, "tet.obj").unwrap();
/// assert!(tet.is_solid());
///
/// let err = obj::parse("v 0 0 0\nv 1 nan 0\n", "bad.obj").unwrap_err();
/// assert_eq!(err.to_string(), "bad.obj:2: y coordinate 'nan' is not a finite number");
/// ```
pub fn parse(text: &str, path: &str) -> Result<Mesh> {
    parse_with(text, path, Validation::Repair)
}

/// [`parse`] with the given treatment of degenerate faces and polygons that are not exactly
/// planar.
///
/// ```
/// use kepler::{io::obj, mesh::Validation};
/// let text = "v 0 0 0\nv 1 0 0\nv 1 1 0.001\nv 0 1 0\nf 1 2 3 4\n";
/// assert_eq!(obj::parse(text, "q.obj").unwrap().split_polygons(), 1);
/// let err = obj::parse_with(text, "q.obj", Validation::Strict).unwrap_err();
/// assert!(err.to_string().starts_with("q.obj:5: face 1 is not planar"));
/// ```
pub fn parse_with(text: &str, path: &str, validation: Validation) -> Result<Mesh> {
    let mut vertices = Vec::new();
    let mut vertex_lines = Vec::new();
    let mut faces = Vec::new();
    let mut face_lines = Vec::new();
    let (mut texture_coordinates, mut normals) = (0, 0);
    for (line, statement) in statements(strip_bom(text)) {
        let mut tokens = statement.split_whitespace();
        let Some(keyword) = tokens.next() else {
            continue;
        };
        let at_line = |message: String| FileError::at_line(path, line, message);
        match keyword {
            "v" => {
                vertices.push(vertex(tokens).map_err(at_line)?);
                vertex_lines.push(line);
            }
            "vt" => texture_coordinates += 1,
            "vn" => normals += 1,
            "f" => {
                let defined = Defined {
                    vertices: vertices.len(),
                    texture_coordinates,
                    normals,
                };
                faces.push(face(tokens, &defined).map_err(at_line)?);
                face_lines.push(line);
            }
            "o" | "g" | "s" | "usemtl" | "mtllib" => {}
            "p" | "l" => {
                let kind = if keyword == "p" { "point" } else { "line" };
                return Err(at_line(format!(
                    "'{keyword}' ({kind}) elements cannot be represented: \
                     only polygon faces ('f') are read"
                )));
            }
            "vp" | "cstype" | "deg" | "bmat" | "step" | "curv" | "curv2" | "surf" | "parm"
            | "trim" | "hole" | "scrv" | "sp" | "end" | "con" => {
                return Err(at_line(format!(
                    "free-form curve and surface statement '{keyword}' is not supported: \
                     only polygon faces ('f') are read"
                )));
            }
            _ => return Err(at_line(format!("unknown keyword {}", quoted(keyword)))),
        }
    }
    Mesh::from_polygons_with(vertices, faces, validation)
        .map_err(|e| located_at_lines(path, e, &vertex_lines, &face_lines))
}

/// How many elements of each kind are defined before a face.
struct Defined {
    vertices: usize,
    texture_coordinates: usize,
    normals: usize,
}

/// The statements of the text with their first 1-based line, comments removed and lines
/// ending with `\` joined to the next.
fn statements(text: &str) -> impl Iterator<Item = (usize, Cow<'_, str>)> {
    let mut lines = text.lines().enumerate();
    std::iter::from_fn(move || {
        let (i, first) = lines.next()?;
        let mut statement = Cow::Borrowed(strip_comment(first));
        while let Some(head) = statement.trim_end().strip_suffix('\\') {
            let mut joined = head.to_owned();
            match lines.next() {
                Some((_, next)) => {
                    joined.push(' ');
                    joined.push_str(strip_comment(next));
                    statement = Cow::Owned(joined);
                }
                None => {
                    statement = Cow::Owned(joined);
                    break;
                }
            }
        }
        Some((i + 1, statement))
    })
}

/// The point of a `v` statement: `x y z`, or `x y z 1`.
fn vertex<'a>(tokens: impl Iterator<Item = &'a str>) -> Result<Point3, String> {
    // The first four tokens and the count, without collecting a line into a vector.
    let mut first = [""; 4];
    let mut count = 0;
    for token in tokens {
        if let Some(slot) = first.get_mut(count) {
            *slot = token;
        }
        count += 1;
    }
    let [x, y, z, w] = first;
    let w = match count {
        3 => None,
        4 => Some(w),
        n if n < 3 => {
            return Err(format!(
                "missing coordinate: expected x y z, found {n} values"
            ));
        }
        n => {
            return Err(format!(
                "too many values: expected x y z and optionally w = 1, found {n} values \
                 (vertex colours are not supported)"
            ));
        }
    };
    let p = Point3::new(
        finite(x, "x coordinate")?,
        finite(y, "y coordinate")?,
        finite(z, "z coordinate")?,
    );
    if let Some(w) = w
        && finite(w, "w coordinate")? != 1.0
    {
        return Err(format!(
            "w coordinate {} is not 1: kepler does not rescale coordinates by w",
            quoted(w)
        ));
    }
    Ok(p)
}

/// The vertex indices (0-based) of an `f` statement, checking the texture coordinate and
/// normal indices too.
fn face<'a>(tokens: impl Iterator<Item = &'a str>, defined: &Defined) -> Result<Vec<u32>, String> {
    tokens.map(|corner| face_corner(corner, defined)).collect()
}

/// One corner of a face, `v`, `v/vt`, `v/vt/vn` or `v//vn`: the 0-based vertex index.
fn face_corner(corner: &str, defined: &Defined) -> Result<u32, String> {
    let mut parts = corner.split('/');
    let (v, vt, vn) = match (parts.next(), parts.next(), parts.next(), parts.next()) {
        (Some(v), None, _, _) => (v, None, None),
        (Some(v), Some(vt), None, _) => (v, Some(vt), None),
        (Some(v), Some(""), Some(vn), None) => (v, None, Some(vn)),
        (Some(v), Some(vt), Some(vn), None) => (v, Some(vt), Some(vn)),
        _ => return Err(malformed_corner(corner)),
    };
    if v.is_empty() || vt == Some("") || vn == Some("") {
        return Err(malformed_corner(corner));
    }
    let i = index(v, "vertex", "vertices", defined.vertices)?;
    if let Some(vt) = vt {
        index(
            vt,
            "texture coordinate",
            "texture coordinates",
            defined.texture_coordinates,
        )?;
    }
    if let Some(vn) = vn {
        index(vn, "normal", "normals", defined.normals)?;
    }
    u32::try_from(i)
        .map_err(|_| format!("vertex index {v} is beyond the 2^32 vertices kepler supports"))
}

/// The message for a face corner that is not `v`, `v/vt`, `v/vt/vn` or `v//vn`.
fn malformed_corner(corner: &str) -> String {
    format!(
        "malformed face corner {}: expected v, v/vt, v/vt/vn or v//vn",
        quoted(corner)
    )
}

/// Resolves a 1-based or negative (relative) OBJ index to a 0-based one, given how many
/// elements of its kind are defined before the line.
fn index(token: &str, kind: &str, kinds: &str, defined: usize) -> Result<usize, String> {
    let i: i64 = token
        .parse()
        .map_err(|_| format!("{kind} index {} is not an integer", quoted(token)))?;
    if i == 0 {
        return Err(format!(
            "{kind} index 0 is invalid: OBJ indices count from 1 (or back from -1)"
        ));
    }
    let resolved = if i > 0 {
        usize::try_from(i - 1).ok().filter(|&r| r < defined)
    } else {
        usize::try_from(i.unsigned_abs())
            .ok()
            .and_then(|back| defined.checked_sub(back))
    };
    resolved.ok_or_else(|| {
        format!("{kind} index {i} is out of range: {defined} {kinds} are defined before this line")
    })
}
