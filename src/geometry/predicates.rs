//! Exact orientation predicates on [`super::Point3`], thin wrappers over `robust`.
//!
//! Each returns the exact sign of its determinant as an [`Ordering`]: the `robust` crate's
//! adaptive-precision arithmetic makes the sign exact for finite inputs without overflow or
//! underflow (coordinates up to 1e100 in magnitude, see [`MAX_COORDINATE`]).
//!
//! ```
//! use kepler::geometry::{Point3, predicates::orient3d};
//! use std::cmp::Ordering;
//! let (a, b, c) = (Point3::new(0.0, 0.0, 0.0), Point3::new(1.0, 0.0, 0.0), Point3::new(0.0, 1.0, 0.0));
//! assert_eq!(orient3d(&a, &b, &c, &Point3::new(0.0, 0.0, -1.0)), Ordering::Greater);
//! assert_eq!(orient3d(&a, &b, &c, &Point3::new(0.3, 0.3, 0.0)), Ordering::Equal);
//! ```

use super::exact::{
    expansion_product, expansion_sum, negated, product_terms, scale_expansion, sum_sign, two_sum,
};
use super::kernel::{Estimate, Exponents, Polynomial, Ring, UNIT_ROUNDOFF, exact_sign, sign_with};
use super::{Point3, Vector3};
use num_rational::BigRational;
use num_traits::Zero;
use robust::{Coord, Coord3D};
use std::cmp::Ordering;

/// The largest coordinate magnitude the engine accepts: beyond it the products inside the
/// predicates could overflow and signs would no longer be exact.
///
/// ```
/// assert_eq!(kepler::geometry::predicates::MAX_COORDINATE, 1e100);
/// ```
pub const MAX_COORDINATE: f64 = 1e100;

fn sign(v: f64) -> Ordering {
    v.partial_cmp(&0.0).unwrap_or(Ordering::Equal)
}

/// Exact sign of the orientation of `d` against the plane through `a`, `b`, `c`: `Greater`
/// when `d` lies below the plane, where "below" means `a`, `b`, `c` appear counter-clockwise
/// seen from above (Shewchuk's convention), `Equal` when the four points are coplanar.
///
/// ```
/// use kepler::geometry::{Point3, predicates::orient3d};
/// use std::cmp::Ordering;
/// let o = Point3::origin();
/// let (x, y) = (Point3::new(1.0, 0.0, 0.0), Point3::new(0.0, 1.0, 0.0));
/// assert_eq!(orient3d(&o, &x, &y, &Point3::new(0.0, 0.0, 1.0)), Ordering::Less);
/// ```
pub fn orient3d(a: &Point3, b: &Point3, c: &Point3, d: &Point3) -> Ordering {
    match orient3d_filter(a, b, c, d).sign() {
        Some(sign) => sign,
        None => orient3d_exact(a, b, c, d),
    }
}

/// [`orient3d`] past its filter: `robust`'s adaptive predicate where its expansions are
/// exact, else rationals.
#[cold]
#[inline(never)]
fn orient3d_exact(a: &Point3, b: &Point3, c: &Point3, d: &Point3) -> Ordering {
    // Two equal points make two rows of the determinant equal (or one zero): exactly zero,
    // and the common case of a shared vertex, which no filter can certify.
    if a == d || b == d || c == d || a == b || b == c || a == c {
        return Ordering::Equal;
    }
    // Four points with one coordinate the same lie in a plane normal to that axis: exactly
    // zero, and common (the axis-aligned faces of buildings and parts).
    if (0..3).any(|k| a[k] == d[k] && b[k] == d[k] && c[k] == d[k]) {
        return Ordering::Equal;
    }
    let det = Orient3d([*a, *b, *c, *d]);
    if !det.exponents().exact_for(3) {
        return exact_sign(&det);
    }
    let p = |q: &Point3| Coord3D {
        x: q.x,
        y: q.y,
        z: q.z,
    };
    sign(robust::orient3d(p(a), p(b), p(c), p(d)))
}

/// The estimate of [`Orient3d`] (see there for the bound), from references: the filter of
/// [`orient3d`], kept apart so that the common case copies no point.
#[inline(always)]
fn orient3d_filter(a: &Point3, b: &Point3, c: &Point3, d: &Point3) -> Estimate {
    let (adx, ady, adz) = (a.x - d.x, a.y - d.y, a.z - d.z);
    let (bdx, bdy, bdz) = (b.x - d.x, b.y - d.y, b.z - d.z);
    let (cdx, cdy, cdz) = (c.x - d.x, c.y - d.y, c.z - d.z);
    let (bdxcdy, cdxbdy) = (bdx * cdy, cdx * bdy);
    let (cdxady, adxcdy) = (cdx * ady, adx * cdy);
    let (adxbdy, bdxady) = (adx * bdy, bdx * ady);
    let det = adz * (bdxcdy - cdxbdy) + bdz * (cdxady - adxcdy) + cdz * (adxbdy - bdxady);
    let permanent = (bdxcdy.abs() + cdxbdy.abs()) * adz.abs()
        + (cdxady.abs() + adxcdy.abs()) * bdz.abs()
        + (adxbdy.abs() + bdxady.abs()) * cdz.abs();
    let outer = adz.abs() + bdz.abs() + cdz.abs();
    let bound = ORIENT3D_ERROR_BOUND * permanent + f64::MIN_POSITIVE * (1.0 + outer);
    Estimate { value: det, bound }
}

/// Half the gap between 1 and the next double (Shewchuk's ε).
const EPS: f64 = UNIT_ROUNDOFF;

/// Relative error bound of the estimate of [`Orient3d`]: `(8 + 256ε)ε`, to multiply by its computed
/// permanent. See the derivation there.
const ORIENT3D_ERROR_BOUND: f64 = (8.0 + 256.0 * EPS) * EPS;

/// Relative error bound of the estimate of [`Orient3dAtInfinity`]: `(7 + 224ε)ε`, to multiply by
/// its computed permanent (one rounding fewer per term than [`ORIENT3D_ERROR_BOUND`]: `u` is
/// not a difference).
const ORIENT3D_AT_INFINITY_ERROR_BOUND: f64 = (7.0 + 224.0 * EPS) * EPS;

/// The exact difference `x - y` as an expansion (at most two components).
fn difference(x: f64, y: f64) -> Vec<f64> {
    let (s, e) = two_sum(x, -y);
    [e, s].into_iter().filter(|&c| c != 0.0).collect()
}

/// The exact expansion of `p·q - r·s` for expansions `p`, `q`, `r`, `s`.
fn minor(p: &[f64], q: &[f64], r: &[f64], s: &[f64]) -> Vec<f64> {
    expansion_sum(&expansion_product(p, q), &negated(&expansion_product(r, s)))
}

/// The determinant whose sign [`orient3d`] returns, `det[a − d, b − d, c − d]` for
/// `Orient3d([a, b, c, d])`, as a [`Polynomial`]: positive when `d` lies below the plane through
/// `a`, `b`, `c`.
///
/// Its [`expansion`](Polynomial::expansion) forms the differences exactly as two-component
/// expansions, the 2×2 minors and the products with expansion arithmetic, so it has at most
/// 192 components (a handful when the differences are exact); it is exact for coordinates up
/// to [`MAX_COORDINATE`] whose nonzero values are at least about `1e-90` in magnitude (then
/// every intermediate product is a multiple of `2^-1074` and no bit is lost to underflow).
///
/// Its [`estimate`](Polynomial::estimate) is Shewchuk's `det = adz (bdx cdy − cdx bdy) +
/// bdz (cdx ady − adx cdy) + cdz (adx bdy − bdx ady)` on the rounded differences
/// `adx = fl(a.x − d.x)`, ..., with a certified bound for finite inputs whose products do not
/// overflow, underflow included. Each of the six monomials of the exact determinant reaches
/// `det` through at most 8 roundings (3 differences, the inner product, the subtraction, the
/// outer product, 2 additions), each a factor `1 + δ` with `|δ| <= ε = 2^-53`, so
/// `|det − exact| <= γ8 · P` with `γ8 = 8ε / (1 − 8ε)` and `P` the exact sum of the
/// monomials' magnitudes. The computed permanent `P̂` (the same expression on magnitudes,
/// reusing the rounded products) passes through the same 8 roundings, so
/// `P <= P̂ / (1 − ε)^8`; with the two roundings of `bound` itself it suffices that
/// `c (1 − ε)^2 >= 8ε / ((1 − 8ε)(1 − ε)^8)`, i.e. `c >= 8ε (1 + 18ε + O(ε²))`: we use
/// `c = (8 + 256ε)ε`. (Shewchuk's `o3derrboundA = (7 + 56ε)ε` is smaller because a sign
/// filter need not count the last addition, which cannot change the sign.) Underflow adds
/// an absolute error of at most `2^-1075` per product, propagated through at most the outer
/// difference (for the inner products) and a few roundings: at most about
/// `2^-1073 (|adz| + |bdz| + |cdz| + 2)` on `det` and likewise on `P̂`, which
/// `MIN_POSITIVE · (1 + |adz| + |bdz| + |cdz|)` covers many times over.
///
/// Its [`sign`](Polynomial::sign) is [`orient3d`], `robust`'s adaptive predicate.
///
/// ```
/// use kepler::geometry::{Point3, exact::estimate, kernel::Polynomial, predicates::Orient3d};
/// let o = Point3::origin();
/// let (x, y) = (Point3::new(1.0, 0.0, 0.0), Point3::new(0.0, 1.0, 0.0));
/// let det = Orient3d([o, x, y, Point3::new(0.0, 0.0, 2.0)]);
/// assert_eq!(det.expansion(), vec![-2.0]);
/// assert_eq!(det.estimate().value, -2.0);
/// assert!(det.estimate().bound > 0.0 && det.estimate().bound < 1e-14);
/// // Far from the origin, on and just below the plane z = 1e15 (doubles are 1/8 apart there).
/// let (a, b, c) = (Point3::new(1e15, 0.0, 1e15), Point3::new(1e15 + 1.0, 0.0, 1e15), Point3::new(1e15, 1.0, 1e15));
/// assert!(Orient3d([a, b, c, Point3::new(-7.0, 1e15, 1e15)]).expansion().is_empty());
/// let d = Point3::new(3.0, 5.0, 1e15 - 0.125);
/// assert_eq!(estimate(&Orient3d([a, b, c, d]).expansion()), 0.125);
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Orient3d(pub [Point3; 4]);

impl Polynomial for Orient3d {
    #[inline]
    fn estimate(&self) -> Estimate {
        let [a, b, c, d] = &self.0;
        orient3d_filter(a, b, c, d)
    }

    fn expansion(&self) -> Vec<f64> {
        let [a, b, c, d] = &self.0;
        let [adx, ady, adz] = [0, 1, 2].map(|i| difference(a[i], d[i]));
        let [bdx, bdy, bdz] = [0, 1, 2].map(|i| difference(b[i], d[i]));
        let [cdx, cdy, cdz] = [0, 1, 2].map(|i| difference(c[i], d[i]));
        // det = adz (bdx cdy - cdx bdy) + bdz (cdx ady - adx cdy) + cdz (adx bdy - bdx ady).
        let t1 = expansion_product(&adz, &minor(&bdx, &cdy, &cdx, &bdy));
        let t2 = expansion_product(&bdz, &minor(&cdx, &ady, &adx, &cdy));
        let t3 = expansion_product(&cdz, &minor(&adx, &bdy, &bdx, &ady));
        expansion_sum(&expansion_sum(&t1, &t2), &t3)
    }

    #[inline]
    fn evaluate<R: Ring>(&self) -> R {
        let [a, b, c, d] = &self.0;
        let diff = |p: &Point3, k: usize| R::from_f64(p[k]) - R::from_f64(d[k]);
        let [adx, ady, adz] = [0, 1, 2].map(|k| diff(a, k));
        let [bdx, bdy, bdz] = [0, 1, 2].map(|k| diff(b, k));
        let [cdx, cdy, cdz] = [0, 1, 2].map(|k| diff(c, k));
        adz * (bdx.clone() * cdy.clone() - cdx.clone() * bdy.clone())
            + bdz * (cdx * ady.clone() - adx.clone() * cdy)
            + cdz * (adx * bdy - bdx * ady)
    }

    fn degree(&self) -> u32 {
        3
    }

    fn exponents(&self) -> Exponents {
        self.0.iter().fold(Exponents::NONE, |e, p| {
            e.union(Exponents::of(p.coords.as_slice()))
        })
    }

    #[inline]
    fn sign(&self) -> Ordering {
        let [a, b, c, d] = &self.0;
        orient3d(a, b, c, d)
    }
}

/// The determinant whose sign [`orient3d_at_infinity`] returns, `−det[a − c, b − c, u]` for
/// `Orient3dAtInfinity([a, b, c], u)` (the limit of `Orient3d([a, b, c, c + λu])` divided by
/// `λ`), as a [`Polynomial`]; zero when the plane through `a`, `b`, `c` is parallel to `u` (or
/// degenerate).
///
/// Its expansion is built like [`Orient3d`]'s (exact two-component differences, expansion
/// products), with at most 96 components, exact under the same conditions with the
/// components of `u` counted as coordinates. Its estimate is `−det[r1, r2, u] =
/// r1x (r2z uy − r2y uz) + r1y (r2x uz − r2z ux) + r1z (r2y ux − r2x uy)` on the rounded
/// differences `r1 = fl(a − c)`, `r2 = fl(b − c)`, its bound derived as [`Orient3d`]'s with at
/// most 7 roundings per monomial (2 differences, inner product, subtraction, outer product,
/// 2 additions; the negation is exact): `c (1 − ε)^2 >= 7ε / ((1 − 7ε)(1 − ε)^7)`, i.e.
/// `c >= 7ε (1 + 16ε + O(ε²))`, and we use `c = (7 + 224ε)ε` times the computed permanent, plus
/// `MIN_POSITIVE · (1 + |r1x| + |r1y| + |r1z|)` for underflow. Its sign is
/// [`orient3d_at_infinity`].
///
/// ```
/// use kepler::geometry::{Point3, Vector3, exact::estimate, kernel::Polynomial, predicates::Orient3dAtInfinity};
/// let (a, b, c) = (Point3::new(0.0, 0.0, 0.0), Point3::new(1.0, 0.0, 0.0), Point3::new(0.0, 1.0, 0.0));
/// let det = |u| Orient3dAtInfinity([a, b, c], u);
/// assert_eq!(det(Vector3::new(0.1, 0.2, -1.0)).expansion(), vec![1.0]);
/// assert!(det(Vector3::new(1.0, 1.0, 0.0)).expansion().is_empty());
/// assert_eq!(estimate(&det(Vector3::new(0.0, 0.0, 0.1)).expansion()), -0.1);
/// let e = det(Vector3::new(0.1, 0.2, -1.0)).estimate();
/// assert_eq!(e.value, 1.0);
/// assert!(e.bound < 1e-15);
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Orient3dAtInfinity(pub [Point3; 3], pub Vector3);

impl Polynomial for Orient3dAtInfinity {
    #[inline]
    fn estimate(&self) -> Estimate {
        let ([a, b, c], u) = (&self.0, &self.1);
        orient3d_at_infinity_filter(a, b, c, u)
    }

    fn expansion(&self) -> Vec<f64> {
        let ([a, b, c], u) = (&self.0, &self.1);
        let r1 = [0, 1, 2].map(|i| difference(a[i], c[i]));
        let r2 = [0, 1, 2].map(|i| difference(b[i], c[i]));
        // -det[r1, r2, u] = r1x (r2z uy - r2y uz) + r1y (r2x uz - r2z ux) + r1z (r2y ux - r2x uy).
        let minor = |i: usize, j: usize| {
            expansion_sum(
                &scale_expansion(&r2[i], u[j]),
                &scale_expansion(&r2[j], -u[i]),
            )
        };
        let t1 = expansion_product(&r1[0], &minor(2, 1));
        let t2 = expansion_product(&r1[1], &minor(0, 2));
        let t3 = expansion_product(&r1[2], &minor(1, 0));
        expansion_sum(&expansion_sum(&t1, &t2), &t3)
    }

    #[inline]
    fn evaluate<R: Ring>(&self) -> R {
        let ([a, b, c], u) = (&self.0, &self.1);
        let r1 = [0, 1, 2].map(|k| R::from_f64(a[k]) - R::from_f64(c[k]));
        let r2 = [0, 1, 2].map(|k| R::from_f64(b[k]) - R::from_f64(c[k]));
        let u = [0, 1, 2].map(|k| R::from_f64(u[k]));
        let minor =
            |i: usize, j: usize| r2[i].clone() * u[j].clone() - r2[j].clone() * u[i].clone();
        r1[0].clone() * minor(2, 1) + r1[1].clone() * minor(0, 2) + r1[2].clone() * minor(1, 0)
    }

    fn degree(&self) -> u32 {
        3
    }

    fn exponents(&self) -> Exponents {
        self.0
            .iter()
            .fold(Exponents::of(self.1.as_slice()), |e, p| {
                e.union(Exponents::of(p.coords.as_slice()))
            })
    }

    #[inline]
    fn sign(&self) -> Ordering {
        let ([a, b, c], u) = (&self.0, &self.1);
        orient3d_at_infinity(a, b, c, u)
    }
}

/// The orientation of three points against a fourth that may be at infinity (the eye of a
/// perspective or an orthographic view): [`Orient3d`] or [`Orient3dAtInfinity`].
///
/// ```
/// use kepler::geometry::{Point3, Vector3, kernel::Polynomial, predicates::{Orient3d, Orientation}};
/// use std::cmp::Ordering;
/// let t = [Point3::new(0.0, 0.0, 0.0), Point3::new(1.0, 0.0, 0.0), Point3::new(0.0, 1.0, 0.0)];
/// let above = Orientation::Point(Orient3d([t[0], t[1], t[2], Point3::new(0.0, 0.0, 1.0)]));
/// assert_eq!(above.sign(), Ordering::Less);
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Orientation {
    /// Against a point.
    Point(Orient3d),
    /// Against a point at infinity.
    Infinity(Orient3dAtInfinity),
    /// The side of a plane given by a point, a normal and an offset (degree 2).
    Side(Side),
}

impl Polynomial for Orientation {
    #[inline]
    fn estimate(&self) -> Estimate {
        match self {
            Orientation::Point(d) => d.estimate(),
            Orientation::Infinity(d) => d.estimate(),
            Orientation::Side(d) => d.estimate(),
        }
    }

    fn expansion(&self) -> Vec<f64> {
        match self {
            Orientation::Point(d) => d.expansion(),
            Orientation::Infinity(d) => d.expansion(),
            Orientation::Side(d) => d.expansion(),
        }
    }

    fn evaluate<R: Ring>(&self) -> R {
        match self {
            Orientation::Point(d) => d.evaluate(),
            Orientation::Infinity(d) => d.evaluate(),
            Orientation::Side(d) => d.evaluate(),
        }
    }

    fn degree(&self) -> u32 {
        match self {
            Orientation::Side(_) => 2,
            _ => 3,
        }
    }

    fn exponents(&self) -> Exponents {
        match self {
            Orientation::Point(d) => d.exponents(),
            Orientation::Infinity(d) => d.exponents(),
            Orientation::Side(d) => d.exponents(),
        }
    }

    #[inline]
    fn sign(&self) -> Ordering {
        match self {
            Orientation::Point(d) => d.sign(),
            Orientation::Infinity(d) => d.sign(),
            Orientation::Side(d) => d.sign(),
        }
    }
}

/// Exact sign of the 2-D orientation of `(a, b, c)`, each given as `[x, y]`: `Greater` when
/// counter-clockwise, `Less` when clockwise, `Equal` when collinear.
///
/// ```
/// use kepler::geometry::predicates::orient2d;
/// use std::cmp::Ordering;
/// assert_eq!(orient2d([0.0, 0.0], [1.0, 0.0], [0.0, 1.0]), Ordering::Greater);
/// assert_eq!(orient2d([0.0, 0.0], [1.0, 1.0], [2.0, 2.0]), Ordering::Equal);
/// ```
pub fn orient2d(a: [f64; 2], b: [f64; 2], c: [f64; 2]) -> Ordering {
    match orient2d_filter(a, b, c).sign() {
        Some(sign) => sign,
        None => orient2d_exact(a, b, c),
    }
}

/// [`orient2d`] past its filter: `robust`'s adaptive predicate where its expansions are
/// exact, else rationals.
#[cold]
#[inline(never)]
fn orient2d_exact(a: [f64; 2], b: [f64; 2], c: [f64; 2]) -> Ordering {
    // Two equal points: exactly zero (see `orient3d_exact`).
    if a == b || b == c || a == c {
        return Ordering::Equal;
    }
    let det = Orient2d([a, b, c]);
    if !det.exponents().exact_for(2) {
        return exact_sign(&det);
    }
    let p = |q: [f64; 2]| Coord { x: q[0], y: q[1] };
    sign(robust::orient2d(p(a), p(b), p(c)))
}

/// The estimate of [`Orient2d`] (see there for the bound).
#[inline(always)]
fn orient2d_filter(a: [f64; 2], b: [f64; 2], c: [f64; 2]) -> Estimate {
    let left = (a[0] - c[0]) * (b[1] - c[1]);
    let right = (a[1] - c[1]) * (b[0] - c[0]);
    Estimate {
        value: left - right,
        bound: ORIENT2D_ERROR_BOUND * (left.abs() + right.abs()) + f64::MIN_POSITIVE,
    }
}

/// The determinant whose sign [`orient2d`] returns, `(a − c) × (b − c)` for
/// `Orient2d([a, b, c])`, as a [`Polynomial`]: positive when `a`, `b`, `c` turn
/// counter-clockwise.
///
/// Its estimate is Shewchuk's: `det = (ax − cx)(by − cy) − (ay − cy)(bx − cx)` with the bound
/// `(3 + 16ε)ε·(|left| + |right|)` of his `ccwerrboundA`, plus `MIN_POSITIVE` for underflow;
/// its expansion is exact (two-component differences, exact products); its sign is
/// [`orient2d`].
///
/// ```
/// use kepler::geometry::{kernel::Polynomial, predicates::Orient2d};
/// use std::cmp::Ordering;
/// let ccw = Orient2d([[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]]);
/// assert_eq!(ccw.estimate().value, 1.0);
/// assert_eq!(ccw.expansion(), vec![1.0]);
/// assert_eq!(Orient2d([[0.0, 0.0], [1.0, 1.0], [2.0, 2.0]]).sign(), Ordering::Equal);
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Orient2d(pub [[f64; 2]; 3]);

/// Shewchuk's `ccwerrboundA`, `(3 + 16ε)ε`.
const ORIENT2D_ERROR_BOUND: f64 = (3.0 + 16.0 * EPS) * EPS;

impl Polynomial for Orient2d {
    #[inline]
    fn estimate(&self) -> Estimate {
        let [a, b, c] = self.0;
        orient2d_filter(a, b, c)
    }

    fn expansion(&self) -> Vec<f64> {
        let [a, b, c] = self.0;
        let diff = |p: [f64; 2], k: usize| {
            let (s, e) = two_sum(p[k], -c[k]);
            [s, e]
        };
        let mut terms = Vec::with_capacity(16);
        product_terms(&diff(a, 0), &diff(b, 1), &mut terms);
        let start = terms.len();
        product_terms(&diff(a, 1), &diff(b, 0), &mut terms);
        terms[start..].iter_mut().for_each(|t| *t = -*t);
        super::exact::expansion(&terms)
    }

    fn evaluate<R: Ring>(&self) -> R {
        let [a, b, c] = self.0;
        let d = |p: [f64; 2], k: usize| R::from_f64(p[k]) - R::from_f64(c[k]);
        d(a, 0) * d(b, 1) - d(a, 1) * d(b, 0)
    }

    fn degree(&self) -> u32 {
        2
    }

    fn exponents(&self) -> Exponents {
        Exponents::of(&self.0.concat())
    }

    #[inline]
    fn sign(&self) -> Ordering {
        let [a, b, c] = self.0;
        orient2d(a, b, c)
    }
}

/// The side of the point `x` of the plane `normal · (x − origin) = offset`, as a
/// [`Polynomial`] of degree 2: positive on the side the normal points to. A plane given by a
/// point, a normal and an offset in doubles (a clipping plane of a view frustum, relative to
/// the eye: the same plane wherever scene and eye are moved together) is exact input like any
/// vertex.
///
/// Its estimate rounds the three differences and products and the two additions: each term
/// `n_k·d_k` is off by at most `2u` of its magnitude and the sum adds `γ2` of the terms'
/// magnitudes, so the kernel's [`sum_error_bound`](super::kernel::sum_error_bound) of four
/// terms over the computed magnitudes bounds it (with room for their own rounding).
///
/// ```
/// use kepler::geometry::{Point3, Vector3, kernel::Polynomial, predicates::Side};
/// use std::cmp::Ordering;
/// let s = |x| Side { origin: Point3::new(0.0, 0.0, 1.0), normal: Vector3::z(), offset: 0.0, x };
/// assert_eq!(s(Point3::new(5.0, 5.0, 3.0)).estimate().value, 2.0);
/// assert_eq!(s(Point3::new(0.1, 0.7, 1.0)).sign(), Ordering::Equal);
/// assert_eq!(s(Point3::new(0.0, 0.0, 0.0)).expansion(), vec![-1.0]);
/// let beyond = Side { offset: 0.5, ..s(Point3::new(0.0, 0.0, 1.5)) };
/// assert_eq!(beyond.sign(), Ordering::Equal);
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Side {
    /// A point of the plane.
    pub origin: Point3,
    /// The plane's normal (need not be a unit vector).
    pub normal: Vector3,
    /// The plane's offset from `origin` along the normal (0 for a plane through `origin`).
    pub offset: f64,
    /// The point whose side is asked.
    pub x: Point3,
}

impl Polynomial for Side {
    #[inline]
    fn estimate(&self) -> Estimate {
        let terms = [0, 1, 2].map(|k| self.normal[k] * (self.x[k] - self.origin[k]));
        let magnitude = terms.iter().map(|t| t.abs()).sum::<f64>() + self.offset.abs();
        Estimate {
            value: terms[0] + terms[1] + terms[2] - self.offset,
            bound: super::kernel::sum_error_bound(5, magnitude),
        }
    }

    fn expansion(&self) -> Vec<f64> {
        let mut terms = Vec::with_capacity(13);
        for k in 0..3 {
            let (s, e) = two_sum(self.x[k], -self.origin[k]);
            product_terms(&[s, e], &[self.normal[k]], &mut terms);
        }
        terms.push(-self.offset);
        super::exact::expansion(&terms)
    }

    fn evaluate<R: Ring>(&self) -> R {
        let term = |k: usize| {
            R::from_f64(self.normal[k]) * (R::from_f64(self.x[k]) - R::from_f64(self.origin[k]))
        };
        term(0) + term(1) + term(2) - R::from_f64(self.offset)
    }

    fn degree(&self) -> u32 {
        2
    }

    fn exponents(&self) -> Exponents {
        Exponents::of(self.origin.coords.as_slice())
            .union(Exponents::of(self.normal.as_slice()))
            .union(Exponents::of(self.x.coords.as_slice()))
            .union(Exponents::of(&[self.offset]))
    }
}

/// The projection of `p` that drops coordinate `axis` (0, 1 or 2), keeping the other two in
/// cyclic order so that orientations in the projection match the sign of the dropped normal
/// component: dropping z gives (x, y), dropping x gives (y, z), dropping y gives (z, x).
///
/// ```
/// use kepler::geometry::{Point3, predicates::project};
/// assert_eq!(project(&Point3::new(1.0, 2.0, 3.0), 1), [3.0, 1.0]);
/// ```
pub fn project(p: &Point3, axis: usize) -> [f64; 2] {
    match axis {
        0 => [p.y, p.z],
        1 => [p.z, p.x],
        _ => [p.x, p.y],
    }
}

/// Exact sign of `orient3d(a, b, c, q)` for the point `q` at infinity in direction `u`: the
/// side of the plane through `a`, `b`, `c` towards which `u` points (`Greater` when `u` points
/// below it, in [`orient3d`]'s sense), `Equal` when the plane is parallel to `u`. It is the
/// sign of `-det[a - c, b - c, u]`, the limit of `orient3d(a, b, c, c + λu)` as λ grows.
///
/// Used for orthographic views, whose eye is such a point at infinity. Written by hand because
/// `robust` has no predicate with a direction: a floating-point filter decides almost every
/// call, and an exact expansion ([`sum_sign`]) the rest; a `u` along a coordinate axis reduces
/// to `robust`'s `orient2d`.
///
/// ```
/// use kepler::geometry::{Point3, Vector3, predicates::orient3d_at_infinity};
/// use std::cmp::Ordering;
/// let (a, b, c) = (Point3::new(0.0, 0.0, 0.0), Point3::new(1.0, 0.0, 0.0), Point3::new(0.0, 1.0, 0.0));
/// assert_eq!(orient3d_at_infinity(&a, &b, &c, &Vector3::new(0.1, 0.2, -1.0)), Ordering::Greater);
/// assert_eq!(orient3d_at_infinity(&a, &b, &c, &Vector3::new(1.0, 1.0, 0.0)), Ordering::Equal);
/// ```
pub fn orient3d_at_infinity(a: &Point3, b: &Point3, c: &Point3, u: &Vector3) -> Ordering {
    if let Some(k) = single_axis(&[u.x, u.y, u.z]) {
        // det[a - c, b - c, u_k e_k] = u_k (the k-th component of (a - c) x (b - c)).
        let o = orient2d(project(a, k), project(b, k), project(c, k));
        return if u[k] > 0.0 { o.reverse() } else { o };
    }
    match orient3d_at_infinity_filter(a, b, c, u).sign() {
        Some(sign) => sign,
        None => {
            let det = Orient3dAtInfinity([*a, *b, *c], *u);
            sign_with(&det, || exact_direction_det(a, b, c, u).reverse())
        }
    }
}

/// The estimate of [`Orient3dAtInfinity`] (see there for the bound), from references.
#[inline(always)]
fn orient3d_at_infinity_filter(a: &Point3, b: &Point3, c: &Point3, u: &Vector3) -> Estimate {
    let (r1x, r1y, r1z) = (a.x - c.x, a.y - c.y, a.z - c.z);
    let (r2x, r2y, r2z) = (b.x - c.x, b.y - c.y, b.z - c.z);
    let (r2zuy, r2yuz) = (r2z * u.y, r2y * u.z);
    let (r2xuz, r2zux) = (r2x * u.z, r2z * u.x);
    let (r2yux, r2xuy) = (r2y * u.x, r2x * u.y);
    let value = r1x * (r2zuy - r2yuz) + r1y * (r2xuz - r2zux) + r1z * (r2yux - r2xuy);
    let permanent = (r2zuy.abs() + r2yuz.abs()) * r1x.abs()
        + (r2xuz.abs() + r2zux.abs()) * r1y.abs()
        + (r2yux.abs() + r2xuy.abs()) * r1z.abs();
    let outer = r1x.abs() + r1y.abs() + r1z.abs();
    let bound = ORIENT3D_AT_INFINITY_ERROR_BOUND * permanent + f64::MIN_POSITIVE * (1.0 + outer);
    Estimate { value, bound }
}

/// The exact sign of `det[a - c, b - c, u]` from its expansion (the filter's fallback).
#[cold]
#[inline(never)]
fn exact_direction_det(a: &Point3, b: &Point3, c: &Point3, u: &Vector3) -> Ordering {
    const PERMUTATIONS: [([usize; 3], f64); 6] = [
        ([0, 1, 2], 1.0),
        ([1, 2, 0], 1.0),
        ([2, 0, 1], 1.0),
        ([0, 2, 1], -1.0),
        ([2, 1, 0], -1.0),
        ([1, 0, 2], -1.0),
    ];
    let diff = |p: &Point3, i: usize| {
        let (s, e) = two_sum(p[i], -c[i]);
        [s, e]
    };
    let mut terms = Vec::with_capacity(96);
    let mut pair = Vec::with_capacity(8);
    for ([i, j, k], sign) in PERMUTATIONS {
        pair.clear();
        product_terms(&diff(a, i), &diff(b, j), &mut pair);
        product_terms(&pair, &[sign * u[k]], &mut terms);
    }
    sum_sign(&terms)
}

/// Exact sign of `orient2d(a, b, q)` for the point `q` at infinity in direction `u`: which
/// side of `u` the vector `a - b` lies on (`Greater` when `(a, b, q)` turn counter-clockwise),
/// the sign of `-det[a - b, u]`.
///
/// ```
/// use kepler::geometry::predicates::orient2d_at_infinity;
/// use std::cmp::Ordering;
/// // Looking from b = (0, 0) along +y, a = (1, 0) lies to the right: clockwise.
/// assert_eq!(orient2d_at_infinity([1.0, 0.0], [0.0, 0.0], [0.0, 1.0]), Ordering::Less);
/// assert_eq!(orient2d_at_infinity([0.0, 3.0], [0.0, 0.0], [0.0, 1.0]), Ordering::Equal);
/// ```
pub fn orient2d_at_infinity(a: [f64; 2], b: [f64; 2], u: [f64; 2]) -> Ordering {
    // det[a - b, u] = (a - b)_x u_y - (a - b)_y u_x.
    let cmp = |x: f64, y: f64| x.partial_cmp(&y).unwrap_or(Ordering::Equal);
    match (u[0] == 0.0, u[1] == 0.0) {
        (true, true) => return Ordering::Equal,
        (true, false) => return cmp(a[0], b[0]).reverse_if(u[1] > 0.0),
        (false, true) => return cmp(a[1], b[1]).reverse_if(u[0] < 0.0),
        (false, false) => {}
    }
    if !Exponents::of(&[a[0], a[1], b[0], b[1], u[0], u[1]]).exact_for(2) {
        // Exactly, in rationals: -det[a - b, u].
        let r = |x: f64| BigRational::from_f64(x);
        let det = (r(a[0]) - r(b[0])) * r(u[1]) - (r(a[1]) - r(b[1])) * r(u[0]);
        return BigRational::zero().cmp(&det);
    }
    let (dx, ex) = two_sum(a[0], -b[0]);
    let (dy, ey) = two_sum(a[1], -b[1]);
    let mut terms = Vec::with_capacity(8);
    product_terms(&[dx, ex], &[u[1]], &mut terms);
    product_terms(&[dy, ey], &[-u[0]], &mut terms);
    sum_sign(&terms).reverse()
}

/// `reverse` when a condition holds: the sign of a product with a factor of known sign.
trait ReverseIf {
    fn reverse_if(self, condition: bool) -> Self;
}

impl ReverseIf for Ordering {
    #[inline]
    fn reverse_if(self, condition: bool) -> Self {
        if condition { self.reverse() } else { self }
    }
}

/// The axis `k` when `v` has exactly one nonzero component, `v[k]`.
#[inline]
fn single_axis(v: &[f64; 3]) -> Option<usize> {
    match (v[0] != 0.0, v[1] != 0.0, v[2] != 0.0) {
        (true, false, false) => Some(0),
        (false, true, false) => Some(1),
        (false, false, true) => Some(2),
        _ => None,
    }
}

/// Whether the three points are collinear, decided exactly (all three coordinate-plane
/// projections are collinear).
///
/// ```
/// use kepler::geometry::{Point3, predicates::collinear};
/// let a = Point3::new(0.0, 0.0, 0.0);
/// assert!(collinear(&a, &Point3::new(1.0, 2.0, 3.0), &Point3::new(2.0, 4.0, 6.0)));
/// assert!(!collinear(&a, &Point3::new(1.0, 2.0, 3.0), &Point3::new(2.0, 4.0, 6.5)));
/// ```
pub fn collinear(a: &Point3, b: &Point3, c: &Point3) -> bool {
    (0..3).all(|k| orient2d(project(a, k), project(b, k), project(c, k)) == Ordering::Equal)
}

/// Whether the triangle `t` meets the *open* box `b` (its interior), decided exactly.
///
/// By the separating-axis theorem, a triangle and a box have disjoint interiors exactly when
/// one of these weakly separates them: a coordinate axis, the triangle's plane, or (for the
/// nine edge-by-axis directions) a line through an edge of the triangle's projection along a
/// coordinate axis, with the projected box on its far side. Each test is a comparison,
/// an `orient3d` or an `orient2d` on input coordinates, so the answer is exact. Touching the
/// box's boundary does not count as meeting it. The box must have positive volume and the
/// triangle must not be degenerate (collinear).
///
/// ```
/// use kepler::geometry::{Aabb, Point3, predicates::triangle_meets_open_box};
/// let b = Aabb::new(Point3::new(0.0, 0.0, 0.0), Point3::new(1.0, 1.0, 1.0));
/// let touching = [Point3::new(1.0, 0.0, 0.0), Point3::new(1.0, 1.0, 0.0), Point3::new(1.0, 0.0, 1.0)];
/// assert!(!triangle_meets_open_box(&touching, &b));
/// let piercing = [Point3::new(0.5, 0.5, -1.0), Point3::new(0.5, 0.5, 2.0), Point3::new(3.0, 3.0, 0.5)];
/// assert!(triangle_meets_open_box(&piercing, &b));
/// ```
pub fn triangle_meets_open_box(t: &[Point3; 3], b: &super::Aabb) -> bool {
    // Coordinate axes.
    for k in 0..3 {
        if t.iter().all(|p| p[k] <= b.min[k]) || t.iter().all(|p| p[k] >= b.max[k]) {
            return false;
        }
    }
    let corners = b.corners();
    // The triangle's plane (skipped for a degenerate triangle, whose orient3d vanishes).
    if !collinear(&t[0], &t[1], &t[2]) {
        let signs = corners.map(|q| orient3d(&t[0], &t[1], &t[2], &q));
        if signs.iter().all(|&s| s != Ordering::Less)
            || signs.iter().all(|&s| s != Ordering::Greater)
        {
            return false;
        }
    }
    // Edge lines of the projections along each axis.
    for k in 0..3 {
        let p = t.map(|q| project(&q, k));
        let rect = [0usize, 1, 2, 3].map(|i| {
            let q = corners[match k {
                0 => [0, 2, 4, 6][i],
                1 => [0, 1, 4, 5][i],
                _ => [0, 1, 2, 3][i],
            }];
            project(&q, k)
        });
        let area = orient2d(p[0], p[1], p[2]);
        for e in 0..3 {
            let (u, v, w) = (p[e], p[(e + 1) % 3], p[(e + 2) % 3]);
            if u == v {
                continue;
            }
            let beyond = |side: Ordering| {
                rect.iter()
                    .all(|&q| matches!(orient2d(u, v, q), o if o == side || o == Ordering::Equal))
            };
            let separated = if area == Ordering::Equal {
                // The projection is a segment: either side of its line separates.
                beyond(Ordering::Less) || beyond(Ordering::Greater)
            } else {
                beyond(orient2d(u, v, w).reverse())
            };
            if separated {
                return false;
            }
        }
    }
    true
}
