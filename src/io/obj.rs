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
use crate::mesh::{Loop, Mesh, Validation};
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
    read_in_pieces(text, path, PIECE)?.into_mesh(path, validation)
}

/// The vertices and faces of an OBJ file, read but not yet made into a mesh, with the lines
/// that define them (for the mesh's errors): the text need not be held while the mesh is
/// built.
pub(crate) struct Read {
    vertices: Vec<Point3>,
    vertex_lines: Vec<usize>,
    faces: Vec<Loop>,
    face_lines: Vec<usize>,
}

impl Read {
    /// The mesh of what was read, its errors located at lines of the file `path`.
    pub(crate) fn into_mesh(self, path: &str, validation: Validation) -> Result<Mesh> {
        let Read {
            vertices,
            vertex_lines,
            faces,
            face_lines,
        } = self;
        Mesh::from_loops_with(vertices, faces, validation)
            .map_err(|e| located_at_lines(path, e, &vertex_lines, &face_lines))
    }
}

/// Reads the text of an OBJ file (see [`parse`]) without building the mesh.
pub(crate) fn read(text: &str, path: &str) -> Result<Read> {
    read_in_pieces(text, path, PIECE)
}

/// [`read`], reading the text in pieces of about `piece` bytes.
fn read_in_pieces(text: &str, path: &str, piece: usize) -> Result<Read> {
    use rayon::prelude::*;
    // Two passes over pieces of the text that start at statements, each piece in parallel:
    // the first counts the lines and the elements each defines, the second parses it knowing
    // how many of each are defined before it, straight into its place in the output. Every
    // statement is read as a sequential reader reads it, and the first error of the first
    // piece with one is the file's first error.
    let pieces = pieces(strip_bom(text), piece);
    let counts: Vec<Counts> = pieces.par_iter().map(|p| Counts::of(p)).collect();
    let total = counts.iter().fold(Counts::default(), |s, c| s.plus(c));
    let mut vertices = vec![Point3::origin(); total.vertices];
    let mut vertex_lines = vec![0; total.vertices];
    let mut faces = vec![Loop::new(); total.faces];
    let mut face_lines = vec![0; total.faces];
    let mut jobs = Vec::with_capacity(pieces.len());
    let (mut v, mut vl, mut f, mut fl) = (
        &mut vertices[..],
        &mut vertex_lines[..],
        &mut faces[..],
        &mut face_lines[..],
    );
    let mut before = Counts::default();
    for (text, count) in pieces.iter().zip(&counts) {
        let (v_here, v_rest) = v.split_at_mut(count.vertices);
        let (vl_here, vl_rest) = vl.split_at_mut(count.vertices);
        let (f_here, f_rest) = f.split_at_mut(count.faces);
        let (fl_here, fl_rest) = fl.split_at_mut(count.faces);
        jobs.push((
            *text,
            before.clone(),
            Out {
                vertices: v_here,
                vertex_lines: vl_here,
                faces: f_here,
                face_lines: fl_here,
            },
        ));
        (v, vl, f, fl) = (v_rest, vl_rest, f_rest, fl_rest);
        before = before.plus(count);
    }
    let results: Vec<Result<()>> = if jobs.len() > 1 {
        jobs.into_par_iter()
            .map(|(text, before, out)| parse_piece(text, path, &before, out))
            .collect()
    } else {
        jobs.into_iter()
            .map(|(text, before, out)| parse_piece(text, path, &before, out))
            .collect()
    };
    results.into_iter().collect::<Result<()>>()?;
    Ok(Read {
        vertices,
        vertex_lines,
        faces,
        face_lines,
    })
}

/// Texts of at least this many bytes are read in pieces of about this size, in parallel.
const PIECE: usize = 1 << 20;

/// The text cut into pieces of about `size` bytes, each starting at a statement: after a
/// line whose content (without its comment) is not blank and does not end with `\`, which
/// therefore ends its statement whatever came before.
fn pieces(text: &str, size: usize) -> Vec<&str> {
    let mut pieces = Vec::with_capacity(text.len() / size + 1);
    let mut start = 0;
    while text.len() - start > size {
        let mut cut = start + size;
        let found = loop {
            let Some(newline) = text.as_bytes()[cut..].iter().position(|&b| b == b'\n') else {
                break None;
            };
            let end = cut + newline;
            let line_start = text[..end].rfind('\n').map_or(0, |i| i + 1);
            let content = strip_comment(&text[line_start..end]).trim_end();
            if !content.is_empty() && !content.ends_with('\\') {
                break Some(end + 1);
            }
            cut = end + 1;
        };
        match found {
            Some(cut) => {
                pieces.push(&text[start..cut]);
                start = cut;
            }
            None => break,
        }
    }
    pieces.push(&text[start..]);
    pieces
}

/// How many lines, vertices, texture coordinates, normals and faces a piece of text has.
#[derive(Clone, Default)]
struct Counts {
    lines: usize,
    vertices: usize,
    texture_coordinates: usize,
    normals: usize,
    faces: usize,
}

impl Counts {
    /// The counts of a piece: its statements' keywords (what [`parse_piece`] reads them as).
    fn of(text: &str) -> Counts {
        let mut c = Counts {
            lines: text.bytes().filter(|&b| b == b'\n').count()
                + usize::from(!text.is_empty() && !text.ends_with('\n')),
            ..Counts::default()
        };
        for (_, statement) in statements(text) {
            match statement.split_whitespace().next() {
                Some("v") => c.vertices += 1,
                Some("vt") => c.texture_coordinates += 1,
                Some("vn") => c.normals += 1,
                Some("f") => c.faces += 1,
                _ => {}
            }
        }
        c
    }

    fn plus(&self, other: &Counts) -> Counts {
        Counts {
            lines: self.lines + other.lines,
            vertices: self.vertices + other.vertices,
            texture_coordinates: self.texture_coordinates + other.texture_coordinates,
            normals: self.normals + other.normals,
            faces: self.faces + other.faces,
        }
    }
}

/// Where a piece's vertices and faces go, with their 1-based lines.
struct Out<'a> {
    vertices: &'a mut [Point3],
    vertex_lines: &'a mut [usize],
    faces: &'a mut [Loop],
    face_lines: &'a mut [usize],
}

/// Parses a piece of the text, with `before` the counts of the text before it, into `out`
/// (sized by [`Counts::of`]); the error is the piece's first.
fn parse_piece(text: &str, path: &str, before: &Counts, out: Out<'_>) -> Result<()> {
    let (mut vertices, mut faces) = (0, 0);
    let (mut texture_coordinates, mut normals) = (before.texture_coordinates, before.normals);
    for (line, statement) in statements(text) {
        let line = before.lines + line;
        let mut tokens = statement.split_whitespace();
        let Some(keyword) = tokens.next() else {
            continue;
        };
        let at_line = |message: String| FileError::at_line(path, line, message);
        match keyword {
            "v" => {
                out.vertices[vertices] = vertex(tokens).map_err(at_line)?;
                out.vertex_lines[vertices] = line;
                vertices += 1;
            }
            "vt" => texture_coordinates += 1,
            "vn" => normals += 1,
            "f" => {
                let defined = Defined {
                    vertices: before.vertices + vertices,
                    texture_coordinates,
                    normals,
                };
                out.faces[faces] = face(tokens, &defined).map_err(at_line)?;
                out.face_lines[faces] = line;
                faces += 1;
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
    Ok(())
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
fn face<'a>(tokens: impl Iterator<Item = &'a str>, defined: &Defined) -> Result<Loop, String> {
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::random::SplitMix64;

    /// A random OBJ text over a grid of points: faces with absolute and relative indices,
    /// texture coordinate and normal references, comments, blank lines, CRLF endings, lines
    /// continued with `\` (also after a line ending in two of them), and now and then an
    /// error (an index out of range, a malformed number, an unknown keyword).
    fn random_obj(rng: &mut SplitMix64, errors: bool) -> String {
        let mut text = String::new();
        let (mut v, mut vt, mut vn) = (0i64, 0i64, 0i64);
        for _ in 0..(20 + rng.below(200)) {
            let end = if rng.below(8) == 0 { "\r\n" } else { "\n" };
            match rng.below(12) {
                0..=3 => {
                    let c = [0; 3].map(|_| rng.below(4) as f64 - 1.5);
                    text += &format!("v {} {} {}{end}", c[0], c[1], c[2]);
                    v += 1;
                }
                4 => {
                    text += &format!("vt 0.5 0.25{end}");
                    vt += 1;
                }
                5 => {
                    text += &format!("vn 0 0 1{end}");
                    vn += 1;
                }
                6..=8 if v >= 3 => {
                    text += "f";
                    for _ in 0..3 + rng.below(2) {
                        let i = 1 + rng.below(v as usize) as i64;
                        let i = if rng.below(2) == 0 { i } else { i - v - 1 };
                        text += &format!(" {i}");
                        if vt > 0 && rng.below(3) == 0 {
                            text += &format!("/{}", 1 + rng.below(vt as usize));
                        } else if vn > 0 && rng.below(3) == 0 {
                            text += &format!("//-{}", 1 + rng.below(vn as usize));
                        }
                        if rng.below(10) == 0 {
                            text += " \\\n ";
                        }
                    }
                    text += end;
                }
                9 => text += &format!("# a comment \\{end}"),
                10 => {
                    // Two backslashes, then a blank line: the statement goes on after it.
                    text += &format!("v 1 2 \\\\{end}{end}0{end}");
                    v += 1;
                }
                _ => text += end,
            }
            if errors && rng.below(150) == 0 {
                text += ["f 1 2 99999\n", "v 1 x 0\n", "q\n", "f 1 2 -99999\n"][rng.below(4)];
            }
        }
        text
    }

    /// The mesh of the text read in pieces of about `piece` bytes.
    fn parse_in_pieces(
        text: &str,
        path: &str,
        validation: Validation,
        piece: usize,
    ) -> Result<Mesh> {
        read_in_pieces(text, path, piece)?.into_mesh(path, validation)
    }

    #[test]
    fn pieces_read_as_the_whole_text() {
        let mut rng = SplitMix64(7);
        for case in 0..300 {
            let text = random_obj(&mut rng, case % 3 == 0);
            let whole = parse_in_pieces(&text, "t.obj", Validation::Repair, usize::MAX);
            for size in [1, 2, 5, 17, 64, 301] {
                let pieces = pieces(&text, size);
                assert_eq!(pieces.concat(), text);
                let cut = parse_in_pieces(&text, "t.obj", Validation::Repair, size);
                match (&whole, &cut) {
                    (Ok(a), Ok(b)) => assert_eq!(a, b, "case {case}, size {size}"),
                    (Err(a), Err(b)) => {
                        assert_eq!(a.to_string(), b.to_string(), "case {case}, size {size}")
                    }
                    _ => panic!("case {case}, size {size}: {whole:?} against {cut:?}"),
                }
            }
        }
    }

    #[test]
    fn an_error_late_in_a_large_file_names_its_line() {
        let mut text = "v 0 0 0\nv 1 0 0\nv 0 1 0\n".to_owned();
        text += &"f 1 2 3\n".repeat(300_000);
        text += "f 1 2 -4\nf 1 2 x\n";
        let err = parse(&text, "big.obj").unwrap_err();
        assert_eq!(
            err.to_string(),
            "big.obj:300004: vertex index -4 is out of range: 3 vertices are defined before \
             this line"
        );
        assert!(pieces(&text, PIECE).len() > 1);
    }
}
