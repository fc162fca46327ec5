//! Rays, and where they meet triangles, decided exactly: whether a ray pierces a triangle,
//! which of two triangles it meets first, and the hit point built once from the input.
//!
//! The ray parameter where a ray `o + t·u` meets the plane of a triangle with normal `n` is
//! `t = n·(a − o) / n·u`; both are polynomials in the input coordinates, kept as exact
//! expansions, so comparing two hits is an exact sign and the hit point is rounded once.
//!
//! ```
//! use kepler::geometry::{Point3, Vector3, ray::{Ray, pierces}};
//! let t = [Point3::new(0.0, 0.0, 0.0), Point3::new(1.0, 0.0, 0.0), Point3::new(0.0, 1.0, 0.0)];
//! let down = Ray { origin: Point3::new(0.25, 0.25, 1.0), direction: -Vector3::z() };
//! assert!(pierces(&down, &t));
//! ```

use super::exact::{accurate_sum, expansion, product_terms, sum_sign, two_sum};
use super::predicates::{orient3d, orient3d_at_infinity};
use super::{Point3, Vector3};
use std::cmp::Ordering;

/// A ray: the points `origin + t·direction` for `t > 0`.
///
/// ```
/// use kepler::{geometry::{Point3, Vector3}, geometry::ray::Ray};
/// let r = Ray { origin: Point3::origin(), direction: Vector3::x() };
/// assert_eq!(r.direction.x, 1.0);
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Ray {
    /// Where the ray starts (not itself part of the ray).
    pub origin: Point3,
    /// Its direction (not zero; need not be a unit vector).
    pub direction: Vector3,
}

/// Whether the ray crosses the plane of `t` at some `t > 0` inside the closed triangle,
/// exactly.
///
/// ```
/// use kepler::geometry::ray::pierces;
/// use kepler::geometry::{Point3, Vector3};
/// use kepler::geometry::ray::Ray;
/// let t = [Point3::new(0.0, 0.0, 0.0), Point3::new(1.0, 0.0, 0.0), Point3::new(0.0, 1.0, 0.0)];
/// let down = |x, y| Ray { origin: Point3::new(x, y, 1.0), direction: -Vector3::z() };
/// assert!(pierces(&down(0.5, 0.5), &t)); // on the hypotenuse
/// assert!(!pierces(&down(0.5, 0.6), &t));
/// ```
pub fn pierces(ray: &Ray, t: &[Point3; 3]) -> bool {
    let u = &ray.direction;
    let origin_side = orient3d(&t[0], &t[1], &t[2], &ray.origin);
    let far_side = orient3d_at_infinity(&t[0], &t[1], &t[2], u);
    if origin_side == Ordering::Equal || far_side != origin_side.reverse() {
        return false;
    }
    let o = &ray.origin;
    let s = [
        orient3d_at_infinity(o, &t[0], &t[1], u),
        orient3d_at_infinity(o, &t[1], &t[2], u),
        orient3d_at_infinity(o, &t[2], &t[0], u),
    ];
    !(s.contains(&Ordering::Greater) && s.contains(&Ordering::Less))
}

/// The exact terms of the ray parameter `t = n·(a - o) / n·u` where the ray meets the plane
/// of triangle `t` (`n` its normal): the numerator's and denominator's expansions.
///
/// ```
/// use kepler::geometry::{Point3, Vector3, exact::estimate, ray::{Ray, parameter}};
/// let t = [Point3::new(0.0, 0.0, 2.0), Point3::new(1.0, 0.0, 2.0), Point3::new(0.0, 1.0, 2.0)];
/// let up = Ray { origin: Point3::origin(), direction: Vector3::new(0.0, 0.0, 0.5) };
/// let (n, d) = parameter(&up, &t);
/// assert_eq!(estimate(&n) / estimate(&d), 4.0);
/// ```
pub fn parameter(ray: &Ray, t: &[Point3; 3]) -> (Vec<f64>, Vec<f64>) {
    let diff = |p: &Point3, q: &Point3, k: usize| {
        let (s, e) = two_sum(p[k], -q[k]);
        [s, e]
    };
    let mut numerator = Vec::new();
    let mut denominator = Vec::new();
    for k in 0..3 {
        let (i, j) = ((k + 1) % 3, (k + 2) % 3);
        // n_k = (b - a)_i (c - a)_j - (b - a)_j (c - a)_i.
        let mut n = Vec::with_capacity(16);
        product_terms(&diff(&t[1], &t[0], i), &diff(&t[2], &t[0], j), &mut n);
        let start = n.len();
        product_terms(&diff(&t[1], &t[0], j), &diff(&t[2], &t[0], i), &mut n);
        n[start..].iter_mut().for_each(|x| *x = -*x);
        let n = expansion(&n);
        product_terms(&n, &diff(&t[0], &ray.origin, k), &mut numerator);
        product_terms(&n, &[ray.direction[k]], &mut denominator);
    }
    (expansion(&numerator), expansion(&denominator))
}

/// The exact order of the points where the ray meets the planes of `a` and `b` (both
/// pierced): `Less` when it meets `a` first.
///
/// ```
/// use kepler::geometry::ray::compare_hits;
/// use kepler::geometry::{Point3, Vector3};
/// use kepler::geometry::ray::Ray;
/// use std::cmp::Ordering;
/// let at = |z| [Point3::new(-1.0, -1.0, z), Point3::new(3.0, -1.0, z), Point3::new(-1.0, 3.0, z)];
/// let ray = Ray { origin: Point3::new(0.0, 0.0, 10.0), direction: -Vector3::z() };
/// assert_eq!(compare_hits(&ray, &at(0.1 + 0.2), &at(0.3)), Ordering::Less);
/// ```
pub fn compare_hits(ray: &Ray, a: &[Point3; 3], b: &[Point3; 3]) -> Ordering {
    let (na, da) = parameter(ray, a);
    let (nb, db) = parameter(ray, b);
    // t_a - t_b = (na·db - nb·da) / (da·db).
    let mut terms = Vec::new();
    product_terms(&na, &db, &mut terms);
    let negated: Vec<f64> = da.iter().map(|x| -x).collect();
    product_terms(&nb, &negated, &mut terms);
    let sign = sum_sign(&terms);
    let denominator_sign = sum_sign(&da) as i8 * sum_sign(&db) as i8;
    if denominator_sign < 0 {
        sign.reverse()
    } else {
        sign
    }
}

/// The hit point `o + t·u`, with `t` from the correctly rounded numerator and denominator.
///
/// ```
/// use kepler::geometry::{Point3, Vector3, ray::{Ray, hit_point}};
/// let t = [Point3::new(0.0, 0.0, 2.0), Point3::new(1.0, 0.0, 2.0), Point3::new(0.0, 1.0, 2.0)];
/// let up = Ray { origin: Point3::new(0.25, 0.5, 0.0), direction: Vector3::z() };
/// assert_eq!(hit_point(&up, &t), Point3::new(0.25, 0.5, 2.0));
/// ```
pub fn hit_point(ray: &Ray, t: &[Point3; 3]) -> Point3 {
    let (n, d) = parameter(ray, t);
    let s = accurate_sum(&n) / accurate_sum(&d);
    Point3::from([0, 1, 2].map(|k| ray.origin[k] + s * ray.direction[k]))
}
