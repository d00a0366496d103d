"""A solve's arm in closed form: whether the solved joints are a 6-axis arm of a family of
:mod:`..closed_form` (their screws at zero read from Pinocchio's Jacobian of the tool), the
flange motions each target asks, and a whole path tracked on one branch.

Tracking: every sample's eight branches come from the closed form; the shoulder and elbow
of the requested configuration, else of the branch nearest the start at the first sample,
are kept, and without a requested configuration the wrist passes through its straight
position continuously (between samples it takes the other wrist branch where that moves the
wrist joints less). Each joint is then unwrapped along the path and moved by whole turns to
start nearest the start within its limits. A path that this branch does not reach at every
sample is left to the numeric solver unless a configuration was requested.
"""

from __future__ import annotations

from typing import Any

import numpy as np
import pinocchio as pin
from numpy.typing import NDArray

from ...errors import JointError
from ...values.se3 import Transform, compose, inverse
from .._plan import PreparedPath
from .._sampling import KERNEL_CHUNK, sample_joints
from ..closed_form.arm_shapes import ArmShape, recognise_arm
from ..closed_form.configurations import branch_flags, kuka_status, wrist_flips
from ..closed_form.solutions import (
    LIMIT_SLACK,
    branch_angles,
    free_wrist_joint,
    straight_wrists,
    turn_periods,
)
from ._newton_tracking import Tracked
from ._path_chunks import TARGET_SOURCE, PathToSolve, raise_unreached, targets_last
from ._solved_joints import SolvedJoints

__all__ = ["AT_START", "JUMP", "arm_order", "closed_form_arm", "flange_motions",
           "solve_in_closed_form", "track_in_closed_form"]

FloatArray = NDArray[np.float64]

_LOCAL = pin.ReferenceFrame.LOCAL

AT_START = 1e-12
"""Radians within which a closed-form solution is the start itself (rounding)."""

JUMP = 0.02
"""Radians: a step this much longer than four times the path's median step is a jump."""


def closed_form_arm(path: PreparedPath, solved: SolvedJoints, frame: str) -> ArmShape:
    """The :class:`ArmShape` of ``solved`` on ``path`` (cached with the path), else
    :class:`~pinframes.errors.JointError` saying why not."""
    key = "closed form arm: " + "\0".join(solved.names)
    refused = path.plans.get(JointError, key)
    if refused is not None:
        raise refused
    cached = path.plans.get(ArmShape, key)
    if cached is None:
        try:
            cached = path.plans.keep(ArmShape, key, _arm(path, solved, frame))
        except JointError as error:
            raise path.plans.keep(JointError, key, error) from None
    return cached


def _arm(path: PreparedPath, solved: SolvedJoints, frame: str) -> ArmShape:
    model = path.model
    assert model is not None
    if solved.moves_reference:
        raise JointError("closed-form inverse kinematics is for an arm that moves the tool "
                         "only; a solved joint moves the target's frame", frame=frame,
                         field="joints")
    if len(solved.names) != 6:
        raise JointError(f"closed-form inverse kinematics is for six joints in a chain; got "
                         f"{len(solved.names)}", frame=frame, field="joints")
    drives = solved.tangent != 0.0
    if not np.all(drives.sum(axis=0) == 1):
        raise JointError("closed-form inverse kinematics is for an arm whose joints each "
                         "turn one axis; a solved joint drives mimic joints", frame=frame,
                         field="joints")
    slots = np.argmax(drives, axis=0)
    pinocchio_model = model.model
    tool = model.frame_ids[frame]
    support = [joint for joint in pinocchio_model.supports[
        pinocchio_model.frames[tool].parentJoint] if joint > 0]
    moving = [pinocchio_model.idx_vs[joint] for joint in support]
    first = min(int(slot) for slot in slots)
    between = [slot for slot in moving if slot >= first and slot not in set(slots.tolist())]
    if between:
        raise JointError("closed-form inverse kinematics is for an arm whose solved joints "
                         "are all that moves between its base and the tool", frame=frame,
                         field="joints")
    q = pin.neutral(pinocchio_model)
    solved.set_configuration(q, np.zeros(len(solved.names)))
    data = pinocchio_model.createData()
    jacobian = solved.jacobian(pin.computeFrameJacobian(pinocchio_model, data, q, tool, _LOCAL)
                               .reshape(6, -1))
    order = np.argsort(slots, kind="stable")
    pin.framesForwardKinematics(pinocchio_model, data, q)
    base_joint = next(joint for joint in support
                      if pinocchio_model.idx_vs[joint] == int(slots[order[0]]))
    up = data.oMf[tool].rotation.T @ data.oMi[base_joint].rotation[:, 2]
    turning = jacobian[3:, order].T
    scales = np.linalg.norm(turning, axis=1)
    for column, scale in zip(order, scales, strict=True):
        if scale == 0.0:
            raise JointError(f"closed-form inverse kinematics is for revolute joints; "
                             f"{solved.names[column]!r} is not one", frame=frame,
                             field="joints")
    axes = turning / scales[:, None]
    points = np.cross(axes, jacobian[:3, order].T)
    return recognise_arm([solved.names[column] for column in order], axes, points, scales, up,
                         frame)


def arm_order(shape: ArmShape, names: tuple[str, ...]) -> list[int]:
    """The columns of ``names`` in the shape's joint order."""
    return [names.index(name) for name in shape.joint_names]


def flange_motions(path: PreparedPath, times: NDArray[np.int64], shifts: dict[str, int],
                   names: tuple[str, ...], targets: Transform | None) -> Transform:
    """Per time, the motion of the tool from where the solved joints at zero put it to its
    target (``targets`` samples last, see :func:`._path_chunks.targets_last`), in the tool's
    axes there: ``(3, 3, N)`` rotations and ``(3, N)`` translations (samples last)."""
    count = times.shape[0]
    zeros = dict.fromkeys(names, 0.0)
    model = path.model
    assert model is not None
    samples = sample_joints(path.samplers, times, shifts, held=zeros)
    tool, reference = model.forward_kinematics(samples, [path.frame, path.relative_to])
    motion = compose(inverse(tool), reference)
    if targets is not None:
        motion = compose(motion, targets)
    rotation, translation = motion
    return (np.broadcast_to(rotation.reshape(3, 3, -1), (3, 3, count)),
            np.broadcast_to(translation.reshape(3, -1), (3, count)))


def track_in_closed_form(
    shape: ArmShape, path: PreparedPath, times: NDArray[np.int64], shifts: dict[str, int],
    solved: SolvedJoints, targets: Any, start: FloatArray, branch: tuple[str, int] | None,
) -> tuple[FloatArray, NDArray[np.bool_], NDArray[np.int64] | None]:
    """Joint values (T, n) in ``solved``'s order along the path, where the branch has a
    solution within the limits (T,), and each sample's branch index when the shoulder and
    elbow were kept (None when a KUKA Status or a singular crossing chose them); ``branch`` as
    :func:`..closed_form.configurations.requested_branch` gives it, or None (the start's).
    ``targets(part)`` gives the targets of the samples ``part`` (None: the frame itself).

    The passes along the path hold one row per joint (6, T): a step, a wrap or a largest
    step is then a pass over contiguous rows (over the last axis of (T, 6) it ran several
    times slower)."""
    order = arm_order(shape, solved.names)
    lower, upper = solved.limits.lower[order, None], solved.limits.upper[order, None]
    start = start[order]
    period = turn_periods(shape)[:, None]
    count = times.shape[0]
    chunks = [flange_motions(path, times[begin:begin + KERNEL_CHUNK], shifts, solved.names,
                             targets(slice(begin, begin + KERNEL_CHUNK)))
              for begin in range(0, count, KERNEL_CHUNK)]

    joined: list[Transform] = []  # the chunks joined, once samples beyond the first ask

    def solved_at(rows: Any, arm: int | None, free: FloatArray | None = None) -> FloatArray:
        if isinstance(rows, slice) and rows.stop is not None and rows.stop <= KERNEL_CHUNK:
            source = chunks[0]
        else:
            if not joined:
                joined.append((np.concatenate([chunk[0] for chunk in chunks], axis=-1),
                               np.concatenate([chunk[1] for chunk in chunks], axis=-1)))
            source = joined[0]
        moved = source[0][..., rows], source[1][..., rows]
        parts = [branch_angles(shape, moved[0][..., begin:begin + KERNEL_CHUNK],
                               moved[1][..., begin:begin + KERNEL_CHUNK], arm,
                               None if free is None else free[begin:begin + KERNEL_CHUNK])
                 for begin in range(0, moved[1].shape[-1], KERNEL_CHUNK)]
        return np.concatenate(parts)

    kept: int | None = None
    steps: FloatArray | None = None  # the path's steps, once known
    if branch is not None and branch[0] == "kuka_status":
        angles = solved_at(slice(None), None)
        matching = kuka_status(shape, angles) == branch[1]
        positions = angles[np.arange(count), np.argmax(matching, axis=1)].T.copy()
        positions[:, ~matching.any(axis=1)] = np.nan
    else:
        candidates = np.empty((2, 6, count))  # per wrist, joint by joint
        first_chunk = 0  # the chunks solved already
        if branch is None:  # the branch nearest the start at the first sample
            # (the first sample's four arms beside the first chunk on the start's own arm,
            # in one pass: a call's fixed cost is that of a few hundred numpy operations)
            guess = int(branch_flags(shape, start[None])[0]) & 6
            rotation, translation = chunks[0]
            size = translation.shape[-1]
            together = branch_angles(
                shape, np.concatenate([np.repeat(rotation[..., :1], 4, axis=-1), rotation],
                                      axis=-1),
                np.concatenate([np.repeat(translation[..., :1], 4, axis=-1), translation],
                               axis=-1),
                np.concatenate([np.arange(0, 8, 2), np.full(size, guess)]))
            away = together[:4].reshape(8, 6) - start
            away -= period.T * np.rint(away / period.T)
            arm = int(np.argmin(np.where(np.isnan(away).any(axis=1), np.inf,
                                         np.abs(away).max(axis=1)))) & 6
            if arm == guess:
                candidates[..., :size] = together[4:].transpose(1, 2, 0)
                first_chunk = 1
        else:
            arm = branch[1] & 6
        for index in range(first_chunk, len(chunks)):
            begin = index * KERNEL_CHUNK
            candidates[..., begin:begin + KERNEL_CHUNK] = branch_angles(
                shape, *chunks[index], arm).transpose(1, 2, 0)
        flip = (np.full(count, bool(branch[1] & 1)) if branch is not None
                else _wrist_passing_through(candidates, start, period))
        positions = np.where(flip, candidates[1], candidates[0])
        _hold_free_wrist(shape, positions, start, lambda rows, free: solved_at(
            rows, arm, free)[np.arange(free.shape[0]), flip[rows].astype(np.intp)])
        kept = arm
        steps = _wrapped_steps(positions, period)
        if branch is None and _jumps(steps):
            free = positions[free_wrist_joint(shape)]
            positions = _nearest_all_along(solved_at(slice(None), None, free), start,
                                           period[:, 0]).T.copy()
            kept = None
            steps = None
    positions = _unwrapped_within(positions, start, period, lower, upper, steps)
    # a sample the start already reaches keeps it as it is (not its rounded closed form)
    columns = start[:, None]
    positions[:, np.abs(positions - columns).max(axis=0) <= AT_START] = columns
    valid = np.all((positions >= lower - LIMIT_SLACK) & (positions <= upper + LIMIT_SLACK),
                   axis=0)  # (False where NaN)
    result = np.empty((count, 6))
    result[:, order] = positions.T
    branches = None if kept is None else kept + wrist_flips(shape, positions[4])
    return result, valid, branches


def _hold_free_wrist(shape: ArmShape, positions: FloatArray, start: FloatArray,
                     again: Any) -> None:
    """The samples of ``positions`` (6, T) at a straight wrist solved ``again(rows, free)``
    ((rows, 6)) with the wrist's free joint held where the sample before left it (the
    first: the start), in place."""
    straight = straight_wrists(shape, positions[4])
    if not straight.any():
        return
    joint = free_wrist_joint(shape)
    index = np.arange(positions.shape[1])
    before = np.maximum.accumulate(np.where(straight, -1, index))
    held = np.where(before >= 0, positions[joint, np.maximum(before, 0)], start[joint])
    rows = np.flatnonzero(straight)
    positions[:, rows] = again(rows, held[rows]).T


def _wrapped_steps(positions: FloatArray, period: FloatArray) -> FloatArray:
    """The steps (6, T - 1) between the samples of ``positions`` (6, T), each joint's the
    shorter way round (``period`` (6, 1))."""
    steps = positions[:, 1:] - positions[:, :-1]
    steps -= period * np.rint(steps / period)
    return steps


def _jumps(steps: FloatArray) -> bool:
    """Whether one of the path's ``steps`` (6, T - 1) is far longer than its usual step (a
    singular configuration crossed: the closed form's branch changes name there)."""
    if not steps.shape[1]:
        return False
    longest = np.nan_to_num(np.abs(steps).max(axis=0))
    return bool((longest > JUMP + 4.0 * np.median(longest)).any())


def _nearest_all_along(angles: FloatArray, start: FloatArray, period: FloatArray
                       ) -> FloatArray:
    """Per sample of ``angles`` (T, 8, 6), the solution nearest the one before (the first:
    nearest ``start``), unwrapped onto it; a sample out of reach is NaN and the next is
    compared with the last solution. A loop over the samples: taken only where a
    singular configuration is crossed."""
    positions = np.full(angles.shape[::2], np.nan)
    previous = start
    for sample in range(angles.shape[0]):
        steps = angles[sample] - previous
        steps -= period * np.rint(steps / period)
        distances = np.abs(steps).max(axis=1)
        if np.isnan(distances).all():
            continue
        previous = positions[sample] = previous + steps[int(np.nanargmin(distances))]
    return positions


def _wrist_passing_through(candidates: FloatArray, start: FloatArray, period: FloatArray
                           ) -> NDArray[np.bool_]:
    """Which of the two wrists (2, 6, T) per sample (True: the second): the start's nearest
    at the first, then the other where it moves the joints less than staying (the two
    wrists are one turn of joints 4 and 6 by half a turn and joint 5 mirrored, so the
    comparison does not depend on which is held)."""
    wrists, start, period = candidates[:, 3:], start[3:, None], period[3:]  # 1 to 3 are one

    def distance(first: FloatArray, second: FloatArray) -> FloatArray:
        steps = second - first
        steps -= period * np.rint(steps / period)
        return np.abs(steps).sum(axis=0)

    stay = distance(wrists[0, :, :-1], wrists[0, :, 1:])
    switch = distance(wrists[0, :, :-1], wrists[1, :, 1:])
    toggles = np.empty(stay.shape[0] + 1, dtype=np.int64)
    toggles[0] = distance(start, wrists[1, :, :1])[0] < distance(start, wrists[0, :, :1])[0]
    toggles[1:] = switch < stay
    return np.cumsum(toggles) % 2 == 1


def _unwrapped_within(positions: FloatArray, start: FloatArray, period: FloatArray,
                      lower: FloatArray, upper: FloatArray, steps: FloatArray | None
                      ) -> FloatArray:
    """``positions`` (6, T) unwrapped along the path and moved by whole turns to begin
    nearest ``start``, or where a move by a few turns keeps a joint within its limits all
    along, that one (NaN columns are kept and skipped); ``steps`` their
    :func:`_wrapped_steps`, when known; ``period``, ``lower``, ``upper`` (6, 1)."""
    known = ~np.isnan(positions).any(axis=0)
    if not known.any():
        return positions
    everywhere = bool(known.all())
    values = positions if everywhere else positions[:, known]
    if steps is None or not everywhere:
        steps = _wrapped_steps(values, period)
    unwrapped = np.empty_like(values)
    unwrapped[:, 0] = values[:, 0]
    np.cumsum(steps, axis=1, out=unwrapped[:, 1:])
    unwrapped[:, 1:] += values[:, :1]
    for joint in range(6):
        row, turn = unwrapped[joint], float(period[joint, 0])
        near = np.rint((start[joint] - row[0]) / turn)
        low, high = float(row.min()), float(row.max())
        for turns in sorted(range(-2, 3), key=abs):
            shift = (near + turns) * turn
            if low + shift >= lower[joint, 0] - LIMIT_SLACK and (
                    high + shift <= upper[joint, 0] + LIMIT_SLACK):
                near += turns
                break
        row += near * turn
    if everywhere:
        return unwrapped
    result = positions.copy()
    result[:, known] = unwrapped
    return result


def solve_in_closed_form(request: PathToSolve, shape: ArmShape, start: FloatArray,
                         branch: tuple[str, int] | None, strict: bool, frame: str
                         ) -> tuple[Tracked, NDArray[np.int64] | None] | None:
    """The solve of ``request`` tracked on one branch (:func:`track_in_closed_form`), its
    errors measured with the compiled path's forward kinematics; None when no
    configuration was requested and the branch misses a sample (the numeric solver then
    solves it). Where a requested branch has no solution, the sample holds the nearest
    one before it (else after it, else ``start``) and is not reached. With it, each sample's
    branch index where :func:`track_in_closed_form` knows them."""
    plan = request.plan
    path, times, shifts = plan.path, plan.sample_times, plan.shifts
    shift = shifts.get(TARGET_SOURCE, 0)
    sampled: dict[int, Transform | None] = {}  # by chunk start: each chunk sampled once

    def targets(part: slice) -> Transform | None:
        if part.start not in sampled:
            sampled[part.start] = targets_last(request.target, times[part], shift)
        return sampled[part.start]

    positions, valid, branches = track_in_closed_form(shape, path, times, shifts,
                                                      request.joints, targets, start, branch)
    if not valid.all():
        if branch is None:
            return None
        positions = _held_where_missing(positions, valid, start)
    position_error = np.empty(times.shape[0])
    orientation_error = np.empty(times.shape[0])
    for begin in range(0, times.shape[0], KERNEL_CHUNK):
        part = slice(begin, begin + KERNEL_CHUNK)
        position_error[part], orientation_error[part] = _pose_errors(
            path, times[part], shifts, request.joints.names, positions[part], targets(part))
    reached = valid & (position_error <= request.position_tolerance) & (
        orientation_error <= request.orientation_tolerance)
    tracked = Tracked(positions, position_error, orientation_error, reached,
                      np.ones(times.shape[0], dtype=bool))
    if strict and not reached.all():
        index = int(np.argmin(reached))
        raise_unreached(request, index, float(position_error[index]),
                        float(orientation_error[index]), frame)
    return tracked, branches


def _pose_errors(path: PreparedPath, times: NDArray[np.int64], shifts: dict[str, int],
                 names: tuple[str, ...], positions: FloatArray, targets: Transform | None
                 ) -> tuple[FloatArray, FloatArray]:
    """Position (m) and orientation (rad) errors (N,) of the tool in its targets with the
    solved joints at ``positions`` (N, n), by the compiled path's forward kinematics:
    what :class:`._tool_error.PoseMatch` measures, without forming the tool in each target
    (``|p - p_target|``, and the angle from ``trace(R_target^T R) = 1 + 2 cos`` and
    ``sum_k target_k x r_k = 2 sin axis``, the columns' cross products)."""
    model = path.model
    assert model is not None
    held = {name: positions[:, column] for column, name in enumerate(names)}
    samples = sample_joints(path.samplers, times, shifts, held=held)
    tool, reference = model.forward_kinematics(samples, [path.frame, path.relative_to])
    rotation, translation = compose(inverse(reference), tool)  # samples last
    if targets is None:
        wanted, place = np.eye(3), np.zeros(3)
    else:
        wanted, place = targets
    offset = translation.reshape(3, -1) - place.reshape(3, -1)
    cosine = sum(wanted[i, j] * rotation[i, j] for i in range(3) for j in range(3))
    across = [sum(wanted[(i + 1) % 3, k] * rotation[(i + 2) % 3, k]
                  - wanted[(i + 2) % 3, k] * rotation[(i + 1) % 3, k] for k in range(3))
              for i in range(3)]
    return (np.sqrt(offset[0] ** 2 + offset[1] ** 2 + offset[2] ** 2),
            np.arctan2(0.5 * np.sqrt(across[0] ** 2 + across[1] ** 2 + across[2] ** 2),
                       0.5 * (cosine - 1.0)))


def _held_where_missing(positions: FloatArray, valid: NDArray[np.bool_], start: FloatArray
                        ) -> FloatArray:
    """``positions`` with each invalid row the nearest valid row before it, else after it,
    else ``start``."""
    if not valid.any():
        return np.broadcast_to(start, positions.shape).copy()
    index = np.arange(valid.shape[0])
    before = np.maximum.accumulate(np.where(valid, index, -1))
    after = np.minimum.accumulate(np.where(valid, index, valid.shape[0])[::-1])[::-1]
    source = np.where(before >= 0, before, after)
    return positions[source]
