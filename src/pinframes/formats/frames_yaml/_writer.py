"""Writing a :class:`~pinframes.FrameTree` as a Duckietown ``frames.yaml`` map layer.

A frame read from ``frames.yaml`` is written back as it was read (key, place in the file,
``relative_to``, unit, values) as long as its kept pose still matches the tree; a frame that
was moved, renamed above, or lost its ``relative_to`` target is written from the tree. Other
frames get ``relative_to: ~`` and their pose in their parent.
"""

from __future__ import annotations

import math
import os
from pathlib import Path
from typing import Any

import numpy as np
import yaml

from ...errors import PinframesError, UnsupportedFeatureError
from ...tree import FrameTree
from ...values.pose import Pose
from .._snapshot import one_instant
from .._writable import check_writable_tree, refuse_attached_data
from ..atomic import atomic_write
from ..limits import current_limits
from ._reader import METADATA_KEY
from ._schema import (
    POSE_FIELDS,
    TileSize,
    load_tile_maps,
    nearest_tile_size,
    tile_maps_beside,
    warn_layer,
)

__all__ = ["write_frames_yaml"]

_POSE_TOLERANCE = 1e-9
"""A kept pose still holds when no matrix entry moved by more (metres, or unitless)."""


def write_frames_yaml(tree: FrameTree, path: str | os.PathLike[str], time: Any = None, *,
                      slash_replacement: str | None = None) -> None:
    """Write ``tree`` as a Duckietown ``frames.yaml`` map layer, atomically.

    Parameters
    ----------
    tree : FrameTree
        The frames to write; the root is the map's origin and is not written. A frame's
        key is its parent's key plus ``/`` plus its name, unless its name already is such
        a key (``map_0/tile_0_0`` under ``map_0``), as for trees read from ``frames.yaml``.
    path : str or path-like
        The file to write. An existing file is replaced only when the write succeeds.
    time : None or time
        frames.yaml holds static poses: with None a tree whose poses move in time is
        refused; otherwise every pose is taken at this time (as for ``FrameTree.pose``).
    slash_replacement : None or str
        Written instead of each ``/`` of a name whose ``/`` would put the frame under
        another one (``robot/base_link`` under ``robot_base`` becomes the key
        ``robot_base/robot_base_link`` with ``"_"``); None refuses such names.

    Raises
    ------
    UnsupportedFeatureError
        A frame moves in time and ``time`` is None; a frame name holds ``/`` where its key
        would put it under another frame; two frames would get one key; data is attached
        to frames (frames.yaml cannot hold it).
    WriteError
        The file cannot be written.
    """
    check_writable_tree(tree, path)
    refuse_attached_data(tree, path, "frames.yaml")
    document = _document(tree, Path(path), time, slash_replacement)
    text = yaml.dump(document, Dumper=_Dumper, sort_keys=False, default_flow_style=False,
                     allow_unicode=True)
    with atomic_write(path, "w") as handle:
        handle.write(text)


def frame_keys(tree: FrameTree, slash_replacement: str | None = None) -> dict[str, str]:
    """The ``frames.yaml`` key of every frame but the root, by frame name."""
    keys: dict[str, str] = {}
    owners: dict[str, str] = {}
    for name in tree.frames[1:]:
        parent_key = keys.get(tree.parent(name) or "", "")
        head, _, last = name.rpartition("/")
        if last and (_kept(tree, name).get("key") == name or (head and head == parent_key)):
            segment = last
        elif "/" not in name:
            segment = name
        elif slash_replacement is not None and "/" not in slash_replacement:
            segment = name.replace("/", slash_replacement)
        else:
            where = f"under {parent_key!r}" if parent_key else "at the top level"
            raise UnsupportedFeatureError(
                f"the name holds '/', which frames.yaml keys use to mark the parent, but the "
                f"frame sits {where}: rename it, or pass slash_replacement='_' (pinframes "
                f"convert --slash-replacement _) to write it as {name.replace('/', '_')!r}",
                frame=name)
        key = f"{parent_key}/{segment}" if parent_key else segment
        if key.count("/") >= current_limits().max_depth:
            raise UnsupportedFeatureError(
                f"its key would have {key.count('/') + 1:,} path segments, more than "
                f"read_frames_yaml reads by default (max_depth="
                f"{current_limits().max_depth:,})", frame=name, field="key")
        if key in owners:
            raise UnsupportedFeatureError(
                f"frames {owners[key]!r} and {name!r} would both get the key {key!r}",
                frame=name)
        keys[name] = key
        owners[key] = name
    return keys


class _Writer:
    """Builds the ``frames`` mapping of one output file."""

    def __init__(self, tree: FrameTree, path: Path, time: Any,
                 slash_replacement: str | None) -> None:
        self.tree = tree
        self.path = path
        self.instant = one_instant(tree, time, path, "frames.yaml")
        self.keys = frame_keys(tree, slash_replacement)
        self.by_original_key = {
            kept["key"]: name for name in tree.frames[1:] if "key" in (kept := _kept(tree, name))}
        self.tiles_in_metres: list[str] = []
        self._tile_sizes: dict[str, TileSize] | None = None
        self._tile_maps_problem = ""

    def frames(self) -> dict[str, dict[str, Any]]:
        rows: list[tuple[float, int, str, dict[str, Any]]] = []
        dummies = []
        for position, name in enumerate(self.tree.frames[1:]):
            kept = _kept(self.tree, name)
            if kept.get("dummy"):
                dummies.append((position, name))
                continue
            entry = self.kept_entry(name, kept) if "entry" in kept else self.new_entry(name)
            rows.append((kept.get("index", math.inf), position, self.keys[name], entry))
        rows += self.needed_dummies(dummies, rows)
        rows.sort(key=lambda row: row[:2])
        return {key: entry for _, _, key, entry in rows}

    def new_entry(self, name: str) -> dict[str, Any]:
        return {"relative_to": None, "pose": _pose_fields(self.pose(name, None))}

    def kept_entry(self, name: str, kept: dict[str, Any]) -> dict[str, Any]:
        """The frame's entry as read, with the pose rewritten only if the tree moved it.

        Its ``relative_to`` follows a renamed target; a removed target falls back to the
        key parent (``~``). Tile units stay only while the output's ``tile_maps.yaml`` gives
        the same tile size.
        """
        entry = dict(kept["entry"])
        target = kept["relative_to"]
        if target is not None:
            target = self.by_original_key.get(target, target if target in self.tree else None)
            entry["relative_to"] = None if target is None else self.keys[target]
        pose = self.pose(name, target)
        unchanged = (target is not None or kept["relative_to"] is None) and np.allclose(
            pose.matrix, kept["pose_in_relative_to"].matrix, rtol=0.0, atol=_POSE_TOLERANCE)
        if unchanged and entry.get("unit") == "tiles" and (
                self.tile_size(name) != kept["tile_size"]):
            self.tiles_in_metres.append(name)
            unchanged = False
        if not unchanged:
            entry["pose"] = _pose_fields(pose)
            if entry.get("unit") == "tiles":
                del entry["unit"]
        return entry

    def needed_dummies(self, dummies: list[tuple[int, str]], rows: list) -> list:
        """Rows for dummy frames that a reader would not recreate at the same pose."""
        written = {key for _, _, key, _ in rows}
        targets = {entry.get("relative_to") for *_, entry in rows}
        extra = []
        for position, name in reversed(dummies):
            key = self.keys[name]
            pose = self.pose(name, None)
            implied = key in targets or any(other.startswith(key + "/") for other in written)
            if not (implied and np.allclose(pose.matrix, np.eye(4), rtol=0.0,
                                            atol=_POSE_TOLERANCE)):
                extra.append((math.inf, position, key, {"relative_to": None,
                                                        "pose": _pose_fields(pose)}))
                written.add(key)
        return extra

    def pose(self, name: str, relative_to: str | None) -> Pose:
        """The static pose of ``name`` in ``relative_to`` (None: its parent)."""
        relative_to = self.tree.parent(name) if relative_to is None else relative_to
        if self.instant.time is None:  # nothing in the tree moves
            return self.tree.pose(name, relative_to)
        sampled = self.tree.pose(name, relative_to, times=[self.instant.time])
        return Pose(sampled.translation.reshape(-1, 3)[0], sampled.rotation.reshape(-1, 3, 3)[0])

    def tile_size(self, name: str) -> TileSize | None:
        """The tile size a reader of the output file would use for frame ``name``."""
        if self._tile_sizes is None:
            beside = tile_maps_beside(self.path)
            self._tile_sizes = {}
            if not beside.is_file():
                self._tile_maps_problem = " (no such file)"
            else:
                try:
                    self._tile_sizes = load_tile_maps(beside)
                except PinframesError as exc:
                    self._tile_maps_problem = f" ({exc})"
        return nearest_tile_size(self.keys[name], self._tile_sizes)

    def warn_about_tiles(self) -> None:
        """One warning for the ``unit: tiles`` frames that had to be written in metres."""
        if self.tiles_in_metres:
            warn_layer(os.fspath(self.path), None, (
                f"{len(self.tiles_in_metres)} 'unit: tiles' frames (first "
                f"{self.tiles_in_metres[0]!r}) are written in metres: "
                f"{tile_maps_beside(self.path)} does not give them their tile size"
                f"{self._tile_maps_problem}"))


def _document(tree: FrameTree, path: Path, time: Any, slash_replacement: str | None
              ) -> dict[str, Any]:
    kept = tree.metadata.get(METADATA_KEY, {})
    document = dict(kept.get("top_level", {"version": 1.0, "frames": None}))
    writer = _Writer(tree, path, time, slash_replacement)
    document["frames"] = writer.frames()
    writer.warn_about_tiles()
    return document


def _kept(tree: FrameTree, name: str) -> dict[str, Any]:
    """What the frames.yaml reader kept for frame ``name`` (empty for other frames)."""
    return tree.frame_metadata(name).get(METADATA_KEY, {})


def _pose_fields(pose: Pose) -> dict[str, float]:
    """All six pose fields of a static pose, metres and radians (no negative zeros)."""
    return {field: float(value) + 0.0 for field, value in zip(POSE_FIELDS, pose.to_xyz_rpy(),
                                                                strict=True)}


class _Dumper(yaml.SafeDumper):
    """Writes ``~`` for unset values, as the Duckietown documentation does."""


_Dumper.add_representer(type(None), lambda dumper, _: dumper.represent_scalar(
    "tag:yaml.org,2002:null", "~"))
