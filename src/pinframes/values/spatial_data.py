"""`SpatialData`: points attached to a frame (weldx ``SpatialData``), static or sampled in time.

Points are coordinates in the frame they are attached to, in metres: ``(M, 3)`` for a static
point cloud, ``(T, M, 3)`` for one cloud per time (a scan taken while the frame moved).
Optional ``triangles`` (``(K, 3)`` indices into the points, row-major over time and point for
time-dependent data, as weldx stores them) make a mesh; ``attributes`` hold one array per
name with one entry per point (normals, colours, measured values).
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ..errors import InvalidDataError
from ._readonly import readonly, readonly_copy
from .numbers import float_array
from .pose import Pose, _time_axis
from .quantities import metres
from .timed import SampledInTime

__all__ = ["SpatialData", "apply_pose"]

FloatArray = NDArray[np.float64]


class SpatialData(SampledInTime):
    """Points in a frame, with optional triangles and per-point attributes.

    Parameters
    ----------
    points : array_like, shape (M, 3) or (T, M, 3)
        Coordinates in metres (or a pint length quantity).
    triangles : None or array_like of int, shape (K, 3)
        Indices of the points forming each triangle (over all ``T * M`` points when timed).
    attributes : None or mapping of str to array_like
        Per-point values; each array's first axis has ``M`` (or ``T * M``) entries.
    times : None or sequence of T times
        Required for ``(T, M, 3)`` points; read as :class:`~pinframes.Pose` reads times.
    reference_time : None or timestamp
        What relative ``times`` count from (None: the tree's reference time).

    SpatialData is immutable.
    """

    __slots__ = ("_attributes", "_points", "_triangles")

    def __init__(self, points: ArrayLike, triangles: ArrayLike | None = None,
                 attributes: Mapping[str, ArrayLike] | None = None, times: Any = None,
                 reference_time: Any = None) -> None:
        array = _float_points(metres(points, "points", InvalidDataError))
        axis = _time_axis(times, reference_time)
        timed = array.ndim == 3
        if timed != (axis is not None):
            raise InvalidDataError(
                "points of shape (T, M, 3) need T times, points of shape (M, 3) take none; got "
                f"shape {array.shape} and {'no' if axis is None else len(axis.offsets)} times",
                field="times")
        if axis is not None and axis.offsets.shape[0] != array.shape[0]:
            raise InvalidDataError(f"{array.shape[0]} point sets given for "
                                   f"{axis.offsets.shape[0]} times", field="times")
        count = int(np.prod(array.shape[:-1]))
        self._points = array
        self._times = None if axis is None else axis.offsets
        self._reference = None if axis is None else axis.reference
        # read-only copies: the arrays handed out cannot change the data behind its back
        self._triangles = None if triangles is None else readonly_copy(
            _triangles(triangles, count))
        self._attributes = {str(name): readonly_copy(_attribute(name, value, array.shape[-2],
                                                                count))
                            for name, value in (attributes or {}).items()}
        readonly(self._points)

    def with_points(self, points: FloatArray, times: NDArray[np.int64] | None,
                    reference: np.datetime64 | None) -> SpatialData:
        """The same triangles and attributes over other points (already checked)."""
        data = SpatialData.__new__(SpatialData)
        data._points, data._times, data._reference = readonly(points), times, reference
        data._triangles, data._attributes = self._triangles, self._attributes
        return data

    @property
    def points(self) -> FloatArray:
        """Coordinates in metres: ``(M, 3)`` or ``(T, M, 3)``."""
        return self._points

    @property
    def triangles(self) -> NDArray[np.int64] | None:
        """Point indices of each triangle, ``(K, 3)``, or None."""
        return self._triangles

    @property
    def attributes(self) -> dict[str, np.ndarray]:
        """Per-point arrays by name (a copy of the mapping; the arrays are shared)."""
        return dict(self._attributes)

    def __repr__(self) -> str:
        mesh = "" if self._triangles is None else f", {len(self._triangles)} triangles"
        timed = "" if self._times is None else f" at {len(self._times)} times"
        return f"SpatialData({self._points.shape[-2]} points{timed}{mesh})"


def apply_pose(pose: Pose, points: FloatArray) -> FloatArray:
    """Coordinates in B of ``points`` given in A, for ``pose`` = the pose of A in B.

    A static pose maps ``(..., 3)`` points; a pose of T samples maps ``(M, 3)`` points to
    ``(T, M, 3)`` and ``(T, M, 3)`` points sample by sample.
    """
    return pose.transform_points(points)


def _float_points(points: Any) -> FloatArray:
    array = float_array(points, "points", InvalidDataError, copy=True)
    if array.ndim not in (2, 3) or array.shape[-1] != 3:
        raise InvalidDataError(f"expected shape (M, 3) or (T, M, 3), got {array.shape}",
                               field="points")
    return array


def _triangles(triangles: ArrayLike, count: int) -> NDArray[np.int64]:
    array = np.asarray(triangles)
    if array.ndim != 2 or array.shape[1] != 3 or (array.size and array.dtype.kind not in "iu"):
        raise InvalidDataError(f"expected integer indices of shape (K, 3), got {array.dtype} "
                               f"of shape {array.shape}", field="triangles")
    array = array.astype(np.int64)
    if array.size and (array.min() < 0 or array.max() >= count):
        raise InvalidDataError(f"indices must lie in [0, {count}), got {array.min()} to "
                               f"{array.max()}", field="triangles")
    array.flags.writeable = False
    return array


def _attribute(name: object, value: ArrayLike, per_set: int, count: int) -> np.ndarray:
    array = np.array(value)
    if array.ndim == 0 or array.shape[0] not in (per_set, count):
        raise InvalidDataError(f"expected one entry per point ({per_set}"
                               + ("" if per_set == count else f" or {count}")
                               + f"), got shape {array.shape}", field=f"attributes.{name}")
    array.flags.writeable = False
    return array
