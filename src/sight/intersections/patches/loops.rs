//! The boundary of a patch as loops, and conditions (B) and (C) on them (see the module
//! above): exact angular order at pinches, segment meetings, and winding numbers.

use crate::geometry::predicates::orient2d;
use crate::grid::{Meeting, intersecting_pairs, meeting};
use geo::{Coord, Line};
use std::cmp::Ordering;
use std::collections::HashMap;

/// A loop of a patch's boundary: its vertices in order, and one of them that no other loop
/// passes through, if any.
pub(super) struct BoundaryLoop {
    vertices: Vec<u32>,
    alone: Option<u32>,
}

/// The loops of a patch's boundary half-edges `(from, to)` (sorted), for a patch of sign `s`
/// (condition A). Where the boundary pinches (several half-edges leave a vertex), the
/// half-edges round the vertex must alternate in and out; each arriving one is first
/// followed by its neighbour across the patch (next clockwise for `s = 1`), and a walk that
/// then passes a vertex twice is split there into loops. `None` when the half-edges do not
/// alternate, or when two loops through a pinch cross there instead of touching.
pub(super) fn loops(
    p: &[(u32, u32)],
    at: &impl Fn(u32) -> [f64; 2],
    s: i32,
) -> Option<Vec<BoundaryLoop>> {
    let leaving = |v: u32| {
        let start = p.partition_point(|x| x.0 < v);
        start..start + p[start..].partition_point(|x| x.0 == v)
    };
    let mut next: Vec<usize> = (0..p.len())
        .map(|e| {
            let r = leaving(p[e].1);
            if r.len() == 1 { r.start } else { usize::MAX }
        })
        .collect();
    let pinched: Vec<usize> = (0..p.len()).filter(|&e| next[e] == usize::MAX).collect();
    if !pinched.is_empty() {
        pair_at_pinches(p, &pinched, &leaving, at, s, &mut next)?;
    }
    let mut done = vec![false; p.len()];
    let mut loops = Vec::new();
    for start in 0..p.len() {
        if done[start] {
            continue;
        }
        let (mut walk, mut e) = (Vec::new(), start);
        while !done[e] {
            done[e] = true;
            walk.push(p[e].0);
            e = *next.get(e)?;
        }
        if pinched.is_empty() {
            loops.push(walk);
        } else {
            split_at_repeats(walk, &mut loops);
        }
    }
    let mut pinches: Vec<u32> = pinched.iter().map(|&e| p[e].1).collect();
    pinches.sort_unstable();
    pinches.dedup();
    if !touch_without_crossing(&pinches, &loops, at) {
        return None;
    }
    Some(
        loops
            .into_iter()
            .map(|vertices| {
                let alone = vertices.iter().copied().find(|&v| leaving(v).len() == 1);
                BoundaryLoop { vertices, alone }
            })
            .collect(),
    )
}

/// Appends to `loops` the closed walk `walk` (its vertices in order) split at every vertex
/// it passes twice, so that each loop passes each vertex once.
fn split_at_repeats(walk: Vec<u32>, loops: &mut Vec<Vec<u32>>) {
    let mut stack: Vec<u32> = Vec::with_capacity(walk.len());
    let mut on_stack: HashMap<u32, usize> = HashMap::new();
    for v in walk {
        if let Some(&i) = on_stack.get(&v) {
            let closed = stack.split_off(i);
            for x in &closed {
                on_stack.remove(x);
            }
            loops.push(closed);
        }
        on_stack.insert(v, stack.len());
        stack.push(v);
    }
    loops.push(stack);
}

/// Whether, at every vertex of `pinches` (sorted), the `loops` through it only touch: round
/// the vertex (counterclockwise, exact), no two loops' pairs of half-edges interleave.
pub(super) fn touch_without_crossing(
    pinches: &[u32],
    loops: &[Vec<u32>],
    at: &impl Fn(u32) -> [f64; 2],
) -> bool {
    // Per pinch, the far ends of each loop's half-edge in and out.
    let mut through: Vec<(u32, u32, u32)> = Vec::new();
    for l in loops {
        let n = l.len();
        for i in 0..n {
            if pinches.binary_search(&l[i]).is_ok() {
                through.push((l[i], l[(i + n - 1) % n], l[(i + 1) % n]));
            }
        }
    }
    through.sort_unstable();
    through.chunk_by(|x, y| x.0 == y.0).all(|here| {
        let c = at(here[0].0);
        let inside = |a: u32, x: u32, b: u32| between_ccw(c, at(a), at(x), at(b));
        here.iter().enumerate().all(|(i, &(_, a, b))| {
            here[i + 1..]
                .iter()
                .all(|&(_, x, y)| inside(a, x, b) == inside(a, y, b))
        })
    })
}

/// Sets `next` for the half-edges `pinched` that arrive at a pinch: round the vertex, in
/// counterclockwise order of direction (exact), the half-edges must alternate in and out,
/// and each one arriving is followed by its neighbour clockwise (`s = 1`) or
/// counterclockwise (`s = -1`), which must leave.
fn pair_at_pinches(
    p: &[(u32, u32)],
    pinched: &[usize],
    leaving: &impl Fn(u32) -> std::ops::Range<usize>,
    at: &impl Fn(u32) -> [f64; 2],
    s: i32,
    next: &mut [usize],
) -> Option<()> {
    let mut by_vertex: Vec<(u32, usize)> = pinched.iter().map(|&e| (p[e].1, e)).collect();
    by_vertex.sort_unstable();
    for arriving in by_vertex.chunk_by(|x, y| x.0 == y.0) {
        let v = arriving[0].0;
        let centre = at(v);
        // (far end, leaves, half-edge)
        let mut round: Vec<(u32, bool, usize)> = arriving
            .iter()
            .map(|&(_, e)| (p[e].0, false, e))
            .chain(leaving(v).map(|e| (p[e].1, true, e)))
            .collect();
        round.sort_by(|x, y| ccw(centre, at(x.0), at(y.0)));
        let n = round.len();
        for (i, &(_, leaves, e)) in round.iter().enumerate() {
            if leaves == round[(i + 1) % n].1 {
                return None;
            }
            if !leaves {
                let j = if s == 1 { (i + n - 1) % n } else { (i + 1) % n };
                next[e] = round[j].2;
            }
        }
    }
    Some(())
}

/// The counterclockwise order of the directions from `c` to `p` and to `q`, starting from
/// the direction of increasing `x` (exact: comparisons and `orient2d` of input points).
fn ccw(c: [f64; 2], p: [f64; 2], q: [f64; 2]) -> Ordering {
    let half = |p: [f64; 2]| !(p[1] > c[1] || (p[1] == c[1] && p[0] > c[0]));
    half(p).cmp(&half(q)).then_with(|| orient2d(c, q, p))
}

/// Whether the direction from `c` to `x` lies strictly inside the sector that turns
/// counterclockwise from the direction to `a` to the direction to `b` (exact, [`ccw`]).
fn between_ccw(c: [f64; 2], a: [f64; 2], x: [f64; 2], b: [f64; 2]) -> bool {
    let after = |y: [f64; 2], z: [f64; 2]| ccw(c, y, z) == Ordering::Less;
    if after(a, b) {
        after(a, x) && after(x, b)
    } else {
        after(a, x) || after(x, b)
    }
}

/// Condition (B): the pictures of two boundary half-edges that meet share an end vertex
/// and meet only there.
pub(super) fn meet_only_at_ends(loops: &[BoundaryLoop], at: &impl Fn(u32) -> [f64; 2]) -> bool {
    let ends: Vec<(u32, u32)> = loops
        .iter()
        .flat_map(|l| {
            let v = &l.vertices;
            (0..v.len()).map(move |i| (v[i], v[(i + 1) % v.len()]))
        })
        .collect();
    let coord = |v: u32| {
        let [x, y] = at(v);
        Coord { x, y }
    };
    let segments: Vec<Line<f64>> = ends
        .iter()
        .map(|&(a, b)| Line::new(coord(a), coord(b)))
        .collect();
    intersecting_pairs(&segments).into_iter().all(|(i, j)| {
        let ((a, b), (c, d)) = (ends[i], ends[j]);
        [a, b]
            .into_iter()
            .find(|v| *v == c || *v == d)
            .is_some_and(|v| meeting(&segments[i], &segments[j]) == Some(Meeting::Point(coord(v))))
    })
}

/// Condition (C): beside every loop of a patch of sign `s`, the winding numbers of the
/// patch's boundary are `0` and `s`: the other loops wind round the loop `0` times and it
/// runs the patch's way, or `s` times and it runs the other way (a hole).
pub(super) fn windings_agree(
    loops: &[BoundaryLoop],
    at: &impl Fn(u32) -> [f64; 2],
    s: i32,
) -> bool {
    let turns: Vec<i32> = loops.iter().map(|l| lowest_turn(&l.vertices, at)).collect();
    loops.iter().enumerate().all(|(i, l)| {
        let others: i32 = loops
            .iter()
            .enumerate()
            .filter(|&(j, _)| j != i)
            .map(|(j, o)| around(l, o, turns[j], at))
            .sum();
        (others == 0 && turns[i] == s) || (others == s && turns[i] == -s)
    })
}

/// How many times the loop `o` (of orientation `turn`) winds round the points beside the
/// loop `l`, which it does not cross: round `l`'s vertex on no other loop, or else (every
/// vertex of `l` a pinch) round the points near `l`'s first vertex `v`, which `o` may pass
/// through: then `o` winds `turn` times round them when `l` leaves `v` into the sector on
/// `o`'s inside there, else `0` times.
fn around(l: &BoundaryLoop, o: &BoundaryLoop, turn: i32, at: &impl Fn(u32) -> [f64; 2]) -> i32 {
    let v = l.alone.unwrap_or(l.vertices[0]);
    let Some(i) = o.vertices.iter().position(|&x| x == v) else {
        return winding(&o.vertices, at, at(v));
    };
    let n = o.vertices.len();
    let (from, to) = (o.vertices[(i + n - 1) % n], o.vertices[(i + 1) % n]);
    // The sector on `o`'s left at `v`: counterclockwise from where it leaves to where it came.
    let d = at(l.vertices[1 % l.vertices.len()]);
    let left = between_ccw(at(v), at(to), d, at(from));
    match (left, turn) {
        (true, 1) | (false, -1) => turn,
        _ => 0,
    }
}

/// The orientation of a loop that passes no vertex twice (`1` counterclockwise): the way it
/// turns at its lowest vertex (least `y`, then least `x`), where its two half-edges do not
/// overlap (condition B).
fn lowest_turn(vertices: &[u32], at: &impl Fn(u32) -> [f64; 2]) -> i32 {
    let n = vertices.len();
    let lower = |i: usize, j: usize| {
        let (p, q) = (at(vertices[i]), at(vertices[j]));
        (p[1], p[0]) < (q[1], q[0])
    };
    let i = (1..n).fold(0, |best, i| if lower(i, best) { i } else { best });
    let (prev, next) = (vertices[(i + n - 1) % n], vertices[(i + 1) % n]);
    match orient2d(at(prev), at(vertices[i]), at(next)) {
        Ordering::Greater => 1,
        Ordering::Less => -1,
        Ordering::Equal => 0,
    }
}

/// The winding number of a loop around a point `q` that is on none of its half-edges:
/// signed crossings of the ray from `q` towards increasing `x`, each half-edge taken as
/// half-open in `y` (exact).
fn winding(vertices: &[u32], at: &impl Fn(u32) -> [f64; 2], q: [f64; 2]) -> i32 {
    let n = vertices.len();
    let mut w = 0;
    for i in 0..n {
        let (a, b) = (at(vertices[i]), at(vertices[(i + 1) % n]));
        if a[1] <= q[1] {
            if b[1] > q[1] && orient2d(a, b, q) == Ordering::Greater {
                w += 1;
            }
        } else if b[1] <= q[1] && orient2d(a, b, q) == Ordering::Less {
            w -= 1;
        }
    }
    w
}
