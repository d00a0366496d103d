"""The fields of a Duckietown ``frames.yaml`` map layer and of its ``tile_maps.yaml``.

A layer is ``{version: str | float, frames: {key: Frame}}``; a Frame is ``relative_to``
(a key, ``~`` or ``''``: unset), ``unit`` (``meters``, ``tiles`` or unset), ``pose``
(``x y z`` and ``roll pitch yaw``, each optional, 0 when missing) and an optional ``twist``.
This module checks those values and hands them on as :class:`Entry` records; it knows
nothing of trees (see docs/frames-yaml.md).
"""

from __future__ import annotations

import math
import os
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from ...errors import FileFormatError, FramesYamlWarning, warn_at_caller
from .._yaml_loader import KeyPath
from ..reading import InputFile

__all__ = [
    "POSE_FIELDS",
    "TILE_MAPS_FILE",
    "Entry",
    "FramesYamlWarning",
    "TileSize",
    "finite_number",
    "is_frames_yaml",
    "is_frames_yaml_name",
    "key_ancestors",
    "key_parent",
    "load_tile_maps",
    "locate_in",
    "nearest_tile_size",
    "parse_layer",
    "tile_maps_beside",
    "warn_layer",
]

POSE_FIELDS = ("x", "y", "z", "roll", "pitch", "yaw")
"""Pose fields: position in metres (or tiles for x, y), then URDF roll, pitch, yaw in radians."""
TWIST_FIELDS = ("v_x", "v_y", "v_z", "w_x", "w_y", "w_z")
FRAME_FIELDS = ("relative_to", "unit", "pose", "twist")
UNITS = ("meters", "tiles")
TILE_MAPS_FILE = "tile_maps.yaml"

TileSize = tuple[float, float]
"""Tile size along x and y, metres."""


@dataclass(frozen=True)
class Entry:
    """One frame of a ``frames.yaml`` file, checked but not yet placed in a tree.

    Attributes
    ----------
    key : str
        The frame's key, as written (``map_0/tile_0_0``).
    index : int
        Its position among the file's frames.
    raw : dict
        The frame's mapping exactly as read (kept to write it back).
    relative_to : str or None
        The key its pose is expressed in; None for ``~``, ``''`` or a missing field,
        meaning the key parent.
    unit : str or None
        ``"meters"``, ``"tiles"`` or None (metres).
    values : dict of str to float
        The six pose fields as written, missing ones 0; x and y in tiles for ``unit: tiles``.
    """

    key: str
    index: int
    raw: dict[str, Any]
    relative_to: str | None
    unit: str | None
    values: dict[str, float]


def key_parent(key: str) -> str | None:
    """The key of the parent (``a/b`` for ``a/b/c``), None at the top level."""
    head, _, _ = key.rpartition("/")
    return head or None


def is_frames_yaml_name(path: Path) -> bool:
    """Whether the file name says frames.yaml: it starts with ``frames``
    (``frames.yaml``, ``frames_map.yaml``), whatever the case."""
    return path.name.lower().startswith("frames")


def is_frames_yaml(source: InputFile) -> bool:
    """Whether ``source`` is a frames.yaml layer (the format's content test): its name says
    so (:func:`is_frames_yaml_name`), or it is a YAML mapping with a ``frames`` key that is
    no list (a list of frames is a scene's)."""
    if is_frames_yaml_name(source.path):
        return True
    document = source.yaml()
    return (isinstance(document, dict) and "frames" in document
            and not isinstance(document["frames"], list))


def key_ancestors(key: str) -> list[str]:
    """Ancestor keys, nearest first (``a/b``, ``a`` for ``a/b/c``)."""
    parts = key.split("/")
    return ["/".join(parts[:end]) for end in range(len(parts) - 1, 0, -1)]


def locate_in(section: str):
    """A locator for :meth:`~pinframes.formats.reading.InputFile.yaml`:
    ``section.<key>.<field>``."""

    def locate(path: KeyPath) -> tuple[str | None, str | None]:
        if len(path) >= 2 and path[0] == section:
            rest = ".".join(str(part) for part in path[2:])
            return str(path[1]), rest or None
        return None, ".".join(str(part) for part in path) or None

    return locate


def parse_layer(document: Any, file: str) -> tuple[dict[str, Any], list[Entry]]:
    """Check a loaded ``frames.yaml`` document.

    Returns
    -------
    top_level : dict
        The top-level entries in file order, with ``frames`` mapped to None.
    entries : list of Entry
        The frames in file order.
    """
    if not isinstance(document, dict):
        raise FileFormatError(
            f"expected a mapping with 'version' and 'frames', got {_kind(document)}", file=file)
    if "frames" not in document:
        hint = (" (this looks like a main.yaml, which includes the layers: read the "
                "frames.yaml it names)") if "main" in document else ""
        raise FileFormatError(f"no 'frames' mapping{hint}", file=file, field="frames")
    version = document.get("version")
    if "version" in document and (isinstance(version, bool)
                                  or not isinstance(version, str | int | float)):
        raise FileFormatError(f"expected a string or a number, got {_kind(version)}",
                              file=file, field="version")
    for name in document:
        if name not in ("version", "frames"):
            warn_layer(file, None, f"unknown top-level field {name!r} is kept but not used")
    frames = document["frames"]
    if not isinstance(frames, dict):
        scene = (" (a list of frames is a pinframes scene's: does the file lack its first "
                 "line 'pinframes_scene: 1'?)" if isinstance(frames, list) else "")
        raise FileFormatError(f"expected a mapping of keys to frames, got {_kind(frames)}"
                              + scene, file=file, field="frames")
    top_level = {name: (None if name == "frames" else value) for name, value in document.items()}
    return top_level, [_entry(key, index, raw, file) for index, (key, raw) in
                       enumerate(frames.items())]


def _entry(key: Any, index: int, raw: Any, file: str) -> Entry:
    if not isinstance(key, str) or not key or "" in key.split("/"):
        raise FileFormatError("a key must be a non-empty string of '/'-separated names, got "
                              f"{key!r}", file=file, frame=str(key))
    if not isinstance(raw, dict):
        raise FileFormatError(f"expected a mapping with relative_to and pose, got {_kind(raw)}",
                              file=file, frame=key)
    for field in raw:
        if field not in FRAME_FIELDS:
            warn_layer(file, key, f"unknown field {field!r} is kept but not used")
    relative_to = raw.get("relative_to")
    if relative_to is not None and not isinstance(relative_to, str):
        raise FileFormatError(f"expected a frame key, ~ or '', got {_kind(relative_to)}",
                              file=file, frame=key, field="relative_to")
    if relative_to == key:
        raise FileFormatError("a frame cannot be relative to itself", file=file, frame=key,
                              field="relative_to")
    unit = raw.get("unit")
    if unit is not None and unit not in UNITS:
        raise FileFormatError(f"expected one of {', '.join(UNITS)} or ~, got {unit!r}",
                              file=file, frame=key, field="unit")
    values = _numbers(raw, "pose", POSE_FIELDS, file, key)
    _numbers(raw, "twist", TWIST_FIELDS, file, key)
    return Entry(key, index, raw, relative_to or None, unit, values)


def _numbers(raw: dict, name: str, fields: tuple[str, ...], file: str, key: str
             ) -> dict[str, float]:
    """The numeric sub-fields of ``raw[name]`` (missing: 0), each checked finite."""
    group = raw.get(name, {})
    if not isinstance(group, dict):
        raise FileFormatError(f"expected a mapping of {', '.join(fields)}, got {_kind(group)}",
                              file=file, frame=key, field=name)
    for field in group:
        if field not in fields:
            warn_layer(file, key, f"unknown field '{name}.{field}' is kept but not used")
    return {field: finite_number(group.get(field, 0), file, key, f"{name}.{field}")
            for field in fields}


def finite_number(value: Any, file: str, frame: str | None, field: str) -> float:
    """``value`` as a float; an error naming the field unless it is a finite int or float."""
    if isinstance(value, bool) or not isinstance(value, int | float):
        raise FileFormatError(f"expected a number, got {_kind(value)}", file=file, frame=frame,
                              field=field)
    try:
        number = float(value)
    except OverflowError:
        raise FileFormatError(f"expected a finite number, got an integer of {len(str(value))} "
                              "digits", file=file, frame=frame, field=field) from None
    if not math.isfinite(number):
        raise FileFormatError(f"expected a finite number, got {value!r}", file=file,
                              frame=frame, field=field)
    return number


def load_tile_maps(path: str | os.PathLike[str]) -> dict[str, TileSize]:
    """Tile sizes in metres by map key, from a ``tile_maps.yaml`` file."""
    file = os.fspath(path)
    document = InputFile(file).yaml(locate_in("tile_maps"))
    maps = document.get("tile_maps") if isinstance(document, dict) else None
    if not isinstance(maps, dict):
        raise FileFormatError("expected a 'tile_maps' mapping of map keys to tile sizes",
                              file=file, field="tile_maps")
    sizes = {}
    for key, entry in maps.items():
        size = entry.get("tile_size") if isinstance(entry, dict) else None
        if not isinstance(size, dict):
            raise FileFormatError("expected a 'tile_size' mapping with x and y", file=file,
                                  frame=str(key), field="tile_size")
        x, y = (finite_number(size.get(axis), file, str(key), f"tile_size.{axis}")
                for axis in "xy")
        if x <= 0 or y <= 0:
            raise FileFormatError(f"tile sizes must be positive, got x={x}, y={y}", file=file,
                                  frame=str(key), field="tile_size")
        sizes[str(key)] = (x, y)
    return sizes


def nearest_tile_size(key: str, sizes: dict[str, TileSize]) -> TileSize | None:
    """The tile size of the nearest key ancestor of ``key`` listed in ``sizes``."""
    for ancestor in key_ancestors(key):
        if ancestor in sizes:
            return sizes[ancestor]
    return None


def tile_maps_beside(file: str | os.PathLike[str]) -> Path:
    """Where the ``tile_maps.yaml`` of a ``frames.yaml`` file is: in the same folder."""
    return Path(file).with_name(TILE_MAPS_FILE)


def warn_layer(file: str, frame: str | None, message: str) -> None:
    """Warn with a :class:`FramesYamlWarning` that names the file and frame."""
    where = f"{file}: frame {frame!r}" if frame is not None else file
    warn_at_caller(f"{where}: {message}", FramesYamlWarning)


def _kind(value: Any) -> str:
    """How an unexpected value is named in messages."""
    if value is None:
        return "nothing (~)"
    if isinstance(value, dict | list):
        return f"a {type(value).__name__}"
    return f"{type(value).__name__} {value!r}"
