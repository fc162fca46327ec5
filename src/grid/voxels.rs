//! The uniform grid in space: each triangle listed in the cells it meets, not in every cell of
//! its bounding box.
//!
//! A long thin triangle (a sliver of a fan, a cone's side, a pole cap of a UV sphere) has a
//! box far larger than itself: listed by its box, it shares cells with every other triangle of
//! the fan, and the pairs to test grow with the square of the fan. Listed by the cells it
//! meets, it shares a cell only with the triangles that pass near it.
//!
//! The cells a triangle meets are found slab by slab: the triangle is clipped to each slab of
//! cells across `x` (Sutherland–Hodgman), the piece to each row across `y`, and the cells of
//! the row are those of the piece's range in `z`. Every clipping plane and every range is
//! widened by a margin of 2⁻⁴⁰ of the largest coordinate of the grid, far more than the
//! rounding of the clipped points (each a convex combination of two points, a few ulps from
//! the exact one), so no cell that the exact triangle meets is missed; a few that it only
//! nearly meets may be listed. The listing is a filter: whatever meets is decided exactly by
//! the caller.
//!
//! Written by hand: the cell walk is Franklin's uniform grid (KEPLER 1981, item 4c) lifted to
//! space; the crates at hand (rstar, parry's BVH) list by bounding box.
//!
//! ```
//! use kepler::{geometry::{Aabb, Point3}, grid::Voxels};
//! let grid = Voxels::new(Aabb::new(Point3::origin(), Point3::new(4.0, 4.0, 4.0)), 1.0);
//! // The diagonal sliver from (0,0,0) to (4,4,4) meets the cells of the diagonal and those
//! // around the grid's corners it passes through, not all 64 cells of its box.
//! let sliver = [Point3::origin(), Point3::new(4.0, 4.0, 4.0), Point3::new(4.0, 4.0, 3.9)];
//! let mut cells = Vec::new();
//! grid.triangle_cells(&sliver, &mut cells);
//! assert!(cells.len() <= 22);
//! assert!(cells.contains(&grid.cell_of(&Point3::new(2.5, 2.5, 2.5))));
//! ```

use crate::geometry::{Aabb, Point3};

/// The relative margin of the clipping: 2⁻⁴⁰ of the grid's largest coordinate (also the
/// margin of the picture cells' lists, `hidden::cover`).
pub(crate) const MARGIN: f64 = 1.0 / (1u64 << 40) as f64;

/// The most cells along one axis (cell numbers fit in 63 bits).
const MAX_CELLS: usize = 1 << 20;

/// A uniform grid of cubic cells over a box.
#[derive(Debug, Clone)]
pub struct Voxels {
    low: [f64; 3],
    size: [f64; 3],
    shape: [usize; 3],
    margin: f64,
    /// Whether only what lies in the region (widened by the margin) is listed
    /// ([`Voxels::within`]); else the first and last cells hold everything beyond.
    bounded: bool,
}

/// A convex polygon of at most 9 points (a triangle clipped by up to four planes).
#[derive(Clone, Copy)]
struct Clipped {
    points: [[f64; 3]; 9],
    len: usize,
}

impl Voxels {
    /// A grid over `region` with cells of about `side` (at least one cell and at most 2²⁰ along
    /// each axis; a region flat along an axis has one cell across it).
    ///
    /// ```
    /// use kepler::{geometry::{Aabb, Point3}, grid::Voxels};
    /// let g = Voxels::new(Aabb::new(Point3::origin(), Point3::new(2.0, 1.0, 0.0)), 0.5);
    /// assert_eq!(g.shape(), [4, 2, 1]);
    /// ```
    pub fn new(region: Aabb, side: f64) -> Voxels {
        let size = region.size();
        let shape = [0, 1, 2].map(|k| {
            if side > 0.0 && size[k] > 0.0 {
                ((size[k] / side).ceil() as usize).clamp(1, MAX_CELLS)
            } else {
                1
            }
        });
        let largest = (0..3).fold(0.0f64, |m, k| {
            m.max(region.min[k].abs()).max(region.max[k].abs())
        });
        Voxels {
            low: [0, 1, 2].map(|k| region.min[k]),
            size,
            shape,
            margin: MARGIN * largest,
            bounded: false,
        }
    }

    /// [`Voxels::new`], except that [`Voxels::triangle_cells`] lists only the cells that the
    /// part of a triangle inside the region (widened by the margin) meets: a grid over one
    /// crowded cell of a larger grid, which need not list what lies in other cells.
    ///
    /// ```
    /// use kepler::{geometry::{Aabb, Point3}, grid::Voxels};
    /// let region = Aabb::new(Point3::origin(), Point3::new(2.0, 2.0, 2.0));
    /// let (within, whole) = (Voxels::within(region, 1.0), Voxels::new(region, 1.0));
    /// let (mut a, mut b) = (Vec::new(), Vec::new());
    /// // A triangle beyond the region: the unbounded grid puts it in its corner cell.
    /// let far = [Point3::new(5.0, 5.0, 5.0), Point3::new(6.0, 5.0, 5.0), Point3::new(5.0, 6.0, 5.0)];
    /// within.triangle_cells(&far, &mut a);
    /// whole.triangle_cells(&far, &mut b);
    /// assert_eq!((a, b), (vec![], vec![7]));
    /// // One reaching in from beyond x = 2: only its part inside is listed.
    /// let (mut a, mut b) = (Vec::new(), Vec::new());
    /// let across = [Point3::new(1.5, 0.5, 0.5), Point3::new(9.0, 0.5, 0.5), Point3::new(9.0, 2.9, 0.5)];
    /// within.triangle_cells(&across, &mut a);
    /// whole.triangle_cells(&across, &mut b);
    /// assert_eq!((a, b), (vec![1], vec![1, 3]));
    /// ```
    pub fn within(region: Aabb, side: f64) -> Voxels {
        Voxels {
            bounded: true,
            ..Voxels::new(region, side)
        }
    }

    /// The number of cells along each axis.
    ///
    /// ```
    /// use kepler::{geometry::{Aabb, Point3}, grid::Voxels};
    /// let g = Voxels::new(Aabb::new(Point3::origin(), Point3::new(1.0, 1.0, 1.0)), 2.0);
    /// assert_eq!(g.shape(), [1, 1, 1]);
    /// ```
    pub fn shape(&self) -> [usize; 3] {
        self.shape
    }

    /// The cell of `p` (points outside the region go to the nearest cell): its number,
    /// `x + nx·(y + ny·z)`.
    ///
    /// ```
    /// use kepler::{geometry::{Aabb, Point3}, grid::Voxels};
    /// let g = Voxels::new(Aabb::new(Point3::origin(), Point3::new(2.0, 2.0, 2.0)), 1.0);
    /// assert_eq!(g.cell_of(&Point3::new(1.5, 0.5, 0.5)), 1);
    /// assert_eq!(g.cell_of(&Point3::new(9.0, 9.0, 9.0)), 7);
    /// ```
    pub fn cell_of(&self, p: &Point3) -> u64 {
        self.number([0, 1, 2].map(|k| self.index(k, p[k])))
    }

    /// Appends to `out` the cells that the closed triangle `t` meets (and maybe a few that it
    /// nearly meets), each once.
    ///
    /// ```
    /// use kepler::{geometry::{Aabb, Point3}, grid::Voxels};
    /// let g = Voxels::new(Aabb::new(Point3::origin(), Point3::new(3.0, 3.0, 1.0)), 1.0);
    /// // A triangle in the plane z = 0.5 short of the diagonal of the square.
    /// let t = [Point3::new(0.1, 0.1, 0.5), Point3::new(2.7, 0.1, 0.5), Point3::new(0.1, 2.7, 0.5)];
    /// let mut cells = Vec::new();
    /// g.triangle_cells(&t, &mut cells);
    /// cells.sort();
    /// assert_eq!(cells, vec![0, 1, 2, 3, 4, 6]); // not the cells 5, 7, 8 beyond x + y = 2.8
    /// ```
    pub fn triangle_cells(&self, t: &[Point3; 3], out: &mut Vec<u64>) {
        let mut whole = Clipped {
            points: [[0.0; 3]; 9],
            len: 3,
        };
        for (k, p) in t.iter().enumerate() {
            whole.points[k] = [p.x, p.y, p.z];
        }
        let [x0, x1] = self.range(&whole, 0);
        for ix in x0..=x1 {
            let slab = if x0 == x1 && !self.bounded {
                whole
            } else {
                self.slab(&whole, 0, ix)
            };
            if slab.len == 0 {
                continue;
            }
            let [y0, y1] = self.range(&slab, 1);
            for iy in y0..=y1 {
                let row = if y0 == y1 && !self.bounded {
                    slab
                } else {
                    self.slab(&slab, 1, iy)
                };
                if row.len == 0 || (self.bounded && !self.reaches(&row, 2)) {
                    continue;
                }
                let [z0, z1] = self.range(&row, 2);
                for iz in z0..=z1 {
                    out.push(self.number([ix, iy, iz]));
                }
            }
        }
    }

    /// The cells of box `b` (widened by the margin), appended to `out`, when there are at
    /// most `most` of them; otherwise nothing is appended and `false` returned. A triangle
    /// inside the box meets only some of them: listing them all is the cheaper filter when
    /// they are few, and needs only the box.
    ///
    /// ```
    /// use kepler::{geometry::{Aabb, Point3}, grid::Voxels};
    /// let g = Voxels::new(Aabb::new(Point3::origin(), Point3::new(3.0, 3.0, 1.0)), 1.0);
    /// let b = Aabb::new(Point3::new(0.5, 0.5, 0.5), Point3::new(1.5, 0.7, 0.5));
    /// let mut cells = Vec::new();
    /// assert!(g.box_cells(&b, 4, &mut cells));
    /// assert_eq!(cells, vec![0, 1]);
    /// assert!(!g.box_cells(&Aabb::new(Point3::origin(), Point3::new(3.0, 3.0, 1.0)), 4, &mut cells));
    /// assert_eq!(cells.len(), 2);
    /// ```
    pub fn box_cells(&self, b: &Aabb, most: usize, out: &mut Vec<u64>) -> bool {
        let r = [0, 1, 2].map(|k| {
            [
                self.index(k, b.min[k] - self.margin),
                self.index(k, b.max[k] + self.margin),
            ]
        });
        if r.iter().map(|[lo, hi]| hi - lo + 1).product::<usize>() > most {
            return false;
        }
        for iz in r[2][0]..=r[2][1] {
            for iy in r[1][0]..=r[1][1] {
                for ix in r[0][0]..=r[0][1] {
                    out.push(self.number([ix, iy, iz]));
                }
            }
        }
        true
    }

    /// The box of cell `c` (as the division of the region gives it; the cell of a point is
    /// decided by [`Voxels::cell_of`], which may round a point on a side either way).
    ///
    /// ```
    /// use kepler::{geometry::{Aabb, Point3}, grid::Voxels};
    /// let g = Voxels::new(Aabb::new(Point3::origin(), Point3::new(2.0, 2.0, 2.0)), 1.0);
    /// assert_eq!(g.cell_box(7), Aabb::new(Point3::new(1.0, 1.0, 1.0), Point3::new(2.0, 2.0, 2.0)));
    /// ```
    pub fn cell_box(&self, c: u64) -> Aabb {
        let c = c as usize;
        let index = [
            c % self.shape[0],
            c / self.shape[0] % self.shape[1],
            c / self.shape[0] / self.shape[1],
        ];
        Aabb::new(
            Point3::from([0, 1, 2].map(|k| self.wall(k, index[k]))),
            Point3::from([0, 1, 2].map(|k| self.wall(k, index[k] + 1))),
        )
    }

    /// The cell number of the indices `c`.
    fn number(&self, c: [usize; 3]) -> u64 {
        ((c[2] * self.shape[1] + c[1]) * self.shape[0] + c[0]) as u64
    }

    /// The index along axis `k` of the cell holding coordinate `v` (monotone in `v`, clamped).
    fn index(&self, k: usize, v: f64) -> usize {
        if self.size[k] <= 0.0 {
            return 0;
        }
        let c = (v - self.low[k]) / self.size[k] * self.shape[k] as f64;
        if c >= self.shape[k] as f64 {
            self.shape[k] - 1
        } else if c > 0.0 {
            c as usize
        } else {
            0
        }
    }

    /// The indices along axis `k` of the cells that the piece's range, widened by the margin,
    /// reaches.
    fn range(&self, piece: &Clipped, k: usize) -> [usize; 2] {
        let (lo, hi) = piece.points[..piece.len]
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), p| {
                (lo.min(p[k]), hi.max(p[k]))
            });
        [
            self.index(k, lo - self.margin),
            self.index(k, hi + self.margin),
        ]
    }

    /// The coordinate along axis `k` where cell `i` starts (and cell `i − 1` ends), as the
    /// division of the region gives it.
    fn wall(&self, k: usize, i: usize) -> f64 {
        self.low[k] + self.size[k] / self.shape[k] as f64 * i as f64
    }

    /// Whether the piece's range along axis `k` reaches the region's, widened by the margin.
    fn reaches(&self, piece: &Clipped, k: usize) -> bool {
        let points = &piece.points[..piece.len];
        points.iter().any(|p| p[k] >= self.low[k] - self.margin)
            && points
                .iter()
                .any(|p| p[k] <= self.low[k] + self.size[k] + self.margin)
    }

    /// The part of `piece` in the slab of cells `i` across axis `k`, widened by the margin
    /// (unbounded beyond the first and last cells, which hold everything outside the region,
    /// unless the grid is bounded).
    fn slab(&self, piece: &Clipped, k: usize, i: usize) -> Clipped {
        let mut out = *piece;
        if i > 0 || self.bounded {
            let lo = self.wall(k, i) - self.margin;
            out = clip(&out, k, lo, true);
        }
        if i + 1 < self.shape[k] || self.bounded {
            let hi = self.wall(k, i + 1) + self.margin;
            out = clip(&out, k, hi, false);
        }
        out
    }
}

/// The part of `piece` where coordinate `k` is at least `bound` (`keep_above`) or at most it.
fn clip(piece: &Clipped, k: usize, bound: f64, keep_above: bool) -> Clipped {
    let inside = |p: &[f64; 3]| {
        if keep_above {
            p[k] >= bound
        } else {
            p[k] <= bound
        }
    };
    let mut out = Clipped {
        points: [[0.0; 3]; 9],
        len: 0,
    };
    let n = piece.len;
    for i in 0..n {
        let (a, b) = (&piece.points[i], &piece.points[(i + 1) % n]);
        let (ia, ib) = (inside(a), inside(b));
        if ia && out.len < 9 {
            out.points[out.len] = *a;
            out.len += 1;
        }
        if ia != ib && out.len < 9 {
            let t = (bound - a[k]) / (b[k] - a[k]);
            let mut p = [0, 1, 2].map(|j| a[j] + t * (b[j] - a[j]));
            p[k] = bound;
            out.points[out.len] = p;
            out.len += 1;
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::random::SplitMix64;

    /// Whether the closed triangle meets the closed box, by brute force: a fine sampling of the
    /// triangle (barycentric lattice), for the test only.
    fn sampled_cells(g: &Voxels, t: &[Point3; 3], n: usize) -> Vec<u64> {
        let mut cells = Vec::new();
        for i in 0..=n {
            for j in 0..=n - i {
                let (a, b) = (i as f64 / n as f64, j as f64 / n as f64);
                let p = t[0] + (t[1] - t[0]) * a + (t[2] - t[0]) * b;
                cells.push(g.cell_of(&p));
            }
        }
        cells.sort_unstable();
        cells.dedup();
        cells
    }

    #[test]
    fn a_bounded_grid_lists_the_cells_of_the_part_inside() {
        let mut rng = SplitMix64(3u64);
        let mut next = || rng.unit();
        let region = Aabb::new(Point3::new(0.0, 0.0, 0.0), Point3::new(1.0, 1.0, 1.0));
        for side in [0.25, 0.3, 1.0] {
            let (within, whole) = (Voxels::within(region, side), Voxels::new(region, side));
            for _ in 0..300 {
                // Triangles from well outside the region to well inside it.
                let mut p =
                    || Point3::new(4.0 * next() - 1.5, 4.0 * next() - 1.5, 4.0 * next() - 1.5);
                let t = [p(), p(), p()];
                let (mut listed, mut all) = (Vec::new(), Vec::new());
                within.triangle_cells(&t, &mut listed);
                whole.triangle_cells(&t, &mut all);
                listed.sort_unstable();
                all.sort_unstable();
                assert!(listed.iter().all(|c| all.binary_search(c).is_ok()), "{t:?}");
                // Every sample of the triangle inside the region lands in a listed cell.
                for i in 0..=60 {
                    for j in 0..=60 - i {
                        let (a, b) = (i as f64 / 60.0, j as f64 / 60.0);
                        let q = t[0] + (t[1] - t[0]) * a + (t[2] - t[0]) * b;
                        if (0..3).all(|k| (0.0..=1.0).contains(&q[k])) {
                            let c = within.cell_of(&q);
                            assert!(listed.binary_search(&c).is_ok(), "{q:?} of {t:?}");
                        }
                    }
                }
            }
        }
    }

    #[test]
    fn every_cell_a_sample_lands_in_is_listed() {
        let mut rng = SplitMix64(7u64);
        let mut next = || rng.unit();
        let region = Aabb::new(Point3::new(-1.0, -2.0, -3.0), Point3::new(5.0, 4.0, 3.0));
        for side in [0.3, 0.7, 2.0] {
            let g = Voxels::new(region, side);
            for _ in 0..300 {
                let mut p = || {
                    Point3::new(
                        -1.0 + 6.0 * next(),
                        -2.0 + 6.0 * next(),
                        -3.0 + 6.0 * next(),
                    )
                };
                let t = [p(), p(), p()];
                let mut listed = Vec::new();
                g.triangle_cells(&t, &mut listed);
                let n = listed.len();
                listed.sort_unstable();
                listed.dedup();
                assert_eq!(listed.len(), n, "a cell listed twice");
                for c in sampled_cells(&g, &t, 40) {
                    assert!(listed.binary_search(&c).is_ok(), "cell {c} of {t:?} missed");
                }
                // The box's cells, when few enough to be listed, hold those the triangle meets.
                let mut boxed = Vec::new();
                if g.box_cells(&Aabb::from_points(&t), 64, &mut boxed) {
                    boxed.sort_unstable();
                    assert!(listed.iter().all(|c| boxed.binary_search(c).is_ok()));
                }
            }
        }
    }

    #[test]
    fn points_on_cell_faces_and_corners_are_listed() {
        // A triangle lying exactly in the plane between two slabs, and one touching a corner.
        let g = Voxels::new(Aabb::new(Point3::origin(), Point3::new(2.0, 2.0, 2.0)), 1.0);
        let on_plane = [
            Point3::new(1.0, 0.2, 0.2),
            Point3::new(1.0, 0.8, 0.2),
            Point3::new(1.0, 0.2, 0.8),
        ];
        let mut cells = Vec::new();
        g.triangle_cells(&on_plane, &mut cells);
        cells.sort_unstable();
        assert_eq!(cells, vec![0, 1]);
        let corner = [
            Point3::new(1.0, 1.0, 1.0),
            Point3::new(1.5, 1.5, 1.0),
            Point3::new(1.5, 1.0, 1.5),
        ];
        cells.clear();
        g.triangle_cells(&corner, &mut cells);
        // Every cell around the corner point (1, 1, 1): all 8.
        cells.sort_unstable();
        assert_eq!(cells, (0..8).collect::<Vec<u64>>());
    }

    #[test]
    fn a_degenerate_triangle_is_listed_along_its_segment() {
        let g = Voxels::new(Aabb::new(Point3::origin(), Point3::new(4.0, 4.0, 4.0)), 1.0);
        let line = [
            Point3::new(0.5, 0.5, 0.5),
            Point3::new(3.5, 0.5, 0.5),
            Point3::new(2.0, 0.5, 0.5),
        ];
        let mut cells = Vec::new();
        g.triangle_cells(&line, &mut cells);
        cells.sort_unstable();
        assert_eq!(cells, vec![0, 1, 2, 3]);
    }
}
