"""Composing YAML within the reader limits: nodes and nesting counted as they are composed.

PyYAML's composer keeps an alias as a second reference to its anchor's node, so a document
of a few hundred bytes can describe billions of nodes (each level of aliases doubling or
tenfolding the last), or a node that contains itself; and a document of millions of plain
nodes takes its composer minutes and gigabytes. :class:`BoundedLoader` counts every node
as it is composed, an alias as all the nodes its anchor holds, and stops at the node that
breaks ``max_yaml_nodes`` (or ``max_depth``), or at an alias inside its own anchor, before
anything more is composed, constructed, formatted or validated. Every YAML that pinframes
reads (scenes, frames.yaml, tile maps, the YAML part of ASDF files) is composed here.
"""

from __future__ import annotations

import os
from typing import Any

import yaml

from ..errors import FileFormatError
from .limits import current_limits, exceeded

__all__ = ["BoundedLoader"]


class BoundedLoader(yaml.SafeLoader):
    """A safe loader whose composer refuses, as it goes, a document that (aliases expanded)
    holds more than ``max_yaml_nodes`` nodes or, with ``depth``, nests more than
    ``max_depth`` levels (:class:`pinframes.Limits`), or a node that contains itself.

    Parameters
    ----------
    stream : str or bytes
        The YAML text.
    file : path or None
        Named in the errors.
    depth : bool
        Whether ``max_depth`` applies (the YAML of an ASDF file is bounded otherwise).
    """

    def __init__(self, stream: str | bytes, file: str | os.PathLike[str] | None = None, *,
                 depth: bool = True) -> None:
        super().__init__(stream)
        limits = current_limits()
        self.file = None if file is None else os.fspath(file)
        self._max_nodes = limits.max_yaml_nodes
        self._max_depth = limits.max_depth if depth else None
        self._nodes = 0  # composed so far, aliases expanded
        self._level = 0  # of the node being composed (the document's root is level 1)
        self._reach = 0  # deepest level composed so far in the open anchored node
        self._open_anchors: set[str] = set()
        self._anchored: dict[str, tuple[int, int]] = {}  # anchor: (nodes, levels) expanded

    def compose_node(self, parent: Any, index: Any) -> Any:
        """The next node, counted; see the class docstring (PyYAML calls this for every node,
        and it recurses through ``compose_sequence_node`` and ``compose_mapping_node``)."""
        event = self.peek_event()
        if isinstance(event, yaml.AliasEvent):
            return self._alias(event, parent, index)
        anchor = event.anchor
        if anchor is not None and anchor in self.anchors:
            raise yaml.composer.ComposerError(
                f"found duplicate anchor {anchor!r}; first occurrence",
                self.anchors[anchor].start_mark, "second occurrence", event.start_mark)
        first = self._nodes
        self._count(1, self._level + 1, event.start_mark)
        self._level += 1
        outer_reach = self._reach
        if anchor is not None:
            self._open_anchors.add(anchor)
            self._reach = self._level
        self.descend_resolver(parent, index)
        node: yaml.Node
        if isinstance(event, yaml.ScalarEvent):
            node = self.compose_scalar_node(anchor)
        elif isinstance(event, yaml.SequenceStartEvent):
            node = self.compose_sequence_node(anchor)
        else:
            node = self.compose_mapping_node(anchor)
        self.ascend_resolver()
        if anchor is not None:
            self._open_anchors.discard(anchor)
            self._anchored[anchor] = (self._nodes - first, self._reach - self._level + 1)
            self._reach = max(outer_reach, self._reach)
        self._level -= 1
        return node

    def compose_document(self) -> Any:
        node = super().compose_document()
        self._anchored = {}
        return node

    def _alias(self, event: yaml.AliasEvent, parent: Any, index: Any) -> Any:
        """The node an alias repeats, counted as every node it holds, once more."""
        anchor = event.anchor
        assert anchor is not None  # an alias names its anchor
        if anchor in self._open_anchors:
            raise FileFormatError(f"the YAML node at {_line(self.anchors[anchor])} contains "
                                  "itself (an alias inside its own anchor)", file=self.file)
        node = super().compose_node(parent, index)  # an undefined alias is PyYAML's error
        nodes, levels = self._anchored[anchor]
        self._count(nodes, self._level + levels, event.start_mark)
        return node

    def _count(self, nodes: int, deepest: int, mark: Any) -> None:
        """Add ``nodes`` composed nodes reaching level ``deepest``; refuse past a limit."""
        self._nodes += nodes
        self._reach = max(self._reach, deepest)
        if self._nodes > self._max_nodes:
            raise exceeded("max_yaml_nodes", f"the YAML holds more than {self._max_nodes:,} "
                           f"nodes by {_line(mark)} (an alias counts the nodes it repeats, "
                           "each time it is used)").located(file=self.file)
        if self._max_depth is not None and deepest > self._max_depth:
            raise exceeded("max_depth", f"the YAML at {_line(mark)} nests more than "
                           f"{self._max_depth:,} levels deep").located(file=self.file)


def _line(where: Any) -> str:
    """``line N`` of a node or a mark."""
    mark = getattr(where, "start_mark", where)
    return f"line {mark.line + 1}" if mark is not None else "document"
