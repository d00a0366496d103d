"""MoveIt's ``joint_limits.yaml``: each joint's velocity, acceleration and jerk limits.

The file holds a ``joint_limits`` mapping from joint names to their entries; an entry gives a
limit with ``has_<kind>_limits: true`` and ``max_<kind>: <number>`` (``velocity``,
``acceleration``, ``jerk``). As MoveIt reads it, a limit counts only when its ``has_`` flag is
true; other keys (positions, scaling factors) are left to MoveIt.
"""

from __future__ import annotations

import math
import os
from collections.abc import Mapping
from types import MappingProxyType
from typing import Any

from ...errors import FileFormatError
from ...values.joint_rate_limits import JointRateLimits
from ..reading import InputFile

__all__ = ["read_joint_limits"]

_KINDS = ("velocity", "acceleration", "jerk")


def read_joint_limits(path: str | os.PathLike[str]) -> Mapping[str, JointRateLimits]:
    """Each joint's velocity, acceleration and jerk limits from a MoveIt ``joint_limits.yaml``.

    Parameters
    ----------
    path : str or path-like
        The file (plain YAML, read within the reader limits).

    Returns
    -------
    Mapping[str, JointRateLimits]
        Read-only, by joint name in the file's order: the limits whose ``has_<kind>_limits``
        is true (rad or m per s, s^2, s^3), None for the others.

    Raises
    ------
    FileFormatError
        No ``joint_limits`` mapping, an entry that is not a mapping, a ``has_`` flag that is
        not true or false, or a limit switched on whose ``max_`` value is missing or not a
        finite number > 0; the error names the file, the joint and the field.
    ReadError
        The file cannot be read.
    """
    source = InputFile.of(path)
    file = os.fspath(source)
    document = source.yaml()
    joints = document.get("joint_limits") if isinstance(document, dict) else None
    if not isinstance(joints, dict):
        raise FileFormatError("holds no 'joint_limits' mapping of joints", file=file,
                              field="joint_limits")
    return MappingProxyType({str(name): _joint(entry, file, str(name))
                             for name, entry in joints.items()})


def _joint(entry: Any, file: str, name: str) -> JointRateLimits:
    """One joint's entry as its limits."""
    if entry is None:
        entry = {}
    if not isinstance(entry, dict):
        raise FileFormatError(f"must be a mapping of limits, got {entry!r}", file=file,
                              joint=name)
    values = {kind: _limit(entry, kind, file, name) for kind in _KINDS}
    return JointRateLimits(**values)


def _limit(entry: dict[Any, Any], kind: str, file: str, name: str) -> float | None:
    """The joint's ``max_<kind>`` when ``has_<kind>_limits`` is true, else None."""
    flag = f"has_{kind}_limits"
    switched_on = entry.get(flag, False)
    if not isinstance(switched_on, bool):
        raise FileFormatError(f"must be true or false, got {switched_on!r}", file=file,
                              joint=name, field=flag)
    if not switched_on:
        return None
    field = f"max_{kind}"
    if field not in entry:
        raise FileFormatError(f"is missing although {flag} is true", file=file, joint=name,
                              field=field)
    value = entry[field]
    if isinstance(value, bool) or not isinstance(value, int | float) \
            or not math.isfinite(value) or value <= 0:
        raise FileFormatError(f"must be a finite number > 0, got {value!r}", file=file,
                              joint=name, field=field)
    return float(value)

