//! The frame of a uniform grid of cells over a rectangle of the plane.

/// A uniform grid of `shape[0] × shape[1]` cells over a rectangle. A coordinate's cell index
/// is one monotone function of it, clamped to the grid, so a point inside a box always falls
/// in a cell of the box's index range, however the arithmetic rounds; the structures built on
/// it list each item in every cell its range covers.
///
/// ```
/// use kepler::grid::Cells;
/// let cells = Cells::new([0.0, 0.0], [10.0, 5.0], [10, 5]);
/// assert_eq!(cells.index(0, 3.5), 3);
/// assert_eq!(cells.index(0, -7.0), 0); // clamped
/// assert_eq!(cells.index(1, 99.0), 4);
/// assert_eq!(cells.cell_of(3.5, 1.2), 13); // row-major
/// assert_eq!(cells.coordinate(0, 2.5), 2.5);
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Cells {
    origin: [f64; 2],
    inverse_cell: [f64; 2],
    shape: [usize; 2],
}

impl Cells {
    /// The grid of `shape` cells (at least one along each axis) over the rectangle from
    /// `origin` spanning `extent`; an axis of zero extent has a single cell.
    ///
    /// ```
    /// let flat = kepler::grid::Cells::new([1.0, 2.0], [0.0, 4.0], [3, 4]);
    /// assert_eq!(flat.shape(), [1, 4]);
    /// ```
    pub fn new(origin: [f64; 2], extent: [f64; 2], shape: [usize; 2]) -> Cells {
        let shape = [0, 1].map(|k| if extent[k] > 0.0 { shape[k].max(1) } else { 1 });
        let inverse_cell = [0, 1].map(|k| {
            if extent[k] > 0.0 {
                shape[k] as f64 / extent[k]
            } else {
                0.0
            }
        });
        Cells {
            origin,
            inverse_cell,
            shape,
        }
    }

    /// Cells along x and y.
    ///
    /// ```
    /// assert_eq!(kepler::grid::Cells::new([0.0; 2], [1.0; 2], [4, 2]).shape(), [4, 2]);
    /// ```
    pub fn shape(&self) -> [usize; 2] {
        self.shape
    }

    /// The number of cells.
    ///
    /// ```
    /// assert_eq!(kepler::grid::Cells::new([0.0; 2], [1.0; 2], [4, 2]).count(), 8);
    /// ```
    pub fn count(&self) -> usize {
        self.shape[0] * self.shape[1]
    }

    /// The cell index along axis `k` (0 for x, 1 for y) of coordinate `v`: monotone in `v`,
    /// clamped to the grid.
    ///
    /// ```
    /// let cells = kepler::grid::Cells::new([0.0; 2], [1.0; 2], [4, 4]);
    /// assert_eq!((cells.index(0, 0.25), cells.index(0, 1.0)), (1, 3));
    /// ```
    #[inline]
    pub fn index(&self, k: usize, v: f64) -> usize {
        let c = (v - self.origin[k]) * self.inverse_cell[k];
        if c >= self.shape[k] as f64 {
            self.shape[k] - 1
        } else if c > 0.0 {
            c as usize
        } else {
            0
        }
    }

    /// The row-major index of the cell of `(x, y)`.
    ///
    /// ```
    /// let cells = kepler::grid::Cells::new([0.0; 2], [1.0; 2], [4, 4]);
    /// assert_eq!(cells.cell_of(0.9, 0.3), 7);
    /// ```
    #[inline]
    pub fn cell_of(&self, x: f64, y: f64) -> usize {
        self.index(1, y) * self.shape[0] + self.index(0, x)
    }

    /// The coordinate along axis `k` at `t` cells from the origin (rounded; cell boundaries
    /// at whole `t`, centres at halves), or the origin on an axis of zero extent.
    ///
    /// ```
    /// let cells = kepler::grid::Cells::new([1.0, 0.0], [2.0, 1.0], [4, 1]);
    /// assert_eq!(cells.coordinate(0, 1.0), 1.5);
    /// ```
    #[inline]
    pub fn coordinate(&self, k: usize, t: f64) -> f64 {
        if self.inverse_cell[k] > 0.0 {
            self.origin[k] + t / self.inverse_cell[k]
        } else {
            self.origin[k]
        }
    }

    /// The rectangle of cell `c` (row-major), as its lowest and highest corners.
    ///
    /// ```
    /// let cells = kepler::grid::Cells::new([1.0, 0.0], [2.0, 1.0], [4, 2]);
    /// assert_eq!(cells.region(5), [[1.5, 0.5], [2.0, 1.0]]);
    /// ```
    pub fn region(&self, c: usize) -> [[f64; 2]; 2] {
        let [columns, _] = self.shape;
        let (col, row) = ((c % columns) as f64, (c / columns) as f64);
        [
            [self.coordinate(0, col), self.coordinate(1, row)],
            [self.coordinate(0, col + 1.0), self.coordinate(1, row + 1.0)],
        ]
    }

    /// The row-major indices of the cells the box `[low, high]`, grown by `margin` on every
    /// side, covers (by the monotone [`Cells::index`], so a point in the box falls in one of
    /// them however it rounds).
    ///
    /// ```
    /// let cells = kepler::grid::Cells::new([0.0; 2], [4.0; 2], [4, 4]);
    /// let covered: Vec<usize> = cells.covering([0.5, 0.5], [1.5, 0.5], 0.0).collect();
    /// assert_eq!(covered, vec![0, 1]);
    /// ```
    pub fn covering(
        &self,
        low: [f64; 2],
        high: [f64; 2],
        margin: f64,
    ) -> impl Iterator<Item = usize> + '_ {
        let range =
            move |k: usize| self.index(k, low[k] - margin)..=self.index(k, high[k] + margin);
        let width = self.shape[0];
        range(1).flat_map(move |row| range(0).map(move |col| row * width + col))
    }

    /// The row-major indices of the cells that the closed triangle `t`, grown by `margin`,
    /// meets (and maybe a few that it nearly meets), appended to `out`: column by column, the
    /// rows of the part of the triangle in the column (the column widened by the margin), so
    /// a sliver is listed along itself and not in every cell of its box. The column bounds
    /// round by far less than any margin of 2⁻⁴⁰ of the grid's coordinates.
    ///
    /// ```
    /// let cells = kepler::grid::Cells::new([0.0; 2], [4.0; 2], [4, 4]);
    /// let mut out = Vec::new();
    /// // The lower left half of the square, just short of the diagonal.
    /// cells.covering_triangle([[0.0, 0.0], [3.9, 0.0], [0.0, 3.9]], 1e-9, &mut out);
    /// out.sort();
    /// assert_eq!(out, vec![0, 1, 2, 3, 4, 5, 6, 8, 9, 12]);
    /// ```
    pub fn covering_triangle(&self, t: [[f64; 2]; 3], margin: f64, out: &mut Vec<usize>) {
        let (lo, hi) = t
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), p| {
                (lo.min(p[0]), hi.max(p[0]))
            });
        let (c0, c1) = (self.index(0, lo - margin), self.index(0, hi + margin));
        for col in c0..=c1 {
            let left = (col > c0).then(|| self.coordinate(0, col as f64) - margin);
            let right = (col < c1).then(|| self.coordinate(0, (col + 1) as f64) + margin);
            let Some((ylo, yhi)) = column_range(&t, left, right) else {
                continue;
            };
            let (r0, r1) = (self.index(1, ylo - margin), self.index(1, yhi + margin));
            out.extend((r0..=r1).map(|row| row * self.shape[0] + col));
        }
    }
}

/// The range of `y` over the part of triangle `t` with `x` between `left` and `right` (either
/// unbounded when `None`), or `None` when that part is empty: the `y` of the vertices inside
/// and of the points where the sides cross the two lines.
fn column_range(t: &[[f64; 2]; 3], left: Option<f64>, right: Option<f64>) -> Option<(f64, f64)> {
    let inside = |x: f64| left.is_none_or(|l| x >= l) && right.is_none_or(|r| x <= r);
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    let mut take = |y: f64| {
        lo = lo.min(y);
        hi = hi.max(y);
    };
    for i in 0..3 {
        let (a, b) = (t[i], t[(i + 1) % 3]);
        if inside(a[0]) {
            take(a[1]);
        }
        for x in [left, right].into_iter().flatten() {
            if (a[0] < x) != (b[0] < x) {
                let s = (x - a[0]) / (b[0] - a[0]);
                take(a[1] + s * (b[1] - a[1]));
            }
        }
    }
    (lo <= hi).then_some((lo, hi))
}

/// The lists of a grid's cells in one array: cell `c` lists `items[start[c]..start[c + 1]]`.
///
/// ```
/// let lists = kepler::grid::CellLists::new(3, vec![(2, 7), (0, 5), (2, 1)]);
/// assert_eq!(lists.get(0), &[5]);
/// assert!(lists.get(1).is_empty());
/// assert_eq!(lists.get(2), &[1, 7]);
/// assert_eq!(lists.entries(), 3);
/// ```
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct CellLists {
    start: Vec<u32>,
    items: Vec<u32>,
}

impl CellLists {
    /// The lists of `cells` cells from `(cell, item)` pairs in any order; each cell lists its
    /// items in increasing order.
    ///
    /// ```
    /// let lists = kepler::grid::CellLists::new(1, Vec::new());
    /// assert!(lists.get(0).is_empty());
    /// ```
    pub fn new(cells: usize, pairs: Vec<(u32, u32)>) -> CellLists {
        // Placed by cell in one counting pass; a cell's items then come in the order of the
        // pairs, usually increasing already (each is sorted only where it is not).
        let (start, mut items) = crate::mesh::by_bucket(cells, &pairs, |p| p.0 as usize, |p| p.1);
        drop(pairs);
        for c in 0..cells {
            let list = &mut items[start[c]..start[c + 1]];
            if !list.is_sorted() {
                list.sort_unstable();
            }
        }
        CellLists {
            start: start.into_iter().map(|s| s as u32).collect(),
            items,
        }
    }

    /// The items of cell `c`.
    ///
    /// ```
    /// let lists = kepler::grid::CellLists::new(2, vec![(1, 4)]);
    /// assert_eq!(lists.get(1), &[4]);
    /// ```
    #[inline]
    pub fn get(&self, c: usize) -> &[u32] {
        &self.items[self.start[c] as usize..self.start[c + 1] as usize]
    }

    /// The number of (cell, item) entries.
    ///
    /// ```
    /// assert_eq!(kepler::grid::CellLists::new(4, vec![(0, 0), (3, 0)]).entries(), 2);
    /// ```
    pub fn entries(&self) -> usize {
        self.items.len()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::random::SplitMix64;

    #[test]
    fn cell_lists_hold_each_cells_items_in_increasing_order() {
        let mut seed = 19u64;
        let mut next = |n: u64| {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            (seed % n) as u32
        };
        for (cells, n) in [(1, 0), (1, 5), (7, 100), (300, 5000)] {
            let pairs: Vec<(u32, u32)> = (0..n).map(|_| (next(cells), next(1000))).collect();
            let lists = CellLists::new(cells as usize, pairs.clone());
            assert_eq!(lists.entries(), n);
            for c in 0..cells as u32 {
                let mut expected: Vec<u32> =
                    pairs.iter().filter(|p| p.0 == c).map(|p| p.1).collect();
                expected.sort_unstable();
                assert_eq!(lists.get(c as usize), expected.as_slice());
            }
        }
    }

    #[test]
    fn covering_triangle_lists_every_cell_a_point_of_the_triangle_falls_in() {
        let mut rng = SplitMix64(11u64);
        let mut next = || rng.unit();
        for shape in [[1, 1], [7, 3], [40, 40]] {
            let cells = Cells::new([-1.0, -2.0], [6.0, 5.0], shape);
            for k in 0..500 {
                let mut p = || [-1.5 + 7.0 * next(), -2.5 + 6.0 * next()];
                let mut t = [p(), p(), p()];
                if k % 4 == 0 {
                    // A sliver, or a segment.
                    t[2] = [
                        t[0][0] + (t[1][0] - t[0][0]) * 0.3,
                        t[0][1] + (t[1][1] - t[0][1]) * 0.3 + if k % 8 == 0 { 0.0 } else { 1e-9 },
                    ];
                }
                let mut listed = Vec::new();
                cells.covering_triangle(t, 1e-12, &mut listed);
                let n = listed.len();
                listed.sort_unstable();
                listed.dedup();
                assert_eq!(listed.len(), n, "a cell listed twice");
                let (mut boxed, _) = (
                    cells
                        .covering(
                            [0, 1].map(|k| t.iter().map(|p| p[k]).fold(f64::INFINITY, f64::min)),
                            [0, 1]
                                .map(|k| t.iter().map(|p| p[k]).fold(f64::NEG_INFINITY, f64::max)),
                            1e-12,
                        )
                        .collect::<Vec<_>>(),
                    (),
                );
                boxed.sort_unstable();
                assert!(
                    listed.iter().all(|c| boxed.binary_search(c).is_ok()),
                    "outside the box"
                );
                let steps = 60;
                for i in 0..=steps {
                    for j in 0..=steps - i {
                        let (a, b) = (i as f64 / steps as f64, j as f64 / steps as f64);
                        let x = t[0][0] + (t[1][0] - t[0][0]) * a + (t[2][0] - t[0][0]) * b;
                        let y = t[0][1] + (t[1][1] - t[0][1]) * a + (t[2][1] - t[0][1]) * b;
                        let c = cells.cell_of(x, y);
                        assert!(listed.binary_search(&c).is_ok(), "cell {c} of {t:?} missed");
                    }
                }
            }
        }
    }
}
