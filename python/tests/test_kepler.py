"""The Python package against the command line: the same drawings (point for point), the same
INCLUDE and VISP answers, the same error messages; and its own API on numpy and trimesh input."""

import json
import subprocess

import numpy as np
import pytest

import kepler
from conftest import ROOT, SCENES

TETRA_V = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], dtype=float)
TETRA_F = np.array([[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]])


def cli_json(cli, scene, tmp_path, *extra):
    svg, out = tmp_path / "out.svg", tmp_path / "out.json"
    subprocess.run([cli, "render", str(scene), "-o", str(svg), "--json", str(out), *extra], check=True)
    return json.loads(out.read_text())["polylines"]


def same(polylines, expected):
    assert len(polylines) == len(expected)
    for p, e in zip(polylines, expected):
        assert (p.edge_class, p.visible) == (e["class"], e["visible"])
        assert p.points.shape == (len(e["points"]), 2)
        # Bit for bit: the JSON's numbers are shortest round-trip decimals.
        assert p.points.tolist() == e["points"]


@pytest.mark.parametrize("scene", SCENES, ids=[s.stem for s in SCENES])
def test_render_is_the_command_lines_drawing(cli, scene, tmp_path):
    expected = cli_json(cli, scene, tmp_path, "--hidden", "dashed")
    same(kepler.Scene.load(str(scene)).render(hidden=True), expected)


def test_views_edges_and_options_match_the_command_line(cli, tmp_path):
    scene = ROOT / "scenes" / "solids.toml"
    s = kepler.Scene.load(str(scene))
    cases = [
        ({"view_dir": (-1, 2, -0.5), "up": (0, 0, 1)}, ["--view-dir", "-1,2,-0.5", "--up", "0,0,1"]),
        ({"eye": (9, -7, 5), "target": (0, 0, 0), "fov": 35}, ["--eye", "9,-7,5", "--target", "0,0,0", "--fov", "35"]),
    ]
    for view, args in cases:
        for edges in ("feature", "all"):
            expected = cli_json(cli, scene, tmp_path, *args, "--edges", edges, "--hidden", "omit", "--order")
            same(s.render(view=view, edges=edges, order=True), expected)
    expected = cli_json(cli, scene, tmp_path, "--keep-overlaps", "--crease-angle", "10")
    same(s.render(hidden=True, overlaps="keep", crease_angle=10), expected)


def test_render_of_arrays_and_lists():
    lines = kepler.render(TETRA_V, TETRA_F, view={"view_dir": (-1, -2, -3)})
    assert [(p.edge_class, p.visible) for p in lines] == [("silhouette", True)]
    assert lines[0].points.dtype == np.float64
    assert np.array_equal(lines[0].points[0], lines[0].points[-1])
    # The same from plain lists, and with hidden lines: the tetrahedron's far edge.
    again = kepler.render(TETRA_V.tolist(), TETRA_F.tolist(), view={"view_dir": (-1, -2, -3)}, hidden=True)
    assert again[-1].points.tolist() == lines[0].points.tolist()
    hidden = [p for p in again if not p.visible]
    assert {p.edge_class for p in hidden} == {"crease"}
    assert sum(len(p) - 1 for p in hidden) == 3


def test_errors_carry_the_librarys_messages(cli, tmp_path):
    with pytest.raises(kepler.KeplerError, match="vertex"):
        kepler.render(TETRA_V, [[0, 1, 7]])
    with pytest.raises(kepler.KeplerError, match="shape"):
        kepler.render(TETRA_V[:, :2], TETRA_F)
    with pytest.raises(kepler.KeplerError, match="unknown view key"):
        kepler.render(TETRA_V, TETRA_F, view={"direction": (0, 0, 1)})
    with pytest.raises(ValueError):
        kepler.render(TETRA_V, TETRA_F, edges="some")
    bad = tmp_path / "bad.obj"
    bad.write_text("v 0 0 0\nv 1 nan 0\n")
    with pytest.raises(kepler.KeplerError) as caught:
        kepler.Scene.load(str(bad))
    run = subprocess.run([cli, "render", str(bad), "-o", str(tmp_path / "x.svg")], capture_output=True, text=True)
    assert run.returncode != 0
    assert str(caught.value) in run.stderr
    assert f"{bad}:2:" in str(caught.value)


def test_include_and_visible_match_the_command_line(cli, tmp_path):
    scene = ROOT / "scenes" / "cube.toml"
    rng = np.random.default_rng(7)
    points = np.vstack([rng.uniform(-2, 2, (200, 3)), [[0, 0, 0], [1, 0, 0], [1, 1, 1]]])
    # Dyadic coordinates: points on faces, edges and corners are exactly there.
    points = np.round(points * 8) / 8
    path = tmp_path / "points.txt"
    path.write_text("".join(f"{float(x)!r} {float(y)!r} {float(z)!r}\n" for x, y, z in points))
    s = kepler.Scene.load(str(scene))
    run = subprocess.run([cli, "include", str(scene), "--points", str(path)], capture_output=True, text=True, check=True)
    codes = {"IN": kepler.IN, "ON": kepler.ON, "OUT": kepler.OUT}
    assert s.include(points).tolist() == [codes[w] for w in run.stdout.split()]
    run = subprocess.run([cli, "visp", str(scene), "--points", str(path), "--view-dir", "1,2,-3"], capture_output=True, text=True, check=True)
    assert s.visible(points, view={"view_dir": (1, 2, -3)}).tolist() == [w == "VISIBLE" for w in run.stdout.split()]


def test_scene_building_transforms_and_bounds():
    trimesh = pytest.importorskip("trimesh")
    s = kepler.Scene()
    g = s.add_group("parts")
    box = trimesh.creation.box(extents=(2, 2, 2))
    a = s.add_trimesh("box", box, parent=g)
    shift = np.eye(4)
    shift[:3, 3] = (10, 0, 0)
    b = s.add_mesh("tetra", TETRA_V, TETRA_F, transform=shift, parent=g)
    assert s.objects() == ["parts", a, b] and a == "parts/box"
    bounds = s.bounds(b)
    assert bounds["cbox"] == ([10.0, 0.0, 0.0], [11.0, 1.0, 1.0])
    assert bounds["solid"] and bounds["faces"] == 4
    assert s.bounds(a)["inbox"] == ([-1.0, -1.0, -1.0], [1.0, 1.0, 1.0])
    inside = s.include(np.array([[0.0, 0, 0], [10.1, 0.1, 0.1], [1.0, 0, 0], [5.0, 0, 0]]))
    assert inside.tolist() == [kepler.IN, kepler.IN, kepler.ON, kepler.OUT]
    seen = s.visible(np.array([[0.0, 0, 1.0], [0.0, 0, -1.0]]), view={"view_dir": (0, 0, -1)})
    assert seen.tolist() == [True, False]
    with pytest.raises(kepler.KeplerError, match="no object named"):
        s.bounds("nothing")
    path = ROOT / "scenes"
    obj = next(path.rglob("*.obj"), None)
    if obj is not None:
        name = s.add_file(str(obj))
        assert name == obj.stem
