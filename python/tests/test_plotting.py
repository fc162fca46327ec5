"""Plotter and CAD output, read by the tools their users have: vpype sees the SVG's layers
and runs the `kepler` plugin command; ezdxf reads the DXF with its layers and linetypes."""

import subprocess

import numpy as np
import pytest

import kepler
from conftest import ROOT, SCENES_QUICK

LAYERS = [
    f"{v}-{c}"
    for v in ("hidden", "visible")
    for c in ("smooth", "crease", "intersection", "boundary", "silhouette")
]


@pytest.mark.parametrize("scene", SCENES_QUICK)
def test_vpype_reads_one_layer_per_class_and_visibility(cli, scene, tmp_path):
    vp = pytest.importorskip("vpype")
    svg = tmp_path / "out.svg"
    subprocess.run([cli, "render", str(scene), "-o", str(svg), "--hidden", "dashed", "--order"], check=True)
    document = vp.read_multilayer_svg(str(svg), quantization=0.1)
    drawing = kepler.Scene.load(str(scene)).render(hidden=True)
    expected = [name for name in LAYERS if any(f"{'visible' if p.visible else 'hidden'}-{p.edge_class}" == name for p in drawing)]
    names = [document.layers[lid].property(vp.METADATA_FIELD_NAME) for lid in sorted(document.layers)]
    assert names == [n.replace("-", " ", 1) for n in expected]
    # Each polyline is one path of its layer; vpype drops a path whose points its SVG reader
    # (svgelements) rounds together, which happens only to pieces far below a pen's width.
    extent = max(abs(x) for p in drawing for x in p.points.flat)
    for lid, name in zip(sorted(document.layers), expected):
        mine = [p for p in drawing if f"{'visible' if p.visible else 'hidden'}-{p.edge_class}" == name]
        tiny = sum(1 for p in mine if np.abs(np.diff(p.points, axis=0)).max() < 1e-9 * extent)
        assert len(mine) - tiny <= len(document.layers[lid]) <= len(mine)


def test_the_vpype_plugin_adds_visible_and_hidden_layers():
    vpype_cli = pytest.importorskip("vpype_cli")
    vp = pytest.importorskip("vpype")
    scene = ROOT / "scenes" / "solids.toml"
    document = vpype_cli.execute(f"kepler --view-dir -1,-2,-1.5 --hidden render {scene}")
    drawing = kepler.Scene.load(str(scene)).render(view={"view_dir": (-1, -2, -1.5)}, hidden=True)
    assert sorted(document.layers) == [1, 2]
    assert document.layers[1].property(vp.METADATA_FIELD_NAME) == "visible"
    assert document.layers[2].property(vp.METADATA_FIELD_NAME) == "hidden"
    assert len(document.layers[1]) == sum(p.visible for p in drawing)
    assert len(document.layers[2]) == sum(not p.visible for p in drawing)
    # Scene units become millimetres (vpype works in CSS pixels, y down).
    first = next(p for p in drawing if p.visible)
    line = document.layers[1][0]
    mm = 96 / 25.4
    assert abs(line[0].real - first.points[0, 0] * mm) < 1e-9
    assert abs(line[0].imag + first.points[0, 1] * mm) < 1e-9
    # In a pipeline with vpype's own commands.
    merged = vpype_cli.execute(f"kepler render {scene} linemerge linesort")
    assert len(merged.layers[1]) <= len(document.layers[1])


@pytest.mark.parametrize("scene", SCENES_QUICK)
@pytest.mark.parametrize("encoding", ["text", "binary"])
def test_ezdxf_reads_the_dxf(cli, scene, encoding, tmp_path):
    ezdxf = pytest.importorskip("ezdxf")
    dxf = tmp_path / "out.dxf"
    subprocess.run([cli, "render", str(scene), "-o", str(dxf), "--hidden", "dashed", "--dxf", encoding], check=True)
    doc = ezdxf.readfile(str(dxf))
    drawing = kepler.Scene.load(str(scene)).render(hidden=True)
    entities = list(doc.modelspace())
    assert len(entities) == len(drawing)
    for e, p in zip(entities, drawing):
        assert e.dxftype() == "LWPOLYLINE"
        assert e.dxf.layer == f"{'visible' if p.visible else 'hidden'}-{p.edge_class}"
        layer = doc.layers.get(e.dxf.layer)
        assert layer.dxf.linetype == ("CONTINUOUS" if p.visible else "DASHED")
        points = [(x, y) for x, y, *_ in e.get_points()]
        if e.closed:
            points.append(points[0])
        exact = encoding == "binary"
        for (x, y), (u, w) in zip(points, p.points.tolist()):
            if exact:
                assert (x, y) == (u, w)
            else:
                # 12 decimal places, then the reader's rounding to a double.
                assert abs(x - u) <= 5e-13 + 4e-16 * max(1, abs(u))
                assert abs(y - w) <= 5e-13 + 4e-16 * max(1, abs(w))
