//! STL, ASCII and binary: one triangle per facet.
//!
//! Written by hand rather than with `stl_io`, which reads ASCII STL coordinates into `f32`
//! (rounding them); here ASCII coordinates are parsed with Rust's correctly rounded
//! `str::parse::<f64>` and binary `f32` coordinates are widened exactly to `f64`.
//!
//! A file is binary when its length is 84 + 50 × n bytes for the triangle count n stored in
//! bytes 80..84 (little-endian), whatever its 80-byte header says (binary headers often begin
//! with `solid` too). Otherwise it must be ASCII: text (no control characters other than
//! whitespace) beginning with `solid`. A file that is neither, such as a truncated binary STL,
//! is an error saying why it is neither.
//!
//! ASCII grammar, keywords in any letter case, tokens separated by any whitespace:
//! `solid [name]`, then any number of facets `facet normal nx ny nz` / `outer loop` / three
//! `vertex x y z` / `endloop` / `endfacet`, then `endsolid [name]` and nothing after it.
//! Binary records hold 12 `f32` (normal, three vertices) and a 16-bit attribute word, which is
//! ignored (some writers keep a colour there; colour is not geometry).
//!
//! The facet normals are checked to be 3 finite numbers but not used: a facet's orientation
//! is given by the order of its vertices (counter-clockwise seen from outside), as everywhere
//! in kepler; normals in STL files are often zero, unnormalised or inconsistent with that
//! order. Vertices shared by facets are merged by [`Mesh::from_polygons`], which merges
//! vertices with equal coordinates. Errors name the line, or for binary files the 1-based
//! triangle (`part.stl:triangle 7: ...`).
//!
//! ```
//! let text = "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\n\
//!             vertex 0 1 0\nendloop\nendfacet\nendsolid t\n";
//! let mesh = kepler::io::stl::parse(text.as_bytes(), "t.stl").unwrap();
//! assert_eq!(mesh.triangles().len(), 1);
//! ```

use super::{FileError, Result};
use super::{finite, last_line, located, located_at_lines, quoted, strip_bom};
use crate::geometry::Point3;
use crate::mesh::{Loop, Mesh, Validation};
use std::iter::Peekable;

/// Parses the bytes of an STL file, ASCII or binary; `path` names the file in error messages.
///
/// ```
/// use kepler::io::stl;
/// // A binary STL with one triangle: 80-byte header, count, then normal, vertices, attribute.
/// let mut bytes = vec![0u8; 80];
/// bytes.extend(1u32.to_le_bytes());
/// for x in [0.0f32, 0.0, 1.0, 0.0, 0.0, 0.0, 0.1, 0.0, 0.0, 0.0, 0.1, 0.0] {
///     bytes.extend(x.to_le_bytes());
/// }
/// bytes.extend([0, 0]);
/// let mesh = stl::parse(&bytes, "t.stl").unwrap();
/// assert_eq!(mesh.vertices()[1].x, f64::from(0.1f32));
///
/// let err = stl::parse(&bytes[..100], "t.stl").unwrap_err();
/// assert!(err.to_string().starts_with("t.stl:header: neither a binary STL"));
/// ```
pub fn parse(bytes: &[u8], path: &str) -> Result<Mesh> {
    parse_with(bytes, path, Validation::Repair)
}

/// [`parse`] with the given treatment of degenerate faces.
///
/// ```
/// use kepler::{io::stl, mesh::Validation};
/// let facet = |a: &str| format!("facet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\n\
///                                vertex {a}\nendloop\nendfacet\n");
/// let text = format!("solid t\n{}{}endsolid t\n", facet("0 1 0"), facet("2 0 0"));
/// assert_eq!(stl::parse(text.as_bytes(), "t.stl").unwrap().degenerate_faces(), 1);
/// let err = stl::parse_with(text.as_bytes(), "t.stl", Validation::Strict).unwrap_err();
/// assert_eq!(err.to_string(), "t.stl:9: face 2 has zero area");
/// ```
pub fn parse_with(bytes: &[u8], path: &str, validation: Validation) -> Result<Mesh> {
    if let Some(records) = binary_records(bytes) {
        return binary(records, path, validation);
    }
    if looks_like_ascii(bytes) {
        return ascii(&String::from_utf8_lossy(bytes), path, validation);
    }
    let binary_reason = match declared_triangles(bytes) {
        None => format!(
            "it has {} bytes, fewer than the 84 of a binary header",
            bytes.len()
        ),
        Some(n) => format!(
            "the triangle count in its header, {n}, needs {} bytes, but it has {}",
            84 + 50 * u64::from(n),
            bytes.len()
        ),
    };
    let ascii_reason = if starts_with_solid(bytes) {
        "it contains binary data"
    } else {
        "it does not start with 'solid'"
    };
    Err(FileError::Input {
        path: path.to_owned(),
        at: "header".to_owned(),
        message: format!(
            "neither a binary STL ({binary_reason}) nor an ASCII STL ({ascii_reason})"
        ),
    })
}

/// The triangle count stored in bytes 80..84, if the file is that long.
fn declared_triangles(bytes: &[u8]) -> Option<u32> {
    let (&[.., a, b, c, d], _) = bytes.split_first_chunk::<84>()?;
    Some(u32::from_le_bytes([a, b, c, d]))
}

/// The 50-byte triangle records, if the file's length is 84 + 50 × the declared count.
fn binary_records(bytes: &[u8]) -> Option<&[[u8; 50]]> {
    let n = declared_triangles(bytes)?;
    let (records, rest) = bytes.get(84..)?.as_chunks::<50>();
    (rest.is_empty() && records.len() as u64 == u64::from(n)).then_some(records)
}

fn starts_with_solid(bytes: &[u8]) -> bool {
    let text = bytes.strip_prefix("\u{feff}".as_bytes()).unwrap_or(bytes);
    text.trim_ascii_start()
        .get(..5)
        .is_some_and(|s| s.eq_ignore_ascii_case(b"solid"))
}

/// Whether the file can be ASCII STL: it starts with `solid` and has no control characters
/// other than whitespace.
fn looks_like_ascii(bytes: &[u8]) -> bool {
    starts_with_solid(bytes)
        && !bytes
            .iter()
            .any(|b| b.is_ascii_control() && !b.is_ascii_whitespace())
}

fn binary(records: &[[u8; 50]], path: &str, validation: Validation) -> Result<Mesh> {
    let at_triangle = |t: usize| format!("triangle {}", t + 1);
    let mut vertices = Vec::new();
    let mut faces = Vec::new();
    for (t, record) in records.iter().enumerate() {
        let error = |message: String| FileError::Input {
            path: path.to_owned(),
            at: at_triangle(t),
            message,
        };
        let [nx, ny, nz, ax, ay, az, bx, by, bz, cx, cy, cz] = floats(record);
        if ![nx, ny, nz].iter().all(|c| c.is_finite()) {
            return Err(error(format!(
                "the normal ({nx}, {ny}, {nz}) is not 3 finite numbers"
            )));
        }
        let face = triangle(vertices.len())
            .ok_or_else(|| error("more vertices than the 2^32 kepler supports".into()))?;
        for (k, [x, y, z]) in [[ax, ay, az], [bx, by, bz], [cx, cy, cz]]
            .into_iter()
            .enumerate()
        {
            if ![x, y, z].iter().all(|c| c.is_finite()) {
                return Err(error(format!(
                    "vertex {} ({x}, {y}, {z}) has a coordinate that is not a finite number",
                    k + 1
                )));
            }
            vertices.push(Point3::new(x, y, z));
        }
        faces.push(face);
    }
    Mesh::from_loops_with(vertices, faces, validation).map_err(|e| {
        located(
            path,
            e,
            |v| Some(at_triangle(v / 3)),
            |f| Some(at_triangle(f)),
        )
    })
}

/// The triangle of the three vertices numbered from `first` on, if their indices fit in `u32`.
fn triangle(first: usize) -> Option<Loop> {
    let last = u32::try_from(first.checked_add(2)?).ok()?;
    Some(Loop::from_slice(&[last - 2, last - 1, last]))
}

/// The 12 `f32` of a binary record (normal, three vertices), widened exactly to `f64`.
fn floats(record: &[u8; 50]) -> [f64; 12] {
    let (words, _attribute) = record.as_chunks::<4>();
    let mut out = [0.0; 12];
    for (o, w) in out.iter_mut().zip(words) {
        *o = f64::from(f32::from_le_bytes(*w));
    }
    out
}

fn ascii(text: &str, path: &str, validation: Validation) -> Result<Mesh> {
    let text = strip_bom(text);
    let mut tokens = Tokens {
        iter: text
            .lines()
            .enumerate()
            .flat_map(|(i, line)| line.split_whitespace().map(move |t| (i + 1, t)))
            .peekable(),
        path,
        last_line: last_line(text),
    };
    let solid = tokens.keyword("solid")?;
    tokens.skip_line(solid);
    let mut vertices = Vec::new();
    let mut vertex_lines = Vec::new();
    let mut faces = Vec::new();
    let mut face_lines = Vec::new();
    loop {
        let (line, token) = tokens.next("'facet' or 'endsolid'")?;
        if token.eq_ignore_ascii_case("endsolid") {
            tokens.skip_line(line);
            break;
        }
        if !token.eq_ignore_ascii_case("facet") {
            return Err(FileError::at_line(
                path,
                line,
                format!("expected 'facet' or 'endsolid', found {}", quoted(token)),
            ));
        }
        tokens.keyword("normal")?;
        for what in ["normal x", "normal y", "normal z"] {
            tokens.number(what)?;
        }
        tokens.keyword("outer")?;
        tokens.keyword("loop")?;
        let face = triangle(vertices.len()).ok_or_else(|| {
            FileError::at_line(path, line, "more vertices than the 2^32 kepler supports")
        })?;
        for _ in 0..3 {
            vertex_lines.push(tokens.keyword("vertex")?);
            let x = tokens.number("x coordinate")?;
            let y = tokens.number("y coordinate")?;
            let z = tokens.number("z coordinate")?;
            vertices.push(Point3::new(x, y, z));
        }
        tokens.keyword("endloop")?;
        tokens.keyword("endfacet")?;
        faces.push(face);
        face_lines.push(line);
    }
    if let Some((line, token)) = tokens.iter.next() {
        return Err(FileError::at_line(
            path,
            line,
            format!("unexpected {} after 'endsolid'", quoted(token)),
        ));
    }
    Mesh::from_loops_with(vertices, faces, validation)
        .map_err(|e| located_at_lines(path, e, &vertex_lines, &face_lines))
}

/// The whitespace-separated tokens of an ASCII STL with their 1-based lines.
struct Tokens<'a, I: Iterator<Item = (usize, &'a str)>> {
    iter: Peekable<I>,
    path: &'a str,
    last_line: usize,
}

impl<'a, I: Iterator<Item = (usize, &'a str)>> Tokens<'a, I> {
    /// The next token, or an error at the end of the file saying what was `expected`.
    fn next(&mut self, expected: &str) -> Result<(usize, &'a str)> {
        self.iter.next().ok_or_else(|| {
            FileError::at_line(
                self.path,
                self.last_line,
                format!("unexpected end of file: expected {expected}"),
            )
        })
    }

    /// Consumes the keyword (in any letter case), returning its line.
    fn keyword(&mut self, keyword: &str) -> Result<usize> {
        let (line, token) = self.next(&format!("'{keyword}'"))?;
        if token.eq_ignore_ascii_case(keyword) {
            Ok(line)
        } else {
            Err(FileError::at_line(
                self.path,
                line,
                format!("expected '{keyword}', found {}", quoted(token)),
            ))
        }
    }

    /// Consumes a finite number; `what` names it in errors.
    fn number(&mut self, what: &str) -> Result<f64> {
        let (line, token) = self.next(what)?;
        finite(token, what).map_err(|m| FileError::at_line(self.path, line, m))
    }

    /// Skips the rest of the tokens on `line` (the name after `solid` or `endsolid`).
    fn skip_line(&mut self, line: usize) {
        while self.iter.next_if(|&(l, _)| l == line).is_some() {}
    }
}
