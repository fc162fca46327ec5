//! Oriented boxes: the intersection of three slabs `lo_k ≤ a_k · x ≤ hi_k` along three
//! (nearly) orthonormal directions, as BOXTREE's principal-component boxes (Barequet et al.
//! 1996) and Schmalstieg and Tobler's boxes (1999) are.
//!
//! Kept as slabs, like the tribox's nine, so that containment is exact: a slab's bounds are
//! rounded outward from the exact dot products, and a point is tested with the exact sign of
//! `a · x − lo`. The corners, volume and area assume the directions orthonormal and are
//! floating point.
//!
//! ```
//! use kepler::lab::oriented::OrientedBox;
//! use kepler::geometry::{Point3, Vector3};
//! let axes = [Vector3::x(), Vector3::y(), Vector3::z()];
//! let points = [Point3::new(0.0, 0.0, 0.0), Point3::new(1.0, 2.0, 3.0)];
//! let b = OrientedBox::from_points(axes, &points);
//! assert!(points.iter().all(|p| b.contains_point(p)));
//! assert!((b.volume() - 6.0).abs() < 1e-12);
//! ```

use crate::geometry::exact::{accurate_sum, product_terms, sum_sign};
use crate::geometry::{Aabb, Point3, Vector3};
use std::cmp::Ordering;

/// A box along three directions: `min[k] ≤ axes[k] · x ≤ max[k]`.
///
/// ```
/// use kepler::lab::oriented::OrientedBox;
/// let b = OrientedBox::from_aabb(&kepler::geometry::Aabb { min: [0.0; 3], max: [1.0; 3] });
/// assert_eq!((b.min, b.max), ([0.0; 3], [1.0; 3]));
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct OrientedBox {
    /// The three directions (unit and orthogonal, up to rounding).
    pub axes: [Vector3; 3],
    /// The low bound of each slab.
    pub min: [f64; 3],
    /// The high bound of each slab.
    pub max: [f64; 3],
}

impl OrientedBox {
    /// The smallest box along `axes` that contains `points` (empty: `min > max`): each bound is
    /// the exact extreme dot product rounded outward, so every point is inside exactly.
    ///
    /// ```
    /// use kepler::lab::oriented::OrientedBox;
    /// use kepler::geometry::{Point3, Vector3};
    /// let s = 0.5f64.sqrt();
    /// let axes = [Vector3::new(s, s, 0.0), Vector3::new(-s, s, 0.0), Vector3::z()];
    /// let p = [Point3::new(0.1, 0.2, 0.3), Point3::new(0.7, -0.2, 0.3)];
    /// let b = OrientedBox::from_points(axes, &p);
    /// assert!(p.iter().all(|p| b.contains_point(p)));
    /// ```
    pub fn from_points(axes: [Vector3; 3], points: &[Point3]) -> OrientedBox {
        let mut min = [f64::INFINITY; 3];
        let mut max = [f64::NEG_INFINITY; 3];
        let mut terms = Vec::with_capacity(6);
        for p in points {
            for k in 0..3 {
                terms.clear();
                for i in 0..3 {
                    product_terms(&[axes[k][i]], &[p[i]], &mut terms);
                }
                // The nearest double to the exact dot product, then one step outward unless
                // it is exact.
                let d = accurate_sum(&terms);
                terms.push(-d);
                let (lo, hi) = match sum_sign(&terms) {
                    Ordering::Equal => (d, d),
                    _ => (d.next_down(), d.next_up()),
                };
                min[k] = min[k].min(lo);
                max[k] = max[k].max(hi);
            }
        }
        OrientedBox { axes, min, max }
    }

    /// The axis-aligned box as an oriented one.
    ///
    /// ```
    /// use kepler::{lab::oriented::OrientedBox, geometry::{Aabb, Point3}};
    /// let b = OrientedBox::from_aabb(&Aabb { min: [0.0; 3], max: [2.0, 1.0, 1.0] });
    /// assert!(b.contains_point(&Point3::new(2.0, 0.5, 1.0)));
    /// ```
    pub fn from_aabb(b: &Aabb) -> OrientedBox {
        OrientedBox {
            axes: [Vector3::x(), Vector3::y(), Vector3::z()],
            min: b.min,
            max: b.max,
        }
    }

    /// Whether the box holds nothing.
    ///
    /// ```
    /// use kepler::{lab::oriented::OrientedBox, geometry::Vector3};
    /// assert!(OrientedBox::from_points([Vector3::x(), Vector3::y(), Vector3::z()], &[]).is_empty());
    /// ```
    pub fn is_empty(&self) -> bool {
        (0..3).any(|k| self.min[k] > self.max[k])
    }

    /// Whether `p` lies in the closed box, decided exactly.
    ///
    /// ```
    /// use kepler::{lab::oriented::OrientedBox, geometry::{Aabb, Point3}};
    /// let b = OrientedBox::from_aabb(&Aabb { min: [0.0; 3], max: [1.0; 3] });
    /// assert!(b.contains_point(&Point3::new(1.0, 1.0, 1.0)));
    /// assert!(!b.contains_point(&Point3::new(1.0, 1.0, 1.0f64.next_up())));
    /// ```
    pub fn contains_point(&self, p: &Point3) -> bool {
        let mut terms = Vec::with_capacity(7);
        (0..3).all(|k| {
            terms.clear();
            for i in 0..3 {
                product_terms(&[self.axes[k][i]], &[p[i]], &mut terms);
            }
            terms.push(-self.min[k]);
            let above_min = sum_sign(&terms) != Ordering::Less;
            terms.pop();
            terms.push(-self.max[k]);
            above_min && sum_sign(&terms) != Ordering::Greater
        })
    }

    /// The extent along each axis, `max − min`.
    ///
    /// ```
    /// use kepler::{lab::oriented::OrientedBox, geometry::Aabb};
    /// let b = OrientedBox::from_aabb(&Aabb { min: [0.0; 3], max: [1.0, 2.0, 3.0] });
    /// assert_eq!(b.extents(), [1.0, 2.0, 3.0]);
    /// ```
    pub fn extents(&self) -> [f64; 3] {
        [0, 1, 2].map(|k| (self.max[k] - self.min[k]).max(0.0))
    }

    /// The volume (the axes taken as orthonormal).
    ///
    /// ```
    /// use kepler::{lab::oriented::OrientedBox, geometry::Aabb};
    /// assert_eq!(OrientedBox::from_aabb(&Aabb { min: [0.0; 3], max: [1.0, 2.0, 3.0] }).volume(), 6.0);
    /// ```
    pub fn volume(&self) -> f64 {
        let [a, b, c] = self.extents();
        a * b * c
    }

    /// The surface area (the axes taken as orthonormal).
    ///
    /// ```
    /// use kepler::{lab::oriented::OrientedBox, geometry::Aabb};
    /// assert_eq!(OrientedBox::from_aabb(&Aabb { min: [0.0; 3], max: [1.0, 2.0, 3.0] }).surface_area(), 22.0);
    /// ```
    pub fn surface_area(&self) -> f64 {
        let [a, b, c] = self.extents();
        2.0 * (a * b + b * c + c * a)
    }

    /// The eight corners, corner `k` taking `max` along axis `i` when bit `i` of `k` is set
    /// (the axes taken as orthonormal; floating point).
    ///
    /// ```
    /// use kepler::{lab::oriented::OrientedBox, geometry::{Aabb, Point3}};
    /// let b = OrientedBox::from_aabb(&Aabb { min: [0.0; 3], max: [1.0, 2.0, 3.0] });
    /// assert_eq!(b.corners()[7], Point3::new(1.0, 2.0, 3.0));
    /// ```
    pub fn corners(&self) -> [Point3; 8] {
        std::array::from_fn(|k| {
            let c = |i: usize| {
                if k & (1 << i) != 0 {
                    self.max[i]
                } else {
                    self.min[i]
                }
            };
            Point3::from(self.axes[0] * c(0) + self.axes[1] * c(1) + self.axes[2] * c(2))
        })
    }
}
