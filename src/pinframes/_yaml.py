"""Loading YAML files strictly: duplicate keys are errors, not silently merged."""

from __future__ import annotations

import os
from typing import Any

import yaml

from .errors import FileFormatError

__all__ = ["load_yaml_file"]


class _StrictLoader(yaml.SafeLoader):
    """A safe loader that refuses mappings with a repeated key (PyYAML keeps the last one)."""


def _construct_mapping(loader: _StrictLoader, node: yaml.MappingNode, deep: bool = False
                       ) -> dict[Any, Any]:
    seen: dict[Any, int] = {}
    for key_node, _ in node.value:
        key = loader.construct_object(key_node, deep=True)
        if key in seen:
            raise yaml.constructor.ConstructorError(
                None, None,
                f"duplicate key {key!r} (first on line {seen[key] + 1})", key_node.start_mark)
        seen[key] = key_node.start_mark.line
    return loader.construct_mapping(node, deep=deep)


_StrictLoader.add_constructor(yaml.resolver.BaseResolver.DEFAULT_MAPPING_TAG, _construct_mapping)


def load_yaml_file(path: str | os.PathLike[str]) -> Any:
    """The content of the YAML file at ``path``.

    Raises
    ------
    FileFormatError
        The file is not valid YAML or repeats a key in a mapping; the message gives the line.
    OSError
        The file cannot be read.
    """
    with open(path, encoding="utf-8") as handle:
        try:
            text = handle.read()
        except UnicodeDecodeError:
            raise FileFormatError("not a UTF-8 text file", file=path) from None
    try:
        return yaml.load(text, Loader=_StrictLoader)
    except yaml.YAMLError as exc:
        mark = getattr(exc, "problem_mark", None)
        where = f"line {mark.line + 1}: " if mark is not None else ""
        problem = getattr(exc, "problem", None) or str(exc)
        raise FileFormatError(f"{where}invalid YAML: {problem}", file=path) from None
