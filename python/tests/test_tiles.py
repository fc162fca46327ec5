"""Tiles (issue 17, item 6): a scene drawn window by window, by hand or on a Dask cluster of
worker processes, stitched into the same drawing as `Scene.render`, bit for bit; scenes
pickled to the workers as the calls that built them."""

import pickle

import numpy as np
import pytest
import trimesh

import kepler
import kepler.dask
from conftest import ROOT, SCENES

OBLIQUE = {"view_dir": (-1, -2, -1.5)}
PERSPECTIVE = {"eye": (9, -14, 8), "target": (0, 0, 0), "fov": 40}


def bits(polylines):
    """A drawing as comparable bits: class, visibility and the points' bytes per polyline."""
    return [(p.edge_class, p.visible, p.points.tobytes()) for p in polylines]


def by_hand(scene, tiles, view=None, **options):
    """The drawing made tile by tile in this process, each tile's bytes stitched."""
    edges = options.get("edges", "feature")
    parts = [
        scene.render_tile(w, view=view, edges=edges) for w in scene.tile_windows(view, tiles)
    ]
    finish = {k: v for k, v in options.items() if k in ("hidden", "overlaps", "order")}
    return kepler.stitch(parts, **finish)


@pytest.mark.parametrize("scene", SCENES, ids=[s.stem for s in SCENES])
def test_tiles_stitch_to_render_on_every_bundled_scene(scene):
    s = kepler.Scene.load(str(scene))
    for view in (None, OBLIQUE):
        for tiles in ((1, 1), (3, 2), (6, 6)):
            assert bits(by_hand(s, tiles, view, hidden=True)) == bits(
                s.render(view=view, hidden=True)
            ), (scene.stem, view, tiles)


def test_every_option_stitches_as_render_draws():
    s = kepler.Scene.load(str(ROOT / "scenes" / "solids.toml"))
    for view in (OBLIQUE, PERSPECTIVE):
        for options in (
            {"edges": "all", "hidden": True},
            {"edges": "mesh"},
            {"overlaps": "keep", "hidden": True},
            {"order": True, "hidden": True},
        ):
            assert bits(by_hand(s, (4, 5), view, **options)) == bits(
                s.render(view=view, **options)
            ), (view, options)


def test_the_city_along_minus_1_minus_2_minus_3_stitches_bit_for_bit():
    """Issue 27: with 2×2 and 4×4 tiles, a border passed 2.6e-16 from a silhouette's vertex
    and its cut survived stitching as an extra vertex."""
    city = kepler.Scene.load(str(ROOT / "scenes" / "city.toml"))
    along = {"view_dir": (-1, -2, -3)}
    for tiles in ((2, 2), (4, 4), (1, 1)):
        for options in ({"hidden": True}, {"hidden": True, "overlaps": "keep"}, {}):
            assert bits(by_hand(city, tiles, along, **options)) == bits(
                city.render(view=along, **options)
            ), (tiles, options)


def test_random_views_and_grids_stitch_bit_for_bit():
    """Random views (oblique and perspective) and random grids up to 16 × 16 over random
    scenes of boxes and tetrahedra with dyadic coordinates, touching and sunk, and over two
    bundled scenes: stitched as `render` draws, bit for bit."""
    rng = np.random.default_rng(27)
    scenes = [kepler.Scene.load(str(ROOT / "scenes" / f"{n}.toml")) for n in ("solids", "polyhedra")]
    for k in range(6):
        s = kepler.Scene()
        for i in range(4):
            lo = rng.integers(0, 12, 3) / 4
            hi = lo + rng.integers(2, 8, 3) / 4
            box = np.array([[hi[0] if c & 1 else lo[0], hi[1] if c & 2 else lo[1], hi[2] if c & 4 else lo[2]] for c in range(8)])
            faces = [[0, 2, 3, 1], [4, 5, 7, 6], [0, 1, 5, 4], [2, 6, 7, 3], [0, 4, 6, 2], [1, 3, 7, 5]]
            s.add_mesh(f"box{i}", box, faces)
        tetra = rng.integers(0, 16, (4, 3)) / 4
        if abs(np.linalg.det(tetra[1:] - tetra[0])) > 0:
            faces = [[0, 1, 2], [0, 3, 1], [1, 3, 2], [0, 2, 3]]
            if np.linalg.det(tetra[1:] - tetra[0]) > 0:
                faces = [f[::-1] for f in faces]
            s.add_mesh("tetra", tetra, faces)
        scenes.append(s)
    for s in scenes:
        for view in (
            {"view_dir": tuple(rng.normal(size=3))},
            {"eye": tuple(rng.normal(size=3) * 4 + (1.5, -12, 8)), "target": (1.5, 1.5, 1), "fov": 50},
        ):
            tiles = (int(rng.integers(1, 17)), int(rng.integers(1, 17)))
            for options in ({"hidden": True}, {"hidden": True, "overlaps": "keep"}):
                assert bits(by_hand(s, tiles, view, **options)) == bits(
                    s.render(view=view, **options)
                ), (view, tiles, options)


def built_scene(tmp_path):
    """A scene built call by call: a group, arrays with a transform, a trimesh, a file."""
    s = kepler.Scene()
    s.add_group("g")
    v = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], dtype=float)
    f = [[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]]
    t = np.eye(4)
    t[:3, 3] = (0.25, 0.5, 0.125)
    s.add_mesh("tetra", v, f, transform=t, parent="g")
    s.add_trimesh("box", trimesh.creation.box(extents=(1, 2, 0.5)))
    path = tmp_path / "cube.obj"
    trimesh.creation.box(extents=(0.5, 0.5, 3)).export(path)
    s.add_file(str(path), transform=np.diag([1.0, 1.0, 1.0, 1.0]))
    return s


def test_a_pickled_scene_is_the_same_scene(tmp_path):
    s = built_scene(tmp_path)
    copy = pickle.loads(pickle.dumps(s))
    assert copy.objects() == s.objects() == ["g", "g/tetra", "box", "cube"]
    for name in s.objects():
        assert copy.bounds(name) == s.bounds(name)
    assert bits(copy.render(view=OBLIQUE, hidden=True)) == bits(s.render(view=OBLIQUE, hidden=True))
    loaded = kepler.Scene.load(str(ROOT / "scenes" / "city.toml"))
    assert pickle.loads(pickle.dumps(loaded)).objects() == loaded.objects()


def test_tile_errors_are_kepler_errors():
    s = kepler.Scene.load(str(ROOT / "scenes" / "cube.toml"))
    with pytest.raises(kepler.KeplerError, match="lower bounds must be less"):
        s.render_tile(((1.0, 0.0), (0.0, 1.0)))
    with pytest.raises(kepler.KeplerError, match="not a tile"):
        kepler.stitch([b"nonsense"])
    with pytest.raises(kepler.KeplerError, match="at least one"):
        s.tile_windows(None, (0, 3))
    with pytest.raises(kepler.KeplerError, match="no objects"):
        kepler.Scene().tile_windows()


def test_render_tiles_on_a_local_dask_cluster(tmp_path):
    from dask.distributed import Client, LocalCluster

    city = kepler.Scene.load(str(ROOT / "scenes" / "city.toml"))
    built = built_scene(tmp_path)
    with LocalCluster(
        n_workers=2,
        threads_per_worker=1,
        processes=True,
        dashboard_address=None,
        env={"RAYON_NUM_THREADS": "1"},
    ) as cluster, Client(cluster) as client:
        for scene, view in ((city, None), (city, PERSPECTIVE), (built, OBLIQUE)):
            lines = kepler.dask.render_tiles(scene, view, tiles=(4, 4), client=client, hidden=True)
            assert bits(lines) == bits(scene.render(view=view, hidden=True))
        # Issue 27: a border 2.6e-16 from a silhouette's vertex kept its cut as a vertex.
        along = {"view_dir": (-1, -2, -3)}
        for tiles in ((2, 2), (4, 4)):
            lines = kepler.dask.render_tiles(city, along, tiles=tiles, client=client, hidden=True)
            assert bits(lines) == bits(city.render(view=along, hidden=True)), tiles
        # Issue 30: given a file's path, the tasks carry the path, not the scene, and each
        # worker reads the file itself.
        for path in (str(ROOT / "scenes" / "city.toml"), ROOT / "scenes" / "polyhedra.toml"):
            lines = kepler.dask.render_tiles(path, OBLIQUE, tiles=(3, 2), client=client, hidden=True)
            whole = kepler.Scene.load(str(path)).render(view=OBLIQUE, hidden=True)
            assert bits(lines) == bits(whole), path
        read = client.run(lambda: sorted(kepler.dask._read)).values()
        polyhedra = [str(ROOT / "scenes" / "polyhedra.toml")]
        assert polyhedra in read and all(r in ([], polyhedra) for r in read), read
        with pytest.raises(kepler.KeplerError):
            kepler.dask.render_tiles(tmp_path / "none.toml", tiles=(2, 2), client=client)
        # The tiles really ran in the worker processes.
        assert len(client.scheduler_info()["workers"]) == 2


def test_a_worker_reads_a_scene_once_and_again_when_it_changes(tmp_path):
    path = tmp_path / "cube.toml"
    path.write_text((ROOT / "scenes" / "cube.toml").read_text())
    first = kepler.dask._scene_at(str(path))
    assert kepler.dask._scene_at(str(path)) is first
    path.write_text((ROOT / "scenes" / "cube.toml").read_text() + "\n# changed\n")
    again = kepler.dask._scene_at(str(path))
    assert again is not first and again.objects() == first.objects()


def test_render_tiles_starts_its_own_cluster():
    s = kepler.Scene.load(str(ROOT / "scenes" / "solids.toml"))
    lines = kepler.dask.render_tiles(s, OBLIQUE, tiles=(3, 3), order=True)
    assert bits(lines) == bits(s.render(view=OBLIQUE, order=True))
