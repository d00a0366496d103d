"""`PoseStack`: the poses of several frames (or frame pairs), stacked along a first axis.

What :meth:`pinframes.FrameTree.poses` returns: entry ``i`` is the pose of ``frames[i]`` in
its ``relative_to``, all on one timeline. Arrays have the pair axis first, then the time axis
when there are times: rotations ``(F, 3, 3)`` or ``(F, T, 3, 3)``, translations ``(F, 3)``
or ``(F, T, 3)`` in metres.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from ._readonly import readonly
from .pose import Pose, trusted_pose
from .timed import Timed

__all__ = ["PoseStack"]


@dataclass(frozen=True, eq=False)
class PoseStack(Timed):
    """Poses of F frames (or pairs), static or on one common timeline of T times.

    Attributes
    ----------
    rotation : ndarray, shape (F, 3, 3) or (F, T, 3, 3)
    translation : ndarray, shape (F, 3) or (F, T, 3)
        Metres.
    offsets : ndarray of int64, shape (T,), or None
        Nanoseconds after :attr:`reference_time`; None for static poses.
    reference_time : numpy.datetime64 or None

    Immutable like :class:`Pose`: the arrays are marked read-only (they are the stack's
    own; the poses ``stack[i]`` are views of them).
    """

    rotation: NDArray[np.float64]
    translation: NDArray[np.float64]
    offsets: NDArray[np.int64] | None = None
    reference_time: np.datetime64 | None = None

    def __post_init__(self) -> None:
        for array in (self.rotation, self.translation, self.offsets):
            if array is not None:
                readonly(array)

    @property
    def matrix(self) -> NDArray[np.float64]:
        """Homogeneous matrices, shape (F, 4, 4) or (F, T, 4, 4)."""
        return trusted_pose(self.rotation, self.translation).matrix

    @property
    def quaternion(self) -> NDArray[np.float64]:
        """Unit quaternions ``(x, y, z, w)``: shape (F, 4), ``w >= 0``, or (F, T, 4), each
        pose's as :attr:`Pose.quaternion` gives it (signs continuous along its times)."""
        if self.rotation.ndim == 4:
            return np.stack([self[index].quaternion for index in range(len(self))])
        return trusted_pose(self.rotation, self.translation).quaternion

    @property
    def times(self) -> NDArray[np.timedelta64] | None:
        """Times after :attr:`reference_time`, ``timedelta64[ns]``; None if static."""
        return None if self.offsets is None else self.offsets.astype("timedelta64[ns]")

    def __len__(self) -> int:
        """Number of frames (pairs)."""
        return int(self.translation.shape[0])

    def __getitem__(self, index: int) -> Pose:
        """The pose of pair ``index``, as :meth:`FrameTree.pose` returns it."""
        return trusted_pose(self.rotation[index], self.translation[index], self.offsets,
                             self.reference_time)
