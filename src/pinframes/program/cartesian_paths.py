"""The tool's target along a linear or seam move, sampled densely enough for the joints
solved at the samples to keep the tool on the path between them.

A target path is a :class:`~pinframes.Pose` in the tree's root with one pose per node and a
path parameter per node: metres along a line, or the seam's own seconds (or metres along it
when it is welded at a given speed). Nodes are at most :data:`NODE_STEP_M` apart in
position and :data:`NODE_STEP_RAD` in rotation.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from ..values.interpolation import rotation_steps
from ..values.pose import Pose
from ..values.weave import Weave

__all__ = ["NODE_STEP_M", "NODE_STEP_RAD", "TargetPath", "line_path", "offset_along_z",
           "seam_path"]

FloatArray = NDArray[np.float64]

NODE_STEP_M = 0.002
"""Largest step of the tool's target between two nodes, metres."""
NODE_STEP_RAD = 0.02
"""Largest turn of the tool's target between two nodes, radians."""


@dataclass(frozen=True)
class TargetPath:
    """Target poses of the tool at nodes along a path.

    Attributes
    ----------
    poses : Pose
        One pose per node (N), in the tree's root; its times are the nodes' parameter
        values read as seconds (what ``solve_joints`` is given; nothing else moves then).
    parameter : ndarray, shape (N,)
        The path parameter, strictly increasing: metres along it, or the seam's own seconds.
    parameter_speed : float or None
        The highest rate of the parameter (m/s, or 1 for a seam on its own times).
    tool_speed_per_parameter : ndarray, shape (N,)
        The tool origin's speed per unit rate of the parameter (1 for metres along it).
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


def line_path(start: Pose, end: Pose, speed: float | None) -> TargetPath:
    """From ``start`` to ``end`` (static poses in the root): the origin on the straight
    line, the rotation slerped; the parameter is metres along the line (radians of the turn
    when the origin does not move)."""
    length = float(np.linalg.norm(end.translation - start.translation))
    turn = float(np.linalg.norm(rotation_steps(np.stack([start.rotation, end.rotation]))))
    count = max(2, math.ceil(length / NODE_STEP_M) + 1, math.ceil(turn / NODE_STEP_RAD) + 1)
    fraction = np.linspace(0.0, 1.0, count)
    ends = Pose(np.stack([start.translation, end.translation]),
                np.stack([start.rotation, end.rotation]), times=[0.0, 1.0])
    sampled = ends.at(fraction)
    if length > 1e-9:
        parameter, per_parameter, speed_limit = fraction * length, np.ones(count), speed
    else:  # a turn on the spot: no speed of the origin to keep
        parameter, per_parameter, speed_limit = fraction * max(turn, 1e-9), np.zeros(count), None
    return TargetPath(_timed(sampled, parameter), parameter, speed_limit, per_parameter)


def seam_path(poses: Pose, seconds: FloatArray, speed: float | None,
              weave: Weave | None, seam_in_torch: FloatArray | None = None) -> TargetPath:
    """The torch's target along a seam: ``poses`` (in the root) at the seam's own
    ``seconds``, filled in between to the node steps, woven across the seam's y when
    ``weave`` is given (``seam_in_torch``: the rotation (3, 3) of the seam frame's axes in
    the torch target's, default the identity), and parameterised by its own seconds or,
    with ``speed``, by metres along it."""
    filled, filled_seconds = _filled(poses, seconds)
    if weave is not None:
        offsets = weave.offsets(filled_seconds - filled_seconds[0])
        if seam_in_torch is not None:
            offsets = offsets @ seam_in_torch.T
        woven = Pose(filled.translation + np.einsum("nij,nj->ni", filled.rotation, offsets),
                     filled.rotation, times=filled_seconds)
        filled, filled_seconds = _filled(woven, filled_seconds)
    steps = np.linalg.norm(np.diff(filled.translation, axis=0), axis=1)
    if speed is None:
        parameter = filled_seconds - filled_seconds[0]
        rate = np.concatenate([steps / np.diff(parameter), [0.0]])
        per_parameter = np.maximum(rate, np.concatenate([[0.0], rate[:-1]]))
        return TargetPath(_timed(filled, parameter), parameter, 1.0, per_parameter)
    keep = np.concatenate([[True], steps > 1e-9])  # nodes where the seam stands still: once
    kept = filled[np.flatnonzero(keep)]
    parameter = np.concatenate([[0.0], np.cumsum(steps[keep[1:]])])
    return TargetPath(_timed(kept, parameter), parameter, speed, np.ones(parameter.shape[0]))


def offset_along_z(pose: Pose, distance: float) -> Pose:
    """``pose`` moved ``distance`` metres along its own -z (back from the work)."""
    return Pose(pose.translation - distance * pose.rotation[..., :, 2], pose.rotation)


def _filled(poses: Pose, seconds: FloatArray) -> tuple[Pose, FloatArray]:
    """``poses`` at ``seconds`` with nodes added where two are further apart than the node
    steps (the poses interpolated as the pose does)."""
    moved = np.linalg.norm(np.diff(poses.translation, axis=0), axis=1)
    turned = np.linalg.norm(rotation_steps(poses.rotation), axis=1)
    pieces = np.maximum(np.ceil(moved / NODE_STEP_M), np.ceil(turned / NODE_STEP_RAD))
    pieces = np.maximum(pieces, 1).astype(int)
    if (pieces == 1).all():
        return poses, seconds
    filled = np.concatenate([
        np.linspace(start, end, count, endpoint=False)
        for start, end, count in zip(seconds[:-1], seconds[1:], pieces.tolist(), strict=True)
    ] + [seconds[-1:]])
    timed = Pose(poses.translation, poses.rotation, times=seconds)
    return timed.at(filled), filled


def _timed(poses: Pose, parameter: FloatArray) -> Pose:
    return Pose(poses.translation, poses.rotation, times=parameter)
