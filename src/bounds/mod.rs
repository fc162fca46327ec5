//! The three bounds Franklin's objects keep: the circumscribing box (CBOX), the inscribing
//! box (INBOX) and, after Crosnier and Rossignac (1999), the tribox.
//!
//! ```
//! use kepler::bounds::{cbox, inbox};
//! let cube = kepler::solids::cube(2.0).unwrap();
//! assert_eq!(cbox(&cube).volume(), 8.0);
//! assert_eq!(inbox(&cube).unwrap().aabb, cbox(&cube));
//! ```

mod inbox;
pub mod tribox;

pub use crate::geometry::Aabb;
pub use inbox::{Inbox, InboxMethod, inbox};

use crate::mesh::Mesh;

/// The CBOX of a mesh: the smallest axis-aligned box containing its vertices (exact: only
/// comparisons).
///
/// ```
/// let b = kepler::bounds::cbox(&kepler::solids::cube(1.0).unwrap());
/// assert_eq!((b.min, b.max), ([-0.5; 3], [0.5; 3]));
/// ```
pub fn cbox(mesh: &Mesh) -> Aabb {
    Aabb::from_points(mesh.vertices())
}
