"""Read-only arrays: how values stay immutable once they enter or leave the library.

A :class:`~pinframes.Pose`, a :class:`~pinframes.JointTrajectory` and the transforms cached by a
tree share their arrays freely (a query may hand out the very arrays a cache keeps), which is
safe only because none of them can be written: writing into one raises numpy's
``ValueError: assignment destination is read-only``. Arrays that come in from a caller are
copied first, so the caller's array stays theirs to change.
"""

from __future__ import annotations

from typing import TypeVar

import numpy as np

__all__ = ["readonly", "readonly_copy"]

_Array = TypeVar("_Array", bound=np.ndarray)


def readonly(array: _Array) -> _Array:
    """``array`` itself, marked read-only. Only for arrays no caller holds a writable view of."""
    array.setflags(write=False)  # half the cost of ``array.flags.writeable = False``
    return array


def readonly_copy(array: np.ndarray) -> np.ndarray:
    """A read-only copy of ``array``, for arrays that come in from a caller."""
    return readonly(np.array(array, copy=True))
