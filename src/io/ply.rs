//! PLY (the Stanford polygon file format): ASCII, binary little-endian and binary big-endian,
//! as scanners and the Stanford repository write them.
//!
//! Read: the `vertex` element's `x`, `y` and `z` (any scalar type; `float` is widened exactly
//! to `f64`, ASCII numbers are parsed correctly rounded to the declared type), and the `face`
//! element's vertex list, `vertex_indices` or `vertex_index` (any integer types), 0-based.
//! Every other property (normals, colours, confidence, texture coordinates) and every other
//! element (`edge`, `material`, ...) is read past and ignored. Errors name the file and the
//! 1-based line of an ASCII file, or the element (`vertex 12`, `face 7`) of a binary one.
//!
//! The header and the elements are parsed by `ply-rs-bw`, the maintained fork of `ply-rs`
//! (the original's last release, 0.1.3, dates from 2020 and depends on a `linked-hash-map`
//! with a known vulnerability); the fork has regular releases (4.0.1 in 2026), forbids
//! `unsafe`, is fuzzed, and its errors carry line numbers. It is driven one element at a time
//! here, so that every error can say which element it is about.
//!
//! ```
//! let text = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n\
//!             property float z\nelement face 1\nproperty list uchar int vertex_indices\n\
//!             end_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
//! let mesh = kepler::io::ply::parse(text.as_bytes(), "tri.ply").unwrap();
//! assert_eq!(mesh.faces().len(), 1);
//! ```

use super::{FileError, Result, located, quoted, shortened};
use crate::geometry::Point3;
use crate::mesh::{Loop, Mesh, Validation};
use ply_rs_bw::parser::{ParseError, Parser, Reader};
use ply_rs_bw::ply::{
    ElementDef, Encoding, Header, PropertyAccess, PropertyAccessResult, PropertyType, ScalarType,
};
use std::io::BufRead;

/// The names of a face's vertex list.
const VERTEX_LISTS: [&str; 2] = ["vertex_indices", "vertex_index"];

/// Parses the bytes of a PLY file; `path` names the file in error messages.
///
/// ```
/// use kepler::io::ply;
/// let mut bytes = b"ply\nformat binary_big_endian 1.0\nelement vertex 3\nproperty double x\n\
///     property double y\nproperty double z\nelement face 1\n\
///     property list uchar uint vertex_indices\nend_header\n".to_vec();
/// for c in [0.0f64, 0.0, 0.0, 1.0, 0.0, 0.0, 0.1, 1.0, 0.0] {
///     bytes.extend(c.to_be_bytes());
/// }
/// bytes.push(3);
/// for i in [0u32, 1, 5] {
///     bytes.extend(i.to_be_bytes());
/// }
/// let err = ply::parse(&bytes, "t.ply").unwrap_err();
/// assert_eq!(
///     err.to_string(),
///     "t.ply:face 1: vertex index 5 is out of range: the file has 3 vertices, numbered from 0"
/// );
/// ```
pub fn parse(bytes: &[u8], path: &str) -> Result<Mesh> {
    parse_with(bytes, path, Validation::Repair)
}

/// [`parse`] with the given treatment of degenerate faces and polygons that are not exactly
/// planar.
///
/// ```
/// use kepler::{io::ply, mesh::Validation};
/// let text = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n\
///             property float z\nelement face 2\nproperty list uchar int vertex_index\n\
///             end_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n3 0 1 1\n";
/// assert_eq!(ply::parse(text.as_bytes(), "t.ply").unwrap().degenerate_faces(), 1);
/// let err = ply::parse_with(text.as_bytes(), "t.ply", Validation::Strict).unwrap_err();
/// assert_eq!(err.to_string(), "t.ply:14: face 2 visits the point (1, 0, 0) twice");
/// ```
pub fn parse_with(bytes: &[u8], path: &str, validation: Validation) -> Result<Mesh> {
    let parser = Parser::<Record>::new();
    let mut reader = Reader::new(bytes);
    let header = parser
        .read_header(&mut reader)
        .map_err(|e| crate_error(path, &e, "header"))?;
    let layout = Layout::of(&header).map_err(|message| FileError::Input {
        path: path.to_owned(),
        at: "header".to_owned(),
        message,
    })?;
    let ascii = header.encoding == Encoding::Ascii;
    let mut elements = Elements {
        parser,
        encoding: header.encoding,
        line: reader.line(),
        reader: reader.into_inner(),
        path,
    };
    let mut vertices = Vec::new();
    let mut faces = Vec::new();
    // Where each vertex and face is: its line in an ASCII file, else its element.
    let (mut vertex_at, mut face_at) = (Vec::new(), Vec::new());
    for element in header.elements.values() {
        let kind = if element.name == "vertex" {
            Kind::Vertex
        } else if element.name == "face" {
            Kind::Face
        } else {
            Kind::Other
        };
        for k in 0..element.count {
            let (at, record) = elements.next(element, k)?;
            // An ASCII file's place is a line: the message names the element.
            let error = |message: String| FileError::Input {
                path: path.to_owned(),
                at: at.clone(),
                message: if ascii {
                    format!("{} {}: {message}", element.name, k + 1)
                } else {
                    message
                },
            };
            match kind {
                Kind::Vertex => {
                    let [Some(x), Some(y), Some(z)] = record.xyz else {
                        return Err(error("missing coordinate".into()));
                    };
                    vertices.push(Point3::new(x, y, z));
                    vertex_at.push(at);
                }
                Kind::Face => {
                    faces.push(face(&record.indices, layout.vertices).map_err(error)?);
                    face_at.push(at);
                }
                Kind::Other => {}
            }
        }
    }
    Mesh::from_loops_with(vertices, faces, validation).map_err(|e| {
        located(
            path,
            e,
            |v| vertex_at.get(v).cloned(),
            |f| face_at.get(f).cloned(),
        )
    })
}

/// Which element a record belongs to.
#[derive(Clone, Copy)]
enum Kind {
    Vertex,
    Face,
    Other,
}

/// What the header promises: how many vertices (checked to have `x`, `y`, `z`) and that faces
/// have a vertex list of integers.
struct Layout {
    vertices: usize,
}

impl Layout {
    fn of(header: &Header) -> Result<Layout, String> {
        let vertices = match header.elements.get("vertex") {
            Some(vertex) => {
                for name in ["x", "y", "z"] {
                    match vertex.properties.get(name).map(|p| &p.data_type) {
                        Some(PropertyType::Scalar(_)) => {}
                        Some(PropertyType::List(..)) => {
                            return Err(format!(
                                "the vertex property '{name}' is a list, not a number"
                            ));
                        }
                        None => return Err(format!("the vertex element has no property '{name}'")),
                    }
                }
                vertex.count
            }
            None => 0,
        };
        if let Some(face) = header.elements.get("face") {
            let list = VERTEX_LISTS
                .iter()
                .find_map(|name| face.properties.get(*name).map(|p| (name, &p.data_type)));
            match list {
                Some((_, PropertyType::List(_, item))) if is_integer(item) => {}
                Some((name, _)) => {
                    return Err(format!(
                        "the face property '{name}' is not a list of integers"
                    ));
                }
                None => {
                    return Err(
                        "the face element has no list 'vertex_indices' or 'vertex_index'".into(),
                    );
                }
            }
        }
        Ok(Layout { vertices })
    }
}

fn is_integer(t: &ScalarType) -> bool {
    !matches!(t, ScalarType::Float | ScalarType::Double)
}

/// The 0-based vertex indices of a face, checked against the number of vertices.
fn face(indices: &[i64], vertex_count: usize) -> Result<Loop, String> {
    indices
        .iter()
        .map(|&i| match usize::try_from(i) {
            Ok(k) if k < vertex_count => u32::try_from(k).map_err(|_| {
                format!("vertex index {k} is beyond the 2^32 vertices kepler supports")
            }),
            _ => Err(format!(
                "vertex index {i} is out of range: the file has {vertex_count} vertices, \
                 numbered from 0"
            )),
        })
        .collect()
}

/// The payload, one element at a time.
struct Elements<'a> {
    parser: Parser<Record>,
    encoding: Encoding,
    reader: &'a [u8],
    /// The 1-based line of the next ASCII record.
    line: usize,
    path: &'a str,
}

impl Elements<'_> {
    /// Element `k` (0-based) of kind `element`, with where it is (its line, or its name and
    /// number for a binary file).
    fn next(&mut self, element: &ElementDef, k: usize) -> Result<(String, Record)> {
        let named = || format!("{} {}", element.name, k + 1);
        let result = match self.encoding {
            Encoding::Ascii => {
                let mut text = String::new();
                // Blank lines between records are tolerated.
                while text.trim().is_empty() {
                    text.clear();
                    let read = self.reader.read_line(&mut text);
                    self.line += 1;
                    let at =
                        |message: String| FileError::at_line(self.path, self.line - 1, message);
                    match read {
                        Ok(0) => {
                            return Err(at(format!(
                                "unexpected end of file: the header announces {} {} elements, \
                                 found {k}",
                                element.count, element.name
                            )));
                        }
                        Ok(_) => {}
                        Err(_) => {
                            return Err(at(format!("{}: the line is not text (UTF-8)", named())));
                        }
                    }
                }
                let at = (self.line - 1).to_string();
                match self.parser.read_ascii_element(&text, element) {
                    Ok(record) => return Ok((at, record)),
                    Err(e) => (at, e),
                }
            }
            Encoding::BinaryLittleEndian => {
                match self
                    .parser
                    .read_little_endian_element(&mut self.reader, element)
                {
                    Ok(record) => return Ok((named(), record)),
                    Err(e) => (named(), e),
                }
            }
            Encoding::BinaryBigEndian => {
                match self
                    .parser
                    .read_big_endian_element(&mut self.reader, element)
                {
                    Ok(record) => return Ok((named(), record)),
                    Err(e) => (named(), e),
                }
            }
        };
        let (at, e) = result;
        let message = if e.kind() == std::io::ErrorKind::UnexpectedEof {
            format!(
                "unexpected end of file: the header announces {} {} elements",
                element.count, element.name
            )
        } else if self.encoding == Encoding::Ascii {
            format!("{}: {}", named(), one_line(&e))
        } else {
            one_line(&e)
        };
        Err(FileError::Input {
            path: self.path.to_owned(),
            at,
            message,
        })
    }
}

/// An error of the PLY parser, at its line when it knows it, else at `at`.
fn crate_error(path: &str, e: &ParseError, at: &str) -> FileError {
    FileError::Input {
        path: path.to_owned(),
        at: e.line().map_or_else(|| at.to_owned(), |l| l.to_string()),
        message: one_line(e),
    }
}

/// The parser's message on one line (it spreads the line it quotes over several), without its
/// own "Line n:" prefix, and cut where it echoes long input. A line it could not parse is
/// named with what was expected there instead of its grammar's internals.
fn one_line(e: &ParseError) -> String {
    let text = e.to_string();
    let text = match (e.line(), text.split_once(": ")) {
        (Some(_), Some((prefix, rest))) if prefix.starts_with("Line ") => rest,
        _ => &text,
    };
    let text = text.split_whitespace().collect::<Vec<_>>().join(" ");
    let quoted_line = |after: &str| {
        let (_, rest) = text.split_once(after)?;
        let (line, _) = rest.rsplit_once("' Error:")?;
        Some(quoted(line.trim()))
    };
    if let Some(line) = quoted_line("Couldn't parse element line. String: '") {
        format!("{line} are not the numbers the header declares")
    } else if let Some(line) = quoted_line("Couldn't parse line. String: '") {
        format!(
            "{line} is not a header line (ply, format, comment, obj_info, element, property or \
             end_header)"
        )
    } else {
        shortened(&text)
    }
}

/// One element's values that kepler reads: the coordinates and the face's vertex list.
#[derive(Debug, Default)]
struct Record {
    xyz: [Option<f64>; 3],
    indices: Vec<i64>,
}

impl Record {
    fn coordinate(&mut self, name: &str, value: f64) -> PropertyAccessResult {
        let k = match name {
            "x" => 0,
            "y" => 1,
            "z" => 2,
            _ => return PropertyAccessResult::Ignored,
        };
        self.xyz[k] = Some(value);
        PropertyAccessResult::Set
    }

    fn list(&mut self, name: &str, values: impl Iterator<Item = i64>) -> PropertyAccessResult {
        if !VERTEX_LISTS.contains(&name) {
            return PropertyAccessResult::Ignored;
        }
        self.indices = values.collect();
        PropertyAccessResult::Set
    }
}

impl PropertyAccess for Record {
    fn new() -> Self {
        Record::default()
    }
    fn set_char(&mut self, name: &str, value: i8) -> PropertyAccessResult {
        self.coordinate(name, f64::from(value))
    }
    fn set_uchar(&mut self, name: &str, value: u8) -> PropertyAccessResult {
        self.coordinate(name, f64::from(value))
    }
    fn set_short(&mut self, name: &str, value: i16) -> PropertyAccessResult {
        self.coordinate(name, f64::from(value))
    }
    fn set_ushort(&mut self, name: &str, value: u16) -> PropertyAccessResult {
        self.coordinate(name, f64::from(value))
    }
    fn set_int(&mut self, name: &str, value: i32) -> PropertyAccessResult {
        self.coordinate(name, f64::from(value))
    }
    fn set_uint(&mut self, name: &str, value: u32) -> PropertyAccessResult {
        self.coordinate(name, f64::from(value))
    }
    fn set_float(&mut self, name: &str, value: f32) -> PropertyAccessResult {
        self.coordinate(name, f64::from(value))
    }
    fn set_double(&mut self, name: &str, value: f64) -> PropertyAccessResult {
        self.coordinate(name, value)
    }
    fn set_list_char(&mut self, name: &str, value: Vec<i8>) -> PropertyAccessResult {
        self.list(name, value.into_iter().map(i64::from))
    }
    fn set_list_uchar(&mut self, name: &str, value: Vec<u8>) -> PropertyAccessResult {
        self.list(name, value.into_iter().map(i64::from))
    }
    fn set_list_short(&mut self, name: &str, value: Vec<i16>) -> PropertyAccessResult {
        self.list(name, value.into_iter().map(i64::from))
    }
    fn set_list_ushort(&mut self, name: &str, value: Vec<u16>) -> PropertyAccessResult {
        self.list(name, value.into_iter().map(i64::from))
    }
    fn set_list_int(&mut self, name: &str, value: Vec<i32>) -> PropertyAccessResult {
        self.list(name, value.into_iter().map(i64::from))
    }
    fn set_list_uint(&mut self, name: &str, value: Vec<u32>) -> PropertyAccessResult {
        self.list(name, value.into_iter().map(i64::from))
    }
}
