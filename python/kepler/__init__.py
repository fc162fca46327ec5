"""kepler: exact visibility for scenes of polyhedra.

The Python face of the kepler crate (PyO3): hidden-line drawings, INCLUDE (inside, outside or
on an object) and VISP (visible or hidden in a view), computed exactly, with numpy arrays in
and out. Errors are raised as :class:`KeplerError` (a ``ValueError``) with the library's
messages.

>>> import numpy as np, kepler
>>> v = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], dtype=float)
>>> f = np.array([[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]])
>>> lines = kepler.render(v, f, view={"view_dir": (-1, -2, -3)})
>>> sorted({p.edge_class for p in lines})
['silhouette']

Views are dicts of the command line's view options: ``{"view_dir": (x, y, z)}`` for an
orthographic view along a direction, ``{"eye": ..., "target": ..., "fov": 40}`` for a
perspective one, each with an optional ``"up"``; ``None`` takes the scene's camera (a scene
file's) or the standard view.

Large scenes render tile by tile, on a Dask cluster: :func:`kepler.dask.render_tiles` (the
``dask`` extra).
"""

from ._kepler import IN, ON, OUT, KeplerError, Polyline, Scene, render, stitch

__all__ = ["IN", "ON", "OUT", "KeplerError", "Polyline", "Scene", "render", "stitch"]
