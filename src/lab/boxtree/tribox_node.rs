//! Triboxes as node shapes: the intersection of slabs along the tribox's 9 fixed directions
//! (x, y, z, x+y, x+z, y+z, x−z, y−x, z−y), after Crosnier and Rossignac (1999). The paper
//! did not have them; they are what the rest of kepler bounds objects with.
//!
//! A leaf's bounds are the exact extreme projections of its vertices rounded outward
//! ([`TriboxBounds::from_points`]); a parent's are the extremes of its children's
//! ([`TriboxBounds::union`]), so it contains them exactly, slab by slab. The overlap test
//! compares the nine pairs of slabs exactly: disjoint slabs prove the triboxes disjoint, and
//! overlapping ones are the paper's interference filter (not an exact polytope test, so it may
//! say "overlap" for disjoint triboxes, never the reverse). The ray test is exact up to the
//! outward rounding of [`super::slab`], a tribox being the intersection of its slabs. The
//! measures are those of the exact boundary ([`TriboxBounds::boundary`]).
//!
//! ```
//! use kepler::lab::boxtree::NodeShape;
//! use kepler::bounds::tribox::TriboxBounds;
//! use kepler::geometry::Point3;
//! let t = [Point3::new(0.0, 0.0, 0.0), Point3::new(1.0, 0.0, 0.0), Point3::new(0.0, 1.0, 0.0)];
//! let b = TriboxBounds::leaf(&t);
//! assert!(!b.contains_point(&Point3::new(0.6, 0.6, 0.0))); // beyond x + y = 1
//! assert!((b.measures().area - 1.0).abs() < 1e-15); // the triangle's two sides
//! ```

use super::slab::meet;
use super::{Measures, NodeShape, RayProbe, Shape};
use crate::bounds::tribox::TriboxBounds;
use crate::geometry::Point3;

impl NodeShape for TriboxBounds {
    const SHAPE: Shape = Shape::Tribox;

    fn leaf(triangle: &[Point3; 3]) -> TriboxBounds {
        TriboxBounds::from_points(triangle)
    }

    fn parent(a: &TriboxBounds, b: &TriboxBounds) -> TriboxBounds {
        a.union(b)
    }

    fn measures(&self) -> Measures {
        let boundary = self.boundary();
        Measures {
            area: boundary.surface_area(),
            volume: boundary.volume(),
        }
    }

    fn center(&self) -> Point3 {
        let (lo, hi) = (self.min(), self.max());
        Point3::from([0, 1, 2].map(|k| 0.5 * lo[k] + 0.5 * hi[k]))
    }

    fn contains_point(&self, p: &Point3) -> bool {
        TriboxBounds::contains_point(self, p)
    }

    fn ray_interval(&self, ray: &RayProbe) -> Option<[f64; 2]> {
        let (lo, hi) = (self.min(), self.max());
        meet((0..9).map(|d| ray.fixed(d).interval(lo[d], hi[d])))
    }

    fn may_overlap(&self, other: &TriboxBounds) -> bool {
        self.intersects(other)
    }
}
