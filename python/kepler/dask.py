"""Tiles on Dask: a scene's drawing made window by window on a cluster, stitched into the same
drawing as :meth:`kepler.Scene.render`, bit for bit.

Each window of :meth:`kepler.Scene.tile_windows` is drawn by a task
(:meth:`kepler.Scene.render_tile`: exact cuts at the window's borders, only the objects whose
bounds reach it), and :func:`kepler.stitch` joins the pieces on the client.

Given the path of a scene or mesh file, each task gets the path and its window, never the
scene: a worker reads the file itself, once per worker process (the workers must see the
file at that path: a shared file system, or a copy on each machine). Given a
:class:`kepler.Scene`, the scene travels to the workers once, pickled as the calls that
built it (files are read again by their absolute paths).

>>> import kepler, kepler.dask                                        # doctest: +SKIP
>>> lines = kepler.dask.render_tiles("scenes/metropolis.toml", tiles=(8, 8))  # doctest: +SKIP
>>> lines == kepler.Scene.load("scenes/metropolis.toml").render()     # doctest: +SKIP
"""

from __future__ import annotations

import os
from typing import Any, Optional, Union

from ._kepler import Polyline, Scene, stitch

__all__ = ["render_tiles"]

# The scenes this process has read for tasks, by absolute path, with the file's size and
# modification time: a worker reads a scene once for all its tiles, and again if the file
# changes.
_read: dict[str, tuple[tuple[int, int], Scene]] = {}


def _scene_at(path: str) -> Scene:
    """The scene of the file at ``path`` (absolute), read once per process."""
    try:
        stat = os.stat(path)
    except OSError:
        return Scene.load(path)  # the engine's error, naming the file
    stamp = (stat.st_size, stat.st_mtime_ns)
    cached = _read.get(path)
    if cached is None or cached[0] != stamp:
        # One scene at a time: a worker that draws tiles of another scene lets go of the last.
        _read.clear()
        _read[path] = (stamp, Scene.load(path))
    return _read[path][1]


def _tile(scene: Union[Scene, str], window, view, edges: str, crease_angle: float) -> bytes:
    """One task: the pieces of the drawing in one window (of the scene, or of the scene in
    the file at that path)."""
    if isinstance(scene, str):
        scene = _scene_at(scene)
    return scene.render_tile(window, view=view, edges=edges, crease_angle=crease_angle)


def render_tiles(
    scene: Union[Scene, str, os.PathLike],
    view: Optional[dict] = None,
    tiles: tuple[int, int] = (8, 8),
    client: Any = None,
    *,
    edges: str = "feature",
    hidden: bool = False,
    crease_angle: float = 30.0,
    overlaps: str = "once",
    order: bool = False,
    progress: bool = True,
) -> list[Polyline]:
    """The hidden-line drawing of ``scene`` (as :meth:`kepler.Scene.render` with the same
    arguments), made on a grid of ``tiles[0]`` by ``tiles[1]`` windows by the workers of a
    ``dask.distributed`` ``client`` (one from ``dask-jobqueue`` or ``dask-kubernetes`` works
    the same). ``scene`` is a :class:`kepler.Scene`, or the path of a scene or mesh file that
    every worker can read: then the tasks carry the path, not the scene. With ``progress``, a
    text progress bar shows the tiles finishing.

    Without a client, a local cluster is started for the call and closed after it: one
    single-threaded worker process per core, each running the engine on one thread
    (``RAYON_NUM_THREADS=1``), so that the workers share the cores instead of fighting over
    them.
    """
    from dask.distributed import Client, LocalCluster
    from dask.distributed import progress as progress_bar

    path = None
    if not isinstance(scene, Scene):
        path = os.path.abspath(os.fspath(scene))
        scene = _scene_at(path)
    windows = scene.tile_windows(view, tiles)
    cluster = None
    if client is None:
        cluster = LocalCluster(
            threads_per_worker=1,
            processes=True,
            dashboard_address=None,
            env={"RAYON_NUM_THREADS": "1"},
        )
        client = Client(cluster)
    try:
        if path is None:
            # A key of its own (not the content's hash): a scene scattered again while an
            # earlier copy is being released would otherwise race with its release.
            shared = client.scatter(scene, broadcast=True, hash=False)
        else:
            shared = path
        futures = [
            client.submit(_tile, shared, window, view, edges, crease_angle, pure=False)
            for window in windows
        ]
        if progress:
            progress_bar(futures, notebook=False)
        parts = client.gather(futures)
    finally:
        if cluster is not None:
            client.close()
            cluster.close()
    return stitch(parts, hidden=hidden, overlaps=overlaps, order=order)
