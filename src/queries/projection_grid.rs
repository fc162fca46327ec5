//! The 2-D projection grid of batch INCLUDE (Franklin 1981, INCLUDE step 3): "If many points
//! are to be tested against a given polyhedron, it can be projected onto a 2-D grid in such a
//! way that each point can be tested in time proportional to the depth complexity of the
//! polyhedron."
//!
//! Each triangle is listed in the cells of a uniform grid over the x-y plane that its
//! projected bounding box covers. A point meets only the triangles of its own cell, and of
//! those only the ones whose box reaches its column, and counts the crossings of its upward
//! vertical ray exactly ([`classify_among`]). Written by hand because it is the paper's own
//! structure; an R-tree ([`TriangleTree`](crate::mesh::TriangleTree)) does the same job more
//! slowly for single queries.
//!
//! Cell indices come from one monotone function of a coordinate ([`Cells`], shared with the
//! segment grid), so a point within a triangle's box (compared exactly) always lands in a cell
//! the triangle is listed in, however the division rounds.

use crate::geometry::Point3;
use crate::grid::Cells;
use crate::mesh::{Containment, Mesh, classify_among, crosses_column};
use rayon::prelude::*;

/// A triangle as the grid stores it: corners and closed bounding box.
#[derive(Debug, Clone, Copy)]
struct Column {
    corners: [Point3; 3],
    min: [f64; 3],
    max: [f64; 3],
}

/// A triangle as a cell lists it: its bounding box rounded outward to `f32` (a compact filter
/// that never rejects a triangle whose exact box reaches the point) and its index.
#[derive(Debug, Clone, Copy)]
struct Candidate {
    min: [f32; 2],
    max: [f32; 3],
    triangle: u32,
}

impl Candidate {
    fn new(c: &Column, triangle: u32) -> Candidate {
        Candidate {
            min: [round_down(c.min[0]), round_down(c.min[1])],
            max: c.max.map(round_up),
            triangle,
        }
    }

    /// Whether the box may reach `p`'s column at or above `p`.
    #[inline]
    fn may_reach(&self, p: &Point3) -> bool {
        f64::from(self.max[2]) >= p.z
            && f64::from(self.min[0]) <= p.x
            && p.x <= f64::from(self.max[0])
            && f64::from(self.min[1]) <= p.y
            && p.y <= f64::from(self.max[1])
    }
}

/// The largest `f32` at most `x` (minus infinity below the `f32` range).
fn round_down(x: f64) -> f32 {
    let f = x as f32;
    if f64::from(f) > x { f.next_down() } else { f }
}

/// The smallest `f32` at least `x` (infinity above the `f32` range).
fn round_up(x: f64) -> f32 {
    let f = x as f32;
    if f64::from(f) < x { f.next_up() } else { f }
}

/// A uniform grid over the x-y projection of a mesh's triangles.
///
/// ```
/// use kepler::{geometry::Point3, mesh::Containment, queries::projection_grid::ProjectionGrid};
/// let grid = ProjectionGrid::new(&kepler::solids::torus(2.0, 0.5, 32, 16).unwrap());
/// assert_eq!(grid.classify(&Point3::new(2.0, 0.0, 0.0)), Containment::Inside);
/// assert_eq!(grid.classify(&Point3::new(0.0, 0.0, 0.0)), Containment::Outside);
/// assert_eq!(grid.classify(&Point3::new(2.5, 0.0, 0.0)), Containment::Boundary);
/// ```
#[derive(Debug, Clone)]
pub struct ProjectionGrid {
    cells: Cells,
    /// Cell `c` lists `items[start[c]..start[c + 1]]`.
    start: Vec<u32>,
    items: Vec<Candidate>,
    columns: Vec<Column>,
    /// Cell `c`'s gaps are `gaps[gap_start[c]..gap_start[c + 1]]`, in increasing z.
    gap_start: Vec<u32>,
    gaps: Vec<Gap>,
}

/// An open z-interval of a cell's column that no listed triangle's box reaches. No triangle
/// meets the part of the column in it (any triangle that did would be listed), so that box is
/// all inside or all outside: below and above every triangle, outside; in between, as one
/// representative point classifies. Most points of a batch fall in a gap and are answered
/// without touching a triangle (the idea of Franklin's later uniform-grid point location).
#[derive(Debug, Clone, Copy)]
struct Gap {
    lo: f64,
    hi: f64,
    inside: bool,
}

impl ProjectionGrid {
    /// Builds the grid of `mesh`'s triangles, about one cell per triangle, shaped like the
    /// mesh's projection.
    ///
    /// ```
    /// let g = kepler::queries::projection_grid::ProjectionGrid::new(&kepler::solids::cube(1.0).unwrap());
    /// assert_eq!(g.triangle_count(), 12);
    /// ```
    pub fn new(mesh: &Mesh) -> ProjectionGrid {
        let columns: Vec<Column> = (0..mesh.triangles().len())
            .into_par_iter()
            .map(|t| {
                let c = mesh.triangle(t);
                let min = |k: usize| c[0][k].min(c[1][k]).min(c[2][k]);
                let max = |k: usize| c[0][k].max(c[1][k]).max(c[2][k]);
                Column {
                    corners: c,
                    min: [min(0), min(1), min(2)],
                    max: [max(0), max(1), max(2)],
                }
            })
            .collect();
        let lo = |k: usize| {
            columns
                .iter()
                .map(|c| c.min[k])
                .fold(f64::INFINITY, f64::min)
        };
        let hi = |k: usize| {
            columns
                .iter()
                .map(|c| c.max[k])
                .fold(f64::NEG_INFINITY, f64::max)
        };
        let (origin, extent) = if columns.is_empty() {
            ([0.0; 2], [0.0; 2])
        } else {
            ([lo(0), lo(1)], [hi(0) - lo(0), hi(1) - lo(1)])
        };
        let cells = Cells::new(origin, extent, grid_shape(columns.len(), extent));
        let mut grid = ProjectionGrid {
            cells,
            start: vec![0; cells.count() + 1],
            items: Vec::new(),
            columns,
            gap_start: Vec::new(),
            gaps: Vec::new(),
        };
        grid.fill();
        let per_cell: Vec<Vec<Gap>> = (0..cells.count())
            .into_par_iter()
            .map(|c| grid.find_gaps(c))
            .collect();
        grid.gap_start = std::iter::once(0)
            .chain(per_cell.iter().scan(0u32, |n, g| {
                *n += g.len() as u32;
                Some(*n)
            }))
            .collect();
        grid.gaps = per_cell.into_iter().flatten().collect();
        grid
    }

    /// The gaps of cell `c`'s column, in increasing z (a middle gap only when its
    /// representative point could be placed in the cell).
    fn find_gaps(&self, c: usize) -> Vec<Gap> {
        let centre = self.centre(c);
        let mut blocks: Vec<(f64, f64, bool)> = self
            .listed(c)
            .iter()
            .map(|t| {
                let column = &self.columns[t.triangle as usize];
                let crosses = centre.is_some_and(|[x, y]| {
                    let within = |k: usize, v: f64| column.min[k] <= v && v <= column.max[k];
                    within(0, x) && within(1, y) && crosses_column(&column.corners, x, y)
                });
                (column.min[2], column.max[2], crosses)
            })
            .collect();
        blocks.sort_unstable_by(|a, b| a.0.total_cmp(&b.0));
        // Sweep up the column through the centre: a gap is inside when the line has crossed
        // an odd number of triangles below it (all of them lie below, in z, the gap).
        let mut gaps = Vec::new();
        let mut top = f64::NEG_INFINITY;
        let mut inside = false;
        for (lo, hi, crosses) in blocks {
            if lo > top && (top == f64::NEG_INFINITY || centre.is_some()) {
                gaps.push(Gap {
                    lo: top,
                    hi: lo,
                    inside,
                });
            }
            top = top.max(hi);
            inside ^= crosses;
        }
        gaps.push(Gap {
            lo: top,
            hi: f64::INFINITY,
            inside: false,
        });
        gaps
    }

    /// The triangles cell `c` lists.
    #[inline]
    fn listed(&self, c: usize) -> &[Candidate] {
        &self.items[self.start[c] as usize..self.start[c + 1] as usize]
    }

    /// A point of the x-y plane that falls in cell `c`, if the rounded centre does.
    fn centre(&self, c: usize) -> Option<[f64; 2]> {
        let nx = self.cells.shape()[0];
        let index = [c % nx, c / nx];
        let xy = [0, 1].map(|k| self.cells.coordinate(k, index[k] as f64 + 0.5));
        (self.cells.index(0, xy[0]) == index[0] && self.cells.index(1, xy[1]) == index[1])
            .then_some(xy)
    }

    /// Lists every triangle in the cells its box covers (counting pass, then filling pass).
    fn fill(&mut self) {
        let ranges: Vec<[[usize; 2]; 2]> = self
            .columns
            .par_iter()
            .map(|c| [0, 1].map(|k| [self.cells.index(k, c.min[k]), self.cells.index(k, c.max[k])]))
            .collect();
        let nx = self.cells.shape()[0];
        for [[x0, x1], [y0, y1]] in &ranges {
            for y in *y0..=*y1 {
                for x in *x0..=*x1 {
                    self.start[y * nx + x + 1] += 1;
                }
            }
        }
        for c in 1..self.start.len() {
            self.start[c] += self.start[c - 1];
        }
        let mut next = self.start.clone();
        let empty = Candidate {
            min: [0.0; 2],
            max: [0.0; 3],
            triangle: 0,
        };
        self.items = vec![empty; *self.start.last().unwrap_or(&0) as usize];
        for (t, [[x0, x1], [y0, y1]]) in ranges.into_iter().enumerate() {
            let candidate = Candidate::new(&self.columns[t], t as u32);
            for y in y0..=y1 {
                for x in x0..=x1 {
                    let slot = &mut next[y * nx + x];
                    self.items[*slot as usize] = candidate;
                    *slot += 1;
                }
            }
        }
    }

    /// Classifies `p` against the mesh exactly (the mesh must be closed): the upward ray's
    /// crossings with the triangles of `p`'s cell that reach its column.
    ///
    /// ```
    /// use kepler::{geometry::Point3, mesh::Containment, queries::projection_grid::ProjectionGrid};
    /// let g = ProjectionGrid::new(&kepler::solids::cube(2.0).unwrap());
    /// assert_eq!(g.classify(&Point3::new(1.0, 1.0, 1.0)), Containment::Boundary);
    /// assert_eq!(g.classify(&Point3::new(1.0, 1.0, -3.0)), Containment::Outside);
    /// ```
    pub fn classify(&self, p: &Point3) -> Containment {
        let cell = self.cells.cell_of(p.x, p.y);
        let gaps = &self.gaps[self.gap_start[cell] as usize..self.gap_start[cell + 1] as usize];
        for gap in gaps {
            if p.z <= gap.lo {
                break;
            }
            if p.z < gap.hi {
                return if gap.inside {
                    Containment::Inside
                } else {
                    Containment::Outside
                };
            }
        }
        let reaching = self
            .listed(cell)
            .iter()
            .filter(|c| c.may_reach(p))
            .map(|c| self.columns[c.triangle as usize].corners);
        classify_among(reaching, p)
    }

    /// The number of triangles in the grid.
    ///
    /// ```
    /// let g = kepler::queries::projection_grid::ProjectionGrid::new(&kepler::solids::tetrahedron(1.0).unwrap());
    /// assert_eq!(g.triangle_count(), 4);
    /// ```
    pub fn triangle_count(&self) -> usize {
        self.columns.len()
    }

    /// The grid's shape, cells along x and y.
    ///
    /// ```
    /// let g = kepler::queries::projection_grid::ProjectionGrid::new(&kepler::solids::cube(1.0).unwrap());
    /// let [nx, ny] = g.shape();
    /// assert!(nx * ny >= 1 && nx * ny <= 12);
    /// ```
    pub fn shape(&self) -> [usize; 2] {
        self.cells.shape()
    }

    /// The average number of triangles listed per cell.
    ///
    /// ```
    /// let g = kepler::queries::projection_grid::ProjectionGrid::new(&kepler::solids::cube(1.0).unwrap());
    /// assert!(g.mean_cell_load() >= 1.0);
    /// ```
    pub fn mean_cell_load(&self) -> f64 {
        self.items.len() as f64 / self.cells.count() as f64
    }
}

/// Cells per triangle: finer grids list fewer triangles per cell but each triangle in more
/// cells; measured on a 70,000-triangle torus, 2 is about best.
const CELLS_PER_TRIANGLE: f64 = 1.0;

/// About `n` cells per triangle (at least one cell), split between the axes in proportion to the extents.
fn grid_shape(n: usize, extent: [f64; 2]) -> [usize; 2] {
    const MAX_CELLS: f64 = (1u64 << 24) as f64;
    let n = (CELLS_PER_TRIANGLE * n as f64).clamp(1.0, MAX_CELLS);
    match (extent[0] > 0.0, extent[1] > 0.0) {
        (true, true) => {
            let aspect = extent[0] / extent[1];
            let nx = (n * aspect).sqrt().clamp(1.0, n);
            let ny = (n / nx).clamp(1.0, n);
            [nx as usize, ny as usize]
        }
        (true, false) => [n as usize, 1],
        (false, true) => [1, n as usize],
        (false, false) => [1, 1],
    }
}
