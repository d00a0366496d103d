"""The YAML of an ASDF file checked against the reader limits
(:mod:`pinframes.formats.limits`) before asdf reads it.

asdf builds, walks and validates the whole YAML tree, expanding every alias as it goes:
a YAML alias bomb of a few hundred bytes, or a node that contains itself, would cost it
minutes and gigabytes (or end in a bare ``RecursionError``). :func:`check_asdf_yaml`
composes the YAML part (up to the document end marker or the first binary block) with
:class:`~pinframes.formats._yaml_size.BoundedLoader`, which stops at ``max_yaml_nodes``,
without constructing anything.
"""

from __future__ import annotations

import yaml

from .._yaml_size import BoundedLoader
from ._depth import MAX_GRAPH_DEPTH, recursion_room

__all__ = ["check_asdf_yaml"]

_CHUNK = 1 << 20
_ENDS = (b"\n...", b"\xd3BLK")


def check_asdf_yaml(file: str) -> None:
    """Refuse the ASDF file at ``file`` if its YAML breaks the node limit or contains
    itself; YAML that does not compose is left to asdf to report."""
    text = _yaml_part(file)
    try:
        # nesting depth is bounded by MAX_GRAPH_DEPTH (weldx 0.1.0 nests frames deeply)
        loader = BoundedLoader(text, file, depth=False)
        try:
            with recursion_room(MAX_GRAPH_DEPTH):
                loader.get_single_node()
        finally:
            loader.dispose()
    except (yaml.YAMLError, RecursionError, UnicodeDecodeError):
        return  # asdf reports broken YAML, and too_deep a graph nested too deeply


def _yaml_part(file: str) -> bytes:
    """The bytes of ``file`` up to the end of its YAML document (read in chunks, so the
    binary blocks after it are never read)."""
    parts: list[bytes] = []
    with open(file, "rb") as handle:
        while chunk := handle.read(_CHUNK):
            parts.append(chunk)
            joined = b"".join(parts[-2:])
            ends = [joined.find(end) for end in _ENDS]
            if any(position >= 0 for position in ends):
                break
    text = b"".join(parts)
    cut = min((position for position in (text.find(end) for end in _ENDS) if position >= 0),
              default=len(text))
    return text[:cut]
