//! Mesh files: Wavefront OBJ, STL (ASCII and binary), OFF and PLY (ASCII and binary); and
//! point files ([`points`]).
//!
//! [`read_mesh`] picks the reader from the file's extension; [`obj::parse`], [`stl::parse`],
//! [`off::parse`] and [`ply::parse`] read text or bytes already in memory (their `parse_with`
//! take a [`Validation`]). Every reader keeps the input as it is: polygons stay polygons,
//! coordinates are parsed with Rust's correctly rounded `str::parse::<f64>` (binary `f32` are
//! widened exactly), and anything a reader cannot represent is an error rather than something
//! skipped. Errors name the file and the 1-based line (for binary files, the 1-based triangle
//! or element) of the offending statement, including the errors [`Mesh::from_polygons_with`]
//! finds in a face or vertex. Input echoed in an error is cut to a readable length
//! ([`quoted`]).
//!
//! The readers are written by hand rather than with `tobj` or `stl_io`: `tobj`'s errors carry
//! no line numbers and it parses `f32` by default, and `stl_io` reads ASCII STL into `f32`.
//!
//! ```
//! let text = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 1 2 9\n";
//! let err = kepler::io::obj::parse(text, "tri.obj").unwrap_err();
//! assert_eq!(
//!     err.to_string(),
//!     "tri.obj:5: vertex index 9 is out of range: 3 vertices are defined before this line"
//! );
//! ```

pub mod obj;
pub mod off;
pub mod ply;
pub mod points;
pub mod stl;

use crate::mesh::{Mesh, MeshError, Validation};
use std::path::Path;

/// What went wrong reading a file, naming the file and the place in it: the io layer's error.
///
/// ```
/// use kepler::io::FileError;
/// let e = FileError::at_line("scenes/a.obj", 12, "expected 3 coordinates");
/// assert_eq!(e.to_string(), "scenes/a.obj:12: expected 3 coordinates");
/// ```
#[derive(Debug, thiserror::Error)]
pub enum FileError {
    /// A file could not be read (or written).
    #[error("{path}: {source}")]
    Io {
        /// The file.
        path: String,
        /// What the operating system said.
        #[source]
        source: std::io::Error,
    },
    /// Bad input at a place in a file: `at` is a line number, or a record such as
    /// `triangle 7` for binary files.
    #[error("{path}:{at}: {message}")]
    Input {
        /// The file.
        path: String,
        /// Where in the file (a 1-based line number, or a record name).
        at: String,
        /// What is wrong.
        message: String,
    },
    /// A face or vertex of a mesh file that [`Mesh::from_polygons`] refuses, at its place in
    /// the file (`mesh` when no single line is at fault).
    #[error("{path}:{at}: {source}")]
    Mesh {
        /// The file.
        path: String,
        /// Where in the file.
        at: String,
        /// What is wrong with the mesh.
        #[source]
        source: MeshError,
    },
}

impl FileError {
    /// A [`FileError::Input`] at a 1-based line of a file.
    ///
    /// ```
    /// let e = kepler::io::FileError::at_line("x.off", 3, "bad");
    /// assert_eq!(e.to_string(), "x.off:3: bad");
    /// ```
    pub fn at_line(path: impl Into<String>, line: usize, message: impl Into<String>) -> FileError {
        FileError::Input {
            path: path.into(),
            at: line.to_string(),
            message: message.into(),
        }
    }

    /// A [`FileError::Io`] for a file.
    ///
    /// ```
    /// use kepler::io::FileError;
    /// let e = FileError::io("missing.obj", std::io::Error::from(std::io::ErrorKind::NotFound));
    /// assert!(e.to_string().starts_with("missing.obj: "));
    /// ```
    pub fn io(path: impl Into<String>, source: std::io::Error) -> FileError {
        FileError::Io {
            path: path.into(),
            source,
        }
    }
}

/// `Result` with the io layer's [`FileError`].
type Result<T, E = FileError> = std::result::Result<T, E>;

/// Reads a mesh file, choosing the format from its extension: `obj`, `stl`, `off` or `ply`,
/// in any letter case; degenerate faces are dropped and polygons that are not exactly planar
/// split ([`Validation::Repair`], see [`read_mesh_with`]). An unknown extension, a file that
/// cannot be read, a file without faces and bad content are errors naming the file (and, for
/// content, the line, triangle or element).
///
/// OBJ and OFF files are decoded as UTF-8; bytes that are not UTF-8 can only be valid in text
/// the readers ignore (comments, group and material names), and anywhere else they make the
/// statement they are in an error, so replacing them cannot change the geometry.
///
/// ```
/// use kepler::io::read_mesh;
/// let path = std::env::temp_dir().join(format!("kepler-doc-{}.OFF", std::process::id()));
/// std::fs::write(&path, "OFF\n4 4 6\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 1 2 3\n3 0 3 2\n")?;
/// let tet = read_mesh(&path)?;
/// std::fs::remove_file(&path)?;
/// assert_eq!(tet.faces().len(), 4);
/// assert!(tet.is_solid());
///
/// let err = read_mesh(std::path::Path::new("scene.3ds")).unwrap_err();
/// assert!(err.to_string().starts_with("scene.3ds: unknown mesh format"));
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn read_mesh(path: &Path) -> Result<Mesh> {
    read_mesh_with(path, Validation::Repair)
}

/// [`read_mesh`] with the given treatment of degenerate faces and polygons that are not
/// exactly planar: [`Validation::Strict`] refuses them, naming the file and the face's line
/// (or triangle, or element).
///
/// ```
/// use kepler::{io::read_mesh_with, mesh::Validation};
/// let path = std::env::temp_dir().join(format!("kepler-doc-strict-{}.obj", std::process::id()));
/// std::fs::write(&path, "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 2 0 0\nf 1 2 3\nf 1 2 4\n")?;
/// let err = read_mesh_with(&path, Validation::Strict).unwrap_err();
/// assert!(err.to_string().ends_with(":6: face 2 has zero area"));
/// assert_eq!(read_mesh_with(&path, Validation::Repair)?.degenerate_faces(), 1);
/// std::fs::remove_file(&path)?;
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn read_mesh_with(path: &Path, validation: Validation) -> Result<Mesh> {
    let name = path.display().to_string();
    let extension = path
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase);
    let format = match extension.as_deref() {
        Some(f @ ("obj" | "stl" | "off" | "ply")) => f,
        _ => {
            let message = "unknown mesh format: the extension must be .obj, .stl, .off or .ply";
            return Err(FileError::io(
                name,
                std::io::Error::new(std::io::ErrorKind::InvalidInput, message),
            ));
        }
    };
    let bytes = std::fs::read(path).map_err(|e| FileError::io(&name, e))?;
    let mesh = match format {
        "stl" => stl::parse_with(&bytes, &name, validation),
        "ply" => ply::parse_with(&bytes, &name, validation),
        "obj" => {
            // The file's bytes are let go before the mesh is built (they would otherwise be
            // held through its peak).
            let read = obj::read(&String::from_utf8_lossy(&bytes), &name)?;
            drop(bytes);
            read.into_mesh(&name, validation)
        }
        _ => off::parse_with(&String::from_utf8_lossy(&bytes), &name, validation),
    }?;
    // A file whose faces were all dropped as degenerate (zero area, after rounding to doubles)
    // is a valid, empty object; one without any face is not a mesh file.
    if mesh.faces().is_empty() && mesh.degenerate_faces() == 0 {
        return Err(FileError::Input {
            path: name,
            at: "1".into(),
            message: "the file has no faces".into(),
        });
    }
    Ok(mesh)
}

/// The most characters of an input that a message echoes.
const ECHOED: usize = 40;

/// A piece of input for an error message: in quotes, and cut after 40 characters, saying how
/// long it was, so that a huge token does not make a huge message.
///
/// ```
/// use kepler::io::quoted;
/// assert_eq!(quoted("vertex"), "'vertex'");
/// let long = "abcdefghij".repeat(100_000);
/// assert_eq!(quoted(&long), format!("'{}…' (1000000 bytes)", &long[..40]));
/// ```
pub fn quoted(input: &str) -> String {
    match input.char_indices().nth(ECHOED) {
        None => format!("'{input}'"),
        Some((cut, _)) => format!("'{}…' ({} bytes)", &input[..cut], input.len()),
    }
}

/// A message from another parser (TOML, PLY) that may echo input: every word (run of
/// characters without whitespace) longer than [`quoted`] allows is cut the same way.
///
/// ```
/// use kepler::io::shortened;
/// let message = format!("unknown field `{}`, expected `name`", "x".repeat(1 << 20));
/// let short = shortened(&message);
/// assert!(short.len() < 100, "{short}");
/// assert!(short.ends_with("(1048579 bytes) expected `name`"));
/// ```
pub fn shortened(message: &str) -> String {
    let mut out = String::with_capacity(message.len().min(1024));
    let mut rest = message;
    while let Some(start) = rest.find(|c: char| !c.is_whitespace()) {
        out.push_str(&rest[..start]);
        rest = &rest[start..];
        let end = rest.find(char::is_whitespace).unwrap_or(rest.len());
        let word = &rest[..end];
        match word.char_indices().nth(ECHOED) {
            None => out.push_str(word),
            Some((cut, _)) => {
                out.push_str(&format!("{}… ({} bytes)", &word[..cut], word.len()));
            }
        }
        rest = &rest[end..];
    }
    out.push_str(rest);
    out
}

/// Parses a number with Rust's correctly rounded `str::parse::<f64>`, requiring it to be
/// finite; `what` names it in the error message.
fn finite(token: &str, what: &str) -> Result<f64, String> {
    match token.parse::<f64>() {
        Ok(x) if x.is_finite() => Ok(x),
        Ok(x) if x.is_nan() || token.to_ascii_lowercase().contains("inf") => {
            Err(format!("{what} {} is not a finite number", quoted(token)))
        }
        Ok(_) => Err(format!(
            "{what} {} is not a finite number: it is too large for f64",
            quoted(token)
        )),
        Err(_) => Err(format!("{what} {} is not a number", quoted(token))),
    }
}

/// The text before a `#` comment.
fn strip_comment(line: &str) -> &str {
    line.split_once('#').map_or(line, |(before, _)| before)
}

/// The text without a leading byte order mark.
fn strip_bom(text: &str) -> &str {
    text.strip_prefix('\u{feff}').unwrap_or(text)
}

/// The 1-based number of the last line of `text` (1 for an empty text): where errors about a
/// premature end of file point.
fn last_line(text: &str) -> usize {
    text.lines().count().max(1)
}

/// Turns an error of [`Mesh::from_polygons`] into a [`FileError::Mesh`] at the place of the
/// offending vertex or face, given by `vertex_at` and `face_at` (0-based index to place).
fn located(
    path: &str,
    err: MeshError,
    vertex_at: impl Fn(usize) -> Option<String>,
    face_at: impl Fn(usize) -> Option<String>,
) -> FileError {
    let at = match err {
        MeshError::NonFinite { vertex } => vertex_at(vertex),
        MeshError::TooFewVertices { face, .. }
        | MeshError::IndexOutOfRange { face, .. }
        | MeshError::RepeatedVertex { face, .. }
        | MeshError::ZeroArea { face }
        | MeshError::NonPlanar { face, .. }
        | MeshError::NotSimple { face } => face_at(face),
        MeshError::SingularTransform => None,
    };
    FileError::Mesh {
        path: path.to_owned(),
        at: at.unwrap_or_else(|| "mesh".to_owned()),
        source: err,
    }
}

/// [`located`] for the text formats, which record the 1-based line of every vertex and face.
fn located_at_lines(
    path: &str,
    err: MeshError,
    vertex_lines: &[usize],
    face_lines: &[usize],
) -> FileError {
    let line = |lines: &[usize], i: usize| lines.get(i).map(usize::to_string);
    located(
        path,
        err,
        |v| line(vertex_lines, v),
        |f| line(face_lines, f),
    )
}
