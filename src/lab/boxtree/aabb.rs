//! Axis-aligned boxes as node shapes: "The choice of axis-parallel parallepipeds for boxes has
//! the advantage of simplicity. (It is a bottom-up version of an R-tree.) [...] There is one
//! obvious parent box rule: make box(v) the smallest box that encloses box(u1) ∪ box(u2)."
//!
//! Everything is exact but the measures: bounds are coordinates, the union takes extremes, and
//! two boxes overlap exactly when their coordinate ranges do.
//!
//! ```
//! use kepler::lab::boxtree::NodeShape;
//! use kepler::geometry::{Aabb, Point3};
//! let t = [Point3::new(0.0, 0.0, 0.0), Point3::new(1.0, 0.0, 0.0), Point3::new(0.0, 2.0, 1.0)];
//! let b = Aabb::leaf(&t);
//! assert_eq!((b.min, b.max), ([0.0; 3], [1.0, 2.0, 1.0]));
//! ```

use super::slab::meet;
use super::{Measures, NodeShape, RayProbe, Shape};
use crate::geometry::{Aabb, Point3};

impl NodeShape for Aabb {
    const SHAPE: Shape = Shape::Aabb;

    fn leaf(triangle: &[Point3; 3]) -> Aabb {
        Aabb::from_points(triangle)
    }

    fn parent(a: &Aabb, b: &Aabb) -> Aabb {
        a.union(b)
    }

    fn measures(&self) -> Measures {
        Measures {
            area: self.surface_area(),
            volume: self.volume(),
        }
    }

    fn center(&self) -> Point3 {
        Point3::from([0, 1, 2].map(|k| 0.5 * self.min[k] + 0.5 * self.max[k]))
    }

    fn contains_point(&self, p: &Point3) -> bool {
        Aabb::contains_point(self, p)
    }

    fn ray_interval(&self, ray: &RayProbe) -> Option<[f64; 2]> {
        meet((0..3).map(|k| ray.fixed(k).interval(self.min[k], self.max[k])))
    }

    fn may_overlap(&self, other: &Aabb) -> bool {
        self.intersects(other)
    }
}
