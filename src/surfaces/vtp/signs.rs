//! The lines and vertices of the cells: each plane met is traced as a line of F's plane
//! (planes keyed by their points, equal traces resolved to one line), each crossing of two
//! lines is a vertex built once, and every decision is the exact sign of a line's form at a
//! vertex.

use super::{At, Cell, Extent, Trace, Vertex, Vtp};
use crate::geometry::Point3;
use crate::geometry::kernel::{Difference, Polynomial, Product};
use crate::geometry::predicates::orient3d;
use crate::sight::along::Form;
use crate::surfaces::extent::SignedForm;
use crate::surfaces::lines::{
    self, Alignment, ArrangementLine, Crossing, Kind, SideAtVertex, Turn,
};
use crate::views::Eye;
use std::cmp::Ordering;

impl<'a> Vtp<'a> {
    /// The corners of a polygon without those between two collinear edges (in the picture),
    /// and the way it turns, when it turns only one way, so is convex; `None` otherwise.
    pub(super) fn convex(&self, corners: &[Point3]) -> Option<(Vec<Point3>, Ordering)> {
        let eye = &self.frame.eye;
        let n = corners.len();
        let mut out = Vec::with_capacity(n);
        let mut turn = Ordering::Equal;
        for i in 0..n {
            let (a, b, c) = (
                &corners[(i + n - 1) % n],
                &corners[i],
                &corners[(i + 1) % n],
            );
            match eye.orient3d(a, b, c) {
                Ordering::Equal => {}
                t if t == turn || turn == Ordering::Equal => {
                    turn = t;
                    out.push(*b);
                }
                _ => return None,
            }
        }
        (out.len() >= 3).then_some((out, turn))
    }

    /// A cell with the input points `corners` (a convex loop turning `turn` in the picture).
    pub(super) fn add_cell(&mut self, corners: &[Point3], turn: Ordering) {
        let n = corners.len();
        let mut lines = Vec::with_capacity(n);
        for i in 0..n {
            match self.line(Kind::Sight(corners[i], corners[(i + 1) % n])) {
                Trace::Line(l, s) => {
                    let (l, t) = self.resolve(l);
                    lines.push((l, times(s, t)));
                }
                // An edge whose sight plane misses F's plane (only for a face far from planar):
                // the triangle has no picture in F's plane.
                Trace::Constant(_) => return,
            }
        }
        let v: Vec<u32> = (0..n)
            .map(|i| self.crossing(lines[(i + n - 1) % n].0, lines[i].0, Some(corners[i])))
            .collect();
        let e = lines
            .into_iter()
            .map(|(l, s)| (l, times(turn, s)))
            .collect();
        let extent = self.extent_of(&v);
        self.cells.push(Cell { v, e, extent });
    }

    /// The trace of the plane `kind` in F's plane: a line (the same id as for the same plane
    /// met before, with the sign relating the two forms), or, for a plane parallel to F's,
    /// the one sign of its form on all of F's plane. Equal lines of different planes are only
    /// found when a line is about to bound cells ([`Vtp::resolve`]).
    pub(super) fn line(&mut self, kind: Kind) -> Trace {
        let (key, sign) = key(&kind);
        if let Some(&(id, first)) = self.kinds.get(&key) {
            return Trace::Line(id, times(sign, first));
        }
        let new = ArrangementLine::new(kind, &self.frame);
        if new.parallel(&self.frame) {
            return Trace::Constant(new.sign_at_origin(&self.frame));
        }
        self.lines.push(new);
        self.alias.push(None);
        let id = (self.lines.len() - 1) as u32;
        self.kinds.insert(key, (id, sign));
        Trace::Line(id, Ordering::Greater)
    }

    /// The line that stands for line `l` in the cells (the first equal line met that bounds
    /// cells, or `l` itself), and the sign relating their forms.
    pub(super) fn resolve(&mut self, l: u32) -> (u32, Ordering) {
        if let Some(found) = self.alias[l as usize] {
            return found;
        }
        let frame = &self.frame;
        let new = &self.lines[l as usize];
        let (q, (c, _)) = (new.direction_estimate(), new.coefficients());
        let found = self
            .bounding
            .find(&c, &q, |u| self.same_trace(u, l))
            .map_or((l, Ordering::Greater), |u| {
                let a = &self.lines[u as usize];
                (u, Alignment { frame, a, b: new }.sign())
            });
        if found.0 == l {
            self.bounding.insert(l, &c, &q);
        }
        self.alias[l as usize] = Some(found);
        found
    }

    /// A point defining line `l` whose picture is vertex `v`, the crossing of two sight planes
    /// (the point lies on both).
    pub(super) fn input_on(&self, v: u32, l: u32) -> Option<Point3> {
        let eye = &self.frame.eye;
        let [a, b] = self.vertices[v as usize]
            .lines
            .map(|a| self.lines[a as usize].kind);
        if !matches!((a, b), (Kind::Sight(..), Kind::Sight(..))) {
            return None;
        }
        let points = match &self.lines[l as usize].kind {
            Kind::Sight(p, q) => vec![*p, *q],
            Kind::Plane(t) => t.to_vec(),
            Kind::Frustum(..) => Vec::new(),
        };
        points
            .into_iter()
            .find(|p| a.sign_at(eye, p) == Ordering::Equal && b.sign_at(eye, p) == Ordering::Equal)
    }

    /// Whether lines `a` and `b` are the same line: for two sight planes, whether they are the
    /// same plane (the ends of one on the other); for two planes, when they are the same plane
    /// or else by the general test ([`lines::coincide`]).
    pub(super) fn same_trace(&self, a: u32, b: u32) -> bool {
        let eye = &self.frame.eye;
        let (la, lb) = (&self.lines[a as usize], &self.lines[b as usize]);
        // Traces that cross are not the same line: the estimate of `W` tells most pairs.
        let w = Turn {
            frame: &self.frame,
            a: la,
            b: lb,
        }
        .estimate();
        if w.value.is_finite() && w.value.abs() > w.bound {
            return false;
        }
        match (la.kind, lb.kind) {
            (Kind::Sight(..), Kind::Sight(p, q)) => {
                la.kind.sign_at(eye, &p) == Ordering::Equal
                    && la.kind.sign_at(eye, &q) == Ordering::Equal
            }
            (Kind::Plane(_), Kind::Plane(t))
                if t.iter().all(|p| la.kind.sign_at(eye, p) == Ordering::Equal) =>
            {
                true
            }
            _ => lines::coincide(&self.frame, la, lb),
        }
    }

    /// The vertex where lines `a` and `b` cross (`input`: the input point it is known to be
    /// the picture of).
    pub(super) fn crossing(&mut self, a: u32, b: u32, input: Option<Point3>) -> u32 {
        let key = (a.min(b), a.max(b));
        if let Some(&v) = self.crossings.get(&key) {
            return v;
        }
        let input = input
            .or_else(|| self.input_at(a, b))
            .map(|p| (p, self.on_f(&p)))
            .filter(|&(p, on_plane)| on_plane || self.seen_through(&p));
        let at = match input {
            Some((p, on_plane)) => At::Input(p, on_plane),
            None => self.cut_at(a, b),
        };
        let frame = &self.frame;
        let (la, lb) = (&self.lines[a as usize], &self.lines[b as usize]);
        let turn = Turn {
            frame,
            a: la,
            b: lb,
        }
        .sign();
        let crossing = Crossing::new(la, lb);
        self.vertices.push(Vertex {
            lines: [a, b],
            at,
            turn,
            crossing,
            extent: crossing.extent(),
        });
        let v = (self.vertices.len() - 1) as u32;
        self.crossings.insert(key, v);
        v
    }

    /// Whether the point of F's plane on the line through the eye and the input point `p` (off
    /// F's plane) lies on `p`'s side of the eye, so that sight planes have the same sign at
    /// both and `p`'s picture is the point's: with `I_F` the form of F's plane at the eye,
    /// when `I_F − s_F(p)` has the sign of `I_F`. Always so when nothing lies behind the eye
    /// (the point is then a point of F, in front of the eye, as `p` is).
    pub(super) fn seen_through(&self, p: &Point3) -> bool {
        if !self.behind {
            return true;
        }
        let [f0, f1, f2] = &self.frame.plane;
        let eye = &self.frame.eye;
        Difference(
            eye.determinant(f0, f1, f2),
            Kind::Plane(self.frame.plane).at(eye, p),
        )
        .sign()
            == self.eye_side
    }

    /// Whether the input point `p` lies on F's plane.
    pub(super) fn on_f(&self, p: &Point3) -> bool {
        let key = p.coords.map(f64::to_bits).into();
        if let Some(&known) = self.on_plane.borrow().get(&key) {
            return known;
        }
        let [f0, f1, f2] = &self.frame.plane;
        let on = orient3d(f0, f1, f2, p) == Ordering::Equal;
        self.on_plane.borrow_mut().insert(key, on);
        on
    }

    /// The crossing of lines `a` and `b` as the cut of an edge, when one is: an edge lying in
    /// F's plane cut by the other plane, or an edge of an occluder through F's plane (the
    /// other line is the occluder's plane, which holds the edge).
    pub(super) fn cut_at(&self, a: u32, b: u32) -> At {
        let eye = &self.frame.eye;
        let (ka, kb) = (self.lines[a as usize].kind, self.lines[b as usize].kind);
        let f = Kind::Plane(self.frame.plane);
        let cut = |p: Point3, q: Point3, m: Kind| {
            let d = Difference(m.at(eye, &p), m.at(eye, &q)).sign();
            At::Cut(p, q, m, d)
        };
        for (edge, other) in [(ka, kb), (kb, ka)] {
            if let Kind::Sight(p, q) = edge
                && self.on_f(&p)
                && self.on_f(&q)
            {
                return cut(p, q, other);
            }
        }
        for (edge, other) in [(ka, kb), (kb, ka)] {
            if let (Kind::Sight(p, q), Kind::Plane(_)) = (edge, other)
                && other.sign_at(eye, &p) == Ordering::Equal
                && other.sign_at(eye, &q) == Ordering::Equal
            {
                return cut(p, q, f);
            }
        }
        At::General
    }

    /// The input point whose picture is where lines `a` and `b` cross, when their planes show
    /// one at once: an end shared by two edges, an end of one edge on the other's sight
    /// plane, or a point of both planes on F's plane.
    pub(super) fn input_at(&self, a: u32, b: u32) -> Option<Point3> {
        let eye = &self.frame.eye;
        let on_f = |p: &Point3| self.on_f(p);
        let (ka, kb) = (self.lines[a as usize].kind, self.lines[b as usize].kind);
        let ends = |k: &Kind| -> Vec<Point3> {
            match k {
                Kind::Sight(p, q) => vec![*p, *q],
                Kind::Plane(t) => t.to_vec(),
                Kind::Frustum(..) => Vec::new(),
            }
        };
        match (ka, kb) {
            (Kind::Sight(..), Kind::Sight(..)) => {
                let (ea, eb) = (ends(&ka), ends(&kb));
                ea.iter()
                    .find(|p| eb.contains(p))
                    .or_else(|| eb.iter().find(|p| ka.sign_at(eye, p) == Ordering::Equal))
                    .or_else(|| ea.iter().find(|p| kb.sign_at(eye, p) == Ordering::Equal))
                    .copied()
            }
            _ => {
                let (ea, eb) = (ends(&ka), ends(&kb));
                ea.iter()
                    .find(|p| on_f(p) && kb.sign_at(eye, p) == Ordering::Equal)
                    .or_else(|| {
                        eb.iter()
                            .find(|p| on_f(p) && ka.sign_at(eye, p) == Ordering::Equal)
                    })
                    .copied()
            }
        }
    }

    /// The box of the cell with vertices `v`: the box of their boxes, when they all have one.
    pub(super) fn extent_of(&self, v: &[u32]) -> Option<Extent> {
        let mut boxes = v.iter().map(|&v| self.vertices[v as usize].extent);
        let first = boxes.next()??;
        boxes.try_fold(first, |all, b| Some(all.union(&b?)))
    }

    /// Line `l`'s form times `side`, for the box filter (see
    /// [`extent`](crate::surfaces::extent)).
    pub(super) fn signed_form(&self, l: u32, side: Ordering) -> Option<SignedForm> {
        let (c, g) = self.lines[l as usize].coefficients();
        SignedForm::new(c, g, side)
    }

    /// The exact sign of line `l`'s form at vertex `v`.
    pub(super) fn sign_at(&mut self, v: u32, l: u32) -> Ordering {
        let vx = &self.vertices[v as usize];
        if vx.lines.contains(&l) {
            return Ordering::Equal;
        }
        let eye = &self.frame.eye;
        let line = &self.lines[l as usize];
        match vx.at {
            // Along the line of sight through an input point every sight plane keeps its
            // side; on F's plane the vertex is the point itself.
            At::Input(p, on_plane) if on_plane || matches!(line.kind, Kind::Sight(..)) => {
                return line.kind.sign_at(eye, &p);
            }
            At::Input(p, _) => {
                if let Kind::Plane(t) = line.kind {
                    return self.sign_on_sight_line(&p, &t);
                }
            }
            At::Cut(a, b, m, d) => return times(cut_sign(eye, &a, &b, &m, &line.kind), d),
            At::General => {}
        }
        let side = SideAtVertex {
            frame: &self.frame,
            a: &self.lines[vx.lines[0] as usize],
            b: &self.lines[vx.lines[1] as usize],
            at: &vx.crossing,
            l: line,
        };
        let turn = vx.turn;
        match side.estimate().sign() {
            Some(s) => times(s, turn),
            None => {
                if let Some(&s) = self.exact.get(&(v, l)) {
                    return s;
                }
                if vx.lines.iter().any(|&a| self.same_trace(a, l)) {
                    self.exact.insert((v, l), Ordering::Equal);
                    return Ordering::Equal;
                }
                // The picture of an input point of `l` on both sight planes.
                if let Some(p) = self.input_on(v, l)
                    && (self.on_f(&p) || self.seen_through(&p))
                {
                    let on_plane = self.on_f(&p);
                    self.vertices[v as usize].at = At::Input(p, on_plane);
                    return self.sign_at(v, l);
                }
                let s = times(side.sign(), turn);
                self.exact.insert((v, l), s);
                s
            }
        }
    }

    /// The sign of the form of the plane through `t` at the point of F's plane on the line of
    /// sight through the input point `p`: with `I` the forms' values at the eye (towards it,
    /// for an eye at infinity), that point is where `I_F s(p) − s_F(p) I` vanishes along the
    /// line, so the sign is that of `I_F s_L(p) − I_L s_F(p)` (degree 6) times the eye's side
    /// of F.
    pub(super) fn sign_on_sight_line(&self, p: &Point3, t: &[Point3; 3]) -> Ordering {
        let eye = &self.frame.eye;
        let [f0, f1, f2] = &self.frame.plane;
        let (f, l) = (Kind::Plane(self.frame.plane), Kind::Plane(*t));
        let value = Difference(
            Product(eye.determinant(f0, f1, f2), l.at(eye, p)),
            Product(eye.determinant(&t[0], &t[1], &t[2]), f.at(eye, p)),
        );
        times(value.sign(), self.eye_side)
    }
}

/// A key for a plane by the bits of its points (a sight plane's ends in increasing order),
/// and the sign relating its form to the form of the plane with the key's points in order.
pub(super) fn key(kind: &Kind) -> ([u64; 9], Ordering) {
    let bits = |p: &Point3| p.coords.map(f64::to_bits);
    match kind {
        Kind::Sight(a, b) => {
            let (ba, bb) = (bits(a), bits(b));
            let (first, second, sign) = if ba.as_slice() <= bb.as_slice() {
                (ba, bb, Ordering::Greater)
            } else {
                (bb, ba, Ordering::Less)
            };
            let mut k = [0; 9];
            k[..3].copy_from_slice(first.as_slice());
            k[3..6].copy_from_slice(second.as_slice());
            // A tag no coordinate's bits can take in the last place: NaN's pattern.
            k[6..].fill(u64::MAX);
            (k, sign)
        }
        Kind::Plane(t) => {
            let mut k = [0; 9];
            for (i, p) in t.iter().enumerate() {
                k[3 * i..3 * i + 3].copy_from_slice(bits(p).as_slice());
            }
            (k, Ordering::Greater)
        }
        Kind::Frustum(normal, offset) => {
            let mut k = [0; 9];
            k[..3].copy_from_slice(normal.map(f64::to_bits).as_slice());
            k[3] = offset.to_bits();
            // A tag of its own (a sight plane's is all of the last three).
            k[4..].fill(u64::MAX - 1);
            (k, Ordering::Greater)
        }
    }
}

/// The sign of the form of `l`, times that of `m(a) − m(b)`, at the point of the line `ab`
/// where the form of `m` vanishes: the sign of `m(a) l(b) − m(b) l(a)` (degree 6), at once when
/// `l` vanishes at `a` or `b`.
pub(super) fn cut_sign(eye: &Eye, a: &Point3, b: &Point3, m: &Kind, l: &Kind) -> Ordering {
    match (l.sign_at(eye, a), l.sign_at(eye, b)) {
        (Ordering::Equal, Ordering::Equal) => Ordering::Equal,
        (Ordering::Equal, lb) => times(m.at(eye, a).sign(), lb),
        (la, Ordering::Equal) => times(m.at(eye, b).sign(), la).reverse(),
        _ => Difference(
            Product(m.at(eye, a), l.at(eye, b)),
            Product(m.at(eye, b), l.at(eye, a)),
        )
        .sign(),
    }
}

/// The form of a line's plane, as the hidden-line queries know it.
pub(super) fn form(kind: &Kind) -> Form {
    match kind {
        Kind::Sight(a, b) => Form::Sight(*a, *b),
        Kind::Plane(t) => Form::Plane(*t),
        Kind::Frustum(normal, offset) => Form::Frustum(*normal, *offset),
    }
}

/// The sign of a product of two signs.
pub(super) fn times(a: Ordering, b: Ordering) -> Ordering {
    match (a, b) {
        (Ordering::Equal, _) | (_, Ordering::Equal) => Ordering::Equal,
        _ if a == b => Ordering::Greater,
        _ => Ordering::Less,
    }
}
