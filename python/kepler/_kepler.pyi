"""Type stubs of kepler's compiled module (re-exported by ``kepler``)."""

from typing import Any, Mapping, Optional, Sequence, Union

import numpy as np
import numpy.typing as npt

View = Optional[Mapping[str, Any]]
"""``{"view_dir": (x, y, z)}`` (orthographic) or ``{"eye": (x, y, z), "target": (x, y, z),
"fov": degrees}`` (perspective), each with an optional ``"up"``; ``None``: the scene's camera."""

Faces = Union[npt.ArrayLike, Sequence[Sequence[int]]]

Window = tuple[tuple[float, float], tuple[float, float]]
"""A window of the picture: ``((x0, x1), (y0, y1))``, half open (``x0 <= x < x1``)."""

IN: int
"""INCLUDE's answer for a point inside an object (1)."""
ON: int
"""INCLUDE's answer for a point on an object's boundary (0)."""
OUT: int
"""INCLUDE's answer for a point outside every object (-1)."""

class KeplerError(ValueError):
    """Invalid input (a mesh, a file, a view, a scene), with the library's message."""

class Polyline:
    """A polyline of a drawing, in view coordinates (x right, y up)."""

    @property
    def points(self) -> npt.NDArray[np.float64]:
        """The points, shape (n, 2); a closed polyline repeats its first point."""
    @property
    def edge_class(self) -> str:
        """``silhouette``, ``boundary``, ``crease``, ``intersection`` or ``smooth``."""
    @property
    def visible(self) -> bool:
        """Whether the polyline is visible (else hidden)."""
    def __len__(self) -> int: ...

class Scene:
    """A graph of named objects (groups and meshes), as kepler's scene files describe."""

    def __init__(self) -> None: ...
    @staticmethod
    def load(path: str) -> Scene:
        """A scene read from a scene file (.toml) or a mesh file (.obj, .stl, .off, .ply)."""
    def add_group(self, name: str, parent: Optional[str] = None) -> str:
        """Adds a group; returns its path."""
    def add_mesh(
        self,
        name: str,
        vertices: npt.ArrayLike,
        faces: Faces,
        transform: Optional[npt.ArrayLike] = None,
        parent: Optional[str] = None,
    ) -> str:
        """Adds a mesh: (n, 3) vertices, 0-based faces, an optional 4x4 transform."""
    def add_trimesh(
        self,
        name: str,
        mesh: Any,
        transform: Optional[npt.ArrayLike] = None,
        parent: Optional[str] = None,
    ) -> str:
        """Adds a trimesh.Trimesh (any object with ``vertices`` and ``faces``)."""
    def add_file(
        self,
        path: str,
        name: Optional[str] = None,
        transform: Optional[npt.ArrayLike] = None,
        parent: Optional[str] = None,
    ) -> str:
        """Adds the mesh of a mesh file; the name defaults to the file's stem."""
    def objects(self) -> list[str]:
        """The paths of the objects, depth first."""
    def bounds(self, name: str) -> dict[str, Any]:
        """``cbox`` and ``inbox`` (``(lo, hi)`` or None), ``faces``, ``vertices``, ``solid``."""
    def include(self, points: npt.ArrayLike) -> npt.NDArray[np.int8]:
        """INCLUDE for each point of an (n, 3) array: IN, ON or OUT."""
    def visible(self, points: npt.ArrayLike, view: View = None) -> npt.NDArray[np.bool_]:
        """VISP for each point of an (n, 3) array: True where visible."""
    def render(
        self,
        view: View = None,
        edges: str = "feature",
        hidden: bool = False,
        crease_angle: float = 30.0,
        overlaps: str = "once",
        order: bool = False,
    ) -> list[Polyline]:
        """The hidden-line drawing (see :func:`render`)."""
    def tile_windows(
        self, view: View = None, tiles: tuple[int, int] = (8, 8)
    ) -> list[Window]:
        """A grid of windows over the picture, each ``((x0, x1), (y0, y1))``, half open; the
        outer ones reach to infinity, so the grid covers the whole picture."""
    def render_tile(
        self,
        window: Window,
        view: View = None,
        edges: str = "feature",
        crease_angle: float = 30.0,
    ) -> bytes:
        """The pieces of the drawing inside one window, as bytes for :func:`stitch`."""

def render(
    vertices: npt.ArrayLike,
    faces: Faces,
    view: View = None,
    edges: str = "feature",
    hidden: bool = False,
    crease_angle: float = 30.0,
    overlaps: str = "once",
    order: bool = False,
) -> list[Polyline]:
    """The hidden-line drawing of one mesh: polylines in view coordinates.

    ``edges``: ``feature`` (silhouette, boundary, crease, intersection), ``all`` (smooth edges
    too) or ``mesh`` (every polygon side). ``hidden``: keep hidden pieces too. ``overlaps``:
    ``once`` draws each stretch of line once, ``keep`` keeps coincident edges. ``order``:
    order each layer's paths to shorten pen travel.
    """

def stitch(
    tiles: Sequence[bytes],
    hidden: bool = False,
    overlaps: str = "once",
    order: bool = False,
) -> list[Polyline]:
    """The drawing of the tiles of a grid (:meth:`Scene.render_tile` of each window of
    :meth:`Scene.tile_windows`), finished as :func:`render` finishes it: the same polylines
    as :meth:`Scene.render`, bit for bit."""
