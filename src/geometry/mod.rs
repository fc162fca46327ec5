//! The exact kernel: points and boxes, the predicates that decide every sign, the exact
//! arithmetic under them, and the constructions that build points from input coordinates.
//!
//! Everything else in the engine asks this layer for signs and never rounds on its own:
//!
//! - [`kernel`]: the error model, written once. A number to decide is a
//!   [`Polynomial`](kernel::Polynomial) of the input, known as an
//!   [`Estimate`](estimate::Estimate) (a rounded value and a certified error bound) and
//!   exactly, as an expansion; its sign is the estimate's when it is certified and the
//!   expansion's otherwise.
//! - [`estimate`]: that rounded value with its certified bound, the filter in front of every
//!   exact sign.
//! - [`arithmetic`]: the cheaper arithmetic (plain `f64`, `f64` with a tolerance, `f32`) that
//!   the error report swaps in to measure what exactness costs, on threads of its own: every
//!   other thread stays exact.
//! - [`predicates`]: `orient2d` and `orient3d` (`robust`'s adaptive predicates), the same
//!   with a point at infinity (an orthographic eye), and the determinants behind them as
//!   polynomials.
//! - [`exact`]: Shewchuk's expansion arithmetic (error-free sums and products, expansion
//!   sums and products, correctly rounded sums), written by hand because `robust` does not
//!   expose it.
//! - [`ray`]: rays and their exact hits on triangles.
//! - [`polygon`]: planar polygons in 3-D (Newell normals, exact triangulation, simplicity).
//! - [`aabb`]: Franklin's boxes.
//!
//! Points are `nalgebra` points in `f64`; no epsilon is used anywhere.
//!
//! ```
//! use kepler::geometry::{Point3, predicates::orient3d};
//! use std::cmp::Ordering;
//! let (a, b, c) = (Point3::new(0.0, 0.0, 0.0), Point3::new(1.0, 0.0, 0.0), Point3::new(0.0, 1.0, 0.0));
//! assert_eq!(orient3d(&a, &b, &c, &Point3::new(0.1, 0.2, 0.0)), Ordering::Equal);
//! ```

pub mod aabb;
pub mod arithmetic;
pub mod estimate;
pub mod exact;
pub mod kernel;
pub mod polygon;
pub mod predicates;
pub mod ray;

pub use aabb::Aabb;

/// A point in 3-D space, in `f64`.
pub type Point3 = nalgebra::Point3<f64>;
/// A vector in 3-D space, in `f64`.
pub type Vector3 = nalgebra::Vector3<f64>;
