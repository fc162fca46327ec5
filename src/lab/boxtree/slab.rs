//! A ray against slabs `lo ≤ a · x ≤ hi`, conservatively: the parameters at which the ray is
//! inside a slab, enclosed by an interval computed with outward rounding.
//!
//! Every bound of the hierarchy is an intersection of slabs (an axis-aligned box of three, an
//! oriented box of three, a tribox of nine), so the ray meets it exactly when the intervals of
//! its slabs overlap at some `t ≥ 0`, and enclosing each interval makes the test conservative:
//! it may report a bound met that the exact ray misses, never the reverse. (The hierarchy's
//! own filter `sight::line` does this for axis-aligned boxes only, with a relative margin;
//! the slabs of oriented boxes have rounded directions, so here the projections `a · o` and
//! `a · u` carry explicit error bounds and each quotient is rounded outward.)
//!
//! ```
//! use kepler::lab::boxtree::RayProbe;
//! use kepler::geometry::{Point3, Vector3};
//! use kepler::geometry::ray::Ray;
//! let probe = RayProbe::new(&Ray { origin: Point3::origin(), direction: Vector3::new(3.0, 0.0, 0.0) }).unwrap();
//! // The direction is rescaled by a power of two (exactly) to have its largest component in [1, 2).
//! assert_eq!(probe.ray().direction.x, 1.5);
//! let [t0, t1] = probe.along(&Vector3::x()).interval(1.5, 3.0);
//! assert!(t0 <= 1.0 && 1.0 - t0 < 1e-14 && t1 >= 2.0 && t1 - 2.0 < 1e-14);
//! ```

use crate::geometry::Vector3;
use crate::geometry::exact::{
    add_round_down, add_round_up, product_terms, sum_sign, two_sum, unit_scaled,
};
use crate::geometry::ray::Ray;
use std::cmp::Ordering;

/// The unit roundoff.
const U: f64 = f64::EPSILON / 2.0;

/// Relative error bound of a three-term dot product with its magnitude (γ₃ rounded up).
const DOT_ERROR: f64 = 4.0 * U;

/// The whole line of parameters.
const FULL: [f64; 2] = [f64::NEG_INFINITY, f64::INFINITY];
/// No parameter.
const EMPTY: [f64; 2] = [f64::INFINITY, f64::NEG_INFINITY];

/// A ray prepared for slab tests: the ray (its direction rescaled by a power of two, which
/// changes no exact answer), and its projections on the tribox's nine fixed directions.
///
/// ```
/// use kepler::lab::boxtree::RayProbe;
/// use kepler::geometry::{Point3, Vector3};
/// use kepler::geometry::ray::Ray;
/// assert!(RayProbe::new(&Ray { origin: Point3::origin(), direction: Vector3::zeros() }).is_none());
/// let p = RayProbe::new(&Ray { origin: Point3::new(1.0, 2.0, 3.0), direction: Vector3::z() }).unwrap();
/// assert_eq!(p.ray().origin, Point3::new(1.0, 2.0, 3.0));
/// ```
#[derive(Debug, Clone, Copy)]
pub struct RayProbe {
    ray: Ray,
    fixed: [SlabProjection; 9],
}

impl RayProbe {
    /// Prepares `ray`; `None` when its direction is zero or a coordinate is not finite (such
    /// a ray meets nothing).
    ///
    /// ```
    /// use kepler::lab::boxtree::RayProbe;
    /// use kepler::geometry::{Point3, Vector3};
    /// use kepler::geometry::ray::Ray;
    /// let r = Ray { origin: Point3::origin(), direction: Vector3::new(f64::NAN, 0.0, 1.0) };
    /// assert!(RayProbe::new(&r).is_none());
    /// ```
    pub fn new(ray: &Ray) -> Option<RayProbe> {
        let finite = ray
            .origin
            .iter()
            .chain(ray.direction.iter())
            .all(|c| c.is_finite());
        if !finite || ray.direction == Vector3::zeros() {
            return None;
        }
        let scaled = Vector3::from(unit_scaled(ray.direction.into()));
        // Keep the rescaled direction only when it is exact (no component underflowed): the
        // same ratios between components.
        let k = scaled.amax() / ray.direction.amax();
        let direction = if scaled
            .iter()
            .zip(ray.direction.iter())
            .all(|(s, u)| *s == u * k)
        {
            scaled
        } else {
            ray.direction
        };
        let ray = Ray {
            origin: ray.origin,
            direction,
        };
        let fixed = std::array::from_fn(|d| SlabProjection::fixed(d, &ray));
        Some(RayProbe { ray, fixed })
    }

    /// The ray the probe tests: the given origin, the direction rescaled by a power of two.
    ///
    /// ```
    /// use kepler::lab::boxtree::RayProbe;
    /// use kepler::geometry::{Point3, Vector3};
    /// use kepler::geometry::ray::Ray;
    /// let p = RayProbe::new(&Ray { origin: Point3::origin(), direction: Vector3::new(0.0, 0.25, 0.0) }).unwrap();
    /// assert_eq!(p.ray().direction, Vector3::y());
    /// ```
    pub fn ray(&self) -> &Ray {
        &self.ray
    }

    /// The projection on tribox direction `d` (0, 1, 2 are x, y, z; see
    /// [`TriboxBounds::DIRECTIONS`](crate::bounds::tribox::TriboxBounds::DIRECTIONS)).
    ///
    /// ```
    /// use kepler::lab::boxtree::RayProbe;
    /// use kepler::geometry::{Point3, Vector3};
    /// use kepler::geometry::ray::Ray;
    /// let p = RayProbe::new(&Ray { origin: Point3::new(1.0, 0.0, 0.0), direction: Vector3::y() }).unwrap();
    /// let [t0, t1] = p.fixed(3).interval(2.0, 3.0); // x + y from 2 to 3
    /// assert!(t0 <= 1.0 && t0 > 0.999 && t1 >= 2.0 && t1 < 2.001);
    /// ```
    pub fn fixed(&self, d: usize) -> &SlabProjection {
        &self.fixed[d % 9]
    }

    /// The projection on an arbitrary direction `a`.
    ///
    /// ```
    /// use kepler::lab::boxtree::RayProbe;
    /// use kepler::geometry::{Point3, Vector3};
    /// use kepler::geometry::ray::Ray;
    /// let p = RayProbe::new(&Ray { origin: Point3::origin(), direction: Vector3::x() }).unwrap();
    /// // Parallel to the slab 1 ≤ y ≤ 2 and outside it: never inside.
    /// let [t0, t1] = p.along(&Vector3::y()).interval(1.0, 2.0);
    /// assert!(t0 > t1);
    /// ```
    pub fn along(&self, a: &Vector3) -> SlabProjection {
        SlabProjection::along(a, &self.ray)
    }
}

/// The projections `s = a · origin` and `w = a · direction` of a ray on a direction: `s`
/// with a bound on its error, and `1/|w|` enclosed by two doubles (or `w` known to be zero,
/// or possibly zero), so that a slab costs two rounded subtractions and two products.
///
/// ```
/// use kepler::lab::boxtree::RayProbe;
/// use kepler::geometry::{Point3, Vector3};
/// use kepler::geometry::ray::Ray;
/// let p = RayProbe::new(&Ray { origin: Point3::origin(), direction: Vector3::new(1.0, 1.0, 0.0) }).unwrap();
/// let [t0, t1] = p.along(&Vector3::new(0.6, 0.8, 0.0)).interval(1.4, 2.8);
/// assert!(t0 <= 1.0 && t1 >= 2.0);
/// ```
#[derive(Debug, Clone, Copy)]
pub struct SlabProjection {
    s: f64,
    es: f64,
    slope: Slope,
}

/// The sign of `w = a · direction` and bounds `[lo, hi]` on `1/|w|`.
#[derive(Debug, Clone, Copy)]
enum Slope {
    /// `w > 0`.
    Forward([f64; 2]),
    /// `w < 0`.
    Backward([f64; 2]),
    /// `w = 0` exactly.
    Parallel,
    /// `w` may be zero, or a projection is not finite: the slab holds the whole line.
    Unknown,
}

impl SlabProjection {
    /// From `s`, `w` and bounds on their errors; `w_zero` says whether `w` is exactly zero
    /// (consulted only when `|w| ≤ ew`).
    fn new(s: f64, es: f64, w: f64, ew: f64, w_zero: impl FnOnce() -> bool) -> SlabProjection {
        let slope = if ![s, es, w, ew].iter().all(|v| v.is_finite()) {
            Slope::Unknown
        } else if w.abs() <= ew {
            if w_zero() {
                Slope::Parallel
            } else {
                Slope::Unknown
            }
        } else {
            // |w| in [m - ew, m + ew], rounded outward, then 1/|w| rounded outward.
            let m = w.abs();
            let (w_lo, w_hi) = (add_round_down(m, -ew), add_round_up(m, ew));
            let r = [(1.0 / w_hi).next_down(), (1.0 / w_lo).next_up()];
            if w > 0.0 {
                Slope::Forward(r)
            } else {
                Slope::Backward(r)
            }
        };
        SlabProjection { s, es, slope }
    }

    /// Along a fixed tribox direction: exact for the axes; for the diagonals the sums' exact
    /// errors (TwoSum) are the bounds, and a rounded `w` is zero only when the exact one is.
    fn fixed(d: usize, ray: &Ray) -> SlabProjection {
        let (o, u) = (&ray.origin, &ray.direction);
        if d < 3 {
            return SlabProjection::new(o[d], 0.0, u[d], 0.0, || u[d] == 0.0);
        }
        let dir = crate::bounds::tribox::TriboxBounds::DIRECTIONS[d];
        let (i, j) = match d {
            3 => (0, 1),
            4 => (0, 2),
            5 => (1, 2),
            6 => (0, 2),
            7 => (1, 0),
            _ => (2, 1),
        };
        // The direction is e_i + dir[j] e_j (dir[i] = 1 for every diagonal).
        let (s, es) = two_sum(o[i], dir[j] * o[j]);
        let (w, ew) = two_sum(u[i], dir[j] * u[j]);
        SlabProjection::new(s, es.abs(), w, ew.abs(), || w == 0.0 && ew == 0.0)
    }

    /// Along any direction: rounded dot products with the bound `γ₃ Σ|aᵢ vᵢ|` (plus the
    /// smallest normal double for underflow); `w` is tested exactly only when that bound cannot
    /// tell it from zero.
    fn along(a: &Vector3, ray: &Ray) -> SlabProjection {
        let dot = |v: &Vector3| {
            let value = a.dot(v);
            let magnitude = a.abs().dot(&v.abs());
            (value, DOT_ERROR * magnitude + f64::MIN_POSITIVE)
        };
        let (s, es) = dot(&ray.origin.coords);
        let (w, ew) = dot(&ray.direction);
        SlabProjection::new(s, es, w, ew, || {
            let mut terms = Vec::with_capacity(6);
            for i in 0..3 {
                product_terms(&[a[i]], &[ray.direction[i]], &mut terms);
            }
            sum_sign(&terms) == Ordering::Equal
        })
    }

    /// An interval of parameters containing every `t` (of the whole line) at which the ray is
    /// in the slab `lo ≤ a · x ≤ hi` (finite bounds): empty (`t0 > t1`) when it surely never
    /// is, the whole line when the ray may be parallel to the slab and inside it.
    ///
    /// ```
    /// use kepler::lab::boxtree::RayProbe;
    /// use kepler::geometry::{Point3, Vector3};
    /// use kepler::geometry::ray::Ray;
    /// let p = RayProbe::new(&Ray { origin: Point3::origin(), direction: -Vector3::x() }).unwrap();
    /// let [t0, t1] = p.fixed(0).interval(-3.0, -1.0);
    /// assert!(t0 <= 1.0 && 1.0 - t0 < 1e-14 && t1 >= 3.0 && t1 - 3.0 < 1e-14);
    /// assert_eq!(p.fixed(1).interval(-1.0, 1.0), [f64::NEG_INFINITY, f64::INFINITY]);
    /// ```
    #[inline]
    pub fn interval(&self, lo: f64, hi: f64) -> [f64; 2] {
        if matches!(lo.partial_cmp(&hi), None | Some(Ordering::Greater)) {
            return EMPTY;
        }
        let SlabProjection { s, es, slope } = *self;
        // With w > 0, t runs from (lo - s)/w to (hi - s)/w; with w < 0, from (s - hi)/|w| to
        // (s - lo)/|w|. Each numerator is widened over every s within es and over the rounding
        // of its subtraction: a rounded difference x is within u|x| of the exact one, and the
        // margin 4u|x| + (1 + 8u) es (plus the smallest normal double, for underflow) also
        // covers the roundings of the margin and of x ± margin (checked case by case: x ± margin
        // of either sign).
        let (x0, x1, r) = match slope {
            Slope::Forward(r) => (lo - s, hi - s, r),
            Slope::Backward(r) => (s - hi, s - lo, r),
            Slope::Parallel => {
                let inside = add_round_up(s, es) >= lo && add_round_down(s, -es) <= hi;
                return if inside { FULL } else { EMPTY };
            }
            Slope::Unknown => return FULL,
        };
        let spread = es * (1.0 + 8.0 * U) + f64::MIN_POSITIVE;
        let from = x0 - (x0.abs() * 4.0 * U + spread);
        let to = x1 + (x1.abs() * 4.0 * U + spread);
        let t0 = from * if from >= 0.0 { r[0] } else { r[1] };
        let t1 = to * if to >= 0.0 { r[1] } else { r[0] };
        [t0.next_down(), t1.next_up()]
    }
}

/// The ray's interval through several slabs, cut to `t ≥ 0`; `None` when empty.
#[inline]
pub(crate) fn meet(intervals: impl IntoIterator<Item = [f64; 2]>) -> Option<[f64; 2]> {
    let [t0, t1] = intervals
        .into_iter()
        .fold([0.0, f64::INFINITY], |[a, b], [c, d]| [a.max(c), b.min(d)]);
    (t0 <= t1).then_some([t0, t1])
}
