"""``vpype kepler render FILE``: kepler's exact hidden-line drawing as a vpype command.

    vpype kepler render part.stl --view-dir -1,-2,-3 --hidden linemerge linesort write out.svg

Visible lines go to one layer (``--layer``, default 1) and, with ``--hidden``, hidden lines to
another (``--hidden-layer``, default 2), named ``visible`` and ``hidden``. One scene unit
becomes ``--unit`` on the page (default 1 mm), y pointing down as vpype's does.
"""

import click
import vpype as vp
import vpype_cli

from . import Scene


def _triple(value):
    if value is None:
        return None
    try:
        x, y, z = (float(t) for t in value.split(","))
    except ValueError as e:
        raise click.BadParameter(f"'{value}' is not three numbers X,Y,Z") from e
    return (x, y, z)


@click.command()
@click.argument("action", type=click.Choice(["render"]))
@click.argument("path", type=vpype_cli.PathType(exists=True, dir_okay=False))
@click.option("--view-dir", "--view", "view_dir", help="Orthographic view along X,Y,Z.")
@click.option("--eye", help="Perspective view from X,Y,Z (with --target).")
@click.option("--target", help="The point a perspective view looks at.")
@click.option("--up", help="The direction that appears upward, X,Y,Z.")
@click.option("--fov", type=float, help="Vertical field of view in degrees (perspective).")
@click.option(
    "--edges",
    type=click.Choice(["feature", "all", "mesh"]),
    default="feature",
    help="Which edges to draw.",
)
@click.option("--hidden", is_flag=True, help="Also add the hidden lines, in their own layer.")
@click.option("--layer", type=vpype_cli.LayerType(accept_new=True), default=1, help="Layer of visible lines.")
@click.option(
    "--hidden-layer",
    type=vpype_cli.LayerType(accept_new=True),
    default=2,
    help="Layer of hidden lines.",
)
@click.option("--unit", type=vpype_cli.LengthType(), default="1mm", help="Page length of one scene unit.")
@vpype_cli.global_processor
def kepler(document, action, path, view_dir, eye, target, up, fov, edges, hidden, layer, hidden_layer, unit):
    """kepler's exact hidden-line drawing of a scene or mesh file (ACTION: render)."""
    view = {}
    for key, value in (("view_dir", view_dir), ("eye", eye), ("target", target), ("up", up)):
        if value is not None:
            view[key] = _triple(value)
    if fov is not None:
        view["fov"] = fov
    scene = Scene.load(str(path))
    polylines = scene.render(view=view or None, edges=edges, hidden=hidden)
    for visible, layer_id, name in ((True, layer, "visible"), (False, hidden_layer, "hidden")):
        lines = vp.LineCollection()
        for p in polylines:
            if p.visible == visible:
                xy = p.points * unit
                lines.append(xy[:, 0] - 1j * xy[:, 1])
        if len(lines) == 0:
            continue
        lid = document.free_id() if layer_id is None else layer_id
        document.add(lines, lid)
        document.layers[lid].set_property(vp.METADATA_FIELD_NAME, name)
    return document


kepler.help_group = "Plugins"
