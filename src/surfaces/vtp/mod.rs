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
//! empty exactly when the union of the pieces covers F. Most pieces miss most cells: a box
//! certified to hold each cell ([`Extent`]) on which one of the piece's forms is certified
//! negative tells such a miss before any sign is taken (on the bundled metropolis the rows
//! of signs taken fall from 11.0 M to 1.3 M).
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
//!
//! # Files
//! - [`signs`]: lines, vertices and exact signs;
//! - [`subtract`]: cell subtraction (occluder pieces and the clip);
//! - [`merge`]: merging the cells into polygons (disjoint sets of equal points and of
//!   connected cells, `crate::union_find`), and the construction of their vertices;
//! - [`rings`]: linking boundary pieces into rings;
//! - [`traces`]: the lines that bound cells, filed by the angle and distance of their traces,
//!   so that a line is compared only with those that may be the same line.

/// Merging the cells into polygons.
mod merge;
/// Boundary pieces linked into rings.
mod rings;
/// Lines, vertices and exact signs.
mod signs;
/// Cell subtraction.
mod subtract;
/// The lines that bound cells, by where they lie.
mod traces;

use super::extent::Extent;
use super::lines::{ArrangementLine, Crossing, Frame, Kind};
use crate::geometry::Point3;
use crate::views::{Eye, Picture};
use foldhash::fast::FixedState;
use std::cell::RefCell;
use std::cmp::Ordering;
use std::collections::HashMap;
use traces::Traces;

/// The maps of VTP(F): keys are ids and bits of coordinates, hashed fast and the same in
/// every run (nothing depends on their order).
type Map<K, V> = HashMap<K, V, FixedState>;

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
    /// A box certified to hold it, when `W` is certified nonzero.
    extent: Option<Extent>,
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
#[derive(Debug, Clone, Default)]
struct Cell {
    v: Vec<u32>,
    e: Vec<(u32, Ordering)>,
    /// A box certified to hold it (the box of its vertices' boxes), when they all have one.
    extent: Option<Extent>,
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
    lines: Vec<ArrangementLine>,
    /// The line for each plane met, by the plane's key, with the sign relating the line's
    /// form to the key's.
    kinds: Map<[u64; 9], (u32, Ordering)>,
    /// For each line, once resolved, the line standing for it in the cells and the sign
    /// relating their forms.
    alias: Vec<Option<(u32, Ordering)>>,
    /// The lines that bound cells: distinct as lines, filed by where they lie.
    bounding: Traces,
    vertices: Vec<Vertex>,
    /// The vertex where two lines cross, by the pair.
    crossings: Map<(u32, u32), u32>,
    /// Whether an input point lies on F's plane, by the bits of its coordinates (F's corners
    /// known at once: the exact test is slow for points on the plane).
    on_plane: RefCell<Map<[u64; 3], bool>>,
    /// Signs that needed exact arithmetic, by (vertex, line).
    exact: Map<(u32, u32), Ordering>,
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
        let frame = Frame::new(*plane, eye);
        let radius = corners
            .iter()
            .map(|c| (c - plane[0]).norm())
            .fold(0.0, f64::max);
        let mut vtp = Vtp {
            bounding: Traces::new(frame.normal(), radius),
            frame,
            eye_side: turn,
            face: corners.to_vec(),
            picture,
            lines: Vec::new(),
            kinds: Map::default(),
            alias: Vec::new(),
            vertices: Vec::new(),
            crossings: Map::default(),
            on_plane: RefCell::new(
                plane
                    .iter()
                    .chain(corners.iter().filter(|_| planar))
                    .map(|c| (c.coords.map(f64::to_bits).into(), true))
                    .collect(),
            ),
            exact: Map::default(),
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

    /// Whether nothing is left.
    pub(super) fn is_empty(&self) -> bool {
        self.cells.is_empty()
    }

    /// Whether some occluder took area away.
    pub(super) fn changed(&self) -> bool {
        self.changed
    }
}

/// The trace of a plane in F's plane.
enum Trace {
    /// A line, and the sign relating the plane's form to the line's.
    Line(u32, Ordering),
    /// No line: the plane is parallel to F's plane, and its form has this sign on all of it.
    Constant(Ordering),
}
