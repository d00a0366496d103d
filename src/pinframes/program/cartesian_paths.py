"""The tool's target along a linear or seam move, sampled densely enough for the joints
solved at the samples to keep the tool on the path between them.

A target path is a :class:`~pinframes.Pose` of the tool in a reference frame (the frame a
move's target is, the torch target of a seam, or the root for a ``Pose`` target), one pose
per node at the times ``solve_joints`` is asked for, and a path parameter per node: metres
along a line or along the seam, or the seam's own seconds. Nodes are at most
:data:`NODE_STEP_M` apart in position and :data:`NODE_STEP_RAD` in rotation.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from ..values.interpolation import rotation_steps
from ..values.pose import Pose, trusted_pose
from ..values.rotations import matrix_from_axis_angle
from ..values.weave import Weave

__all__ = ["NODE_STEP_M", "NODE_STEP_RAD", "NOMINAL_STEP_S", "TargetPath", "filled_times",
           "line_path", "offset_along_z", "seam_path"]

FloatArray = NDArray[np.float64]

NODE_STEP_M = 0.002
"""Largest step of the tool's target between two nodes, metres."""
NODE_STEP_RAD = 0.02
"""Largest turn of the tool's target between two nodes, radians."""
NOMINAL_STEP_S = 1e-6
"""The times a line's nodes are solved at lie this far apart (seconds): the tree as it is
at the line's time."""
WEAVE_NODES_PER_PERIOD = 40
"""Nodes per weave period at least."""


@dataclass(frozen=True)
class TargetPath:
    """Target poses of the tool at nodes along a path.

    Attributes
    ----------
    poses : Pose
        One pose per node (N) in the path's reference frame, at the times it is solved at.
    parameter : ndarray, shape (N,)
        The path parameter, strictly increasing: metres along it, or the seam's own seconds.
    parameter_speed : float or None
        The highest rate of the parameter (m/s, or 1 for a seam on its own times).
    tool_speed_per_parameter : ndarray, shape (N,)
        The tool origin's speed along the path per unit rate of the parameter (1 for metres
        along it).
    """

    poses: Pose
    parameter: FloatArray
    parameter_speed: float | None
    tool_speed_per_parameter: FloatArray

    @property
    def requested_speed(self) -> float | None:
        """The tool's highest speed asked for, m/s: the parameter's highest rate times the
        path's highest speed per parameter (a seam on its own times: its own fastest
        speed); None when the parameter has no highest rate."""
        if self.parameter_speed is None:
            return None
        return self.parameter_speed * float(self.tool_speed_per_parameter.max())


def line_path(start: Pose, end: Pose, speed: float | None, at: float,
              ending: bool = False) -> TargetPath:
    """From ``start`` to ``end`` (static poses in one frame): the origin on the straight
    line, the rotation slerped, solved from ``at`` seconds on (``ending``: up to ``at``),
    nodes :data:`NOMINAL_STEP_S` apart; the parameter is metres along the line (radians of
    the turn when the origin does not move)."""
    length = float(np.linalg.norm(end.translation - start.translation))
    step = rotation_steps(np.stack([start.rotation, end.rotation]))[0]  # the turn, rad
    turn = float(np.linalg.norm(step))
    count = max(2, math.ceil(length / NODE_STEP_M) + 1, math.ceil(turn / NODE_STEP_RAD) + 1)
    fraction = np.linspace(0.0, 1.0, count)
    translation = start.translation + fraction[:, None] * (end.translation - start.translation)
    # slerp: the turn taken in equal parts about its one axis
    axis = step / turn if turn > 0.0 else np.array([0.0, 0.0, 1.0])
    rotation = matrix_from_axis_angle(axis, fraction * turn) @ start.rotation
    times = at + NOMINAL_STEP_S * (np.arange(count) - (count - 1 if ending else 0))
    nanoseconds = np.round(times * 1e9).astype(np.int64)
    poses = trusted_pose(rotation, translation, nanoseconds)
    if length > 1e-9:
        return TargetPath(poses, fraction * length, speed, np.ones(count))
    # a turn on the spot: no speed of the origin to keep
    return TargetPath(poses, fraction * max(turn, 1e-9), None, np.zeros(count))


def seam_path(seconds: FloatArray, travel: FloatArray, speed: float | None,
              weave: Weave | None, seam_in_torch: FloatArray) -> TargetPath:
    """The tool's target along a seam, in the torch target's frame, at the seam's own
    ``seconds`` (the nodes, see :func:`filled_times`): the torch target itself, or with
    ``weave`` moved across the seam frame's y (``seam_in_torch``: the seam frame's axes in
    the torch target's (3, 3)). ``travel`` (N, 3) is the seam frame's origin in its parent
    at the nodes, metres: the parameter is the seam's own seconds, or with ``speed`` metres
    along ``travel``."""
    count = seconds.shape[0]
    offsets = np.zeros((count, 3))
    if weave is not None:
        offsets = weave.offsets(seconds - seconds[0]) @ seam_in_torch.T
    steps = np.linalg.norm(np.diff(travel, axis=0), axis=1)
    if speed is None:
        parameter = seconds - seconds[0]
        rate = np.concatenate([steps / np.diff(parameter), [0.0]])
        per_parameter = np.maximum(rate, np.concatenate([[0.0], rate[:-1]]))
        poses = Pose(offsets, None, times=seconds)
        return TargetPath(poses, parameter, 1.0, per_parameter)
    keep = np.flatnonzero(np.concatenate([[True], steps > 1e-9]))  # standing still: once
    parameter = np.concatenate([[0.0], np.cumsum(steps)])[keep]
    poses = Pose(offsets[keep], None, times=seconds[keep])
    return TargetPath(poses, parameter, speed, np.ones(keep.shape[0]))


def filled_times(poses: Pose, seconds: FloatArray, weave: Weave | None) -> FloatArray:
    """``seconds`` with times added where the poses (their samples at ``seconds``) are
    further apart than the node steps, and where a ``weave`` needs
    :data:`WEAVE_NODES_PER_PERIOD` nodes a period."""
    moved = np.linalg.norm(np.diff(poses.translation, axis=0), axis=1)
    turned = np.linalg.norm(rotation_steps(poses.rotation), axis=1)
    pieces = np.maximum(np.ceil(moved / NODE_STEP_M), np.ceil(turned / NODE_STEP_RAD))
    if weave is not None:
        longest = 1.0 / (WEAVE_NODES_PER_PERIOD * weave.frequency)
        pieces = np.maximum(pieces, np.ceil(np.diff(seconds) / longest))
    pieces = np.maximum(pieces, 1).astype(int)
    if (pieces == 1).all():
        return seconds
    return np.concatenate([
        np.linspace(start, end, count, endpoint=False)
        for start, end, count in zip(seconds[:-1], seconds[1:], pieces.tolist(), strict=True)
    ] + [seconds[-1:]])


def offset_along_z(pose: Pose, distance: float) -> Pose:
    """``pose`` moved ``distance`` metres along its own -z (back from the work)."""
    return Pose(pose.translation - distance * pose.rotation[..., :, 2], pose.rotation)
