//! The triangles round a crowded vertex of a mesh, found by angle: the occluder index's answer
//! to the fan.
//!
//! A vertex shared by many triangles (a hub: a cone's apex, a pole of a UV sphere) makes a
//! uniform grid of the picture quadratic: its triangles' pictures are slivers that all meet at
//! the hub's picture, so a cell of any size near the hub lists a crowd of them, and a cell
//! small enough to hold few lists each sliver in many cells. Seen from the hub, though, the
//! slivers are told apart by angle: the picture of a triangle with a corner at the hub lies in
//! the sector between the directions of its other two corners. So each hub's triangles are
//! listed by the buckets of angle their sectors cover ([`Hub`]), and a point is looked up by
//! its own angle, widened by how far from the point a triangle may lie and still hide it.
//!
//! Sound like the grid it stands beside: a triangle whose rounded picture comes within `slack`
//! of a point at distance `d > slack` from the hub has a point in its sector whose angle is
//! within `asin(slack / d)` of the point's; the window is widened further by far more than the
//! rounding of the angles. A point within a few `slack` of the hub's picture gets every
//! triangle of the hub, and a triangle whose sector is not well defined (a picture seen edge-on
//! through the hub, or with a corner on it) is in every answer. This is only a filter: the
//! exact test decides, so the drawing is the same with or without it.
//!
//! Cost: `n` triangles at a hub listed in `n` buckets, each in the buckets its sector covers
//! (a fan round the hub covers the circle a few times over: a few entries per triangle); a
//! query reads the buckets of its window.

use crate::geometry::polygon::bounding_box;
use std::f64::consts::{PI, TAU};

/// A vertex is a hub when at least this many listed triangles share it.
pub(super) const HUB: usize = 64;

/// The angle by which sectors and windows are widened, far above the rounding of `atan2` of
/// rounded differences (a few units in 10⁻¹⁶).
const ANGLE_MARGIN: f64 = 1e-9;

/// A sector this wide or wider is not trusted to be the triangle's: the triangle is in every
/// answer.
const WIDEST: f64 = PI - 1e-6;

/// The triangles at one hub, by angle round its picture.
#[derive(Debug)]
pub(super) struct Hub {
    centre: [f64; 2],
    /// The box of the pictures of the hub's triangles.
    bounds: [[f64; 2]; 2],
    /// Bucket `k` (of angles from `-π + k·TAU/n`) lists `listed[start[k]..start[k + 1]]`.
    start: Vec<u32>,
    listed: Vec<u32>,
    /// The triangles in every answer.
    wide: Vec<u32>,
    /// Every triangle of the hub, for points near its picture.
    all: Vec<u32>,
}

impl Hub {
    /// The hub at `centre` (its picture) of the `triangles`, each with the pictures of its two
    /// other corners.
    pub(super) fn new(centre: [f64; 2], triangles: &[(u32, [[f64; 2]; 2])]) -> Hub {
        let n = triangles.len().max(1);
        let width = TAU / n as f64;
        let bucket = |a: f64| (((a + PI) / width) as usize).min(n - 1);
        let mut wide = Vec::new();
        let mut pairs: Vec<(u32, u32)> = Vec::new();
        for &(t, corners) in triangles {
            let Some([lo, hi]) = sector(centre, corners) else {
                wide.push(t);
                continue;
            };
            let (first, last) = (bucket(lo), bucket(hi.min(PI)));
            pairs.extend((first..=last).map(|k| (k as u32, t)));
            if hi > PI {
                // Wrapped past π: the rest from -π.
                pairs.extend((0..=bucket(hi - TAU)).map(|k| (k as u32, t)));
            }
        }
        pairs.sort_unstable();
        let mut start = vec![0u32; n + 1];
        for &(k, _) in &pairs {
            start[k as usize + 1] += 1;
        }
        for k in 0..n {
            start[k + 1] += start[k];
        }
        let corners = triangles.iter().flat_map(|(_, c)| c.iter().copied());
        Hub {
            bounds: bounding_box(corners.chain([centre])),
            centre,
            start,
            listed: pairs.into_iter().map(|(_, t)| t).collect(),
            wide,
            all: triangles.iter().map(|&(t, _)| t).collect(),
        }
    }

    /// The hub's triangles whose pictures may come within `slack` of `p` (some more than
    /// once), a superset of those that do.
    pub(super) fn near(&self, p: [f64; 2], slack: f64) -> Box<dyn Iterator<Item = &u32> + '_> {
        let [low, high] = self.bounds;
        if (0..2).any(|k| p[k] + slack < low[k] || p[k] - slack > high[k]) {
            // Beyond every triangle's picture (compared with the slack: the box holds them).
            return Box::new(std::iter::empty());
        }
        let (dx, dy) = (p[0] - self.centre[0], p[1] - self.centre[1]);
        let d = dx.hypot(dy);
        if !(d > 4.0 * slack && d.is_finite()) {
            return Box::new(self.all.iter());
        }
        let n = self.start.len() - 1;
        let width = TAU / n as f64;
        let window = 1.001 * (slack / d).asin() + ANGLE_MARGIN;
        let angle = dy.atan2(dx);
        let buckets = ((2.0 * window / width) as usize + 2).min(n);
        let first = ((angle - window + PI) / width).floor();
        let first = first.rem_euclid(n as f64) as usize % n;
        let lists = (0..buckets).flat_map(move |k| {
            let b = (first + k) % n;
            &self.listed[self.start[b] as usize..self.start[b + 1] as usize]
        });
        Box::new(lists.chain(&self.wide))
    }

    /// The number of (bucket, triangle) entries.
    pub(super) fn entries(&self) -> usize {
        self.listed.len() + self.wide.len()
    }
}

/// The hubs among the `triangles` (by vertex indices) for which `listed` holds, with the
/// pictures of the vertices: the vertices at least [`HUB`] of them share, and whether each
/// triangle is listed at a hub (at the hub of its corners that most share, the first of
/// equals) instead of in the grid's cells.
pub(super) fn hubs(
    triangles: &[[u32; 3]],
    pictures: &[[f64; 2]],
    listed: impl Fn(usize) -> bool,
) -> (Vec<Hub>, Vec<bool>) {
    let mut at_hub = vec![false; triangles.len()];
    if triangles.len() < HUB {
        return (Vec::new(), at_hub);
    }
    let mut degree = vec![0u32; pictures.len()];
    for (t, tri) in triangles.iter().enumerate() {
        if listed(t) {
            tri.iter().for_each(|&v| degree[v as usize] += 1);
        }
    }
    let mut members: Vec<(u32, u32)> = Vec::new();
    for (t, tri) in triangles.iter().enumerate() {
        if !listed(t) {
            continue;
        }
        let hub = tri
            .iter()
            .copied()
            .max_by(|&x, &y| degree[x as usize].cmp(&degree[y as usize]).then(y.cmp(&x)));
        if let Some(h) = hub.filter(|&h| degree[h as usize] as usize >= HUB) {
            members.push((h, t as u32));
            at_hub[t] = true;
        }
    }
    members.sort_unstable();
    let hubs = members
        .chunk_by(|x, y| x.0 == y.0)
        .map(|run| {
            let h = run[0].0;
            let fan: Vec<(u32, [[f64; 2]; 2])> = run
                .iter()
                .map(|&(_, t)| {
                    let tri = triangles[t as usize];
                    let mut others = tri
                        .iter()
                        .filter(|&&v| v != h)
                        .map(|&v| pictures[v as usize]);
                    let first = others.next().unwrap_or(pictures[h as usize]);
                    (t, [first, others.next().unwrap_or(first)])
                })
                .collect();
            Hub::new(pictures[h as usize], &fan)
        })
        .collect();
    (hubs, at_hub)
}

/// The angles `[lo, hi]` (`-π ≤ lo < π`, `lo ≤ hi < lo + π`) of the sector from `centre`
/// between the directions of `corners`, widened by [`ANGLE_MARGIN`]; `None` when a corner's
/// direction is not defined or the sector is too wide to be trusted.
fn sector(centre: [f64; 2], corners: [[f64; 2]; 2]) -> Option<[f64; 2]> {
    let angles = corners.map(|c| {
        let (dx, dy) = (c[0] - centre[0], c[1] - centre[1]);
        let finite = dx.is_finite() && dy.is_finite() && (dx != 0.0 || dy != 0.0);
        finite.then(|| dy.atan2(dx))
    });
    let [Some(a), Some(b)] = angles else {
        return None;
    };
    let (lo, hi) = (a.min(b), a.max(b));
    let (lo, hi) = if hi - lo > PI {
        (hi, lo + TAU)
    } else {
        (lo, hi)
    };
    if hi - lo >= WIDEST {
        return None;
    }
    let lo = lo - ANGLE_MARGIN;
    let (lo, hi) = if lo < -PI {
        (lo + TAU, hi + ANGLE_MARGIN + TAU)
    } else {
        (lo, hi + ANGLE_MARGIN)
    };
    Some([lo, hi])
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::random::SplitMix64;

    /// Whether the closed triangle `a b c` comes within `s` of `p` (by brute force: `p` in
    /// it, or within `s` of a side).
    fn within(tri: [[f64; 2]; 3], p: [f64; 2], s: f64) -> bool {
        let cross = |a: [f64; 2], b: [f64; 2], c: [f64; 2]| {
            (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])
        };
        let signs = [0, 1, 2].map(|k| cross(tri[k], tri[(k + 1) % 3], p));
        if signs.iter().all(|&x| x >= 0.0) || signs.iter().all(|&x| x <= 0.0) {
            return true;
        }
        (0..3).any(|k| {
            let (a, b) = (tri[k], tri[(k + 1) % 3]);
            let (ux, uy) = (b[0] - a[0], b[1] - a[1]);
            let len = ux * ux + uy * uy;
            let t = if len > 0.0 {
                (((p[0] - a[0]) * ux + (p[1] - a[1]) * uy) / len).clamp(0.0, 1.0)
            } else {
                0.0
            };
            let (x, y) = (a[0] + t * ux - p[0], a[1] + t * uy - p[1]);
            x.hypot(y) <= s
        })
    }

    #[test]
    fn every_triangle_near_a_point_is_in_its_answer() {
        for seed in 0..20 {
            let mut rng = SplitMix64(seed);
            let centre = [rng.range(-3.0, 3.0), rng.range(-3.0, 3.0)];
            let n = [64, 100, 500][seed as usize % 3];
            // A fan round the centre (some slivers folded over, some through it, some with a
            // corner on it), and scattered triangles.
            let triangles: Vec<(u32, [[f64; 2]; 2])> = (0..n)
                .map(|t| {
                    let corner = |rng: &mut SplitMix64| {
                        let (a, r) = (rng.range(-PI, PI), rng.range(0.0, 2.0));
                        [centre[0] + r * a.cos(), centre[1] + r * a.sin()]
                    };
                    let c = match rng.below(10) {
                        0 => [corner(&mut rng), centre],
                        1 => {
                            let q = corner(&mut rng);
                            [q, [2.0 * centre[0] - q[0], 2.0 * centre[1] - q[1]]]
                        }
                        2 => {
                            let (a, r) = (rng.range(-PI, PI), rng.range(0.1, 2.0));
                            let q = [centre[0] + r * a.cos(), centre[1] + r * a.sin()];
                            let b = a + rng.range(-0.01, 0.01);
                            [
                                q,
                                [centre[0] + 2.0 * r * b.cos(), centre[1] + 2.0 * r * b.sin()],
                            ]
                        }
                        _ => [corner(&mut rng), corner(&mut rng)],
                    };
                    (t as u32, c)
                })
                .collect();
            let hub = Hub::new(centre, &triangles);
            assert!(hub.entries() >= n);
            for _ in 0..400 {
                let p = [rng.range(-6.0, 6.0), rng.range(-6.0, 6.0)];
                let s = [0.0, 1e-9, 1e-3, 0.1, 1.0][rng.below(5)];
                let answer: Vec<u32> = hub.near(p, s).copied().collect();
                for &(t, [q, r]) in &triangles {
                    if within([centre, q, r], p, s * 0.999) {
                        assert!(answer.contains(&t), "seed {seed}: {t} missed at {p:?}, {s}");
                    }
                }
            }
        }
    }

    #[test]
    fn a_point_far_from_a_fan_gets_few_triangles() {
        let n = 10_000;
        let triangles: Vec<(u32, [[f64; 2]; 2])> = (0..n)
            .map(|t| {
                let a = |k: usize| TAU * (k % n) as f64 / n as f64;
                (
                    t as u32,
                    [[a(t).cos(), a(t).sin()], [a(t + 1).cos(), a(t + 1).sin()]],
                )
            })
            .collect();
        let hub = Hub::new([0.0, 0.0], &triangles);
        assert!(hub.entries() <= 3 * n);
        let answer = hub.near([0.5, 0.001], 1e-12).count();
        assert!((1..=8).contains(&answer), "{answer} triangles");
        assert_eq!(hub.near([1e-13, 0.0], 1e-12).count(), n);
    }
}
