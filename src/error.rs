//! kepler's error: every layer's error, wrapped, each message naming the file and line, or the
//! object, at fault.
//!
//! Each layer has its own typed error ([`FileError`] for files, [`MeshError`] for meshes,
//! [`SceneError`] for scenes, [`ViewError`] for views, [`QueryError`] for INCLUDE,
//! [`DrawError`] for drawings, [`SurfacesError`] for visible surfaces); [`Error`] wraps any of
//! them with `?`, keeping its message, for callers that use several layers.
//!
//! ```
//! use kepler::{Error, io::FileError};
//! let e: Error = FileError::at_line("scenes/a.obj", 12, "expected 3 coordinates").into();
//! assert_eq!(e.to_string(), "scenes/a.obj:12: expected 3 coordinates");
//! ```

use crate::hidden::DrawError;
use crate::io::FileError;
use crate::mesh::MeshError;
use crate::queries::QueryError;
use crate::scene::SceneError;
use crate::solids::SolidError;
use crate::surfaces::SurfacesError;
use crate::views::ViewError;

/// Everything that can go wrong in kepler's engine: one variant per layer.
///
/// ```
/// use kepler::{Error, scene::file::load};
/// let e: Error = load("missing.toml".as_ref()).unwrap_err().into();
/// assert!(matches!(e, Error::Scene(_)));
/// assert!(e.to_string().starts_with("missing.toml: "));
/// ```
#[derive(Debug, thiserror::Error)]
pub enum Error {
    /// A file could not be read, or holds bad input.
    #[error(transparent)]
    File(#[from] FileError),
    /// An invalid mesh built by the library.
    #[error(transparent)]
    Mesh(#[from] MeshError),
    /// A built-in solid with bad parameters.
    #[error(transparent)]
    Solid(#[from] SolidError),
    /// A scene that cannot be built or read.
    #[error(transparent)]
    Scene(#[from] SceneError),
    /// A view that cannot be built, or a scene it cannot picture.
    #[error(transparent)]
    View(#[from] ViewError),
    /// A query that cannot be answered.
    #[error(transparent)]
    Query(#[from] QueryError),
    /// A drawing that cannot be made.
    #[error(transparent)]
    Draw(#[from] DrawError),
    /// Visible surfaces that cannot be computed.
    #[error(transparent)]
    Surfaces(#[from] SurfacesError),
}

/// `Result` with kepler's [`Error`].
pub type Result<T, E = Error> = std::result::Result<T, E>;
