//! Intersection lines, exactly: the line where the planes of two faces meet, its points defined
//! from the input, their order along it, the signs of planes at a point between two of them,
//! and the pictures of the points where it is cut.
//!
//! # The line and its points
//!
//! A [`Meet`] is the line `L` where two planes `A` and `B` meet, each given by three input
//! points, with the affine form `oA(x) = orient3d(a0, a1, a2, x)` (see [`Form::Plane`]). Each
//! affine form `F` has a gradient `gF`; `L` is directed along `gA × gB`. Every point of `L` the
//! hidden-line pass uses is an [`OnLine`], defined from input coordinates only:
//! - an input vertex on `L`;
//! - the crossing of an input edge `pq` (of one face, oriented so that `oO(p) > 0`) with the
//!   other face's plane `O`: `X = (oO(p)·q − oO(q)·p) / (oO(p) − oO(q))`;
//! - the cut of `L` by a third plane `Π` (a third face's plane, or the plane through a contour
//!   edge and the eye), oriented so that it increases along `L`: `Z = A ∩ B ∩ Π`.
//!
//! For any affine form `F`, each point `P` has a *numerator* `N_P(F) = W_P·F(P)`, a polynomial
//! of the input, with a *weight* `W_P > 0`:
//! - a vertex: `N = F(v)`, `W = 1` (degree 3);
//! - a crossing: `N = oO(p)·F(q) − oO(q)·F(p)`, `W = oO(p) − oO(q)` (degree 6);
//! - a cut: with `D(Π) = det[gA, gB, gΠ]` (the slope of `Π` along `L`; degree 6) and the
//!   reference point `o = a0` (so `oA(o) = 0`), Cramer's rule gives
//!   `N = D(Π)·F(Z) = F(o)·D(Π) − oB(o)·det[gA, gF, gΠ] − Π(o)·det[gA, gB, gF]`, `W = D(Π)`
//!   (degree 9: the 4×4 determinant of the four forms).
//!
//! # Order
//!
//! Each point has a *pivot*: a plane through it that crosses `L`, oriented to increase along
//! `L` (a cut's own plane; for a crossing, the plane through its edge and a vertex of the other
//! face off this face's plane; for a vertex, the plane through it, another vertex of its
//! triangle and such a vertex). `P` comes before `P'` exactly when `P`'s pivot is positive at
//! `P'`, the sign of `N_P'(pivot)`: degree 6 or 9, decided exactly.
//!
//! # Signs between two points
//!
//! Between two points `P1 < P2` of `L`, the point
//! `M = (c1·W1·P1 + c2·W2·P2) / (c1·W1 + c2·W2)`, with powers of two `c_i` that bring `c_i·W_i`
//! near 1 (so that `M` lies well inside), is strictly between them and defined from the input
//! (never rounded): every affine `F` has `F(M)` of the sign of `c1·N1(F) + c2·N2(F)`, equal signs
//! at the two points deciding at once ([`Meet::sign_between`]).
//!
//! # Filters and exact evaluation
//!
//! The numerators and slopes are [`Polynomial`]s. The deg-6 ones compose the kernel's
//! [`Product`] and [`Difference`] of orientations. The cut's `Q` and `D` are one formula written
//! once over any [`Ring`]: evaluated in a ring of [`Estimate`]s (each operation's certified bound
//! as the kernel derives it for [`Estimate::product`] and [`Estimate::difference`], so the
//! running bound of the whole formula is certified), in expansions (exact), and in
//! `BigRational` (exact, for inputs whose exponents expansions cannot carry).
//!
//! # Constructions
//!
//! The picture of a cut is `ℓ(Z)` for the picture forms `ℓ_k(x) = rows[k]·(x − origin)`
//! ([`Picture::rows`]): for a perspective view `x = Q(Π, ℓ_0) / Q(Π, ℓ_2)` (and `y` with
//! `ℓ_1`), for an orthographic one `x = Q(Π, ℓ_0) / D(Π)`: a ratio of two exact polynomials of
//! the input, each rounded once, then divided, as every constructed point of the engine. Its
//! value does not depend on the reference point `o` nor on which input points stand for the
//! planes (only on the planes' forms: a reversed face negates numerator and denominator alike),
//! so mirroring, permuting axes, scaling by powers of two and (in perspective) translating
//! scene and eye together give the same bits, transformed.

pub(crate) use super::along::balance;
use super::along::{Blend, Form, FormAt, Formula, cut_point, cut_point_of, exact_sign_rational};
use super::ratio::rounded_ratio;
use crate::geometry::kernel::{
    Difference, Estimate, Exponents, Polynomial, Product, Ring, expansion_sign, rounded,
    value_within,
};
use crate::geometry::predicates::{Orient3d, Orientation};
use crate::geometry::{Point3, Vector3};
use crate::views::{Eye, Picture};
use std::cmp::Ordering;

/// The line where the planes of two faces meet, directed along `gA × gB` (see the module
/// documentation).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Meet {
    /// The planes `A` and `B`, each through three input points.
    pub planes: [[Point3; 3]; 2],
}

/// A point of a [`Meet`] line, defined from the input (see the module documentation).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum OnLine {
    /// An input vertex on the line, with its pivot.
    Vertex {
        /// The vertex.
        point: Point3,
        /// A plane through it crossing the line, increasing along it.
        pivot: Form,
    },
    /// Where an input edge crosses the other face's plane.
    Crossing {
        /// The edge, oriented so that its first end is on the positive side of `plane`.
        edge: [Point3; 2],
        /// The plane crossed (a [`Form::Plane`]).
        plane: Form,
        /// A plane through the edge crossing the line, increasing along it.
        pivot: Form,
    },
    /// Where a plane crosses the line; the form increases along it.
    Cut(Form),
}

impl OnLine {
    /// The plane through the point that crosses the line, increasing along it.
    fn pivot(&self) -> &Form {
        match self {
            OnLine::Vertex { pivot, .. } | OnLine::Crossing { pivot, .. } => pivot,
            OnLine::Cut(form) => form,
        }
    }

    /// The degree of the point's numerators, in thirds: which of two points is cheaper to
    /// evaluate forms at.
    fn rank(&self) -> u8 {
        match self {
            OnLine::Vertex { .. } => 0,
            OnLine::Crossing { .. } => 1,
            OnLine::Cut(_) => 2,
        }
    }
}

/// A form reversed: negated exactly (two points swapped).
pub(crate) fn reversed(form: &Form) -> Form {
    match *form {
        Form::Plane([p, q, r]) => Form::Plane([p, r, q]),
        Form::Sight(c, d) => Form::Sight(d, c),
        Form::Frustum(n, d) => Form::Frustum(-n, -d),
    }
}

impl Meet {
    /// The form of plane `A` (`side` 0) or `B` (1).
    pub(crate) fn plane(&self, side: usize) -> Form {
        Form::Plane(self.planes[side])
    }

    /// `form` oriented to increase along the line (it must cross it).
    pub(crate) fn increasing(&self, eye: &Eye, form: Form) -> Form {
        if self.slope(eye, &form).sign() == Ordering::Less {
            reversed(&form)
        } else {
            form
        }
    }

    /// The exact sign of the slope of a form along the line: `Equal` when the form's plane is
    /// parallel to the line (it does not cross it).
    pub(crate) fn slope_sign(&self, eye: &Eye, form: &Form) -> Ordering {
        self.slope(eye, form).sign()
    }

    /// The slope `D(Π) = det[gA, gB, gΠ]` of a form along the line, as a polynomial.
    fn slope<'a>(&'a self, eye: &'a Eye, form: &'a Form) -> Along<'a> {
        Along {
            meet: self,
            eye,
            kind: Kind::Slope(form),
        }
    }

    /// The numerator `N_P(F)` of the form `f` at the point `p`.
    fn numerator<'a>(&'a self, eye: &'a Eye, p: &'a OnLine, f: &'a Form) -> Numerator<'a> {
        let at = |form: &'a Form, x: &'a Point3| FormAt { form, eye, x };
        match p {
            OnLine::Vertex { point, .. } => Numerator::Vertex(at(f, point)),
            OnLine::Crossing {
                edge: [a, b],
                plane,
                ..
            } => Numerator::Crossing(Minor(at(plane, a), at(f, b), at(plane, b), at(f, a))),
            OnLine::Cut(cut) => Numerator::Cut(Along {
                meet: self,
                eye,
                kind: Kind::At(cut, Affine::Form(f)),
            }),
        }
    }

    /// The exact sign of `form` at the point `p`.
    pub(crate) fn sign_at(&self, eye: &Eye, p: &OnLine, form: &Form) -> Ordering {
        self.numerator(eye, p, form).sign()
    }

    /// The exact order of `p` and `q` along the line: `Less` when `p` comes first.
    pub(crate) fn compare(&self, eye: &Eye, p: &OnLine, q: &OnLine) -> Ordering {
        // The same point named the same way (pivots aside).
        match (p, q) {
            (OnLine::Vertex { point: a, .. }, OnLine::Vertex { point: b, .. }) if a == b => {
                return Ordering::Equal;
            }
            (
                OnLine::Crossing { edge, plane, .. },
                OnLine::Crossing {
                    edge: e, plane: f, ..
                },
            ) if edge == e && plane == f => return Ordering::Equal,
            (OnLine::Cut(a), OnLine::Cut(b)) if a == b => return Ordering::Equal,
            _ => {}
        }
        // The pivot of the point with the dearer numerators, evaluated at the cheaper one.
        if q.rank() > p.rank() {
            return self.compare(eye, q, p).reverse();
        }
        self.numerator(eye, q, p.pivot()).sign().reverse()
    }

    /// The exact sign of `form` at the point strictly between the distinct points `p` and `q`
    /// defined by the powers of two `scales` (see the module documentation).
    pub(crate) fn sign_between(
        &self,
        eye: &Eye,
        [p, q]: [&OnLine; 2],
        scales: [f64; 2],
        form: &Form,
    ) -> Ordering {
        Blend {
            parts: [self.numerator(eye, p, form), self.numerator(eye, q, form)],
            scales,
        }
        .sign()
    }

    /// The weight `W_P > 0` of a point (see the module documentation), within `2⁻⁴²` of it.
    pub(crate) fn weight(&self, eye: &Eye, p: &OnLine) -> f64 {
        match p {
            OnLine::Vertex { .. } => 1.0,
            OnLine::Crossing {
                edge: [a, b],
                plane,
                ..
            } => accurate(&Difference(plane.at(eye, a), plane.at(eye, b))),
            OnLine::Cut(cut) => accurate(&self.slope(eye, cut)),
        }
    }

    /// The largest coordinate magnitude of the points that define the line and `p` (the scale
    /// of [`Meet::approximate`]'s error).
    pub(crate) fn magnitude(&self, p: &OnLine) -> f64 {
        let form_points = |f: &Form| match f {
            Form::Plane(t) => t.to_vec(),
            Form::Sight(c, d) => vec![*c, *d],
            Form::Frustum(..) => Vec::new(),
        };
        let own = match p {
            OnLine::Vertex { point, .. } => vec![*point],
            OnLine::Crossing { edge, plane, .. } => {
                let mut v = edge.to_vec();
                v.extend(form_points(plane));
                v
            }
            OnLine::Cut(form) => form_points(form),
        };
        self.planes
            .iter()
            .flatten()
            .chain(&own)
            .fold(0.0f64, |m, x| m.max(x.coords.amax()))
    }

    /// The point, within `2⁻⁴²` of the magnitude of its coordinates or of the points that
    /// define it (for the box filters of visibility queries, whose margins are `2⁻⁴⁰` of such
    /// magnitudes; never for decisions): from the estimates when their bounds allow, else from
    /// exact values rounded once.
    pub(crate) fn approximate(&self, eye: &Eye, p: &OnLine) -> Point3 {
        match p {
            OnLine::Vertex { point, .. } => *point,
            OnLine::Crossing {
                edge: [a, b],
                plane,
                ..
            } => {
                // Opposite signs: `t = oa / (oa − ob)` is off by at most the bounds over
                // `|oa| + |ob|` less the bounds, times the edge's length for the point.
                let (ea, eb) = (plane.at(eye, a).estimate(), plane.at(eye, b).estimate());
                let bounds = ea.bound + eb.bound;
                let length = (b - a).amax();
                let scale = a.coords.amax().max(b.coords.amax());
                let tight = bounds * length
                    <= (ea.value.abs() + eb.value.abs() - bounds) * scale * ACCURATE;
                let (oa, ob) = if tight {
                    (ea.value, eb.value)
                } else {
                    (rounded(&plane.at(eye, a)), rounded(&plane.at(eye, b)))
                };
                let t = (oa / (oa - ob)).clamp(0.0, 1.0);
                a + (b - a) * t
            }
            OnLine::Cut(cut) => {
                // Z = o + V / D: off by at most (bV + |V̂|·bD / |D̂|) / (|D̂| − bD).
                let along = |kind| Along {
                    meet: self,
                    eye,
                    kind,
                };
                let o = self.planes[0][0];
                let d = along(Kind::Slope(cut)).estimate();
                let v = [0, 1, 2].map(|k| along(Kind::Offset(cut, k)).estimate());
                let magnitude =
                    |v: &[Estimate; 3]| v.iter().fold(0.0f64, |m, v| m.max(v.value.abs()));
                let (vmax, bv) = (magnitude(&v), v.iter().fold(0.0f64, |m, v| m.max(v.bound)));
                let error = (bv + vmax * d.bound / d.value.abs()) / (d.value.abs() - d.bound);
                let defining = self
                    .planes
                    .iter()
                    .flatten()
                    .fold(0.0f64, |m, p| m.max(p.coords.amax()));
                let scale = defining.max(vmax / d.value.abs());
                let (v, d) =
                    if error.is_finite() && d.value.abs() > d.bound && error <= scale * ACCURATE {
                        (v.map(|v| v.value), d.value)
                    } else {
                        (
                            [0, 1, 2].map(|k| rounded(&along(Kind::Offset(cut, k)))),
                            rounded(&along(Kind::Slope(cut))),
                        )
                    };
                o + Vector3::from(v) / d
            }
        }
    }

    /// The picture of a point, built once from the input coordinates: an input vertex's
    /// picture, an edge's crossing with a plane ([`cut_point`]), or a cut's (see the module
    /// documentation).
    pub(crate) fn picture(&self, picture: &Picture, eye: &Eye, p: &OnLine) -> [f64; 2] {
        match p {
            OnLine::Vertex { point, .. } => picture.point(point),
            OnLine::Crossing {
                edge: [a, b],
                plane,
                ..
            } => cut_point(picture, eye, plane, a, b),
            // A contour's cut: the point of the contour edge `cd` seen on the line, where the
            // plane through the line and the eye vanishes (degree 6, cheaper than Cramer's
            // rule); the same picture.
            OnLine::Cut(Form::Sight(c, d)) => cut_point_of(
                picture,
                [self.sight_form(eye, c), self.sight_form(eye, d)],
                c,
                d,
            ),
            OnLine::Cut(cut) => {
                let (rows, origin) = picture.rows();
                let at = |k: usize| Along {
                    meet: self,
                    eye,
                    kind: Kind::At(cut, Affine::Row(rows[k], origin)),
                };
                let depth = if picture.is_perspective() {
                    at(2)
                } else {
                    self.slope(eye, cut)
                };
                [0, 1].map(|k| rounded_ratio(&at(k), &depth))
            }
        }
    }

    /// `orient3d` of plane `side` at `x`.
    fn side_at(&self, side: usize, x: &Point3) -> Orientation {
        Orientation::Point(Orient3d([
            self.planes[side][0],
            self.planes[side][1],
            self.planes[side][2],
            *x,
        ]))
    }

    /// The form of the plane through the line and the point `c`, at `d`:
    /// `oA(c)·oB(d) − oB(c)·oA(d)`, zero on the line and at `c`. Its sign against
    /// [`Meet::sight_side`] at `c` tells on which side of the line the segment `cd` passes, in
    /// front or behind, where their pictures cross.
    pub(crate) fn twist(&self, c: &Point3, d: &Point3) -> Ordering {
        Minor(
            self.side_at(0, c),
            self.side_at(1, d),
            self.side_at(1, c),
            self.side_at(0, d),
        )
        .sign()
    }

    /// The side of `x` of the plane through the line and the eye (the side of the picture of
    /// the line): `oA(x)·E_B − oB(x)·E_A` with `E` the planes' orientations against the eye.
    pub(crate) fn sight_side(&self, eye: &Eye, x: &Point3) -> Ordering {
        self.sight_form(eye, x).sign()
    }

    /// The point `p` lifted for exact arithmetic relative to `origin`: `(W·(p − origin), W)`
    /// with its positive weight `W` (see the module documentation), in the ring `R`. Every
    /// affine function of `p` times `W` is affine in these four values.
    pub(crate) fn lifted<R: Ring>(&self, eye: &Eye, p: &OnLine, origin: &Point3) -> ([R; 3], R) {
        match p {
            OnLine::Vertex { point, .. } => (difference(point, origin), R::from_f64(1.0)),
            OnLine::Crossing {
                edge: [a, b],
                plane,
                ..
            } => {
                // W = oO(a) − oO(b) > 0 (a on the positive side), W·X = oO(a)·b − oO(b)·a.
                let (fa, fb) = (
                    plane.at(eye, a).evaluate::<R>(),
                    plane.at(eye, b).evaluate::<R>(),
                );
                let (da, db) = (difference::<R>(a, origin), difference::<R>(b, origin));
                let x = [0, 1, 2].map(|k| fa.clone() * db[k].clone() - fb.clone() * da[k].clone());
                (x, fa - fb)
            }
            OnLine::Cut(cut) => {
                // D·(Z − origin) = D·(Z − o) + D·(o − origin), with D > 0 (the form increases
                // along the line).
                let along = |kind| {
                    Along {
                        meet: self,
                        eye,
                        kind,
                    }
                    .value::<R>()
                };
                let d = along(Kind::Slope(cut));
                let r = difference::<R>(&self.planes[0][0], origin);
                let x = [0, 1, 2].map(|k| along(Kind::Offset(cut, k)) + d.clone() * r[k].clone());
                (x, d)
            }
        }
    }

    /// The degree of [`Meet::lifted`]'s values in the inputs.
    pub(crate) fn lifted_degree(&self, eye: &Eye, p: &OnLine) -> u32 {
        match p {
            OnLine::Vertex { .. } => 1,
            OnLine::Crossing { edge, plane, .. } => plane.at(eye, &edge[0]).degree() + 1,
            OnLine::Cut(_) => 7,
        }
    }

    /// The binary exponents of the inputs that define the line and `p`.
    pub(crate) fn exponents_with(&self, eye: &Eye, p: &OnLine) -> Exponents {
        let planes = self.planes.iter().flatten();
        let e = planes.fold(eye_exponents(eye), |e, q| e.union(point_exponents(q)));
        match p {
            OnLine::Vertex { point, .. } => e.union(point_exponents(point)),
            OnLine::Crossing { edge, plane, .. } => e
                .union(point_exponents(&edge[0]))
                .union(point_exponents(&edge[1]))
                .union(form_exponents(plane)),
            OnLine::Cut(cut) => e.union(form_exponents(cut)),
        }
    }

    /// The form of [`Meet::sight_side`] at `x`, as a polynomial (degree 6).
    fn sight_form(&self, eye: &Eye, x: &Point3) -> Minor<Orientation> {
        let [a, b] = self.planes;
        Minor(
            self.side_at(0, x),
            eye.determinant(&b[0], &b[1], &b[2]),
            self.side_at(1, x),
            eye.determinant(&a[0], &a[1], &a[2]),
        )
    }
}

/// `p·q − r·s` for four polynomials of one type: the kernel's [`Difference`] of [`Product`]s,
/// whose exact sign, when the filter fails, comes from the factors' signs where they decide
/// (a zero factor, products of opposite signs: common where faces touch) before the exact
/// value.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Minor<P>(P, P, P, P);

impl<P: Polynomial + Copy> Minor<P> {
    fn terms(&self) -> Difference<Product<P, P>, Product<P, P>> {
        Difference(Product(self.0, self.1), Product(self.2, self.3))
    }
}

impl<P: Polynomial + Copy> Polynomial for Minor<P> {
    #[inline]
    fn estimate(&self) -> Estimate {
        self.terms().estimate()
    }

    fn expansion(&self) -> Vec<f64> {
        self.terms().expansion()
    }

    fn evaluate<R: Ring>(&self) -> R {
        self.terms().evaluate()
    }

    fn degree(&self) -> u32 {
        self.terms().degree()
    }

    fn exponents(&self) -> Exponents {
        self.terms().exponents()
    }

    fn sign(&self) -> Ordering {
        if let Some(sign) = self.estimate().sign() {
            return sign;
        }
        let product = |a: Ordering, b: Ordering| match (a, b) {
            (Ordering::Equal, _) | (_, Ordering::Equal) => Ordering::Equal,
            _ if a == b => Ordering::Greater,
            _ => Ordering::Less,
        };
        let first = product(self.0.sign(), self.1.sign());
        let second = product(self.2.sign(), self.3.sign());
        if second == Ordering::Equal {
            return first;
        }
        if first == Ordering::Equal || first != second {
            return second.reverse();
        }
        sign_with_exact(&self.terms())
    }
}

/// The exact sign of `p` past its filter: its expansion's when its inputs allow, else its
/// rational value's.
fn sign_with_exact<P: Polynomial>(p: &P) -> Ordering {
    if p.exponents().exact_for(p.degree()) {
        expansion_sign(&p.expansion())
    } else {
        exact_sign_rational(p)
    }
}

/// What an [`Along`] polynomial computes.
#[derive(Debug, Clone, Copy)]
enum Kind<'a> {
    /// `D(Π)`.
    Slope(&'a Form),
    /// `Q(Π, F) = D(Π)·F(Z)` at the cut `Z` of the line by `Π`.
    At(&'a Form, Affine<'a>),
    /// Coordinate `k` of `D(Π)·(Z − o)`.
    Offset(&'a Form, usize),
}

/// An affine function of a point: a form, or a picture form `row·(x − origin)`.
#[derive(Debug, Clone, Copy)]
enum Affine<'a> {
    Form(&'a Form),
    Row(Vector3, Point3),
}

/// A polynomial of the input along a [`Meet`] line's cut by a plane (see [`Kind`]), written
/// once over any [`Ring`].
#[derive(Debug, Clone, Copy)]
pub(crate) struct Along<'a> {
    meet: &'a Meet,
    eye: &'a Eye,
    kind: Kind<'a>,
}

impl Formula for Along<'_> {
    /// The polynomial in the ring `R`.
    fn value<R: Ring>(&self) -> R {
        let o = self.meet.planes[0][0];
        let eye = self.eye;
        let [ga, gb] = [0, 1].map(|s| gradient::<R>(eye, &self.meet.plane(s)));
        match self.kind {
            Kind::Slope(cut) => det(&ga, &gb, &gradient(eye, cut)),
            Kind::At(cut, f) => {
                let gc = gradient::<R>(eye, cut);
                let gf = f.gradient::<R>(eye);
                let b_o = Affine::Form(&self.meet.plane(1)).at::<R>(eye, &o);
                f.at::<R>(eye, &o) * det(&ga, &gb, &gc)
                    - b_o * det(&ga, &gf, &gc)
                    - Affine::Form(cut).at::<R>(eye, &o) * det(&ga, &gb, &gf)
            }
            Kind::Offset(cut, k) => {
                // D·(Z − o) = −(oB(o)·(gΠ × gA) + Π(o)·(gA × gB)), as oA(o) = 0.
                let gc = gradient::<R>(eye, cut);
                let b_o = Affine::Form(&self.meet.plane(1)).at::<R>(eye, &o);
                let c_o = Affine::Form(cut).at::<R>(eye, &o);
                let (u, v) = (cross(&gc, &ga), cross(&ga, &gb));
                -(b_o * u[k].clone() + c_o * v[k].clone())
            }
        }
    }

    fn formula_degree(&self) -> u32 {
        match self.kind {
            Kind::Slope(_) => 6,
            Kind::Offset(..) => 7,
            Kind::At(..) => 9,
        }
    }

    fn formula_exponents(&self) -> Exponents {
        let planes = self.meet.planes.iter().flatten();
        let mut e = planes.fold(eye_exponents(self.eye), |e, p| e.union(point_exponents(p)));
        let mut form = |f: &Form| e = e.union(form_exponents(f));
        match self.kind {
            Kind::Slope(cut) | Kind::Offset(cut, _) => form(cut),
            Kind::At(cut, Affine::Form(f)) => {
                form(cut);
                form(f);
            }
            Kind::At(cut, Affine::Row(row, origin)) => {
                form(cut);
                e = e
                    .union(Exponents::of(row.as_slice()))
                    .union(point_exponents(&origin));
            }
        }
        e
    }
}

impl Affine<'_> {
    /// The value at `o`: the gradient times `o` less a point where the function vanishes (the
    /// same polynomial as the determinant, with less cancellation in its estimate).
    fn at<R: Ring>(&self, eye: &Eye, o: &Point3) -> R {
        match self {
            Affine::Form(form) => {
                let anchor = match form {
                    Form::Plane([p, ..]) => p,
                    Form::Sight(c, _) => c,
                    Form::Frustum(_, offset) => {
                        // n·(o − eye) − d: the eye is where the plane's offset is measured.
                        let e = match eye {
                            Eye::Point(e) => *e,
                            Eye::Infinity(_) => Point3::origin(),
                        };
                        return dot(&gradient::<R>(eye, form), &difference::<R>(o, &e))
                            - R::from_f64(*offset);
                    }
                };
                dot(&gradient(eye, form), &difference(o, anchor))
            }
            Affine::Row(row, origin) => dot(
                &[0, 1, 2].map(|k| R::from_f64(row[k])),
                &difference(o, origin),
            ),
        }
    }

    /// The gradient.
    fn gradient<R: Ring>(&self, eye: &Eye) -> [R; 3] {
        match self {
            Affine::Form(f) => gradient(eye, f),
            Affine::Row(row, _) => [0, 1, 2].map(|k| R::from_f64(row[k])),
        }
    }
}

/// The gradient of a form: `orient3d(p, q, r, x) = (x − p)·((r − p) × (q − p))`;
/// `orient3d(c, d, x, e) = (x − e)·((c − e) × (d − e))`, the gradient written
/// `(c − e) × (d − c)` (equal, and without the cancellation of two long vectors for a distant
/// eye); at infinity, `−det[c − x, d − x, u] = (x − c)·((d − c) × u)`. A sight form vanishes at
/// `c`, a plane's at `p`.
pub(crate) fn gradient<R: Ring>(eye: &Eye, form: &Form) -> [R; 3] {
    match form {
        Form::Plane([p, q, r]) => cross(&difference(r, p), &difference(q, p)),
        Form::Sight(c, d) => match eye {
            Eye::Point(e) => cross(&difference(c, e), &difference(d, c)),
            Eye::Infinity(u) => cross(&difference(d, c), &[0, 1, 2].map(|k| R::from_f64(u[k]))),
        },
        Form::Frustum(n, _) => [0, 1, 2].map(|k| R::from_f64(n[k])),
    }
}

pub(crate) fn difference<R: Ring>(p: &Point3, q: &Point3) -> [R; 3] {
    [0, 1, 2].map(|k| R::from_f64(p[k]) - R::from_f64(q[k]))
}

pub(crate) fn cross<R: Ring>(a: &[R; 3], b: &[R; 3]) -> [R; 3] {
    let m = |i: usize, j: usize| a[i].clone() * b[j].clone() - a[j].clone() * b[i].clone();
    [m(1, 2), m(2, 0), m(0, 1)]
}

pub(crate) fn dot<R: Ring>(a: &[R; 3], b: &[R; 3]) -> R {
    a[0].clone() * b[0].clone() + a[1].clone() * b[1].clone() + a[2].clone() * b[2].clone()
}

pub(crate) fn det<R: Ring>(a: &[R; 3], b: &[R; 3], c: &[R; 3]) -> R {
    dot(a, &cross(b, c))
}

pub(crate) fn point_exponents(p: &Point3) -> Exponents {
    Exponents::of(p.coords.as_slice())
}

pub(crate) fn eye_exponents(eye: &Eye) -> Exponents {
    match eye {
        Eye::Point(e) => point_exponents(e),
        Eye::Infinity(u) => Exponents::of(u.as_slice()),
    }
}

pub(crate) fn form_exponents(form: &Form) -> Exponents {
    match form {
        Form::Plane(t) => t
            .iter()
            .fold(Exponents::NONE, |e, p| e.union(point_exponents(p))),
        Form::Sight(c, d) => point_exponents(c).union(point_exponents(d)),
        Form::Frustum(n, d) => Exponents::of(n.as_slice()).union(Exponents::of(&[*d])),
    }
}

/// A form's numerator at a point of a line (see [`Meet::numerator`]).
#[derive(Debug, Clone, Copy)]
enum Numerator<'a> {
    /// At a vertex: the form there.
    Vertex(FormAt<'a>),
    /// At a crossing: `oO(p)·F(q) − oO(q)·F(p)`.
    Crossing(Minor<FormAt<'a>>),
    /// At a cut: `Q(Π, F)`.
    Cut(Along<'a>),
}

impl Polynomial for Numerator<'_> {
    #[inline]
    fn estimate(&self) -> Estimate {
        match self {
            Numerator::Vertex(p) => p.estimate(),
            Numerator::Crossing(p) => p.estimate(),
            Numerator::Cut(p) => p.estimate(),
        }
    }

    fn expansion(&self) -> Vec<f64> {
        match self {
            Numerator::Vertex(p) => p.expansion(),
            Numerator::Crossing(p) => p.expansion(),
            Numerator::Cut(p) => p.expansion(),
        }
    }

    fn evaluate<R: Ring>(&self) -> R {
        match self {
            Numerator::Vertex(p) => p.evaluate(),
            Numerator::Crossing(p) => p.evaluate(),
            Numerator::Cut(p) => p.evaluate(),
        }
    }

    fn degree(&self) -> u32 {
        match self {
            Numerator::Vertex(p) => p.degree(),
            Numerator::Crossing(p) => p.degree(),
            Numerator::Cut(p) => p.degree(),
        }
    }

    fn exponents(&self) -> Exponents {
        match self {
            Numerator::Vertex(p) => p.exponents(),
            Numerator::Crossing(p) => p.exponents(),
            Numerator::Cut(p) => p.exponents(),
        }
    }

    #[inline]
    fn sign(&self) -> Ordering {
        match self {
            Numerator::Vertex(p) => p.sign(),
            Numerator::Crossing(p) => p.sign(),
            Numerator::Cut(p) => p.sign(),
        }
    }
}

/// The relative error below which an estimate is taken as accurate enough for an approximate
/// point or weight: `2⁻⁴²`, below the `2⁻⁴⁰` margins of the visibility queries' box filters.
const ACCURATE: f64 = 1.0 / (1u64 << 42) as f64;

/// The value of `p` within `2⁻⁴²` of its magnitude ([`value_within`]).
fn accurate<P: Polynomial>(p: &P) -> f64 {
    value_within(p, ACCURATE)
}
