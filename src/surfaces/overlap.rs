//! Whether a triangle of an occluder hides some area of a triangle of the face, decided
//! exactly: the test behind VISIBLE (no occluder hides any area of F) and the filter that keeps
//! pieces touching F only along a line out of the clipping.
//!
//! Written by hand because it is VISFAC's own predicate: no crate decides overlap of pictures
//! of 3-D polygons with their depth order. Everything is a sign of an `orient3d` of input
//! points, or of one degree-two combination of them for the points where the occluder crosses
//! F's plane, so no picture is ever rounded.
//!
//! The part of triangle `s` that can hide anything of triangle `t` of F is `s` cut by F's
//! plane to its eye side; its picture `Q` is convex, and so is the picture `t'` of `t`. Two
//! convex polygons with interiors have disjoint interiors exactly when the line through an edge
//! of one of them leaves the other wholly on its far side (weakly). The edges of `Q` lie on
//! `s`'s edges and on the picture of the line where the two planes meet; across that line, a
//! point of F's plane is seen through `Q` only when it lies behind `s`'s plane, so its test is
//! the side of `t`'s vertices of `s`'s plane.

use crate::geometry::Point3;
use crate::geometry::kernel::{Difference, Polynomial, Product};
use crate::geometry::predicates::{Orient3d, orient3d};
use crate::views::Eye;
use std::cmp::Ordering;

/// The edges of a triangle, each with its vertices in cyclic order.
const EDGES: [(usize, usize); 3] = [(0, 1), (1, 2), (2, 0)];

/// Whether the part of triangle `s` strictly on the eye's side of the plane through `f` (F's
/// plane, which the eye is on side `eye_side` of, never `Equal`) hides a region of positive
/// area of triangle `t` (lying in that plane), seen from `eye`. `g` is a triangle spanning
/// `s`'s plane (the occluder face's plane; `s` itself may be degenerate). Exact.
pub(super) fn hides_area(
    eye: &Eye,
    f: &[Point3; 3],
    eye_side: Ordering,
    t: &[Point3; 3],
    s: &[Point3; 3],
    g: &[Point3; 3],
) -> bool {
    let t_turn = eye.orient3d(&t[0], &t[1], &t[2]);
    let s_turn = eye.orient3d(&s[0], &s[1], &s[2]);
    let g_side = eye.orient3d(&g[0], &g[1], &g[2]);
    if t_turn == Ordering::Equal || s_turn == Ordering::Equal || g_side == Ordering::Equal {
        // A picture with no area hides nothing and has nothing to hide.
        return false;
    }
    let sides = s.map(|c| orient3d(&f[0], &f[1], &f[2], &c));
    if !sides.contains(&eye_side) {
        return false;
    }
    // The line where the planes meet: `t` wholly on the eye's side of `s`'s plane (weakly).
    if t.iter()
        .all(|v| orient3d(&g[0], &g[1], &g[2], v) != g_side.reverse())
    {
        return false;
    }
    // The edges of `s`: `t` wholly outside one (weakly).
    let outside = |turn: Ordering, side: Ordering| side != turn;
    if EDGES.iter().any(|&(i, j)| {
        t.iter()
            .all(|v| outside(s_turn, eye.orient3d(&s[i], &s[j], v)))
    }) {
        return false;
    }
    // The edges of `t`: every vertex of `Q` outside one (weakly). The vertices of `Q` are the
    // corners of `s` not behind F's plane and the points where `s`'s edges cross it.
    !EDGES.iter().any(|&(i, j)| {
        let corners_out = (0..3)
            .filter(|&k| sides[k] != eye_side.reverse())
            .all(|k| outside(t_turn, eye.orient3d(&t[i], &t[j], &s[k])));
        corners_out
            && EDGES.iter().all(|&(a, b)| {
                let crosses = sides[a] != Ordering::Equal && sides[b] == sides[a].reverse();
                !crosses
                    || outside(
                        t_turn,
                        side_of_crossing(eye, f, [&t[i], &t[j]], &s[a], &s[b]),
                    )
            })
    })
}

/// The side of the sight plane through `edge` (the sign of `eye.orient3d(edge[0], edge[1], ·)`)
/// of the point where segment `ab` crosses the plane through `f`, `a` and `b` being strictly on
/// opposite sides of it.
///
/// With `O` the orientation against `f` and `E` the one against the sight plane (both affine),
/// the crossing is `(O(a) b − O(b) a) / (O(a) − O(b))`, so `E` there has the sign of
/// `O(a) · (O(a) E(b) − O(b) E(a))`: a degree-two polynomial of the input, decided by the
/// kernel.
fn side_of_crossing(
    eye: &Eye,
    f: &[Point3; 3],
    edge: [&Point3; 2],
    a: &Point3,
    b: &Point3,
) -> Ordering {
    let plane = |x: &Point3| Orient3d([f[0], f[1], f[2], *x]);
    let sight = |x: &Point3| eye.determinant(edge[0], edge[1], x);
    let sign = Difference(Product(plane(a), sight(b)), Product(plane(b), sight(a))).sign();
    if orient3d(&f[0], &f[1], &f[2], a) == Ordering::Less {
        sign.reverse()
    } else {
        sign
    }
}

/// Whether the occluder polygon `corners` (a face, with a triangle `g` spanning its plane and
/// oriented like it) alone hides all of the face with vertices `face`: every vertex of the face
/// lies weakly behind `g`'s plane and, in the picture, weakly inside every edge of the
/// occluder. Those points form a convex set (the occluder's kernel cut by a half-space), so the
/// vertices decide for the whole face. Exact; the caller has made sure the face is not in the
/// occluder's plane and the occluder is not seen edge-on.
pub(super) fn hides_all(eye: &Eye, face: &[Point3], corners: &[Point3], g: &[Point3; 3]) -> bool {
    // The side of the occluder's plane the eye is on is also the turn of its picture.
    let g_side = eye.orient3d(&g[0], &g[1], &g[2]);
    g_side != Ordering::Equal
        && face
            .iter()
            .all(|v| orient3d(&g[0], &g[1], &g[2], v) != g_side)
        && (0..corners.len()).all(|i| {
            let (a, b) = (&corners[i], &corners[(i + 1) % corners.len()]);
            face.iter()
                .all(|v| eye.orient3d(a, b, v) != g_side.reverse())
        })
}
