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
//! Cell indices come from one monotone function of a coordinate, so a point within a
//! triangle's box (compared exactly) always lands in a cell the triangle is listed in, however
//! the division rounds.

use crate::geometry::Point3;
use crate::mesh::{Containment, Mesh, classify_among};

/// A triangle as the grid stores it: corners and closed bounding box.
#[derive(Debug, Clone, Copy)]
struct Column {
    corners: [Point3; 3],
    min: [f64; 2],
    max: [f64; 3],
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
    origin: [f64; 2],
    inverse_cell: [f64; 2],
    cells: [usize; 2],
    /// Cell `c` lists `items[start[c]..start[c + 1]]`.
    start: Vec<u32>,
    items: Vec<u32>,
    columns: Vec<Column>,
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
            .map(|t| {
                let c = mesh.triangle(t);
                let min = |k: usize| c[0][k].min(c[1][k]).min(c[2][k]);
                let max = |k: usize| c[0][k].max(c[1][k]).max(c[2][k]);
                Column {
                    corners: c,
                    min: [min(0), min(1)],
                    max: [max(0), max(1), max(2)],
                }
            })
            .collect();
        let lo = |k: usize| columns.iter().map(|c| c.min[k]).fold(f64::INFINITY, f64::min);
        let hi = |k: usize| columns.iter().map(|c| c.max[k]).fold(f64::NEG_INFINITY, f64::max);
        let (origin, extent) = if columns.is_empty() {
            ([0.0; 2], [0.0; 2])
        } else {
            ([lo(0), lo(1)], [hi(0) - lo(0), hi(1) - lo(1)])
        };
        let cells = grid_shape(columns.len(), extent);
        let inverse_cell = [0, 1].map(|k| {
            if extent[k] > 0.0 {
                cells[k] as f64 / extent[k]
            } else {
                0.0
            }
        });
        let mut grid = ProjectionGrid {
            origin,
            inverse_cell,
            cells,
            start: vec![0; cells[0] * cells[1] + 1],
            items: Vec::new(),
            columns,
        };
        grid.fill();
        grid
    }

    /// Lists every triangle in the cells its box covers (counting pass, then filling pass).
    fn fill(&mut self) {
        let ranges: Vec<[[usize; 2]; 2]> = self
            .columns
            .iter()
            .map(|c| [0, 1].map(|k| [self.cell(k, c.min[k]), self.cell(k, c.max[k])]))
            .collect();
        let nx = self.cells[0];
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
        self.items = vec![0; *self.start.last().unwrap_or(&0) as usize];
        for (t, [[x0, x1], [y0, y1]]) in ranges.into_iter().enumerate() {
            for y in y0..=y1 {
                for x in x0..=x1 {
                    let slot = &mut next[y * nx + x];
                    self.items[*slot as usize] = t as u32;
                    *slot += 1;
                }
            }
        }
    }

    /// The cell index along axis `k` of coordinate `v`: a monotone function of `v`, clamped
    /// to the grid.
    #[inline]
    fn cell(&self, k: usize, v: f64) -> usize {
        let c = (v - self.origin[k]) * self.inverse_cell[k];
        if c >= self.cells[k] as f64 {
            self.cells[k] - 1
        } else if c > 0.0 {
            c as usize
        } else {
            0
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
        let cell = self.cell(1, p.y) * self.cells[0] + self.cell(0, p.x);
        let listed = &self.items[self.start[cell] as usize..self.start[cell + 1] as usize];
        let reaching = listed.iter().map(|&t| &self.columns[t as usize]).filter(|c| {
            c.max[2] >= p.z
                && c.min[0] <= p.x
                && p.x <= c.max[0]
                && c.min[1] <= p.y
                && p.y <= c.max[1]
        });
        classify_among(reaching.map(|c| c.corners), p)
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
        self.cells
    }

    /// The average number of triangles listed per cell.
    ///
    /// ```
    /// let g = kepler::queries::projection_grid::ProjectionGrid::new(&kepler::solids::cube(1.0).unwrap());
    /// assert!(g.mean_cell_load() >= 1.0);
    /// ```
    pub fn mean_cell_load(&self) -> f64 {
        self.items.len() as f64 / (self.cells[0] * self.cells[1]) as f64
    }
}

/// About `n` cells (at least one), split between the axes in proportion to the extents.
fn grid_shape(n: usize, extent: [f64; 2]) -> [usize; 2] {
    const MAX_CELLS: f64 = (1u64 << 24) as f64;
    let n = (n as f64).clamp(1.0, MAX_CELLS);
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
