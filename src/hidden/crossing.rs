//! Where the picture of a line meets the picture of a contour in front of it, decided exactly
//! in 3-D: [`crossing`] for an edge, [`crossing_line`] for an intersection line (the cuts of
//! stage 3, see `cuts.rs`).

use super::line::{Cut, Line, MeetLine, rough_parameter};
use crate::geometry::Point3;
use crate::geometry::predicates::{collinear, orient3d};
use crate::sight::along::Form;
use crate::sight::collinear::corners;
use crate::sight::frustum::{Clip, contour_in_front};
use crate::sight::meet::{OnLine, reversed};
use crate::views::Eye;
use std::cmp::Ordering;

/// The cuts on `l` where its picture meets the picture of the contour `c`: a crossing (one
/// cut), or, for collinear pictures, at the pictures of `c`'s ends inside `l` and where `l`
/// passes through the plane of one of `c`'s faces (`c_sides`, the triangles on its sides).
/// When the view clips (`clip`), a wide contour cuts only where its point behind the crossing
/// is in front of the eye.
pub(super) fn crossing(
    eye: &Eye,
    clip: Option<Clip>,
    l: &Line,
    c: &Line,
    c_sides: impl Fn() -> Vec<[Point3; 3]>,
) -> Option<Vec<Cut>> {
    // Lines with a common end meet there, at the end of each: no cut (and the exact zero
    // determinants would take the predicates' slowest path).
    if l.a == c.a || l.a == c.b || l.b == c.a || l.b == c.b {
        return None;
    }
    let (sc, sd) = (
        eye.orient3d(&l.a, &l.b, &c.a),
        eye.orient3d(&l.a, &l.b, &c.b),
    );
    let (sa, sb) = (
        eye.orient3d(&c.a, &c.b, &l.a),
        eye.orient3d(&c.a, &c.b, &l.b),
    );
    let zero = Ordering::Equal;
    if [sc, sd, sa, sb].iter().all(|&s| s == zero) {
        return Some(collinear_cuts(eye, clip, l, c, c_sides));
    }
    if (sc == sd && sc != zero) || (sa == sb && sa != zero) {
        return None;
    }
    if let Some(n) = &clip
        && c.wide
        && !contour_in_front(n, eye, [&l.a, &l.b], [&c.a, &c.b], [sc, sd])
    {
        return None;
    }
    // Where the contour passes behind the line it changes nothing on it. Which of two lines
    // whose pictures cross is in front is the sign of orient3d(a, b, c0, c1) against the side
    // of the picture of ab that c0 lies on (the same sign when c is in front).
    let c_side = if sc != zero {
        (sc, c.a, c.b)
    } else {
        (sd, c.b, c.a)
    };
    let volume = orient3d(&l.a, &l.b, &c_side.1, &c_side.2);
    if volume != zero && volume != c_side.0 {
        return None;
    }
    let zero = Form::Sight(c.a, c.b).zero_on(eye, &l.a, &l.b)?;
    let [u, v] = c.vertices;
    Some(vec![Cut::on_edge(
        zero,
        None,
        [2, c.object(), u.min(v), u.max(v)],
    )])
}

/// The cuts on `l` where its picture lies on the picture of the contour `c` (see
/// [`crossing`]; `c_sides`, the triangles on `c`'s sides).
fn collinear_cuts(
    eye: &Eye,
    clip: Option<Clip>,
    l: &Line,
    c: &Line,
    c_sides: impl Fn() -> Vec<[Point3; 3]>,
) -> Vec<Cut> {
    let zero = Ordering::Equal;
    // Collinear pictures: cut where the lines of sight through the contour's ends (those in
    // front of the eye, whose pictures are drawn) meet this line strictly inside it, each
    // the zero of the plane through the eye, the end and a point off the plane of both
    // lines. On a wide line the point may lie behind the eye: then it bounds no drawn piece.
    let sides = c_sides();
    let ends_in_front = [c.a, c.b].map(|x| clip.is_none_or(|n| n.in_front(&x)));
    let off = off_plane(eye, l, sides.iter().flatten());
    let mut cuts: Vec<Cut> = (0..2)
        .filter(|&k| ends_in_front[k])
        .filter_map(|k| {
            let zero = Form::Sight([c.a, c.b][k], off?).zero_on(eye, &l.a, &l.b)?;
            let key = [0, c.object(), c.vertices[k], 0];
            Some(Cut::on_edge(zero, Some(c.ends[k]), key))
        })
        .collect();
    // These cuts are made on a wide line too (its pictures play no part). Besides, where
    // the visibility of `l` changes at an end of `c`, the outline also leaves the plane of
    // both lines there through a contour edge ending at that end, whose crossing with `l`
    // the general case of [`crossing`] cuts at the same point (and the grid pairs it with `l`: both
    // pictures hold the end's). So no such end is left uncut (tests/collinear_cuts.rs
    // fails only without both).
    //
    // Both lines lie in one plane through the eye, which meets a face of `c` not seen
    // edge-on only along `c`: behind `c`'s picture, `l` is hidden by the face exactly where
    // it lies behind the face's plane, so it is cut where it crosses that plane too (at an
    // end of `c` when one lies on the line of `l`: cut there already).
    let meets_end = collinear(&l.a, &l.b, &c.a) || collinear(&l.a, &l.b, &c.b);
    for tri in sides.into_iter().filter(|_| !meets_end) {
        let form = Form::Plane(tri);
        if eye.orient3d(&tri[0], &tri[1], &tri[2]) != zero
            && let Some(z) = form.zero_on(eye, &l.a, &l.b)
        {
            let [u, v] = c.vertices;
            cuts.push(Cut::on_edge(z, None, [1, c.object(), u.min(v), u.max(v)]));
        }
    }
    cuts
}

/// A point off the plane through the eye and the edge `l` (not seen end-on): one of `near`
/// if any is, else one of four affinely independent points at the scale of `l`'s ends, of
/// which one must be. Only the plane it spans with the eye and a point of `l`'s plane matters,
/// never where it is.
pub(super) fn off_plane<'p>(
    eye: &Eye,
    l: &Line,
    near: impl Iterator<Item = &'p Point3>,
) -> Option<Point3> {
    let top = l.a.coords.amax().max(l.b.coords.amax());
    near.copied()
        .chain(corners(top))
        .find(|w| eye.orient3d(&l.a, &l.b, w) != Ordering::Equal)
}

/// The cuts on the intersection line `l` (lying on `m`) where its picture meets the picture of
/// the contour `c` in front of it, decided exactly as [`crossing`] decides for an edge: the
/// sides of `c`'s ends against the plane through the line and the eye, the sides of the line's
/// ends against `c`'s sight plane, and which passes in front where they cross
/// ([`Meet::twist`](crate::sight::meet::Meet::twist)). For collinear pictures, at the lines
/// of sight through `c`'s ends.
pub(super) fn crossing_line(eye: &Eye, m: &MeetLine, l: &Line, c: &Line) -> Option<Vec<Cut>> {
    let (meet, [x, y]) = (&m.meet, &m.ends);
    let is_end = |p: &Point3| {
        [x, y]
            .iter()
            .any(|e| matches!(e, OnLine::Vertex { point, .. } if point == p))
    };
    if is_end(&c.a) || is_end(&c.b) {
        return None;
    }
    let (sc, sd) = (meet.sight_side(eye, &c.a), meet.sight_side(eye, &c.b));
    let sight = Form::Sight(c.a, c.b);
    let (sa, sb) = (meet.sign_at(eye, x, &sight), meet.sign_at(eye, y, &sight));
    let zero = Ordering::Equal;
    let rough = |form: &Form| rough_parameter(eye, form, &l.a, &l.b);
    if [sc, sd, sa, sb].iter().all(|&s| s == zero) {
        // Collinear pictures: cut where the lines of sight through the contour's ends meet the
        // line inside it, each point given by a sight plane through the end that crosses it.
        let off = *meet
            .planes
            .iter()
            .flatten()
            .find(|q| meet.sight_side(eye, q) != zero)?;
        let cuts = [0, 1]
            .into_iter()
            .filter_map(|k| {
                let (p, picture) = ([c.a, c.b][k], c.ends[k]);
                let form = meet.increasing(eye, Form::Sight(p, off));
                let inside = meet.sign_at(eye, x, &form) == Ordering::Less
                    && meet.sign_at(eye, y, &form) == Ordering::Greater;
                let key = [0, c.object(), c.vertices[k], 0];
                inside.then(|| Cut::on_line(form, rough(&form), Some(picture), key))
            })
            .collect();
        return Some(cuts);
    }
    if sa == sb || sa == zero || sb == zero || (sc == sd && sc != zero) {
        return None;
    }
    // Where the contour passes behind the line it changes nothing on it: the contour is in
    // front when its end `d` lies on the eye's side of the plane through the line and `c`.
    let volume = meet.twist(&c.a, &c.b);
    let in_front = if sc != zero {
        volume == zero || volume == sc
    } else {
        volume == zero || volume.reverse() == sd
    };
    if !in_front {
        return None;
    }
    let form = if sa == Ordering::Less {
        sight
    } else {
        reversed(&sight)
    };
    let (sighted, key) = if sc == zero {
        (Some(c.ends[0]), [0, c.object(), c.vertices[0], 0])
    } else if sd == zero {
        (Some(c.ends[1]), [0, c.object(), c.vertices[1], 0])
    } else {
        let [u, v] = c.vertices;
        (None, [2, c.object(), u.min(v), u.max(v)])
    };
    Some(vec![Cut::on_line(form, rough(&form), sighted, key)])
}
