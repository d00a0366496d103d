"""A bag's compressed parts inflated in bounded pieces, within ``max_decompressed_bytes``.

A few kB of bz2, lz4 or zstd can inflate to gigabytes, and a bag's headers (a ROS 1 chunk's
``size``, an MCAP chunk's ``uncompressed_size``) may understate it. rosbags inflates a
compressed part whole before anything can count it, so pinframes inflates them itself, at
most :data:`PIECE_BYTES` at a time, and counts every byte produced for the bag being read
(:class:`InflationBudget`); once the count passes ``max_decompressed_bytes`` the read stops
with the limit's :class:`~pinframes.errors.FileFormatError` naming the bag, whatever the
headers say. The three places a bag is compressed:

- ROS 1 chunks (bz2, lz4) and MCAP chunks (lz4, zstd): rosbags looks their decompressors up
  in two tables; :func:`bound_rosbags_chunks` puts bounded ones in their place, which draw
  on the budget of the read in progress (:meth:`InflationBudget.active`; outside a read by
  pinframes they inflate as rosbags' own do);
- ROS 2 messages (``compression_mode: message``): :meth:`InflationBudget.inflate`, called by
  the bag reader on each message;
- ROS 2 storage files (``compression_mode: file``): :meth:`InflationBudget.inflate_file`,
  which streams a file to disk, so the disk a bag takes is bounded too.

As the libraries rosbags calls do: bz2 and zstd data may hold several streams (frames) one
after another, lz4 data is one frame (what follows it is ignored).
"""

from __future__ import annotations

import bz2
import contextlib
import contextvars
import functools
from collections.abc import Callable, Iterable, Iterator
from pathlib import Path
from typing import Any

from ..limits import current_limits, exceeded

__all__ = ["PIECE_BYTES", "InflationBudget", "bound_rosbags_chunks"]

PIECE_BYTES = 1 << 20
"""The most one step of inflation produces (bytes)."""

_ACTIVE: contextvars.ContextVar[InflationBudget | None] = contextvars.ContextVar(
    "pinframes_bag_inflation", default=None)


@functools.cache
def _decompressor_class(codec: str) -> Callable[[], Any]:
    """The streaming decompressor class of ``codec``: the modules rosbags inflates with."""
    if codec == "bz2":
        return bz2.BZ2Decompressor
    if codec == "lz4":
        from lz4.frame import LZ4FrameDecompressor  # type: ignore[import-untyped]

        return LZ4FrameDecompressor  # type: ignore[no-any-return]
    try:
        from compression import zstd  # type: ignore[import-not-found]  # Python 3.14
    except ImportError:
        from backports import zstd  # type: ignore[import-not-found,no-redef]
    return zstd.ZstdDecompressor  # type: ignore[no-any-return]


_STREAMS_FOLLOW = {"bz2": True, "zstd": True, "lz4": False}
"""Per codec: whether further streams (frames) may follow one."""


class InflationBudget:
    """What a bag's compressed parts inflate to in one read, at most
    ``max_decompressed_bytes`` of the limits in force when it is made.

    Attributes
    ----------
    bag : Path
        The bag, named by the error.
    limit : int
        The most bytes all parts may inflate to.
    produced : int
        Bytes inflated so far.
    """

    def __init__(self, bag: Path) -> None:
        self.bag = bag
        self.limit = current_limits().max_decompressed_bytes
        self.produced = 0

    def inflate(self, data: bytes, codec: str) -> bytes:
        """``data`` (compressed with ``codec``: ``"bz2"``, ``"lz4"`` or ``"zstd"``)
        inflated."""
        return b"".join(self._pieces([data], codec))

    def inflate_file(self, source: Path, target: Path, codec: str) -> None:
        """Inflate the file ``source`` into the new file ``target``, a piece at a time."""
        with open(source, "rb") as compressed, open(target, "xb") as inflated:
            blocks = iter(lambda: compressed.read(PIECE_BYTES), b"")
            for piece in self._pieces(blocks, codec):
                inflated.write(piece)

    @contextlib.contextmanager
    def active(self) -> Iterator[InflationBudget]:
        """Within this block rosbags' chunk decompressors draw on this budget."""
        token = _ACTIVE.set(self)
        try:
            yield self
        finally:
            _ACTIVE.reset(token)

    def _pieces(self, blocks: Iterable[bytes], codec: str) -> Iterator[bytes]:
        """The inflated bytes of the compressed ``blocks``, counted as they come."""
        new_decompressor, streams_follow = _decompressor_class(codec), _STREAMS_FOLLOW[codec]
        decompressor = new_decompressor()
        fed = holding = False  # the decompressor has had input / still holds unread output
        for data in blocks:
            while data or holding:
                if decompressor.eof:  # another stream (frame) follows the one that ended
                    decompressor = new_decompressor()
                piece = decompressor.decompress(data, min(PIECE_BYTES, self._left() + 1))
                fed, data = True, b""
                self.produced += len(piece)
                if self.produced > self.limit:
                    raise exceeded("max_decompressed_bytes", f"its compressed data inflates "
                                   f"to more than {self.limit:,} bytes").located(file=self.bag)
                yield piece
                if decompressor.eof:
                    if not streams_follow:
                        return
                    data, fed, holding = decompressor.unused_data, False, False
                else:
                    holding = not decompressor.needs_input
        if fed:
            raise EOFError(f"{codec} data that ends before its end-of-stream marker")

    def _left(self) -> int:
        return max(self.limit - self.produced, 0)


def bound_rosbags_chunks() -> None:
    """Put bounded decompressors into rosbags' tables of ROS 1 and MCAP chunk decompressors
    (once; rosbags must be importable)."""
    from rosbags.rosbag1 import reader as ros1_reader
    from rosbags.rosbag2 import storage_mcap

    for table, codecs in ((ros1_reader.decompressors, ("bz2", "lz4")),
                          (storage_mcap.DECOMPRESSORS, ("lz4", "zstd"))):
        for codec in codecs:
            table[codec] = _bounded(codec, table[codec])


def _bounded(codec: str, own: Callable[..., bytes]) -> Callable[..., bytes]:
    """rosbags' decompressor ``own`` (``(data)`` for ROS 1, ``(data, size)`` for MCAP),
    drawing on the budget of the read in progress, if any."""
    if getattr(own, "pinframes_bounded", False):
        return own

    def inflate(data: bytes, *declared_size: int) -> bytes:
        budget = _ACTIVE.get()
        return own(data, *declared_size) if budget is None else budget.inflate(data, codec)

    inflate.pinframes_bounded = True  # type: ignore[attr-defined]
    return inflate
