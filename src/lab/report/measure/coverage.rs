//! Coverage: the parameter intervals of a segment of one drawing that lie within the
//! tolerance of the other drawing's segments (inside their capsules), found with an R-tree.

use crate::hidden::Drawing;
use rstar::primitives::{GeomWithData, Rectangle};
use rstar::{AABB, RTree};

/// One segment of a drawing, from `a` to `b`: `a + t d` for `t` in `[0, 1]`, `d = b - a`.
/// Both ends are kept as drawn (not recomputed from `d`), so that a segment covers itself,
/// and its reversal, on exactly `[0, 1]`.
pub(super) struct DrawnSegment {
    pub(super) a: [f64; 2],
    pub(super) b: [f64; 2],
    pub(super) d: [f64; 2],
    pub(super) visible: bool,
    /// Both ends have finite coordinates (`d` may still overflow).
    pub(super) finite: bool,
}

impl DrawnSegment {
    pub(super) fn length(&self) -> f64 {
        if self.finite {
            self.d[0].hypot(self.d[1])
        } else {
            f64::INFINITY
        }
    }
}

pub(super) fn segments(drawing: &Drawing) -> Vec<DrawnSegment> {
    drawing
        .polylines
        .iter()
        .flat_map(|line| {
            line.points.windows(2).map(move |w| {
                let (a, b) = (w[0], w[1]);
                DrawnSegment {
                    a,
                    b,
                    d: [b[0] - a[0], b[1] - a[1]],
                    visible: line.visible,
                    finite: a.iter().chain(&b).all(|x| x.is_finite()),
                }
            })
        })
        .collect()
}

pub(super) type Envelope = GeomWithData<Rectangle<[f64; 2]>, usize>;

/// The finite segments' envelopes widened by the tolerance, a little more so that rounding
/// the widened bounds never leaves out a segment within the tolerance.
pub(super) fn segment_tree(segments: &[DrawnSegment], tolerance: f64) -> RTree<Envelope> {
    let widen = |x: f64, by: f64| (x + by).clamp(-f64::MAX, f64::MAX);
    RTree::bulk_load(
        segments
            .iter()
            .enumerate()
            .filter(|(_, s)| s.finite)
            .map(|(i, s)| {
                let (a, b) = (s.a, s.b);
                let lo = [0, 1].map(|k| widen(a[k].min(b[k]), -tolerance).next_down());
                let hi = [0, 1].map(|k| widen(a[k].max(b[k]), tolerance).next_up());
                GeomWithData::new(Rectangle::from_corners(lo, hi), i)
            })
            .collect(),
    )
}

/// The parameter intervals of one segment covered by the visible and by the hidden segments
/// of the other drawing, each sorted and merged.
pub(super) struct Cover {
    pub(super) visible: Vec<(f64, f64)>,
    pub(super) hidden: Vec<(f64, f64)>,
}

impl Cover {
    pub(super) fn of(
        s: &DrawnSegment,
        others: &[DrawnSegment],
        tree: &RTree<Envelope>,
        tolerance: f64,
    ) -> Cover {
        let mut cover = Cover {
            visible: Vec::new(),
            hidden: Vec::new(),
        };
        if !s.finite || s.length() == 0.0 {
            return cover;
        }
        let (a, b) = (s.a, s.b);
        let query = AABB::from_corners(
            [a[0].min(b[0]), a[1].min(b[1])],
            [a[0].max(b[0]), a[1].max(b[1])],
        );
        for near in tree.locate_in_envelope_intersecting(&query) {
            let other = &others[near.data];
            if let Some((lo, hi)) = capsule(s, other.a, other.b, tolerance) {
                let (lo, hi) = (lo.max(0.0), hi.min(1.0));
                if lo <= hi {
                    if other.visible {
                        cover.visible.push((lo, hi));
                    } else {
                        cover.hidden.push((lo, hi));
                    }
                }
            }
        }
        merge(&mut cover.visible);
        merge(&mut cover.hidden);
        cover
    }

    /// The intervals covered by any segment.
    pub(super) fn any(&self) -> Vec<(f64, f64)> {
        let mut all = [self.visible.as_slice(), self.hidden.as_slice()].concat();
        merge(&mut all);
        all
    }
}

/// Sorts intervals and merges those that overlap or touch.
pub(super) fn merge(intervals: &mut Vec<(f64, f64)>) {
    intervals.sort_by(|x, y| x.0.total_cmp(&y.0));
    let mut merged: Vec<(f64, f64)> = Vec::with_capacity(intervals.len());
    for &(lo, hi) in intervals.iter() {
        match merged.last_mut() {
            Some(last) if lo <= last.1 => last.1 = last.1.max(hi),
            _ => merged.push((lo, hi)),
        }
    }
    *intervals = merged;
}

/// The measure of `[lo, hi]` outside the sorted, merged intervals `covered`.
pub(super) fn gaps(lo: f64, hi: f64, covered: &[(f64, f64)]) -> f64 {
    let mut reached = lo;
    let mut total = 0.0;
    for &(a, b) in covered {
        if a >= hi {
            break;
        }
        if a > reached {
            total += a - reached;
        }
        reached = reached.max(b);
    }
    if hi > reached {
        total += hi - reached;
    }
    total
}

/// The interval of parameters `t` with `s.a + t s.d` within `r` of the segment `ab`: the
/// line's intersection with the capsule of `ab`, the union of its intersections with the
/// rectangle of half-width `r` along `ab` and with the discs of radius `r` at `a` and `b`
/// (an interval, since the capsule is convex). `None` if the line misses it.
pub(super) fn capsule(s: &DrawnSegment, a: [f64; 2], b: [f64; 2], r: f64) -> Option<(f64, f64)> {
    let e = [b[0] - a[0], b[1] - a[1]];
    let ee = dot(e, e);
    let mut pieces = [disc(s, a, r), disc(s, b, r), None];
    if ee > 0.0 {
        let w = [s.a[0] - a[0], s.a[1] - a[1]];
        let half_width = r * ee.sqrt();
        pieces[2] = Some((f64::NEG_INFINITY, f64::INFINITY))
            .and_then(|t| slab(t, dot(w, e), dot(s.d, e), 0.0, ee))
            .and_then(|t| slab(t, cross(e, w), cross(e, s.d), -half_width, half_width));
    }
    pieces
        .into_iter()
        .flatten()
        .reduce(|x, y| (x.0.min(y.0), x.1.max(y.1)))
}

/// The part of the interval `t` where `lo <= f0 + f1 t <= hi`.
pub(super) fn slab(t: (f64, f64), f0: f64, f1: f64, lo: f64, hi: f64) -> Option<(f64, f64)> {
    let (from, to) = if f1 == 0.0 {
        if lo <= f0 && f0 <= hi {
            t
        } else {
            return None;
        }
    } else {
        let (x, y) = ((lo - f0) / f1, (hi - f0) / f1);
        (t.0.max(x.min(y)), t.1.min(x.max(y)))
    };
    // Also false for NaN (an overflow of huge coordinates): no cover.
    (from <= to).then_some((from, to))
}

/// The parameters `t` with `|s.a + t s.d - c| <= r`: the roots of
/// `|d|^2 t^2 + 2 (d.w) t + |w|^2 - r^2` for `w = a - c`, computed without cancellation.
pub(super) fn disc(s: &DrawnSegment, c: [f64; 2], r: f64) -> Option<(f64, f64)> {
    let w = [s.a[0] - c[0], s.a[1] - c[1]];
    let a = dot(s.d, s.d);
    let b = dot(s.d, w);
    let c = dot(w, w) - r * r;
    let discriminant = b * b - a * c;
    if !(a > 0.0 && discriminant >= 0.0) {
        return None;
    }
    let q = -(b + discriminant.sqrt().copysign(b));
    let (x, y) = if q == 0.0 { (0.0, 0.0) } else { (q / a, c / q) };
    Some((x.min(y), x.max(y))).filter(|(x, y)| x <= y)
}

pub(super) fn dot(u: [f64; 2], v: [f64; 2]) -> f64 {
    u[0] * v[0] + u[1] * v[1]
}

pub(super) fn cross(u: [f64; 2], v: [f64; 2]) -> f64 {
    u[0] * v[1] - u[1] * v[0]
}
