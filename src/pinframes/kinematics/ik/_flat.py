"""Flat welding: a frame's z turned toward up, a secondary task in the null space of the tool's.

With a positioner solved together with the robot, the joints have freedom left once the tool
is on its target; :class:`FlatFrame` spends it on turning a frame of the workpiece (a seam:
its z the face of the weld) so that its z points up. Its task has two rows, the angular
velocity of the frame across its z (its x and y, in the model root's axes) per unit rate of
each solved joint, ``B``, and asks for the rotation ``w`` that carries z onto up, across z.
Within the null space ``N`` of the tool's rows ``A``, the motion is the task-priority step
``(B N)^+ w``: the smallest with ``A m = 0`` and ``B m = w``, from one damped least-squares
solve of the two stacked (the solver's projection keeps it whole, and removes what the
damping lets into the tool's rows), at most :data:`LONGEST_TURN` per joint.
A joint whose step would cross its limit goes to the limit and the others solve for the
rest. Where the remaining freedom cannot turn the frame further, the motion fades and the
frame stays as close to up as it gets.

A sample solved from a start is served until the frame is within :data:`FLAT_ENOUGH` of up;
a tracked sample only when it is beyond its tolerance (one forward kinematics to look),
then by one step, or a few until it is within (:data:`TRACKED_ROUNDS`): the tool's smallest
motion lets the frame drift a little per sample, and serving only where that adds up keeps
``flat=`` within twice a plain solve's time (benchmarks/bench_positioner.py). The
prediction of each sample carries on the whole last step, the positioner's turning included
(``carries_self_motion``), so the frame drifts by second-order amounts only and few samples
need serving.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Iterator
from typing import Any

import numpy as np
import pinocchio as pin
from numpy.typing import NDArray

from ...errors import JointError
from ...values.numbers import unit_direction
from .._description import TreeDescription
from .._model import CompiledModel
from ._bounded_step import LeastSquares
from ._solved_joints import SolvedJoints

__all__ = ["FLAT_ENOUGH", "FLAT_ROUNDS", "FLAT_TOLERANCE", "SAME_START", "FlatFrame",
           "flat_objective"]

FloatArray = NDArray[np.float64]

FLAT_ENOUGH = 1e-9
"""Radians between the frame's z and up below which nothing more is asked on a sample solved
from a start (the first: to convergence)."""

FLAT_TOLERANCE = math.radians(0.5)
"""The default ``flat_tolerance``: radians between the frame's z and up below which nothing
is asked on a sample solved from a prediction: a sample beyond it is turned back (to within
the step's linearisation error), the others left as the tool's smallest motion put them."""

FLAT_ROUNDS = 100
"""Rounds at most on a sample solved from a start (each one a task-priority step)."""

TRACKED_ROUNDS = 5
"""Rounds at most on a tracked sample beyond the tolerance: one step turns the frame back to
within its linearisation error, which after a long time step can still exceed the
tolerance."""

SPREAD = 4
"""Starts per joint that turns the flat frame, spread over its range (within -pi..pi), for
the global choice of the first sample (:meth:`FlatFrame.flat_starts`)."""

MOST_TURNING = 3
"""Joints that turn the flat frame spread over at most (the first ones of the chain)."""

SAME_START = 1e-3
"""Radians or metres (largest joint difference) within which two turned-up starts are one."""

LONGEST_TURN = 0.3
"""Largest change of one joint per round, radians or metres."""

DAMPING = 1e-6
"""Damping of the two-row system (rad^2): where the freedom left cannot turn the frame, the
step stays small instead of growing without bound."""

SMALLEST_MOTION = 1e-12
"""Radians or metres: a motion no larger is nothing (the freedom is spent)."""

_WORLD_ALIGNED = pin.ReferenceFrame.LOCAL_WORLD_ALIGNED



class FlatFrame:
    """The secondary objective of ``solve_joints(flat=...)``.

    Parameters
    ----------
    model, data : pinocchio.Model, pinocchio.Data
        The compiled path (rooted at the lowest common ancestor of tool and target).
    joints : SolvedJoints
        The unknowns.
    joint_id : int
        The Pinocchio joint that carries the flat frame.
    rotation_on_joint : ndarray, shape (3, 3)
        The flat frame's axes in that joint's.
    up : ndarray, shape (3,)
        The unit direction the frame's z is turned toward, in the model root's axes.
    solver : LeastSquares
        The linear algebra of the null-space projection.
    """

    quiet_margin = math.inf
    rounds_tracked = TRACKED_ROUNDS
    rounds_from_a_start = FLAT_ROUNDS
    carries_self_motion = True

    def __init__(self, model: pin.Model, data: pin.Data, joints: SolvedJoints, joint_id: int,
                 rotation_on_joint: FloatArray, up: FloatArray, solver: LeastSquares,
                 tolerance: float = FLAT_TOLERANCE) -> None:
        self._model, self._data, self._joints = model, data, joints
        self.tolerance = tolerance  # radians
        self._within_tolerance = math.cos(tolerance)  # z dot up at least this: nothing asked
        self._joint_id = joint_id
        self.carrier = joint_id - 1  # the compiled model's index of the joint carrying it
        self._rotation_on_joint = np.asarray(rotation_on_joint, dtype=float)
        self._z_on_joint = self._rotation_on_joint[:, 2].copy()
        self._up = np.asarray(up, dtype=float)
        self._solver = solver

    def motion(self, theta: FloatArray, configuration: FloatArray,
               task_rows: Callable[[], FloatArray], settle: bool) -> FloatArray | None:
        """The task-priority step toward up (module docstring); None when the frame is
        within its tolerance of up (``settle``: :data:`FLAT_ENOUGH`) or the freedom
        left cannot turn it."""
        model, data = self._model, self._data
        if not settle:  # a look first: most samples stay within the tolerance
            pin.forwardKinematics(model, data, configuration)
            face = data.oMi[self._joint_id].rotation.dot(self._z_on_joint)
            if face.dot(self._up) >= self._within_tolerance:
                return None
        rows = task_rows()
        if not self._joints.moves_reference:  # else task_rows() computed them
            pin.computeJointJacobians(model, data, configuration)
        axes = self._axes()
        wanted = _turn_across(axes, self._up, FLAT_ENOUGH)
        if wanted is None:
            return None
        jacobian = pin.getJointJacobian(model, data, self._joint_id, _WORLD_ALIGNED)
        across = axes[:, :2].T.dot(self._joints.jacobian(jacobian)[3:])  # (2, n)
        # the smallest motion with rows @ m = 0 and across @ m = wanted: (B N)^+ w when the
        # stacked rows have full rank (the solver's projection removes what damping leaks)
        stacked = np.concatenate([rows, across])
        goal = np.zeros(stacked.shape[0])
        goal[-2:] = wanted
        motion: FloatArray = self._solver.correction(stacked, goal, DAMPING)
        limits = self._joints.limits
        beyond = (theta + motion > limits.upper) | (theta + motion < limits.lower)
        if beyond.any():  # those go to their limit, the others do the rest
            onto_limits = np.where(beyond, limits.clipped(theta + motion) - theta, 0.0)
            rest = goal - stacked.dot(onto_limits)
            stacked[:, beyond] = 0.0
            motion = self._solver.correction(stacked, rest, DAMPING) + onto_limits
        largest = float(np.abs(motion).max())
        if not largest > SMALLEST_MOTION:
            return None
        if largest > LONGEST_TURN:
            motion *= LONGEST_TURN / largest
        return motion

    def turned_up(self, theta: FloatArray, configuration: FloatArray) -> FloatArray:
        """``theta`` (n,) with the frame's z turned up by the joints alone, the tool let go:
        the default start of the first sample, so that the tool's smallest motion starts
        near a flat configuration rather than wherever the joints rest (from there the
        frame might only get to a local best against a limit). ``configuration``: the
        first sample's ``q``, copied."""
        model, data, joints = self._model, self._data, self._joints
        q = configuration.copy()
        for _ in range(FLAT_ROUNDS):
            joints.set_configuration(q, theta)
            pin.computeJointJacobians(model, data, q)
            axes = self._axes()
            wanted = _turn_across(axes, self._up, FLAT_ENOUGH)
            if wanted is None:
                break
            jacobian = pin.getJointJacobian(model, data, self._joint_id, _WORLD_ALIGNED)
            across = axes[:, :2].T.dot(joints.jacobian(jacobian)[3:])
            step = self._solver.correction(across, wanted, DAMPING)
            largest = float(np.abs(step).max())
            if largest > LONGEST_TURN:
                step *= LONGEST_TURN / largest
            moved = joints.limits.clipped(theta + step)
            if not float(np.abs(moved - theta).max()) > SMALLEST_MOTION:
                break
            theta = moved
        return theta

    def could_turn_up(self, theta: FloatArray, configuration: FloatArray) -> bool:
        """Whether the solved joints alone, the tool let go, turn the frame within the
        tolerance of up from ``theta`` or from any of the starts of :meth:`flat_starts`
        (``configuration``: the sample's ``q``): the frame could be flat there, also where
        ``theta`` holds a joint on its limit that another configuration leaves free (a turn
        joint at the end of its range, a whole turn short of one that is flat)."""
        return any(cosine >= self._within_tolerance
                   for _, cosine in self._turned_from_spread_starts(theta, configuration))

    def _cosine(self, theta: FloatArray, configuration: FloatArray) -> float:
        """The cosine of the frame's angle from up with the solved joints at ``theta``
        (``configuration``: the sample's ``q``, left as it is)."""
        q = configuration.copy()
        self._joints.set_configuration(q, theta)
        pin.forwardKinematics(self._model, self._data, q)
        face = self._data.oMi[self._joint_id].rotation.dot(self._z_on_joint)
        return float(face.dot(self._up))

    @property
    def z_on_carrier(self) -> FloatArray:
        """The flat frame's z (3,) in the axes of the joint that carries it."""
        return self._z_on_joint

    @property
    def up(self) -> FloatArray:
        """The unit direction (3,) the frame's z is turned toward, in the model root's axes."""
        return self._up

    def flat_starts(self, theta: FloatArray, configuration: FloatArray) -> list[FloatArray]:
        """The first sample's candidate starts (``configuration``: its ``q``): the
        configurations of :meth:`_turned_from_spread_starts` within the tolerance of up,
        distinct (:data:`SAME_START` apart), ``theta``'s own first; when none is within, the
        one nearest up (the first of equals).

        A local turn from one start can stop where the frame's z only spins about up's level
        (no first-order gain) or on a limit; and of the configurations that turn the first
        sample up, only some may keep it up along the path (a turn joint of 400 degrees that
        a whole girth seam needs from one end of its range): the caller tracks each."""
        flat: list[FloatArray] = []
        nearest, nearest_cosine = theta, -math.inf
        for turned, cosine in self._turned_from_spread_starts(theta, configuration):
            if cosine >= self._within_tolerance:
                if all(float(np.abs(turned - other).max()) > SAME_START for other in flat):
                    flat.append(turned)
            elif cosine > nearest_cosine:
                nearest, nearest_cosine = turned, cosine
        return flat or [nearest]

    def _turned_from_spread_starts(self, theta: FloatArray, configuration: FloatArray
                                   ) -> Iterator[tuple[FloatArray, float]]:
        """:meth:`turned_up` from ``theta``, then from starts spread over the ranges of the
        joints that turn the frame (:data:`SPREAD` values each, within -pi..pi, the others
        as in ``theta``), each with the cosine of the frame's angle from up there
        (``configuration``: the sample's ``q``)."""
        joints = self._joints
        q = configuration.copy()
        joints.set_configuration(q, theta)
        pin.computeJointJacobians(self._model, self._data, q)
        jacobian = joints.jacobian(pin.getJointJacobian(self._model, self._data,
                                                        self._joint_id, _WORLD_ALIGNED))
        turning = np.flatnonzero(np.abs(jacobian[3:]).max(axis=0) > 0.0)[:MOST_TURNING]
        limits = joints.limits
        grids = []
        for column in turning.tolist():
            low = max(float(limits.lower[column]), -math.pi)
            high = min(float(limits.upper[column]), math.pi)
            grids.append(low + (high - low) * (np.arange(SPREAD) + 0.5) / SPREAD)
        starts = [theta]
        for values in (np.stack(np.meshgrid(*grids, indexing="ij"), -1).reshape(-1, len(grids))
                       if grids else ()):
            start = theta.copy()
            start[turning] = values
            starts.append(start)
        for start in starts:
            turned = self.turned_up(start, configuration)
            yield turned, self._cosine(turned, configuration)

    def angles(self, positions: FloatArray, configurations: FloatArray) -> FloatArray:
        """Per sample (N,), the frame's angle from up (radians) with the solved joints at
        ``positions`` (N, n); ``configurations`` (at least N, nq): the samples' ``q``, left as
        they are."""
        cosines = [self._cosine(theta, q) for theta, q in
                   zip(positions, configurations[:positions.shape[0]], strict=True)]
        return np.arccos(np.clip(cosines, -1.0, 1.0))

    def _axes(self) -> FloatArray:
        """The flat frame's axes (3, 3) in the model root's, from Pinocchio's data."""
        return self._data.oMi[self._joint_id].rotation.dot(self._rotation_on_joint)  # type: ignore[no-any-return]


def _turn_across(axes: FloatArray, up: FloatArray, tolerance: float) -> FloatArray | None:
    """The rotation (2,) carrying the frame's z onto ``up``, in the frame's x and y (rad:
    its length the angle between them); None within ``tolerance`` (rad). Upside down, half
    a turn about x."""
    (x_x, y_x, z_x), (x_y, y_y, z_y), (x_z, y_z, z_z) = axes.tolist()
    up_x, up_y, up_z = up.tolist()
    # z x up, in the frame's axes: its z component is 0
    normal_x, normal_y, normal_z = (z_y * up_z - z_z * up_y, z_z * up_x - z_x * up_z,
                                    z_x * up_y - z_y * up_x)
    along_x = x_x * normal_x + x_y * normal_y + x_z * normal_z
    along_y = y_x * normal_x + y_y * normal_y + y_z * normal_z
    sine = math.hypot(along_x, along_y)
    angle = math.atan2(sine, z_x * up_x + z_y * up_y + z_z * up_z)
    if angle <= tolerance:
        return None
    if sine == 0.0:
        return np.array([angle, 0.0])
    return np.array([along_x * angle / sine, along_y * angle / sine])


def flat_objective(tree: TreeDescription, model: CompiledModel, joints: SolvedJoints,
                   flat: str, up: Any, frame: str, solver: LeastSquares,
                   tolerance: float = FLAT_TOLERANCE) -> FlatFrame:
    """The :class:`FlatFrame` of ``solve_joints(frame, ..., flat=flat, up=up)`` on the
    compiled path ``model``; ``up`` a 3-vector in the tree root's axes (None: its +z), which
    the root of ``model`` (where tool and target meet) must not turn."""
    up_in_root = _unit_vector(up, frame)
    anchor, (rotation_on_anchor, _) = tree.anchor(flat)
    model_root_anchor, (model_root_in_root, _) = tree.anchor(model.root)
    if model_root_anchor != tree.root:
        raise JointError(f"flat= takes up in the root's axes, and {model.root!r} (where tool "
                         f"and target meet) moves in the root", frame=model.root, field="up")
    carriers = [index + 1 for index, joint in enumerate(model.joints) if joint.frame == anchor]
    pinocchio_model = model.model
    if carriers:
        slots = [pinocchio_model.idx_vs[support] for support in pinocchio_model.supports[
            carriers[0]][1:]]
        moved = bool(np.any(joints.tangent[slots]))
    if not carriers or not moved:
        raise JointError(f"no solved joint turns {flat!r}: flat= needs a frame that the solved "
                         f"joints move (the workpiece on a positioner solved with "
                         f"joints=[...])", frame=frame, field="flat")
    return FlatFrame(pinocchio_model, model.data, joints, carriers[0], rotation_on_anchor,
                     model_root_in_root.T.dot(up_in_root), solver, tolerance)


def _unit_vector(up: Any, frame: str) -> FloatArray:
    """``up`` as a unit 3-vector (None: +z)."""
    if up is None:
        return np.array([0.0, 0.0, 1.0])
    return unit_direction(up, "up", frame=frame)
