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

/// A uniform grid over the x-y projection of a mesh's triangles. It lists triangle indices
/// only and reads the corners from the mesh it borrows.
///
/// ```
/// use kepler::{geometry::Point3, mesh::Containment, queries::projection_grid::ProjectionGrid};
/// let torus = kepler::solids::torus(2.0, 0.5, 32, 16).unwrap();
/// let grid = ProjectionGrid::new(&torus);
/// assert_eq!(grid.classify(&Point3::new(2.0, 0.0, 0.0)), Containment::Inside);
/// assert_eq!(grid.classify(&Point3::new(0.0, 0.0, 0.0)), Containment::Outside);
/// assert_eq!(grid.classify(&Point3::new(2.5, 0.0, 0.0)), Containment::Boundary);
/// ```
#[derive(Debug, Clone)]
pub struct ProjectionGrid<'m> {
    mesh: &'m Mesh,
    cells: Cells,
    /// Cell `c` lists the triangles `items[start[c]..start[c + 1]]`, in increasing index.
    start: Vec<usize>,
    items: Vec<u32>,
    /// Each triangle's box, rounded outward to `f32`: a compact filter read before the corners.
    boxes: Vec<FlatBox>,
    /// Cell `c`'s gaps are `gaps[gap_start[c]..gap_start[c + 1]]`, in increasing z.
    gap_start: Vec<usize>,
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

/// A triangle's bounding box rounded outward to `f32` (a filter that never rejects a triangle
/// whose exact box reaches a point), without its low z (a point's upward ray only meets
/// triangles that reach above it).
#[derive(Debug, Clone, Copy)]
struct FlatBox {
    min: [f32; 2],
    max: [f32; 3],
}

impl FlatBox {
    fn new(c: &[Point3; 3]) -> FlatBox {
        let (min, max) = bounds(c);
        FlatBox {
            min: [round_down(min[0]), round_down(min[1])],
            max: max.map(round_up),
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

/// The closed bounding box of a triangle, low and high corners.
#[inline]
fn bounds(c: &[Point3; 3]) -> ([f64; 3], [f64; 3]) {
    let min = |k: usize| c[0][k].min(c[1][k]).min(c[2][k]);
    let max = |k: usize| c[0][k].max(c[1][k]).max(c[2][k]);
    ([min(0), min(1), min(2)], [max(0), max(1), max(2)])
}

/// The extent of the triangles' projection and the sums of their boxes' x and y sizes.
#[derive(Debug, Clone, Copy)]
struct Extent {
    lo: [f64; 2],
    hi: [f64; 2],
    sizes: [f64; 2],
}

impl Extent {
    const EMPTY: Extent = Extent {
        lo: [f64::INFINITY; 2],
        hi: [f64::NEG_INFINITY; 2],
        sizes: [0.0; 2],
    };

    fn with(self, c: &[Point3; 3]) -> Extent {
        let (min, max) = bounds(c);
        Extent {
            lo: [0, 1].map(|k| self.lo[k].min(min[k])),
            hi: [0, 1].map(|k| self.hi[k].max(max[k])),
            sizes: [0, 1].map(|k| self.sizes[k] + (max[k] - min[k])),
        }
    }

    fn join(self, o: Extent) -> Extent {
        Extent {
            lo: [0, 1].map(|k| self.lo[k].min(o.lo[k])),
            hi: [0, 1].map(|k| self.hi[k].max(o.hi[k])),
            sizes: [0, 1].map(|k| self.sizes[k] + o.sizes[k]),
        }
    }
}

impl<'m> ProjectionGrid<'m> {
    /// Builds the grid of `mesh`'s triangles, shaped like the mesh's projection, with cells
    /// about as large as the triangles' projected boxes.
    ///
    /// ```
    /// let cube = kepler::solids::cube(1.0).unwrap();
    /// let g = kepler::queries::projection_grid::ProjectionGrid::new(&cube);
    /// assert_eq!(g.triangle_count(), 12);
    /// ```
    pub fn new(mesh: &'m Mesh) -> ProjectionGrid<'m> {
        let n = mesh.triangles().len();
        let extent = if n >= crate::mesh::PARALLEL_POLYGONS {
            (0..n)
                .into_par_iter()
                .fold(|| Extent::EMPTY, |e, t| e.with(&mesh.triangle(t)))
                .reduce(|| Extent::EMPTY, Extent::join)
        } else {
            (0..n).fold(Extent::EMPTY, |e, t| e.with(&mesh.triangle(t)))
        };
        let cells = if n == 0 {
            Cells::new([0.0; 2], [0.0; 2], [1, 1])
        } else {
            let size = [0, 1].map(|k| extent.hi[k] - extent.lo[k]);
            let mean = extent.sizes.map(|s| s / n as f64);
            Cells::new(extent.lo, size, grid_shape(n, size, mean))
        };
        let (start, items) = fill(mesh, &cells);
        let boxes = if n >= crate::mesh::PARALLEL_POLYGONS {
            (0..n)
                .into_par_iter()
                .map(|t| FlatBox::new(&mesh.triangle(t)))
                .collect()
        } else {
            (0..n).map(|t| FlatBox::new(&mesh.triangle(t))).collect()
        };
        let mut grid = ProjectionGrid {
            mesh,
            cells,
            start,
            items,
            boxes,
            gap_start: Vec::new(),
            gaps: Vec::new(),
        };
        grid.find_all_gaps();
        grid
    }

    /// Finds every cell's gaps, a row of cells at a time in parallel.
    fn find_all_gaps(&mut self) {
        let [nx, ny] = self.cells.shape();
        let rows: Vec<(Vec<usize>, Vec<Gap>)> = (0..ny)
            .into_par_iter()
            .map_init(Vec::new, |blocks, row| {
                let mut counts = Vec::with_capacity(nx);
                let mut gaps = Vec::new();
                for c in row * nx..(row + 1) * nx {
                    let before = gaps.len();
                    self.find_gaps(c, blocks, &mut gaps);
                    counts.push(gaps.len() - before);
                }
                (counts, gaps)
            })
            .collect();
        let total = rows.iter().map(|(_, g)| g.len()).sum();
        let mut gap_start = Vec::with_capacity(self.cells.count() + 1);
        let mut gaps = Vec::with_capacity(total);
        gap_start.push(0);
        for (counts, row) in rows {
            for k in counts {
                gap_start.push(gap_start[gap_start.len() - 1] + k);
            }
            gaps.extend(row);
        }
        self.gap_start = gap_start;
        self.gaps = gaps;
    }

    /// Appends the gaps of cell `c`'s column to `gaps`, in increasing z (a middle gap only
    /// when its representative point could be placed in the cell); `blocks` is scratch space.
    fn find_gaps(&self, c: usize, blocks: &mut Vec<(f64, f64, bool)>, gaps: &mut Vec<Gap>) {
        let centre = self.centre(c);
        blocks.clear();
        blocks.extend(self.listed(c).iter().map(|&t| {
            let corners = self.mesh.triangle(t as usize);
            let (min, max) = bounds(&corners);
            let crosses = centre.is_some_and(|[x, y]| {
                let within = |k: usize, v: f64| min[k] <= v && v <= max[k];
                within(0, x) && within(1, y) && crosses_column(&corners, x, y)
            });
            (min[2], max[2], crosses)
        }));
        blocks.sort_unstable_by(|a, b| a.0.total_cmp(&b.0));
        // Sweep up the column through the centre: a gap is inside when the line has crossed
        // an odd number of triangles below it (all of them lie below, in z, the gap).
        let mut top = f64::NEG_INFINITY;
        let mut inside = false;
        for &(lo, hi, crosses) in blocks.iter() {
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
    }

    /// The triangles cell `c` lists.
    #[inline]
    fn listed(&self, c: usize) -> &[u32] {
        &self.items[self.start[c]..self.start[c + 1]]
    }

    /// A point of the x-y plane that falls in cell `c`, if the rounded centre does.
    fn centre(&self, c: usize) -> Option<[f64; 2]> {
        let nx = self.cells.shape()[0];
        let index = [c % nx, c / nx];
        let xy = [0, 1].map(|k| self.cells.coordinate(k, index[k] as f64 + 0.5));
        (self.cells.index(0, xy[0]) == index[0] && self.cells.index(1, xy[1]) == index[1])
            .then_some(xy)
    }

    /// Classifies `p` against the mesh exactly (the mesh must be closed): the upward ray's
    /// crossings with the triangles of `p`'s cell that reach its column.
    ///
    /// ```
    /// use kepler::{geometry::Point3, mesh::Containment, queries::projection_grid::ProjectionGrid};
    /// let cube = kepler::solids::cube(2.0).unwrap();
    /// let g = ProjectionGrid::new(&cube);
    /// assert_eq!(g.classify(&Point3::new(1.0, 1.0, 1.0)), Containment::Boundary);
    /// assert_eq!(g.classify(&Point3::new(1.0, 1.0, -3.0)), Containment::Outside);
    /// ```
    pub fn classify(&self, p: &Point3) -> Containment {
        let cell = self.cells.cell_of(p.x, p.y);
        for gap in &self.gaps[self.gap_start[cell]..self.gap_start[cell + 1]] {
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
            .filter(|&&t| self.boxes[t as usize].may_reach(p))
            .map(|&t| self.mesh.triangle(t as usize));
        classify_among(reaching, p)
    }

    /// The number of triangles in the grid.
    ///
    /// ```
    /// let tetrahedron = kepler::solids::tetrahedron(1.0).unwrap();
    /// let g = kepler::queries::projection_grid::ProjectionGrid::new(&tetrahedron);
    /// assert_eq!(g.triangle_count(), 4);
    /// ```
    pub fn triangle_count(&self) -> usize {
        self.mesh.triangles().len()
    }

    /// The grid's shape, cells along x and y.
    ///
    /// ```
    /// let cube = kepler::solids::cube(1.0).unwrap();
    /// let [nx, ny] = kepler::queries::projection_grid::ProjectionGrid::new(&cube).shape();
    /// assert!(nx * ny >= 1 && nx * ny <= 12);
    /// ```
    pub fn shape(&self) -> [usize; 2] {
        self.cells.shape()
    }

    /// The average number of triangles listed per cell.
    ///
    /// ```
    /// let cube = kepler::solids::cube(1.0).unwrap();
    /// let g = kepler::queries::projection_grid::ProjectionGrid::new(&cube);
    /// assert!(g.mean_cell_load() >= 1.0);
    /// ```
    pub fn mean_cell_load(&self) -> f64 {
        self.items.len() as f64 / self.cells.count() as f64
    }
}

/// Lists every triangle of `mesh` in the cells of `cells` its box covers: `(start, items)`,
/// cell `c` listing `items[start[c]..start[c + 1]]` in increasing triangle index (a counting
/// pass, then a filling pass).
fn fill(mesh: &Mesh, cells: &Cells) -> (Vec<usize>, Vec<u32>) {
    let nx = cells.shape()[0];
    let range = |t: usize| {
        let (min, max) = bounds(&mesh.triangle(t));
        [0, 1].map(|k| cells.index(k, min[k])..=cells.index(k, max[k]))
    };
    let mut start = vec![0usize; cells.count() + 1];
    for t in 0..mesh.triangles().len() {
        let [xs, ys] = range(t);
        for y in ys {
            for x in xs.clone() {
                start[y * nx + x + 1] += 1;
            }
        }
    }
    for c in 1..start.len() {
        start[c] += start[c - 1];
    }
    let mut next = start.clone();
    let mut items = vec![0u32; start[cells.count()]];
    for t in 0..mesh.triangles().len() {
        let [xs, ys] = range(t);
        for y in ys {
            for x in xs.clone() {
                let slot = &mut next[y * nx + x];
                items[*slot] = t as u32;
                *slot += 1;
            }
        }
    }
    (start, items)
}

/// At most one cell per triangle, and no cell smaller than the triangles' mean projected box:
/// smaller cells would list each triangle in several (on a sphere of a million triangles, ten
/// on average with a cell per triangle, four with cells the size of the mean box, which also
/// answer a torus's points faster).
const CELLS_PER_TRIANGLE: f64 = 1.0;

/// The grid's shape for `n` triangles whose projection spans `extent` and whose boxes' mean
/// sizes are `mean`: at least one cell, split between the axes in proportion to the extents.
fn grid_shape(n: usize, extent: [f64; 2], mean: [f64; 2]) -> [usize; 2] {
    const MAX_CELLS: f64 = (1u64 << 24) as f64;
    let mut n = (CELLS_PER_TRIANGLE * n as f64).clamp(1.0, MAX_CELLS);
    if extent[0] > 0.0 && extent[1] > 0.0 && mean[0] > 0.0 && mean[1] > 0.0 {
        let boxes = extent[0] / mean[0] * (extent[1] / mean[1]);
        n = n.min(boxes).max(1.0);
    }
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

#[cfg(test)]
mod tests {
    //! The grid against the brute-force classification (every triangle tested) on points
    //! chosen to be hard: vertices, edge midpoints, points straight above and below vertices,
    //! points on the grid's cell borders and the cells' representative centres, and random
    //! points, on meshes with vertical faces, far from the origin, and at 1e-90 and 1e90.

    use super::*;
    use crate::mesh::classify_point_brute_force;
    use crate::random::SplitMix64;
    use proptest::prelude::*;

    /// The test meshes: a cube (vertical faces), a torus, a coarse sphere, an octahedron, and
    /// a non-convex union of two boxes touching along a face.
    fn mesh(which: usize) -> Mesh {
        match which {
            0 => crate::solids::cube(2.0),
            1 => crate::solids::torus(2.0, 0.7, 24, 12),
            2 => crate::solids::uv_sphere(1.0, 17, 9),
            3 => crate::solids::octahedron(1.5),
            _ => {
                let a = crate::solids::box_between([0.0; 3], [2.0, 1.0, 1.0]);
                let b = crate::solids::box_between([0.0, 0.0, 1.0], [1.0, 1.0, 3.0]);
                return Mesh::concatenate([&a.unwrap(), &b.unwrap()]).unwrap();
            }
        }
        .unwrap()
    }

    /// `mesh` scaled by a power of two (exactly), or moved by 1e8 along x and y.
    fn placed(m: Mesh, placement: usize) -> Mesh {
        match placement {
            0 => m,
            1 => m.scaled_exactly(-300).unwrap(),
            2 => m.scaled_exactly(300).unwrap(),
            _ => m
                .transformed(&nalgebra::Matrix4::new_translation(
                    &nalgebra::Vector3::new(1e8, -1e8, 0.0),
                ))
                .unwrap(),
        }
    }

    /// Hard points for `grid`'s mesh.
    fn points(grid: &ProjectionGrid, rng: &mut SplitMix64) -> Vec<Point3> {
        let mesh = grid.mesh;
        let v = mesh.vertices();
        let lo = |k: usize| v.iter().map(|p| p[k]).fold(f64::INFINITY, f64::min);
        let hi = |k: usize| v.iter().map(|p| p[k]).fold(f64::NEG_INFINITY, f64::max);
        let within = |k: usize, t: f64| lo(k) + (hi(k) - lo(k)) * t;
        let z = |rng: &mut SplitMix64| match rng.below(3) {
            0 => v[rng.below(v.len())].z,
            _ => within(2, rng.unit() * 1.4 - 0.2),
        };
        let mut out: Vec<Point3> = v.to_vec();
        for t in mesh.triangles() {
            let [a, b, c] = t.map(|i| v[i as usize]);
            out.push(nalgebra::center(&a, &b));
            out.push(nalgebra::center(&b, &c));
            out.push(Point3::from((a.coords + b.coords + c.coords) / 3.0));
        }
        for _ in 0..200 {
            let p = v[rng.below(v.len())];
            out.push(Point3::new(p.x, p.y, z(rng)));
        }
        let [nx, ny] = grid.cells.shape();
        for _ in 0..400 {
            // A cell border or centre along one or both axes, at a vertex's or a random z.
            let line = |k: usize, n: usize, rng: &mut SplitMix64| {
                let t = rng.below(2 * n + 1) as f64 / 2.0;
                match rng.below(3) {
                    0 => grid.cells.coordinate(k, t),
                    1 => grid.cells.coordinate(k, t.floor()),
                    _ => within(k, rng.unit() * 1.2 - 0.1),
                }
            };
            out.push(Point3::new(line(0, nx, rng), line(1, ny, rng), z(rng)));
        }
        for c in 0..grid.cells.count() {
            if let Some([x, y]) = grid.centre(c) {
                out.push(Point3::new(x, y, z(rng)));
            }
        }
        out
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(40))]

        #[test]
        fn the_grid_agrees_with_brute_force(which in 0..5usize, placement in 0..4usize,
                                            seed in any::<u64>()) {
            let m = placed(mesh(which), placement);
            let grid = ProjectionGrid::new(&m);
            let mut rng = SplitMix64(seed);
            for p in points(&grid, &mut rng) {
                prop_assert_eq!(grid.classify(&p), classify_point_brute_force(&m, &p),
                                "mesh {} placement {} point {:?}", which, placement, p);
            }
        }
    }

    #[test]
    fn cells_are_not_smaller_than_the_mean_box() {
        // A million-triangle sphere listed each triangle in ten cells on average with a cell
        // per triangle; cells the size of the mean projected box list fewer than five.
        let sphere = crate::solids::uv_sphere(1.0, 200, 101).unwrap();
        let grid = ProjectionGrid::new(&sphere);
        assert!(
            grid.items.len() < 5 * grid.triangle_count(),
            "{}",
            grid.items.len()
        );
        assert!(grid.cells.count() <= grid.triangle_count());
        // Every triangle is listed in order in the cells its box covers, and nowhere else.
        for (t, c) in (0..sphere.triangles().len()).map(|t| (t, sphere.triangle(t))) {
            let (min, max) = bounds(&c);
            let xs = grid.cells.index(0, min[0])..=grid.cells.index(0, max[0]);
            let ys = grid.cells.index(1, min[1])..=grid.cells.index(1, max[1]);
            for y in ys {
                for x in xs.clone() {
                    let cell = y * grid.cells.shape()[0] + x;
                    assert!(grid.listed(cell).binary_search(&(t as u32)).is_ok());
                }
            }
        }
        let expected: usize = (0..sphere.triangles().len())
            .map(|t| {
                let (min, max) = bounds(&sphere.triangle(t));
                [0, 1]
                    .map(|k| grid.cells.index(k, max[k]) - grid.cells.index(k, min[k]) + 1)
                    .iter()
                    .product::<usize>()
            })
            .sum();
        assert_eq!(grid.items.len(), expected);
        assert!((0..grid.cells.count()).all(|c| grid.listed(c).is_sorted()));
    }

    #[test]
    fn an_empty_mesh_has_one_cell_and_nothing_inside() {
        let empty = Mesh::from_polygons(Vec::new(), Vec::new()).unwrap();
        let grid = ProjectionGrid::new(&empty);
        assert_eq!((grid.shape(), grid.triangle_count()), ([1, 1], 0));
        assert_eq!(grid.classify(&Point3::origin()), Containment::Outside);
    }
}
