"""Visual and collision geometry of the URDF links in a frame tree, as triangles.

:func:`load_geometry` reads the shapes recorded when each robot was attached
(:class:`~pinframes.FrameGeometry`, the same record the clearance query measures; the URDF is
not parsed again) and makes their triangles with trimesh: boxes, cylinders and spheres as
trimesh's primitives, meshes (STL, DAE, OBJ) read from the file
:class:`~pinframes.kinematics.collision.mesh_files.MeshFiles` finds, scaled, every node of a
DAE scene in its place, a visual's URDF colour on meshes without colours of their own (as yourdfpy
draws them). Nothing here is used by :meth:`FrameTree.pose`: geometry is loaded only when
asked for.
"""

from __future__ import annotations

import os
from collections.abc import Iterable
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from ..errors import GeometryWarning, UnsupportedFeatureError, warn_at_caller
from ..formats.limits import Limits, current_limits, reader_with_limits
from ..kinematics.collision.mesh_files import (
    HOW_TO_SEARCH,
    MeshFiles,
    mesh_file_problem,
    package_search_dirs,
)
from ..tree import FrameTree
from ..values.geometry import GEOMETRY_METADATA_KEY, FrameGeometry, Shape

__all__ = ["LinkGeometry", "load_geometry"]

_DEFAULT_RGBA = (0.7, 0.7, 0.72, 1.0)


@dataclass(frozen=True)
class LinkGeometry:
    """One piece of a link's geometry, as triangles.

    Attributes
    ----------
    frame : str
        The tree frame of the link (prefix included).
    link : str
        The link's name in its URDF.
    pose_in_frame : ndarray, shape (4, 4)
        Placement of the vertices' coordinate system in ``frame`` (the ``<origin>`` of the
        ``<visual>``/``<collision>`` times any placement inside the mesh file); metres.
    vertices : ndarray, shape (n, 3), float64
        Metres, in the geometry's own coordinates (mesh scale applied).
    faces : ndarray, shape (m, 3), int64
        Vertex indices of each triangle.
    colours : ndarray, shape (4,) or (n, 4)
        RGBA in 0..1: one colour, or one per vertex.
    source : str
        The mesh file as the URDF names it, or ``box``/``cylinder``/``sphere``.
    """

    frame: str
    link: str
    pose_in_frame: np.ndarray
    vertices: np.ndarray
    faces: np.ndarray
    colours: np.ndarray
    source: str


@reader_with_limits
def load_geometry(
    tree: FrameTree, *, collision: bool = False,
    package_dirs: Iterable[str | os.PathLike[str]] = (), limits: Limits | None = None,
) -> list[LinkGeometry]:
    """The visual (or, with ``collision=True``, collision) geometry of every robot link.

    Mesh names (``package://``, ``file://``, absolute or relative to the URDF) are looked up
    in ``package_dirs``, then in the folders of ``ROS_PACKAGE_PATH``, then beside the URDF
    and in its ancestors (a robot attached from an XML string has no folder: only the first
    two). A mesh that is missing, unreadable or empty, and a shape the URDF does not
    describe well, is a :class:`GeometryWarning` naming the link, the file and how to give a
    search folder; the link keeps its other geometry. Mesh files are read uncompressed only,
    and up to ``limits.max_decompressed_bytes`` each (None: the limits in effect, see
    :class:`pinframes.Limits`); others are skipped with a :class:`GeometryWarning` too, and
    so is a mesh of points without triangles. Needs trimesh and, for DAE meshes, pycollada
    (``pip install "pinframes[view]"``).
    """
    kind = "collision" if collision else "visual"
    search_dirs = package_search_dirs(package_dirs)
    scenes: dict[str, Any] = {}  # mesh file -> its trimesh scene, None when unreadable or
    # not found (key: the name and the places searched)
    pieces: list[LinkGeometry] = []
    for frame in tree.frames:
        recorded = tree.frame_metadata(frame).get(GEOMETRY_METADATA_KEY)
        if not isinstance(recorded, FrameGeometry):
            continue
        for field, problem in recorded.unreadable_shapes(kind):
            _warn(recorded, f"{field}: {problem}", "geometry")
        mesh_files = MeshFiles(None if recorded.urdf is None else Path(recorded.urdf),
                               search_dirs)
        for shape in recorded.shapes(kind):
            with np.errstate(over="ignore", invalid="ignore"):  # 1e308 m: left out on the page
                parts = _triangles(shape, recorded, mesh_files, scenes)
            for pose_in_shape, mesh in parts:
                if len(mesh.faces) == 0:  # a primitive of a size that is zero or not finite
                    _warn(recorded, f"{shape.describe()} has no triangles", "geometry")
                    continue
                pieces.append(LinkGeometry(
                    frame, recorded.link, shape.origin.matrix @ pose_in_shape,
                    np.asarray(mesh.vertices, dtype=float),
                    np.asarray(mesh.faces, dtype=np.int64), _colours(mesh, shape),
                    shape.kind if shape.mesh is None else shape.mesh))
    return pieces


def _triangles(shape: Shape, recorded: FrameGeometry, mesh_files: MeshFiles,
               scenes: dict[str, Any]) -> list[tuple[np.ndarray, Any]]:
    """``(placement in the shape's coordinates, trimesh.Trimesh)`` of each part of ``shape``."""
    trimesh = _trimesh()
    if shape.kind == "box":
        return [(np.eye(4), trimesh.primitives.Box(extents=shape.dimensions).to_mesh())]
    if shape.kind == "cylinder":
        radius, length = shape.dimensions
        return [(np.eye(4), trimesh.primitives.Cylinder(radius=radius, height=length)
                 .to_mesh())]
    if shape.kind == "sphere":
        return [(np.eye(4), trimesh.primitives.Sphere(radius=shape.dimensions[0]).to_mesh())]
    assert shape.mesh is not None  # a mesh always names its file
    path = mesh_files.find(shape.mesh)
    if path is None:
        missing = f"not found: {shape.mesh} in {mesh_files.candidates(shape.mesh)}"
        if missing not in scenes:  # one warning per mesh and search, not one per link
            scenes[missing] = None
            _warn(recorded, f"mesh {shape.mesh!r} not found ({mesh_files.looked_in(shape.mesh)}"
                  f"); {HOW_TO_SEARCH}")
        return []
    key = str(path)
    if key not in scenes:
        problem = mesh_file_problem(path, current_limits().max_decompressed_bytes)
        if problem is not None:
            _warn(recorded, f"mesh {shape.mesh!r} ({path}) {problem}")
            scenes[key] = None
        else:
            scenes[key] = _read_scene(trimesh, path, recorded, shape.mesh)
    scene = scenes[key]
    if scene is None:
        return []
    if shape.scale != (1.0, 1.0, 1.0):
        scene = scene.scaled(np.array(shape.scale))
    parts = []
    for node in scene.graph.nodes_geometry:
        placement, name = scene.graph.get(node)
        if len(getattr(scene.geometry[name], "faces", ())) > 0:  # not points or lines
            parts.append((np.asarray(placement, dtype=float), scene.geometry[name]))
    return parts


def _read_scene(trimesh: Any, path: Path, recorded: FrameGeometry, name: str) -> Any:
    """The mesh file as a trimesh scene of triangle meshes, or None (with a warning)."""
    try:
        scene = trimesh.load(str(path), force="scene")
    except Exception as exc:
        _warn(recorded, f"mesh {name!r} cannot be read ({type(exc).__name__}: {exc})")
        return None
    kept = [geometry for geometry in scene.geometry.values()
            if len(getattr(geometry, "faces", ())) > 0]
    if not kept:
        kinds = {type(geometry).__name__ for geometry in scene.geometry.values()}
        what = f"a {', '.join(sorted(kinds))}, points or lines only" if kinds else "empty"
        _warn(recorded, f"mesh {name!r} has no triangles ({what})")
        return None
    return scene


def _colours(mesh: Any, shape: Shape) -> np.ndarray:
    """One RGBA colour for the mesh when it is uniform, else one per vertex (0..1): the
    visual's URDF colour on a mesh coloured by face or vertex or not at all (as yourdfpy
    paints it), else the mesh's own (a texture's, a material's), else grey."""
    visual = mesh.visual
    if shape.rgba is not None and visual.kind in ("face", "vertex", None):
        return np.array(shape.rgba)
    if visual.kind == "texture":
        visual = visual.to_color()
    if visual.kind not in ("face", "vertex"):
        return np.array(_DEFAULT_RGBA)
    colours = np.atleast_2d(np.asarray(visual.vertex_colors, dtype=float)) / 255.0
    if np.all(colours == colours[0]):
        return colours[0]
    return colours


def _warn(recorded: FrameGeometry, problem: str, what: str = "mesh") -> None:
    warn_at_caller(f"{recorded.urdf or '<urdf string>'}: link {recorded.link!r}: {problem}; "
                   f"the link is drawn without that {what}", GeometryWarning)


def _trimesh() -> Any:
    try:
        import trimesh  # type: ignore[import-untyped]
    except ImportError:
        raise UnsupportedFeatureError('drawing robot geometry needs trimesh: pip install '
                                      '"pinframes[view]"') from None
    return trimesh
