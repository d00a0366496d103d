"""How deep a weldx ``di_graph`` may nest, and room on Python's stack for asdf to walk it.

In ``coordinate_system_hierarchy-0.1.0`` every frame is nested inside its parent's node
(``di_node`` -> ``edges`` -> ``di_edge`` -> ``target_node``). asdf walks, writes and
validates that YAML recursively, about 28 Python calls per frame (measured, asdf 6.0), so a
chain of 40 frames already exceeds Python's default recursion limit. :func:`recursion_room`
raises the limit for one asdf call, by a bounded amount; graphs deeper than
:data:`MAX_GRAPH_DEPTH` frames are refused with :func:`too_deep`. The limit is process-wide:
another thread recursing meanwhile gets the same higher limit.
"""

from __future__ import annotations

import contextlib
import os
import sys
from collections.abc import Iterable, Iterator

import yaml

from ...errors import UnsupportedFeatureError

__all__ = ["MAX_GRAPH_DEPTH", "deepest_frame", "deepest_frame_in_yaml", "recursion_room",
           "too_deep"]

MAX_GRAPH_DEPTH = 400
_CALLS_PER_LEVEL = 32
_NODE_TAG = "core/graph/di_node-"


@contextlib.contextmanager
def recursion_room(depth: int) -> Iterator[None]:
    """Within this block Python recurses ``depth`` (at most MAX_GRAPH_DEPTH) frames deeper."""
    old = sys.getrecursionlimit()
    sys.setrecursionlimit(old + min(depth, MAX_GRAPH_DEPTH) * _CALLS_PER_LEVEL)
    try:
        yield
    finally:
        sys.setrecursionlimit(old)


def deepest_frame(frames: Iterable[tuple[str, str]]) -> tuple[str | None, int]:
    """``(frame, depth)`` of the deepest of ``(frame, parent)`` pairs given parents first;
    the root (never listed as a frame) has depth 0; ``(None, 0)`` for no frames."""
    depths: dict[str, int] = {}
    deepest, most = None, 0
    for name, parent in frames:
        depths[name] = depths.get(parent, 0) + 1
        if depths[name] > most:
            deepest, most = name, depths[name]
    return deepest, most


def too_deep(frame: str | None, depth: int, file: str | os.PathLike[str]
             ) -> UnsupportedFeatureError:
    """The error for a graph nesting ``frame`` ``depth`` frames below its root."""
    return UnsupportedFeatureError(
        f"frame {frame!r} lies {depth} frames below the root; in the weldx 0.1.0 format "
        f"frames nest in their parents, and pinframes handles at most {MAX_GRAPH_DEPTH} "
        "levels: write the tree with schema=\"1.0.0\", which lists frames flat",
        file=file, frame=frame, field="graph.root_node")


def deepest_frame_in_yaml(path: str | os.PathLike[str]) -> tuple[str | None, int]:
    """``(name, depth)`` of the most deeply nested ``di_node`` in an ASDF file's YAML, found
    from the YAML events without building (or recursing into) the tree; the root node has
    depth 0 and ``(None, 0)`` means no node."""
    with open(path, "rb") as handle:
        text = handle.read().split(b"\n...", 1)[0]
    deepest, most = None, -1
    open_nodes: list[list] = []  # per open collection: [is a node, items seen, last key]
    depth = -1
    for event in _events(text):
        if isinstance(event, yaml.NodeEvent) and open_nodes and open_nodes[-1][1] is not None:
            entry = open_nodes[-1]
            if entry[0] and entry[1] % 2 == 1 and entry[2] == "name" and depth > most:
                deepest, most = getattr(event, "value", None), depth
            entry[2] = getattr(event, "value", None) if entry[1] % 2 == 0 else None
            entry[1] += 1
        if isinstance(event, yaml.CollectionStartEvent):
            is_node = _NODE_TAG in (event.tag or "")
            depth += is_node
            items = 0 if isinstance(event, yaml.MappingStartEvent) else None
            open_nodes.append([is_node, items, None])
        elif isinstance(event, yaml.CollectionEndEvent):
            depth -= open_nodes.pop()[0]
    return deepest, max(most, 0)


def _events(text: bytes) -> Iterator[yaml.Event]:
    """The YAML events of ``text``, up to the first YAML error if any."""
    with contextlib.suppress(yaml.YAMLError):
        yield from yaml.parse(text, Loader=yaml.SafeLoader)
