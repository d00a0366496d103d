"""The size of a composed YAML document with its aliases expanded, found without expanding.

PyYAML's composer keeps an alias as a second reference to its anchor's node, so a document
of a few hundred bytes can describe billions of nodes (each level of aliases doubling or
tenfolding the last), or a node that contains itself. :func:`check_yaml_size` walks the
node graph once, each distinct node once, and refuses both before anything constructs,
formats or validates the data.
"""

from __future__ import annotations

import os

import yaml

from ..errors import FileFormatError
from .limits import current_limits, exceeded

__all__ = ["check_yaml_size"]


def check_yaml_size(root: yaml.Node, file: str | os.PathLike[str] | None = None, *,
                    depth: bool = True) -> None:
    """Refuse ``root`` if it contains itself, or if expanded it exceeds
    ``max_yaml_nodes`` nodes or (with ``depth``) ``max_depth`` levels
    (:mod:`pinframes.limits`)."""
    limits = current_limits()
    size: dict[int, int] = {}
    levels: dict[int, int] = {}
    visiting: set[int] = set()
    stack: list[tuple[yaml.Node, bool]] = [(root, False)]
    while stack:
        node, finished = stack.pop()
        key = id(node)
        if finished:
            visiting.discard(key)
            children = _children(node)
            size[key] = min(1 + sum(size[id(child)] for child in children),
                            limits.max_yaml_nodes + 1)
            levels[key] = 1 + max((levels[id(child)] for child in children), default=0)
            if size[key] > limits.max_yaml_nodes:
                raise _located(exceeded(
                    "max_yaml_nodes", f"the YAML node at {_line(node)} expands (through its "
                    f"aliases) to more than {limits.max_yaml_nodes:,} nodes"), file)
            if depth and levels[key] > limits.max_depth:
                raise _located(exceeded("max_depth", f"the YAML at {_line(node)} nests more "
                                        f"than {limits.max_depth:,} levels deep"), file)
            continue
        if key in size:
            continue
        if key in visiting:
            raise FileFormatError(f"the YAML node at {_line(node)} contains itself (an alias "
                                  "inside its own anchor)", file=file)
        visiting.add(key)
        stack.append((node, True))
        stack.extend((child, False) for child in _children(node))


def _children(node: yaml.Node) -> list[yaml.Node]:
    if isinstance(node, yaml.SequenceNode):
        return list(node.value)
    if isinstance(node, yaml.MappingNode):
        return [part for pair in node.value for part in pair]
    return []


def _line(node: yaml.Node) -> str:
    return f"line {node.start_mark.line + 1}" if node.start_mark is not None else "document"


def _located(error: FileFormatError, file: str | os.PathLike[str] | None) -> FileFormatError:
    return error if file is None else error.located(file=file)  # type: ignore[return-value]
