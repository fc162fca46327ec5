//! A line of sight (or a ray) against boxes, in rounded arithmetic made safe by a margin.
//!
//! These are the hierarchy's filters, not its decisions: [`Sight::may_meet`] may say yes for a
//! box the exact line misses (the faces then decide exactly), never no for one it meets;
//! [`Sight::surely_meets_open`] may say no for a box the exact line crosses, never yes for one
//! it misses. Each tests a box grown (or shrunk) by a margin of 2⁻⁴⁰ times the largest
//! coordinate involved, which exceeds the rounding of the slab computation by a factor of
//! about 2¹⁰: every computed slab parameter `(bound - p)/d` is off by a few units in the last
//! place of `max|coordinate| / |d|`, while the margin moves it by 2⁻⁴⁰ of that. The direction
//! of an orthographic eye is scaled by a power of two (exactly) so the parameters cannot
//! overflow; the direction to a perspective eye is rounded once, an error of the same order.
//! A sight from a point known only to within a distance ([`Sight::blurred`]) widens the
//! margin by that distance: every line of sight from a point so near lies within it.

use crate::geometry::exact::unit_scaled;
use crate::geometry::{Aabb, Point3, Vector3};
use crate::views::Eye;

/// The relative margin: 2⁻⁴⁰.
const MARGIN: f64 = 1.0 / (1u64 << 40) as f64;

/// The half-open segment or ray `origin + t·direction`, `0 < t < limit`.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Sight {
    origin: Point3,
    /// A perspective eye (`None` for an eye at infinity or a plain ray).
    eye: Option<Point3>,
    direction: Vector3,
    limit: f64,
    /// The largest coordinate magnitude of the origin and a perspective eye.
    scale: f64,
    /// How far the exact point may lie from `origin` (see [`Sight::blurred`]).
    slack: f64,
}

impl Sight {
    /// The line of sight from `p` to the eye.
    pub(crate) fn to_eye(p: &Point3, eye: &Eye) -> Sight {
        match eye {
            Eye::Point(e) => Sight {
                origin: *p,
                eye: Some(*e),
                direction: e - p,
                limit: 1.0,
                scale: max_abs(p).max(max_abs(e)),
                slack: 0.0,
            },
            Eye::Infinity(u) => Sight::ray(p, u),
        }
    }

    /// The ray from `p` along `u` (which must not be zero).
    pub(crate) fn ray(p: &Point3, u: &Vector3) -> Sight {
        Sight {
            origin: *p,
            eye: None,
            direction: Vector3::from(unit_scaled((*u).into())),
            limit: f64::INFINITY,
            scale: max_abs(p),
            slack: 0.0,
        }
    }

    /// The sight from a point known only to lie within `radius` of this one's origin: its box
    /// tests answer for every point so near (each box is grown, or shrunk, by `radius` more).
    pub(crate) fn blurred(self, radius: f64) -> Sight {
        Sight {
            slack: radius * (1.0 + 1.0 / (1u64 << 20) as f64),
            ..self
        }
    }

    /// The margin of the box `b`'s tests.
    #[inline]
    fn margin(&self, b: &Aabb) -> f64 {
        MARGIN * self.scale.max(max_abs_box(b)) + self.slack
    }

    /// Whether the eye is outside the closed box `b` (an eye at infinity always is), decided
    /// exactly. Only then does a line of sight through an INBOX inside `b` prove the point
    /// hidden: from an eye inside a solid, points inside it are in plain view.
    #[inline]
    pub(crate) fn eye_outside(&self, b: &Aabb) -> bool {
        self.eye.is_none_or(|e| !b.contains_point(&e))
    }

    /// Whether the sight may meet the closed box `b`; never false when it does.
    #[inline]
    pub(crate) fn may_meet(&self, b: &Aabb) -> bool {
        let m = self.margin(b);
        self.slabs(b.min.map(|v| v - m), b.max.map(|v| v + m), false)
    }

    /// Whether the sight surely meets the open box `b`; never true when it does not.
    #[inline]
    pub(crate) fn surely_meets_open(&self, b: &Aabb) -> bool {
        let m = self.margin(b);
        let (lo, hi) = (b.min.map(|v| v + m), b.max.map(|v| v - m));
        (0..3).all(|k| lo[k] < hi[k]) && self.slabs(lo, hi, true)
    }

    /// The slab test of the box `[lo, hi]` for `t` in `[0, limit]` (closed) or `(0, limit)`
    /// against the open box (`open`). A point at the eye has an empty line of sight.
    #[inline]
    fn slabs(&self, lo: [f64; 3], hi: [f64; 3], open: bool) -> bool {
        if self.direction == Vector3::zeros() {
            return false;
        }
        let (mut enter, mut exit) = (0.0f64, self.limit);
        for k in 0..3 {
            let (p, d) = (self.origin[k], self.direction[k]);
            if d == 0.0 {
                let inside = if open {
                    lo[k] < p && p < hi[k]
                } else {
                    lo[k] <= p && p <= hi[k]
                };
                if !inside {
                    return false;
                }
                continue;
            }
            let (a, b) = ((lo[k] - p) / d, (hi[k] - p) / d);
            enter = enter.max(a.min(b));
            exit = exit.min(a.max(b));
        }
        if open { enter < exit } else { enter <= exit }
    }
}

fn max_abs(p: &Point3) -> f64 {
    p.coords.amax()
}

fn max_abs_box(b: &Aabb) -> f64 {
    b.min
        .iter()
        .chain(b.max.iter())
        .fold(0.0f64, |m, v| m.max(v.abs()))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn unit() -> Aabb {
        Aabb::new(Point3::new(0.0, 0.0, 0.0), Point3::new(1.0, 1.0, 1.0))
    }

    #[test]
    fn vertical_rays() {
        let up = Eye::Infinity(Vector3::z());
        let below = Sight::to_eye(&Point3::new(0.5, 0.5, -1.0), &up);
        assert!(below.may_meet(&unit()) && below.surely_meets_open(&unit()));
        let above = Sight::to_eye(&Point3::new(0.5, 0.5, 2.0), &up);
        assert!(!above.may_meet(&unit()) && !above.surely_meets_open(&unit()));
        // Grazing the side face: may meet the closed box, does not cross the open one.
        let side = Sight::to_eye(&Point3::new(1.0, 0.5, -1.0), &up);
        assert!(side.may_meet(&unit()) && !side.surely_meets_open(&unit()));
    }

    #[test]
    fn segment_stops_at_the_eye() {
        let eye = Eye::Point(Point3::new(0.5, 0.5, -0.5));
        let s = Sight::to_eye(&Point3::new(0.5, 0.5, -2.0), &eye);
        assert!(!s.may_meet(&unit()));
        let through = Eye::Point(Point3::new(0.5, 0.5, 3.0));
        assert!(Sight::to_eye(&Point3::new(0.5, 0.5, -2.0), &through).surely_meets_open(&unit()));
    }

    #[test]
    fn a_point_at_the_eye_sees_everything() {
        let e = Point3::new(0.5, 0.5, 0.5);
        let s = Sight::to_eye(&e, &Eye::Point(e));
        assert!(!s.may_meet(&unit()) && !s.surely_meets_open(&unit()));
    }

    #[test]
    fn tiny_and_huge_directions_do_not_overflow() {
        for scale in [1e-300, 1e300] {
            let r = Sight::ray(
                &Point3::new(-1e10, 0.5, 0.5),
                &Vector3::new(scale, 0.0, 0.0),
            );
            assert!(r.may_meet(&unit()) && r.surely_meets_open(&unit()));
        }
    }
}
