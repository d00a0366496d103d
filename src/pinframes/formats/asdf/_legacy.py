"""The legacy weldx hierarchy, ``coordinate_system_hierarchy-1.0.0`` (weldx up to 0.4).

``coordinate_systems`` is a flat list of transformations ``name`` in ``reference_system``, in
any order, and an edge that was defined parent-in-child appears with the two swapped: the
tree is rebuilt from ``root_system_name``, accepting either end of an entry as the one
already known (docs/asdf-format.md). ``subsystems`` lists all nesting levels. weldx 0.4's
``spatial_data`` list of ``{coordinate_system, name, data}`` is read by ``_data``.
"""

from __future__ import annotations

from collections import deque
from typing import Any

from ...errors import FileFormatError
from ._data import read_data
from ._decode import as_list, required
from ._hierarchy import Hierarchy, read_header, read_subsystem
from ._lcs import pose_from_lcs

__all__ = ["read_legacy_hierarchy"]


def read_legacy_hierarchy(node: Any) -> Hierarchy:
    """The hierarchy of a ``coordinate_system_hierarchy-1.0.0`` node."""
    root = str(required(node, "root_system_name", "root_system_name"))
    hierarchy = read_header(node, root)
    entries = [_entry(item, index) for index, item in
               enumerate(as_list(required(node, "coordinate_systems", "coordinate_systems"),
                               "coordinate_systems"))]
    hierarchy.frames = _frames_from_root(root, entries)
    hierarchy.subsystems = [
        read_subsystem(item, f"subsystems[{index}]", root_key="root_cs",
                       parent_key="parent_system", nested_key="subsystem_names")
        for index, item in enumerate(as_list(node.get("subsystems") or [], "subsystems"))]
    for index, item in enumerate(as_list(node.get("spatial_data") or [], "spatial_data")):
        field = f"spatial_data[{index}]"
        frame = str(required(item, "coordinate_system", field))
        name = str(required(item, "name", field))
        hierarchy.data.append((name, frame, read_data(required(item, "data", field), frame,
                                                      name, field)))
    return hierarchy


def _entry(item: Any, index: int) -> tuple[str, str, Any, str]:
    """``(name, reference_system, transformation, field)`` of one list entry."""
    field = f"coordinate_systems[{index}]"
    return (str(required(item, "name", field)),
            str(required(item, "reference_system", field)),
            required(item, "transformation", field), f"{field}.transformation")


def _frames_from_root(root: str, entries: list[tuple[str, str, Any, str]]) -> list:
    touching: dict[str, list[int]] = {}
    for index, (name, reference, _, _) in enumerate(entries):
        touching.setdefault(name, []).append(index)
        touching.setdefault(reference, []).append(index)
    known = {root}
    used: set[int] = set()
    frames = []
    queue = deque([root])
    while queue:
        parent = queue.popleft()
        for index in touching.get(parent, []):
            if index in used:
                continue
            used.add(index)
            name, reference, transformation, field = entries[index]
            child = name if reference == parent else reference
            if child in known:
                raise FileFormatError(
                    f"the entry {name!r} in {reference!r} closes a loop: both frames are "
                    "already connected to the root", frame=name, field=field)
            pose = pose_from_lcs(transformation, name, field)
            frames.append((child, parent, pose if reference == parent else pose.inverse()))
            known.add(child)
            queue.append(child)
    unreachable = [entries[index] for index in range(len(entries)) if index not in used]
    if unreachable:
        name, reference, _, field = unreachable[0]
        raise FileFormatError(
            f"the entry {name!r} in {reference!r} is not connected to the root system "
            f"{root!r}", frame=name, field=field.rsplit(".", 1)[0])
    return frames
