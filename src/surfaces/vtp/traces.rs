//! The lines that bound cells, filed by where their traces lie in F's plane: two lines can be
//! the same line only when their traces have the same direction and the same distance from
//! F's first vertex `O`, so a line is compared with the few filed near it rather than with
//! all of them. (A face cut by many occluders meets hundreds of lines, many of them parallel
//! in a city, and the comparisons grew as their square.)
//!
//! A trace `c + g·(x − O) = 0` of F's plane has the direction `q = g_F × g` and lies at the
//! distance `|c|·|g_F| / |q|` from `O`. The angle of `q` is read in its projection on a
//! coordinate plane that F's plane is not perpendicular to (the projection keeps directions
//! apart), modulo π (the same line may come with either orientation). From the estimates of
//! `c`, `g_F` and `q` and their error bounds come an interval certified to hold the exact
//! angle and one to hold the exact distance; a line is filed under every (angle, distance)
//! bucket the two meet, and a line whose angle cannot be told (a direction not certified
//! nonzero, or no axis) is filed apart and tried against every query. Two lines with the same
//! trace have the same exact angle and distance, so they share a bucket: the buckets only
//! spare comparisons, and the exact test (`Vtp::same_trace`) still decides.

use super::Map;
use crate::geometry::estimate::Estimate;
use std::cmp::Ordering;
use std::f64::consts::PI;

/// Buckets over the angles `[0, π)`.
const ANGLES: usize = 256;
/// Buckets over the distances `[0, R]`, `R` the face's radius about `O` (farther distances
/// go to the last: no line that bounds a cell of F lies farther).
const DISTANCES: usize = 64;

/// The lines filed by the angle and distance of their traces.
#[derive(Debug, Default)]
pub(super) struct Traces {
    /// The coordinate dropped by the projection, when one is certified to keep directions
    /// apart (F's plane's normal has a component there certified nonzero).
    axis: Option<usize>,
    /// The estimate of `|g_F|`'s value and a bound on its error.
    normal_length: (f64, f64),
    /// The width of a distance bucket (0: one bucket for all).
    width: f64,
    /// The lines under each (angle, distance) bucket.
    buckets: Map<(u16, u16), Vec<u32>>,
    /// The lines whose angle is not known closely enough (every line, without an axis).
    anywhere: Vec<u32>,
}

/// Runs of buckets: a first angle bucket and a count (wrapping round π), and a first
/// distance bucket and a count.
type Span = ((usize, usize), (usize, usize));

/// The length of the vector estimated by `v` and a bound on its error: `|v̂ − v| ≤ Σ e`, the
/// roundings of the length and of the bound covered by a relative 1e-12.
fn length(v: &[Estimate]) -> (f64, f64) {
    let value = v.iter().map(|e| e.value * e.value).sum::<f64>().sqrt();
    let bound = v.iter().map(|e| e.bound).sum::<f64>() + 1e-12 * value;
    (value, bound)
}

impl Traces {
    /// For a face with the normal estimated by `normal` (the gradient of its plane's form)
    /// and radius `radius` about `O` (any positive value: it only sets the buckets' width).
    pub(super) fn new(normal: [Estimate; 3], radius: f64) -> Traces {
        let k = (0..3)
            .max_by(|&i, &j| normal[i].value.abs().total_cmp(&normal[j].value.abs()))
            .unwrap_or(0);
        let n = normal[k];
        let axis = (n.value.is_finite() && n.value.abs() > n.bound).then_some(k);
        let width = radius / DISTANCES as f64;
        Traces {
            axis,
            normal_length: length(&normal),
            width: if width.is_finite() && width > 0.0 {
                width
            } else {
                0.0
            },
            buckets: Map::default(),
            anywhere: Vec::new(),
        }
    }

    /// The buckets holding the exact angle and distance of the trace with value at `O`
    /// estimated by `c` and direction by `q`; `None` when the angle cannot be told.
    fn span(&self, c: &Estimate, q: &[Estimate; 3]) -> Option<Span> {
        let k = self.axis?;
        let (i, j) = ((k + 1) % 3, (k + 2) % 3);
        let (x, y) = (q[i].value, q[j].value);
        let projected = x.hypot(y);
        let error = q[i].bound + q[j].bound;
        // A perturbation of length at most `error` turns a vector of length `projected` by
        // at most `asin(error / projected)` ≤ `(π/2)·error / projected` (for a small ratio);
        // 1e-9 covers the roundings of `atan2` and of this bound many times over.
        if !(projected.is_finite() && error < 0.25 * projected) {
            return None;
        }
        let spread = 2.0 * error / projected + 1e-9;
        let angle = y.atan2(x).rem_euclid(PI);
        let step = PI / ANGLES as f64;
        let first = ((angle - spread) / step).floor();
        let count = (((angle + spread) / step).floor() - first) as usize + 1;
        let angles = (
            (first as isize).rem_euclid(ANGLES as isize) as usize,
            count.min(ANGLES),
        );
        Some((angles, self.distances(c, q)))
    }

    /// The distance buckets holding `|c|·|g_F| / |q|`.
    fn distances(&self, c: &Estimate, q: &[Estimate; 3]) -> (usize, usize) {
        let all = (0, DISTANCES);
        let (q_length, q_error) = length(q);
        let (n_length, n_error) = self.normal_length;
        let below = |a: f64, b: f64| a.partial_cmp(&b) == Some(Ordering::Less);
        if self.width == 0.0 || !below(q_error, q_length) || !below(n_error, n_length) {
            return all;
        }
        let low = (c.value.abs() - c.bound).max(0.0) * (n_length - n_error) / (q_length + q_error);
        let high = (c.value.abs() + c.bound) * (n_length + n_error) / (q_length - q_error);
        let (low, high) = (low * (1.0 - 1e-9), high * (1.0 + 1e-9));
        if !(low.is_finite() && high.is_finite()) {
            return all;
        }
        let bucket = |d: f64| ((d / self.width).floor() as usize).min(DISTANCES - 1);
        let first = bucket(low);
        (first, bucket(high) - first + 1)
    }

    /// The keys of the buckets in a span.
    fn keys(span: Span) -> impl Iterator<Item = (u16, u16)> {
        let ((a0, na), (d0, nd)) = span;
        (0..na)
            .flat_map(move |a| (d0..d0 + nd).map(move |d| (((a0 + a) % ANGLES) as u16, d as u16)))
    }

    /// Files line `l`, its trace's value at `O` estimated by `c` and direction by `q`.
    pub(super) fn insert(&mut self, l: u32, c: &Estimate, q: &[Estimate; 3]) {
        match self.span(c, q) {
            Some(span) => {
                for key in Traces::keys(span) {
                    self.buckets.entry(key).or_default().push(l);
                }
            }
            None => self.anywhere.push(l),
        }
    }

    /// A filed line for which `same` holds, among those that may share the trace with value
    /// at `O` estimated by `c` and direction by `q` (every filed line is tried when its angle
    /// cannot be told). At most one holds when the filed lines are distinct.
    pub(super) fn find(
        &self,
        c: &Estimate,
        q: &[Estimate; 3],
        mut same: impl FnMut(u32) -> bool,
    ) -> Option<u32> {
        if let Some(&l) = self.anywhere.iter().find(|&&l| same(l)) {
            return Some(l);
        }
        match self.span(c, q) {
            Some(span) => Traces::keys(span)
                .filter_map(|key| self.buckets.get(&key))
                .flatten()
                .copied()
                .find(|&l| same(l)),
            None => {
                let mut all: Vec<u32> = self.buckets.values().flatten().copied().collect();
                all.sort_unstable();
                all.dedup();
                all.into_iter().find(|&l| same(l))
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::random::SplitMix64;

    fn exact(v: [f64; 3]) -> [Estimate; 3] {
        v.map(Estimate::exact)
    }

    fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
        [
            a[1] * b[2] - a[2] * b[1],
            a[2] * b[0] - a[0] * b[2],
            a[0] * b[1] - a[1] * b[0],
        ]
    }

    /// A line filed with noisy estimates (a multiple of its form, either way, at any scale)
    /// is found from exact ones; a turned or moved line is not, unless its buckets overlap.
    #[test]
    fn the_same_trace_is_found() {
        let mut rng = SplitMix64(3);
        let mut apart = 0;
        for round in 0..4_000 {
            let normal = [rng.range(-1.0, 1.0), rng.range(-1.0, 1.0), 1.0];
            let mut traces = Traces::new(exact(normal), 4.0);
            let g = [
                rng.range(-1.0, 1.0),
                rng.range(-1.0, 1.0),
                rng.range(-1.0, 1.0),
            ];
            let c = rng.range(-1.0, 1.0);
            let q = cross(normal, g);
            let scale = if round % 2 == 0 { -3.5 } else { 2f64.powi(40) };
            // Errors up to a tenth of a bucket's width in angle, and none.
            let relative = [0.0, 1e-9, 1e-3][round % 3];
            let mut noisy = |x: f64| {
                let bound = (x * scale).abs() * relative;
                Estimate {
                    value: x * scale + bound * (2.0 * rng.unit() - 1.0),
                    bound,
                }
            };
            let (c_noisy, q_noisy) = (noisy(c), q.map(&mut noisy));
            traces.insert(7, &c_noisy, &q_noisy);
            let c = Estimate::exact(c);
            assert_eq!(traces.find(&c, &exact(q), |l| l == 7), Some(7), "{round}");
            let turned = [-q[1], q[0], q[2]];
            let moved = Estimate::exact(c.value + 2.0);
            for (c, q) in [(c, turned), (moved, q)] {
                let found = traces.find(&c, &exact(q), |l| l == 7).is_some();
                let span = traces.span(&c, &exact(q));
                let shared = span.is_some_and(|s| {
                    Traces::keys(s).any(|k| traces.buckets.get(&k).is_some_and(|b| b.contains(&7)))
                });
                assert_eq!(found, shared || span.is_none(), "{round}");
                apart += usize::from(!found);
            }
        }
        assert!(apart > 6_000, "{apart}");
    }

    /// Without a certified axis, or for a direction not certified nonzero, every line is
    /// tried.
    #[test]
    fn unknown_directions_are_tried_against_all() {
        let c = Estimate::exact(0.5);
        let mut traces = Traces::new(exact([0.0, 0.0, 0.0]), 1.0);
        traces.insert(1, &c, &exact([1.0, 0.0, 0.0]));
        assert_eq!(
            traces.find(&c, &exact([0.0, 1.0, 0.0]), |l| l == 1),
            Some(1)
        );
        let mut traces = Traces::new(exact([0.0, 0.0, 1.0]), 1.0);
        let vague = [1.0, 0.0, 0.0].map(|v| Estimate {
            value: v,
            bound: 1.0,
        });
        traces.insert(2, &c, &vague);
        traces.insert(3, &c, &exact([1.0, 0.0, 0.0]));
        assert_eq!(
            traces.find(&c, &exact([0.0, 1.0, 0.0]), |l| l == 2),
            Some(2)
        );
        assert_eq!(traces.find(&c, &vague, |l| l == 3), Some(3));
        assert_eq!(traces.find(&c, &exact([0.0, 1.0, 0.0]), |l| l == 3), None);
    }
}
