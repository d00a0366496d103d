"""What the page shows, as meshcat commands: frames with axes, robot geometry, tool paths.

Every frame of the tree is a group ``/pinframes/frames/<name>`` placed in the drawing frame
(``relative_to``); its axes and its link geometry hang below it, so moving the group moves
them. A path of frame A drawn in frame B hangs below B's group and moves with it. Groups
that move get an animation track (position and quaternion per sample, float32). The closest
pair of a clearance is marked under ``/pinframes/clearance``: a dot on each closest point and
the segment between them (a unit segment, stretched by a scale track).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ..errors import UnsupportedFeatureError
from ..values.rotations import quaternion_from_matrix
from ._geometry import LinkGeometry

__all__ = ["CLEARANCE_PATH", "SceneCommands", "msgpack", "node_path"]

_ROOT = ("pinframes", "frames")
CLEARANCE_PATH = "/pinframes/clearance"
"""The group of the closest pair's marks: dots ``a`` and ``b`` and the ``segment``."""
_CLEARANCE_COLOUR = 0xE8200C
_FLOAT32 = 0x17  # msgpack extension code that meshcat's viewer reads as a Float32Array


def node_path(frame: str) -> str:
    """The meshcat path of ``frame``'s group: ``/pinframes/frames/frame:<name>``.

    Any frame name gives its own path: ``%`` and ``/`` (which would nest groups) are
    percent-encoded, so ``a/b`` and ``a\u2215b`` stay apart, and the prefix keeps names such
    as ``constructor`` or ``__proto__`` from meeting the properties of the viewer's
    JavaScript objects, which are keyed by path segments.
    """
    return "/" + "/".join((*_ROOT, _segment("frame", frame)))


def _segment(kind: str, name: str) -> str:
    """One path segment for ``name``, never empty and never a JavaScript property name."""
    return f"{kind}:" + name.replace("%", "%25").replace("/", "%2F")


@dataclass
class SceneCommands:
    """meshcat commands (plain dicts, msgpack-ready) building the scene and its animation."""

    commands: list[dict[str, Any]] = field(default_factory=list)
    animations: list[dict[str, Any]] = field(default_factory=list)

    def add_frame(self, frame: str, matrices: np.ndarray, times_s: np.ndarray,
                  axis_length: float) -> None:
        """A frame's group at ``matrices[0]``, its axes, and a track when it moves.

        ``matrices`` has shape (n, 4, 4): the frame's pose in the drawing frame at ``times_s``
        (seconds from the start of the page's animation).
        """
        path = node_path(frame)
        self.commands.append({"type": "set_transform", "path": path,
                              "matrix": _column_major(matrices[0])})
        self.commands.append(_set_object(path + "/axes", _axes(axis_length)))
        if len(matrices) > 1 and np.ptp(matrices[:, :3, :], axis=0).max() > 1e-12:
            self.animations.append(_track(path, matrices, times_s))

    def add_geometry(self, index: int, piece: LinkGeometry) -> None:
        """One piece of link geometry, fixed in its frame's group."""
        path = f"{node_path(piece.frame)}/geometry/{index}"
        vertices = np.asarray(piece.vertices, dtype=np.float32)
        attributes = {"position": _attribute(vertices)}
        material: dict[str, Any] = {"type": "MeshLambertMaterial", "side": 2}
        if piece.colours.ndim == 2:
            attributes["color"] = _attribute(np.asarray(piece.colours[:, :3], np.float32))
            material["vertexColors"] = True
        else:
            material["color"] = _hex_colour(piece.colours)
            if piece.colours[3] < 1.0:
                material.update(transparent=True, opacity=float(piece.colours[3]))
        geometry = {"type": "BufferGeometry",
                    "data": {"attributes": attributes,
                             "index": _attribute(np.asarray(piece.faces, np.uint32))}}
        self.commands.append(_set_object(path, {"type": "Mesh", "geometry": geometry,
                                                "material": material}))
        self.commands.append({"type": "set_transform", "path": path,
                              "matrix": _column_major(piece.pose_in_frame)})

    def add_path(self, frame: str, drawn_in: str, points: np.ndarray) -> None:
        """The path of ``frame`` (``points``, shape (n, 3), metres in ``drawn_in``)."""
        path = f"{node_path(drawn_in)}/paths/{_segment('path', frame)}"
        geometry = {"type": "BufferGeometry",
                    "data": {"attributes": {"position": _attribute(points.astype(np.float32))}}}
        material = {"type": "LineBasicMaterial", "color": 0xCC00CC, "linewidth": 2}
        self.commands.append(_set_object(path, {"type": "Line", "geometry": geometry,
                                                "material": material}))

    def add_closest_pair(self, point_a: np.ndarray, point_b: np.ndarray, times_s: np.ndarray,
                         dot_radius: float) -> None:
        """The closest points of a clearance (shapes (n, 3), metres in the drawing frame) as
        two dots and the segment between them, moving per sample at ``times_s``."""
        for name, points in (("a", point_a), ("b", point_b)):
            matrices = np.broadcast_to(np.eye(4), (len(points), 4, 4)).copy()
            matrices[:, :3, 3] = points
            self._add_moving(f"{CLEARANCE_PATH}/{name}", _dot(dot_radius), matrices, times_s)
        apart = point_b - point_a
        length = np.linalg.norm(apart, axis=1)
        direction = np.where(length[:, None] > 1e-12, apart / np.maximum(length, 1e-300)[:, None],
                             [1.0, 0.0, 0.0])
        matrices = np.broadcast_to(np.eye(4), (len(point_a), 4, 4)).copy()
        matrices[:, :3, :3] = _turning_x_to(direction)
        matrices[:, :3, 3] = point_a
        # the unit segment along x, stretched to the distance (a tiny one at contact)
        self._add_moving(f"{CLEARANCE_PATH}/segment", _unit_segment(), matrices, times_s,
                         np.maximum(length, 1e-9))

    def _add_moving(self, path: str, obj: dict[str, Any], matrices: np.ndarray,
                    times_s: np.ndarray, stretch: np.ndarray | None = None) -> None:
        """``obj`` at ``path``, placed by ``matrices`` (n, 4, 4) per sample and stretched
        along its x axis by ``stretch`` (n,)."""
        first = matrices[0].copy()
        if stretch is not None:
            first[:3, 0] *= stretch[0]
        self.commands.append(_set_object(path, obj))
        self.commands.append({"type": "set_transform", "path": path,
                              "matrix": _column_major(first)})
        if len(matrices) > 1:
            self.animations.append(_track(path, matrices, times_s, stretch))

    def animation_command(self) -> dict[str, Any] | None:
        """The one ``set_animation`` command (paused at the start), or None if nothing moves."""
        if not self.animations:
            return None
        return {"type": "set_animation", "animations": self.animations, "path": "",
                "options": {"play": False, "repetitions": 1}}


def _track(path: str, matrices: np.ndarray, times_s: np.ndarray,
           stretch: np.ndarray | None = None) -> dict[str, Any]:
    """A three.js clip moving the group at ``path`` through ``matrices`` (fps 1: seconds),
    and scaling it along x by ``stretch``."""
    times = _float32(times_s)
    positions = _float32(matrices[:, :3, 3].reshape(-1))
    quaternions = quaternion_from_matrix(matrices[:, :3, :3])  # x, y, z, w as three.js
    tracks = [{"name": ".position", "type": "vector3", "times": times, "values": positions},
              {"name": ".quaternion", "type": "quaternion", "times": times,
               "values": _float32(quaternions.reshape(-1))}]
    if stretch is not None:
        scales = np.ones((len(stretch), 3))
        scales[:, 0] = stretch
        tracks.append({"name": ".scale", "type": "vector3", "times": times,
                       "values": _float32(scales.reshape(-1))})
    return {"path": path, "clip": {"fps": 1, "name": "default", "tracks": tracks}}


def _turning_x_to(direction: np.ndarray) -> np.ndarray:
    """Rotations (n, 3, 3) whose x axis is the unit ``direction`` (n, 3)."""
    helper = np.where(np.abs(direction[:, 2:3]) < 0.9, [0.0, 0.0, 1.0], [1.0, 0.0, 0.0])
    y = np.cross(helper, direction)
    y /= np.linalg.norm(y, axis=1, keepdims=True)
    return np.stack([direction, y, np.cross(direction, y)], axis=2)


def _dot(radius: float) -> dict[str, Any]:
    return {"type": "Mesh",
            "geometry": {"type": "SphereGeometry", "radius": radius, "widthSegments": 16,
                         "heightSegments": 12},
            "material": {"type": "MeshBasicMaterial", "color": _CLEARANCE_COLOUR}}


def _unit_segment() -> dict[str, Any]:
    ends = np.array([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0]], np.float32)
    return {"type": "Line",
            "geometry": {"type": "BufferGeometry",
                         "data": {"attributes": {"position": _attribute(ends)}}},
            "material": {"type": "LineBasicMaterial", "color": _CLEARANCE_COLOUR,
                         "linewidth": 3}}


def _set_object(path: str, obj: dict[str, Any]) -> dict[str, Any]:
    """meshcat's ``set_object`` with a three.js JSON object (uuids made from the path)."""
    obj = dict(obj, uuid=f"{path}#object")
    lowered: dict[str, Any] = {"metadata": {"version": 4.5, "type": "Object"},
                               "object": obj}
    for kind, plural in (("geometry", "geometries"), ("material", "materials")):
        if kind in obj:
            content = dict(obj[kind], uuid=f"{path}#{kind}")
            lowered[plural] = [content]
            obj[kind] = content["uuid"]
    return {"type": "set_object", "path": path, "object": lowered}


def _axes(length: float) -> dict[str, Any]:
    """x, y, z axes as red, green, blue line segments of ``length`` metres."""
    ends = np.zeros((6, 3), np.float32)
    ends[[1, 3, 5], [0, 1, 2]] = length
    colours = np.repeat(np.eye(3, dtype=np.float32), 2, axis=0)
    geometry = {"type": "BufferGeometry", "data": {"attributes": {
        "position": _attribute(ends), "color": _attribute(colours)}}}
    return {"type": "LineSegments", "geometry": geometry,
            "material": {"type": "LineBasicMaterial", "vertexColors": True, "linewidth": 2}}


def msgpack() -> Any:
    """The ``umsgpack`` module (u-msgpack-python, in the ``view`` extra); without it an
    :class:`UnsupportedFeatureError` saying how to get it."""
    try:
        import umsgpack  # type: ignore[import-untyped]
    except ImportError:
        raise UnsupportedFeatureError('the 3-D page needs u-msgpack-python: pip install '
                                      '"pinframes[view]"') from None
    return umsgpack


def _attribute(values: np.ndarray) -> dict[str, Any]:
    """A three.js buffer attribute (rows are items) as meshcat packs it."""
    umsgpack = msgpack()
    codes = {np.dtype(np.float32): ("Float32Array", _FLOAT32),
             np.dtype(np.uint32): ("Uint32Array", 0x16)}
    name, code = codes[values.dtype]
    return {"itemSize": 1 if values.ndim == 1 else values.shape[1], "type": name,
            "array": umsgpack.Ext(code, np.ascontiguousarray(values).tobytes()),
            "normalized": False}


def _float32(values: np.ndarray) -> Any:
    return msgpack().Ext(_FLOAT32, np.ascontiguousarray(values, dtype=np.float32).tobytes())


def _column_major(matrix: np.ndarray) -> list[float]:
    return [float(value) for value in np.asarray(matrix).T.reshape(-1)]


def _hex_colour(rgba: np.ndarray) -> int:
    red, green, blue = (round(255 * float(channel)) for channel in rgba[:3])
    return (red << 16) + (green << 8) + blue
