//! An R-tree (rstar) over the triangles of a mesh, for the queries the bounds need: triangles
//! near a box, triangles above a point, and the nearest triangle.
//!
//! The tree holds the triangles' boxes scaled by a power of two when the mesh's coordinates are
//! very large or very small, so that the squared distances rstar computes neither overflow
//! (into infinities whose differences are NaN, which its nearest-neighbour search cannot
//! order) nor underflow; the boxes are rounded outward where the scaling is not exact, and
//! every query is scaled the same way, so the answers are the same triangles.

use super::Mesh;
use super::build::{largest_coordinate, normalising_exponent, times_power_of_two};
use crate::geometry::{Aabb, Point3, Vector3};
use rstar::{AABB, PointDistance, RTree, RTreeObject, SelectionFunction};

/// Coordinates below `2^SAFE` in magnitude (and not too small) are used as they are: the
/// fourth powers in the distances stay finite and normal.
const SAFE: i32 = 200;

/// One triangle of the mesh in the tree: its index in [`Mesh::triangles`], corners, and box
/// in the tree's scaled coordinates (kept, not recomputed: bulk loading asks for it at every
/// comparison of its sorts).
#[derive(Debug, Clone, Copy)]
struct Entry {
    index: usize,
    corners: [Point3; 3],
    envelope: AABB<[f64; 3]>,
    exponent: i32,
}

impl Entry {
    fn new(index: usize, corners: [Point3; 3], exponent: i32) -> Entry {
        let b = scaled_box(&Aabb::from_points(&corners), exponent);
        Entry {
            index,
            corners,
            envelope: AABB::from_corners(b.min, b.max),
            exponent,
        }
    }
}

/// `x · 2^e` rounded down (`up` false) or up, exactly when it can be.
fn scaled_toward(x: f64, e: i32, up: bool) -> f64 {
    let y = times_power_of_two(x, e);
    let back = times_power_of_two(y, -e);
    match (back == x, up) {
        (true, _) => y,
        (false, false) if back > x => y.next_down(),
        (false, true) if back < x => y.next_up(),
        _ => y,
    }
}

/// The box `b` scaled by `2^e`, rounded outward (so it still holds what `b` holds).
fn scaled_box(b: &Aabb, e: i32) -> Aabb {
    if e == 0 {
        return *b;
    }
    Aabb {
        min: b.min.map(|x| scaled_toward(x, e, false)),
        max: b.max.map(|x| scaled_toward(x, e, true)),
    }
}

impl RTreeObject for Entry {
    type Envelope = AABB<[f64; 3]>;
    fn envelope(&self) -> Self::Envelope {
        self.envelope
    }
}

impl PointDistance for Entry {
    /// The squared distance from `p` (in the tree's scaled coordinates) to the triangle,
    /// rounded.
    fn distance_2(&self, p: &[f64; 3]) -> f64 {
        let corners = self
            .corners
            .map(|c| c.map(|x| times_power_of_two(x, self.exponent)));
        let q = closest_point_on_triangle(&Point3::from(*p), &corners);
        (q - Point3::from(*p)).norm_squared()
    }
}

/// The triangles of a mesh in a bulk-loaded R-tree.
///
/// ```
/// use kepler::{mesh::TriangleTree, geometry::{Aabb, Point3}};
/// let cube = kepler::solids::cube(2.0).unwrap();
/// let tree = TriangleTree::new(&cube);
/// let near_top = Aabb::new(Point3::new(-0.1, -0.1, 0.9), Point3::new(0.1, 0.1, 1.1));
/// assert_eq!(tree.in_box(&near_top).count(), 2);
/// assert!((tree.distance(&Point3::origin()) - 1.0).abs() < 1e-15);
/// ```
#[derive(Debug)]
pub struct TriangleTree {
    tree: RTree<Entry>,
    /// The tree's coordinates are the mesh's times `2^exponent`.
    exponent: i32,
}

impl TriangleTree {
    /// Bulk-loads the triangles of `mesh`.
    ///
    /// ```
    /// let t = kepler::mesh::TriangleTree::new(&kepler::solids::cube(1.0).unwrap());
    /// assert_eq!(t.len(), 12);
    /// ```
    pub fn new(mesh: &Mesh) -> TriangleTree {
        let exponent = normalising_exponent(largest_coordinate(mesh.vertices()), SAFE);
        let entries = (0..mesh.triangles().len())
            .map(|index| Entry::new(index, mesh.triangle(index), exponent))
            .collect();
        TriangleTree {
            tree: RTree::bulk_load(entries),
            exponent,
        }
    }

    /// Number of triangles.
    ///
    /// ```
    /// let t = kepler::mesh::TriangleTree::new(&kepler::solids::tetrahedron(1.0).unwrap());
    /// assert_eq!(t.len(), 4);
    /// ```
    pub fn len(&self) -> usize {
        self.tree.size()
    }

    /// Whether the tree holds no triangle.
    ///
    /// ```
    /// let t = kepler::mesh::TriangleTree::new(&kepler::solids::tetrahedron(1.0).unwrap());
    /// assert!(!t.is_empty());
    /// ```
    pub fn is_empty(&self) -> bool {
        self.tree.size() == 0
    }

    /// Triangles (index and corners) whose bounding boxes meet the closed box `b`.
    ///
    /// ```
    /// use kepler::{mesh::TriangleTree, geometry::{Aabb, Point3}};
    /// let t = TriangleTree::new(&kepler::solids::cube(2.0).unwrap());
    /// let inside = Aabb::new(Point3::new(-0.5, -0.5, -0.5), Point3::new(0.5, 0.5, 0.5));
    /// assert_eq!(t.in_box(&inside).count(), 0);
    /// ```
    pub fn in_box(&self, b: &Aabb) -> impl Iterator<Item = (usize, [Point3; 3])> + use<> {
        let b = scaled_box(b, self.exponent);
        let envelope = AABB::from_corners(b.min, b.max);
        let found: Vec<_> = self
            .tree
            .locate_in_envelope_intersecting(&envelope)
            .map(|e| (e.index, e.corners))
            .collect();
        found.into_iter()
    }

    /// Triangles whose bounding boxes meet the vertical ray from `p` upward (`p` included).
    ///
    /// ```
    /// use kepler::{mesh::TriangleTree, geometry::Point3};
    /// let t = TriangleTree::new(&kepler::solids::cube(2.0).unwrap());
    /// assert_eq!(t.above(&Point3::new(0.2, 0.3, 0.0)).count(), 2);
    /// ```
    pub fn above(&self, p: &Point3) -> impl Iterator<Item = (usize, [Point3; 3])> + use<> {
        self.in_box(&Aabb::new(*p, Point3::new(p.x, p.y, f64::MAX)))
    }

    /// Triangles (index and corners) whose bounding boxes pass `meets`, found lazily. `meets`
    /// is asked about the tree's inner boxes too, so it must accept every box that meets the
    /// region searched (a conservative test is fine: the caller tests the triangles exactly).
    ///
    /// ```
    /// use kepler::{mesh::TriangleTree, geometry::{Aabb, Point3}};
    /// let t = TriangleTree::new(&kepler::solids::cube(2.0).unwrap());
    /// // Boxes reaching above z = 0.5: the top face's two triangles and the four sides' eight.
    /// assert_eq!(t.select(|b: &Aabb| b.max[2] > 0.5).count(), 10);
    /// ```
    pub fn select<'a, F>(&'a self, meets: F) -> impl Iterator<Item = (usize, [Point3; 3])> + 'a
    where
        F: Fn(&Aabb) -> bool + 'a,
    {
        self.tree
            .locate_with_selection_function(BoxTest(meets, self.exponent))
            .map(|e| (e.index, e.corners))
    }

    /// The distance from `p` to the nearest triangle (rounded, for heuristics only), or
    /// infinity for an empty tree.
    ///
    /// ```
    /// use kepler::{mesh::TriangleTree, geometry::Point3};
    /// let t = TriangleTree::new(&kepler::solids::cube(2.0).unwrap());
    /// assert!((t.distance(&Point3::new(0.5, 0.0, 0.0)) - 0.5).abs() < 1e-15);
    /// ```
    pub fn distance(&self, p: &Point3) -> f64 {
        let q = p
            .coords
            .map(|x| times_power_of_two(x, self.exponent))
            .into();
        self.tree.nearest_neighbor(&q).map_or(f64::INFINITY, |e| {
            times_power_of_two(e.distance_2(&q).sqrt(), -self.exponent)
        })
    }
}

/// An rstar selection function from a test on boxes (in the mesh's coordinates: the tree's
/// scaled by `2^-exponent`, rounded outward).
struct BoxTest<F>(F, i32);

impl<F: Fn(&Aabb) -> bool> SelectionFunction<Entry> for BoxTest<F> {
    fn should_unpack_parent(&self, envelope: &AABB<[f64; 3]>) -> bool {
        let b = Aabb {
            min: envelope.lower(),
            max: envelope.upper(),
        };
        (self.0)(&scaled_box(&b, -self.1))
    }

    fn should_unpack_leaf(&self, leaf: &Entry) -> bool {
        self.should_unpack_parent(&leaf.envelope())
    }
}

/// The point of triangle `t` closest to `p` (Ericson, *Real-Time Collision Detection* §5.1.5),
/// in rounded arithmetic.
fn closest_point_on_triangle(p: &Point3, t: &[Point3; 3]) -> Point3 {
    let [a, b, c] = *t;
    let (ab, ac, ap): (Vector3, Vector3, Vector3) = (b - a, c - a, p - a);
    let (d1, d2) = (ab.dot(&ap), ac.dot(&ap));
    if d1 <= 0.0 && d2 <= 0.0 {
        return a;
    }
    let bp = p - b;
    let (d3, d4) = (ab.dot(&bp), ac.dot(&bp));
    if d3 >= 0.0 && d4 <= d3 {
        return b;
    }
    let vc = d1 * d4 - d3 * d2;
    if vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0 {
        return a + ab * (d1 / (d1 - d3));
    }
    let cp = p - c;
    let (d5, d6) = (ab.dot(&cp), ac.dot(&cp));
    if d6 >= 0.0 && d5 <= d6 {
        return c;
    }
    let vb = d5 * d2 - d1 * d6;
    if vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0 {
        return a + ac * (d2 / (d2 - d6));
    }
    let va = d3 * d6 - d5 * d4;
    if va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0 {
        return b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)));
    }
    let denom = va + vb + vc;
    if denom == 0.0 {
        return a;
    }
    a + ab * (vb / denom) + ac * (vc / denom)
}
