"""Strict YAML reading: plain data only, every duplicate key and custom tag reported.

PyYAML's ``safe_load`` keeps the last of two equal keys in a mapping without a word, so a
mis-indented line can silently replace a value. :func:`load_yaml` reports such keys, YAML
syntax errors (with their line) and tags it has no constructor for (``!include``), each as a
:class:`~pinframes.errors.FileFormatError` naming the file.
"""

from __future__ import annotations

import os
import re
from collections.abc import Callable, Hashable
from typing import Any

import yaml

from ..errors import FileFormatError
from ._yaml_size import check_yaml_size
from .reading import read_text

__all__ = ["KeyPath", "Locate", "load_yaml"]

KeyPath = tuple[Hashable, ...]
"""Keys from the document's top down to a node (list items count by index)."""

Locate = Callable[[KeyPath], tuple[str | None, str | None]]
"""Turns a key path into the ``frame`` and ``field`` of an error."""

_MERGE_TAG = "tag:yaml.org,2002:merge"


def _dotted(path: KeyPath) -> tuple[str | None, str | None]:
    """The default :data:`Locate`: no frame, the keys joined by dots as the field."""
    return None, ".".join(str(part) for part in path) or None


def load_yaml(path: str | os.PathLike[str], locate: Locate = _dotted) -> Any:
    """Read one YAML document of plain data (mappings, lists, scalars) from ``path``.

    Parameters
    ----------
    path : str or path-like
        The file to read (UTF-8).
    locate : callable
        Maps the key path of a bad node to the ``frame`` and ``field`` of the error.

    Raises
    ------
    ReadError
        The file is missing, a folder, unreadable or not UTF-8 text.
    FileFormatError
        On a YAML syntax error, a mapping with two equal keys, or a tag other than the
        YAML core tags; the message gives the line.
    """
    text = read_text(path)
    file = os.fspath(path)
    loader = None
    try:
        loader = _StrictLoader(text, file, locate)  # refuses unprintable characters
        node = loader.get_single_node()
        if node is None:
            return None
        check_yaml_size(node, file)  # aliases: before anything expands them
        loader.check_tags_and_index(node, ())
        return loader.construct_document(node)
    except yaml.MarkedYAMLError as exc:
        raise FileFormatError(_syntax_message(exc), file=file) from exc
    except yaml.YAMLError as exc:
        raise FileFormatError(f"YAML error: {exc}", file=file) from exc
    except RecursionError:
        raise FileFormatError("YAML nested too deeply to read", file=file) from None
    finally:
        if loader is not None:
            loader.dispose()


class _StrictLoader(yaml.SafeLoader):
    """A SafeLoader that refuses duplicate keys and unknown tags, naming where they are."""

    def __init__(self, text: str, file: str, locate: Locate) -> None:
        super().__init__(text)
        self._file = file
        self._locate = locate
        self._paths: dict[int, KeyPath] = {}

    def check_tags_and_index(self, node: yaml.Node, path: KeyPath) -> None:
        """Walk the composed document: refuse unknown tags, remember each mapping's path."""
        stack = [(node, path)]
        seen: set[int] = set()
        while stack:
            current, where = stack.pop()
            if id(current) in seen:  # an alias shares its anchor's node
                continue
            seen.add(id(current))
            if current.tag not in self.yaml_constructors:
                frame, field = self._locate(where)
                raise FileFormatError(
                    f"unsupported YAML tag {current.tag!r} at line {current.start_mark.line + 1}"
                    ": this file must hold plain data (a main.yaml that includes layers with "
                    "!include is not a layer file)", file=self._file, frame=frame, field=field)
            if isinstance(current, yaml.MappingNode):
                self._paths[id(current)] = where
                for key_node, value_node in current.value:
                    label = key_node.value if isinstance(key_node, yaml.ScalarNode) else "?"
                    stack.append((key_node, where))
                    stack.append((value_node, (*where, label)))
            elif isinstance(current, yaml.SequenceNode):
                stack.extend((item, (*where, index)) for index, item in enumerate(current.value))

    def construct_mapping(self, node: yaml.MappingNode, deep: bool = False) -> dict:
        first_lines: dict[Any, int] = {}
        for key_node, _ in node.value:
            if key_node.tag == _MERGE_TAG:
                continue
            key = self.construct_object(key_node, deep=True)
            line = key_node.start_mark.line + 1
            if isinstance(key, Hashable) and key in first_lines:
                frame, field = self._locate((*self._paths.get(id(node), ()), key))
                raise FileFormatError(
                    f"duplicate key {key!r} at line {line} (first at line {first_lines[key]}); "
                    "YAML readers would silently keep only the last one",
                    file=self._file, frame=frame, field=field)
            if isinstance(key, Hashable):
                first_lines[key] = line
        return super().construct_mapping(node, deep=deep)


_AMBIGUOUS_NUMBER = re.compile(r"^[-+]?(0[0-7_]+|[0-9][0-9_]*(:[0-5]?[0-9])+(\.[0-9_]*)?)$")
"""YAML 1.1 numbers that other readers take differently: ``010`` is octal 8 and ``1:30``
base-60 90 for PyYAML, but 10 and a string for YAML 1.2 readers."""


def _unambiguous(construct: Callable[[yaml.SafeLoader, yaml.ScalarNode], Any]
                 ) -> Callable[[_StrictLoader, yaml.ScalarNode], Any]:
    """``construct``, refusing the YAML 1.1 octal and base-60 forms of numbers."""
    def strict(loader: _StrictLoader, node: yaml.ScalarNode) -> Any:
        if _AMBIGUOUS_NUMBER.match(node.value):
            raise FileFormatError(
                f"the number {node.value!r} at line {node.start_mark.line + 1} is read as "
                f"{construct(loader, node)!r} by YAML 1.1 (octal or base 60) and differently "
                "by YAML 1.2 readers: quote it, or write it in decimal", file=loader._file)
        return construct(loader, node)
    return strict


for _tag, _construct in (("tag:yaml.org,2002:int", yaml.SafeLoader.construct_yaml_int),
                         ("tag:yaml.org,2002:float", yaml.SafeLoader.construct_yaml_float)):
    _StrictLoader.add_constructor(_tag, _unambiguous(_construct))


def _syntax_message(exc: yaml.MarkedYAMLError) -> str:
    mark = exc.problem_mark or exc.context_mark
    where = f" at line {mark.line + 1}, column {mark.column + 1}" if mark is not None else ""
    problem = exc.problem or exc.context or "malformed YAML"
    return f"YAML syntax error{where}: {problem}"
