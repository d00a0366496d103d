"""`TreeQueries`: the questions asked of a frame tree's frames, handed to the kinematics.

Poses (one pair, many pairs), points and vectors carried between frames, velocities,
Jacobians, the default sample times, the whole tree at one instant and as one Pinocchio
model. Each method checks the frame names, then hands the tree's
:class:`~pinframes.kinematics.TreeDescription` of this version to the kinematics, which does
all the work. :class:`~pinframes.FrameTree` is this class with the clearance
(:mod:`._collision_queries`), the data and the whole-tree operations added.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import replace
from functools import partial
from typing import Any

import numpy as np

from ..errors import (
    GeometryError,
    InvalidPoseError,
    PinframesError,
    TreeStructureError,
)
from ..kinematics import (
    FrameJacobian,
    IkSolutions,
    JointSolution,
    PinocchioTree,
    Snapshot,
    Velocity,
    WeldProcess,
    default_times,
    evaluate_ik_solutions,
    evaluate_jacobian,
    evaluate_pose,
    evaluate_poses,
    evaluate_solve_joints,
    evaluate_velocity,
    evaluate_weld_process,
    paths_to_common_ancestor,
    snapshot,
)
from ..kinematics.ik.joint_jumps import DEFAULT_JUMP_FACTOR
from ..kinematics.ik.solve_joints import DEFAULT_PATH_TOLERANCE, FLAT_TOLERANCE
from ..values.geometry import GEOMETRY_METADATA_KEY, FrameGeometry
from ..values.numbers import require_finite_result
from ..values.pose import Pose
from ..values.pose_stack import PoseStack
from ..values.timeconv import TimeAxis
from ._structure import EditableTree
from .robot_semantics import group_joints, group_state_values
from .urdf_names import urdf_joint_names

__all__ = ["TreeQueries"]


class TreeQueries(EditableTree):
    """The queries of a :class:`~pinframes.FrameTree` (see there)."""

    # -- queries ---------------------------------------------------------------------------
    def path(self, frame: str, relative_to: str) -> list[str]:
        """Frames from ``frame`` up to their lowest common ancestor and down to ``relative_to``."""
        self._require(frame)
        self._require(relative_to)
        up, down = paths_to_common_ancestor(self._parent, self._depth, frame, relative_to)
        return up + down[::-1][1:]

    def pose(
        self,
        frame: str,
        relative_to: str | None = None,
        times: Any = None,
        time_ref: Any = None,
        *,
        extrapolation: str = "clamp",
    ) -> Pose:
        """The pose of ``frame`` in ``relative_to`` (default: its parent).

        Follows weldx ``CoordinateSystemManager.get_cs`` (docs/time-semantics.md): every moving
        frame and joint on the path is interpolated onto one timeline first (translation
        linear, rotation SLERP), then Pinocchio's kinematics composes the path.

        Parameters
        ----------
        frame, relative_to : str
            Frame names; the result maps coordinates in ``frame`` to ``relative_to``.
        times : None, times, or a frame name
            None: the union of the keyframe times of the moving things on the path (a
            static pose if nothing on it moves). A frame name: that frame's keyframe times.
            Relative times count from ``time_ref``, else from the result's reference time.
        time_ref : None or timestamp
            Reference time of the result (ignored when ``times`` is None).
        extrapolation : {"clamp", "error"}
            Outside a frame's keyframes hold its first/last pose, or raise
            :class:`~pinframes.errors.ExtrapolationError`.

        Returns
        -------
        Pose
            One pose per requested time; ``reference_time`` set by the rules of
            docs/time-semantics.md.
        """
        self._require(frame, "frame")
        relative_to = self._default_reference(frame, relative_to)
        self._require(relative_to, "relative_to")
        return evaluate_pose(self._frozen(), frame, relative_to, times, time_ref,
                             extrapolation)

    def poses(
        self,
        frames: Sequence[str],
        relative_to: str | Sequence[str] | None = None,
        times: Any = None,
        time_ref: Any = None,
        *,
        extrapolation: str = "clamp",
    ) -> PoseStack:
        """The poses of many frames in one call, stacked: ``result[i]`` equals
        ``self.pose(frames[i], relative_to[i], times, time_ref)``.

        Parameters
        ----------
        frames : sequence of str
            F frame names.
        relative_to : None, str or sequence of F str
            One frame for all (the poses of several frames in it), one per frame (F pairs),
            or None for each frame's parent.
        times, time_ref, extrapolation
            As for :meth:`pose`, shared by all pairs.

        Returns
        -------
        PoseStack
            Rotations ``(F, 3, 3)`` / translations ``(F, 3)`` when no pair moves and no
            times are given, else ``(F, T, 3, 3)`` / ``(F, T, 3)`` on the one timeline of the
            moving pairs (static pairs repeat over it). Pairs whose default timelines or
            reference times differ are an :class:`~pinframes.errors.InvalidTimeError`:
            pass ``times`` (and ``time_ref``).
        """
        frames = list(frames)
        if relative_to is None:
            references = [self._default_reference(frame, None) for frame in frames]
        elif isinstance(relative_to, str):
            references = [relative_to] * len(frames)
        else:
            references = list(relative_to)
            if len(references) != len(frames):
                raise TreeStructureError(
                    f"relative_to names {len(references)} frames for {len(frames)} frames",
                    field="relative_to")
        for name in set(frames):
            self._require(name, "frame")
        for name in set(references):
            self._require(name, "relative_to")
        if not frames:
            return PoseStack(np.empty((0, 3, 3)), np.empty((0, 3)))
        stack = evaluate_poses(self._frozen(), frames, references, times, time_ref,
                               extrapolation)
        if not np.isfinite(stack.translation).all():  # name the first pair that overflowed
            pair = int(np.argwhere(~np.isfinite(stack.translation))[0][0])
            _require_finite(stack.translation[pair], "translation",
                            f"the pose of {frames[pair]!r} in {references[pair]!r}", frames[pair])
        return stack

    def transform_points(
        self, points: Any, frame: str, relative_to: str, times: Any = None, *,
        per_time: bool = False, time_ref: Any = None, extrapolation: str = "clamp",
    ) -> np.ndarray:
        """Points given in ``frame`` (metres), returned in ``relative_to``, at ``times``.

        Times follow :meth:`pose` (None: every keyframe and joint sample on the path; a
        static path keeps the points' shape). Shapes follow :meth:`Pose.transform_points`:
        with ``T`` times, ``(M, 3)`` is the same points at every time, giving
        ``(T, M, 3)`` whatever ``M`` (as :meth:`get_data`), and ``(T, M, 3)`` a profile per
        time. ``per_time=True`` pairs ``(T, 3)`` points with the times instead: row ``i`` at
        time ``i``, giving ``(T, 3)`` (an :class:`~pinframes.errors.InvalidDataError` when
        the counts differ). Bad data raise :class:`~pinframes.errors.InvalidDataError`
        naming ``points`` and ``frame``.
        """
        pose = self.pose(frame, relative_to, times, time_ref, extrapolation=extrapolation)
        return _located(partial(pose.transform_points, per_time=per_time), points, frame)

    def transform_vectors(
        self, vectors: Any, frame: str, relative_to: str, times: Any = None, *,
        per_time: bool = False, time_ref: Any = None, extrapolation: str = "clamp",
    ) -> np.ndarray:
        """Directions given in ``frame``, returned in ``relative_to``: rotated, never moved.

        Arguments, times, shapes and ``per_time`` as :meth:`transform_points`.
        """
        pose = self.pose(frame, relative_to, times, time_ref, extrapolation=extrapolation)
        return _located(partial(pose.transform_vectors, per_time=per_time), vectors, frame)

    def velocity(
        self, frame: str, relative_to: str | None = None, times: Any = None,
        expressed_in: str | None = None, *, time_ref: Any = None,
        extrapolation: str = "clamp",
    ) -> Velocity:
        """Linear (m/s) and angular (rad/s) velocity of ``frame`` relative to ``relative_to``.

        Exact derivatives of what :meth:`pose` interpolates, at the times :meth:`pose` would
        use (arguments as there): translations move linearly and rotations by SLERP between
        keyframes, and joints linearly between samples (mimic joints at their multiplier
        times their primary's rate), so velocities are constant on each segment; a frame
        held outside its keyframes does not move. At a keyframe the segment that starts
        there counts; at the last keyframe, the segment that ends there.

        ``linear`` is the velocity of the origin of ``frame`` seen from ``relative_to`` (the
        derivative of ``pose(frame, relative_to).translation``), ``angular`` the angular
        velocity ``w`` with ``dR/dt = [w]x @ R``. Both are written in the axes of
        ``expressed_in``: ``relative_to`` by default (Pinocchio's ``LOCAL_WORLD_ALIGNED``
        frame velocity when ``relative_to`` is the root of the model), ``frame`` (Pinocchio's
        ``LOCAL``), or any other frame of the tree (rotated by its pose in ``relative_to``).

        Returns
        -------
        Velocity
            ``linear`` and ``angular`` of shape (T, 3), ``times`` and ``reference_time`` as
            :meth:`pose` gives them (a static path without times: T = 1, ``times`` None).
        """
        self._require(frame, "frame")
        relative_to = self._default_reference(frame, relative_to)
        self._require(relative_to, "relative_to")
        if expressed_in is None:
            expressed_in = relative_to
        self._require(expressed_in, "expressed_in")
        velocity = evaluate_velocity(self._frozen(), frame, relative_to, times, time_ref,
                                     extrapolation, expressed_in)
        what = f"the velocity of {frame!r} relative to {relative_to!r}"
        _require_finite(velocity.linear, "linear", what, frame)
        _require_finite(velocity.angular, "angular", what, frame)
        return velocity

    def weld_process(
        self, torch: str, seam: str, *, times: Any = None, time_ref: Any = None,
        workpiece: str | None = None, contact_tip: str | None = None,
        extrapolation: str = "clamp", up: Any = None,
    ) -> WeldProcess:
        """The welding process ``torch`` produces along ``seam``, per sample.

        The terms are defined in docs/welding-process.md.

        ``seam`` is a frame at the weld point with x along the travel direction and z the
        surface normal out of the material (:meth:`Pose.along_curve` makes one); ``torch``
        the tool centre point whose z axis is the wire axis, pointing toward the work.
        Returns the travel speed (m/s: of the weld point, where the wire axis meets the
        seam's x-y plane, relative to ``workpiece``, default the seam's parent, along the
        seam's x), the travel angle (rad, positive push) and work angle (rad, pi/2 square to
        the surface) of the wire axis, the torch origin in seam axes (m), the seam's slope
        and face rotation against ``up`` (rad; a 3-vector in the root's axes, default +z)
        with the ISO 6947 welding position they give ("PA" .. "PG") and, when
        ``contact_tip`` names a frame, the contact tip to work distance (m). Without times,
        every keyframe and joint sample that moves the torch or the seam relative to the
        workpiece or the seam in the root; otherwise times as :meth:`pose` (arguments as
        there). The speed is
        exact, from :meth:`velocity`. Turning the torch about its own axis changes none of
        these.
        """
        self._require(torch, "torch")
        self._require(seam, "seam")
        if workpiece is None:
            workpiece = self._parent.get(seam)
            if workpiece is None:
                raise TreeStructureError("the seam is the root frame, which has no parent; "
                                         "pass workpiece", frame=seam, field="workpiece")
        self._require(workpiece, "workpiece")
        if contact_tip is not None:
            self._require(contact_tip, "contact_tip")
        return evaluate_weld_process(self._frozen(), torch, seam, times, time_ref,
                                     extrapolation, workpiece, contact_tip, up)

    def jacobian(
        self, frame: str, relative_to: str | None = None, times: Any = None,
        joints: Sequence[str] | None = None, *, time_ref: Any = None,
        extrapolation: str = "clamp",
    ) -> FrameJacobian:
        """Jacobians ``(T, 6, n)`` of ``frame`` relative to ``relative_to`` in the robot joints.

        Column ``k`` holds the velocity (rows: linear m/s of the origin of ``frame``, then
        angular rad/s, in the axes of ``relative_to``, as :meth:`velocity`) per unit
        velocity of joint ``k``: every actuated joint of the tree in its order (as
        :meth:`set_joint_trajectory` takes them), or those named in ``joints``. Joints off
        the path have zero columns; a mimic joint counts in its primary's column. When
        ``relative_to`` is an ancestor of ``frame`` this is Pinocchio's
        ``computeFrameJacobian(..., LOCAL_WORLD_ALIGNED)`` in a model rooted at
        ``relative_to``; otherwise it is the same in the tree re-rooted at ``relative_to``
        (joints that move ``relative_to`` count with the opposite sign, about the origin of
        ``frame``). ``J @ qdot`` is the part of :meth:`velocity` that the joints cause.
        Times as :meth:`pose`.
        """
        self._require(frame, "frame")
        relative_to = self._default_reference(frame, relative_to)
        self._require(relative_to, "relative_to")
        jacobian = evaluate_jacobian(self._frozen(), frame, relative_to, times, time_ref,
                                     extrapolation, joints)
        _require_finite(jacobian.matrix, "matrix",
                        f"the Jacobian of {frame!r} relative to {relative_to!r}", frame)
        return jacobian

    def solve_joints(
        self, frame: str, target: str | Pose, *, relative_to: str | None = None,
        times: Any = None, time_ref: Any = None, joints: str | Sequence[str] | None = None,
        free_axis: str | None = None, seed: Any = None, position_tolerance: float = 1e-6,
        orientation_tolerance: float = 1e-6, strict: bool = False, flat: str | None = None,
        up: Any = None, tilt: tuple[float, float] | None = None,
        add_joints: Sequence[str] | None = None, configuration: Any = None,
        path_tolerance: float | tuple[float, float] | None = DEFAULT_PATH_TOLERANCE,
        jump_threshold: float = DEFAULT_JUMP_FACTOR, flat_tolerance: float = FLAT_TOLERANCE,
    ) -> JointSolution:
        """Joint values that put ``frame`` (a tool) on ``target`` at each time: inverse
        kinematics along a path.

        Parameters
        ----------
        frame : str
            The tool frame, e.g. ``"torch_tcp"``.
        target : str or Pose
            A frame the tool must coincide with at each time (it may move, e.g. ride on a
            turning positioner), or a :class:`Pose` (with times, or static) of the tool
            wanted in ``relative_to``.
        relative_to : str, optional
            The frame a ``Pose`` target is given in (default: the root).
        times, time_ref
            As for :meth:`pose`. Default: every keyframe and joint sample of what moves on
            the path from ``frame`` to the target (a ``Pose`` target's times too), except
            the samples of the solved joints themselves, and between them as many more as
            ``path_tolerance`` needs. Given times are the samples, and
            ``JointSolution.path_deviation`` says how far the tool strays between them.
        joints : str or sequence of str, optional
            The actuated joints to solve for (default: every robot joint between ``frame``
            and the lowest common ancestor of the two frames), or the name of a joint group
            of a robot's SRDF (``"manipulator"``: its chains, joints, links and subgroups
            as MoveIt expands them). May name joints on the
            target's side, e.g. a positioner attached as a URDF: then robot and positioner
            are solved together. Mimic joints follow their primaries; every other joint
            keeps its trajectory.
        add_joints : sequence of str, optional
            Joints solved for beside ``joints`` (or beside the default ones): a positioner's
            joints added to the robot's, ``add_joints=["pos/tilt", "pos/turn"]``.
        free_axis : {"x", "y", "z"}, optional
            An axis of the tool about which its rotation is free (a welding torch): only
            the position and that axis's direction must match, and the solver takes the
            smallest joint motion, so the freedom keeps the motion continuous.
        seed : mapping or sequence, optional
            Joint values (radians or metres) the first sample starts from, by name (may
            name some joints only) or one per solved joint, or the name of a group state of
            a robot's SRDF (``"home"``). Default: the joints' trajectories at the first
            time, else their rest values, tried first among 64 fixed starts spread over the
            joint ranges; of their distinct solutions (at most 16), the first that reaches
            every sample of the first 4,096 in which the path moves is taken, else, of those
            that follow the path furthest before a miss, the one reaching the most.
        position_tolerance, orientation_tolerance : float
            A sample is reached when the tool's origin is within this many metres of the
            target's and its rotation within this many radians (at least 1e-12).
        strict : bool
            Raise :class:`~pinframes.errors.TargetNotReachedError`, naming the first time
            not reached and its errors, instead of returning it as not reached; and
            :class:`~pinframes.errors.JointSpeedError`, naming the joint, the time and the
            ratio, where a joint moves faster than its URDF velocity limit (a mimic joint
            that moves: its own limit); and :class:`~pinframes.errors.JointJumpError` at
            the first jump (see ``jump_threshold``).
        flat : str, optional
            A frame the solved joints move (a seam on a positioner solved with the robot):
            once the tool is on its target, the freedom left turns this frame's z toward
            ``up`` as far as it can (flat welding: the weld's face looks up, position PA).
            A secondary task, in the null space of the tool's: the tool's target is never
            traded for it. Without a seed, the default start first has the joints turn
            ``flat`` up alone (the tool let go), so that the solve does not settle for a
            local best against a joint limit. The first sample is turned to convergence
            (from the seed, when given: a local method, it finds the flat configuration
            nearest to where it starts), then sample by
            sample one step turns the frame back wherever its z has come more than 0.5
            degrees from ``up``. Takes the place of the default secondary task of keeping
            joints out of the bands along their limits.
        up : sequence of 3 floats, optional
            The direction ``flat``'s z is turned toward, in the root's axes (default: the
            root's +z).
        tilt : (about_x, about_y), optional
            Process windows, radians (each from 0 to below pi/2): the tool's z may tilt
            from the target's by up to ``about_x`` about the target's x and ``about_y`` about
            its y (a seam-like target, x along the travel: the work and travel angle
            windows). The windows are used only where needed: the target's own
            orientation (no tilt) wherever it is reachable, and on the stretches where it
            is not, the tilt within the windows that the smallest motion from the sample
            before needs; reported per sample (``JointSolution.tilt``). With
            ``free_axis="z"`` the spin about the tool's z is free too; without, it is the
            target's. A sample is reached within the windows (to ``orientation_tolerance``)
            and the position tolerance.
        configuration : str or int, optional
            For a 6-axis arm of a closed-form family (docs/closed-form-ik.md): the branch
            the whole path keeps, as flags (``"front,up,noflip"``) or a KUKA Status (0..7).
            Samples the branch does not reach hold the nearest solution and are not
            reached. Without it such an arm is solved in closed form on the branch nearest
            the seed (or default start), the wrist passing through straight continuously,
            unless that branch misses a sample (then as any other chain).
        path_tolerance : float or (float, float) or None
            Without ``times``: how far the tool may stray from its target between two
            samples while the solved joints move linearly from the one to the other (as a
            controller interpolates a joint trajectory), metres and radians (default 0.1 mm
            and 0.1 degree; one number: metres, the angle the default). An interval that
            strays further (measured at its midpoint and quarter points) is halved, its
            midpoint added and the path solved again, down to 1 ms, where both its ends
            reach their targets (an added sample out of reach is taken out again). None:
            the default times only.
        flat_tolerance : float
            With ``flat=``: radians (default 0.5 degree) the frame's z may stray from
            ``up``; a sample beyond it where the solved joints could turn it up (the tool
            let go) is not reached. ``JointSolution.flat_error`` gives the angle per
            sample. Without a seed, the first sample's start turns the frame up from
            starts spread over the ranges of the joints that turn it (4 per joint, the
            first 3 such joints), and keeps the one nearest to up.
        jump_threshold : float
            A sample whose step from the one before (the largest change of one solved
            joint) is more than this many times the path's median step, and more than 0.1
            radian (or metre), jumps: ``JointSolution.jumps`` lists it, and ``strict=True``
            raises :class:`~pinframes.errors.JointJumpError` naming its time and joint.

        Returns
        -------
        JointSolution
            Per time, the joint values (within the URDF position limits; continuous joints
            unbounded), the errors and whether the target was reached. Each sample starts
            from the one before, so the solution stays on one branch; with joints to spare
            (7 axes, a free axis, a positioner) it is the smallest motion from the one
            before, and a target that stands still gives joints that do. A sample out of reach
            holds the closest configuration found, and the solver finds its way back when
            the target comes back into reach. Its ``velocities`` and ``speed_ratio`` say
            whether the robot can keep up. Apply it with ``set_joint_trajectory(
            sol.seconds, sol.positions, joint_names=sol.joint_names)``.
        """
        self._require(frame, "frame")
        if isinstance(target, str):
            self._require(target, "target")
        if relative_to is not None:
            self._require(relative_to, "relative_to")
        if flat is not None:
            self._require(flat, "flat")
        near = [frame] + ([target] if isinstance(target, str) else [])
        if isinstance(joints, str) and joints not in self.joints:  # one joint: a list, please
            joints = group_joints(self, joints, near)
        if isinstance(seed, str):
            seed = group_state_values(self, seed, near)
            if joints is not None:  # a state of a larger group seeds the joints solved for
                seed = {name: value for name, value in seed.items() if name in joints}
        solution = evaluate_solve_joints(
            self._frozen(), frame, target, relative_to=relative_to, times=times,
            time_ref=time_ref, joints=joints, free_axis=free_axis, seed=seed,
            position_tolerance=position_tolerance,
            orientation_tolerance=orientation_tolerance, strict=strict, flat=flat, up=up,
            tilt=tilt, add_joints=add_joints, configuration=configuration,
            path_tolerance=path_tolerance, jump_threshold=jump_threshold,
            flat_tolerance=flat_tolerance)
        named = urdf_joint_names(self, solution.joint_names)
        return solution if named is None else replace(solution, urdf_joint_names=tuple(named))

    def ik_solutions(
        self, frame: str, target: str | Pose, *, relative_to: str | None = None,
        times: Any = None, time_ref: Any = None, joints: str | Sequence[str] | None = None,
        whole_turns: bool = True,
    ) -> IkSolutions:
        """Every joint solution that puts ``frame`` on ``target`` at each time, for a 6-axis
        arm of a closed-form family: an OPW arm (ortho-parallel base, spherical wrist) or a
        UR-type arm, recognised from the joints' axes (docs/closed-form-ik.md).

        ``target``, ``relative_to``, ``times``, ``time_ref`` and ``joints`` are as for
        :meth:`solve_joints`. With ``whole_turns`` (default), a joint whose range spans
        more than a turn gives each of its values within the range as a further branch;
        without, the one nearest the middle of its range.

        Returns
        -------
        IkSolutions
            ``positions`` (T, k, n), NaN where a branch has no solution within the limits,
            ``valid`` (T, k), ``configurations`` (k,) naming the branches, ``arm`` the
            recognised arm.

        Raises :class:`~pinframes.errors.JointError` for joints that form neither family,
        naming them and what breaks each shape.
        """
        self._require(frame, "frame")
        if isinstance(target, str):
            self._require(target, "target")
        if relative_to is not None:
            self._require(relative_to, "relative_to")
        if isinstance(joints, str) and joints not in self.joints:
            joints = group_joints(self, joints, [frame] + (
                [target] if isinstance(target, str) else []))
        return evaluate_ik_solutions(
            self._frozen(), frame, target, relative_to=relative_to, times=times,
            time_ref=time_ref, joints=joints, whole_turns=bool(whole_turns))

    def sample_times(self, frame: str, relative_to: str | None = None) -> TimeAxis | None:
        """The times :meth:`pose` evaluates at when given none, without evaluating.

        Every keyframe and joint sample time on the path, as a :class:`~pinframes.TimeAxis`
        (int64 nanosecond ``offsets`` after the ``reference`` time the result would carry);
        None when nothing on the path moves.
        """
        self._require(frame, "frame")
        relative_to = self._default_reference(frame, relative_to)
        self._require(relative_to, "relative_to")
        return default_times(self._frozen(), frame, relative_to)

    def snapshot(self, time: Any = None, time_ref: Any = None) -> Snapshot:
        """The instant ``time`` for the whole tree, and every joint's value then.

        One instant for every frame (a relative ``time`` counts from the tree's reference
        time, else the lowest reference time of its moving frames and joints, as in
        :meth:`to_pinocchio`); pass ``snapshot.time`` to :meth:`pose` to take any pose then.
        ``time=None`` is for trees in which nothing moves.
        """
        return snapshot(self._frozen(), time, time_ref)

    def to_pinocchio(self) -> PinocchioTree:
        """The whole tree as one Pinocchio model, with name mappings and configurations, and
        its URDF links' geometry (:meth:`PinocchioTree.geometry_model`).

        Beware: Pinocchio's ``createData`` grows with the cube of the number of joints
        (50 free-flyer joints: seconds and gigabytes); :meth:`pose` never builds such a model.
        """
        recorded = {frame: geometry for frame in self._children
                    if (geometry := self._recorded_geometry(frame)) is not None}
        return PinocchioTree(self._frozen(), recorded)

    # -- helpers ---------------------------------------------------------------------------
    def _recorded_geometry(self, frame: str) -> FrameGeometry | None:
        """The URDF geometry recorded for ``frame`` when its robot was attached, or None."""
        recorded = self._frame_metadata.get(frame, {}).get(GEOMETRY_METADATA_KEY)
        if recorded is not None and not isinstance(recorded, FrameGeometry):
            raise GeometryError(f"frame metadata {GEOMETRY_METADATA_KEY!r} holds a "
                                f"{type(recorded).__name__}, not a FrameGeometry", frame=frame,
                                field=GEOMETRY_METADATA_KEY)
        return recorded

    def _default_reference(self, frame: str, relative_to: str | None) -> str:
        """``relative_to``, or the parent of ``frame`` when it is None."""
        if relative_to is not None:
            return relative_to
        parent = self._parent.get(frame)
        if parent is None:
            raise TreeStructureError("the root frame has no parent; pass relative_to",
                                     frame=frame, field="relative_to")
        return parent


def _require_finite(array: np.ndarray, field: str, what: str, frame: str) -> None:
    """An :class:`InvalidPoseError` when a result computed from finite poses overflowed."""
    require_finite_result(array, what, InvalidPoseError, frame=frame, field=field)


def _located(transform: Callable[[Any], np.ndarray], data: Any, frame: str) -> np.ndarray:
    """``transform(data)``, with its errors naming the frame the data are given in."""
    try:
        return transform(data)
    except PinframesError as exc:
        raise exc.located(frame=frame) from None
