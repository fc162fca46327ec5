//! Errors, each naming the file and line, or the object, at fault.
//!
//! ```
//! use kepler::Error;
//! let e = Error::at_line("scenes/a.obj", 12, "expected 3 coordinates");
//! assert_eq!(e.to_string(), "scenes/a.obj:12: expected 3 coordinates");
//! ```

use crate::mesh::MeshError;

/// Everything that can go wrong in kepler.
#[derive(Debug, thiserror::Error)]
pub enum Error {
    /// A file could not be read.
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
    /// A problem with a named object of a scene.
    #[error("object '{object}': {message}")]
    Object {
        /// The object's name.
        object: String,
        /// What is wrong.
        message: String,
    },
    /// A view that cannot be built (a zero direction, an up vector along it, ...).
    #[error("invalid view: {0}")]
    View(#[from] crate::views::ViewError),
    /// An invalid mesh built by the library (a built-in solid with bad parameters, say).
    #[error(transparent)]
    Mesh(#[from] MeshError),
}

impl Error {
    /// An [`Error::Input`] at a 1-based line of a file.
    ///
    /// ```
    /// let e = kepler::Error::at_line("x.off", 3, "bad");
    /// assert_eq!(e.to_string(), "x.off:3: bad");
    /// ```
    pub fn at_line(path: impl Into<String>, line: usize, message: impl Into<String>) -> Error {
        Error::Input {
            path: path.into(),
            at: line.to_string(),
            message: message.into(),
        }
    }

    /// An [`Error::Io`] for a file.
    ///
    /// ```
    /// let e = kepler::Error::io("missing.obj", std::io::Error::from(std::io::ErrorKind::NotFound));
    /// assert!(e.to_string().starts_with("missing.obj: "));
    /// ```
    pub fn io(path: impl Into<String>, source: std::io::Error) -> Error {
        Error::Io {
            path: path.into(),
            source,
        }
    }
}

/// `Result` with kepler's [`Error`].
pub type Result<T, E = Error> = std::result::Result<T, E>;
