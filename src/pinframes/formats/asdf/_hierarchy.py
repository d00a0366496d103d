"""What a weldx hierarchy holds, whatever its generation, and the FrameTree built from it."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ...errors import FileFormatError, PinframesError
from ...tree import FrameTree
from ...values.pose import Pose
from ...values.spatial_data import SpatialData
from ...values.subsystem import Subsystem
from ._decode import as_list, required, timestamp

__all__ = ["Hierarchy", "read_header", "read_subsystem"]


@dataclass
class Hierarchy:
    """A hierarchy as read from a file, before it becomes a tree.

    Attributes
    ----------
    name : str
        The hierarchy's name.
    root : str
        Its root frame.
    reference_time : numpy.datetime64 or None
        Its reference time.
    frames : list of (frame, parent, pose_frame_in_parent)
        Every frame but the root, each after its parent.
    subsystems : list of Subsystem
        The merged subsystems, all nesting levels.
    data : list of (name, frame, SpatialData)
        Data attached to frames, in file order.
    """

    name: str
    root: str
    reference_time: np.datetime64 | None = None
    frames: list[tuple[str, str, Pose]] = field(default_factory=list)
    subsystems: list[Subsystem] = field(default_factory=list)
    data: list[tuple[str, str, SpatialData]] = field(default_factory=list)

    def to_tree(self) -> FrameTree:
        """A new :class:`FrameTree` holding every frame and subsystem."""
        try:
            tree = FrameTree(self.root, self.name, self.reference_time)
        except PinframesError as exc:
            raise exc.located(frame=str(self.root)) from None
        for name, parent, pose in self.frames:
            try:
                tree.add(name, parent, pose)
            except PinframesError as exc:
                raise exc.located(frame=str(name)) from None
        for name, frame, data in self.data:
            try:
                tree.assign_data(name, data, frame)
            except PinframesError as exc:
                raise exc.located(frame=str(frame), field=f"data.{name}") from None
        for subsystem in self.subsystems:
            _check_subsystem(subsystem, tree)
        tree.subsystems = list(self.subsystems)
        return tree


def _check_subsystem(subsystem: Subsystem, tree: FrameTree) -> None:
    for part, names in (("root", (subsystem.root,)), ("members", subsystem.members)):
        missing = [name for name in names if name not in tree]
        if missing:
            raise FileFormatError(
                f"subsystem {subsystem.name!r} names frames the hierarchy does not hold: "
                f"{', '.join(map(repr, missing))}", frame=missing[0],
                field=f"subsystems.{part}")


def read_subsystem(item: Any, field: str, *, root_key: str, parent_key: str | None = None,
                   parent: str | None = None, nested_key: str | None = None,
                   nested: tuple[str, ...] = ()) -> Subsystem:
    """One subsystem entry: its ``name``, root frame under ``root_key``, ``members``,
    ``reference_time`` and ``data`` names; its parent and nested subsystem names under the
    given keys, or as given."""
    name = str(required(item, "name", field))
    root = str(required(item, root_key, field))
    if parent_key is not None and item.get(parent_key) is not None:
        parent = str(item[parent_key])
    if nested_key is not None:
        nested = tuple(map(str, as_list(item.get(nested_key) or [], f"{field}.{nested_key}")))
    reference = item.get("reference_time")
    return Subsystem(
        name, root, tuple(map(str, as_list(item.get("members") or [], f"{field}.members"))),
        parent, None if reference is None else timestamp(reference, f"{field}.reference_time"),
        nested, tuple(map(str, as_list(item.get("data") or [], f"{field}.data"))))


def read_header(node: Any, root: str) -> Hierarchy:
    """A hierarchy with the ``name`` and ``reference_time`` of ``node``, rooted at ``root``."""
    reference = node.get("reference_time")
    return Hierarchy(str(required(node, "name", "name")), root,
                     None if reference is None else timestamp(reference, "reference_time"))
