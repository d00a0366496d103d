"""Every array of a hierarchy, checked before any of them is decoded.

asdf reads an ``ndarray`` lazily, when its data is first asked for: pinframes' decoding,
and asdf itself when the hierarchy is validated against its schemas. Before either,
:func:`check_arrays` walks the hierarchy once and refuses

- an array whose data lives elsewhere (``source:`` a file name, a path, an ``http://`` or
  ``ftp://`` address): asdf would open that file or connection; pinframes opens nothing but
  the file it was given;
- a file whose arrays decode to more than ``max_decompressed_bytes`` in total: each binary
  block once, at the size its header declares once decompressed, and each array read from
  it, at its shape and dtype (60 frames that share one compressed block of 45 MB decode to
  2.7 GB). Only headers are read here, nothing is decompressed.
"""

from __future__ import annotations

import math
from collections.abc import Iterator
from typing import Any

import numpy as np

from ...errors import FileFormatError
from ..limits import current_limits, exceeded
from ._decode import DECODING_ERRORS
from ._extension import frame_on_path

__all__ = ["check_arrays"]


def check_arrays(hierarchy: Any) -> None:
    """Refuse external arrays and a total past ``max_decompressed_bytes`` in ``hierarchy``
    (raw tagged data as read), naming the frame and the field (the path to the array)."""
    limit = current_limits().max_decompressed_bytes
    blocks_seen: set[int] = set()
    total = 0
    for path, array in _arrays(hierarchy):
        field = "".join(f"[{step}]" if isinstance(step, int) else f".{step}"
                        for step in path).lstrip(".")
        frame = frame_on_path(hierarchy, path)
        source = array._source
        if isinstance(source, str):
            raise FileFormatError(
                f"the array's data is outside the file ({source!r}); pinframes reads arrays "
                "stored in the file only and opens no other file or address", frame=frame,
                field=field)
        size = _declared_bytes(array)
        if size > limit:
            raise exceeded("max_decompressed_bytes", f"the array of shape "
                           f"{tuple(array._shape)} ({array._dtype}) takes {size:,} bytes",
                           field=field, frame=frame)
        if isinstance(source, int) and source not in blocks_seen:
            blocks_seen.add(source)
            total += _block_bytes(array)
        total += size
        if total > limit:
            raise exceeded("max_decompressed_bytes", f"the arrays read up to this one "
                           f"decode to {total:,} bytes (each binary block once, and each "
                           "array read from it)", field=field, frame=frame)


def _arrays(hierarchy: Any) -> Iterator[tuple[list[Any], Any]]:
    """``(path, array)`` of every asdf ``NDArrayType`` below ``hierarchy`` and of their
    masks, in file order; each use of a shared (aliased) node counts, as each is decoded."""
    from asdf.tags.core import NDArrayType

    stack: list[tuple[list[Any], Any]] = [([], hierarchy)]
    while stack:
        path, node = stack.pop()
        if isinstance(node, NDArrayType):
            yield path, node
            if isinstance(node._mask, NDArrayType):
                stack.append(([*path, "mask"], node._mask))
        elif isinstance(node, dict):
            stack.extend(([*path, key], value) for key, value in reversed(list(node.items())))
        elif isinstance(node, list):
            stack.extend(([*path, index], value)
                         for index, value in reversed(list(enumerate(node))))


def _declared_bytes(array: Any) -> int:
    """Bytes of the array's data by its declared shape and dtype (0 when either is not
    known before reading: a streamed block, whose size is its block's)."""
    shape, dtype = array._shape, array._dtype
    if not isinstance(shape, (list, tuple)) or not all(
            isinstance(n, int) and not isinstance(n, bool) for n in shape):
        return 0
    try:
        itemsize = np.dtype(dtype).itemsize
    except TypeError:
        return 0
    return math.prod(shape) * itemsize


def _block_bytes(array: Any) -> int:
    """The decompressed size of the binary block the array is read from, by its header;
    0 for a header that cannot be read (nor then its block: decoding the array says why)."""
    try:
        return int(array._data_callback(_attr="header")["data_size"])
    except DECODING_ERRORS:
        return 0
