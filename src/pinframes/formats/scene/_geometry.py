"""A scene frame's ``geometry`` entry: the shapes on the frame, read and written.

::

    - name: fixture
      parent: world
      geometry:
        - box: {size: [0.4, 0.3, 0.2]}            # full edge lengths, centred
          xyz: [0, 0, 0.1]                        # the shape's origin in the frame
        - cylinder: {radius: 0.1, length: 0.5}    # axis along z
          rpy: [1.5707963, 0, 0]
          kind: collision                         # collision, visual or both (default)
        - sphere: {radius: 0.05}
          rgba: [0.8, 0.2, 0.1, 1.0]              # its colour on the page
        - mesh: {file: meshes/clamp.stl, scale: 0.001}

A mesh ``file`` is relative to the scene's folder unless it is absolute or a
``package://``, ``model://`` or ``file://`` name. Lengths in metres, angles in radians.
"""

from __future__ import annotations

import os
from pathlib import Path
from typing import Any

from ...errors import FileFormatError, PinframesError, UnsupportedFeatureError
from ...tree import FrameTree
from ...values.geometry import GEOMETRY_METADATA_KEY, FrameGeometry, Shape
from ...values.pose import Pose
from ...values.shapes import Box, Cylinder, Mesh, ShapeLike, Sphere

__all__ = ["GeometryEntry", "add_geometry", "geometry_entries", "read_geometry"]

_SHAPE_KEYS = {"box": {"size"}, "cylinder": {"radius", "length"}, "sphere": {"radius"},
               "mesh": {"file", "scale"}}
_ENTRY_KEYS = {"xyz", "rpy", "quaternion", "kind", "rgba"}
_NAMED = ("package://", "model://", "file://")

GeometryEntry = tuple[ShapeLike, Pose, str, "tuple[float, float, float, float] | None"]
"""A shape, its origin in the frame, its kind and its colour (or None)."""


def read_geometry(value: Any, scene: Path, frame: str, field: str) -> list[GeometryEntry]:
    """The shapes of a ``geometry`` entry of frame ``frame`` in the scene file ``scene``."""
    if not isinstance(value, list):
        raise FileFormatError(f"expected a list of shapes, got {type(value).__name__}",
                              file=scene, frame=frame, field=field)
    return [_entry(item, scene, frame, f"{field}[{index}]") for index, item in enumerate(value)]


def _entry(item: Any, scene: Path, frame: str, field: str) -> GeometryEntry:
    def wrong(message: str, where: str = "") -> FileFormatError:
        return FileFormatError(message, file=scene, frame=frame, field=field + where)

    if not isinstance(item, dict):
        raise wrong(f"expected a mapping, got {type(item).__name__}")
    kinds = [key for key in item if key in _SHAPE_KEYS]
    unknown = sorted(str(key) for key in item if key not in _SHAPE_KEYS and
                     key not in _ENTRY_KEYS)
    if unknown or len(kinds) != 1:
        raise wrong(f"expected one of {', '.join(_SHAPE_KEYS)} and optionally "
                    f"{', '.join(sorted(_ENTRY_KEYS))}; got {', '.join(map(str, item))}")
    (kind,) = kinds
    sizes = item[kind]
    if not isinstance(sizes, dict) or set(sizes) - _SHAPE_KEYS[kind] or (
            kind != "mesh" and set(sizes) != _SHAPE_KEYS[kind]) or (
            kind == "mesh" and "file" not in sizes):
        raise wrong(f"expected a mapping with {', '.join(sorted(_SHAPE_KEYS[kind]))}",
                    f".{kind}")
    try:
        shape = _shape(kind, sizes, scene)
    except PinframesError as exc:
        raise wrong(exc.message, f".{kind}" + (f".{exc.field}" if exc.field else "")) from None
    try:
        origin = _origin(item)
        rgba = None if item.get("rgba") is None else _numbers(item["rgba"], 4, "rgba")
        if rgba is not None and not all(0.0 <= value <= 1.0 for value in rgba):
            raise FileFormatError(f"expected red, green, blue, alpha in 0..1, got {rgba}",
                                  field="rgba")
    except PinframesError as exc:
        raise wrong(exc.message, f".{exc.field or 'quaternion'}") from None
    use = item.get("kind", "both")
    if use not in ("both", "collision", "visual"):
        raise wrong(f"expected both, collision or visual, got {use!r}", ".kind")
    colour = None if rgba is None else (rgba[0], rgba[1], rgba[2], rgba[3])
    return shape, origin, use, colour


def _numbers(value: Any, count: int, field: str) -> tuple[float, ...]:
    if (not isinstance(value, list) or len(value) != count or not all(
            isinstance(v, (int, float)) and not isinstance(v, bool) for v in value)):
        raise FileFormatError(f"expected a list of {count} numbers, got {value!r}",
                              field=field)
    return tuple(float(v) for v in value)


def _shape(kind: str, sizes: dict, scene: Path) -> ShapeLike:
    if kind == "box":
        return Box(_numbers(sizes["size"], 3, "size"))
    if kind == "cylinder":
        return Cylinder(sizes["radius"], sizes["length"])
    if kind == "sphere":
        return Sphere(sizes["radius"])
    file = sizes["file"]
    if not isinstance(file, str) or not file:
        raise FileFormatError(f"expected a file name, got {file!r}", field="file")
    if not file.startswith(_NAMED):
        file = str(scene.parent / file)
    return Mesh(file, sizes.get("scale", 1.0))


def _origin(item: dict) -> Pose:
    if "rpy" in item and "quaternion" in item:
        raise FileFormatError("give either rpy or quaternion, not both", field="rpy")
    xyz = _numbers(item.get("xyz", [0.0, 0.0, 0.0]), 3, "xyz")
    if "quaternion" in item:
        return Pose(xyz, _numbers(item["quaternion"], 4, "quaternion"))
    rpy = _numbers(item.get("rpy", [0.0, 0.0, 0.0]), 3, "rpy")
    return Pose.from_xyz_rpy(*xyz, *rpy)


def add_geometry(tree: FrameTree, frame: str, entries: list[GeometryEntry]) -> None:
    """Put every shape of ``entries`` on ``frame``."""
    for shape, origin, kind, rgba in entries:
        tree.add_geometry(frame, shape, origin=origin, kind=kind, rgba=rgba)


def geometry_entries(tree: FrameTree, frame: str, scene_folder: Path) -> list[dict[str, Any]]:
    """The ``geometry`` entry of ``frame`` (empty without shapes): a shape both collision and
    visual once, with ``kind`` only when it is one of them; mesh files inside
    ``scene_folder`` relative to it."""
    recorded = tree.frame_metadata(frame).get(GEOMETRY_METADATA_KEY)
    if not isinstance(recorded, FrameGeometry):
        return []
    if frame == tree.root and (recorded.collision or recorded.visual):
        raise UnsupportedFeatureError("shapes on the root frame: a scene keeps shapes on the "
                                      "frames it lists; put them on a frame below the root",
                                      frame=frame, field="geometry")
    visual = list(recorded.visual)
    entries = []
    for shape in recorded.collision:
        both = shape in visual
        if both:
            visual.remove(shape)
        entries.append(_written(shape, "both" if both else "collision", recorded, scene_folder))
    entries += [_written(shape, "visual", recorded, scene_folder) for shape in visual]
    return entries


def _written(shape: Shape, kind: str, recorded: FrameGeometry,
             scene_folder: Path) -> dict[str, Any]:
    entry: dict[str, Any]
    if shape.kind == "box":
        entry = {"box": {"size": list(shape.dimensions)}}
    elif shape.kind == "cylinder":
        entry = {"cylinder": {"radius": shape.dimensions[0], "length": shape.dimensions[1]}}
    elif shape.kind == "sphere":
        entry = {"sphere": {"radius": shape.dimensions[0]}}
    else:
        entry = {"mesh": {"file": _mesh_name(shape, recorded, scene_folder)}}
        if shape.scale != (1.0, 1.0, 1.0):
            entry["mesh"]["scale"] = list(shape.scale)
    if any(shape.xyz):
        entry["xyz"] = list(shape.xyz)
    if any(shape.rpy):
        entry["rpy"] = list(shape.rpy)
    if kind != "both":
        entry["kind"] = kind
    if shape.rgba is not None:
        entry["rgba"] = list(shape.rgba)
    return entry


def _mesh_name(shape: Shape, recorded: FrameGeometry, scene_folder: Path) -> str:
    """The mesh's name for the scene: ``package://`` names as they are, files relative to
    the scene's folder when inside it, else absolute."""
    name = str(shape.mesh)
    if name.startswith(_NAMED):
        return name
    if not os.path.isabs(name) and recorded.urdf is not None:
        name = os.path.join(os.path.dirname(recorded.urdf), name)  # relative to its URDF
    path = Path(os.path.abspath(name))
    folder = Path(os.path.abspath(scene_folder))
    return path.relative_to(folder).as_posix() if path.is_relative_to(folder) else str(path)

