//! A tile as a file (`.kpt`): a tile's bytes with the place of its window in its grid and a
//! fingerprint of what it was drawn from, so that tiles drawn by separate processes (`kepler
//! render --tiles 4x4 --tile 2,3`, one job of a batch scheduler each) are stitched only with
//! the other tiles of their own grid (`kepler stitch`), and a missing or foreign tile is an
//! error that names it.
//!
//! The format (little-endian): the magic `KTFILE\0\x01`; the grid's columns and rows and the
//! tile's column and row (`u32` each); the fingerprint (`u64`); then the tile's own bytes
//! ([`TileDrawing::to_bytes`]) to the end.
//!
//! The fingerprint is a hash (`crate::fnv`: the same in every build) of the view, of every
//! window of the grid (their bounds' bits), of the options that change a tile's pieces (the
//! edge selection and the crease angle), and of every mesh of the scene (its CBOX's and its
//! vertices' bits, and its triangles). Two tiles with one fingerprint were drawn from one
//! scene, view and options, whatever process drew them.

use super::{Stitcher, TileDrawing, draw_tile, tile_windows};
use crate::fnv::Fnv;
use crate::hidden::{DrawError, Drawing, EdgeSelection, Options, Result};
use crate::scene::Scene;
use crate::views::{View, Window};

/// One tile of a grid, with where it lies in the grid and the fingerprint of its scene,
/// view and options (see the module documentation).
///
/// ```
/// use kepler::{scene::Scene, views::View, hidden::{Options, draw, tiles::TileFile}};
/// let mut scene = Scene::new();
/// scene.add_mesh(None, "cube", kepler::solids::cube(2.0).unwrap()).unwrap();
/// let (view, options) = (View::standard(), Options::default());
/// let tiles: Vec<(String, TileFile)> = (0..2)
///     .flat_map(|j| (0..3).map(move |i| [i, j]))
///     .map(|at| {
///         let tile = TileFile::draw(&scene, &view, &options, [3, 2], at).unwrap();
///         let read = TileFile::from_bytes(&tile.to_bytes()).unwrap();
///         (format!("{}-{}.kpt", at[0], at[1]), read)
///     })
///     .collect();
/// let whole = draw(&scene, &view, &options).unwrap();
/// // Without tile 2,1: an error naming it.
/// let err = TileFile::stitch(tiles[..5].to_vec(), &options).unwrap_err().to_string();
/// assert!(err.contains("tile 2,1 of the 3x2 grid is missing"), "{err}");
/// assert_eq!(TileFile::stitch(tiles, &options).unwrap().polylines, whole.polylines);
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct TileFile {
    /// The grid's columns and rows, as asked for.
    pub grid: [usize; 2],
    /// The tile's column (from the left, from 0) and row (from the bottom, from 0).
    pub at: [usize; 2],
    /// The fingerprint of the scene, the view, the grid's windows and the options.
    pub fingerprint: u64,
    /// What the tile drew.
    pub tile: TileDrawing,
}

/// The first bytes of a tile file, with the format's version.
const MAGIC: &[u8; 8] = b"KTFILE\x00\x01";

impl TileFile {
    /// Draws the tile in column `at[0]` and row `at[1]` of a grid of `grid[0]` columns by
    /// `grid[1]` rows over the picture ([`tile_windows`]). Where the picture is too thin for
    /// that many columns or rows, the grid has fewer, and a tile beyond them draws nothing
    /// (so a script that draws every tile it asked for still gets a full set). An error for
    /// a tile outside the grid.
    pub fn draw(
        scene: &Scene,
        view: &View,
        options: &Options,
        grid: [usize; 2],
        at: [usize; 2],
    ) -> Result<TileFile> {
        if grid.contains(&0) || at[0] >= grid[0] || at[1] >= grid[1] {
            return Err(DrawError::Tiles(format!(
                "tile {},{} is not in a grid of {}x{} (columns and rows count from 0)",
                at[0], at[1], grid[0], grid[1]
            )));
        }
        let windows = tile_windows(scene, view, grid)?;
        let shape = shape(&windows);
        let tile = if at[0] < shape[0] && at[1] < shape[1] {
            draw_tile(scene, view, options, &windows[at[1] * shape[0] + at[0]])?
        } else {
            TileDrawing::empty()
        };
        Ok(TileFile {
            grid,
            at,
            fingerprint: fingerprint(scene, view, &windows, grid, options),
            tile,
        })
    }

    /// The tile file's bytes.
    pub fn to_bytes(&self) -> Vec<u8> {
        let mut out = MAGIC.to_vec();
        for n in self.grid.iter().chain(&self.at) {
            out.extend_from_slice(&(*n as u32).to_le_bytes());
        }
        out.extend_from_slice(&self.fingerprint.to_le_bytes());
        out.extend_from_slice(&self.tile.to_bytes());
        out
    }

    /// The tile file of [`TileFile::to_bytes`]'s bytes; an error for bytes that are not one.
    ///
    /// ```
    /// let err = kepler::hidden::tiles::TileFile::from_bytes(b"<svg/>").unwrap_err();
    /// assert_eq!(err.to_string(), "tiles: not a kepler tile file (wrong header)");
    /// ```
    pub fn from_bytes(bytes: &[u8]) -> Result<TileFile> {
        let bad = |why: &str| DrawError::Tiles(format!("not a kepler tile file ({why})"));
        let rest = bytes
            .strip_prefix(MAGIC.as_slice())
            .ok_or_else(|| bad("wrong header"))?;
        if rest.len() < 24 {
            return Err(bad("too short"));
        }
        let word =
            |k: usize| u32::from_le_bytes(rest[4 * k..4 * k + 4].try_into().unwrap_or([0; 4]));
        let (grid, at) = ([word(0), word(1)], [word(2), word(3)]);
        if grid.contains(&0) || at[0] >= grid[0] || at[1] >= grid[1] {
            return Err(bad("its place in its grid is malformed"));
        }
        let fingerprint = u64::from_le_bytes(rest[16..24].try_into().unwrap_or([0; 8]));
        let tile = TileDrawing::from_bytes(&rest[24..])?;
        Ok(TileFile {
            grid: grid.map(|n| n as usize),
            at: at.map(|n| n as usize),
            fingerprint,
            tile,
        })
    }

    /// The drawing of a whole grid's tile files, `(name, tile)` (the names for errors), given
    /// in any order: see [`TileSet`].
    pub fn stitch(files: Vec<(String, TileFile)>, options: &Options) -> Result<Drawing> {
        let mut set = TileSet::default();
        for (name, file) in files {
            set.add(&name, file)?;
        }
        set.finish(options)
    }
}

/// The tile files of one grid, added one at a time (each let go once added), then finished
/// into the drawing: [`stitch`](super::stitch) of their tiles, once every tile of the grid
/// is there exactly once and all share one grid and fingerprint. Errors name the tile
/// missing, the file given twice for one tile, or the file of another grid or drawing.
#[derive(Default)]
pub struct TileSet {
    /// The first file's name, grid and fingerprint, which every other must share.
    first: Option<(String, [usize; 2], u64)>,
    /// Which file holds each tile, row by row.
    found: Vec<Option<String>>,
    stitcher: Stitcher,
}

impl TileSet {
    /// Adds the tile file named `name`; an error for a file of another grid or drawing, or
    /// for a tile already added.
    pub fn add(&mut self, name: &str, file: TileFile) -> Result<()> {
        let (first_name, grid, fingerprint) = self
            .first
            .get_or_insert_with(|| (name.to_string(), file.grid, file.fingerprint));
        let [columns, rows] = *grid;
        if file.grid != *grid {
            return Err(DrawError::Tiles(format!(
                "{name} is a tile of a {}x{} grid, but {first_name} of a {columns}x{rows} grid",
                file.grid[0], file.grid[1]
            )));
        }
        if file.fingerprint != *fingerprint {
            return Err(DrawError::Tiles(format!(
                "{name} is a tile of another scene, view or options than {first_name}"
            )));
        }
        self.found.resize(columns * rows, None);
        let slot = &mut self.found[file.at[1] * columns + file.at[0]];
        if let Some(other) = slot {
            return Err(DrawError::Tiles(format!(
                "{other} and {name} are both tile {},{}",
                file.at[0], file.at[1]
            )));
        }
        *slot = Some(name.to_string());
        self.stitcher.add(&file.tile)
    }

    /// The drawing of the tiles added, finished with `options`; an error naming the first
    /// tile of the grid missing.
    pub fn finish(self, options: &Options) -> Result<Drawing> {
        let Some((_, [columns, rows], _)) = self.first else {
            return Err(DrawError::Tiles("no tile files to stitch".into()));
        };
        if let Some(k) = self.found.iter().position(Option::is_none) {
            return Err(DrawError::Tiles(format!(
                "tile {},{} of the {columns}x{rows} grid is missing (no file given holds it)",
                k % columns,
                k / columns
            )));
        }
        self.stitcher.finish(options)
    }
}

/// The columns and rows of a grid of windows (row by row, from the bottom left).
fn shape(windows: &[Window]) -> [usize; 2] {
    let columns = windows
        .iter()
        .take_while(|w| w.y == windows[0].y)
        .count()
        .max(1);
    [columns, windows.len() / columns]
}

/// The fingerprint of a grid's tiles (see the module documentation).
fn fingerprint(
    scene: &Scene,
    view: &View,
    windows: &[Window],
    grid: [usize; 2],
    options: &Options,
) -> u64 {
    let mut h = Fnv::new(0);
    grid.iter().for_each(|&n| h.word(n as u64));
    view.bits().into_iter().for_each(|b| h.word(b));
    for w in windows {
        w.x.iter().chain(&w.y).for_each(|c| h.word(c.to_bits()));
    }
    h.word(match options.edges {
        EdgeSelection::Feature => 0,
        EdgeSelection::All => 1,
        EdgeSelection::Mesh => 2,
    });
    h.word(options.crease_angle.to_bits());
    for (id, mesh) in scene.mesh_objects(scene.roots()) {
        let cbox = scene.cbox(id);
        cbox.min
            .iter()
            .chain(cbox.max.iter())
            .for_each(|c| h.word(c.to_bits()));
        h.word(mesh.vertices().len() as u64);
        for p in mesh.vertices() {
            p.iter().for_each(|c| h.word(c.to_bits()));
        }
        for t in mesh.triangles() {
            h.word(u64::from(t[0]) << 32 | u64::from(t[1]));
            h.word(u64::from(t[2]));
        }
    }
    h.finish()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::{Point3, Vector3};
    use crate::hidden::draw;
    use crate::mesh::Mesh;

    /// Every tile of a `grid`, as files read back from their bytes.
    fn files(scene: &Scene, view: &View, grid: [usize; 2]) -> Vec<(String, TileFile)> {
        let options = Options::default();
        (0..grid[1])
            .flat_map(|j| (0..grid[0]).map(move |i| [i, j]))
            .map(|at| {
                let tile = TileFile::draw(scene, view, &options, grid, at).unwrap();
                let read = TileFile::from_bytes(&tile.to_bytes()).unwrap();
                assert_eq!(read, tile);
                (format!("{at:?}"), read)
            })
            .collect()
    }

    /// A square in the plane x = 0, seen along y: its picture has no width, so a grid of
    /// three columns has one, and the tiles beyond it draw nothing; stitched, they are the
    /// whole drawing.
    #[test]
    fn tiles_beyond_a_thin_picture_draw_nothing() {
        let square = Mesh::from_polygons(
            vec![
                Point3::new(0.0, 0.0, 0.0),
                Point3::new(0.0, 1.0, 0.0),
                Point3::new(0.0, 1.0, 1.0),
                Point3::new(0.0, 0.0, 1.0),
            ],
            vec![vec![0, 1, 2, 3]],
        )
        .unwrap();
        let mut scene = Scene::new();
        scene.add_mesh(None, "square", square).unwrap();
        let view = View::orthographic(Vector3::new(0.0, 1.0, 0.0), Vector3::z()).unwrap();
        let files = files(&scene, &view, [3, 2]);
        assert!(files[1].1.tile.is_empty() && files[2].1.tile.is_empty());
        let options = Options::default();
        let whole = draw(&scene, &view, &options).unwrap();
        assert!(!whole.polylines.is_empty());
        assert_eq!(
            TileFile::stitch(files, &options).unwrap().polylines,
            whole.polylines
        );
    }

    /// Every prefix of a tile file, and a file whose place lies outside its grid, is an
    /// error, not a panic.
    #[test]
    fn broken_files_are_errors() {
        let mut scene = Scene::new();
        scene
            .add_mesh(None, "cube", crate::solids::cube(2.0).unwrap())
            .unwrap();
        let files = files(&scene, &View::standard(), [2, 1]);
        let bytes = files[1].1.to_bytes();
        for len in 0..bytes.len() {
            assert!(TileFile::from_bytes(&bytes[..len]).is_err(), "{len} bytes");
        }
        let mut outside = bytes.clone();
        outside[16] = 2; // column 2 of 2
        let err = TileFile::from_bytes(&outside).unwrap_err().to_string();
        assert!(
            err.ends_with("its place in its grid is malformed)"),
            "{err}"
        );
        assert!(TileFile::stitch(Vec::new(), &Options::default()).is_err());
    }
}
