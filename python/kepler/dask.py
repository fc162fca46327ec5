"""Tiles on Dask: a scene's drawing made window by window on a cluster, stitched into the same
drawing as :meth:`kepler.Scene.render`, bit for bit.

Each window of :meth:`kepler.Scene.tile_windows` is drawn by a task
(:meth:`kepler.Scene.render_tile`: exact cuts at the window's borders, only the objects whose
bounds reach it), and :func:`kepler.stitch` joins the pieces on the client. The scene travels
to the workers once, pickled as the calls that built it (files are read again by their
absolute paths, so the workers must see the same files).

>>> import kepler, kepler.dask                                        # doctest: +SKIP
>>> scene = kepler.Scene.load("scenes/metropolis.toml")               # doctest: +SKIP
>>> lines = kepler.dask.render_tiles(scene, tiles=(8, 8))             # doctest: +SKIP
>>> lines == scene.render()                                           # doctest: +SKIP
"""

from __future__ import annotations

from typing import Any, Optional

from ._kepler import Polyline, Scene, stitch

__all__ = ["render_tiles"]


def _tile(scene: Scene, window, view, edges: str, crease_angle: float) -> bytes:
    """One task: the pieces of the drawing in one window."""
    return scene.render_tile(window, view=view, edges=edges, crease_angle=crease_angle)


def render_tiles(
    scene: Scene,
    view: Optional[dict] = None,
    tiles: tuple[int, int] = (8, 8),
    client: Any = None,
    *,
    edges: str = "feature",
    hidden: bool = False,
    crease_angle: float = 30.0,
    overlaps: str = "once",
    order: bool = False,
) -> list[Polyline]:
    """The hidden-line drawing of ``scene`` (as :meth:`kepler.Scene.render` with the same
    arguments), made on a grid of ``tiles[0]`` by ``tiles[1]`` windows by the workers of a
    ``dask.distributed`` ``client``.

    Without a client, a local cluster is started for the call and closed after it: one
    single-threaded worker process per core, each running the engine on one thread
    (``RAYON_NUM_THREADS=1``), so that the workers share the cores instead of fighting over
    them.
    """
    from dask.distributed import Client, LocalCluster

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
        # A key of its own (not the content's hash): a scene scattered again while an earlier
        # copy is being released would otherwise race with its release.
        shared = client.scatter(scene, broadcast=True, hash=False)
        futures = [
            client.submit(_tile, shared, window, view, edges, crease_angle, pure=False)
            for window in windows
        ]
        parts = client.gather(futures)
    finally:
        if cluster is not None:
            client.close()
            cluster.close()
    return stitch(parts, hidden=hidden, overlaps=overlaps, order=order)
