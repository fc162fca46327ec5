//! Cell subtraction: what an occluder hides of F is a convex piece of F's plane; taking it
//! from a cell splits the cell by the piece's lines one after another, keeping the parts
//! outside each line and dropping the part inside all of them.

use super::signs::times;
use super::{Cell, Trace, Vtp};
use crate::geometry::Point3;
use crate::geometry::predicates::orient3d;
use crate::sight::along::Form;
use crate::sight::frustum::Clip;
use crate::surfaces::extent::SignedForm;
use crate::surfaces::lines::Kind;
use smallvec::SmallVec;
use std::cmp::Ordering;

impl<'a> Vtp<'a> {
    /// Takes away what the occluder face with vertex loop `corners`, a triangle `plane` of its
    /// vertices and triangles `triangles` hides: as one convex piece when it lies exactly in
    /// `plane` (`planar`) and is convex in the picture, else triangle by triangle (each exactly planar).
    pub(in crate::surfaces) fn subtract(
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
    pub(super) fn subtract_piece(
        &mut self,
        corners: &[Point3],
        turn: Ordering,
        plane: &[Point3; 3],
        plane_turn: Ordering,
    ) {
        let [g0, g1, g2] = plane;
        let (mut behind, mut in_front) = (false, false);
        for v in &self.face {
            let side = orient3d(g0, g1, g2, v);
            behind |= side == plane_turn.reverse();
            in_front |= side == plane_turn;
        }
        if !behind {
            return;
        }
        let n = corners.len();
        let mut kinds: SmallVec<[(Kind, Ordering); 8]> = (0..n)
            .map(|i| (Kind::Sight(corners[i], corners[(i + 1) % n]), turn))
            .collect();
        if in_front {
            kinds.push((Kind::Plane(*plane), plane_turn.reverse()));
        }
        let mut piece: SmallVec<[(u32, Ordering); 8]> = SmallVec::with_capacity(kinds.len());
        for (kind, side) in kinds {
            match self.line(kind) {
                Trace::Line(l, s) => piece.push((l, times(side, s))),
                // A plane parallel to F's: all of F's plane is on one side of it.
                Trace::Constant(s) if s == side => {}
                Trace::Constant(_) => return,
            }
        }
        // The piece's lines' forms, each times the piece's side: a cell whose box is certified
        // negative on one of them lies wholly outside the piece (see `extent`).
        let forms: SmallVec<[SignedForm; 8]> = piece
            .iter()
            .filter_map(|&(k, side)| self.signed_form(k, side))
            .collect();
        // The cells stay where they are until one is cut; from then on they are moved, in
        // order, to a new list with the parts in place of the cut ones.
        let mut rebuilt: Option<Vec<Cell>> = None;
        for i in 0..self.cells.len() {
            let missed = self.cells[i]
                .extent
                .as_ref()
                .is_some_and(|e| forms.iter().any(|f| e.surely_negative(f)));
            let parts = if missed {
                None
            } else {
                let cell = std::mem::take(&mut self.cells[i]);
                let parts = self.without(&cell, &piece);
                self.cells[i] = cell;
                parts
            };
            match (parts, &mut rebuilt) {
                (Some(parts), None) => {
                    let mut cells = Vec::with_capacity(self.cells.len() + parts.len());
                    cells.extend(self.cells[..i].iter_mut().map(std::mem::take));
                    cells.extend(parts);
                    rebuilt = Some(cells);
                }
                (Some(parts), Some(cells)) => cells.extend(parts),
                (None, Some(cells)) => cells.push(std::mem::take(&mut self.cells[i])),
                (None, None) => {}
            }
        }
        if let Some(cells) = rebuilt {
            self.changed = true;
            self.cells = cells;
        }
    }

    /// Some of the scene may lie behind the eye (the view clips): an occluder's corner behind
    /// it may lie on a line of sight through a point of F in front of it.
    pub(in crate::surfaces) fn may_see_behind(&mut self) {
        self.behind = true;
    }

    /// Keeps only the part of VTP(F) strictly inside the frustum `clip` (each of its planes a
    /// line of F's plane, or, for a plane parallel to F's, all of F's plane on one side).
    pub(in crate::surfaces) fn clip(&mut self, clip: &Clip) {
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
                rest.extent = self.extent_of(&rest.v);
                self.cells.push(rest);
            }
        }
    }

    /// The parts of `cell` outside the convex `piece` (each line with the side of the piece),
    /// or `None` when the piece's interior misses the cell.
    pub(super) fn without(&mut self, cell: &Cell, piece: &[(u32, Ordering)]) -> Option<Vec<Cell>> {
        // The signs of the cell's vertices, `Greater` on the piece's side of each line; a line
        // with the whole cell weakly outside: disjoint interiors.
        // One row of signs per line, kept inline (no allocation for a cell the piece misses).
        let n = cell.v.len();
        let mut table: SmallVec<[Ordering; 48]> = SmallVec::with_capacity(piece.len() * n);
        for &(k, side) in piece {
            let start = table.len();
            for &v in &cell.v {
                let sign = times(self.sign_at(v, k), side);
                table.push(sign);
            }
            if !table[start..].contains(&Ordering::Greater) {
                return None;
            }
        }
        let mut rest = cell.clone();
        let mut parts = Vec::new();
        for (&(k, side), known) in piece.iter().zip(table.chunks(n)) {
            let signs: SmallVec<[Ordering; 16]> = rest
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
            let (inside, mut outside) = self.split(&rest, k, times(side, s), &signs);
            outside.extent = self.extent_of(&outside.v);
            parts.push(outside);
            rest = inside;
        }
        Some(parts)
    }

    /// The cell cut by line `k` into its part on side `side` and the part on the other, given
    /// the signs of its vertices (`Greater` on side `side`); both have vertices strictly on
    /// their sides. Neither has its box yet: the caller gives one to the part it keeps.
    pub(super) fn split(
        &mut self,
        cell: &Cell,
        k: u32,
        side: Ordering,
        signs: &[Ordering],
    ) -> (Cell, Cell) {
        let n = cell.v.len();
        let mut inside = Cell {
            v: Vec::new(),
            e: Vec::new(),
            extent: None,
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
}
