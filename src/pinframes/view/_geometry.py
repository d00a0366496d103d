"""Visual and collision geometry of the URDF robots in a frame tree, loaded with yourdfpy.

:func:`load_geometry` finds the robots that :meth:`FrameTree.attach_urdf` (or ``read_urdf``, or
a scene's ``robots``) put into a tree, reads each URDF with yourdfpy and returns every
geometry (box, cylinder, sphere, STL/DAE/OBJ mesh) as triangles placed in the frame of its
link. Nothing here is used by :meth:`FrameTree.pose`: geometry is loaded only when asked for.
"""

from __future__ import annotations

import logging
import os
from collections.abc import Iterable, Iterator
from contextlib import contextmanager
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from ..errors import UnsupportedFeatureError, warn_at_caller
from ..formats.limits import Limits, current_limits, reader_with_limits
from ..formats.urdf import URDF_METADATA_KEY
from ..kinematics.mesh_files import (
    HOW_TO_SEARCH,
    MeshFiles,
    mesh_file_problem,
    package_search_dirs,
)
from ..tree import FrameTree

__all__ = ["GeometryWarning", "LinkGeometry", "load_geometry"]

_DEFAULT_RGBA = (0.7, 0.7, 0.72, 1.0)


class GeometryWarning(UserWarning):
    """Something left out of a drawing: a link's mesh that is missing, unreadable, empty,
    compressed or too large, a point cloud; on the 3-D page also geometry or a frame that is
    not finite or too far away to draw."""


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
    and in its ancestors. A mesh that is missing, unreadable or empty is a
    :class:`GeometryWarning` naming the link, the file and how to give a search folder; the
    link keeps its other geometry. Mesh files are read uncompressed only, and up to
    ``limits.max_decompressed_bytes`` each (None: the limits in effect, see
    :class:`pinframes.Limits`); others are skipped with a :class:`GeometryWarning` too, and
    so is a mesh of points without triangles. Needs yourdfpy (a pinframes dependency) and, for DAE
    meshes, pycollada (``pip install "pinframes[view]"``).
    """
    search_dirs = package_search_dirs(package_dirs)
    geometry: list[LinkGeometry] = []
    frames_of_links: dict[str, dict[str, str]] = {}
    for frame in tree.frames:
        kept = tree.frame_metadata(frame).get(URDF_METADATA_KEY)
        if kept and "link" in kept:
            frames_of_links.setdefault(kept["robot"], {})[kept["link"]] = frame
    robots = tree.metadata.get(URDF_METADATA_KEY, {})
    for root_frame, links in frames_of_links.items():
        source = robots.get(root_frame, {}).get("source")
        if source is None or source == "<urdf string>":
            warn_at_caller(f"robot at {root_frame!r} was attached from an XML string, not a "
                           "file: its geometry is not loaded", GeometryWarning)
            continue
        with _without_yourdfpy_mesh_notes():
            geometry += _robot_geometry(Path(source), links, collision,
                                        MeshFiles(Path(source), search_dirs))
    return geometry


class _MeshNotes(logging.Filter):
    def filter(self, record: logging.LogRecord) -> bool:
        return not record.getMessage().startswith("Can't find ")


@contextmanager
def _without_yourdfpy_mesh_notes() -> Iterator[None]:
    """Drop yourdfpy's bare "Can't find FILE" log lines (on standard error, through logging's
    last-resort handler) for meshes pinframes skips: a GeometryWarning already names them."""
    logger, notes = logging.getLogger("yourdfpy.urdf"), _MeshNotes()
    logger.addFilter(notes)
    try:
        yield
    finally:
        logger.removeFilter(notes)


def _robot_geometry(urdf_path: Path, frames: dict[str, str], collision: bool,
                    mesh_files: MeshFiles) -> list[LinkGeometry]:
    """The geometry of one URDF file's links that are frames of the tree."""
    yourdfpy = _yourdfpy()
    parsed = yourdfpy.URDF.load(str(urdf_path), build_scene_graph=False, load_meshes=False,
                                filename_handler=mesh_files)
    meshes: dict[str, str] = {}  # file name as written -> link, for the messages
    files_of_links: dict[str, set[str]] = {}
    for link in parsed.robot.links:
        for element in (link.collisions if collision else link.visuals):
            mesh = element.geometry.mesh if element.geometry is not None else None
            if mesh is not None:
                files_of_links.setdefault(link.name, set()).add(mesh.filename)
            if mesh is not None and mesh.filename not in meshes:
                meshes[mesh.filename] = link.name
                found = mesh_files.find(mesh.filename)
                if found is None:
                    mesh_files.skip(mesh.filename)
                    _warn(urdf_path, link.name, mesh.filename, "not found (looked in "
                          + ", ".join(map(str, mesh_files.candidates(mesh.filename)[:4]))
                          + f"); {HOW_TO_SEARCH}")
                elif (problem := mesh_file_problem(
                        found, current_limits().max_decompressed_bytes)) is not None:
                    mesh_files.skip(mesh.filename)
                    _warn(urdf_path, link.name, mesh.filename, f"({found}) {problem}")
    try:
        scene = _scene(yourdfpy, parsed, collision, mesh_files)
    except Exception:
        for fname, link_name in meshes.items():
            _check_readable(urdf_path, link_name, fname, mesh_files)
        scene = _scene(yourdfpy, parsed, collision, mesh_files)
    nodes_of_links: dict[str, int] = {}
    for node in scene.graph.nodes_geometry:
        link = scene.graph.transforms.parents[node]
        nodes_of_links[link] = nodes_of_links.get(link, 0) + 1
    for link in parsed.robot.links:  # an empty mesh file gives no node at all
        elements = link.collisions if collision else link.visuals
        loadable = [e for e in elements if e.geometry is not None and (
            e.geometry.mesh is None or mesh_files(e.geometry.mesh.filename))]
        if nodes_of_links.get(link.name, 0) < len(loadable):
            for element in loadable:
                if element.geometry.mesh is not None:
                    _check_readable(urdf_path, link.name, element.geometry.mesh.filename,
                                    mesh_files)
    result = []
    for node in scene.graph.nodes_geometry:
        link = scene.graph.transforms.parents[node]
        pose_in_link, geometry_name = scene.graph.get(frame_to=node, frame_from=link)
        mesh = scene.geometry[geometry_name]
        files = files_of_links.get(link, set())
        source = (next(iter(files)) if len(files) == 1 and type(mesh).__name__ == "Trimesh"
                  else mesh.metadata.get("file_name", type(mesh).__name__.lower()))
        if link not in frames:
            continue
        if not hasattr(mesh, "faces"):  # a point cloud or a path: from a file, no faces
            named = next(iter(files)) if len(files) == 1 else str(source)
            _warn(urdf_path, link, named, f"has no triangles (a "
                  f"{type(mesh).__name__}, points or lines only)")
        elif len(mesh.faces) == 0:  # empty mesh files were skipped above: a primitive
            _warn(urdf_path, link, str(source), "has no triangles (a size that is zero or "
                  "not finite)", what="geometry")
        else:
            result.append(LinkGeometry(
                frames[link], link, np.asarray(pose_in_link, dtype=float),
                np.asarray(mesh.vertices, dtype=float), np.asarray(mesh.faces, dtype=np.int64),
                _colours(mesh), str(source)))
    return result


def _scene(yourdfpy: Any, parsed: Any, collision: bool, mesh_files: MeshFiles) -> Any:
    """yourdfpy's scene graph of the links with their geometry loaded (meshes included)."""
    with np.errstate(over="ignore", invalid="ignore"):  # sizes of 1e308 or NaN: left out
        model = yourdfpy.URDF(robot=parsed.robot, build_scene_graph=not collision,
                              build_collision_scene_graph=collision,
                              load_meshes=not collision, load_collision_meshes=collision,
                              filename_handler=mesh_files, force_collision_mesh=False)
    return model.collision_scene if collision else model.scene


def _check_readable(urdf_path: Path, link: str, fname: str, mesh_files: MeshFiles) -> None:
    """Load one mesh alone; skip it with a warning when it cannot be read."""
    import trimesh  # type: ignore[import-untyped]

    path = mesh_files(fname)
    if not path:
        return
    try:
        mesh = trimesh.load(path, force="mesh")
    except Exception as exc:
        mesh_files.skip(fname)
        _warn(urdf_path, link, fname, f"cannot be read ({type(exc).__name__}: {exc})")
        return
    if len(getattr(mesh, "faces", ())) == 0:
        mesh_files.skip(fname)
        _warn(urdf_path, link, fname, "has no triangles (unreadable or empty)")


def _colours(mesh: Any) -> np.ndarray:
    """One RGBA colour for the mesh when it is uniform, else one per vertex (0..1)."""
    visual = mesh.visual
    if visual.kind == "texture":
        visual = visual.to_color()
    if visual.kind not in ("face", "vertex"):
        return np.array(_DEFAULT_RGBA)
    colours = np.atleast_2d(np.asarray(visual.vertex_colors, dtype=float)) / 255.0
    if np.all(colours == colours[0]):
        return colours[0]
    return colours


def _warn(urdf_path: Path, link: str, fname: str, problem: str, what: str = "mesh") -> None:
    warn_at_caller(f"{urdf_path}: link {link!r}: {what} {fname!r} {problem}; the link is "
                   "drawn without it", GeometryWarning)


def _yourdfpy() -> Any:
    try:
        import yourdfpy  # type: ignore[import-untyped]
    except ImportError:
        raise UnsupportedFeatureError("loading robot geometry needs yourdfpy: pip install "
                                      "yourdfpy") from None
    return yourdfpy
