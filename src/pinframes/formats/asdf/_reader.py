"""``read_asdf``: the weldx coordinate system hierarchy of an ASDF file as a FrameTree."""

from __future__ import annotations

import os
from collections.abc import Iterator
from typing import Any

from ...errors import FileFormatError, PinframesError
from ...tree import FrameTree
from .._paths import path_argument
from ..limits import Limits, reader_with_limits
from ._arrays import check_arrays
from ._decode import open_raw_tree, weldx_tag
from ._depth import MAX_GRAPH_DEPTH, deepest_frame, recursion_room, too_deep
from ._digraph import read_digraph_hierarchy
from ._extension import validate_hierarchy
from ._hierarchy import Hierarchy
from ._legacy import read_legacy_hierarchy

__all__ = ["read_asdf"]

_HIERARCHY_TAG = "core/transformations/coordinate_system_hierarchy"


@reader_with_limits
def read_asdf(path: str | os.PathLike[str], key: str | None = None, *,
              limits: Limits | None = None) -> FrameTree:
    """Read the weldx coordinate system hierarchy stored in the ASDF file at ``path``.

    All three generations of weldx files are read (docs/asdf-format.md): the legacy ``1.0.0``
    format (weldx up to 0.4), weldx 0.5 (``di_graph``, coordinates without unit) and weldx
    0.6 to 0.8 (coordinates with units). Lengths become metres (no unit means millimetres);
    times keep their reference times. weldx itself is never used, even when installed.

    Parameters
    ----------
    path : path
        The ASDF file.
    key : str or None
        Where the hierarchy is in the file's tree: a top-level key such as ``"csm"``, or a
        ``/``-separated path to a nested one (list positions as numbers). None finds the
        only hierarchy in the file.
    limits : Limits or None
        Bounds on what the file may cost to read (:class:`pinframes.Limits`; None: the
        defaults, or those of the reader this one is called from).

    Returns
    -------
    FrameTree
        Named as the hierarchy, rooted at its root system, with its reference time;
        merged subsystems are in ``tree.subsystems`` (their root is the frame they share
        with the hierarchy they were merged into).

    Raises
    ------
    ReadError
        The file is missing or unreadable.
    FileFormatError
        Not an ASDF file, no hierarchy (or several, and no ``key``), an unknown ``key``, or
        a hierarchy that breaks the format or pinframes' weldx schemas (checked after
        pinframes' own, more specific checks), an array stored outside the file
        (``source:`` a file or an address: nothing is opened), or arrays that decode to more
        than ``max_decompressed_bytes`` in all; the message names the frame and field.
    UnsupportedFeatureError
        Coordinates given as a math expression (``core/time_series``), or a graph (weldx
        0.1.0 format) with a frame more than 400 frames below its root; the legacy format
        lists frames flat and has no such bound.
    InvalidPoseError, InvalidTimeError, ReferenceTimeError
        Rotations that are not rotations, non-finite values, times that do not increase,
        reference times that cannot be combined.

    Data attached to frames (weldx 0.4 ``spatial_data``, node ``attributes.data`` later) is
    read into :meth:`FrameTree.get_data`; data pinframes cannot hold (a ``time_series``, a
    ``shape``) is an :class:`UnsupportedFeatureError` naming the frame, the data and its tag.
    """
    path = path_argument(path)
    try:
        with open_raw_tree(path) as tree:
            node = _find_hierarchy(tree, key)
            check_arrays(node)  # before asdf or pinframes decodes any of them
            hierarchy = _read_hierarchy(node)
            depth = 0
            tag = weldx_tag(node)  # found by its hierarchy tag
            if tag is not None and not tag[1].startswith("1."):  # only 0.1.0 nests (_depth)
                deepest, depth = deepest_frame(
                    (name, parent) for name, parent, _ in hierarchy.frames)
                if depth > MAX_GRAPH_DEPTH:
                    raise too_deep(deepest, depth, path)
            with recursion_room(depth):
                validate_hierarchy(node)
        return hierarchy.to_tree()
    except PinframesError as exc:
        raise exc.located(file=path) from None


def _find_hierarchy(tree: dict[str, Any], key: str | None) -> Any:
    found = dict(_hierarchies(tree, ""))
    if key is not None:
        if key not in found:
            where = f"; hierarchies are under: {_listed(found)}" if found else ""
            raise FileFormatError(f"no weldx coordinate system hierarchy under the key "
                                  f"{key!r}{where}")
        return found[key]
    if not found:
        raise FileFormatError("no weldx coordinate system hierarchy in the file")
    if len(found) > 1:
        raise FileFormatError(f"{len(found)} coordinate system hierarchies, under the keys "
                              f"{_listed(found)}: pass key= to choose one")
    return next(iter(found.values()))


def _hierarchies(node: Any, where: str) -> Iterator[tuple[str, Any]]:
    """``(key path, node)`` of every hierarchy below ``node``, in file order."""
    tag = weldx_tag(node)
    if tag is not None and tag[0] == _HIERARCHY_TAG:
        yield where, node
        return
    items: Iterator[tuple[str, Any]]
    if isinstance(node, dict):
        items = ((str(key), value) for key, value in node.items())
    elif isinstance(node, list):
        items = ((str(index), value) for index, value in enumerate(node))
    else:
        return
    for name, value in items:
        yield from _hierarchies(value, f"{where}/{name}" if where else name)


def _read_hierarchy(node: Any) -> Hierarchy:
    tag = weldx_tag(node)
    assert tag is not None  # found by its hierarchy tag
    version = tag[1]
    if version.startswith("1."):
        return read_legacy_hierarchy(node)
    return read_digraph_hierarchy(node)


def _listed(found: dict[str, Any]) -> str:
    return ", ".join(repr(key) for key in found)
