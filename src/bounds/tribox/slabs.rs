//! The slabs: [`TriboxBounds`], the lower and upper bound of a point set along each of the
//! 9 directions (the 18 parameters of its tribox), computed exactly in one (or a parallel)
//! pass, with the set operations the engine uses on them (containment, overlap, union,
//! intersection, split).

use std::cmp::Ordering;

use rayon::prelude::*;
use serde::{Serialize, Serializer};

use super::directions::{self, DIAGONAL_AXES, projections};
use crate::geometry::Point3;
use crate::geometry::exact::{sum_sign, two_sum};

/// Bounds of a point set along the tribox's 9 directions: the 18 parameters of its tribox.
///
/// Serialises (serde) as the 18 numbers of [`to_array18`](Self::to_array18).
///
/// ```
/// use kepler::bounds::tribox::TriboxBounds;
/// use kepler::geometry::Point3;
/// let b = TriboxBounds::from_points(&[Point3::new(1.0, 2.0, 3.0), Point3::new(0.0, 0.0, 0.0)]);
/// assert_eq!(b.max()[3], 3.0); // max of x + y
/// assert_eq!(b.min()[8], 0.0); // min of z - y
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TriboxBounds {
    pub(super) min: [f64; 9],
    pub(super) max: [f64; 9],
}

impl Serialize for TriboxBounds {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        self.to_array18().serialize(serializer)
    }
}

impl TriboxBounds {
    /// The 9 directions in the paper's order: x, y, z, x+y, x+z, y+z, x−z, y−x, z−y.
    ///
    /// ```
    /// use kepler::bounds::tribox::TriboxBounds;
    /// assert_eq!(TriboxBounds::DIRECTIONS[7], [-1.0, 1.0, 0.0]); // y - x
    /// ```
    pub const DIRECTIONS: [[f64; 3]; 9] = directions::DIRECTIONS;

    /// The bounds of no point: every minimum +∞, every maximum −∞.
    ///
    /// ```
    /// use kepler::bounds::tribox::TriboxBounds;
    /// assert!(TriboxBounds::empty().is_empty());
    /// ```
    pub fn empty() -> Self {
        Self {
            min: [f64::INFINITY; 9],
            max: [f64::NEG_INFINITY; 9],
        }
    }

    /// The bounds of a point set, in one pass. Points with a NaN coordinate are skipped for the
    /// directions it touches (and are then never contained).
    ///
    /// Each diagonal sum is rounded in `f64`; its exact error is looked at only when the rounded
    /// sum reaches the current extreme, and the final bound is moved one ulp outward when a point
    /// attaining it has an exact sum beyond it. The result is the exact extreme rounded outward.
    ///
    /// ```
    /// use kepler::bounds::tribox::TriboxBounds;
    /// use kepler::geometry::Point3;
    /// let b = TriboxBounds::from_points(&[Point3::new(0.1, 0.7, 0.0)]);
    /// assert_eq!(b.max()[3], (0.1f64 + 0.7).next_up()); // 0.1 + 0.7 rounds down in f64
    /// assert_eq!(b.min()[3], 0.1 + 0.7);
    /// ```
    pub fn from_points(points: &[Point3]) -> Self {
        let mut acc = Accumulator::new();
        acc.add(points);
        acc.finish()
    }

    /// [`from_points`](Self::from_points) in parallel (rayon): chunks are folded on separate
    /// threads and their accumulators merged. Same result.
    ///
    /// ```
    /// use kepler::bounds::tribox::TriboxBounds;
    /// use kepler::geometry::Point3;
    /// let pts: Vec<Point3> = (0..1000).map(|i| Point3::new(i as f64 * 0.1, 1.0, -0.3)).collect();
    /// assert_eq!(TriboxBounds::par_from_points(&pts), TriboxBounds::from_points(&pts));
    /// ```
    pub fn par_from_points(points: &[Point3]) -> Self {
        const CHUNK: usize = 1 << 15;
        points
            .par_chunks(CHUNK)
            .map(|chunk| {
                let mut acc = Accumulator::new();
                acc.add(chunk);
                acc
            })
            .reduce(Accumulator::new, Accumulator::merge)
            .finish()
    }

    /// Whether these bounds contain no point.
    ///
    /// ```
    /// use kepler::bounds::tribox::TriboxBounds;
    /// use kepler::geometry::Point3;
    /// assert!(!TriboxBounds::from_points(&[Point3::origin()]).is_empty());
    /// ```
    pub fn is_empty(&self) -> bool {
        self.min[0] > self.max[0]
    }

    /// The lower bounds, one per direction, in the order of [`DIRECTIONS`](Self::DIRECTIONS).
    ///
    /// ```
    /// use kepler::bounds::tribox::TriboxBounds;
    /// use kepler::geometry::Point3;
    /// let b = TriboxBounds::from_points(&[Point3::new(1.0, 2.0, 4.0)]);
    /// assert_eq!(b.min(), &[1.0, 2.0, 4.0, 3.0, 5.0, 6.0, -3.0, 1.0, 2.0]);
    /// ```
    pub fn min(&self) -> &[f64; 9] {
        &self.min
    }

    /// The upper bounds, one per direction, in the order of [`DIRECTIONS`](Self::DIRECTIONS).
    ///
    /// ```
    /// use kepler::bounds::tribox::TriboxBounds;
    /// use kepler::geometry::Point3;
    /// let b = TriboxBounds::from_points(&[Point3::new(1.0, 2.0, 4.0)]);
    /// assert_eq!(b.max(), b.min());
    /// ```
    pub fn max(&self) -> &[f64; 9] {
        &self.max
    }

    /// The 18 bounds as `[min_x, max_x, min_y, max_y, min_z, max_z, min_(x+y), max_(x+y), …,
    /// min_(z−y), max_(z−y)]`: element `2d` / `2d+1` is the lower / upper bound of direction `d`,
    /// which is also the index of the corresponding plane and face. This is the JSON layout.
    ///
    /// ```
    /// use kepler::bounds::tribox::TriboxBounds;
    /// use kepler::geometry::Point3;
    /// let b = TriboxBounds::from_points(&[Point3::new(0.0, 0.0, 0.0), Point3::new(1.0, 2.0, 3.0)]);
    /// assert_eq!(&b.to_array18()[..8], &[0.0, 1.0, 0.0, 2.0, 0.0, 3.0, 0.0, 3.0]);
    /// assert_eq!(serde_json::to_string(&b).unwrap(),
    ///     "[0.0,1.0,0.0,2.0,0.0,3.0,0.0,3.0,0.0,4.0,0.0,5.0,-2.0,0.0,0.0,1.0,0.0,1.0]");
    /// ```
    pub fn to_array18(&self) -> [f64; 18] {
        std::array::from_fn(|j| {
            if j % 2 == 0 {
                self.min[j / 2]
            } else {
                self.max[j / 2]
            }
        })
    }

    /// Whether `p` satisfies all 18 inequalities, decided exactly (a point on a bounding plane
    /// is inside). Diagonal projections are not rounded: their comparison with the bound is the
    /// exact sign of a three-term sum.
    ///
    /// ```
    /// use kepler::bounds::tribox::TriboxBounds;
    /// use kepler::geometry::Point3;
    /// let b = TriboxBounds::from_points(&[Point3::new(0.0, 0.0, 0.0), Point3::new(1.0, 1.0, 0.0)]);
    /// assert!(b.contains_point(&Point3::new(0.5, 0.5, 0.0)));
    /// assert!(!b.contains_point(&Point3::new(1.0, 0.0, 0.0))); // y - x below its minimum 0
    /// ```
    pub fn contains_point(&self, p: &Point3) -> bool {
        let c = [p.x, p.y, p.z];
        let axes_inside = c
            .iter()
            .zip(self.min.iter().zip(&self.max))
            .all(|(&v, (&lo, &hi))| lo <= v && v <= hi);
        axes_inside
            && DIAGONAL_AXES.iter().enumerate().all(|(k, &(i, j, minus))| {
                let (a, b) = (c[i], if minus { -c[j] } else { c[j] });
                let (lo, hi) = (self.min[3 + k], self.max[3 + k]);
                (lo == f64::NEG_INFINITY || sum_sign(&[a, b, -lo]) != Ordering::Less)
                    && (hi == f64::INFINITY || sum_sign(&[a, b, -hi]) != Ordering::Greater)
            })
    }

    /// Whether the slabs of `self` and `other` overlap along all 9 directions (touching counts).
    /// Disjoint slabs along one direction prove the triboxes disjoint; overlapping slabs along
    /// all nine are the paper's interference filter (not an exact polytope test).
    ///
    /// ```
    /// use kepler::bounds::tribox::TriboxBounds;
    /// use kepler::geometry::Point3;
    /// let a = TriboxBounds::from_points(&[Point3::new(0.0, 0.0, 0.0), Point3::new(1.0, 0.0, 0.0)]);
    /// let b = TriboxBounds::from_points(&[Point3::new(1.0, 0.0, 0.0), Point3::new(2.0, 0.0, 0.0)]);
    /// let c = TriboxBounds::from_points(&[Point3::new(0.0, 1.0, 0.0), Point3::new(1.0, 2.0, 0.0)]);
    /// assert!(a.intersects(&b));
    /// assert!(!a.intersects(&c));
    /// ```
    pub fn intersects(&self, other: &TriboxBounds) -> bool {
        (0..9).all(|d| self.min[d] <= other.max[d] && other.min[d] <= self.max[d])
    }

    /// The bounds of the union of both point sets.
    ///
    /// ```
    /// use kepler::bounds::tribox::TriboxBounds;
    /// use kepler::geometry::Point3;
    /// let p = [Point3::new(0.0, 0.0, 0.0), Point3::new(1.0, 2.0, 3.0)];
    /// let a = TriboxBounds::from_points(&p[..1]);
    /// let b = TriboxBounds::from_points(&p[1..]);
    /// assert_eq!(a.union(&b), TriboxBounds::from_points(&p));
    /// assert_eq!(a.union(&TriboxBounds::empty()), a);
    /// ```
    pub fn union(&self, other: &TriboxBounds) -> TriboxBounds {
        TriboxBounds {
            min: std::array::from_fn(|d| self.min[d].min(other.min[d])),
            max: std::array::from_fn(|d| self.max[d].max(other.max[d])),
        }
    }

    /// The points in both: the intersection of the two sets of 18 half-spaces (empty bounds
    /// when some slab pair does not overlap).
    ///
    /// ```
    /// use kepler::bounds::tribox::TriboxBounds;
    /// use kepler::geometry::Point3;
    /// let a = TriboxBounds::from_points(&[Point3::new(0.0, 0.0, 0.0), Point3::new(2.0, 2.0, 2.0)]);
    /// let b = TriboxBounds::from_points(&[Point3::new(1.0, 1.0, 1.0), Point3::new(3.0, 3.0, 3.0)]);
    /// let both = a.intersection(&b);
    /// assert_eq!((both.min()[0], both.max()[0], both.max()[3]), (1.0, 2.0, 4.0));
    /// assert!(a.intersection(&TriboxBounds::empty()).is_empty());
    /// ```
    pub fn intersection(&self, other: &TriboxBounds) -> TriboxBounds {
        let b = TriboxBounds {
            min: std::array::from_fn(|d| self.min[d].max(other.min[d])),
            max: std::array::from_fn(|d| self.max[d].min(other.max[d])),
        };
        if (0..9).any(|d| b.min[d] > b.max[d]) {
            TriboxBounds::empty()
        } else {
            b
        }
    }

    /// The two halves cut by the plane `d · x = h` across direction `d` (an index into
    /// [`DIRECTIONS`](Self::DIRECTIONS)): `[below, above]`, the first with its maximum along `d`
    /// lowered to `h`, the second with its minimum raised to `h` (either empty when `h` lies
    /// outside the slab). Hierarchical triboxes split their regions this way.
    ///
    /// ```
    /// use kepler::bounds::tribox::TriboxBounds;
    /// use kepler::geometry::Point3;
    /// let b = TriboxBounds::from_points(&[Point3::new(0.0, 0.0, 0.0), Point3::new(2.0, 2.0, 2.0)]);
    /// let [below, above] = b.split(3, 1.0); // the plane x + y = 1
    /// assert_eq!((below.min()[3], below.max()[3]), (0.0, 1.0));
    /// assert_eq!((above.min()[3], above.max()[3]), (1.0, 4.0));
    /// assert!(b.split(0, 5.0)[1].is_empty());
    /// ```
    pub fn split(&self, d: usize, h: f64) -> [TriboxBounds; 2] {
        let (mut below, mut above) = (*self, *self);
        below.max[d] = below.max[d].min(h);
        above.min[d] = above.min[d].max(h);
        [below, above].map(|b| b.intersection(&b))
    }

    /// The bounds as offsets of the 18 half-spaces n_j · x ≤ β_j: β_(2d) = −min_d,
    /// β_(2d+1) = max_d (negation is exact).
    pub(super) fn offsets(&self) -> [f64; 18] {
        std::array::from_fn(|j| {
            if j % 2 == 0 {
                -self.min[j / 2]
            } else {
                self.max[j / 2]
            }
        })
    }

    /// The bounds with half-space offsets `beta` (see [`offsets`](Self::offsets)).
    pub(super) fn from_offsets(beta: &[f64; 18]) -> Self {
        TriboxBounds {
            min: std::array::from_fn(|d| -beta[2 * d]),
            max: std::array::from_fn(|d| beta[2 * d + 1]),
        }
    }
}

/// Running extremes of a point set. For the 6 diagonal directions the extremes are of the
/// rounded sums, with a flag telling whether a point attaining the extreme has an exact sum
/// beyond it.
#[derive(Clone, Copy)]
pub(super) struct Accumulator {
    min: [f64; 9],
    max: [f64; 9],
    below_min: [bool; 6],
    above_max: [bool; 6],
}

impl Accumulator {
    /// The extremes of no point.
    fn new() -> Self {
        Accumulator {
            min: [f64::INFINITY; 9],
            max: [f64::NEG_INFINITY; 9],
            below_min: [false; 6],
            above_max: [false; 6],
        }
    }

    /// Adds points, block by block. A branch-free pass takes the extremes of the 9 rounded
    /// projections of a block (cache resident); only when a block reaches a running diagonal
    /// extreme is it scanned again, for the exact errors of the sums attaining it.
    fn add(&mut self, points: &[Point3]) {
        const BLOCK: usize = 2048;
        for block in points.chunks(BLOCK) {
            let mut lo = [f64::INFINITY; 9];
            let mut hi = [f64::NEG_INFINITY; 9];
            for p in block {
                let v = projections(p);
                for d in 0..9 {
                    lo[d] = if v[d] < lo[d] { v[d] } else { lo[d] };
                    hi[d] = if v[d] > hi[d] { v[d] } else { hi[d] };
                }
            }
            for d in 0..3 {
                self.min[d] = self.min[d].min(lo[d]);
                self.max[d] = self.max[d].max(hi[d]);
            }
            for (k, &(i, j, minus)) in DIAGONAL_AXES.iter().enumerate() {
                let d = 3 + k;
                // The exact error of the sums of the block's points that round to `m`: whether
                // one is positive (`sign` 1) or negative (-1).
                let error_beyond = |m: f64, sign: f64| {
                    block.iter().any(|p| {
                        let (a, b) = (p[i], if minus { -p[j] } else { p[j] });
                        a + b == m && two_sum(a, b).1 * sign > 0.0
                    })
                };
                if hi[d] >= self.max[d] {
                    let above = error_beyond(hi[d], 1.0);
                    if hi[d] > self.max[d] {
                        self.max[d] = hi[d];
                        self.above_max[k] = above;
                    } else {
                        self.above_max[k] |= above;
                    }
                }
                if lo[d] <= self.min[d] {
                    let below = error_beyond(lo[d], -1.0);
                    if lo[d] < self.min[d] {
                        self.min[d] = lo[d];
                        self.below_min[k] = below;
                    } else {
                        self.below_min[k] |= below;
                    }
                }
            }
        }
    }

    /// The extremes of both accumulators' points.
    fn merge(self, other: Self) -> Self {
        let mut out = self;
        for d in 0..9 {
            out.min[d] = self.min[d].min(other.min[d]);
            out.max[d] = self.max[d].max(other.max[d]);
        }
        for k in 0..6 {
            let d = 3 + k;
            out.below_min[k] = (self.min[d] == out.min[d] && self.below_min[k])
                || (other.min[d] == out.min[d] && other.below_min[k]);
            out.above_max[k] = (self.max[d] == out.max[d] && self.above_max[k])
                || (other.max[d] == out.max[d] && other.above_max[k]);
        }
        out
    }

    /// The bounds: diagonal extremes moved one ulp outward where an exact sum goes beyond.
    fn finish(self) -> TriboxBounds {
        let mut b = TriboxBounds {
            min: self.min,
            max: self.max,
        };
        for k in 0..6 {
            if self.below_min[k] {
                b.min[3 + k] = b.min[3 + k].next_down();
            }
            if self.above_max[k] {
                b.max[3 + k] = b.max[3 + k].next_up();
            }
        }
        b
    }
}
