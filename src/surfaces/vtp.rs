//! VTP(F), exactly: the face minus the union of what its occluders hide of it, as convex cells
//! of F's plane whose vertices are points of the input's planes, merged into polygons.
//!
//! Franklin's VISFAC starts VTP(F) as F and takes away, occluder by occluder, the part each
//! hides. Here VTP(F) is a set of convex cells with disjoint interiors in F's plane, each a
//! cycle of vertices and of the lines between them (see [`super::lines`]: every line is the
//! trace of a sight plane or of an occluder's plane; every vertex is where two of them cross).
//! What an occluder face G hides of F is the convex piece of F's plane inside the sight planes
//! of G's edges and strictly behind G's plane. Taking it from a cell splits the cell by the
//! piece's lines one after another (the parts outside each line stay, the part inside all of
//! them goes), and leaves the cell whole when the piece's interior misses it: a line with every
//! vertex of the cell weakly outside, or an empty remainder. Every decision is the exact sign
//! of a line's form at a vertex, so a cell is kept exactly when it has area, and VTP(F) is
//! empty exactly when the union of the pieces covers F.
//!
//! The cells are then merged into polygons: along each line, the cells' edges are cut where
//! their endpoints fall (in an exact order along the line); a piece of line is part of the
//! boundary when exactly one of its sides is covered by a cell, and joins the cells on its two
//! sides otherwise. The boundary pieces are linked into rings (at a point where rings touch,
//! the next piece is the first one clockwise from the way back, so each ring keeps its own
//! region on its left), vertices between two pieces of one line are dropped, a ring passing
//! twice through a point is split there, and each ring is an outer ring or a hole as it turns
//! once counter-clockwise or clockwise (angles from rounded directions, their signs exact).
//! Rings of no area, spikes and vertices on an edge cannot arise: each would need a piece of
//! boundary with cells on both sides or on neither.
//!
//! Each vertex of the result is built once from the input: the picture of an input vertex by
//! [`Picture::point`]; a point where an edge of F (or of an occluder lying in F's plane) meets
//! another plane, or where an occluder's edge pierces F's plane, by the cut of that edge
//! ([`cut_point`], exact expansions rounded once); any other point from the three planes that
//! make it ([`lines::construct`]). Its texture coordinates likewise.

use super::lines::{self, Alignment, Crossing, Frame, Kind, Line, Side, Turn};
use crate::geometry::Point3;
use crate::geometry::kernel::{Difference, Polynomial, Product};
use crate::geometry::predicates::orient3d;
use crate::mesh::TextureFrame;
use crate::queries::along::{Form, cut_point, cut_point_on_plane};
use crate::queries::frustum::Clip;
use crate::views::{Eye, Picture};
use geo::{Coord, LineString, MultiPolygon, Polygon};
use std::cell::RefCell;
use std::cmp::Ordering;
use std::collections::HashMap;

/// A point of F's plane where two lines cross.
#[derive(Debug, Clone)]
struct Vertex {
    /// The two lines (crossing, not parallel).
    lines: [u32; 2],
    /// What else is known of the point.
    at: At,
    /// The exact sign of `W` for its two lines.
    turn: Ordering,
    /// The estimates of `W` and `N`.
    crossing: Crossing,
}

/// What is known of a vertex beyond its two lines: it decides the cheapest exact sign of a
/// form there and how its picture is built.
#[derive(Debug, Clone, Copy)]
enum At {
    /// The picture of the input point `p`: `p` itself when it lies on F's plane (`true`), else
    /// the point of F's plane on `p`'s line of sight.
    Input(Point3, bool),
    /// The point of the line through the input points `a` and `b` where the form of the plane
    /// `m` vanishes (the line lies in F's plane, or `m` is F's plane), with the sign of
    /// `m(a) − m(b)`.
    Cut(Point3, Point3, Kind, Ordering),
    /// Only the three planes.
    General,
}

/// A convex cell: vertex `v[i]` to `v[i + 1]` runs along line `e[i].0`, the cell lying where
/// that line's form has sign `e[i].1`.
#[derive(Debug, Clone)]
struct Cell {
    v: Vec<u32>,
    e: Vec<(u32, Ordering)>,
}

/// VTP(F) being built.
pub(super) struct Vtp<'a> {
    frame: Frame,
    /// The side of F's plane the eye is on.
    eye_side: Ordering,
    /// F's vertex loop.
    face: Vec<Point3>,
    picture: &'a Picture,
    /// The lines met so far.
    lines: Vec<Line>,
    /// The line for each plane met, by the plane's key, with the sign relating the line's
    /// form to the key's.
    kinds: HashMap<[u64; 9], (u32, Ordering)>,
    /// For each line, once resolved, the line standing for it in the cells and the sign
    /// relating their forms.
    alias: Vec<Option<(u32, Ordering)>>,
    /// The lines that bound cells: distinct as lines.
    bounding: Vec<u32>,
    vertices: Vec<Vertex>,
    /// The vertex where two lines cross, by the pair.
    crossings: HashMap<(u32, u32), u32>,
    /// Whether an input point lies on F's plane, by the bits of its coordinates (F's corners
    /// known at once: the exact test is slow for points on the plane).
    on_plane: RefCell<HashMap<[u64; 3], bool>>,
    /// Signs that needed exact arithmetic, by (vertex, line).
    exact: HashMap<(u32, u32), Ordering>,
    cells: Vec<Cell>,
    /// Whether some occluder (or the frustum) took area away.
    changed: bool,
    /// Whether some of the scene may lie behind the eye ([`Vtp::may_see_behind`]): then an
    /// input point off F's plane stands for a vertex only when the two lie on the same side of
    /// the eye.
    behind: bool,
}

impl<'a> Vtp<'a> {
    /// VTP(F) = F: the face with vertex loop `corners` (either way round) and triangles
    /// `triangles`, `plane` spanning the plane the arrangement lies in (holding every corner
    /// when `planar`), seen from `eye` with turn `turn` (the eye's
    /// side of `plane`, not `Equal`). A convex face is one cell, any other its triangles.
    pub(super) fn new(
        corners: &[Point3],
        plane: &[Point3; 3],
        planar: bool,
        triangles: &[[Point3; 3]],
        eye: Eye,
        turn: Ordering,
        picture: &'a Picture,
    ) -> Vtp<'a> {
        let mut vtp = Vtp {
            frame: Frame::new(*plane, eye),
            eye_side: turn,
            face: corners.to_vec(),
            picture,
            lines: Vec::new(),
            kinds: HashMap::new(),
            alias: Vec::new(),
            bounding: Vec::new(),
            vertices: Vec::new(),
            crossings: HashMap::new(),
            on_plane: RefCell::new(
                plane
                    .iter()
                    .chain(corners.iter().filter(|_| planar))
                    .map(|c| (c.coords.map(f64::to_bits).into(), true))
                    .collect(),
            ),
            exact: HashMap::new(),
            cells: Vec::new(),
            changed: false,
            behind: false,
        };
        match vtp.convex(corners) {
            Some((loop_, turn)) => vtp.add_cell(&loop_, turn),
            None => {
                for t in triangles {
                    let turn = eye.orient3d(&t[0], &t[1], &t[2]);
                    if turn != Ordering::Equal {
                        vtp.add_cell(t, turn);
                    }
                }
            }
        }
        vtp
    }

    /// The corners of a polygon without those between two collinear edges (in the picture),
    /// and the way it turns, when it turns only one way, so is convex; `None` otherwise.
    fn convex(&self, corners: &[Point3]) -> Option<(Vec<Point3>, Ordering)> {
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
    fn add_cell(&mut self, corners: &[Point3], turn: Ordering) {
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
        self.cells.push(Cell { v, e });
    }

    /// The trace of the plane `kind` in F's plane: a line (the same id as for the same plane
    /// met before, with the sign relating the two forms), or, for a plane parallel to F's,
    /// the one sign of its form on all of F's plane. Equal lines of different planes are only
    /// found when a line is about to bound cells ([`Vtp::resolve`]).
    fn line(&mut self, kind: Kind) -> Trace {
        let (key, sign) = key(&kind);
        if let Some(&(id, first)) = self.kinds.get(&key) {
            return Trace::Line(id, times(sign, first));
        }
        let new = Line::new(kind, &self.frame);
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
    fn resolve(&mut self, l: u32) -> (u32, Ordering) {
        if let Some(found) = self.alias[l as usize] {
            return found;
        }
        let frame = &self.frame;
        let new = &self.lines[l as usize];
        let found = self
            .bounding
            .iter()
            .find(|&&u| self.same_trace(u, l))
            .map_or((l, Ordering::Greater), |&u| {
                let a = &self.lines[u as usize];
                (u, Alignment { frame, a, b: new }.sign())
            });
        if found.0 == l {
            self.bounding.push(l);
        }
        self.alias[l as usize] = Some(found);
        found
    }

    /// A point defining line `l` whose picture is vertex `v`, the crossing of two sight planes
    /// (the point lies on both).
    fn input_on(&self, v: u32, l: u32) -> Option<Point3> {
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
    fn same_trace(&self, a: u32, b: u32) -> bool {
        let eye = &self.frame.eye;
        let (la, lb) = (&self.lines[a as usize], &self.lines[b as usize]);
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
    fn crossing(&mut self, a: u32, b: u32, input: Option<Point3>) -> u32 {
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
        self.vertices.push(Vertex {
            lines: [a, b],
            at,
            turn,
            crossing: Crossing::new(la, lb),
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
    fn seen_through(&self, p: &Point3) -> bool {
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
    fn on_f(&self, p: &Point3) -> bool {
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
    fn cut_at(&self, a: u32, b: u32) -> At {
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
    fn input_at(&self, a: u32, b: u32) -> Option<Point3> {
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

    /// The exact sign of line `l`'s form at vertex `v`.
    fn sign_at(&mut self, v: u32, l: u32) -> Ordering {
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
        let side = Side {
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
    fn sign_on_sight_line(&self, p: &Point3, t: &[Point3; 3]) -> Ordering {
        let eye = &self.frame.eye;
        let [f0, f1, f2] = &self.frame.plane;
        let (f, l) = (Kind::Plane(self.frame.plane), Kind::Plane(*t));
        let value = Difference(
            Product(eye.determinant(f0, f1, f2), l.at(eye, p)),
            Product(eye.determinant(&t[0], &t[1], &t[2]), f.at(eye, p)),
        );
        times(value.sign(), self.eye_side)
    }

    /// Takes away what the occluder face with vertex loop `corners`, a triangle `plane` of its
    /// vertices and triangles `triangles` hides: as one convex piece when it lies exactly in
    /// `plane` (`planar`) and is convex in the picture, else triangle by triangle (each exactly planar).
    pub(super) fn subtract(
        &mut self,
        corners: &[Point3],
        plane: [Point3; 3],
        planar: bool,
        triangles: &[[Point3; 3]],
    ) {
        let eye = self.frame.eye;
        let plane = &plane;
        let [g0, g1, g2] = plane;
        let turn = eye.orient3d(g0, g1, g2);
        if planar
            && turn != Ordering::Equal
            && let Some((loop_, loop_turn)) = self.convex(corners)
        {
            self.subtract_piece(&loop_, loop_turn, plane, turn);
            return;
        }
        // The triangles of a planar face turn like it: each is cut off by the face's plane as
        // given, the same whatever the triangulation.
        for t in triangles {
            let turn = eye.orient3d(&t[0], &t[1], &t[2]);
            if turn != Ordering::Equal {
                if planar {
                    self.subtract_piece(t, turn, plane, eye.orient3d(g0, g1, g2));
                } else {
                    self.subtract_piece(t, turn, t, turn);
                }
            }
        }
    }

    /// Takes away what the convex polygon `corners` (turning `turn` in the picture, in the plane
    /// of the triangle `plane`, which turns `plane_turn`) hides: the points inside the sight planes of its edges
    /// and strictly behind its plane (a line only when some vertex of F is strictly in front
    /// of the plane; nothing when none is strictly behind it).
    fn subtract_piece(
        &mut self,
        corners: &[Point3],
        turn: Ordering,
        plane: &[Point3; 3],
        plane_turn: Ordering,
    ) {
        let [g0, g1, g2] = plane;
        let sides: Vec<Ordering> = self.face.iter().map(|v| orient3d(g0, g1, g2, v)).collect();
        if !sides.contains(&plane_turn.reverse()) {
            return;
        }
        let n = corners.len();
        let mut kinds: Vec<(Kind, Ordering)> = (0..n)
            .map(|i| (Kind::Sight(corners[i], corners[(i + 1) % n]), turn))
            .collect();
        if sides.contains(&plane_turn) {
            kinds.push((Kind::Plane(*plane), plane_turn.reverse()));
        }
        let mut piece: Vec<(u32, Ordering)> = Vec::with_capacity(kinds.len());
        for (kind, side) in kinds {
            match self.line(kind) {
                Trace::Line(l, s) => piece.push((l, times(side, s))),
                // A plane parallel to F's: all of F's plane is on one side of it.
                Trace::Constant(s) if s == side => {}
                Trace::Constant(_) => return,
            }
        }
        let cells = std::mem::take(&mut self.cells);
        for cell in cells {
            match self.without(&cell, &piece) {
                Some(parts) => {
                    self.changed = true;
                    self.cells.extend(parts);
                }
                None => self.cells.push(cell),
            }
        }
    }

    /// Some of the scene may lie behind the eye (the view clips): an occluder's corner behind
    /// it may lie on a line of sight through a point of F in front of it.
    pub(super) fn may_see_behind(&mut self) {
        self.behind = true;
    }

    /// Keeps only the part of VTP(F) strictly inside the frustum `clip` (each of its planes a
    /// line of F's plane, or, for a plane parallel to F's, all of F's plane on one side).
    pub(super) fn clip(&mut self, clip: &Clip) {
        let mut region: Vec<(u32, Ordering)> = Vec::with_capacity(5);
        for (form, inside) in clip.planes() {
            let Form::Frustum(normal, offset) = form else {
                continue;
            };
            let kind = Kind::Frustum(normal, offset);
            match self.line(kind) {
                Trace::Line(l, s) => region.push((l, times(inside, s))),
                Trace::Constant(s) if s == inside => {}
                Trace::Constant(_) => {
                    self.changed |= !self.cells.is_empty();
                    self.cells.clear();
                    return;
                }
            }
        }
        let cells = std::mem::take(&mut self.cells);
        for cell in cells {
            let mut rest = cell;
            let mut kept = true;
            for &(k, side) in &region {
                let signs: Vec<Ordering> = rest
                    .v
                    .iter()
                    .map(|&v| times(self.sign_at(v, k), side))
                    .collect();
                if !signs.contains(&Ordering::Less) {
                    continue;
                }
                self.changed = true;
                if !signs.contains(&Ordering::Greater) {
                    kept = false;
                    break;
                }
                let (k, s) = self.resolve(k);
                rest = self.split(&rest, k, times(side, s), &signs).0;
            }
            if kept {
                self.cells.push(rest);
            }
        }
    }

    /// The parts of `cell` outside the convex `piece` (each line with the side of the piece),
    /// or `None` when the piece's interior misses the cell.
    fn without(&mut self, cell: &Cell, piece: &[(u32, Ordering)]) -> Option<Vec<Cell>> {
        // The signs of the cell's vertices, `Greater` on the piece's side of each line; a line
        // with the whole cell weakly outside: disjoint interiors.
        let mut table: Vec<Vec<Ordering>> = Vec::with_capacity(piece.len());
        for &(k, side) in piece {
            let signs: Vec<Ordering> = cell
                .v
                .iter()
                .map(|&v| times(self.sign_at(v, k), side))
                .collect();
            if !signs.contains(&Ordering::Greater) {
                return None;
            }
            table.push(signs);
        }
        let mut rest = cell.clone();
        let mut parts = Vec::new();
        for (&(k, side), known) in piece.iter().zip(&table) {
            let signs: Vec<Ordering> = rest
                .v
                .iter()
                .map(|&v| match cell.v.iter().position(|&u| u == v) {
                    Some(i) => known[i],
                    None => times(self.sign_at(v, k), side),
                })
                .collect();
            if !signs.contains(&Ordering::Less) {
                continue;
            }
            if !signs.contains(&Ordering::Greater) {
                return None;
            }
            // Signs against `k` are signs against the line standing for it, times `s`.
            let (k, s) = self.resolve(k);
            let (inside, outside) = self.split(&rest, k, times(side, s), &signs);
            parts.push(outside);
            rest = inside;
        }
        Some(parts)
    }

    /// The cell cut by line `k` into its part on side `side` and the part on the other, given
    /// the signs of its vertices (`Greater` on side `side`); both have vertices strictly on
    /// their sides.
    fn split(&mut self, cell: &Cell, k: u32, side: Ordering, signs: &[Ordering]) -> (Cell, Cell) {
        let n = cell.v.len();
        let mut inside = Cell {
            v: Vec::new(),
            e: Vec::new(),
        };
        let mut outside = inside.clone();
        for i in 0..n {
            let (si, sj) = (signs[i], signs[(i + 1) % n]);
            let (v, e) = (cell.v[i], cell.e[i]);
            if si != Ordering::Less {
                inside.v.push(v);
                inside
                    .e
                    .push(if si == Ordering::Equal && sj == Ordering::Less {
                        (k, side)
                    } else {
                        e
                    });
            }
            if si != Ordering::Greater {
                outside.v.push(v);
                outside
                    .e
                    .push(if si == Ordering::Equal && sj == Ordering::Greater {
                        (k, side.reverse())
                    } else {
                        e
                    });
            }
            if si != Ordering::Equal && sj == si.reverse() {
                let x = self.crossing(e.0, k, None);
                if si == Ordering::Greater {
                    inside.v.push(x);
                    inside.e.push((k, side));
                    outside.v.push(x);
                    outside.e.push(e);
                } else {
                    outside.v.push(x);
                    outside.e.push((k, side.reverse()));
                    inside.v.push(x);
                    inside.e.push(e);
                }
            }
        }
        (inside, outside)
    }

    /// Whether nothing is left.
    pub(super) fn is_empty(&self) -> bool {
        self.cells.is_empty()
    }

    /// Whether some occluder took area away.
    pub(super) fn changed(&self) -> bool {
        self.changed
    }

    /// The visible polygons, in the picture and in the texture coordinates `texture`: outer
    /// rings counter-clockwise in the picture, holes clockwise; each outer ring starts at the
    /// vertex before its leftmost (lowest) one, each hole at its leftmost; polygons and holes
    /// in the order of their leftmost vertices (the conventions of [`crate::clip`]).
    pub(super) fn polygons(
        mut self,
        texture: &TextureFrame,
        eye_side: Ordering,
    ) -> (MultiPolygon<f64>, MultiPolygon<f64>) {
        let merged = self.merge();
        let mut points: HashMap<u32, ([f64; 2], [f64; 2])> = HashMap::new();
        for (outer, holes) in &merged.polygons {
            for &v in outer.iter().chain(holes.iter().flatten()) {
                if let std::collections::hash_map::Entry::Vacant(e) = points.entry(v) {
                    e.insert(self.construct(&merged.classes[&v], texture));
                }
            }
        }
        // Rings in the picture: reversed when the eye sees F's plane from its negative side.
        let ring = |r: &Vec<u32>| -> Vec<([f64; 2], [f64; 2])> {
            let mut out: Vec<_> = r.iter().map(|v| points[v]).collect();
            if eye_side == Ordering::Less {
                out.reverse();
            }
            out
        };
        type Ring = Vec<([f64; 2], [f64; 2])>;
        let mut built: Vec<(Ring, Vec<Ring>)> = merged
            .polygons
            .iter()
            .map(|(outer, holes)| {
                let mut outer = ring(outer);
                rotate(&mut outer, 1);
                let mut holes: Vec<Ring> = holes.iter().map(ring).collect();
                for h in &mut holes {
                    rotate(h, 0);
                }
                holes.sort_by(|a, b| leftmost(a).total_cmp2(&leftmost(b)));
                (outer, holes)
            })
            .collect();
        built.sort_by(|a, b| leftmost(&a.0).total_cmp2(&leftmost(&b.0)));
        let polygon = |k: usize| -> MultiPolygon<f64> {
            built
                .iter()
                .map(|(outer, holes)| {
                    let ring = |r: &Ring| -> LineString<f64> {
                        r.iter()
                            .map(|p| {
                                let [x, y] = if k == 0 { p.0 } else { p.1 };
                                Coord { x, y }
                            })
                            .collect()
                    };
                    Polygon::new(ring(outer), holes.iter().map(ring).collect())
                })
                .collect()
        };
        (polygon(0), polygon(1))
    }

    /// The picture and texture coordinates of a point, from the vertices that are it: the
    /// picture of an input point, else the cut of an edge, else the point of three planes.
    fn construct(&self, class: &[u32], texture: &TextureFrame) -> ([f64; 2], [f64; 2]) {
        let eye = &self.frame.eye;
        let vertices: Vec<&Vertex> = class.iter().map(|&v| &self.vertices[v as usize]).collect();
        let general = |v: &Vertex| {
            lines::construct(
                &self.frame,
                &self.lines[v.lines[0] as usize],
                &self.lines[v.lines[1] as usize],
                self.picture,
                texture,
            )
        };
        for v in &vertices {
            if let At::Input(p, on_plane) = v.at {
                let uv = if on_plane {
                    lines::texture_of(texture, &p)
                } else {
                    lines::texture_on_sight_line(texture, &self.frame, &p)
                };
                return (self.picture.point(&p), uv);
            }
        }
        for v in &vertices {
            if let At::Cut(a, b, m, _) = v.at {
                let xy = match m {
                    Kind::Plane(t) if t == self.frame.plane => {
                        cut_point_on_plane(self.picture, eye, &t, &a, &b)
                    }
                    _ => cut_point(self.picture, eye, &form(&m), &a, &b),
                };
                return (xy, lines::texture_of_cut(texture, eye, &m, &a, &b));
            }
        }
        general(vertices[0])
    }

    /// The boundary of the union of the cells, as polygons of vertex ids (each standing for its
    /// class of equal points), outer rings counter-clockwise seen from the side F's plane's
    /// gradient points to.
    fn merge(&mut self) -> Merged {
        let mut points = UnionFind::new(self.vertices.len());
        let mut components = UnionFind::new(self.cells.len());
        // The cells' edges by line.
        let mut by_line: HashMap<u32, Vec<(u32, u32, Ordering, usize)>> = HashMap::new();
        for (c, cell) in self.cells.iter().enumerate() {
            let n = cell.v.len();
            for i in 0..n {
                let (l, side) = cell.e[i];
                by_line
                    .entry(l)
                    .or_default()
                    .push((cell.v[i], cell.v[(i + 1) % n], side, c));
            }
        }
        let mut line_ids: Vec<u32> = by_line.keys().copied().collect();
        line_ids.sort_unstable();
        // Boundary pieces: (from, to, line, direction along q_L, cell on the left).
        let mut pieces: Vec<Piece> = Vec::new();
        for l in line_ids {
            let edges = &by_line[&l];
            let mut ends: Vec<u32> = edges.iter().flat_map(|e| [e.0, e.1]).collect();
            ends.sort_unstable();
            ends.dedup();
            ends.sort_by(|&u, &v| self.along(l, u, v));
            // Positions of the distinct points along the line.
            let mut position: HashMap<u32, usize> = HashMap::new();
            let mut at: Vec<u32> = Vec::new();
            for (i, &v) in ends.iter().enumerate() {
                if i > 0 && self.along(l, ends[i - 1], v) == Ordering::Equal {
                    points.union(ends[i - 1] as usize, v as usize);
                } else {
                    at.push(v);
                }
                position.insert(v, at.len() - 1);
            }
            let intervals = at.len().saturating_sub(1);
            let mut cover: [Vec<Option<usize>>; 2] = [vec![None; intervals], vec![None; intervals]];
            for &(u, v, side, c) in edges {
                let (pu, pv) = (position[&u], position[&v]);
                let s = usize::from(side == Ordering::Less);
                for slot in &mut cover[s][pu.min(pv)..pu.max(pv)] {
                    *slot = Some(c);
                }
            }
            for j in 0..intervals {
                match (cover[0][j], cover[1][j]) {
                    (Some(a), Some(b)) => components.union(a, b),
                    // The cell on the positive side: walk against q_L, keeping it on the left.
                    (Some(c), None) => pieces.push(Piece {
                        from: at[j + 1],
                        to: at[j],
                        line: l,
                        forward: false,
                        cell: c,
                    }),
                    (None, Some(c)) => pieces.push(Piece {
                        from: at[j],
                        to: at[j + 1],
                        line: l,
                        forward: true,
                        cell: c,
                    }),
                    (None, None) => {}
                }
            }
        }
        for p in &mut pieces {
            p.from = points.find(p.from as usize) as u32;
            p.to = points.find(p.to as usize) as u32;
        }
        let rings = self.link(&pieces);
        // Group by connected cells: each group's counter-clockwise ring is its outer ring.
        let mut groups: HashMap<usize, (Vec<VertexRing>, Vec<VertexRing>)> = HashMap::new();
        let mut order: Vec<usize> = Vec::new();
        for ring in rings {
            let group = components.find(pieces[ring[0]].cell);
            let entry = groups.entry(group).or_insert_with(|| {
                order.push(group);
                (Vec::new(), Vec::new())
            });
            let outer = self.turning(&pieces, &ring) > 0.0;
            let vertices = ring.iter().map(|&p| pieces[p].from).collect();
            if outer {
                entry.0.push(vertices);
            } else {
                entry.1.push(vertices);
            }
        }
        let mut polygons = Vec::new();
        for g in order {
            let (outers, holes) = groups.remove(&g).unwrap_or_default();
            let mut outers = outers.into_iter();
            if let Some(first) = outers.next() {
                polygons.push((first, holes));
            }
            polygons.extend(outers.map(|o| (o, Vec::new())));
        }
        let mut classes: HashMap<u32, Vec<u32>> = HashMap::new();
        for v in 0..self.vertices.len() {
            classes
                .entry(points.find(v) as u32)
                .or_default()
                .push(v as u32);
        }
        Merged { polygons, classes }
    }

    /// The order of vertices `u` and `v` of line `l` along its direction `q_L`.
    fn along(&mut self, l: u32, u: u32, v: u32) -> Ordering {
        if u == v {
            return Ordering::Equal;
        }
        let [a, b] = self.vertices[u as usize].lines;
        let m = if a == l { b } else { a };
        let s = self.sign_at(v, m);
        if s == Ordering::Equal {
            return Ordering::Equal;
        }
        // s_M grows along q_L as det(g_F, g_L, g_M) = W(L, M).
        let turn = self.turn(l, m);
        times(s, turn).reverse()
    }

    /// The exact sign of `W` for lines `a` and `b`.
    fn turn(&self, a: u32, b: u32) -> Ordering {
        if a == b {
            return Ordering::Equal;
        }
        Turn {
            frame: &self.frame,
            a: &self.lines[a as usize],
            b: &self.lines[b as usize],
        }
        .sign()
    }

    /// The boundary pieces linked into rings (of piece indices): at a point with several ways
    /// on, the first one clockwise from the way back; pieces along one line merged; rings
    /// through a point twice split there.
    fn link(&self, pieces: &[Piece]) -> Vec<Vec<usize>> {
        let mut leaving: HashMap<u32, Vec<usize>> = HashMap::new();
        for (i, p) in pieces.iter().enumerate() {
            leaving.entry(p.from).or_default().push(i);
        }
        let mut used = vec![false; pieces.len()];
        let mut rings = Vec::new();
        for start in 0..pieces.len() {
            if used[start] {
                continue;
            }
            let mut ring = Vec::new();
            let mut current = start;
            loop {
                used[current] = true;
                ring.push(current);
                let options = leaving.get(&pieces[current].to).map_or(&[][..], |v| &v[..]);
                let next = match options {
                    [only] => Some(*only),
                    _ => self.next_clockwise(pieces, current, options),
                };
                match next {
                    Some(n) if n == start => break,
                    Some(n) if !used[n] => current = n,
                    // Not closed (cannot happen for a boundary of cells): drop the ring.
                    _ => {
                        ring.clear();
                        break;
                    }
                }
            }
            if !ring.is_empty() {
                rings.extend(split_at_repeats(pieces, ring));
            }
        }
        rings
            .into_iter()
            .map(|r| merge_collinear(pieces, r))
            .filter(|r| r.len() >= 3)
            .collect()
    }

    /// Among `options` leaving the end of piece `incoming`, the first clockwise from the way
    /// back along `incoming` (seen from the side F's plane's gradient points to).
    fn next_clockwise(
        &self,
        pieces: &[Piece],
        incoming: usize,
        options: &[usize],
    ) -> Option<usize> {
        let back = (pieces[incoming].line, !pieces[incoming].forward);
        let dir = |p: usize| (pieces[p].line, pieces[p].forward);
        let orient = |x: (u32, bool), y: (u32, bool)| -> Ordering {
            let t = self.turn(x.0, y.0);
            if x.1 == y.1 { t } else { t.reverse() }
        };
        let half = |p: usize| match orient(back, dir(p)) {
            Ordering::Less => 0,
            Ordering::Equal => 1,
            Ordering::Greater => 2,
        };
        options.iter().copied().min_by(|&x, &y| {
            half(x)
                .cmp(&half(y))
                .then_with(|| match orient(dir(x), dir(y)) {
                    Ordering::Less => Ordering::Less,
                    Ordering::Greater => Ordering::Greater,
                    Ordering::Equal => x.cmp(&y),
                })
        })
    }

    /// The total turning of a ring of pieces, in radians (±2π): each turn's size from the
    /// rounded directions of the lines, its sign exact.
    fn turning(&self, pieces: &[Piece], ring: &[usize]) -> f64 {
        let n = ring.len();
        let direction = |p: &Piece| {
            let d = self.lines[p.line as usize].direction();
            let s = if p.forward { 1.0 } else { -1.0 };
            let norm = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
            d.map(|c| s * c / norm)
        };
        (0..n)
            .map(|i| {
                let (p, q) = (&pieces[ring[i]], &pieces[ring[(i + 1) % n]]);
                let (a, b) = (direction(p), direction(q));
                let cross = [
                    a[1] * b[2] - a[2] * b[1],
                    a[2] * b[0] - a[0] * b[2],
                    a[0] * b[1] - a[1] * b[0],
                ];
                let size = (cross[0] * cross[0] + cross[1] * cross[1] + cross[2] * cross[2])
                    .sqrt()
                    .atan2(a[0] * b[0] + a[1] * b[1] + a[2] * b[2]);
                let t = self.turn(p.line, q.line);
                let sign = if p.forward == q.forward {
                    t
                } else {
                    t.reverse()
                };
                match sign {
                    Ordering::Greater => size,
                    Ordering::Less => -size,
                    Ordering::Equal => 0.0,
                }
            })
            .sum()
    }
}

/// A key for a plane by the bits of its points (a sight plane's ends in increasing order),
/// and the sign relating its form to the form of the plane with the key's points in order.
fn key(kind: &Kind) -> ([u64; 9], Ordering) {
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

/// The trace of a plane in F's plane.
enum Trace {
    /// A line, and the sign relating the plane's form to the line's.
    Line(u32, Ordering),
    /// No line: the plane is parallel to F's plane, and its form has this sign on all of it.
    Constant(Ordering),
}

/// A piece of the boundary of the cells' union: from one point to another along a line, the
/// way `q_L` points (`forward`) or against it, with a cell on its left.
#[derive(Debug, Clone, Copy)]
struct Piece {
    from: u32,
    to: u32,
    line: u32,
    forward: bool,
    cell: usize,
}

/// A ring of vertex ids.
type VertexRing = Vec<u32>;

/// What [`Vtp::merge`] finds: polygons of point classes and the classes' vertices.
struct Merged {
    polygons: Vec<(Vec<u32>, Vec<Vec<u32>>)>,
    classes: HashMap<u32, Vec<u32>>,
}

/// The ring split into rings through distinct points.
fn split_at_repeats(pieces: &[Piece], ring: Vec<usize>) -> Vec<Vec<usize>> {
    let mut out = Vec::new();
    let mut todo = vec![ring];
    while let Some(ring) = todo.pop() {
        let mut seen: HashMap<u32, usize> = HashMap::new();
        let repeat = ring
            .iter()
            .enumerate()
            .find_map(|(j, &p)| seen.insert(pieces[p].from, j).map(|i| (i, j)));
        match repeat {
            Some((i, j)) => {
                todo.push(ring[i..j].to_vec());
                todo.push(ring[j..].iter().chain(&ring[..i]).copied().collect());
            }
            None => out.push(ring),
        }
    }
    out
}

/// The ring with consecutive pieces along one line joined.
fn merge_collinear(pieces: &[Piece], ring: Vec<usize>) -> Vec<usize> {
    let n = ring.len();
    // Keep a piece when the one before it runs along another line.
    let kept: Vec<usize> = (0..n)
        .filter(|&i| pieces[ring[(i + n - 1) % n]].line != pieces[ring[i]].line)
        .map(|i| ring[i])
        .collect();
    if kept.is_empty() { ring } else { kept }
}

/// The sign of the form of `l`, times that of `m(a) − m(b)`, at the point of the line `ab`
/// where the form of `m` vanishes: the sign of `m(a) l(b) − m(b) l(a)` (degree 6), at once when
/// `l` vanishes at `a` or `b`.
fn cut_sign(eye: &Eye, a: &Point3, b: &Point3, m: &Kind, l: &Kind) -> Ordering {
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
fn form(kind: &Kind) -> Form {
    match kind {
        Kind::Sight(a, b) => Form::Sight(*a, *b),
        Kind::Plane(t) => Form::Plane(*t),
        Kind::Frustum(normal, offset) => Form::Frustum(*normal, *offset),
    }
}

/// The sign of a product of two signs.
fn times(a: Ordering, b: Ordering) -> Ordering {
    match (a, b) {
        (Ordering::Equal, _) | (_, Ordering::Equal) => Ordering::Equal,
        _ if a == b => Ordering::Greater,
        _ => Ordering::Less,
    }
}

/// The ring rotated so that its leftmost (then lowest) picture point comes at index `at`.
fn rotate(ring: &mut [([f64; 2], [f64; 2])], at: usize) {
    if ring.is_empty() {
        return;
    }
    let n = ring.len();
    let i = (0..n)
        .min_by(|&a, &b| ring[a].0.total_cmp2(&ring[b].0))
        .unwrap_or(0);
    ring.rotate_left((i + n - at) % n);
}

/// The leftmost (then lowest) picture point of a ring.
fn leftmost(ring: &[([f64; 2], [f64; 2])]) -> [f64; 2] {
    ring.iter()
        .map(|p| p.0)
        .min_by(|a, b| a.total_cmp2(b))
        .unwrap_or([0.0; 2])
}

/// Lexicographic total order on points.
trait TotalCmp2 {
    fn total_cmp2(&self, other: &Self) -> Ordering;
}

impl TotalCmp2 for [f64; 2] {
    fn total_cmp2(&self, other: &[f64; 2]) -> Ordering {
        self[0]
            .total_cmp(&other[0])
            .then(self[1].total_cmp(&other[1]))
    }
}

/// Disjoint sets of indices.
struct UnionFind(Vec<usize>);

impl UnionFind {
    fn new(n: usize) -> UnionFind {
        UnionFind((0..n).collect())
    }

    fn find(&mut self, mut i: usize) -> usize {
        while self.0[i] != i {
            self.0[i] = self.0[self.0[i]];
            i = self.0[i];
        }
        i
    }

    fn union(&mut self, a: usize, b: usize) {
        let (a, b) = (self.find(a), self.find(b));
        if a != b {
            self.0[a.max(b)] = a.min(b);
        }
    }
}
