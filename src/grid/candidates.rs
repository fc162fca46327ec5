//! The candidate pairs of a [`SegmentGrid`] for a caller that needs only the pairs with a
//! *key* segment (stage 3 of the hidden-line pass: pairs with a contour), and splits crowded
//! cells.
//!
//! Two things make a uniform grid quadratic, and both are common in drawings:
//!
//! - **Many segments through one point** (the edges of a cone round its apex, seen head-on):
//!   every cell round the point lists all of them, however small the cells. Only pairs with a
//!   key are enumerated: a non-key item sweeps the cell's key items only, so a crowd with no
//!   key in it (the apex of a cone: its edges are no contours) costs one pass over the cell.
//! - **Cells too coarse for part of the picture** (the rim of the cone, ten thousand short
//!   contours in the few cells its long edges set the size of): a cell whose key pairs
//!   outnumber its items [`CROWDED`] times is split into [`SPLIT`] × [`SPLIT`] smaller cells,
//!   its items walked into them again as the grid walks them, while that lessens the pairs to
//!   test (not where the crowd is lines through one point: they stay together in every split),
//!   at most [`SPLITS`] times over and never into cells a few thousand margins across.
//!
//! A pair whose exact segments meet is listed together in the cell of their meeting point at
//! every depth (the walks are widened by the grid's margin, and a border cell of a split takes
//! what lies beyond it), so splitting never loses a pair; a pair listed in several cells is
//! reported once.
//!
//! Cost: a pass over each cell's items, plus, per key item, the items whose x-ranges meet its
//! own in its (split) cells; each split lists its items in a few smaller cells.

use super::{Cells, Item, SegmentGrid, unpacked, walk};
use geo::{Line, coord};
use rayon::prelude::*;

/// A cell is crowded when its key pairs are more than this many per item.
const CROWDED: usize = 8;

/// The fewest items of a crowded cell.
const CROWD: usize = 24;

/// A crowded cell is split into this many cells along each axis.
const SPLIT: usize = 4;

/// A cell is split at most this many times over (into cells 4⁻⁸ as wide).
const SPLITS: usize = 8;

/// A cell narrower than this many margins is not split: its walks would list each item in
/// most of the smaller cells.
const NARROWEST: f64 = 4096.0;

impl SegmentGrid {
    /// Every pair `(i, j)`, `i < j`, with `key(i)` or `key(j)`, listed together in some cell
    /// (crowded cells split, see the module documentation), whose bounding boxes, grown by the
    /// grid's margin (2⁻⁴⁶ of the largest coordinate), meet, and for which `keep(i, j)` holds;
    /// each once, in increasing order. For callers whose segments stand for exact ones within
    /// a few units in the last place (pictures of 3-D edges, say): the grid then still lists
    /// every pair with a key whose exact segments meet, and `keep` decides exactly.
    ///
    /// ```
    /// use geo::{Line, coord};
    /// use kepler::grid::SegmentGrid;
    /// let s = [
    ///     Line::new(coord! { x: 0.0, y: 0.0 }, coord! { x: 1.0, y: 1.0 }),
    ///     Line::new(coord! { x: 0.0, y: 1.0 }, coord! { x: 1.0, y: 0.0 }),
    ///     Line::new(coord! { x: 0.0, y: 2.0 }, coord! { x: 1.0, y: 2.0 }),
    /// ];
    /// let grid = SegmentGrid::new(&s);
    /// assert_eq!(grid.candidates(|_| true, |_, _| true), vec![(0, 1)]);
    /// assert_eq!(grid.candidates(|i| i == 1, |_, _| true), vec![(0, 1)]);
    /// assert!(grid.candidates(|i| i == 2, |_, _| true).is_empty());
    /// assert!(grid.candidates(|_| true, |i, _| i > 0).is_empty());
    /// ```
    pub fn candidates<K, F>(&self, key: K, keep: F) -> Vec<(usize, usize)>
    where
        K: Fn(usize) -> bool + Sync,
        F: Fn(usize, usize) -> bool + Sync,
    {
        let keys: Vec<bool> = (0..self.segments).into_par_iter().map(&key).collect();
        let sweep = Sweep {
            keys: &keys,
            keep: &keep,
            margin: self.margin,
        };
        let pairs: Vec<u64> = (0..self.cells.count())
            .into_par_iter()
            .fold(
                || (Vec::new(), Vec::new()),
                |(mut out, mut keys), c| {
                    // One buffer of key positions per thread, not one per cell.
                    let here = &self.items[self.start[c] as usize..self.start[c + 1] as usize];
                    sweep.cell(here, self.cells.region(c), 0, (&mut out, &mut keys));
                    (out, keys)
                },
            )
            .map(|(out, _)| out)
            .reduce(Vec::new, |mut x, mut y| {
                x.append(&mut y);
                x
            });
        unpacked(pairs)
    }
}

/// What the pairs of a cell are found with: which segments are keys, the caller's test, and
/// the grid's margin.
struct Sweep<'a, F> {
    keys: &'a [bool],
    keep: &'a F,
    margin: f64,
}

impl<F: Fn(usize, usize) -> bool + Sync> Sweep<'_, F> {
    /// Appends to `out` the key pairs of one cell's items (by increasing left end's x), the
    /// cell spanning `region`, split `depth` times already: from smaller cells when it is
    /// crowded and splitting lessens its pairs.
    fn cell(
        &self,
        here: &[Item],
        region: [[f64; 2]; 2],
        depth: usize,
        (out, keys): (&mut Vec<u64>, &mut Vec<usize>),
    ) {
        let key_items = here.iter().filter(|x| self.is_key(x)).count();
        if key_items == 0 {
            return;
        }
        let load = key_items * here.len();
        let narrow = (0..2).any(|k| region[1][k] - region[0][k] < NARROWEST * self.margin);
        if depth < SPLITS && here.len() >= CROWD && load > CROWDED * here.len() && !narrow {
            let (cells, subcells) = self.split(here, region);
            let loads: usize = subcells.iter().map(|(_, sub)| self.load(sub)).sum();
            if loads < load {
                for (c, sub) in &subcells {
                    self.cell(sub, cells.region(*c), depth + 1, (&mut *out, &mut *keys));
                }
                return;
            }
        }
        self.pairs(here, out, keys);
    }

    fn is_key(&self, x: &Item) -> bool {
        self.keys[x.segment as usize]
    }

    /// The pairs a cell's sweep would test, at most.
    fn load(&self, here: &[Item]) -> usize {
        here.iter().filter(|x| self.is_key(x)).count() * here.len()
    }

    /// The cell `region` cut into [`SPLIT`] × [`SPLIT`] cells, and the items `here` listed in
    /// them as the grid lists segments (each cell's items by increasing left end's x).
    fn split(&self, here: &[Item], region: [[f64; 2]; 2]) -> (Cells, Vec<(usize, Vec<Item>)>) {
        let [low, high] = region;
        let cells = Cells::new(low, [high[0] - low[0], high[1] - low[1]], [SPLIT; 2]);
        let mut listed: Vec<(u32, Item)> = Vec::new();
        for x in here {
            let s = Line::new(
                coord! { x: x.a[0], y: x.a[1] },
                coord! { x: x.b[0], y: x.b[1] },
            );
            walk(&cells, self.margin, &s, |c| {
                listed.push((c, Item { cell: c, ..*x }))
            });
        }
        listed.sort_by(|x, y| x.0.cmp(&y.0).then(x.1.a[0].total_cmp(&y.1.a[0])));
        let subcells = listed
            .chunk_by(|x, y| x.0 == y.0)
            .map(|run| (run[0].0 as usize, run.iter().map(|x| x.1).collect()))
            .collect();
        (cells, subcells)
    }

    /// Appends the key pairs of one cell: each item against the later items (a key item) or
    /// the later key items (another) whose left ends lie within its x-range.
    fn pairs(&self, here: &[Item], out: &mut Vec<u64>, keys: &mut Vec<usize>) {
        let m = self.margin;
        keys.clear();
        keys.extend((0..here.len()).filter(|&n| self.is_key(&here[n])));
        for (n, a) in here.iter().enumerate() {
            let right = a.b[0] + m;
            let mut test = |b: &Item| {
                if b.a[0] - m > right {
                    return false;
                }
                let (i, j) = (a.segment.min(b.segment), a.segment.max(b.segment));
                if i != j && a.boxes_meet_within(b, m) && (self.keep)(i as usize, j as usize) {
                    out.push((u64::from(i) << 32) | u64::from(j));
                }
                true
            };
            if self.is_key(a) {
                here[n + 1..].iter().take_while(|b| test(b)).for_each(drop);
            } else {
                let later = keys.partition_point(|&p| p <= n);
                keys[later..]
                    .iter()
                    .take_while(|&&p| test(&here[p]))
                    .for_each(drop);
            }
        }
    }
}
