"""The weldx 0.5 to 0.8 hierarchy, ``coordinate_system_hierarchy-0.1.0`` with a ``di_graph``.

The graph's ``root_node`` is the root frame; each node lists ``edges`` to its children. Under
node P with target C, a ``bwd`` edge holds the pose of C in P, a ``fwd`` edge the pose of P
in C (inverted here). ``subsystems`` nest; each is kept with the node it shares with the
hierarchy it was merged into (``common_node``) as its root (docs/asdf-format.md). Data attached to
nodes (``attributes.data``) is read by ``_data``.
"""

from __future__ import annotations

from typing import Any

from ...errors import FileFormatError
from ...values.pose import Pose
from ...values.subsystem import Subsystem
from ._data import read_data
from ._decode import as_list, required
from ._hierarchy import Hierarchy, read_header, read_subsystem
from ._lcs import pose_from_lcs

__all__ = ["read_digraph_hierarchy"]

_DIRECTIONS = ("bwd", "fwd")


def read_digraph_hierarchy(node: Any) -> Hierarchy:
    """The hierarchy of a ``coordinate_system_hierarchy-0.1.x`` node."""
    graph = required(node, "graph", "graph")
    root_node = required(graph, "root_node", "graph")
    hierarchy = read_header(node, _node_name(root_node, None, "graph.root_node"))
    hierarchy.frames, hierarchy.data = _frames_depth_first(root_node)
    hierarchy.subsystems = _subsystems(node.get("subsystems") or [], hierarchy.name,
                                       "subsystems")
    return hierarchy


def _frames_depth_first(root_node: Any) -> tuple[list, list]:
    """``(frame, parent, pose)`` for every edge, parents first, in file order, and
    ``(name, frame, data)`` for the data of every node.

    Errors on an edge name the frame it leads to, with fields starting at ``edge``.
    """
    frames, data = [], []
    seen: set[str] = set()
    stack: list[tuple[Any, str | None, Any, str]] = [(root_node, None, None, "graph.root_node")]
    while stack:
        node, parent, edge, field = stack.pop()
        name = _node_name(node, parent, field)
        if name in seen:
            raise FileFormatError("the frame appears twice in the graph", frame=name,
                                  field="edge.target_node")
        seen.add(name)
        if parent is not None:
            frames.append((name, parent, _edge_pose(edge, name)))
        attributes = node.get("attributes")
        sets = attributes.get("data") if isinstance(attributes, dict) else None
        for key, value in (sets.items() if isinstance(sets, dict) else ()):
            data.append((str(key), name, read_data(value, name, str(key), "attributes.data")))
        edges = as_list(node.get("edges") or [], "edges")
        for index in reversed(range(len(edges))):
            try:
                target = required(edges[index], "target_node", f"edges[{index}]")
            except FileFormatError as exc:
                raise exc.located(frame=name) from None
            stack.append((target, name, edges[index], f"edges[{index}].target_node"))
    return frames, data


def _edge_pose(edge: Any, child: str) -> Pose:
    """The pose of ``child`` in its parent stored on ``edge``."""
    try:
        direction = required(edge, "direction", "edge")
        if not isinstance(direction, str) or direction not in _DIRECTIONS:
            raise FileFormatError(f"expected 'bwd' or 'fwd', got {direction!r}",
                                  field="edge.direction")
        transformation = required(required(edge, "attributes", "edge"), "transformation",
                                  "edge.attributes")
    except FileFormatError as exc:
        raise exc.located(frame=child) from None
    pose = pose_from_lcs(transformation, child, "edge.attributes.transformation")
    return pose if direction == "bwd" else pose.inverse()


def _subsystems(items: Any, parent: str, field: str) -> list[Subsystem]:
    """Every subsystem of ``items`` and those nested in them, depth first."""
    found = []
    for index, item in enumerate(as_list(items, field)):
        here = f"{field}[{index}]"
        nested = as_list(item.get("subsystems") or [], f"{here}.subsystems") \
            if isinstance(item, dict) else []
        subsystem = read_subsystem(
            item, here, root_key="common_node", parent=parent,
            nested=tuple(str(required(inner, "name", f"{here}.subsystems")) for inner in nested))
        found.append(subsystem)
        found.extend(_subsystems(nested, subsystem.name, f"{here}.subsystems"))
    return found


def _node_name(node: Any, parent: str | None, field: str) -> str:
    """A node's name; errors name the parent frame and the edge (or the root node)."""
    try:
        return str(required(node, "name", field))
    except FileFormatError as exc:
        raise exc.located(frame=parent) from None
