//! The lines of VTP(F), exactly: planes met with F's plane, and the exact signs and points of
//! their arrangement.
//!
//! Every line that bounds a visible part of a face F is where F's plane meets another plane
//! of the input: a sight plane (through an edge `ab` and the eye; for an eye at infinity,
//! through `ab` along the view direction), whose trace in F's plane has for picture the line
//! through the pictures of `a` and `b`, or the plane of an occluder face G, whose trace is
//! where "behind G" begins. Each plane is kept as its affine form `s(x)`, the orientation
//! determinant of degree 3 in the input coordinates that the predicates use
//! (`Orient3d([p, q, r, x])` for a face plane, `eye.determinant(a, b, x)` for a sight plane),
//! written as `s(x) = c + g·(x − O)` about F's first vertex `O`: the gradient `g` has degree 2
//! and the value `c = s(O)` degree 3.
//!
//! A vertex of the arrangement is the point `X` of F's plane on two lines `A` and `B`. With
//! `g_F` the gradient of F's plane (whose form vanishes at `O`) and `q_L = g_F × g_L`
//! (the direction of `L`'s trace), Cramer's rule gives `X = O + N / W` with
//! `W = det(g_F, g_A, g_B) = g_B·q_A` (degree 6) and `N = c_A q_B − c_B q_A` (degree 7), so the
//! value of a third form at `X` is `s_L(X) = (c_L W + c_A g_L·q_B − c_B g_L·q_A) / W`: its sign
//! is the sign of a polynomial of degree 9 times the sign of `W`. The same `W` orders two
//! traces' directions (`q_A × q_B = g_F W`), and two traces coincide exactly when `W` and `N`
//! vanish. Each of these is a [`Polynomial`] of the kernel: an estimate composed from
//! [`Estimate`]'s products and differences (so its bound is certified by construction), the
//! exact expansion, and the same formula in any [`Ring`].
//!
//! Written by hand because these are VISFAC's own predicates (no crate decides signs of points
//! built from three planes of the input exactly).

use super::extent::Extent;
use crate::geometry::exact::estimate;
use crate::geometry::kernel::{Difference, Estimate, Exponents, Polynomial, Ring};
use crate::geometry::predicates::{Orient3d, Orientation, orient2d, project};
use crate::geometry::{Point3, Vector3};
use crate::mesh::TextureFrame;
use crate::sight::along::{Expanded, Filtered, Form};
use crate::views::{Eye, Picture};
use num_rational::BigRational;
use num_traits::{ToPrimitive, Zero};
use std::cmp::Ordering;

/// A plane of the input whose trace in F's plane is a line of the arrangement.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) enum Kind {
    /// The sight plane through the segment `ab`: the picture of the line `ab`.
    Sight(Point3, Point3),
    /// The plane through a triangle (an occluder face's plane, or F's own).
    Plane([Point3; 3]),
    /// A plane of a perspective view's frustum, `n·(x − eye) − d` (see `queries/frustum.rs`):
    /// given relative to the eye, so that moving scene and eye together leaves it unchanged.
    Frustum(Vector3, f64),
}

impl Kind {
    /// The plane's form at `x`, a polynomial of degree 3.
    pub(super) fn at(&self, eye: &Eye, x: &Point3) -> Orientation {
        match self {
            Kind::Sight(a, b) => eye.determinant(a, b, x),
            Kind::Plane([p, q, r]) => Orientation::Point(Orient3d([*p, *q, *r, *x])),
            Kind::Frustum(normal, offset) => Form::Frustum(*normal, *offset).at(eye, x),
        }
    }

    /// The exact sign of the form at the input point `x`, at once when `x` defines the plane.
    pub(super) fn sign_at(&self, eye: &Eye, x: &Point3) -> Ordering {
        match self {
            Kind::Sight(a, b) if a == x || b == x => Ordering::Equal,
            Kind::Plane(t) if t.contains(x) => Ordering::Equal,
            _ => self.at(eye, x).sign(),
        }
    }

    /// The form's gradient, in the ring `R`: for `Orient3d([p, q, r, x])` it is
    /// `(r − p) × (q − p)`, for `eye.determinant(a, b, x)` it is `(a − e) × (b − e)` with an
    /// eye point `e` and `(b − a) × u` with an eye at infinity in direction `u`.
    fn gradient<R: Ring>(&self, eye: &Eye) -> [R; 3] {
        match (self, eye) {
            (Kind::Plane([p, q, r]), _) => cross(&difference(r, p), &difference(q, p)),
            (Kind::Sight(a, b), Eye::Point(e)) => cross(&difference(a, e), &difference(b, e)),
            (Kind::Sight(a, b), Eye::Infinity(u)) => cross(&difference(b, a), &vector(u)),
            (Kind::Frustum(normal, _), _) => vector(normal),
        }
    }

    /// The binary exponents of the points that define the plane.
    fn exponents(&self) -> Exponents {
        match self {
            Kind::Sight(a, b) => points_exponents(&[*a, *b]),
            Kind::Plane(t) => points_exponents(t),
            Kind::Frustum(normal, offset) => {
                Exponents::of(normal.as_slice()).union(Exponents::of(&[*offset]))
            }
        }
    }
}

/// The face whose plane carries the arrangement, and the eye.
#[derive(Debug, Clone)]
pub(super) struct Frame {
    /// A triangle spanning F's plane; its first vertex is the origin `O` of the forms.
    pub(super) plane: [Point3; 3],
    pub(super) eye: Eye,
    /// F's plane as a line kind (its own trace is all of F's plane).
    kind: Kind,
    /// The estimate of `g_F`.
    g: [Filtered; 3],
    /// The exponents of F's triangle and the eye.
    exponents: Exponents,
    /// The coordinate F's plane holds constant, when it is perpendicular to an axis (its
    /// triangle sharing that coordinate and not degenerate): then the form of F's plane takes
    /// the same value at two points exactly when they share that coordinate.
    axis: Option<usize>,
}

impl Frame {
    pub(super) fn new(plane: [Point3; 3], eye: Eye) -> Frame {
        let kind = Kind::Plane(plane);
        let eye_exponents = match &eye {
            Eye::Point(e) => points_exponents(&[*e]),
            Eye::Infinity(u) => Exponents::of(u.as_slice()),
        };
        let [p, q, r] = &plane;
        let axis = (0..3).find(|&k| {
            p[k] == q[k]
                && p[k] == r[k]
                && orient2d(project(p, k), project(q, k), project(r, k)) != Ordering::Equal
        });
        Frame {
            plane,
            eye,
            kind,
            g: kind.gradient(&eye),
            exponents: kind.exponents().union(eye_exponents),
            axis,
        }
    }

    /// The estimate of the gradient of F's plane's form: a normal of F's plane.
    pub(super) fn normal(&self) -> [Estimate; 3] {
        self.g.map(|f| f.0)
    }

    /// The origin of the forms, F's first vertex.
    fn origin(&self) -> &Point3 {
        &self.plane[0]
    }
}

/// A line of the arrangement with the estimates of its form's coefficients.
#[derive(Debug, Clone)]
pub(super) struct ArrangementLine {
    pub(super) kind: Kind,
    /// `g_L`.
    g: [Filtered; 3],
    /// `c_L = s_L(O)`.
    c: Filtered,
    /// `q_L = g_F × g_L`.
    q: [Filtered; 3],
    exponents: Exponents,
}

impl ArrangementLine {
    pub(super) fn new(kind: Kind, frame: &Frame) -> ArrangementLine {
        let g = kind.gradient(&frame.eye);
        ArrangementLine {
            kind,
            g,
            c: Filtered(kind.at(&frame.eye, frame.origin()).estimate()),
            q: cross(&frame.g, &g),
            exponents: kind.exponents(),
        }
    }

    /// Whether the plane is parallel to F's plane (or is it), so that its trace is empty (or
    /// all of it) and its form has one sign on all of F's plane: the form of F's plane takes
    /// one value at the points that define the plane (and the eye, for a sight plane). Exact.
    pub(super) fn parallel(&self, frame: &Frame) -> bool {
        let f = |x: &Point3| frame.kind.at(&frame.eye, x);
        // The form of a plane `x_k = c` is a nonzero multiple of `x_k − c`.
        let same = |x: &Point3, y: &Point3| match frame.axis {
            Some(k) => x[k] == y[k],
            None => Difference(f(x), f(y)).sign() == Ordering::Equal,
        };
        match (&self.kind, &frame.eye) {
            (Kind::Plane([p, q, r]), _) => same(p, q) && same(p, r),
            (Kind::Sight(a, b), Eye::Point(e)) => same(a, b) && same(a, e),
            // A sight plane contains the view direction, which F's plane does not.
            (Kind::Sight(..), Eye::Infinity(_)) => false,
            // Parallel planes have parallel gradients: their cross product vanishes.
            (Kind::Frustum(..), _) => {
                let c = trace_direction::<BigRational>(frame, &self.kind);
                c.iter().all(|x| x.is_zero())
            }
        }
    }

    /// The exact sign of the form at F's first vertex (on all of F's plane when the plane is
    /// [`parallel`](Self::parallel) to it).
    pub(super) fn sign_at_origin(&self, frame: &Frame) -> Ordering {
        self.kind.at(&frame.eye, frame.origin()).sign()
    }

    /// The estimates of the form's value at F's first vertex and of its gradient:
    /// `s_L(x) = c_L + g_L·(x − O)`.
    pub(super) fn coefficients(&self) -> (Estimate, [Estimate; 3]) {
        (self.c.0, self.g.map(|f| f.0))
    }

    /// The estimate of the trace's direction `q_L`.
    pub(super) fn direction_estimate(&self) -> [Estimate; 3] {
        self.q.map(|f| f.0)
    }

    /// The direction of the trace, `q_L`, rounded (for angles, not for decisions).
    pub(super) fn direction(&self) -> [f64; 3] {
        self.q.map(|e| e.0.value)
    }
}

/// The exponents of every input a polynomial of these lines reads.
fn exponents(frame: &Frame, lines: &[&ArrangementLine]) -> Exponents {
    lines
        .iter()
        .fold(frame.exponents, |e, l| e.union(l.exponents))
}

/// `W = det(g_F, g_A, g_B)`: nonzero exactly when the traces of `A` and `B` cross; its sign
/// orders their directions (`q_A × q_B = g_F W`). Degree 6.
pub(super) struct Turn<'a> {
    pub(super) frame: &'a Frame,
    pub(super) a: &'a ArrangementLine,
    pub(super) b: &'a ArrangementLine,
}

impl Polynomial for Turn<'_> {
    fn estimate(&self) -> Estimate {
        dot(&self.b.g, &self.a.q).0
    }

    fn expansion(&self) -> Vec<f64> {
        self.evaluate::<Expanded>().0
    }

    fn evaluate<R: Ring>(&self) -> R {
        let gb = self.b.kind.gradient::<R>(&self.frame.eye);
        dot(&gb, &trace_direction(self.frame, &self.a.kind))
    }

    fn degree(&self) -> u32 {
        6
    }

    fn exponents(&self) -> Exponents {
        exponents(self.frame, &[self.a, self.b])
    }
}

/// The estimates of `W` and `N` for the point `X = O + N / W` on the traces of two lines,
/// kept with the vertex so that each side test costs one dot product.
#[derive(Debug, Clone, Copy)]
pub(super) struct Crossing {
    w: Filtered,
    n: [Filtered; 3],
}

impl Crossing {
    pub(super) fn new(a: &ArrangementLine, b: &ArrangementLine) -> Crossing {
        Crossing {
            w: dot(&b.g, &a.q),
            n: [0, 1, 2].map(|k| a.c * b.q[k] - b.c * a.q[k]),
        }
    }

    /// A box certified to hold the point `O + N / W`, when `W` is certified nonzero.
    pub(super) fn extent(&self) -> Option<Extent> {
        Extent::of_quotient(self.n.map(|f| f.0), self.w.0)
    }
}

/// `W · s_L(X)` at the point `X` of F's plane on the traces of `A` and `B`:
/// `c_L W + g_L·N`, that is `c_L W + c_A g_L·q_B − c_B g_L·q_A`. Degree 9.
pub(super) struct SideAtVertex<'a> {
    pub(super) frame: &'a Frame,
    pub(super) a: &'a ArrangementLine,
    pub(super) b: &'a ArrangementLine,
    /// The estimates of `W` and `N` for `A` and `B`.
    pub(super) at: &'a Crossing,
    pub(super) l: &'a ArrangementLine,
}

impl Polynomial for SideAtVertex<'_> {
    fn estimate(&self) -> Estimate {
        let (at, l) = (self.at, self.l);
        (l.c * at.w + dot(&l.g, &at.n)).0
    }

    fn expansion(&self) -> Vec<f64> {
        self.evaluate::<Expanded>().0
    }

    fn evaluate<R: Ring>(&self) -> R {
        let eye = &self.frame.eye;
        let [n, [w, _, _]] = point::<R>(self.frame, &self.a.kind, &self.b.kind);
        let gl = self.l.kind.gradient::<R>(eye);
        let cl = self.l.kind.at(eye, self.frame.origin()).evaluate::<R>();
        cl * w + dot(&gl, &n)
    }

    fn degree(&self) -> u32 {
        9
    }

    fn exponents(&self) -> Exponents {
        exponents(self.frame, &[self.a, self.b, self.l])
    }
}

/// Component `k` of `N = c_A q_B − c_B q_A`: with `W`, the point `X = O + N / W`; when `W`
/// vanishes (parallel traces), `N` vanishes exactly when the traces coincide. Degree 7.
pub(super) struct Numerator<'a> {
    pub(super) frame: &'a Frame,
    pub(super) a: &'a ArrangementLine,
    pub(super) b: &'a ArrangementLine,
    pub(super) k: usize,
}

impl Polynomial for Numerator<'_> {
    fn estimate(&self) -> Estimate {
        let (a, b, k) = (self.a, self.b, self.k);
        (a.c * b.q[k] - b.c * a.q[k]).0
    }

    fn expansion(&self) -> Vec<f64> {
        self.evaluate::<Expanded>().0
    }

    fn evaluate<R: Ring>(&self) -> R {
        let [n, _] = point::<R>(self.frame, &self.a.kind, &self.b.kind);
        n[self.k].clone()
    }

    fn degree(&self) -> u32 {
        7
    }

    fn exponents(&self) -> Exponents {
        exponents(self.frame, &[self.a, self.b])
    }
}

/// `q_A·q_B`: for two traces that coincide, positive when their forms grow to the same side
/// (the forms are then positive multiples of each other on F's plane), negative otherwise.
/// Degree 8.
pub(super) struct Alignment<'a> {
    pub(super) frame: &'a Frame,
    pub(super) a: &'a ArrangementLine,
    pub(super) b: &'a ArrangementLine,
}

impl Polynomial for Alignment<'_> {
    fn estimate(&self) -> Estimate {
        dot(&self.a.q, &self.b.q).0
    }

    fn expansion(&self) -> Vec<f64> {
        self.evaluate::<Expanded>().0
    }

    fn evaluate<R: Ring>(&self) -> R {
        let [qa, qb] = [&self.a.kind, &self.b.kind].map(|k| trace_direction(self.frame, k));
        dot(&qa, &qb)
    }

    fn degree(&self) -> u32 {
        8
    }

    fn exponents(&self) -> Exponents {
        exponents(self.frame, &[self.a, self.b])
    }
}

/// Whether the traces of `a` and `b` are the same line: `W = 0` and `N = 0`, exactly, with
/// the estimates deciding at once when they can tell a component apart from zero.
pub(super) fn coincide(frame: &Frame, a: &ArrangementLine, b: &ArrangementLine) -> bool {
    let turn = Turn { frame, a, b };
    let numerators = [0, 1, 2].map(|k| Numerator { frame, a, b, k });
    let nonzero = |e: Estimate| e.sign().is_some_and(|s| s != Ordering::Equal);
    if nonzero(turn.estimate()) || numerators.iter().any(|n| nonzero(n.estimate())) {
        return false;
    }
    turn.sign() == Ordering::Equal && numerators.iter().all(|n| n.sign() == Ordering::Equal)
}

/// `q_L = g_F × g_L`, the direction of the trace of `kind` in F's plane, in the ring `R`.
fn trace_direction<R: Ring>(frame: &Frame, kind: &Kind) -> [R; 3] {
    let eye = &frame.eye;
    cross(&frame.kind.gradient::<R>(eye), &kind.gradient::<R>(eye))
}

/// `[N, (W, 0, 0)]`: the point `O + N / W` on the traces of `a` and `b`, in the ring `R`.
fn point<R: Ring>(frame: &Frame, a: &Kind, b: &Kind) -> [[R; 3]; 2] {
    let (eye, o) = (&frame.eye, frame.origin());
    let gf = frame.kind.gradient::<R>(eye);
    let (ga, gb) = (a.gradient::<R>(eye), b.gradient::<R>(eye));
    let (ca, cb) = (a.at(eye, o).evaluate::<R>(), b.at(eye, o).evaluate::<R>());
    let (qa, qb) = (cross(&gf, &ga), cross(&gf, &gb));
    let w = dot(&gb, &qa);
    let n = [0, 1, 2].map(|k| ca.clone() * qb[k].clone() - cb.clone() * qa[k].clone());
    [n, [w, R::from_f64(0.0), R::from_f64(0.0)]]
}

/// The picture and the texture coordinates of the point of F's plane on the traces of `a`
/// and `b` (which must cross): each coordinate a ratio of two exact polynomials of the input,
/// each rounded once, then divided (degree 8 over degree 7 for a perspective picture, over
/// degree 6 otherwise). Exact expansions where they are exact for the inputs' exponents,
/// exact rationals elsewhere.
pub(super) fn construct(
    frame: &Frame,
    a: &ArrangementLine,
    b: &ArrangementLine,
    picture: &Picture,
    texture: &TextureFrame,
) -> ([f64; 2], [f64; 2]) {
    if exponents(frame, &[a, b]).exact_for(8) {
        construct_in::<Expanded>(frame, a, b, picture, texture, |x| estimate(&x.0))
    } else {
        construct_in::<BigRational>(frame, a, b, picture, texture, |x| {
            x.to_f64().unwrap_or(f64::NAN)
        })
    }
}

/// [`construct`] in the ring `R`, with `round` rounding an exact value to the nearest double.
fn construct_in<R: Ring>(
    frame: &Frame,
    a: &ArrangementLine,
    b: &ArrangementLine,
    picture: &Picture,
    texture: &TextureFrame,
    round: impl Fn(R) -> f64,
) -> ([f64; 2], [f64; 2]) {
    let [n, [w, _, _]] = point::<R>(frame, &a.kind, &b.kind);
    let o = frame.origin();
    // The homogeneous point `(O − origin) W + N` for an affine map with that origin.
    let homogeneous = |origin: &Point3| -> [R; 3] {
        [0, 1, 2].map(|k| {
            let offset = R::from_f64(o[k]) - R::from_f64(origin[k]);
            offset * w.clone() + n[k].clone()
        })
    };
    let (rows, origin) = picture.rows();
    let h = homogeneous(&origin);
    let depth = if picture.is_perspective() {
        round(dot(&vector(&rows[2]), &h))
    } else {
        round(w.clone())
    };
    let xy = [0, 1].map(|k| round(dot(&vector(&rows[k]), &h)) / depth);
    let t = homogeneous(&texture.origin());
    let weight = round(w.clone());
    let uv =
        [texture.x_axis(), texture.y_axis()].map(|axis| round(dot(&vector(&axis), &t)) / weight);
    (xy, uv)
}

/// The texture coordinates of an input point of F's plane: `axis·(p − origin)`, exact, rounded
/// once.
pub(super) fn texture_of(texture: &TextureFrame, p: &Point3) -> [f64; 2] {
    let d = difference::<Expanded>(p, &texture.origin());
    [texture.x_axis(), texture.y_axis()]
        .map(|axis| estimate(&dot(&vector::<Expanded>(&axis), &d).0))
}

/// The texture coordinates of the point of F's plane on the line of sight through the input
/// point `p`: for an eye point `e`, the cut of the line `ep` by F's plane; for an eye at
/// infinity in direction `u`, `(I_F T(p) − s_F(p) axis·u) / I_F` with `I_F = g_F·u` the form of
/// F's plane towards the eye. Numerators and denominators exact, each rounded once.
pub(super) fn texture_on_sight_line(texture: &TextureFrame, frame: &Frame, p: &Point3) -> [f64; 2] {
    match &frame.eye {
        Eye::Point(e) => texture_of_cut(texture, &frame.eye, &frame.kind, e, p),
        Eye::Infinity(u) => {
            let [f0, f1, f2] = &frame.plane;
            let towards = Expanded(frame.eye.determinant(f0, f1, f2).expansion());
            let sp = Expanded(frame.kind.at(&frame.eye, p).expansion());
            let d = difference::<Expanded>(p, &texture.origin());
            let denominator = estimate(&towards.0);
            [texture.x_axis(), texture.y_axis()].map(|axis| {
                let axis = vector::<Expanded>(&axis);
                let numerator =
                    towards.clone() * dot(&axis, &d) - sp.clone() * dot(&axis, &vector(u));
                estimate(&numerator.0) / denominator
            })
        }
    }
}

/// The texture coordinates of the point `a + t (b − a)` where the form `m` vanishes on the
/// line `ab`: `(m(a) T(b) − m(b) T(a)) / (m(a) − m(b))` for the affine texture maps `T`,
/// numerator and denominator exact, each rounded once.
pub(super) fn texture_of_cut(
    texture: &TextureFrame,
    eye: &Eye,
    m: &Kind,
    a: &Point3,
    b: &Point3,
) -> [f64; 2] {
    let (ma, mb) = (
        Expanded(m.at(eye, a).expansion()),
        Expanded(m.at(eye, b).expansion()),
    );
    let (da, db) = (
        difference::<Expanded>(a, &texture.origin()),
        difference::<Expanded>(b, &texture.origin()),
    );
    let denominator = estimate(&(ma.clone() - mb.clone()).0);
    [texture.x_axis(), texture.y_axis()].map(|axis| {
        let axis = vector::<Expanded>(&axis);
        let numerator = ma.clone() * dot(&axis, &db) - mb.clone() * dot(&axis, &da);
        estimate(&numerator.0) / denominator
    })
}

// ---------------------------------------------------------------------------------------------
// Vectors in a ring.

fn difference<R: Ring>(a: &Point3, b: &Point3) -> [R; 3] {
    [0, 1, 2].map(|k| R::from_f64(a[k]) - R::from_f64(b[k]))
}

fn vector<R: Ring>(v: &Vector3) -> [R; 3] {
    [0, 1, 2].map(|k| R::from_f64(v[k]))
}

fn cross<R: Ring>(a: &[R; 3], b: &[R; 3]) -> [R; 3] {
    let m = |i: usize, j: usize| a[i].clone() * b[j].clone() - a[j].clone() * b[i].clone();
    [m(1, 2), m(2, 0), m(0, 1)]
}

fn dot<R: Ring>(a: &[R; 3], b: &[R; 3]) -> R {
    a[0].clone() * b[0].clone() + a[1].clone() * b[1].clone() + a[2].clone() * b[2].clone()
}

fn points_exponents(points: &[Point3]) -> Exponents {
    points.iter().fold(Exponents::NONE, |e, p| {
        e.union(Exponents::of(p.coords.as_slice()))
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::Vector3;

    /// The gradient is the form's: `s(O + v) − s(O) = g·v` for the three kinds of plane.
    #[test]
    fn gradients_are_the_forms() {
        let (p, q, r) = (
            Point3::new(0.5, -1.0, 2.0),
            Point3::new(3.0, 1.25, -0.5),
            Point3::new(-2.0, 0.75, 1.5),
        );
        let o = Point3::new(0.25, 0.5, -0.75);
        for eye in [
            Eye::Point(Point3::new(7.0, -3.0, 5.0)),
            Eye::Infinity(Vector3::new(0.5, -1.5, 1.0)),
        ] {
            for kind in [Kind::Plane([p, q, r]), Kind::Sight(p, q)] {
                let g = kind.gradient::<f64>(&eye);
                let s0 = kind.at(&eye, &o).evaluate::<f64>();
                for k in 0..3 {
                    let mut x = o;
                    x[k] += 1.0;
                    let s1 = kind.at(&eye, &x).evaluate::<f64>();
                    assert!((s1 - s0 - g[k]).abs() < 1e-12, "{kind:?} {k}");
                }
            }
        }
    }
}
