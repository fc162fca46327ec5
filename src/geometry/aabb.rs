//! Franklin's *box*: "a rectangular solid whose sides are parallel to the axes ... defined by
//! six numbers: XL, YL, ZL, XH, YH, ZH". Both the CBOX and the INBOX of an object are boxes.

use super::Point3;
use serde::Serialize;

/// An axis-aligned box `[min, max]` (closed), or the empty box.
///
/// ```
/// use kepler::{geometry::Aabb, geometry::Point3};
/// let b = Aabb::from_points(&[Point3::new(0.0, 0.0, 0.0), Point3::new(2.0, 1.0, 3.0)]);
/// assert_eq!(b.volume(), 6.0);
/// assert!(b.contains_point(&Point3::new(2.0, 0.5, 0.0)));
/// assert!(Aabb::EMPTY.is_empty());
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Aabb {
    /// The low corner (XL, YL, ZL).
    pub min: [f64; 3],
    /// The high corner (XH, YH, ZH).
    pub max: [f64; 3],
}

impl Aabb {
    /// The empty box: contains nothing, and is the identity of [`Aabb::union`].
    ///
    /// ```
    /// use kepler::geometry::Aabb;
    /// assert_eq!(Aabb::EMPTY.volume(), 0.0);
    /// ```
    pub const EMPTY: Aabb = Aabb {
        min: [f64::INFINITY; 3],
        max: [f64::NEG_INFINITY; 3],
    };

    /// The box with the given corners.
    ///
    /// ```
    /// use kepler::{geometry::Aabb, geometry::Point3};
    /// let b = Aabb::new(Point3::new(0.0, 0.0, 0.0), Point3::new(1.0, 1.0, 1.0));
    /// assert_eq!(b.max, [1.0, 1.0, 1.0]);
    /// ```
    pub fn new(min: Point3, max: Point3) -> Aabb {
        Aabb {
            min: min.into(),
            max: max.into(),
        }
    }

    /// The smallest box containing the points (the CBOX of a point set).
    ///
    /// ```
    /// use kepler::{geometry::Aabb, geometry::Point3};
    /// assert!(Aabb::from_points(&[]).is_empty());
    /// ```
    pub fn from_points(points: &[Point3]) -> Aabb {
        points.iter().fold(Aabb::EMPTY, |b, p| b.with_point(p))
    }

    /// This box grown to contain `p`.
    ///
    /// ```
    /// use kepler::{geometry::Aabb, geometry::Point3};
    /// let b = Aabb::EMPTY.with_point(&Point3::new(1.0, 2.0, 3.0));
    /// assert_eq!((b.min, b.max), ([1.0, 2.0, 3.0], [1.0, 2.0, 3.0]));
    /// ```
    pub fn with_point(&self, p: &Point3) -> Aabb {
        let mut b = *self;
        for k in 0..3 {
            b.min[k] = b.min[k].min(p[k]);
            b.max[k] = b.max[k].max(p[k]);
        }
        b
    }

    /// The smallest box containing both.
    ///
    /// ```
    /// use kepler::{geometry::Aabb, geometry::Point3};
    /// let a = Aabb::new(Point3::new(0.0, 0.0, 0.0), Point3::new(1.0, 1.0, 1.0));
    /// let b = Aabb::new(Point3::new(2.0, 0.0, 0.0), Point3::new(3.0, 1.0, 1.0));
    /// assert_eq!(a.union(&b).volume(), 3.0);
    /// ```
    pub fn union(&self, other: &Aabb) -> Aabb {
        let mut b = *self;
        for k in 0..3 {
            b.min[k] = b.min[k].min(other.min[k]);
            b.max[k] = b.max[k].max(other.max[k]);
        }
        b
    }

    /// Whether the box contains no point.
    ///
    /// ```
    /// use kepler::{geometry::Aabb, geometry::Point3};
    /// assert!(!Aabb::from_points(&[Point3::origin()]).is_empty());
    /// ```
    pub fn is_empty(&self) -> bool {
        (0..3).any(|k| {
            self.min[k]
                .partial_cmp(&self.max[k])
                .is_none_or(|o| o == std::cmp::Ordering::Greater)
        })
    }

    /// The low corner.
    ///
    /// ```
    /// use kepler::{geometry::Aabb, geometry::Point3};
    /// assert_eq!(Aabb::from_points(&[Point3::new(1.0, 2.0, 3.0)]).min_point(), Point3::new(1.0, 2.0, 3.0));
    /// ```
    pub fn min_point(&self) -> Point3 {
        Point3::from(self.min)
    }

    /// The high corner.
    ///
    /// ```
    /// use kepler::{geometry::Aabb, geometry::Point3};
    /// assert_eq!(Aabb::from_points(&[Point3::new(1.0, 2.0, 3.0)]).max_point(), Point3::new(1.0, 2.0, 3.0));
    /// ```
    pub fn max_point(&self) -> Point3 {
        Point3::from(self.max)
    }

    /// Edge lengths along x, y, z (zero for the empty box).
    ///
    /// ```
    /// use kepler::{geometry::Aabb, geometry::Point3};
    /// let b = Aabb::new(Point3::new(0.0, 0.0, 0.0), Point3::new(1.0, 2.0, 3.0));
    /// assert_eq!(b.size(), [1.0, 2.0, 3.0]);
    /// ```
    pub fn size(&self) -> [f64; 3] {
        if self.is_empty() {
            return [0.0; 3];
        }
        [0, 1, 2].map(|k| self.max[k] - self.min[k])
    }

    /// The volume.
    ///
    /// ```
    /// use kepler::{geometry::Aabb, geometry::Point3};
    /// assert_eq!(Aabb::new(Point3::origin(), Point3::new(2.0, 2.0, 2.0)).volume(), 8.0);
    /// ```
    pub fn volume(&self) -> f64 {
        let s = self.size();
        s[0] * s[1] * s[2]
    }

    /// The surface area.
    ///
    /// ```
    /// use kepler::{geometry::Aabb, geometry::Point3};
    /// assert_eq!(Aabb::new(Point3::origin(), Point3::new(1.0, 1.0, 1.0)).surface_area(), 6.0);
    /// ```
    pub fn surface_area(&self) -> f64 {
        let s = self.size();
        2.0 * (s[0] * s[1] + s[1] * s[2] + s[2] * s[0])
    }

    /// Whether `p` lies in the closed box (exact: only comparisons).
    ///
    /// ```
    /// use kepler::{geometry::Aabb, geometry::Point3};
    /// let b = Aabb::new(Point3::origin(), Point3::new(1.0, 1.0, 1.0));
    /// assert!(b.contains_point(&Point3::new(1.0, 0.0, 0.5)));
    /// assert!(!b.contains_point(&Point3::new(1.5, 0.0, 0.5)));
    /// ```
    pub fn contains_point(&self, p: &Point3) -> bool {
        (0..3).all(|k| self.min[k] <= p[k] && p[k] <= self.max[k])
    }

    /// Whether the closed boxes share a point (exact).
    ///
    /// ```
    /// use kepler::{geometry::Aabb, geometry::Point3};
    /// let a = Aabb::new(Point3::origin(), Point3::new(1.0, 1.0, 1.0));
    /// let b = Aabb::new(Point3::new(1.0, 1.0, 1.0), Point3::new(2.0, 2.0, 2.0));
    /// assert!(a.intersects(&b));
    /// ```
    pub fn intersects(&self, other: &Aabb) -> bool {
        (0..3).all(|k| self.min[k] <= other.max[k] && other.min[k] <= self.max[k])
    }

    /// The eight corners, in the order of the bits (x, y, z) of the index.
    ///
    /// ```
    /// use kepler::{geometry::Aabb, geometry::Point3};
    /// let b = Aabb::new(Point3::origin(), Point3::new(1.0, 2.0, 3.0));
    /// assert_eq!(b.corners()[7], Point3::new(1.0, 2.0, 3.0));
    /// ```
    pub fn corners(&self) -> [Point3; 8] {
        std::array::from_fn(|i| {
            Point3::new(
                if i & 1 == 0 { self.min[0] } else { self.max[0] },
                if i & 2 == 0 { self.min[1] } else { self.max[1] },
                if i & 4 == 0 { self.min[2] } else { self.max[2] },
            )
        })
    }
}
