"""Visual and collision geometry of the URDF links in a frame tree, as triangles.

:func:`load_geometry` reads the shapes recorded when each robot was attached or each shape
added (:class:`~pinframes.FrameGeometry`, the same record the clearance query measures; the
URDF is not parsed again) and makes their triangles: boxes, cylinders and spheres as
trimesh's primitives, meshes from the file
:class:`~pinframes.kinematics.collision.mesh_files.MeshFiles` finds, read by the clearance's
own reader (:func:`~pinframes.kinematics.collision.mesh_reader.read_mesh`: COLLADA units
applied, every node in its place), scaled, a visual's URDF colour on every part (as yourdfpy
draws them), else a COLLADA material's colour. Nothing here is used by
:meth:`FrameTree.pose`: geometry is loaded only when asked for.
"""

from __future__ import annotations

import os
from collections.abc import Iterable
from dataclasses import dataclass
from typing import Any

import numpy as np

from ..errors import GeometryError, GeometryWarning, UnsupportedFeatureError, warn_at_caller
from ..formats.limits import Limits, current_limits, reader_with_limits
from ..kinematics.collision.mesh_files import (
    HOW_TO_SEARCH,
    MeshFiles,
    mesh_file_problem,
    mesh_files_of,
    outside_its_package,
)
from ..kinematics.collision.mesh_reader import TriangleBudget, TriangleMesh, read_mesh
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
        The link's name in its URDF (a frame's own name for shapes it was given).
    pose_in_frame : ndarray, shape (4, 4)
        Placement of the vertices' coordinate system in ``frame`` (the ``<origin>`` of the
        ``<visual>``/``<collision>``, or of the added shape); metres.
    vertices : ndarray, shape (n, 3), float64
        Metres, in the shape's own coordinates (for a mesh: every node of the file placed,
        its unit and the scale applied).
    faces : ndarray, shape (m, 3), int64
        Vertex indices of each triangle.
    colours : ndarray, shape (4,)
        RGBA in 0..1.
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

    Mesh names (``package://``, ``model://``, ``file://``, absolute or relative to the URDF)
    are looked up in ``package_dirs``, then in the folders given when the robot was read,
    then in the folders of ``ROS_PACKAGE_PATH``, then beside the URDF
    and in its ancestors (a robot attached from an XML string has no folder: only the first
    two). A mesh that is missing, unreadable or empty, and a shape the URDF does not
    describe well, is a :class:`GeometryWarning` naming the link, the file and how to give a
    search folder; the link keeps its other geometry. Mesh files are read uncompressed only,
    and up to ``limits.max_decompressed_bytes`` each (None: the limits in effect, see
    :class:`pinframes.Limits`); others are skipped with a :class:`GeometryWarning` too, and
    so is a mesh of points without triangles and one of more than ``limits.max_triangles``
    triangles after instancing, or one that would bring all the page's meshes (each counted
    once per link that uses it) past ``limits.max_triangles``. Needs trimesh for the
    primitives (``pip install "pinframes[view]"``).
    """
    kind = "collision" if collision else "visual"
    # mesh file -> its triangles, None: unreadable or not found (key: name and places searched)
    meshes: dict[str, TriangleMesh | None] = {}
    budget = TriangleBudget(current_limits().max_triangles)  # every link's meshes together
    pieces: list[LinkGeometry] = []
    for frame in tree.frames:
        recorded = tree.frame_metadata(frame).get(GEOMETRY_METADATA_KEY)
        if not isinstance(recorded, FrameGeometry):
            continue
        for field, problem in recorded.unreadable_shapes(kind):
            _warn(recorded, f"{field}: {problem}", "geometry")
        mesh_files = mesh_files_of(recorded, package_dirs)
        for shape in recorded.shapes(kind):
            with np.errstate(over="ignore", invalid="ignore"):  # 1e308 m: left out on the page
                parts = _triangles(shape, recorded, mesh_files, meshes, budget)
            for vertices, faces, rgba in parts:
                if len(faces) == 0:  # a primitive of a size that is zero or not finite
                    _warn(recorded, f"{shape.describe()} has no triangles", "geometry")
                    continue
                colour = shape.rgba or rgba or _DEFAULT_RGBA
                pieces.append(LinkGeometry(
                    frame, recorded.link, shape.origin.matrix, vertices, faces,
                    np.array(colour, dtype=float),
                    shape.kind if shape.mesh is None else shape.mesh))
    return pieces


Part = tuple[np.ndarray, np.ndarray, "tuple[float, float, float, float] | None"]


def _triangles(shape: Shape, recorded: FrameGeometry, mesh_files: MeshFiles,
               meshes: dict[str, TriangleMesh | None], budget: TriangleBudget) -> list[Part]:
    """``(vertices (n, 3) m, faces (m, 3), rgba or None)`` of each part of ``shape``, in the
    shape's coordinates; a mesh past the page's ``budget`` of triangles is left out."""
    if shape.kind != "mesh":
        trimesh = _trimesh()
        if shape.kind == "box":
            made = trimesh.primitives.Box(extents=shape.dimensions)
        elif shape.kind == "cylinder":
            radius, length = shape.dimensions
            made = trimesh.primitives.Cylinder(radius=radius, height=length)
        else:
            made = trimesh.primitives.Sphere(radius=shape.dimensions[0])
        mesh = made.to_mesh()
        return [(np.asarray(mesh.vertices, dtype=float), np.asarray(mesh.faces, dtype=np.int64),
                 None)]
    assert shape.mesh is not None  # a mesh always names its file
    if (refused := outside_its_package(shape.mesh)) is not None:
        _warn(recorded, f"mesh {shape.mesh!r} {refused}")
        return []
    path = mesh_files.find(shape.mesh)
    if path is None:
        missing = f"not found: {shape.mesh} in {mesh_files.candidates(shape.mesh)}"
        if missing not in meshes:  # one warning per mesh and search, not one per link
            meshes[missing] = None
            _warn(recorded, f"mesh {shape.mesh!r} not found ({mesh_files.looked_in(shape.mesh)}"
                  f"); {HOW_TO_SEARCH}")
        return []
    key = str(path)
    if key not in meshes:
        limits = current_limits()
        problem = mesh_file_problem(path, limits.max_decompressed_bytes)
        if problem is not None:
            _warn(recorded, f"mesh {shape.mesh!r} ({path}) {problem}")
            meshes[key] = None
        else:
            try:
                meshes[key] = read_mesh(path, max_triangles=limits.max_triangles)
            except GeometryError as exc:
                _warn(recorded, f"mesh {shape.mesh!r} {exc.message} ({path})")
                meshes[key] = None
    mesh = meshes[key]
    if mesh is None:
        return []
    if (problem := budget.problem(mesh.triangle_count)) is not None:
        _warn(recorded, f"mesh {shape.mesh!r} ({path}): {problem}")
        return []
    scale = np.array(shape.scale)
    return [(part.vertices * scale, part.triangles, part.rgba) for part in mesh.parts]


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
