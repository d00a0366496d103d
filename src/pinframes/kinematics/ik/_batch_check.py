"""Measuring many solutions at once: the tool in its target at the samples the solver loop
took as solved without measuring them (a full Newton step from close by, see
:mod:`._newton_tracking`), from one pass of the compiled path's numpy forward kinematics
instead of Pinocchio's sample by sample; the rare sample that missed its tolerances is
solved again. The tilts of a tool in its process windows come from the same pass."""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from ...values.se3 import (
    Transform,
    compose,
    inverse,
    rotated_vector,
    rotation_product,
    rotations_first,
    samples_last,
    to_stacks,
    vectors_first,
)
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
    """The tool of ``path`` in its ``targets`` (samples last: ``(3, 3[, N])`` rotations,
    ``(3[, N])`` translations, metres) with the solved joints at ``positions`` (N, n) at
    ``times``: ``(N, 3, 3)`` rotations and ``(N, 3)`` translations (metres), read-only in
    spirit: views of samples-last arrays, whose rows the error kernels read contiguously."""
    model = path.model
    assert model is not None
    count = times.shape[0]
    held = {name: positions[:, column] for column, name in enumerate(joint_names)}
    samples = sample_joints(path.samplers, times, shifts, held=held)
    tool, reference = model.forward_kinematics(samples, [path.frame, path.relative_to])
    rotation, translation = compose(inverse(reference), tool)
    if targets is not None:  # the target's inverse applied at once: one rotated vector
        target_rotation, target_translation = targets
        transposed = np.swapaxes(target_rotation, 0, 1)
        rotation = rotation_product(transposed, rotation)
        translation = rotated_vector(transposed, _difference(translation, target_translation))
    if rotation.ndim == 2 or translation.ndim == 1:
        return to_stacks((rotation, translation), count)
    return rotations_first(rotation), vectors_first(translation)


def _difference(left: FloatArray, right: FloatArray) -> FloatArray:
    """``left - right`` for static ``(3,)`` or batched ``(3, N)`` vectors."""
    if left.ndim == right.ndim:
        return left - right
    return (left[:, None] if left.ndim == 1 else left) - (
        right[:, None] if right.ndim == 1 else right)


def check_unmeasured(path: PreparedPath, times: NDArray[np.int64], shifts: dict[str, int],
                     targets: Transform | None, problem: TrackingProblem, tracked: Tracked) -> None:
    """Measure the samples of ``problem`` that the loop took as solved unmeasured, all at
    once, and solve again (measuring) any that missed its tolerances; ``tracked`` is
    updated in place."""
    unmeasured = np.flatnonzero(~tracked.measured)
    if not unmeasured.shape[0]:
        return
    subset = None if targets is None else samples_last(
        (targets[0][unmeasured], targets[1][unmeasured]))
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
    rotations, _ = tools_in_targets(path, times, shifts, joint_names, positions,
                                    None if targets is None else samples_last(targets))
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
