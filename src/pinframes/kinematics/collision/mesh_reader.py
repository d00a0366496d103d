"""Mesh files as triangles in metres: the one reader of the clearance and the 3-D page.

:func:`read_mesh` reads a mesh file into a :class:`TriangleMesh`; the clearance builds
coal's BVH models from its triangles (:mod:`.coal_objects`), the 3-D page draws them. Two
readers stand behind it, chosen by the file's content and name:

- COLLADA (``.dae``, or any file whose content is XML) by pycollada, with every node's
  placement applied down the node tree (``<instance_node>`` included) and the file's
  ``<unit meter="...">`` applied, as RViz applies it: the KUKA KR210's visual meshes are
  written in inches (``meter="0.0254"``). The ``<up_axis>`` is *not* applied, as RViz and
  MoveIt do not apply it: ROS meshes are drawn in their file's coordinates, and robot
  descriptions were written to look right there (some ship ``Y_UP`` files that must not be
  turned). The document ends at its root's end tag: bytes after ``</COLLADA>`` are left
  out (a real KUKA iiwa mesh has leftovers of an older file there). Instances and triangles
  are counted before any triangle is built: a file of a few kB whose nodes instance each
  other can describe billions of triangles.
- STL, OBJ, PLY and OFF by coal's own mesh loader (assimp), the reader
  ``pinocchio.buildGeomFromUrdf`` uses, so the triangles are those Pinocchio measures. These
  formats hold no instances: their triangles grow with the file's size only.

Every problem is a :class:`~pinframes.errors.GeometryError` naming the file, its message
saying what the mesh is (``cannot be read: ...``, ``has no triangles``, ``describes ...
triangles ...``); callers add the frame and the field.
"""

from __future__ import annotations

import io
import re
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import coal
import numpy as np
from numpy.typing import NDArray

from ...errors import GeometryError
from .mesh_counts import polygon_triangles

__all__ = [
    "ASSIMP_SUFFIXES",
    "DEFAULT_BOUNDS",
    "MAX_NODE_DEPTH",
    "MAX_TRIANGLES",
    "NODE_INSTANCES_PER_TRIANGLE",
    "MeshBounds",
    "MeshPart",
    "TriangleBudget",
    "TriangleMesh",
    "read_mesh",
]

MAX_TRIANGLES = 1_000_000
"""Default bound on the triangles of one mesh file after instancing (the largest of the 173
mesh files of ROS-Industrial's kuka_experimental has 70,010)."""

NODE_INSTANCES_PER_TRIANGLE = 4
"""COLLADA node instances (of nodes that hold triangles) allowed per triangle of
``max_triangles``: the nodes of a tree of instances are fewer than twice its leaves, and a
few nodes above place the whole."""

MAX_NODE_DEPTH = 256
"""COLLADA nodes nested deeper than this (through ``<node>`` and ``<instance_node>``) are
refused; robot meshes nest a few levels."""

ASSIMP_SUFFIXES = (".stl", ".obj", ".ply", ".off")
"""Mesh formats read by coal's loader (assimp): none of them instances a part."""

_COLLADA_END = re.compile(rb"</(?:[A-Za-z_][\w.-]*:)?COLLADA\s*>")
_XML_DECLARATIONS = (b"<!DOCTYPE", b"<!ENTITY")

FloatArray = NDArray[np.float64]
IndexArray = NDArray[np.int64]


@dataclass(frozen=True)
class MeshBounds:
    """What reading one mesh file may cost: ``max_triangles`` after instancing, and
    ``max_bytes`` of file (None: any size)."""

    max_triangles: int = MAX_TRIANGLES
    max_bytes: int | None = None


DEFAULT_BOUNDS = MeshBounds()
"""1,000,000 triangles, files of any size."""


class TriangleBudget:
    """The triangles one request (a clearance, a 3-D page) may build from mesh files: each
    mesh counted once per shape that uses it, since each use is built apart (scaled and
    placed for its link), against ``max_triangles`` for the whole request."""

    def __init__(self, max_triangles: int = MAX_TRIANGLES) -> None:
        self.max_triangles = max_triangles
        self.spent = 0

    def problem(self, triangles: int) -> str | None:
        """Take ``triangles`` more from the budget, or say why not (then nothing is taken)."""
        if self.spent + triangles > self.max_triangles:
            return (f"its {triangles:,} triangles would bring the meshes of this request to "
                    f"{self.spent + triangles:,} (each use by a link counts), over the limit "
                    f"max_triangles={self.max_triangles:,}; raise it for trusted files "
                    "(limits=pinframes.Limits(max_triangles=...) or --max-triangles)")
        self.spent += triangles
        return None


@dataclass(frozen=True)
class MeshPart:
    """Triangles of one material of a mesh file.

    Attributes
    ----------
    vertices : ndarray, shape (n, 3)
        Metres, in the mesh file's coordinates (every node placement and the file's unit
        applied; a URDF ``scale`` not yet).
    triangles : ndarray of int64, shape (m, 3)
        Vertex indices of each triangle, counter-clockwise seen from outside as written.
    rgba : tuple of float or None
        The material's diffuse colour (0..1) when the file gives one as a colour.
    """

    vertices: FloatArray
    triangles: IndexArray
    rgba: tuple[float, float, float, float] | None = None


@dataclass(frozen=True)
class TriangleMesh:
    """The triangles of one mesh file, in parts of one material each."""

    parts: tuple[MeshPart, ...]

    @property
    def triangle_count(self) -> int:
        return sum(part.triangles.shape[0] for part in self.parts)

    def merged(self) -> tuple[FloatArray, IndexArray]:
        """Every part's vertices ``(n, 3)`` and triangles ``(m, 3)`` in one pair of arrays."""
        offsets = np.cumsum([0] + [part.vertices.shape[0] for part in self.parts])
        vertices = np.concatenate([part.vertices for part in self.parts])
        triangles = np.concatenate([part.triangles + offset
                                    for part, offset in zip(self.parts, offsets, strict=False)])
        return vertices, triangles


def read_mesh(path: Path, *, max_triangles: int = MAX_TRIANGLES) -> TriangleMesh:
    """The triangles of the mesh file at ``path`` (metres), at most ``max_triangles`` of them
    after instancing; a file that holds none is an error too."""
    with open(path, "rb") as handle:
        head = handle.read(256).lstrip(b"\xef\xbb\xbf \t\r\n")
    if path.suffix.lower() == ".dae" or head.startswith(b"<"):
        mesh = _read_collada(path.read_bytes(), max_triangles, path)
    elif path.suffix.lower() in ASSIMP_SUFFIXES:
        mesh = _read_with_assimp(path, max_triangles)
    else:
        raise GeometryError(f"cannot be read: {path.suffix or 'a name without suffix'} is "
                            "no mesh format pinframes reads (STL, COLLADA .dae, OBJ, PLY, OFF)",
                            file=str(path))
    if mesh.triangle_count == 0:
        raise GeometryError("has no triangles (points or lines only, or empty)",
                            file=str(path))
    return mesh


def _too_many(found: str, max_triangles: int, path: Path) -> GeometryError:
    return GeometryError(
        f"{found}, over the limit max_triangles={max_triangles:,}; if the file is trusted, "
        "raise it (limits=pinframes.Limits(max_triangles=...) or --max-triangles)",
        file=str(path))


def _read_with_assimp(path: Path, max_triangles: int) -> TriangleMesh:
    """An STL, OBJ, PLY or OFF file through coal's loader (assimp), as Pinocchio reads it,
    once its triangles are counted from its bytes (:mod:`.mesh_counts`)."""
    counted = polygon_triangles(path)
    if counted > max_triangles:
        raise _too_many(f"holds {counted:,} triangles (counted before loading)",
                        max_triangles, path)
    try:
        model = coal.MeshLoader().load(str(path), np.ones(3))
    except (ValueError, RuntimeError) as exc:
        raise GeometryError(f"cannot be read: {_loader_message(exc)}",
                            file=str(path)) from None
    count = int(model.num_tris)
    if count > max_triangles:
        raise _too_many(f"holds {count:,} triangles", max_triangles, path)
    vertices = np.array(model.vertices(), dtype=float).reshape(-1, 3)
    triangles = np.array([(corners[0], corners[1], corners[2]) for corners in
                          map(model.tri_indices, range(count))], dtype=np.int64).reshape(-1, 3)
    return TriangleMesh((MeshPart(vertices, triangles),))


def _loader_message(error: Exception) -> str:
    """The reason in coal's loader error, without its C++ file and function lines."""
    text = str(error)
    _, found, reason = text.partition("message:")
    lines = [line.strip() for line in (reason if found else text).splitlines() if line.strip()]
    return "; ".join(lines[:3]) or type(error).__name__


def _read_collada(data: bytes, max_triangles: int, path: Path) -> TriangleMesh:
    """A COLLADA document: its scene's triangles in metres, counted before they are built."""
    end = _COLLADA_END.search(data)
    if end is None:
        raise GeometryError("cannot be read: not a COLLADA document (no </COLLADA> end tag)",
                            file=str(path))
    # whitespace before the XML declaration (a Doosan mesh has a line break there) is what
    # assimp reads past and an XML parser refuses
    document = data[:end.end()].lstrip(b"\xef\xbb\xbf \t\r\n")
    if any(declaration in document for declaration in _XML_DECLARATIONS):
        raise GeometryError("cannot be read: COLLADA with a DOCTYPE or entity declarations "
                            "is not read",
                            file=str(path))
    import collada  # type: ignore[import-untyped]

    try:
        scene_file = collada.Collada(io.BytesIO(document), ignore=[
            collada.common.DaeUnsupportedError, collada.common.DaeBrokenRefError])
    except Exception as exc:  # pycollada raises many kinds for malformed documents
        raise GeometryError(f"cannot be read as COLLADA ({type(exc).__name__}: "
                            f"{str(exc).strip()[:200]})", file=str(path)) from None
    scene = scene_file.scene
    if scene is None:
        raise GeometryError("cannot be read: COLLADA without a <scene>", file=str(path))
    counted: dict[int, tuple[int, int]] = {}
    triangles, instances = _count(scene.nodes, counted, (), path)
    if triangles > max_triangles:
        raise _too_many(f"describes {triangles:,} triangles after instancing", max_triangles,
                        path)
    if instances > NODE_INSTANCES_PER_TRIANGLE * max_triangles:
        raise _too_many(f"describes {instances:,} node instances after instancing (more "
                        f"than {NODE_INSTANCES_PER_TRIANGLE} per triangle allowed)",
                        max_triangles, path)
    unit = _unit(scene_file, path)
    found: dict[tuple[int, Any], tuple[Any, list[FloatArray]]] = {}
    for primitive, rgba, placements in _placed_primitives(scene.nodes, counted):
        found.setdefault((id(primitive), rgba), (primitive, []))[1].append(placements)
    parts = [_placed_parts(np.concatenate(stacks), primitive, rgba, unit, path)
             for (_, rgba), (primitive, stacks) in found.items()]
    return TriangleMesh(tuple(part for part in parts if part.triangles.shape[0]))


def _unit(scene_file: Any, path: Path) -> float:
    """The document's ``<unit meter>``: 1 when absent, a positive finite number else."""
    asset = getattr(scene_file, "xmlnode", None)
    written = None
    if asset is not None:
        unit = asset.find(".//{*}asset/{*}unit")
        written = None if unit is None else unit.get("meter")
    if written is None:
        return 1.0
    try:
        value = float(written)
    except ValueError:
        value = float("nan")
    if not np.isfinite(value) or value <= 0:
        raise GeometryError(f"cannot be read: <unit meter> must be a positive number of "
                            f"metres, got {written!r}", file=str(path))
    return value


def _triangles_in(primitive: Any) -> int:
    """Triangles a primitive set makes: a triangle set's, a polygon list's fans; lines none."""
    if hasattr(primitive, "vcounts"):
        counts = np.asarray(primitive.vcounts, dtype=np.int64)
        return int(np.clip(counts - 2, 0, None).sum())
    if type(primitive).__name__ == "TriangleSet":
        return len(primitive)
    return 0


def _count(nodes: Any, counted: dict[int, tuple[int, int]], path_ids: tuple[int, ...],
           path: Path) -> tuple[int, int]:
    """Triangles under ``nodes`` with every instance counted, and the instances of nodes
    that hold triangles (those the placement walk visits); each node's own counts computed
    once (``counted``); a node that instances itself is an error."""
    triangles = instances = 0
    for node in nodes:
        target = getattr(node, "node", node)  # an <instance_node> counts as its node
        key = id(target)
        if len(path_ids) >= MAX_NODE_DEPTH:
            raise GeometryError(f"cannot be read: COLLADA nodes nested more than "
                                f"{MAX_NODE_DEPTH} deep", file=str(path))
        if key in path_ids:
            raise GeometryError(f"cannot be read: COLLADA node {getattr(target, 'id', None)!r} "
                                "instances itself", file=str(path))
        if key not in counted:
            own = sum(_triangles_in(primitive) for primitive in
                      getattr(getattr(target, "geometry", None), "primitives", ()))
            below, visits = _count(getattr(target, "children", ()), counted,
                                   (*path_ids, key), path)
            counted[key] = own + below, (1 + visits) if own + below else 0
        triangles += counted[key][0]
        instances += counted[key][1]
    return triangles, instances


def _placed_primitives(nodes: Any, counted: dict[int, tuple[int, int]]
                       ) -> list[tuple[Any, Any, FloatArray]]:
    """``(triangle primitive, rgba, its placements (k, 4, 4) in the file)`` of every
    primitive under ``nodes``. Each node that holds triangles is visited once, parents
    first, with the stack of all its instances' placements, which numpy composes with its
    matrix and hands to its children; nodes without triangles are left out."""
    order: list[Any] = []
    seen: set[int] = set()

    def visit(node: Any) -> None:  # depth-first, children before their parents
        target = getattr(node, "node", node)
        if id(target) in seen or not counted.get(id(target), (0, 0))[0]:
            return
        seen.add(id(target))
        for child in getattr(target, "children", ()):
            visit(child)
        order.append(target)

    for node in nodes:
        visit(node)
    incoming: dict[int, list[FloatArray]] = {}
    for node in nodes:
        incoming.setdefault(id(getattr(node, "node", node)), []).append(np.eye(4)[None])
    placed = []
    for target in reversed(order):  # every parent before its children
        stack = np.concatenate(incoming.pop(id(target)))
        matrix = getattr(target, "matrix", None)
        if matrix is not None:
            stack = np.einsum("kij,jl->kil", stack, np.asarray(matrix, dtype=float))
        geometry = getattr(target, "geometry", None)
        if geometry is not None:
            colours = {material.symbol: _diffuse(material.target)
                       for material in getattr(target, "materials", ())}
            placed += [(primitive, colours.get(primitive.material), stack)
                       for primitive in geometry.primitives if _triangles_in(primitive)]
        for child in getattr(target, "children", ()):
            key = id(getattr(child, "node", child))
            if counted.get(key, (0, 0))[0]:
                incoming.setdefault(key, []).append(stack)
    return placed


def _diffuse(material: Any) -> tuple[float, float, float, float] | None:
    """A material's diffuse colour (0..1) when it is a colour (not a texture)."""
    diffuse = getattr(getattr(material, "effect", None), "diffuse", None)
    if isinstance(diffuse, tuple) and len(diffuse) in (3, 4):
        values = [float(value) for value in diffuse] + [1.0] * (4 - len(diffuse))
        if all(np.isfinite(values)):
            red, green, blue, alpha = np.clip(values, 0.0, 1.0).tolist()
            return (red, green, blue, alpha)
    return None


def _placed_parts(placements: FloatArray, primitive: Any,
                  rgba: tuple[float, float, float, float] | None, unit: float,
                  path: Path) -> MeshPart:
    """A primitive's triangles at each of its ``placements`` ``(k, 4, 4)`` in the file's
    coordinates, scaled to metres, as one part (its vertices computed once, placed with
    numpy)."""
    triangle_set = primitive.triangleset() if hasattr(primitive, "vcounts") else primitive
    vertices = np.asarray(triangle_set.vertex, dtype=float).reshape(-1, 3)
    triangles = np.asarray(triangle_set.vertex_index, dtype=np.int64).reshape(-1, 3)
    if triangles.size and (triangles.min() < 0 or triangles.max() >= vertices.shape[0]):
        raise GeometryError("cannot be read: COLLADA triangle indices outside the vertices",
                            file=str(path))
    used, triangles = np.unique(triangles, return_inverse=True)  # unused vertices left out
    triangles = triangles.reshape(-1, 3).astype(np.int64)
    count = placements.shape[0]
    with np.errstate(over="ignore", invalid="ignore"):  # one product for every placement
        turned = (placements[:, :3, :3].reshape(-1, 3) @ vertices[used].T).reshape(count, 3, -1)
        placed = (turned.transpose(0, 2, 1) + placements[:, None, :3, 3]) * unit
    offsets = np.arange(count, dtype=np.int64)[:, None, None] * used.shape[0]
    return MeshPart(placed.reshape(-1, 3), (triangles[None] + offsets).reshape(-1, 3), rgba)
