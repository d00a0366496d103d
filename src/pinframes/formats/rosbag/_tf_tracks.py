"""tf2's rules (docs/ros-bags.md) applied to the transforms of a bag: one track per frame.

- The child is ``child_frame_id``, the parent ``header.frame_id``, a leading ``/`` dropped;
  the time is ``header.stamp``. Transforms that tf2's buffer refuses (an empty name, a
  frame its own parent, NaN, a quaternion whose squared norm is off 1 by more than 0.01)
  are skipped with one :class:`~pinframes.errors.BagWarning`, as tf2 skips them; the
  others' quaternions are normalised.
- A frame of a static topic holds its last received transform for all time; a frame of
  the other topics is keyframed at its stamps, sorted (bags keep receive order). Of two
  transforms of a frame at one stamp, the bag's ROS version decides, as its tf2 does: in a
  ROS 1 bag the first received is kept (ROS 1's tf2 ignores the second, warning
  ``TF_REPEATED_DATA``), in a ROS 2 bag the later received (ROS 2's tf2 stores both and
  looks up the later); one warning for the read.
- A frame published under two parents (tf2 allows re-parenting, a tree cannot) or on both a
  static and a dynamic topic is a :class:`~pinframes.errors.TreeStructureError`.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np
from numpy.typing import NDArray

from ...errors import BagWarning, TreeStructureError, warn_at_caller
from ...values.timeconv import format_timestamp_iso
from ..limits import current_limits, exceeded
from ._tf_messages import TransformColumns

__all__ = ["FrameTrack", "frame_tracks", "kept_of_repeated_stamps", "repeated_stamp_rule",
           "stamp_iso"]

QUATERNION_TOLERANCE = 0.01
"""tf2 refuses a quaternion whose squared norm differs from 1 by more than this."""


@dataclass(frozen=True)
class FrameTrack:
    """What a bag says about one frame.

    Attributes
    ----------
    child, parent : str
        The frame and its parent (leading ``/`` dropped).
    static : bool
        From a static topic: one transform that holds for all time.
    stamps_ns : ndarray of int64, shape (K,)
        Strictly increasing stamps, ns since the epoch (a static frame: its stamp).
    translations : ndarray, shape (K, 3)
        Metres.
    quaternions : ndarray, shape (K, 4)
        Unit ``(x, y, z, w)``.
    """

    child: str
    parent: str
    static: bool
    stamps_ns: NDArray[np.int64]
    translations: NDArray[np.float64]
    quaternions: NDArray[np.float64]


def frame_tracks(columns: TransformColumns, static: NDArray[np.bool_], file: Path,
                 ros_version: int) -> dict[str, FrameTrack]:
    """The tracks of the frames in ``columns`` (``static``: per transform, whether it came
    from a static topic) of a bag of ``ros_version`` (1 or 2), in order of first
    appearance."""
    names, parents, children = _without_leading_slash(columns)
    kept = _accepted_by_tf2(names, parents, children, columns, file)
    parents, children, static = parents[kept], children[kept], static[kept]
    stamps = columns.stamps_ns[kept]
    translations = columns.translations[kept]
    quaternions = columns.quaternions[kept]
    quaternions = quaternions / np.linalg.norm(quaternions, axis=1, keepdims=True)
    _check_one_parent(names, parents, children, static, stamps, file)
    # stable: equal stamps keep receive order, so a run of one stamp starts with the first
    # received and ends with the last
    order = np.lexsort((stamps, children))
    children, parents, static, stamps = (children[order], parents[order], static[order],
                                         stamps[order])
    translations, quaternions = translations[order], quaternions[order]
    bounds = np.flatnonzero(np.diff(children)) + 1
    starts = np.concatenate([[0], bounds]).astype(np.int64)
    stops = np.concatenate([bounds, [children.shape[0]]]).astype(np.int64)
    tracks: dict[str, FrameTrack] = {}
    repeated: list[str] = []
    changed_static: list[str] = []
    for start, stop in zip(starts.tolist(), stops.tolist(), strict=True):
        if start == stop:
            continue
        child = names[int(children[start])]
        if static[start]:
            # the last received: order by receive position, not by stamp
            rows = np.arange(start, stop)[np.argsort(order[start:stop], kind="stable")]
            last = rows[-1:]
            if (np.ptp(translations[rows], axis=0).any()
                    or np.ptp(quaternions[rows], axis=0).any()):
                changed_static.append(child)
        else:
            last = start + kept_of_repeated_stamps(stamps[start:stop], ros_version)
            if last.shape[0] < stop - start:
                repeated.append(child)
            if last.shape[0] > current_limits().max_samples:
                raise exceeded("max_samples", f"{last.shape[0]:,} transforms",
                               frame=child).located(file=file)
        tracks[child] = FrameTrack(child, names[int(parents[start])], bool(static[start]),
                                   stamps[last], translations[last], quaternions[last])
    _warn_once(repeated, "frames with two transforms at one stamp "
               + repeated_stamp_rule(ros_version), file)
    _warn_once(changed_static, "static frames published with different transforms (the "
               "last received holds)", file)
    first_seen = {names[int(code)]: None for code in columns.children[kept]}
    return {name: tracks[name] for name in first_seen if name in tracks}


def _without_leading_slash(columns: TransformColumns
                           ) -> tuple[list[str], NDArray[np.int64], NDArray[np.int64]]:
    """Names without a leading ``/`` (``/map`` and ``map`` are one frame, as in tf2)."""
    stripped = [name[1:] if name.startswith("/") else name for name in columns.names]
    names = list(dict.fromkeys(stripped))
    position = {name: index for index, name in enumerate(names)}
    recode = np.array([position[name] for name in stripped], np.int64)
    if not stripped:
        return names, columns.parents, columns.children
    return names, recode[columns.parents], recode[columns.children]


def _accepted_by_tf2(names: list[str], parents: NDArray[np.int64],
                     children: NDArray[np.int64], columns: TransformColumns, file: Path
                     ) -> NDArray[np.bool_]:
    """Which transforms tf2's buffer would store; one warning counting the others."""
    empty = np.array([name == "" for name in names] or [False])
    values = np.hstack([columns.translations, columns.quaternions])
    squared_norm = np.einsum("ij,ij->i", columns.quaternions, columns.quaternions)
    reasons = {
        "an empty frame name": empty[parents] | empty[children],
        "the frame as its own parent": parents == children,
        "NaN values": ~np.isfinite(values).all(axis=1),
        "a quaternion that is not unit": ~(np.abs(squared_norm - 1.0) <= QUATERNION_TOLERANCE),
    }
    refused = np.zeros(parents.shape[0], bool)
    counts = []
    for reason, mask in reasons.items():
        mask = mask & ~refused
        if mask.any():
            counts.append(f"{int(mask.sum()):,} with {reason} (first: frame "
                          f"{names[int(children[np.argmax(mask)])]!r})")
        refused |= mask
    if counts:
        warn_at_caller(f"{file}: skipped transforms that tf2 refuses: "
                       + "; ".join(counts), BagWarning)
    return ~refused


def _check_one_parent(names: list[str], parents: NDArray[np.int64],
                      children: NDArray[np.int64], static: NDArray[np.bool_],
                      stamps: NDArray[np.int64], file: Path) -> None:
    """A frame has one parent and is either static or not; else an error naming it."""
    if parents.shape[0] == 0:
        return
    count = len(names)
    pairs = np.unique(children * count + parents)  # one integer per (child, parent) pair
    pair_children = pairs // count
    reparented = np.flatnonzero(pair_children[1:] == pair_children[:-1])
    if reparented.size:
        child = int(pair_children[reparented[0]])
        described = []
        for parent in (pairs[pair_children == child] % count).tolist():
            mask = (children == child) & (parents == parent)
            described.append(f"{names[parent]!r} (first at {stamp_iso(stamps[mask].min())})")
        raise TreeStructureError(
            "published under several parents: " + " and ".join(described)
            + "; tf2 re-parents a frame in time, a tree cannot (read the bag in parts, or "
            "leave out a tf topic)", file=file, frame=names[child])
    kinds = np.unique(children * 2 + static)
    both = np.flatnonzero(kinds[1:] // 2 == kinds[:-1] // 2)
    if both.size:
        raise TreeStructureError("published on both a static and a dynamic tf topic",
                       file=file, frame=names[int(kinds[both[0]] // 2)])


def kept_of_repeated_stamps(stamps_ns: NDArray[np.int64], ros_version: int
                            ) -> NDArray[np.int64]:
    """Positions in ``stamps_ns`` (sorted, equal stamps in receive order) of the samples
    tf2 of ``ros_version`` keeps: of each run of one stamp the first (ROS 1) or the last
    (ROS 2)."""
    changes = stamps_ns[1:] != stamps_ns[:-1]
    if ros_version == 1:
        return np.flatnonzero(np.insert(changes, 0, True))
    return np.flatnonzero(np.append(changes, True))


def repeated_stamp_rule(ros_version: int) -> str:
    """Which of two samples at one stamp :func:`kept_of_repeated_stamps` keeps, for
    warnings."""
    if ros_version == 1:
        return "(the first received is kept, as ROS 1's tf2 keeps it: TF_REPEATED_DATA)"
    return "(the later received is kept, as ROS 2's tf2 looks it up)"


def stamp_iso(stamp_ns: int) -> str:
    """A stamp (ns since the epoch) as an ISO timestamp, for messages."""
    return format_timestamp_iso(np.datetime64(int(stamp_ns), "ns"))


def _warn_once(frames: list[str], what: str, file: Path) -> None:
    if frames:
        shown = ", ".join(repr(frame) for frame in frames[:5])
        warn_at_caller(f"{file}: {len(frames)} {what}: {shown}"
                       + (" ..." if len(frames) > 5 else ""), BagWarning)
