//! The paper's arbitrarily oriented boxes (section 3.2), built from principal components.
//!
//! "Given a pair of boxes, their 16 vertices are treated as a 3D population whose covariance
//! matrix is computed and diagonalized. [...] We investigated three methods for determining
//! the enclosing box, given the 16 vertices of a pair of child boxes:
//! 1. All-Principal-Component Box: We use the three principal components (ie, eigenvectors)
//!    as the three directions of the newly-built box. [...]
//! 2. Max-Principal-Component Box: We use the first principal component (the eigendirection
//!    that corresponds to the largest eigenvalue) as one direction. We then project the
//!    'population' (vertices of the input boxes) to a plane normal to that eigendirection. We
//!    find the minimum-area enclosing box in two dimensions. This box determines the other two
//!    directions of the resulting three-dimensional box.
//! 3. Min-Principal-Component Box: We use the shortest principal component (corresponding to
//!    the smallest eigenvalue) as one direction of the newly-built box. We then proceed as in
//!    the previous method."
//!
//! Leaves follow the paper too: "Smallest enclosing rectangles (turned into boxes of zero
//! thickness) can be used to cover each facet": the rectangle has a side along an edge of the
//! triangle (a minimum-area rectangle always has a side along the hull), and the box's third
//! axis is the triangle's normal. The all-principal-component box here is the tightest box
//! along its three directions; the paper centres it at the points' centre of mass, which can
//! only make it larger.
//!
//! # Exact containment
//! A box is kept as three slabs ([`OrientedBox`]) whose bounds are the exact extreme dot
//! products of its points rounded outward, so it contains them exactly. Its eight corners are
//! not doubles (the axes are orthonormal only up to rounding), so a parent cannot simply bound
//! its children's rounded corners. Instead each box also keeps an enclosing parallelepiped
//! `center ± half[0] ± half[1] ± half[2]`, certified once: its eight rounded corners each lie,
//! exactly, beyond the box's corner of the same signs on all three slabs (`a_j · p ≥ max_j`
//! where the corner takes the maximum of slab j, `≤ min_j` where it takes the minimum). In the
//! box's slab coordinates `y = A x` such points enclose the box `[min, max]` (a point of the
//! box cut off from their hull by a plane `w · y = c` would make the corner maximising `w`
//! lie beyond it, and so the point in that corner's orthant), and the linear map keeps hulls.
//! The parent is then the slabs of its children's 16 certified corners: it contains their
//! hulls, hence their boxes, exactly. The paper's population of 16 box vertices is exactly
//! these corners.
//!
//! # Nesting makes boxes grow
//! A parent contains its children's boxes (the paper's `box(v) ⊇ box(u1) ∪ box(u2)`), not
//! merely their triangles, so the slack of each level is carried into the next, and a box
//! turned against its children adds its own. On a 60 × 30 torus the min-principal-component
//! boxes at height 6 have 1.9 times the area of the box of their own triangles along the same
//! axes, and the root 15 times. The paper saw this ("The axis-parallel box method seems to be
//! the worst in the lower levels of the hierarchy although in the upper levels it is the best")
//! and switched to axis-aligned boxes in the upper levels of its experiments. Taking, per node,
//! the smaller of the two boxes of the 16 corners hardly helps (an axis-aligned box of swollen
//! children is as swollen), so the shapes here are the paper's three plain definitions.
//!
//! The overlap test is the separating-axis test (the 15 axes of two boxes) on the
//! parallelepipeds grown by the rounding of their corners, in floating point with an error
//! bound, so it never reports disjoint boxes that overlap.
//!
//! ```
//! use kepler::lab::boxtree::{NodeShape, pca::PcaMin};
//! use kepler::geometry::Point3;
//! let t = [Point3::new(0.0, 0.0, 0.0), Point3::new(2.0, 0.0, 0.0), Point3::new(1.0, 1.0, 0.0)];
//! let u = [Point3::new(0.0, 0.0, 1.0), Point3::new(2.0, 0.0, 1.0), Point3::new(1.0, 1.0, 1.0)];
//! let (a, b) = (PcaMin::leaf(&t), PcaMin::leaf(&u));
//! assert!(a.measures().volume < 1e-12); // a flat rectangle of area 2, counted on both sides
//! assert!((a.measures().area - 4.0).abs() < 1e-12);
//! let p = PcaMin::parent(&a, &b);
//! assert!(t.iter().chain(&u).all(|v| p.contains_point(v)));
//! assert!((p.measures().volume - 2.0).abs() < 1e-9); // the prism's 2 × 1 × 1 box
//! assert!(!a.may_overlap(&b));
//! ```

use super::slab::meet;
use super::{Measures, NodeShape, RayProbe, Shape};
use crate::geometry::exact::{product_terms, sum_sign};
use crate::geometry::{Point3, Vector3};
use crate::lab::oriented::OrientedBox;
use nalgebra::{Matrix3, SymmetricEigen};
use std::cmp::Ordering;
use std::marker::PhantomData;

/// Unit roundoff.
const U: f64 = f64::EPSILON / 2.0;

/// Which principal component fixes a box's first direction: one of the marker types [`All`],
/// [`Max`] and [`Min`].
///
/// ```
/// use kepler::lab::boxtree::{Shape, pca::{Max, Principal}};
/// assert_eq!(Max::SHAPE, Shape::PcaMax);
/// ```
pub trait Principal: Send + Sync + 'static {
    /// The shape of boxes built this way.
    const SHAPE: Shape;
}

/// All principal components as the box's directions.
///
/// ```
/// use kepler::lab::boxtree::pca::{All, Principal};
/// assert_eq!(All::SHAPE.name(), "pca-all");
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct All;

/// The largest principal component, then the minimum-area rectangle normal to it.
///
/// ```
/// use kepler::lab::boxtree::pca::{Max, Principal};
/// assert_eq!(Max::SHAPE.name(), "pca-max");
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Max;

/// The smallest principal component, then the minimum-area rectangle normal to it.
///
/// ```
/// use kepler::lab::boxtree::pca::{Min, Principal};
/// assert_eq!(Min::SHAPE.name(), "pca-min");
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Min;

impl Principal for All {
    const SHAPE: Shape = Shape::PcaAll;
}

impl Principal for Max {
    const SHAPE: Shape = Shape::PcaMax;
}

impl Principal for Min {
    const SHAPE: Shape = Shape::PcaMin;
}

/// All-principal-component boxes.
pub type PcaAll = PcaBox<All>;
/// Max-principal-component boxes.
pub type PcaMax = PcaBox<Max>;
/// Min-principal-component boxes.
pub type PcaMin = PcaBox<Min>;

/// A principal-component box: its slabs and a certified enclosing parallelepiped (see the
/// module documentation).
///
/// ```
/// use kepler::lab::boxtree::{NodeShape, pca::PcaAll};
/// use kepler::geometry::Point3;
/// let t = [Point3::new(0.1, 0.2, 0.3), Point3::new(1.7, -0.4, 0.9), Point3::new(-0.3, 1.1, 2.0)];
/// let b = PcaAll::leaf(&t);
/// assert!(t.iter().all(|v| b.oriented().contains_point(v)));
/// assert_eq!(b.corners().len(), 8);
/// ```
#[derive(Debug)]
pub struct PcaBox<P> {
    obb: OrientedBox,
    hull: Parallelepiped,
    rule: PhantomData<fn() -> P>,
}

// By hand: a derive would ask the marker `P` to be `Clone` and `Copy` too.
impl<P> Clone for PcaBox<P> {
    fn clone(&self) -> Self {
        *self
    }
}

impl<P> Copy for PcaBox<P> {}

/// `center + Σ αₖ half[k]` for `|αₖ| ≤ 1`, grown by `slack` along each coordinate.
#[derive(Debug, Clone, Copy)]
struct Parallelepiped {
    center: Point3,
    half: [Vector3; 3],
    slack: f64,
}

impl<P: Principal> PcaBox<P> {
    /// The box as slabs.
    ///
    /// ```
    /// use kepler::lab::boxtree::{NodeShape, pca::PcaMax};
    /// use kepler::geometry::Point3;
    /// let t = [Point3::new(0.0, 0.0, 0.0), Point3::new(3.0, 0.0, 0.0), Point3::new(0.0, 4.0, 0.0)];
    /// let e = PcaMax::leaf(&t).oriented().extents();
    /// assert!((e[0] * e[1] - 12.0).abs() < 1e-12); // the 3 × 4 rectangle along the legs
    /// ```
    pub fn oriented(&self) -> &OrientedBox {
        &self.obb
    }

    /// Eight points whose convex hull contains the box, exactly: the certified corners a
    /// parent bounds (the paper's "16 vertices of a pair of child boxes").
    ///
    /// ```
    /// use kepler::lab::boxtree::{NodeShape, pca::PcaMin};
    /// use kepler::geometry::Point3;
    /// let t = [Point3::new(0.0, 0.0, 0.0), Point3::new(1.0, 0.0, 0.0), Point3::new(0.0, 1.0, 0.0)];
    /// let b = PcaMin::leaf(&t);
    /// // A rectangle of area 1 (twice the triangle's) in the plane z = 0, a hair thick.
    /// let e = b.oriented().extents();
    /// assert!((e[0] * e[1] - 1.0).abs() < 1e-12 && e[2] < 1e-15);
    /// assert!(b.corners().iter().all(|c| c.z.abs() < 1e-12));
    /// ```
    pub fn corners(&self) -> [Point3; 8] {
        self.hull.corners()
    }

    fn from_box(obb: OrientedBox) -> PcaBox<P> {
        PcaBox {
            obb,
            hull: enclose(&obb),
            rule: PhantomData,
        }
    }

    /// The 16 certified corners of two boxes.
    fn population(a: &PcaBox<P>, b: &PcaBox<P>) -> [Point3; 16] {
        let (ca, cb) = (a.corners(), b.corners());
        std::array::from_fn(|i| if i < 8 { ca[i] } else { cb[i - 8] })
    }
}

impl<P: Principal> NodeShape for PcaBox<P> {
    const SHAPE: Shape = P::SHAPE;

    fn leaf(triangle: &[Point3; 3]) -> PcaBox<P> {
        PcaBox::from_box(OrientedBox::from_points(leaf_axes(triangle), triangle))
    }

    fn parent(a: &PcaBox<P>, b: &PcaBox<P>) -> PcaBox<P> {
        let points = PcaBox::population(a, b);
        PcaBox::from_box(OrientedBox::from_points(axes(P::SHAPE, &points), &points))
    }

    fn parent_measures(a: &PcaBox<P>, b: &PcaBox<P>) -> Measures {
        let points = PcaBox::population(a, b);
        let [x, y, z] = axes(P::SHAPE, &points).map(|axis| {
            let (lo, hi) = points
                .iter()
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), p| {
                    let d = axis.dot(&p.coords);
                    (lo.min(d), hi.max(d))
                });
            hi - lo
        });
        Measures {
            area: 2.0 * (x * y + y * z + z * x),
            volume: x * y * z,
        }
    }

    fn measures(&self) -> Measures {
        Measures {
            area: self.obb.surface_area(),
            volume: self.obb.volume(),
        }
    }

    fn center(&self) -> Point3 {
        self.hull.center
    }

    fn contains_point(&self, p: &Point3) -> bool {
        self.obb.contains_point(p)
    }

    fn ray_interval(&self, ray: &RayProbe) -> Option<[f64; 2]> {
        let b = &self.obb;
        meet((0..3).map(|k| ray.along(&b.axes[k]).interval(b.min[k], b.max[k])))
    }

    fn may_overlap(&self, other: &PcaBox<P>) -> bool {
        let (a, b) = (&self.obb.axes, &other.obb.axes);
        let d = other.hull.center - self.hull.center;
        let face_axes = a.iter().chain(b.iter()).copied();
        let edge_axes = a.iter().flat_map(|x| b.iter().map(move |y| x.cross(y)));
        !face_axes
            .chain(edge_axes)
            .any(|axis| separates(&axis, &self.hull, &other.hull, &d))
    }
}

/// Whether `axis` separates the parallelepipeds, certified: the distance between their
/// centres' projections exceeds the sum of their radii by more than a bound on the rounding
/// of all the dot products and sums involved (`d` is the rounded difference of the centres).
fn separates(axis: &Vector3, a: &Parallelepiped, b: &Parallelepiped, d: &Vector3) -> bool {
    let abs = axis.abs();
    let radius = |p: &Parallelepiped| {
        p.half.iter().map(|h| axis.dot(h).abs()).sum::<f64>() + p.slack * abs.sum()
    };
    let magnitude = abs.dot(&(a.center.coords.abs() + b.center.coords.abs()))
        + a.half
            .iter()
            .chain(&b.half)
            .map(|h| abs.dot(&h.abs()))
            .sum::<f64>()
        + (a.slack + b.slack) * abs.sum();
    let gap = axis.dot(d).abs() - (radius(a) + radius(b));
    gap > 32.0 * U * magnitude + f64::MIN_POSITIVE
}

impl Parallelepiped {
    /// The eight corners, corner `s` taking `+half[k]` when bit `k` of `s` is set; always
    /// computed the same way, so always the same doubles.
    fn corners(&self) -> [Point3; 8] {
        std::array::from_fn(|s| {
            let pick = |k: usize| {
                if s & (1 << k) != 0 {
                    self.half[k]
                } else {
                    -self.half[k]
                }
            };
            self.center + pick(0) + pick(1) + pick(2)
        })
    }
}

/// A parallelepiped whose rounded corners each lie beyond the box's corner of the same signs,
/// exactly (see the module documentation), with the slack of that rounding: the half extents
/// are padded until the corners certify (at once in practice: the pad starts far above the
/// rounding of the corners and of the axes' orthogonality).
fn enclose(b: &OrientedBox) -> Parallelepiped {
    let scale = (0..3)
        .map(|k| b.min[k].abs().max(b.max[k].abs()))
        .fold(f64::MIN_POSITIVE, f64::max);
    let mid: [f64; 3] = std::array::from_fn(|k| 0.5 * b.min[k] + 0.5 * b.max[k]);
    let half: [f64; 3] = std::array::from_fn(|k| (0.5 * b.max[k] - 0.5 * b.min[k]).max(0.0));
    let center = Point3::from(b.axes[0] * mid[0] + b.axes[1] * mid[1] + b.axes[2] * mid[2]);
    // Far above the corners' rounding (a few ulps of the scale), so that the filter of
    // `beyond` decides at once; still only 2⁻⁴² of the scale.
    let mut pad = scale * 2f64.powi(-42);
    loop {
        let p = Parallelepiped {
            center,
            half: std::array::from_fn(|k| b.axes[k] * (half[k] + pad)),
            slack: 0.0,
        };
        let corners = p.corners();
        let certified = !pad.is_finite()
            || corners.iter().enumerate().all(|(s, c)| {
                (0..3).all(|j| {
                    let above = s & (1 << j) != 0;
                    beyond(
                        &b.axes[j],
                        c,
                        if above { b.max[j] } else { b.min[j] },
                        above,
                    )
                })
            });
        if certified {
            let reach = (0..3)
                .map(|i| p.center[i].abs() + p.half.iter().map(|h| h[i].abs()).sum::<f64>())
                .fold(0.0, f64::max);
            return Parallelepiped {
                slack: if pad.is_finite() {
                    4.0 * U * reach + f64::MIN_POSITIVE
                } else {
                    f64::INFINITY
                },
                ..p
            };
        }
        pad *= 4.0;
    }
}

/// Whether `a · p ≥ bound` (`above`) or `a · p ≤ bound`, exactly (a floating-point filter
/// first, then the exact sign of the sum of the products' exact terms).
fn beyond(a: &Vector3, p: &Point3, bound: f64, above: bool) -> bool {
    let value = a.dot(&p.coords) - bound;
    let magnitude = a.abs().dot(&p.coords.abs()) + bound.abs();
    let error = 8.0 * U * magnitude + f64::MIN_POSITIVE;
    let sign = if value > error {
        Ordering::Greater
    } else if value < -error {
        Ordering::Less
    } else {
        let mut terms = Vec::with_capacity(7);
        for i in 0..3 {
            product_terms(&[a[i]], &[p[i]], &mut terms);
        }
        terms.push(-bound);
        sum_sign(&terms)
    };
    if above {
        sign != Ordering::Less
    } else {
        sign != Ordering::Greater
    }
}

/// The leaf's axes: the minimum-area rectangle of the triangle in its plane (a side along one
/// of its edges) and its normal; a degenerate triangle takes its principal components.
fn leaf_axes(t: &[Point3; 3]) -> [Vector3; 3] {
    let normal = (t[1] - t[0]).cross(&(t[2] - t[0]));
    let n = normal.norm();
    if !(n.is_finite() && n > 0.0) {
        return axes(Shape::PcaAll, t);
    }
    let normal = normal / n;
    (0..3)
        .filter_map(|i| {
            let e = (t[(i + 1) % 3] - t[i]).try_normalize(0.0)?;
            let m = normal.cross(&e);
            let width = |a: &Vector3| {
                let d = t.map(|p| a.dot(&p.coords));
                d.iter().fold(f64::NEG_INFINITY, |x, &y| x.max(y))
                    - d.iter().fold(f64::INFINITY, |x, &y| x.min(y))
            };
            Some((width(&e) * width(&m), [e, m, normal]))
        })
        .min_by(|a, b| a.0.total_cmp(&b.0))
        .map_or_else(|| axes(Shape::PcaAll, t), |(_, a)| a)
}

/// The box's axes for a population of points by the paper's rule for `shape` (floating
/// point: any axes give a box that contains the points; these are the small ones).
fn axes(shape: Shape, points: &[Point3]) -> [Vector3; 3] {
    let [small, middle, large] = principal_components(points);
    match shape {
        Shape::PcaMax => with_rectangle(large, [middle, small], points),
        Shape::PcaMin => with_rectangle(small, [large, middle], points),
        _ => frame(large, middle),
    }
}

/// The eigenvectors of the points' covariance matrix, by increasing eigenvalue.
fn principal_components(points: &[Point3]) -> [Vector3; 3] {
    let n = points.len().max(1) as f64;
    let mean = points.iter().fold(Vector3::zeros(), |s, p| s + p.coords) / n;
    let covariance = points.iter().fold(Matrix3::zeros(), |c, p| {
        let d = p.coords - mean;
        c + d * d.transpose()
    });
    let eigen = SymmetricEigen::new(covariance);
    let mut order = [0, 1, 2];
    order.sort_by(|&i, &j| eigen.eigenvalues[i].total_cmp(&eigen.eigenvalues[j]));
    order.map(|i| eigen.eigenvectors.column(i).into_owned())
}

/// A right-handed orthonormal frame whose first axis is along `first` and second in the plane
/// of `first` and `second` (Gram–Schmidt), or the coordinate axes when they are degenerate.
fn frame(first: Vector3, second: Vector3) -> [Vector3; 3] {
    let fallback = [Vector3::x(), Vector3::y(), Vector3::z()];
    let Some(a) = first.try_normalize(0.0) else {
        return fallback;
    };
    let helper = if a.x.abs() < 0.9 {
        Vector3::x()
    } else {
        Vector3::y()
    };
    let b = (second - a * a.dot(&second))
        .try_normalize(f64::EPSILON)
        .or_else(|| a.cross(&helper).try_normalize(0.0));
    match b {
        Some(b) if b.iter().all(|c| c.is_finite()) => [a, b, a.cross(&b)],
        _ => fallback,
    }
}

/// A frame whose first axis is `axis` and whose other two are the sides of the minimum-area
/// rectangle enclosing the points projected on the plane spanned by `plane`.
fn with_rectangle(axis: Vector3, plane: [Vector3; 2], points: &[Point3]) -> [Vector3; 3] {
    let [a, u, _] = frame(axis, plane[0]);
    let v = a.cross(&u);
    let projected: Vec<[f64; 2]> = points
        .iter()
        .map(|p| [u.dot(&p.coords), v.dot(&p.coords)])
        .collect();
    let [c, s] = min_area_rectangle(&projected);
    frame(a, u * c + v * s)
}

/// The direction (a unit vector) of a side of the minimum-area rectangle enclosing the plane
/// points: a side lies along an edge of their convex hull (Freeman and Shapira 1975), so each
/// hull edge is tried. Written by hand: 16 points at most, and geo's rotating calipers work
/// on its own polygon types.
fn min_area_rectangle(points: &[[f64; 2]]) -> [f64; 2] {
    let hull = convex_hull_2d(points);
    let mut best = ([1.0, 0.0], f64::INFINITY);
    for i in 0..hull.len() {
        let (p, q) = (hull[i], hull[(i + 1) % hull.len()]);
        let (dx, dy) = (q[0] - p[0], q[1] - p[1]);
        let len = dx.hypot(dy);
        if !(len > 0.0 && len.is_finite()) {
            continue;
        }
        let (ex, ey) = (dx / len, dy / len);
        let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
        for r in &hull {
            let d = [r[0] * ex + r[1] * ey, r[1] * ex - r[0] * ey];
            for k in 0..2 {
                lo[k] = lo[k].min(d[k]);
                hi[k] = hi[k].max(d[k]);
            }
        }
        let area = (hi[0] - lo[0]) * (hi[1] - lo[1]);
        if area < best.1 {
            best = ([ex, ey], area);
        }
    }
    best.0
}

/// The convex hull of plane points (Andrew's monotone chain, floating point: it only picks
/// candidate directions), counter-clockwise.
fn convex_hull_2d(points: &[[f64; 2]]) -> Vec<[f64; 2]> {
    let mut p: Vec<[f64; 2]> = points.to_vec();
    p.sort_by(|a, b| a[0].total_cmp(&b[0]).then(a[1].total_cmp(&b[1])));
    p.dedup();
    if p.len() < 3 {
        return p;
    }
    let cross = |o: [f64; 2], a: [f64; 2], b: [f64; 2]| {
        (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0])
    };
    let mut hull: Vec<[f64; 2]> = Vec::with_capacity(2 * p.len());
    // The lower chain left to right, then the upper chain right to left; each drops its last
    // point, the first of the other.
    let mut chain = |points: &mut dyn Iterator<Item = [f64; 2]>| {
        let start = hull.len();
        for q in points {
            while hull.len() >= start + 2
                && cross(hull[hull.len() - 2], hull[hull.len() - 1], q) <= 0.0
            {
                hull.pop();
            }
            hull.push(q);
        }
        hull.pop();
    };
    chain(&mut p.iter().copied());
    chain(&mut p.iter().rev().copied());
    hull
}
