"""``tf2_msgs/TFMessage`` bytes encoded in bulk with numpy: the writing side of
:mod:`._tf_messages`.

Every ``/tf`` message of a tree holds the same frames in the same order, so every message
has the same layout; only the stamps and the seven numbers of each transform differ. The
first message is serialised by rosbags (the template), the others are copies of it with
their stamps and numbers written in place, at the offsets the layout gives:

- CDR (ROS 2): a 4-byte encapsulation header, then fields aligned to their size counted
  from its end; ``sec`` int32, ``nanosec`` uint32; strings with a length that counts
  their terminating NUL.
- ROS 1: no alignment; ``header.seq`` before the stamp (0, as in the template); ``secs``
  and ``nsecs`` uint32; strings without a terminator.

The offsets are checked against the template's length; the written messages are checked
against rosbags' deserialiser and the ``mcap`` library's in the tests.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
from numpy.typing import NDArray

__all__ = ["encode_tf_messages"]

_NS = 1_000_000_000
_VALUES = 7 * 8  # translation x y z, rotation x y z w: float64 each
_CDR_ORIGIN = 4  # CDR aligns from the end of the encapsulation header


def encode_tf_messages(template: bytes, ros_version: int, parents: Sequence[str],
                       children: Sequence[str], stamps_ns: NDArray[np.int64],
                       translations: NDArray[np.float64], quaternions: NDArray[np.float64]
                       ) -> NDArray[np.uint8]:
    """The T messages, one row each (shape (T, bytes)): ``template`` (rosbags' bytes of the
    first message, of the F transforms ``children`` in ``parents``) with the stamps
    ``stamps_ns`` (T,) and ``translations`` (F, T, 3), ``quaternions`` (F, T, 4) put in."""
    stamp_offsets, value_offsets, end = _layout(parents, children, ros_version)
    size = len(template)
    if not end <= size <= end + (3 if ros_version == 2 else 0):  # CDR pads to 4 bytes
        raise AssertionError(f"TFMessage layout of {end} bytes, rosbags wrote {size}")
    count = stamps_ns.shape[0]
    rows = np.tile(np.frombuffer(template, np.uint8), (count, 1))
    stamp = np.empty((count, 2), "<u4")  # stamps lie in 0 .. 2^31 s: int32 and uint32 alike
    stamp[:, 0] = stamps_ns // _NS
    stamp[:, 1] = stamps_ns % _NS
    stamp_bytes = stamp.view(np.uint8)
    values = np.concatenate([translations, quaternions], axis=2).astype("<f8")
    for frame, (stamp_at, values_at) in enumerate(zip(stamp_offsets, value_offsets,
                                                      strict=True)):
        rows[:, stamp_at:stamp_at + 8] = stamp_bytes
        rows[:, values_at:values_at + _VALUES] = np.ascontiguousarray(values[frame]).view(
            np.uint8)
    return rows


def _layout(parents: Sequence[str], children: Sequence[str], ros_version: int
            ) -> tuple[list[int], list[int], int]:
    """Offsets of each transform's stamp and numbers, and the end of the message."""
    cdr = ros_version == 2
    at = _CDR_ORIGIN + 4 if cdr else 4  # the transforms' count

    def aligned(position: int, size: int) -> int:
        if not cdr:
            return position
        return _CDR_ORIGIN + -(-(position - _CDR_ORIGIN) // size) * size

    stamps, values = [], []
    for parent, child in zip(parents, children, strict=True):
        if not cdr:
            at += 4  # header.seq
        at = aligned(at, 4)
        stamps.append(at)
        at += 8
        for name in (parent, child):
            at = aligned(at, 4)
            at += 4 + len(name.encode("utf-8")) + (1 if cdr else 0)
        at = aligned(at, 8)
        values.append(at)
        at += _VALUES
    return stamps, values, at
