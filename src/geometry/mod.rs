//! Points, exact predicates and exact sums, and polygon helpers.
//!
//! Points are `nalgebra` points in `f64`. Signs are decided with the exact predicates of the
//! `robust` crate ([`predicates`]) or with exact sums of doubles ([`exact`]); no epsilon.
//!
//! ```
//! use kepler::geometry::Point3;
//! let p = Point3::new(1.0, 2.0, 3.0);
//! assert_eq!(p.x + p.y, 3.0);
//! ```

pub mod aabb;
pub mod exact;
pub mod kernel;

/// A point in 3-D space, in `f64`.
pub type Point3 = nalgebra::Point3<f64>;
/// A vector in 3-D space, in `f64`.
pub type Vector3 = nalgebra::Vector3<f64>;
pub mod polygon;
pub mod predicates;
pub mod ray;

pub use aabb::Aabb;
