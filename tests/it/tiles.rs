//! Tiles (issue 17): a drawing made window by window and stitched equals the whole drawing,
//! polyline for polyline and bit for bit — on the bundled scenes, on lattices of touching and
//! stacked boxes whose edges and vertices lie on the windows' borders, on random boxes in
//! random views and grids, and at extreme scales and offsets.

use crate::common::SplitMix64;
use crate::common::exact::cuboid_at;
use kepler::geometry::{Point3, Vector3};
use kepler::hidden::tiles::{TileDrawing, draw_tile, stitch, tile_windows};
use kepler::hidden::{DrawError, Drawing, EdgeSelection, Options, Overlaps, draw};
use kepler::scene::{Scene, file};
use kepler::views::{View, Window};
use std::path::Path;

/// The scene drawn tile by tile over `windows` (each tile's bytes read back, as they travel
/// between processes), stitched.
fn tiled(scene: &Scene, view: &View, options: &Options, windows: &[Window]) -> Drawing {
    let tiles: Vec<TileDrawing> = windows
        .iter()
        .map(|w| {
            let tile = draw_tile(scene, view, options, w).unwrap();
            TileDrawing::from_bytes(&tile.to_bytes()).unwrap()
        })
        .collect();
    stitch(&tiles, options).unwrap()
}

/// Asserts that the tiled drawing is the whole one, bit for bit; `what` names the case.
fn same(scene: &Scene, view: &View, options: &Options, windows: &[Window], what: &str) {
    let whole = draw(scene, view, options).unwrap();
    let stitched = tiled(scene, view, options, windows);
    let bits = |d: &Drawing| -> Vec<(u8, bool, Vec<[u64; 2]>)> {
        d.polylines
            .iter()
            .map(|p| {
                let points = p.points.iter().map(|q| q.map(f64::to_bits)).collect();
                (p.class as u8, p.visible, points)
            })
            .collect()
    };
    assert_eq!(
        bits(&stitched),
        bits(&whole),
        "{what}: {} windows, {} polylines stitched against {} whole",
        windows.len(),
        stitched.polylines.len(),
        whole.polylines.len()
    );
}

fn options(edges: EdgeSelection, hidden: bool) -> Options {
    Options {
        edges,
        hidden,
        ..Options::default()
    }
}

#[test]
fn bundled_scenes_stitch_to_the_whole_drawing() {
    let scenes = [
        "cube",
        "solids",
        "polyhedra",
        "torus",
        "meshes",
        "bunny",
        "city",
    ];
    for name in scenes {
        let scene = file::load(Path::new(&format!("scenes/{name}.toml"))).unwrap();
        let camera = kepler::views::ViewOptions::default()
            .resolve(scene.camera())
            .unwrap();
        let views = [
            camera.clone().with_aspect(1.5).unwrap_or(camera),
            View::orthographic(Vector3::new(-1.0, -2.0, -1.5), Vector3::z()).unwrap(),
        ];
        for (v, view) in views.iter().enumerate() {
            for grid in [[1, 1], [3, 2], [7, 5]] {
                let windows = tile_windows(&scene, view, grid).unwrap();
                same(
                    &scene,
                    view,
                    &Options::default(),
                    &windows,
                    &format!("{name}, view {v}, grid {grid:?}"),
                );
            }
        }
    }
}

#[test]
fn metropolis_stitches_on_a_fine_grid() {
    let scene = file::load(Path::new("scenes/metropolis.toml")).unwrap();
    let view = kepler::views::ViewOptions::default()
        .resolve(scene.camera())
        .unwrap();
    let view = view.clone().with_aspect(1.5).unwrap_or(view);
    let windows = tile_windows(&scene, &view, [8, 8]).unwrap();
    same(
        &scene,
        &view,
        &Options::default(),
        &windows,
        "metropolis 8×8",
    );
}

/// A lattice of unit boxes, touching and stacked, with some sunk into each other (so they
/// make intersection lines), seen along the axes and obliquely, cut by windows whose
/// borders pass through the boxes' vertices and along their edges.
#[test]
fn lattices_cut_through_vertices_and_along_edges() {
    let mut rng = SplitMix64(17);
    for round in 0..12 {
        let mut scene = Scene::new();
        for i in 0..6 {
            let at = [rng.int(0, 3), rng.int(0, 3), rng.int(0, 2)];
            let size = [rng.int(1, 2), rng.int(1, 2), rng.pick(&[1.0, 1.5])];
            scene
                .add_mesh(None, format!("box{i}"), cuboid_at(size, at))
                .unwrap();
        }
        let views = [
            View::standard(),
            View::orthographic(Vector3::new(0.0, -1.0, 0.0), Vector3::z()).unwrap(),
            View::orthographic(Vector3::new(-1.0, -2.0, -3.0), Vector3::z()).unwrap(),
            View::perspective(
                Point3::new(-4.0, -6.0, 8.0),
                Point3::new(2.0, 2.0, 1.0),
                Vector3::z(),
                50.0,
            )
            .unwrap(),
        ];
        for (v, view) in views.iter().enumerate() {
            // Borders on whole and half units: through vertices, along edges.
            let borders = |rng: &mut SplitMix64| -> [f64; 2] {
                let a = rng.int(-1, 4) / rng.pick(&[1.0, 2.0]);
                [a, a + rng.int(1, 3)]
            };
            let (x, y) = (borders(&mut rng), borders(&mut rng));
            let cut = |b: [f64; 2]| {
                [
                    [f64::NEG_INFINITY, b[0]],
                    [b[0], b[1]],
                    [b[1], f64::INFINITY],
                ]
            };
            let windows: Vec<Window> = cut(y)
                .iter()
                .flat_map(|&y| cut(x).map(|x| Window::new(x, y).unwrap()))
                .collect();
            for (edges, hidden) in [(EdgeSelection::Feature, true), (EdgeSelection::All, false)] {
                same(
                    &scene,
                    view,
                    &options(edges, hidden),
                    &windows,
                    &format!("lattice round {round}, view {v}, {edges:?}"),
                );
            }
        }
    }
}

/// Random boxes (some turned, some touching) in random views, random grids.
#[test]
fn random_boxes_in_random_views_and_grids() {
    let mut rng = SplitMix64(2026);
    for round in 0..30 {
        let mut scene = Scene::new();
        for i in 0..5 {
            let at = [
                rng.range(-2.0, 2.0),
                rng.range(-2.0, 2.0),
                rng.range(0.0, 2.0),
            ];
            let size = [
                rng.range(0.2, 2.0),
                rng.range(0.2, 2.0),
                rng.range(0.2, 2.0),
            ];
            scene
                .add_mesh(None, format!("b{i}"), cuboid_at(size, at))
                .unwrap();
        }
        let direction = rng.vector(1.0);
        let view = if round % 3 == 2 {
            let eye = Point3::from(rng.vector(3.0) + Vector3::new(0.0, 0.0, 9.0));
            View::perspective(eye, Point3::new(0.0, 0.0, 1.0), Vector3::z(), 60.0).unwrap()
        } else {
            match View::orthographic(direction, Vector3::z()) {
                Ok(v) => v,
                Err(_) => continue,
            }
        };
        let grid = [1 + rng.below(9), 1 + rng.below(9)];
        let windows = tile_windows(&scene, &view, grid).unwrap();
        same(
            &scene,
            &view,
            &Options::default(),
            &windows,
            &format!("random round {round}, grid {grid:?}"),
        );
    }
}

/// An eye inside the scene: the view clips to its frustum, and the tiles clip to it too.
#[test]
fn an_eye_inside_the_scene_clips_the_tiles_too() {
    let mut scene = Scene::new();
    for i in 0..4 {
        let at = [f64::from(i) * 3.0 - 6.0, 2.0, -1.0];
        scene
            .add_mesh(None, format!("b{i}"), cuboid_at([2.0, 2.0, 2.0], at))
            .unwrap();
    }
    scene
        .add_mesh(
            None,
            "room",
            cuboid_at([30.0, 30.0, 10.0], [-15.0, -15.0, -2.0]),
        )
        .unwrap();
    let view = View::perspective(
        Point3::new(0.0, -5.0, 0.5),
        Point3::new(0.0, 10.0, 0.0),
        Vector3::z(),
        70.0,
    )
    .unwrap()
    .with_aspect(1.5)
    .unwrap();
    for grid in [[2, 2], [5, 3]] {
        let windows = tile_windows(&scene, &view, grid).unwrap();
        same(&scene, &view, &Options::default(), &windows, "eye inside");
    }
}

/// Scaled by `2^±300` (worked on in the kernel's working range) and moved to `1e8`.
#[test]
fn extreme_scales_and_offsets() {
    for (scale, offset) in [(2f64.powi(300), 0.0), (2f64.powi(-300), 0.0), (1.0, 1e8)] {
        let mut scene = Scene::new();
        for (i, at) in [
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.5, 0.5, 1.0],
            [0.25, -0.5, 0.5],
        ]
        .iter()
        .enumerate()
        {
            let at = at.map(|c| c * scale + offset);
            scene
                .add_mesh(None, format!("b{i}"), cuboid_at([scale; 3], at))
                .unwrap();
        }
        let view = View::orthographic(Vector3::new(-1.0, -2.0, -1.5), Vector3::z()).unwrap();
        let windows = tile_windows(&scene, &view, [4, 3]).unwrap();
        same(
            &scene,
            &view,
            &Options::default(),
            &windows,
            &format!("scale {scale:e}, offset {offset:e}"),
        );
    }
}

/// Each tile draws only inside its window, and leaves out what cannot reach it.
#[test]
fn a_tile_draws_only_inside_its_window() {
    let mut scene = Scene::new();
    for i in 0..10 {
        let at = [f64::from(i) * 2.0, 0.0, 0.0];
        scene
            .add_mesh(None, format!("b{i}"), cuboid_at([1.0, 1.0, 1.0], at))
            .unwrap();
    }
    let view = View::standard();
    // Box i spans x in [2i − 0.5, 2i + 0.5]: the window holds boxes 2 and 3 (its lower bound
    // is inside it), and box 4 begins on its upper bound (outside).
    let window = Window::new([3.5, 7.5], [f64::NEG_INFINITY, f64::INFINITY]).unwrap();
    let tile = draw_tile(&scene, &view, &Options::default(), &window).unwrap();
    let drawing = stitch(&[tile], &Options::default()).unwrap();
    let xs: Vec<f64> = drawing
        .polylines
        .iter()
        .flat_map(|p| p.points.iter().map(|q| q[0]))
        .collect();
    assert!(xs.iter().all(|&x| (3.5..=6.5).contains(&x)), "{xs:?}");
    assert_eq!(
        drawing.length(kepler::hidden::EdgeClass::Silhouette, true),
        8.0
    );
    // A window through the middle of a box cuts it there, exactly.
    let half = Window::new([4.0, 7.5], [f64::NEG_INFINITY, f64::INFINITY]).unwrap();
    let tile = draw_tile(&scene, &view, &Options::default(), &half).unwrap();
    let drawing = stitch(&[tile], &Options::default()).unwrap();
    let min = drawing
        .polylines
        .iter()
        .flat_map(|p| p.points.iter().map(|q| q[0]))
        .fold(f64::INFINITY, f64::min);
    assert_eq!(min, 4.0);
    // Half of box 2's square (no line where the window cuts it) and box 3's whole.
    assert_eq!(
        drawing.length(kepler::hidden::EdgeClass::Silhouette, true),
        6.0
    );
}

#[test]
fn tiles_of_different_scenes_and_bad_bytes_are_refused() {
    let mut small = Scene::new();
    small
        .add_mesh(None, "a", cuboid_at([1.0; 3], [0.0; 3]))
        .unwrap();
    let mut huge = Scene::new();
    huge.add_mesh(None, "a", cuboid_at([1e200; 3], [0.0; 3]))
        .unwrap();
    let view = View::standard();
    let o = Options::default();
    let a = draw_tile(&small, &view, &o, &Window::ALL).unwrap();
    let b = draw_tile(&huge, &view, &o, &Window::ALL).unwrap();
    assert!(matches!(
        stitch(&[a.clone(), b], &o),
        Err(DrawError::Tiles(_))
    ));
    let bytes = a.to_bytes();
    assert!(TileDrawing::from_bytes(&bytes[..bytes.len() - 1]).is_err());
    // The first line's class (after the header, the eye, the slack, the count, the line's
    // name): one that does not exist.
    let mut flipped = bytes.clone();
    flipped[8 + 4 + 1 + 25 + 8 + 8 + 13] = 9;
    assert!(TileDrawing::from_bytes(&flipped).is_err());
    // A point that is not finite.
    let mut flipped = bytes.clone();
    flipped[8 + 4 + 1 + 25 + 8 + 8 + 15..][..8].copy_from_slice(&f64::NAN.to_le_bytes());
    assert!(TileDrawing::from_bytes(&flipped).is_err());
    // Every shorter prefix is refused too.
    for k in 0..bytes.len() {
        assert!(TileDrawing::from_bytes(&bytes[..k]).is_err());
    }
    assert!(Window::grid([0.0; 2], [1.0; 2], [0, 1]).is_err());
    assert!(Window::grid([0.0; 2], [f64::INFINITY; 2], [1, 1]).is_err());
}

/// Both ways of finishing a drawing: every piece, and each stretch once.
fn both(options: Options) -> [Options; 2] {
    [
        options,
        Options {
            overlaps: Overlaps::Once,
            ..options
        },
    ]
}

/// The windows cut by vertical borders at `xs` and horizontal ones at `ys` (each list
/// sorted, without repeats): they cover the picture once.
fn cut_by(xs: &[f64], ys: &[f64]) -> Vec<Window> {
    let bands = |b: &[f64]| -> Vec<[f64; 2]> {
        let mut edges = vec![f64::NEG_INFINITY];
        edges.extend_from_slice(b);
        edges.push(f64::INFINITY);
        edges.windows(2).map(|w| [w[0], w[1]]).collect()
    };
    let (bx, by) = (bands(xs), bands(ys));
    by.iter()
        .flat_map(|&y| bx.iter().map(move |&x| Window::new(x, y).unwrap()))
        .collect()
}

/// The city seen along (−1, −2, −3) in 2×2 and 4×4 tiles: a border passed 2.6e-16 from a
/// silhouette's vertex, and the border's cut survived stitching as an extra vertex, because
/// pieces were ordered by their rough parameters (issue 27).
#[test]
fn the_city_seen_along_minus_1_minus_2_minus_3() {
    let scene = file::load(Path::new("scenes/city.toml")).unwrap();
    let view = View::orthographic(Vector3::new(-1.0, -2.0, -3.0), Vector3::z()).unwrap();
    for options in both(Options::default()) {
        for grid in [[2, 2], [4, 4], [3, 5]] {
            let windows = tile_windows(&scene, &view, grid).unwrap();
            let what = format!("city along (-1, -2, -3), grid {grid:?}, {options:?}");
            same(&scene, &view, &options, &windows, &what);
        }
    }
}

/// Dyadic boxes and tetrahedra, touching and sunk, in random views (along the axes, oblique,
/// in perspective), cut by borders through points of the drawing (pictures of vertices, of
/// cuts where lines cross, of intersection lines' ends) and one unit in the last place to
/// either side of them.
#[test]
fn borders_through_vertices_cuts_and_crossings_and_an_ulp_beside() {
    let mut rng = SplitMix64(2727);
    let mut cases = 0;
    for round in 0..24 {
        let mut scene = Scene::new();
        for i in 0..4 + rng.below(3) {
            let at = [0; 3].map(|_| rng.int(0, 12) / 4.0);
            let size = [0; 3].map(|_| rng.int(2, 8) / 4.0);
            scene
                .add_mesh(None, format!("box{i}"), cuboid_at(size, at))
                .unwrap();
        }
        let view = match round % 4 {
            0 => View::orthographic(Vector3::new(0.0, -1.0, 0.0), Vector3::z()),
            1 => View::orthographic(rng.vector(1.0), Vector3::z()),
            2 => View::orthographic(Vector3::new(-1.0, -2.0, -3.0), Vector3::z()),
            _ => View::perspective(
                Point3::from(rng.vector(4.0) + Vector3::new(1.5, -9.0, 6.0)),
                Point3::new(1.5, 1.5, 1.0),
                Vector3::z(),
                50.0,
            ),
        };
        let Ok(view) = view else { continue };
        let whole = draw(&scene, &view, &Options::default()).unwrap();
        let points: Vec<[f64; 2]> = whole
            .polylines
            .iter()
            .flat_map(|p| p.points.iter().copied())
            .collect();
        for _ in 0..3 {
            // Two borders each way through points of the drawing, moved by an ulp or not.
            let mut border = |k: usize| -> Vec<f64> {
                let mut b: Vec<f64> = (0..2)
                    .map(|_| {
                        let c = rng.pick(&points)[k];
                        match rng.below(3) {
                            0 => c.next_down(),
                            1 => c,
                            _ => c.next_up(),
                        }
                    })
                    .collect();
                b.sort_by(f64::total_cmp);
                b.dedup();
                b
            };
            let (xs, ys) = (border(0), border(1));
            let windows = cut_by(&xs, &ys);
            for edges in [EdgeSelection::Feature, EdgeSelection::All] {
                for options in both(options(edges, true)) {
                    let what = format!("round {round}, borders {xs:?} {ys:?}, {options:?}");
                    same(&scene, &view, &options, &windows, &what);
                    cases += 1;
                }
            }
        }
    }
    assert!(cases >= 250, "{cases} cases");
}

/// Every bundled scene in random views (oblique orthographic and perspective from around
/// it) and random grids from 1×1 to 16×16 (the whole 16×16 for the smaller scenes: each
/// tile of a scene whose one object spans the picture does that object's work again), with
/// overlaps kept and drawn once.
#[test]
fn bundled_scenes_in_random_views_and_grids() {
    let mut rng = SplitMix64(1616);
    let scenes = [
        ("cube", true),
        ("solids", true),
        ("polyhedra", true),
        ("torus", false),
        ("meshes", false),
        ("city", false),
    ];
    for (n, (name, small)) in scenes.into_iter().enumerate() {
        let scene = file::load(Path::new(&format!("scenes/{name}.toml"))).unwrap();
        let bounds = scene
            .mesh_objects(scene.roots())
            .iter()
            .map(|(id, _)| scene.cbox(*id))
            .reduce(|a, b| a.union(&b))
            .unwrap();
        let centre = Point3::from([0, 1, 2].map(|k| (bounds.min[k] + bounds.max[k]) / 2.0));
        let size = (0..3)
            .map(|k| bounds.max[k] - bounds.min[k])
            .fold(0.0, f64::max);
        for v in [n % 2, 1 - n % 2] {
            let view = if v == 0 {
                View::orthographic(rng.vector(1.0), rng.vector(1.0))
            } else {
                let eye = centre + rng.vector(1.0).normalize() * (2.0 * size);
                View::perspective(eye, centre, Vector3::z(), rng.range(30.0, 70.0))
            };
            let Ok(view) = view else { continue };
            let grid = if small && v == 0 {
                [16, 16]
            } else {
                [1 + rng.below(16), 1 + rng.below(3)]
            };
            let windows = tile_windows(&scene, &view, grid).unwrap();
            let options = both(Options::default())[v];
            let what = format!("{name}, view {view:?}, grid {grid:?}, {options:?}");
            same(&scene, &view, &options, &windows, &what);
        }
    }
}
