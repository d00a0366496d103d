"""``tf2_msgs/TFMessage`` bytes, decoded in bulk with numpy into columns of transforms.

A TFMessage is a list of ``geometry_msgs/TransformStamped``: ``header`` (ROS 1: ``seq``
uint32; then ``stamp`` as sec, nanosec; then the string ``frame_id``), the string
``child_frame_id``, then ``transform``: translation x y z and rotation x y z w, seven
float64. ROS 1 packs the fields without padding and strings without a terminator; ROS 2's
CDR starts with a 4-byte encapsulation header (byte 1: 1 little-, 0 big-endian), aligns
every primitive to its size counted from the end of that header, ends strings with a NUL
that their length counts, and may pad the message by up to 3 bytes.

Decoding a message at a time in Python costs about 20 µs (rosbags' deserialiser); here the
messages of a topic are joined into one buffer and every message's k-th transform is read
by the same few array operations, so the cost is a few passes over the bytes plus one step
per transform position in the longest message. tests/ros/test_tf_messages.py checks it
against rosbags' own deserialiser.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

__all__ = ["CorruptMessage", "TransformColumns", "decode_tf_messages"]

_VALUES_BYTES = 56  # 7 float64


class CorruptMessage(Exception):
    """Message ``index`` (in the order given) is not a well-formed TFMessage."""

    def __init__(self, index: int, reason: str) -> None:
        super().__init__(reason)
        self.index = index
        self.reason = reason


@dataclass(frozen=True)
class TransformColumns:
    """Transforms as columns, in the order of the messages and within each message.

    Attributes
    ----------
    names : list of str
        Frame names as written (a leading ``/`` kept); ``parents`` and ``children`` index it.
    parents, children : ndarray of int64, shape (N,)
        ``header.frame_id`` and ``child_frame_id`` of each transform.
    stamps_ns : ndarray of int64, shape (N,)
        ``header.stamp`` in nanoseconds since the epoch.
    translations : ndarray, shape (N, 3)
        Metres, the child's origin in the parent.
    quaternions : ndarray, shape (N, 4)
        ``(x, y, z, w)`` as written (not normalised).
    message_index : ndarray of int64, shape (N,)
        The message each transform came from.
    """

    names: list[str]
    parents: NDArray[np.int64]
    children: NDArray[np.int64]
    stamps_ns: NDArray[np.int64]
    translations: NDArray[np.float64]
    quaternions: NDArray[np.float64]
    message_index: NDArray[np.int64]


def decode_tf_messages(messages: Sequence[bytes], ros_version: int) -> TransformColumns:
    """Decode serialised TFMessages (``ros_version`` 1: ROS 1, 2: CDR).

    Raises
    ------
    CorruptMessage
        For the first message (by index) that is truncated, too long, has an unknown CDR
        encapsulation or a name that is not UTF-8.
    """
    lengths = np.fromiter((len(message) for message in messages), np.int64, len(messages))
    starts = np.zeros(len(messages) + 1, np.int64)
    np.cumsum(lengths, out=starts[1:])
    buffer = np.frombuffer(b"".join(messages), np.uint8)
    ends = starts[1:]
    origins = starts[:-1].copy()  # where alignment counts from
    little = np.ones(len(messages), bool)
    if ros_version == 2:
        little = _cdr_byte_orders(buffer, starts[:-1], ends)
        origins += 4
    reader = _Reader(buffer, origins, ends, ros_version, little)
    return reader.transforms()


def _cdr_byte_orders(buffer: NDArray[np.uint8], starts: NDArray[np.int64],
                     ends: NDArray[np.int64]) -> NDArray[np.bool_]:
    """True for little-endian CDR messages; unknown encapsulations are corrupt."""
    short = np.flatnonzero(ends - starts < 4)
    if short.size:
        raise CorruptMessage(int(short[0]), "shorter than the CDR header")
    first, second = buffer[starts], buffer[starts + 1]
    bad = np.flatnonzero((first != 0) | (second > 1))
    if bad.size:
        index = int(bad[0])
        raise CorruptMessage(index, f"unknown CDR encapsulation {int(first[index]):#04x}"
                             f"{int(second[index]):02x}")
    return second == 1


class _Reader:
    """Cursors into every message, advanced field by field for all messages at once."""

    def __init__(self, buffer: NDArray[np.uint8], origins: NDArray[np.int64],
                 ends: NDArray[np.int64], ros_version: int, little: NDArray[np.bool_]) -> None:
        self.buffer = buffer
        self.origins = origins
        self.ends = ends
        self.cdr = ros_version == 2
        self.little = little

    def transforms(self) -> TransformColumns:
        messages = np.arange(self.origins.shape[0])
        cursor = self.origins.copy()
        counts = self._uint32(messages, cursor, "transforms count")
        cursor += 4
        # each transform takes at least 4 + 8 + 4 + 4 + 56 bytes (CDR: 2 more NULs)
        smallest = 76 + (2 if self.cdr else 0)
        too_many = np.flatnonzero(counts * smallest > self.ends - cursor)
        if too_many.size:
            raise CorruptMessage(int(too_many[0]), f"{int(counts[too_many[0]])} transforms do "
                                 "not fit in the message (truncated?)")
        first_of = np.zeros(messages.shape[0] + 1, np.int64)
        np.cumsum(counts, out=first_of[1:])
        total = int(first_of[-1])
        stamps = np.empty(total, np.int64)
        values = np.empty((total, 7), np.float64)
        name_spans = np.empty((2, total, 2), np.int64)  # (frame_id, child) x (start, length)
        message_index = np.repeat(messages, counts)
        for position in range(int(counts.max(initial=0))):
            active = np.flatnonzero(counts > position)
            at = cursor[active]
            rows = first_of[active] + position
            stamps[rows], at = self._stamp(active, at)
            for which, field in enumerate(("header.frame_id", "child_frame_id")):
                at = self._align(active, at, 4)
                length = self._uint32(active, at, field)
                name_spans[which, rows, 0] = at + 4
                name_spans[which, rows, 1] = length - 1 if self.cdr else length
                at = self._string_end(active, at, length, field)
            at = self._align(active, at, 8)
            values[rows] = self._float64s(active, at)
            cursor[active] = at + _VALUES_BYTES
        self._check_ends(cursor)
        names, codes = _unique_names(self.buffer, name_spans.reshape(-1, 2), message_index)
        return TransformColumns(names, codes[:total], codes[total:], stamps, values[:, :3],
                                values[:, 3:], message_index)

    # -- fields ----------------------------------------------------------------------------
    def _align(self, active: NDArray[np.int64], at: NDArray[np.int64], size: int
               ) -> NDArray[np.int64]:
        if not self.cdr:
            return at
        origin = self.origins[active]
        return origin + (at - origin + size - 1) // size * size

    def _check(self, active: NDArray[np.int64], end: NDArray[np.int64], what: str) -> None:
        over = np.flatnonzero(end > self.ends[active])
        if over.size:
            raise CorruptMessage(int(active[over[0]]), f"ends inside {what} (truncated?)")

    def _bytes(self, active: NDArray[np.int64], at: NDArray[np.int64], size: int, what: str
               ) -> NDArray[np.uint8]:
        """``size`` bytes at each cursor, in little-endian order, shape (len(at), size)."""
        self._check(active, at + size, what)
        raw = self.buffer[at[:, None] + np.arange(size)]
        if self.cdr and not self.little[active].all():
            big = ~self.little[active]
            raw[big] = raw[big, ::-1] if size in (4, 8) else _swap_each(raw[big], 8)
        return raw

    def _uint32(self, active: NDArray[np.int64], at: NDArray[np.int64], what: str
                ) -> NDArray[np.int64]:
        raw = self._bytes(active, at, 4, what)
        return raw.view("<u4")[:, 0].astype(np.int64)

    def _stamp(self, active: NDArray[np.int64], at: NDArray[np.int64]
               ) -> tuple[NDArray[np.int64], NDArray[np.int64]]:
        if not self.cdr:
            at = at + 4  # header.seq
        at = self._align(active, at, 4)
        seconds_raw = self._bytes(active, at, 4, "header.stamp.sec")
        nanoseconds = self._uint32(active, at + 4, "header.stamp.nanosec")
        # ROS 1 time is unsigned, ROS 2's builtin_interfaces/Time.sec is an int32
        seconds = seconds_raw.view("<i4" if self.cdr else "<u4")[:, 0].astype(np.int64)
        return seconds * 1_000_000_000 + nanoseconds, at + 8

    def _string_end(self, active: NDArray[np.int64], at: NDArray[np.int64],
                    length: NDArray[np.int64], field: str) -> NDArray[np.int64]:
        end = at + 4 + length
        self._check(active, end, field)
        if self.cdr:
            empty = np.flatnonzero(length < 1)
            if empty.size:
                raise CorruptMessage(int(active[empty[0]]), f"{field}: a CDR string of "
                                     "length 0 (no terminator)")
            unterminated = np.flatnonzero(self.buffer[end - 1] != 0)
            if unterminated.size:
                raise CorruptMessage(int(active[unterminated[0]]),
                                     f"{field}: string without its terminating NUL")
        return end

    def _float64s(self, active: NDArray[np.int64], at: NDArray[np.int64]
                  ) -> NDArray[np.float64]:
        raw = self._bytes(active, at, _VALUES_BYTES, "transform")
        return raw.view("<f8")

    def _check_ends(self, cursor: NDArray[np.int64]) -> None:
        spare = self.ends - cursor
        allowed = 3 if self.cdr else 0  # CDR payloads are padded to 4 bytes
        bad = np.flatnonzero((spare < 0) | (spare > allowed))
        if bad.size:
            raise CorruptMessage(int(bad[0]), f"{int(spare[bad[0]])} bytes left after the "
                                 "last transform (not a TFMessage?)")


def _swap_each(raw: NDArray[np.uint8], size: int) -> NDArray[np.uint8]:
    """Reverse the bytes of each ``size``-byte value in rows of several values."""
    rows = raw.shape[0]
    return raw.reshape(rows, -1, size)[:, :, ::-1].reshape(rows, -1)


def _unique_names(buffer: NDArray[np.uint8], spans: NDArray[np.int64],
                  message_index: NDArray[np.int64]) -> tuple[list[str], NDArray[np.int64]]:
    """The distinct strings at ``spans`` (start, length) and each span's index among them.

    Spans are grouped by length, and each group's bytes compared as rows of one array, so
    the memory used is that of the strings themselves.
    """
    codes = np.empty(spans.shape[0], np.int64)
    names: list[str] = []
    lengths = spans[:, 1]
    for length in np.unique(lengths).tolist():
        members = np.flatnonzero(lengths == length)
        if length == 0:
            codes[members] = len(names)
            names.append("")
            continue
        rows = np.ascontiguousarray(buffer[spans[members, 0][:, None] + np.arange(length)])
        keys = rows.view(np.dtype((np.void, length)))[:, 0]
        _, first, inverse = np.unique(keys, return_index=True, return_inverse=True)
        codes[members] = len(names) + inverse.reshape(-1)
        for row in first.tolist():
            try:
                names.append(bytes(rows[row]).decode("utf-8"))
            except UnicodeDecodeError:
                transform = int(members[row]) % message_index.shape[0]
                raise CorruptMessage(int(message_index[transform]),
                                     "a frame name that is not UTF-8") from None
    return names, codes
