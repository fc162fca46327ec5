//! `kepler render --tiles CxR --tile I,J` and `kepler stitch`: tile files drawn one process
//! each and stitched equal `render`'s files byte for byte, for every finishing option; sets
//! that are not one grid's tiles, and files that are not tiles, are errors naming them.

use super::cli::{fails, kepler, ok, stderr};
use std::path::{Path, PathBuf};

/// A fresh scratch folder for one test.
fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("kepler-cli-tiles-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("a scratch folder");
    dir
}

fn path(dir: &Path, name: &str) -> String {
    dir.join(name).display().to_string()
}

/// Draws every tile of a `columns`x`rows` grid of `scene` with the pass's `options`, one
/// process each, into `dir`; the files' paths, in a scrambled order.
fn tiles(dir: &Path, scene: &str, grid: [usize; 2], options: &[&str]) -> Vec<String> {
    let tiles = format!("{}x{}", grid[0], grid[1]);
    let mut files = Vec::new();
    for j in 0..grid[1] {
        for i in 0..grid[0] {
            let file = path(dir, &format!("t-{i}-{j}.kpt"));
            let at = format!("{i},{j}");
            let mut args = vec![
                "render", scene, "--tiles", &tiles, "--tile", &at, "-o", &file,
            ];
            args.extend(options);
            ok(&args);
            files.push(file);
        }
    }
    // Any order: the files say where they lie.
    files.reverse();
    let turn = grid[0].min(files.len() - 1);
    files.rotate_left(turn);
    files
}

fn read(file: &str) -> Vec<u8> {
    std::fs::read(file).unwrap_or_else(|e| panic!("{file}: {e}"))
}

/// A scene, a grid, the pass's options (given to every tile) and the finishing options
/// (given to `stitch`).
type Case<'a> = (&'a str, [usize; 2], &'a [&'a str], &'a [&'a str]);

/// Stitched tiles write exactly `render`'s SVG, DXF and JSON, over bundled scenes, grids,
/// views and every option that changes the pass or its finish.
#[test]
fn stitched_tiles_are_the_whole_render_byte_for_byte() {
    let dir = scratch("whole");
    let cases: &[Case] = &[
        ("scenes/city.toml", [3, 2], &[], &[]),
        ("scenes/city.toml", [1, 1], &[], &["--hidden", "omit"]),
        (
            "scenes/polyhedra.toml",
            [2, 2],
            &["--edges", "all"],
            &["--keep-overlaps"],
        ),
        (
            "scenes/solids.toml",
            [4, 3],
            &["--view-dir", "-1,-2,-3", "--crease-angle", "10"],
            &["--order", "--page", "200x200", "--stroke", "silhouette=0.7"],
        ),
        (
            "scenes/city.toml",
            [2, 3],
            &["--eye", "3,-9,4", "--target", "0,0,0"],
            &["--hidden", "omit"],
        ),
        ("scenes/torus.toml", [5, 1], &["--edges", "mesh"], &[]),
    ];
    for (n, &(scene, grid, pass, finish)) in cases.iter().enumerate() {
        let files = tiles(&dir, scene, grid, pass);
        for output in ["svg", "dxf"] {
            let (whole, json) = (
                path(&dir, &format!("whole.{output}")),
                path(&dir, "whole.json"),
            );
            let mut args = vec!["render", scene, "-o", &whole, "--json", &json];
            args.extend(pass);
            args.extend(finish);
            ok(&args);
            let (joined, joined_json) = (
                path(&dir, &format!("stitched.{output}")),
                path(&dir, "stitched.json"),
            );
            let mut args = vec!["stitch"];
            args.extend(files.iter().map(String::as_str));
            args.extend(["-o", &joined, "--json", &joined_json]);
            args.extend(finish);
            ok(&args);
            assert!(
                read(&whole) == read(&joined),
                "case {n} ({scene}), {output}"
            );
            assert!(
                read(&json) == read(&joined_json),
                "case {n} ({scene}), JSON"
            );
        }
    }
}

/// A set of tiles that is not one whole grid's, and files that are not tiles, are errors
/// naming the tile or the file; so are options that belong to the stitch.
#[test]
fn sets_that_are_not_one_grid_are_errors_naming_the_tile() {
    let dir = scratch("errors");
    let files = tiles(&dir, "scenes/cube.toml", [2, 2], &[]);
    let named = |k: usize| path(&dir, &format!("t-{}-{}.kpt", k % 2, k / 2));
    let out = path(&dir, "out.svg");
    let stitch = |files: &[String]| {
        let mut args = vec!["stitch"];
        args.extend(files.iter().map(String::as_str));
        args.extend(["-o", &out]);
        fails(&args)
    };
    // Missing: tile 1,0.
    let some: Vec<String> = [0, 2, 3].map(named).to_vec();
    assert_eq!(
        stitch(&some),
        "tiles: tile 1,0 of the 2x2 grid is missing (no file given holds it)"
    );
    // Twice.
    let twice: Vec<String> = [0, 1, 2, 3, 2].map(named).to_vec();
    assert_eq!(
        stitch(&twice),
        format!("tiles: {} and {} are both tile 0,1", named(2), named(2))
    );
    // Another scene, other pass options, another grid.
    for (scene, grid, options) in [
        ("scenes/torus.toml", "2x2", &[][..]),
        ("scenes/cube.toml", "2x2", &["--edges", "all"][..]),
        ("scenes/cube.toml", "2x2", &["--view-dir", "-1,-2,-3"][..]),
        ("scenes/cube.toml", "3x1", &[][..]),
    ] {
        let foreign = path(&dir, "foreign.kpt");
        let mut args = vec![
            "render", scene, "--tiles", grid, "--tile", "0,0", "-o", &foreign,
        ];
        args.extend(options);
        ok(&args);
        // Tiles 1,0, 0,1 and 1,1 of the grid, and the foreign one in place of 0,0.
        let mut set: Vec<String> = [1, 2, 3].map(named).to_vec();
        set.push(foreign.clone());
        let err = stitch(&set);
        let expected = if grid == "2x2" {
            format!(
                "tiles: {foreign} is a tile of another scene, view or options than {}",
                set[0]
            )
        } else {
            format!(
                "tiles: {foreign} is a tile of a 3x1 grid, but {} of a 2x2 grid",
                set[0]
            )
        };
        assert_eq!(err, expected, "{scene} {grid} {options:?}");
    }
    // Not a tile: another file, every truncation of a tile, a missing file.
    let svg = path(&dir, "whole.svg");
    ok(&["render", "scenes/cube.toml", "-o", &svg]);
    assert_eq!(
        stitch(std::slice::from_ref(&svg)),
        format!("{svg}: tiles: not a kepler tile file (wrong header)")
    );
    let bytes = read(&files[0]);
    let cut = path(&dir, "cut.kpt");
    for len in [0, 7, 8, 20, 31, 32, 40, bytes.len() / 2, bytes.len() - 1] {
        std::fs::write(&cut, &bytes[..len]).expect("written");
        let err = stitch(std::slice::from_ref(&cut));
        assert!(
            err.starts_with(&format!("{cut}: tiles: not a")),
            "{len}: {err}"
        );
    }
    let gone = path(&dir, "gone.kpt");
    assert!(stitch(std::slice::from_ref(&gone)).starts_with(&format!("cannot read {gone}: ")));
    // Options of the stitch given to a tile, and a tile outside its grid.
    let tile = path(&dir, "t.kpt");
    for (option, name) in [
        (&["--order"][..], "--order"),
        (&["--keep-overlaps"][..], "--keep-overlaps"),
        (&["--hidden", "omit"][..], "--hidden omit"),
        (&["--hatch"][..], "--hatch"),
        (&["--json", "x.json"][..], "--json"),
    ] {
        let mut args = vec![
            "render",
            "scenes/cube.toml",
            "--tiles",
            "2x2",
            "--tile",
            "0,0",
            "-o",
            &tile,
        ];
        args.extend(option);
        assert_eq!(
            fails(&args),
            format!("{name} finishes a whole drawing, not a tile: give it to `kepler stitch`")
        );
    }
    // A tile outside its grid, and a tile written to a file that is not a tile file.
    for (at, output, expected) in [
        (
            "2,0",
            &tile,
            "tiles: tile 2,0 is not in a grid of 2x2 (columns and rows count from 0)".to_string(),
        ),
        (
            "1,0",
            &out,
            format!("with --tile the output is a tile file, whose name ends in .kpt, not {out}"),
        ),
    ] {
        let args = [
            "render",
            "scenes/cube.toml",
            "--tiles",
            "2x2",
            "--tile",
            at,
            "-o",
            output,
        ];
        assert_eq!(fails(&args), expected);
    }
    // `--tile` without `--tiles` is clap's usage error, exit code 2.
    let o = kepler(&["render", "scenes/cube.toml", "--tile", "1,0", "-o", &tile]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
}
