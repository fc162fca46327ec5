//! Intersection lines: where two faces pierce each other, in different objects or in one.
//!
//! Candidate triangle pairs are those whose boxes meet, found with a uniform 3-D grid over the
//! region where the two meshes' boxes overlap (a crowded cell, such as where the rims of two
//! fans of slivers meet, split into smaller cells: see [`candidates`]); objects whose CBOXes
//! do not overlap are not compared at all. Which vertices lie on which side of the other triangle's plane is
//! decided exactly, and two triangles pierce each other only when each has vertices strictly
//! on both sides of the other's plane, or lies on it along a diagonal of its flat face (the
//! face is then cut along the diagonal, whichever way it is triangulated): touching faces (a
//! box resting on another, neighbours sharing an edge or a vertex) make no intersection line,
//! and coplanar faces none either.
//!
//! The part of the line inside both triangles runs between two of the points where a
//! triangle's edge crosses the other's plane (or a vertex lies on it): each such end is an
//! input vertex or the crossing of an input edge with an input plane, and the four candidates
//! are ordered along the line exactly ([`Meet::compare`]). Where a face is a polygon whose
//! vertices lie exactly on one plane, that plane stands for all its triangles (through the
//! three of its vertices with the smallest indices that are not collinear), and the pieces of
//! one pair of faces that touch end to end are merged: a segment runs from face boundary to
//! face boundary, whatever the triangulation (a reversed face is triangulated differently).
//! Where several candidates are the same point, the end is named the same way whatever the
//! triangulation: an input vertex first, then the crossing of a face's edge (of the first
//! mesh, then of the second), then of a diagonal.

use super::along::{Form, Zero};
use super::meet::{Meet, OnLine, reversed};
use crate::geometry::Point3;
use crate::geometry::predicates::{collinear, orient3d};
use crate::mesh::Mesh;
use crate::views::Eye;
use candidates::candidate_pairs;
use rayon::prelude::*;
use std::cmp::Ordering;
use std::collections::HashMap;

mod candidates;
mod patches;

/// Which plane stands for a face in a segment: the face's own (its vertices lie exactly on one
/// plane), or one triangle's.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
pub(crate) enum PlaneKey {
    /// The plane of a face.
    Face(usize),
    /// The plane of a triangle of a face that is not exactly flat.
    Triangle(usize),
}

/// A maximal segment along which two faces (of meshes 0 and 1) pierce each other.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Segment {
    /// The line, on the planes of the two faces.
    pub meet: Meet,
    /// Its ends, in the line's direction.
    pub ends: [OnLine; 2],
    /// Its ends, approximately.
    pub points: [Point3; 2],
    /// The faces, in meshes 0 and 1.
    pub faces: [usize; 2],
    /// The pairs of triangles (in meshes 0 and 1) whose pieces make it up.
    pub triangles: Vec<[usize; 2]>,
}

/// The part of a segment from one pair of triangles.
#[derive(Debug, Clone, Copy)]
struct PairPiece {
    keys: [PlaneKey; 2],
    meet: Meet,
    ends: [OnLine; 2],
    faces: [usize; 2],
    triangles: [usize; 2],
}

/// The intersection segments of the faces of `m0` with those of `m1` (`same` when they are
/// one mesh: then each pair once, and triangles sharing a vertex or a face are not compared).
pub(crate) fn between(m0: &Mesh, m1: &Mesh, same: bool, eye: &Eye) -> Vec<Segment> {
    meetings(m0, m1, same, eye).0
}

/// [`between`], and the pairs of triangles `(t, u)` (in meshes `k` and `1 − k`, as
/// `[k, t, u]`) where a side of `t` crosses `u`'s plane strictly and passes through the closed
/// triangle `u`: an edge piercing a face, also where the faces along the edge only touch `u`
/// (an edge that enters a solid exactly across an edge of its surface, making no intersection
/// segment).
pub(crate) fn meetings(
    m0: &Mesh,
    m1: &Mesh,
    same: bool,
    eye: &Eye,
) -> (Vec<Segment>, Vec<[usize; 3]>) {
    let (crossing, contacts) = crossing_and_contacts(m0, m1, same);
    if crossing.is_empty() {
        return (Vec::new(), contacts);
    }
    // The plane of each face met, once.
    let planes = |m: &Mesh, side: usize| -> HashMap<usize, (PlaneKey, [Point3; 3])> {
        let mut faces: Vec<(usize, usize)> = crossing
            .iter()
            .map(|p| {
                let t = if side == 0 { p.0 } else { p.1 };
                (m.face_of(t), t)
            })
            .collect();
        faces.sort_unstable();
        faces.dedup_by_key(|f| f.0);
        faces
            .par_iter()
            .map(|&(f, t)| (f, plane_of(m, t)))
            .collect()
    };
    let (planes0, planes1) = (planes(m0, 0), planes(m1, 1));
    let plane = |m: &Mesh, planes: &HashMap<usize, (PlaneKey, [Point3; 3])>, t: usize| match planes
        [&m.face_of(t)]
    {
        (PlaneKey::Face(f), p) => (PlaneKey::Face(f), p),
        (PlaneKey::Triangle(_), _) => (PlaneKey::Triangle(t), m.triangle(t)),
    };
    let mut pieces: Vec<PairPiece> = crossing
        .par_iter()
        .filter_map(|&(i, j, sides)| {
            let planes = [plane(m0, &planes0, i), plane(m1, &planes1, j)];
            piece(m0, i, m1, j, sides, planes, eye)
        })
        .collect();
    pieces.par_sort_unstable_by(|x, y| x.keys.cmp(&y.keys).then(x.triangles.cmp(&y.triangles)));
    let groups: Vec<&[PairPiece]> = pieces.chunk_by(|x, y| x.keys == y.keys).collect();
    let segments = groups
        .par_iter()
        .flat_map_iter(|group| merged(group, eye))
        .collect();
    (segments, contacts)
}

/// The pairs of triangles that pierce each other (with their sides), and those where a face's
/// side passes through the other triangle (partners for piercings even where they make no
/// segment), as [`meetings`] returns them: `[k, t, u]`.
type Found = (Vec<(usize, usize, Sides)>, Vec<[usize; 3]>);

/// The candidate pairs of `m0` and `m1` ([`candidate_pairs`]) tested exactly: those that
/// pierce each other, and the contacts (see [`Found`]).
fn crossing_and_contacts(m0: &Mesh, m1: &Mesh, same: bool) -> Found {
    candidate_pairs(m0, m1, same)
        .par_iter()
        .fold(
            || (Vec::new(), Vec::new()),
            |(mut crossing, mut contacts): Found, &(i, j)| {
                let (i, j) = (i as usize, j as usize);
                if let Some([s0, s1]) = sides(m0, i, m1, j) {
                    if crosses(&s0, m0, i)
                        && crosses(&s1, m1, j)
                        && !surely_apart(&m0.triangle(i), &m1.triangle(j))
                    {
                        crossing.push((i, j, [s0, s1]));
                    }
                    // (Also for a pair that pierces: it may meet in one point, no segment.)
                    if straddles(&s0) || straddles(&s1) {
                        let (t0, t1) = (m0.triangle(i), m1.triangle(j));
                        if edge_through(&t0, &s0, m0, i, &t1) {
                            contacts.push([0, i, j]);
                        }
                        if edge_through(&t1, &s1, m1, j, &t0) {
                            contacts.push([1, j, i]);
                        }
                    }
                }
                (crossing, contacts)
            },
        )
        .reduce(
            || (Vec::new(), Vec::new()),
            |(mut a, mut b), (c, d)| {
                a.extend(c);
                b.extend(d);
                (a, b)
            },
        )
}

/// The pieces of one pair of planes, merged where they touch end to end.
fn merged(group: &[PairPiece], eye: &Eye) -> Vec<Segment> {
    let meet = group[0].meet;
    let mut order: Vec<&PairPiece> = group.iter().collect();
    order.sort_by(|x, y| {
        meet.compare(eye, &x.ends[0], &y.ends[0])
            .then(x.triangles.cmp(&y.triangles))
    });
    let mut out: Vec<Segment> = Vec::new();
    for p in order {
        if let Some(last) = out.last_mut()
            && meet.compare(eye, &last.ends[1], &p.ends[0]) != Ordering::Less
        {
            if meet.compare(eye, &last.ends[1], &p.ends[1]) == Ordering::Less {
                last.ends[1] = p.ends[1];
            }
            last.triangles.push(p.triangles);
            continue;
        }
        out.push(Segment {
            meet,
            ends: p.ends,
            points: [Point3::origin(); 2],
            faces: p.faces,
            triangles: vec![p.triangles],
        });
    }
    for s in &mut out {
        s.points = s.ends.map(|e| meet.approximate(eye, &e));
    }
    out
}

/// Whether the closed triangles `a` and `b` are certainly disjoint: some direction across an
/// edge of each (one of the nine cross products of their sides) separates their projections by
/// more than the rounding of the projections can move them. A filter before the exact section
/// of a pair whose planes cross (on a curved surface, most near neighbours cross each other's
/// planes without meeting): the direction may be rounded, any direction that separates proves
/// them apart; only the comparison must be sure, and each projection `p·d` is within
/// `γ₃·Σ|pₖ·dₖ|` of its rounded value (with a term for underflow).
fn surely_apart(a: &[Point3; 3], b: &[Point3; 3]) -> bool {
    const GAMMA: f64 = 4.0 * f64::EPSILON / 2.0;
    let sides = |t: &[Point3; 3]| [t[1] - t[0], t[2] - t[1], t[0] - t[2]];
    let (sa, sb) = (sides(a), sides(b));
    let range = |t: &[Point3; 3], d: &crate::geometry::Vector3| {
        t.iter().fold(
            (f64::INFINITY, f64::NEG_INFINITY, 0.0f64),
            |(lo, hi, err), p| {
                let v = p.x * d.x + p.y * d.y + p.z * d.z;
                let e = (p.x * d.x).abs() + (p.y * d.y).abs() + (p.z * d.z).abs();
                (lo.min(v), hi.max(v), err.max(e))
            },
        )
    };
    sa.iter().any(|ea| {
        sb.iter().any(|eb| {
            let d = ea.cross(eb);
            let (alo, ahi, ae) = range(a, &d);
            let (blo, bhi, be) = range(b, &d);
            let slack = GAMMA * (ae + be) + 8.0 * f64::MIN_POSITIVE;
            let gap = (blo - ahi).max(alo - bhi);
            gap.is_finite() && gap > slack
        })
    })
}

/// The plane that stands for the face of triangle `t`, and its key: for a face whose vertices
/// lie exactly on one plane, the three of them with the smallest indices that are not
/// collinear (in increasing order of index, so the same for the face reversed); else the
/// triangle itself.
pub(crate) fn plane_of(mesh: &Mesh, t: usize) -> (PlaneKey, [Point3; 3]) {
    let f = mesh.face_of(t);
    let mut idx = mesh.faces()[f].vertices().to_vec();
    idx.sort_unstable();
    let v = |i: u32| mesh.vertices()[i as usize];
    let (a, b) = (v(idx[0]), v(idx[1]));
    let third = idx[2..].iter().position(|&i| !collinear(&a, &b, &v(i)));
    if let Some(k) = third {
        let c = v(idx[2 + k]);
        // A face whose vertices share one coordinate is flat (boxes' faces), without asking.
        let level = (0..3).any(|axis| idx.iter().all(|&i| v(i)[axis] == a[axis]));
        let flat = level
            || idx[2..]
                .iter()
                .enumerate()
                .all(|(n, &i)| n == k || orient3d(&a, &b, &c, &v(i)) == Ordering::Equal);
        if flat {
            return (PlaneKey::Face(f), [a, b, c]);
        }
    }
    (PlaneKey::Triangle(t), mesh.triangle(t))
}

/// Which sides of triangle `t` of `mesh` are sides of its face (not diagonals of the face's
/// triangulation).
fn face_sides(mesh: &Mesh, t: usize) -> [bool; 3] {
    let tri = mesh.triangles()[t];
    let face = mesh.faces()[mesh.face_of(t)].vertices();
    let n = face.len();
    let at = |v: u32| face.iter().position(|&w| w == v);
    [0, 1, 2].map(|i| match (at(tri[i]), at(tri[(i + 1) % 3])) {
        (Some(x), Some(y)) => (x + 1) % n == y || (y + 1) % n == x,
        _ => false,
    })
}

/// The sides of each triangle's vertices against the other's plane.
type Sides = [[Ordering; 3]; 2];

/// The sides of each triangle's vertices against the other's plane, unless the first lies
/// strictly on one side of the second's (then they do not meet). They pierce each other only
/// when each crosses the other's plane (see [`crosses`]).
fn sides(m0: &Mesh, i: usize, m1: &Mesh, j: usize) -> Option<Sides> {
    let (t0, t1) = (m0.triangle(i), m1.triangle(j));
    let s0 = t0.map(|p| orient3d(&t1[0], &t1[1], &t1[2], &p));
    // Wholly on one side of the other's plane, the triangles do not meet; on it (coplanar),
    // neither crosses the other's plane.
    if s0[0] == s0[1] && s0[1] == s0[2] {
        return None;
    }
    let s1 = t1.map(|p| orient3d(&t0[0], &t0[1], &t0[2], &p));
    Some([s0, s1])
}

/// Whether triangle `t` of `mesh`, with the sides `s` of its vertices, crosses the other's
/// plane: it has vertices strictly on both sides ([`straddles`]), or it lies along it on a
/// diagonal of its face (two vertices on the plane, joined by a side of the triangle that is
/// not a side of the face). A flat face is then cut by the plane along that diagonal, its
/// triangles on either side of it: whichever way the face is triangulated, its segment is
/// found.
fn crosses(s: &[Ordering; 3], mesh: &Mesh, t: usize) -> bool {
    if straddles(s) {
        return true;
    }
    let on = s.iter().filter(|&&x| x == Ordering::Equal).count();
    let off = s.iter().position(|&x| x != Ordering::Equal);
    match off {
        Some(k) if on == 2 => !face_sides(mesh, t)[(k + 1) % 3],
        _ => false,
    }
}

/// The piece where triangle `i` of `m0` and triangle `j` of `m1` (which [`pierce`] each
/// other, with the sides `sides`; their faces' planes `planes`) meet, if they do along a
/// segment of positive length.
fn piece(
    m0: &Mesh,
    i: usize,
    m1: &Mesh,
    j: usize,
    [s0, s1]: Sides,
    [(k0, p0), (k1, p1)]: [(PlaneKey, [Point3; 3]); 2],
    eye: &Eye,
) -> Option<PairPiece> {
    let (t0, t1) = (m0.triangle(i), m1.triangle(j));
    // A triangle along the other's plane on a diagonal: only a flat face is cut there.
    let along = |s: &[Ordering; 3], key| !straddles(s) && matches!(key, PlaneKey::Triangle(_));
    if along(&s0, k0) || along(&s1, k1) {
        return None;
    }
    // The sides against the planes that stand for the faces (the triangles', or reversed).
    let s0 = against(s0, &p1, &t0);
    let s1 = against(s1, &p0, &t1);
    let meet = Meet { planes: [p0, p1] };
    let sides = [face_sides(m0, i), face_sides(m1, j)];
    let e0 = section(&meet, eye, 0, (&t0, &s0, &sides[0]), (&t1, &s1))?;
    let e1 = section(&meet, eye, 1, (&t1, &s1, &sides[1]), (&t0, &s0))?;
    // The later start and the earlier end; of two candidates at one point, the lower rank.
    let pick = |x: (OnLine, u8), y: (OnLine, u8), later: bool| match meet.compare(eye, &x.0, &y.0) {
        Ordering::Equal => {
            if x.1 <= y.1 {
                x
            } else {
                y
            }
        }
        Ordering::Less => {
            if later {
                y
            } else {
                x
            }
        }
        Ordering::Greater => {
            if later {
                x
            } else {
                y
            }
        }
    };
    let start = pick(e0[0], e1[0], true).0;
    let end = pick(e0[1], e1[1], false).0;
    (meet.compare(eye, &start, &end) == Ordering::Less).then_some(PairPiece {
        keys: [k0, k1],
        meet,
        ends: [start, end],
        faces: [m0.face_of(i), m1.face_of(j)],
        triangles: [i, j],
    })
}

/// The sides `s` of the vertices of `t` against its partner's triangle, made the sides against
/// `plane`, the same plane perhaps oriented the other way.
fn against(s: [Ordering; 3], plane: &[Point3; 3], t: &[Point3; 3]) -> [Ordering; 3] {
    let k = s.iter().position(|&x| x != Ordering::Equal).unwrap_or(0);
    if orient3d(&plane[0], &plane[1], &plane[2], &t[k]) == s[k] {
        s
    } else {
        s.map(Ordering::reverse)
    }
}

/// Whether the triangle has vertices strictly on both sides of the other's plane. Without,
/// the triangles are apart, coplanar, or only touch (a face resting on another meets it along
/// an edge that is drawn already): no intersection line.
/// Whether a side of triangle `t` (triangle `index` of `mesh`) that is a side of its face (the
/// vertices' sides `s` of `u`'s plane) crosses `u`'s plane strictly and passes through the
/// closed triangle `u`, decided exactly.
fn edge_through(
    t: &[Point3; 3],
    s: &[Ordering; 3],
    mesh: &Mesh,
    index: usize,
    u: &[Point3; 3],
) -> bool {
    if !straddles(s) {
        return false;
    }
    let edges = face_sides(mesh, index);
    (0..3).filter(|&k| edges[k]).any(|k| {
        let (a, b) = (&t[k], &t[(k + 1) % 3]);
        let crossing =
            s[k] != Ordering::Equal && s[(k + 1) % 3] != Ordering::Equal && s[k] != s[(k + 1) % 3];
        crossing && {
            let sides = [0, 1, 2].map(|m| orient3d(a, b, &u[m], &u[(m + 1) % 3]));
            !(sides.contains(&Ordering::Greater) && sides.contains(&Ordering::Less))
        }
    })
}

fn straddles(s: &[Ordering; 3]) -> bool {
    s.contains(&Ordering::Greater) && s.contains(&Ordering::Less)
}

/// The two ends of the section of triangle `t` (on side `side` of `meet`, with the sides `s`
/// of its vertices against the other plane and which of its sides are the face's) by the
/// other plane, in the line's direction, each with its rank (see the module documentation);
/// `other` is the other triangle with its vertices' sides against this plane.
fn section(
    meet: &Meet,
    eye: &Eye,
    side: usize,
    (t, s, face_sides): (&[Point3; 3], &[Ordering; 3], &[bool; 3]),
    (other, s_other): (&[Point3; 3], &[Ordering; 3]),
) -> Option<[(OnLine, u8); 2]> {
    let apart = other[s_other.iter().position(|&x| x != Ordering::Equal)?];
    let plane = Form::Plane(meet.planes[1 - side]);
    let mut ends = Vec::with_capacity(2);
    for i in 0..3 {
        let j = (i + 1) % 3;
        if s[i] == Ordering::Equal {
            let off = t[(i + 1..i + 3)
                .map(|k| k % 3)
                .find(|&k| s[k] != Ordering::Equal)?];
            let pivot = meet.increasing(eye, Form::Plane([t[i], off, apart]));
            ends.push((OnLine::Vertex { point: t[i], pivot }, 0));
        } else if s[j] != Ordering::Equal && s[i] != s[j] {
            let edge = if s[i] == Ordering::Greater {
                [t[i], t[j]]
            } else {
                [t[j], t[i]]
            };
            let pivot = meet.increasing(eye, Form::Plane([edge[0], edge[1], apart]));
            let rank = if face_sides[i] { 1 } else { 3 } + side as u8;
            ends.push((OnLine::Crossing { edge, plane, pivot }, rank));
        }
    }
    match ends[..] {
        [a, b] => match meet.compare(eye, &a.0, &b.0) {
            Ordering::Less => Some([a, b]),
            Ordering::Greater => Some([b, a]),
            Ordering::Equal => None,
        },
        _ => None,
    }
}

/// Where the segment `ab` passes through the closed triangle `t` of `mesh` crossing its plane
/// (its ends strictly on either side of it), the crossing: the zero along `ab` of the plane of
/// its face (see [`plane_of`]).
pub(crate) fn pierces(eye: &Eye, a: &Point3, b: &Point3, mesh: &Mesh, t: usize) -> Option<Zero> {
    let tri = mesh.triangle(t);
    let (sa, sb) = (
        orient3d(&tri[0], &tri[1], &tri[2], a),
        orient3d(&tri[0], &tri[1], &tri[2], b),
    );
    if sa == Ordering::Equal || sb == Ordering::Equal || sa == sb {
        return None;
    }
    let (mut above, mut below) = (false, false);
    for i in 0..3 {
        match orient3d(a, b, &tri[i], &tri[(i + 1) % 3]) {
            Ordering::Greater => above = true,
            Ordering::Less => below = true,
            Ordering::Equal => {}
        }
    }
    if above && below {
        return None;
    }
    Form::Plane(plane_of(mesh, t).1).zero_on(eye, a, b)
}

/// Where the segment `ends` of the line `meet` passes through the closed triangle `tri`
/// strictly between its ends: the plane `plane` of its face (see [`plane_of`]), oriented to
/// increase along the line. Decided exactly, like [`pierces`] for an edge.
pub(crate) fn pierces_line(
    meet: &Meet,
    eye: &Eye,
    ends: &[OnLine; 2],
    tri: &[Point3; 3],
    plane: &[Point3; 3],
) -> Option<Form> {
    let form = Form::Plane(*plane);
    let sx = meet.sign_at(eye, &ends[0], &form);
    let sy = meet.sign_at(eye, &ends[1], &form);
    if sx == Ordering::Equal || sy == Ordering::Equal || sx == sy {
        return None;
    }
    let (mut above, mut below) = (false, false);
    for i in 0..3 {
        match meet.twist(&tri[i], &tri[(i + 1) % 3]) {
            Ordering::Greater => above = true,
            Ordering::Less => below = true,
            Ordering::Equal => {}
        }
    }
    if above && below {
        return None;
    }
    Some(if sx == Ordering::Less {
        form
    } else {
        reversed(&form)
    })
}

#[cfg(test)]
mod tests;
