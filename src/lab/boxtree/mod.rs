//! BOXTREE (Barequet, Chazelle, Guibas, Mitchell and Tal 1996): a binary hierarchy of nested
//! bounds over the triangles of a surface, built bottom up, for ray shooting and collision
//! detection.
//!
//! "It is a binary tree whose leaves are in bijection with the facets of a triangulated or
//! meshed surface. [...] With each leaf we associate a box that encloses the corresponding
//! facet. In a similar manner, each internal node is associated with a box that encloses the
//! boxes of its two children." The paper weighs three design factors, "(i) box shape, (ii)
//! merge rule, (iii) design of parent box"; here:
//!
//! - **Node shapes** ([`NodeShape`], [`Shape`]): axis-aligned boxes ([`crate::geometry::Aabb`]),
//!   the paper's all-, max- and min-principal-component boxes ([`pca::PcaBox`]), and the tribox
//!   of Crosnier and Rossignac ([`TriboxBounds`](crate::bounds::tribox::TriboxBounds)), which
//!   the paper did not have. Its pie slices are left out.
//! - **Merge rule** ([`Merge`]): sibling pairs are picked level by level, by smallest parent
//!   surface area (the paper's conclusion: "the average complexity of a query is minimized by
//!   simply choosing boxes that minimize the total surface area they occupy") or volume (its
//!   Table 1 is of "volume-directed hierarchies"); see [`tree`].
//! - **Parent box**: a bound that contains both children's bounds *exactly* (as point sets),
//!   so that, by induction, every node's bound contains every vertex of the triangles below it.
//!
//! Queries ([`ray`], [`collide`]) use the bounds only as conservative filters (floating point
//! with outward error bounds: they may report a meeting that does not happen, never miss one)
//! and decide triangles exactly with `orient3d` ([`tritri`], and the exact ray parameters of
//! [`ray`]). [`spheres`] reproduces the paper's Table 1 setting: pairs of concentric random
//! convex spheres and the number of bound-bound collision tests per shape.
//!
//! ```
//! use kepler::lab::boxtree::{BoxTree, Merge};
//! use kepler::geometry::{Aabb, Point3, Vector3};
//! use kepler::geometry::ray::Ray;
//! let cube = kepler::solids::cube(2.0).unwrap();
//! let tree: BoxTree<Aabb> = BoxTree::build(&cube, Merge::Area);
//! assert_eq!(tree.nodes().len(), 2 * 12 - 1);
//! let ray = Ray { origin: Point3::new(0.2, 0.3, -5.0), direction: Vector3::z() };
//! let shot = tree.first_hit(&ray);
//! assert_eq!(shot.hit.unwrap().point, Point3::new(0.2, 0.3, -1.0));
//! assert!(shot.visited <= tree.nodes().len());
//! ```

pub mod aabb;
pub mod collide;
mod hull;
pub mod pca;
pub mod ray;
pub mod slab;
pub mod spheres;
pub mod tree;
pub mod tribox_node;
pub mod tritri;

pub use collide::Collision;
pub use ray::{RayHit, RayShot};
pub use slab::RayProbe;
pub use spheres::{Row, paper_tests, sphere_experiment, sphere_pair};
pub use tree::{BoxTree, Node};

use crate::geometry::Point3;
use serde::Serialize;

/// The five node shapes, by the names the paper's methods and the command line use.
///
/// ```
/// use kepler::lab::boxtree::Shape;
/// assert_eq!(Shape::PcaMin.to_string(), "pca-min");
/// assert_eq!("tribox".parse::<Shape>(), Ok(Shape::Tribox));
/// assert_eq!(Shape::ALL.len(), 5);
/// assert_eq!(serde_json::to_string(&Shape::PcaAll).unwrap(), "\"pca-all\"");
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Shape {
    /// Axis-aligned boxes: "a bottom-up version of an R-tree".
    Aabb,
    /// All-principal-component boxes: the three principal components as the box's axes.
    PcaAll,
    /// Max-principal-component boxes: the largest principal component, then the minimum-area
    /// rectangle of the projection on the plane normal to it.
    PcaMax,
    /// Min-principal-component boxes: the smallest principal component, then the
    /// minimum-area rectangle of the projection on the plane normal to it.
    PcaMin,
    /// Triboxes (Crosnier and Rossignac 1999): slabs along 9 fixed directions.
    Tribox,
}

impl Shape {
    /// Every shape, in the order of the experiment's rows.
    ///
    /// ```
    /// assert_eq!(kepler::lab::boxtree::Shape::ALL[0], kepler::lab::boxtree::Shape::Aabb);
    /// ```
    pub const ALL: [Shape; 5] = [
        Shape::Aabb,
        Shape::PcaAll,
        Shape::PcaMax,
        Shape::PcaMin,
        Shape::Tribox,
    ];

    /// The shape's name: `aabb`, `pca-all`, `pca-max`, `pca-min` or `tribox`.
    ///
    /// ```
    /// assert_eq!(kepler::lab::boxtree::Shape::PcaMax.name(), "pca-max");
    /// ```
    pub fn name(self) -> &'static str {
        match self {
            Shape::Aabb => "aabb",
            Shape::PcaAll => "pca-all",
            Shape::PcaMax => "pca-max",
            Shape::PcaMin => "pca-min",
            Shape::Tribox => "tribox",
        }
    }
}

impl std::fmt::Display for Shape {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

/// A name that is not one of the five shapes.
///
/// ```
/// let e = "sphere".parse::<kepler::lab::boxtree::Shape>().unwrap_err();
/// assert_eq!(e.to_string(), "unknown shape 'sphere' (expected aabb, pca-all, pca-max, pca-min or tribox)");
/// ```
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("unknown shape '{0}' (expected aabb, pca-all, pca-max, pca-min or tribox)")]
pub struct UnknownShape(pub String);

impl std::str::FromStr for Shape {
    type Err = UnknownShape;

    fn from_str(s: &str) -> Result<Shape, UnknownShape> {
        Shape::ALL
            .into_iter()
            .find(|shape| shape.name() == s)
            .ok_or_else(|| UnknownShape(s.to_string()))
    }
}

/// Which measure of a candidate parent the merge rule minimises; the other breaks ties.
///
/// ```
/// use kepler::lab::boxtree::{Measures, Merge};
/// let flat = Measures { area: 2.0, volume: 0.0 };
/// let cube = Measures { area: 6.0, volume: 1.0 };
/// assert!(Merge::Area.key(&flat) < Merge::Area.key(&cube));
/// assert!(Merge::Volume.key(&flat) < Merge::Volume.key(&cube));
/// assert_eq!(Merge::Volume.to_string(), "volume");
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize)]
// The command line's --merge: its `--help` lists the values by name only, the paper's setting
// first.
#[cfg_attr(feature = "cli", derive(clap::ValueEnum))]
#[serde(rename_all = "kebab-case")]
pub enum Merge {
    /// Smallest parent volume (the paper's Table 1 setting).
    #[cfg_attr(feature = "cli", value(help = None::<&str>))]
    Volume,
    /// Smallest parent surface area (the paper's conclusion, by Cauchy's formula).
    #[cfg_attr(feature = "cli", value(help = None::<&str>))]
    Area,
}

impl Merge {
    /// The sort key of a candidate parent: (minimised measure, tie-breaking measure).
    ///
    /// ```
    /// use kepler::lab::boxtree::{Measures, Merge};
    /// assert_eq!(Merge::Volume.key(&Measures { area: 6.0, volume: 1.0 }), [1.0, 6.0]);
    /// ```
    pub fn key(self, m: &Measures) -> [f64; 2] {
        match self {
            Merge::Area => [m.area, m.volume],
            Merge::Volume => [m.volume, m.area],
        }
    }
}

impl std::fmt::Display for Merge {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            Merge::Area => "area",
            Merge::Volume => "volume",
        })
    }
}

/// Surface area and volume of a bound (floating point: they only rank candidates).
///
/// ```
/// use kepler::lab::boxtree::{Measures, NodeShape};
/// use kepler::geometry::{Aabb, Point3};
/// let b = Aabb::new(Point3::origin(), Point3::new(1.0, 2.0, 3.0));
/// assert_eq!(b.measures(), Measures { area: 22.0, volume: 6.0 });
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Measures {
    /// The surface area.
    pub area: f64,
    /// The volume.
    pub volume: f64,
}

/// A node shape: how a leaf's bound is made from its triangle, how a parent's bound is made
/// from its children's, and the conservative tests the queries run on bounds (after parry's
/// `BoundingVolume`).
///
/// Implementations guarantee, exactly: `leaf(t)` contains the three vertices of `t`, and
/// `parent(a, b)` contains every point of `a` and of `b`. The filters may err only one way:
/// [`ray_interval`](Self::ray_interval) and [`may_overlap`](Self::may_overlap) never say
/// "disjoint" for a bound the ray or the other bound meets.
///
/// ```
/// use kepler::lab::boxtree::NodeShape;
/// use kepler::bounds::tribox::TriboxBounds;
/// use kepler::geometry::Point3;
/// let t = [Point3::new(0.0, 0.0, 0.0), Point3::new(1.0, 0.0, 0.0), Point3::new(0.0, 1.0, 0.0)];
/// let u = [Point3::new(2.0, 2.0, 0.0), Point3::new(3.0, 2.0, 0.0), Point3::new(2.0, 3.0, 1.0)];
/// let (a, b) = (TriboxBounds::leaf(&t), TriboxBounds::leaf(&u));
/// let p = TriboxBounds::parent(&a, &b);
/// assert!(t.iter().chain(&u).all(|v| p.contains_point(v)));
/// assert!(!a.may_overlap(&b));
/// ```
pub trait NodeShape: Clone + Send + Sync + Sized {
    /// Which of the five shapes this is.
    const SHAPE: Shape;

    /// The bound of one triangle: contains its vertices exactly.
    fn leaf(triangle: &[Point3; 3]) -> Self;

    /// The bound of a parent: contains both children exactly.
    fn parent(a: &Self, b: &Self) -> Self;

    /// The measures of the parent [`parent`](Self::parent) would build, possibly estimated
    /// without its exact rounding: what the merge rule compares for candidate pairs.
    fn parent_measures(a: &Self, b: &Self) -> Measures {
        Self::parent(a, b).measures()
    }

    /// Surface area and volume.
    fn measures(&self) -> Measures;

    /// A point near the middle of the bound, for the neighbour search of the construction.
    fn center(&self) -> Point3;

    /// Whether `p` lies in the closed bound, decided exactly.
    fn contains_point(&self, p: &Point3) -> bool;

    /// An interval `[t0, t1]` of ray parameters (`t0 ≥ 0`) that contains every `t ≥ 0` at
    /// which the ray is in the bound, or `None` when the ray surely misses it.
    fn ray_interval(&self, ray: &RayProbe) -> Option<[f64; 2]>;

    /// Whether the two bounds may share a point: `false` only when they are surely disjoint.
    fn may_overlap(&self, other: &Self) -> bool;
}
