//! One hatch line against the polygons' edges: where the edges meet it, their exact order
//! along it, the runs the polygons cover, and the final exact check of each segment.

use crate::geometry::exact::{expansion_sum, lerp, sum_sign, two_product};
use crate::geometry::kernel::{
    Difference, Estimate, Polynomial, Product, expansion_sign, value_within,
};
use crate::geometry::predicates::{Orient2d, Side, orient2d, orient2d_at_infinity};
use crate::geometry::{Point3, Vector3};
use std::cmp::Ordering;

/// The hatch direction `d` and the normal `n` across it (`d` turned a quarter to the left).
pub(super) struct HatchFrame {
    pub(super) normal: [f64; 2],
    pub(super) dir: [f64; 2],
}

/// An edge of a ring, with its rounded extent `[min u, max u]` across the lines.
pub(super) struct PolygonEdge {
    p: [f64; 2],
    q: [f64; 2],
    pub(super) u: [f64; 2],
}

impl PolygonEdge {
    pub(super) fn new(p: [f64; 2], q: [f64; 2], frame: &HatchFrame) -> PolygonEdge {
        let u = |x: [f64; 2]| frame.normal[0] * x[0] + frame.normal[1] * x[1];
        let (a, b) = (u(p), u(q));
        PolygonEdge {
            p,
            q,
            u: [a.min(b), a.max(b)],
        }
    }
}

/// The linear form `w·x − offset` at the point `x` of the picture, as an exact polynomial.
fn form(w: [f64; 2], offset: f64, x: [f64; 2]) -> Side {
    Side {
        origin: Point3::origin(),
        normal: Vector3::new(w[0], w[1], 0.0),
        offset,
        x: Point3::new(x[0], x[1], 0.0),
    }
}

/// One hatch line `n·x = offset` (in the scaled picture).
pub(super) struct HatchLine<'a> {
    pub(super) frame: &'a HatchFrame,
    pub(super) offset: f64,
    pub(super) margin: f64,
}

/// Where an edge meets the line: `low` on the line or on its negative side, `high` on it or on
/// its positive side, not both on it; the point where the segment `low high` meets the line.
/// `vertex` is that point when it is a vertex (on the line); `above` and `below` say whether
/// the edge crosses the line moved infinitesimally towards `+n` or `−n`.
#[derive(Clone, Copy)]
struct EdgeHit {
    low: [f64; 2],
    high: [f64; 2],
    vertex: Option<[f64; 2]>,
    above: bool,
    below: bool,
}

/// A point of a run: exact (a vertex) or constructed on an edge; and, when the run passes
/// through it (the polygons cover both sides of the edges there), the range of the meetings
/// there, whose edges the run may cross.
#[derive(Clone)]
struct RunPoint {
    at: [f64; 2],
    constructed: bool,
    through: std::ops::Range<usize>,
}

impl HatchLine<'_> {
    /// The exact side of `x`: the sign of `n·x − offset`.
    fn side(&self, x: [f64; 2]) -> Ordering {
        form(self.frame.normal, self.offset, x).sign()
    }

    /// The runs of the line through the polygons with `edges`, and the number of segments
    /// dropped by the final check.
    pub(super) fn hatch(&self, edges: &[PolygonEdge]) -> (Vec<Vec<[f64; 2]>>, usize) {
        let near: Vec<&PolygonEdge> = edges
            .iter()
            .filter(|e| e.u[0] - self.margin <= self.offset && self.offset <= e.u[1] + self.margin)
            .collect();
        let meetings = self.meetings(&near, edges);
        if meetings.is_empty() {
            return (Vec::new(), 0);
        }
        // Runs of points, each point with the meetings there.
        let mut runs: Vec<Vec<RunPoint>> = Vec::new();
        let mut current: Vec<RunPoint> = Vec::new();
        let (mut above, mut below) = (false, false);
        let mut start = 0;
        while start < meetings.len() {
            let mut end = start + 1;
            while end < meetings.len()
                && self.order(&meetings[start], &meetings[end]) == Ordering::Equal
            {
                end += 1;
            }
            let group = &meetings[start..end];
            let inside_before = above && below;
            for m in group {
                above ^= m.above;
                below ^= m.below;
            }
            let inside_after = above && below;
            if inside_before || inside_after {
                let mut point = self.point(group);
                if inside_before && inside_after {
                    point.through = start..end;
                }
                if point.constructed && inside_before != inside_after {
                    let towards = if inside_after {
                        self.frame.dir
                    } else {
                        self.frame.dir.map(|c| -c)
                    };
                    point.at = inward(point.at, group, towards);
                }
                if current.last().is_none_or(|p| p.at != point.at) {
                    current.push(point);
                }
                if !inside_after {
                    runs.push(std::mem::take(&mut current));
                }
            }
            start = end;
        }
        let mut out = Vec::new();
        let mut dropped = 0;
        for run in runs {
            let mut kept: Vec<[f64; 2]> = Vec::new();
            for w in run.windows(2) {
                let through: Vec<&EdgeHit> = w
                    .iter()
                    .flat_map(|p| &meetings[p.through.clone()])
                    .collect();
                let ok = !(w[0].constructed || w[1].constructed)
                    || self.segment_inside(w[0].at, w[1].at, &near, &through);
                if ok {
                    if kept.is_empty() {
                        kept.push(w[0].at);
                    }
                    kept.push(w[1].at);
                } else {
                    dropped += 1;
                    if kept.len() >= 2 {
                        out.push(std::mem::take(&mut kept));
                    }
                    kept.clear();
                }
            }
            if kept.len() >= 2 {
                out.push(kept);
            }
        }
        (out, dropped)
    }

    /// Where the edges near the line meet it, sorted along the hatch direction (exactly). A
    /// vertex on the line meets it once per ring through it, as the start of its edge; its
    /// position is read against a vertex of the polygons off the line (`None`: all lie on the
    /// line, which then meets no area).
    fn meetings(&self, near: &[&PolygonEdge], edges: &[PolygonEdge]) -> Vec<EdgeHit> {
        let Some(pivot) = edges
            .iter()
            .map(|e| e.p)
            .find(|&x| self.side(x) != Ordering::Equal)
        else {
            return Vec::new();
        };
        let pivot_side = self.side(pivot);
        let mut meetings = Vec::new();
        for e in near {
            let (sp, sq) = (self.side(e.p), self.side(e.q));
            let above = (sp == Ordering::Greater) != (sq == Ordering::Greater);
            let below = (sp == Ordering::Less) != (sq == Ordering::Less);
            // The edge's ends (or, for an edge along the line, its start and a vertex off
            // the line) with their sides; the one on the lower side is `low`.
            let (vertex, ends) = match (sp, sq) {
                // The vertex `p`, with whatever toggles its edge makes there.
                (Ordering::Equal, Ordering::Equal) => (Some(e.p), [(e.p, sp), (pivot, pivot_side)]),
                (Ordering::Equal, _) => (Some(e.p), [(e.p, sp), (e.q, sq)]),
                // Its toggles at `q`; the vertex `q` itself is met as the start of the next
                // edge.
                (_, Ordering::Equal) => (Some(e.q), [(e.p, sp), (e.q, sq)]),
                _ if sp != sq => (None, [(e.p, sp), (e.q, sq)]),
                _ => continue,
            };
            let [(low, _), (high, _)] = if ends[0].1 < ends[1].1 {
                ends
            } else {
                [ends[1], ends[0]]
            };
            meetings.push(EdgeHit {
                low,
                high,
                vertex,
                above,
                below,
            });
        }
        meetings.sort_by(|a, b| self.order(a, b));
        meetings
    }

    /// The exact order along the hatch direction of the points where two meetings' segments
    /// meet the line. With `a = n·low − c ≤ 0 ≤ b = n·high − c` (not both zero), the point is
    /// `(b·low − a·high)/(b − a)` and its position `(b·(d·low) − a·(d·high))/(b − a)`.
    fn order(&self, x: &EdgeHit, y: &EdgeHit) -> Ordering {
        if let (Some(v), Some(w)) = (x.vertex, y.vertex) {
            // `d·(v − w)`.
            return Side {
                origin: Point3::new(w[0], w[1], 0.0),
                normal: Vector3::new(self.frame.dir[0], self.frame.dir[1], 0.0),
                offset: 0.0,
                x: Point3::new(v[0], v[1], 0.0),
            }
            .sign();
        }
        let numerator = |m: &EdgeHit| {
            let a = form(self.frame.normal, self.offset, m.low);
            let b = form(self.frame.normal, self.offset, m.high);
            let e = form(self.frame.dir, 0.0, m.low);
            let f = form(self.frame.dir, 0.0, m.high);
            (Difference(Product(b, e), Product(a, f)), Difference(b, a))
        };
        let (nx, dx) = numerator(x);
        let (ny, dy) = numerator(y);
        // Both denominators are positive.
        Difference(Product(nx, dy), Product(ny, dx)).sign()
    }

    /// The point of a group of meetings at one place: the vertex if one is there, else the
    /// crossing of the segment first in the order of its ends' coordinates, constructed once.
    fn point(&self, group: &[EdgeHit]) -> RunPoint {
        if let Some(v) = group.iter().find_map(|m| m.vertex) {
            return RunPoint {
                at: v,
                constructed: false,
                through: 0..0,
            };
        }
        let ends = |m: &EdgeHit| [m.low[0], m.low[1], m.high[0], m.high[1]];
        let mut sorted: Vec<&EdgeHit> = group.iter().collect();
        sorted.sort_by(|m, n| {
            let (a, b) = (ends(m), ends(n));
            (0..4)
                .map(|k| a[k].total_cmp(&b[k]))
                .find(|o| o.is_ne())
                .unwrap_or(Ordering::Equal)
        });
        let points: Vec<[f64; 2]> = sorted.iter().map(|m| self.crossing(m)).collect();
        // A point on the lines of all the group's segments (where several cross, it may be
        // exact from one of them).
        let on_all = points.iter().find(|&&x| {
            sorted
                .iter()
                .all(|m| orient2d(m.low, m.high, x) == Ordering::Equal)
        });
        RunPoint {
            at: *on_all.unwrap_or(&points[0]),
            constructed: true,
            through: 0..0,
        }
    }

    /// The point where the segment of a meeting crosses the line, constructed once: each
    /// coordinate interpolated between its ends at the ratio of their offsets from the line
    /// (each exact offset rounded once); the coordinate across an axis-parallel line is the
    /// line's, exactly.
    fn crossing(&self, m: &EdgeHit) -> [f64; 2] {
        let a = value_within(&form(self.frame.normal, self.offset, m.low), f64::EPSILON);
        let b = value_within(&form(self.frame.normal, self.offset, m.high), f64::EPSILON);
        let t = (a / (a - b)).clamp(0.0, 1.0);
        let t = if t.is_nan() { 0.5 } else { t };
        let mut x = [lerp(m.low[0], m.high[0], t), lerp(m.low[1], m.high[1], t)];
        let [n0, n1] = self.frame.normal;
        match (n0 == 0.0, n1 == 0.0) {
            (true, false) => x[1] = self.offset / n1,
            (false, true) => x[0] = self.offset / n0,
            _ => {}
        }
        x
    }

    /// Whether the segment `x y` (with an end constructed) crosses none of the edges near the
    /// line properly, but for those of the meetings `through` at its ends which the run passes
    /// through, and its midpoint lies inside or on the polygons: exact.
    fn segment_inside(
        &self,
        x: [f64; 2],
        y: [f64; 2],
        near: &[&PolygonEdge],
        through: &[&EdgeHit],
    ) -> bool {
        let passed = |e: &PolygonEdge| {
            through
                .iter()
                .any(|m| (m.low, m.high) == (e.p, e.q) || (m.low, m.high) == (e.q, e.p))
        };
        let crosses = |e: &PolygonEdge| {
            let opposite = |s: Ordering, t: Ordering| s != Ordering::Equal && s == t.reverse();
            opposite(orient2d(x, y, e.p), orient2d(x, y, e.q))
                && opposite(orient2d(e.p, e.q, x), orient2d(e.p, e.q, y))
        };
        !near.iter().any(|e| !passed(e) && crosses(e))
            && midpoint_inside(x, y, self.frame.dir, near)
    }
}

/// `x` moved along `towards` until it lies on the line of each crossing segment of `group` or
/// on the side of it `towards` points to: by a unit in the last place of the largest
/// coordinate of it and the segments' ends, then twice that, and so on, at most 32 times (the final check judges the
/// result).
fn inward(x: [f64; 2], group: &[EdgeHit], towards: [f64; 2]) -> [f64; 2] {
    let inside = |x: [f64; 2]| {
        group.iter().all(|m| {
            let s = orient2d(m.low, m.high, x);
            s == Ordering::Equal || s == orient2d_at_infinity(m.low, m.high, towards)
        })
    };
    let largest = group
        .iter()
        .flat_map(|m| m.low.into_iter().chain(m.high))
        .chain(x)
        .fold(0.0f64, |l, c| l.max(c.abs()));
    let mut step = (largest.next_up() - largest).max(f64::MIN_POSITIVE);
    let mut moved = x;
    for _ in 0..32 {
        if inside(moved) {
            return moved;
        }
        moved = [x[0] + step * towards[0], x[1] + step * towards[1]];
        step *= 2.0;
    }
    moved
}

/// Whether the midpoint `m = (x + y)/2` lies inside or on the polygons whose edges meet the
/// line through `m` along `dir` (`near`): on an edge, or crossing an odd number of them along
/// the ray from `m` towards `dir` (half-open at vertices). Exact: every sign is of a sum of
/// exact products of the doubles.
fn midpoint_inside(x: [f64; 2], y: [f64; 2], dir: [f64; 2], near: &[&PolygonEdge]) -> bool {
    // Twice the cross product `dir × (p − m)`: which side of the ray's line `p` lies on.
    let side = |p: [f64; 2]| {
        let mut terms = Vec::with_capacity(12);
        for (w, c) in [
            (dir[0], 2.0 * p[1]),
            (-dir[0], x[1]),
            (-dir[0], y[1]),
            (-dir[1], 2.0 * p[0]),
            (dir[1], x[0]),
            (dir[1], y[0]),
        ] {
            let (h, l) = two_product(w, c);
            terms.extend([h, l]);
        }
        sum_sign(&terms)
    };
    let mut odd = false;
    for e in near {
        // Twice `orient2d(p, q, m)`.
        let turn = {
            let (s, t) = (Orient2d([e.p, e.q, x]), Orient2d([e.p, e.q, y]));
            let estimate = s.estimate().difference(&kneg(t.estimate()));
            estimate
                .sign()
                .unwrap_or_else(|| expansion_sign(&expansion_sum(&s.expansion(), &t.expansion())))
        };
        if turn == Ordering::Equal {
            // On the edge's line: on the edge when between its ends along a coordinate in
            // which they differ.
            let k = if e.p[0] != e.q[0] { 0 } else { 1 };
            let to = |end: f64| sum_sign(&[x[k], y[k], -2.0 * end]);
            if to(e.p[k]) != to(e.q[k]) || to(e.p[k]) == Ordering::Equal {
                return true;
            }
            continue;
        }
        let (sp, sq) = (side(e.p), side(e.q));
        if (sp == Ordering::Greater) != (sq == Ordering::Greater)
            && turn == orient2d_at_infinity(e.p, e.q, dir).reverse()
        {
            odd = !odd;
        }
    }
    odd
}

/// The negated estimate.
fn kneg(e: Estimate) -> Estimate {
    Estimate {
        value: -e.value,
        bound: e.bound,
    }
}
