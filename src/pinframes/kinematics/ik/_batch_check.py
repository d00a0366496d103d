"""Measuring many solutions at once: the tool in its target at the samples the solver loop
took as solved without measuring them (a full Newton step from close by, see
:mod:`._newton_tracking`), from one pass of the compiled path's numpy forward kinematics
instead of Pinocchio's sample by sample; the rare sample that missed its tolerances is
solved again. The tilts of a tool in its process windows come from the same pass."""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from ...values.se3 import Transform, compose, inverse, samples_last, to_stacks
from .._plan import PreparedPath
from .._sampling import sample_joints
from ._newton_tracking import Tracked, TrackingProblem, solve_again
from ._tool_error import tilts_of

__all__ = ["check_unmeasured", "flat_errors", "tilts_at", "tools_in_targets"]

FloatArray = NDArray[np.float64]


def tools_in_targets(
    path: PreparedPath, times: NDArray[np.int64], shifts: dict[str, int],
    joint_names: tuple[str, ...], positions: FloatArray, targets: Transform | None,
) -> Transform:
    """The tool of ``path`` in its targets with the solved joints at ``positions`` (N, n) at
    ``times``: ``(N, 3, 3)`` rotations and ``(N, 3)`` translations (metres)."""
    model = path.model
    assert model is not None
    count = times.shape[0]
    held = {name: positions[:, column] for column, name in enumerate(joint_names)}
    samples = sample_joints(path.samplers, times, shifts, held=held)
    tool, reference = model.forward_kinematics(samples, [path.frame, path.relative_to])
    tool_in_target = compose(inverse(reference), tool)
    if targets is not None:
        tool_in_target = compose(inverse(samples_last(targets)), tool_in_target)
    return to_stacks(tool_in_target, count)


def check_unmeasured(path: PreparedPath, times: NDArray[np.int64], shifts: dict[str, int],
                     targets: Transform | None, problem: TrackingProblem, tracked: Tracked) -> None:
    """Measure the samples of ``problem`` that the loop took as solved unmeasured, all at
    once, and solve again (measuring) any that missed its tolerances; ``tracked`` is
    updated in place."""
    unmeasured = np.flatnonzero(~tracked.measured)
    if not unmeasured.shape[0]:
        return
    subset = None if targets is None else (targets[0][unmeasured], targets[1][unmeasured])
    position, orientation = problem.error.errors(*tools_in_targets(
        path, times[unmeasured], shifts, problem.joints.names,
        tracked.positions[unmeasured], subset))
    tracked.position_error[unmeasured] = position
    tracked.orientation_error[unmeasured] = orientation
    missed = (position > problem.position_tolerance) | (
        orientation > problem.orientation_tolerance)
    for index in unmeasured[missed]:
        (tracked.positions[index], tracked.position_error[index],
         tracked.orientation_error[index], tracked.reached[index]) = solve_again(
            problem, int(index), tracked.positions[index])


def tilts_at(
    path: PreparedPath, times: NDArray[np.int64], shifts: dict[str, int],
    joint_names: tuple[str, ...], positions: FloatArray, targets: Transform | None,
) -> FloatArray:
    """The tilts (N, 2) of the tool of ``path`` about its targets' x and y, radians, with the
    solved joints at ``positions`` (N, n)."""
    rotations, _ = tools_in_targets(path, times, shifts, joint_names, positions, targets)
    return tilts_of(rotations)


def flat_errors(path: PreparedPath, times: NDArray[np.int64], shifts: dict[str, int],
                joint_names: tuple[str, ...], positions: FloatArray, carrier: int,
                z_on_carrier: FloatArray, up: FloatArray) -> FloatArray:
    """Per sample (N,), the angle (radians) between a frame's z and ``up`` (both in the
    compiled model root's axes), the frame's z ``z_on_carrier`` in the axes of the model's
    joint ``carrier`` (its index), with the solved joints at ``positions`` (N, n)."""
    count = times.shape[0]
    held = {name: positions[:, column] for column, name in enumerate(joint_names)}
    samples = sample_joints(path.samplers, times, shifts, held=held)
    assert path.model is not None
    rotation = next(frame for index, frame in path.model.joint_frames(samples)
                    if index == carrier)[0]
    rotations = to_stacks((rotation, np.zeros((3, count))), count)[0]
    return np.arccos(np.clip(rotations.dot(z_on_carrier).dot(up), -1.0, 1.0))
