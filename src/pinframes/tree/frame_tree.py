"""`FrameTree`: a tree of named coordinate frames whose poses may move in time."""

from __future__ import annotations

import dataclasses
import os
from collections.abc import Callable, Iterator, Sequence
from typing import Any

import numpy as np

from ..errors import (
    ArgumentTypeError,
    FrameExistsError,
    FrameNotFoundError,
    InvalidPoseError,
    InvalidTimeError,
    JointError,
    PinframesError,
    ReferenceTimeError,
    TreeStructureError,
    near_misses,
)
from ..kinematics import (
    FrameJacobian,
    PinocchioTree,
    Snapshot,
    TreeDescription,
    Velocity,
    default_times,
    evaluate_jacobian,
    evaluate_pose,
    evaluate_poses,
    evaluate_velocity,
    paths_to_common_ancestor,
    snapshot,
)
from ..values.joint import Joint
from ..values.joint_trajectory import JointTrajectory, joint_trajectories_from_samples
from ..values.pose import Pose
from ..values.pose_stack import PoseStack
from ..values.spatial_data import SpatialData, apply_pose
from ..values.subsystem import Subsystem
from ..values.timeconv import TimeAxis, parse_timestamp
from ._robot_formats import robot_mounter

__all__ = ["FrameTree"]


class FrameTree:
    """A tree of coordinate frames, compiled to Pinocchio to answer pose queries.

    Parameters
    ----------
    root : str
        Name of the root frame.
    name : str or None
        Name of the tree (weldx calls it the hierarchy's name).
    reference_time : None or timestamp
        Reference time of the tree: relative keyframe times of frames without their own
        reference time count from it, and query results use it (SPEC section 4).

    Every frame other than the root has a parent and a pose in that parent: static, moving
    (a time-dependent :class:`Pose`) or driven by a robot :class:`Joint`.
    """

    def __init__(
        self, root: str = "world", name: str | None = None, reference_time: Any = None
    ) -> None:
        _check_name(root)
        self.name = name
        self._root = root
        self._reference = None if reference_time is None else parse_timestamp(reference_time)
        # Every frame is a key of _children (in insertion order, root first); every frame but
        # the root is a key of _parent.
        self._parent: dict[str, str] = {}
        self._children: dict[str, dict[str, None]] = {root: {}}
        self._depth: dict[str, int] = {root: 0}
        self._local: dict[str, Pose] = {}
        self._joints: dict[str, Joint] = {}
        self._joint_frames: dict[str, str] = {}
        self._joint_trajectories: dict[str, JointTrajectory] = {}
        self._timed_with_reference = 0
        self._timed_without_reference = 0
        self._frame_metadata: dict[str, dict[str, Any]] = {}
        self.metadata: dict[str, Any] = {}
        self.subsystems: list[Subsystem] = []
        self._data: dict[str, tuple[str, SpatialData]] = {}
        self._description: TreeDescription | None = None

    # -- inspection ------------------------------------------------------------------------
    @property
    def root(self) -> str:
        """Name of the root frame."""
        return self._root

    @property
    def reference_time(self) -> np.datetime64 | None:
        """The tree's reference time, ``datetime64[ns]``, or None."""
        return self._reference

    @property
    def frames(self) -> list[str]:
        """All frame names, root first, every parent before its children."""
        return list(self._children)

    def __contains__(self, name: object) -> bool:
        return name in self._children

    def __len__(self) -> int:
        return len(self._children)

    def __iter__(self) -> Iterator[str]:
        """The frame names when iteration starts (the tree may change meanwhile)."""
        return iter(list(self._children))

    def __repr__(self) -> str:
        moving = sum(1 for pose in self._local.values() if pose.is_time_dependent)
        return (f"FrameTree(root={self._root!r}, frames={len(self)}, moving={moving}, "
                f"joints={len(self._joints)})")

    def parent(self, name: str) -> str | None:
        """The parent frame of ``name`` (None for the root)."""
        self._require(name)
        return self._parent.get(name)

    def children(self, name: str) -> list[str]:
        """The child frames of ``name``, in the order they were added."""
        self._require(name)
        return list(self._children[name])

    def local_pose(self, name: str) -> Pose:
        """The pose of ``name`` in its parent exactly as stored.

        For a link moved by a robot joint this is the joint's origin (the pose at joint
        value 0); see :meth:`joint_of`.
        """
        self._require(name)
        if name == self._root:
            raise TreeStructureError("the root frame has no parent", frame=name)
        return self._local[name]

    def is_moving(self, name: str) -> bool:
        """True when the pose of ``name`` in its parent is time-dependent."""
        return self.local_pose(name).is_time_dependent

    def joint_of(self, name: str) -> Joint | None:
        """The robot joint between ``name`` and its parent, or None."""
        self._require(name)
        return self._joints.get(name)

    @property
    def joints(self) -> dict[str, Joint]:
        """Robot joints by joint name, in the order they were added."""
        return {name: self._joints[frame] for name, frame in self._joint_frames.items()}

    def joint_trajectory(self, joint_name: str) -> JointTrajectory | None:
        """The trajectory of a robot joint, or None when it was never set."""
        return self._joint_trajectories.get(joint_name)

    def frame_metadata(self, name: str) -> dict[str, Any]:
        """A free dictionary kept with frame ``name`` (formats keep their extras there)."""
        self._require(name)
        return self._frame_metadata.setdefault(name, {})

    def path(self, frame: str, relative_to: str) -> list[str]:
        """Frames from ``frame`` up to their lowest common ancestor and down to ``relative_to``."""
        self._require(frame)
        self._require(relative_to)
        up, down = paths_to_common_ancestor(self._parent, self._depth, frame, relative_to)
        return up + down[::-1][1:]

    # -- editing ---------------------------------------------------------------------------
    def add(self, name: str, parent: str, pose: Pose | None = None) -> None:
        """Add frame ``name`` under ``parent`` at ``pose`` (None: the identity).

        A time-dependent ``pose`` makes a moving frame. In a tree without its own
        reference time, moving frames must all have reference times or all have none.
        """
        self._check_new(name, parent)
        pose = _checked_pose(pose, name, "pose")
        if pose.is_time_dependent:
            self._count_reference(pose.reference_time, name)
        self._insert(name, parent, pose)

    def attach_joint(self, name: str, parent: str, joint: Joint, origin: Pose | None = None
                     ) -> None:
        """Add link frame ``name`` under ``parent``, moved by ``joint`` (value 0 until set).

        The pose of ``name`` in ``parent`` is ``origin @ motion(value)``.
        """
        self._check_new(name, parent)
        if not isinstance(joint, Joint):
            raise ArgumentTypeError(f"expected a pinframes.Joint, got {type(joint).__name__}",
                                    frame=name, field="joint")
        if joint.name in self._joint_frames:
            raise FrameExistsError(f"the tree already has a joint named {joint.name!r}",
                                   frame=name, field="joint")
        origin = _checked_pose(origin, name, "origin")
        if origin.is_time_dependent:
            raise InvalidPoseError("a joint origin must be static", frame=name, field="origin")
        self._insert(name, parent, origin)
        self._joints[name] = joint
        self._joint_frames[joint.name] = name

    def attach_urdf(
        self, urdf: str | os.PathLike[str], parent: str, pose: Pose | None = None,
        prefix: str = "", *, strict: bool = False, limits: Any = None,
    ) -> list[str]:
        """Mount a robot: its root link at ``parent`` (at ``pose``), every link a frame.

        Parameters
        ----------
        urdf : path or str
            A URDF file, or its XML text. Meshes are never needed.
        parent : str
            The frame the robot's root link is placed on.
        pose : Pose or None
            The root link's pose in ``parent`` (identity if None; may move in time).
        prefix : str
            Put before every link and joint name, to mount several copies of a robot.
        strict : bool
            Refuse a mimic joint whose primary joint is not in the file; by default it
            stays an independent joint, with one ``BrokenMimicWarning`` per such joint.
        limits : pinframes.Limits or None
            Bounds on the XML elements and their nesting (None: those of the read in
            progress, e.g. a scene's, else the defaults).

        Returns
        -------
        list of str
            The new frame names, root link first. Revolute, continuous and prismatic
            joints stay joints, at their rest value (0, or the limit nearest to 0) until
            :meth:`set_joint_trajectory` gives them samples; fixed,
            floating and planar joints become frames at their origin. A failed import
            leaves the tree unchanged.
        """
        return robot_mounter("urdf")(self, urdf, parent, pose, prefix, strict=strict,
                                     limits=limits)

    def graft(self, other: FrameTree, at: str | None = None, prefix: str = "",
              name: str | None = None, record: bool = True) -> Subsystem | None:
        """Mount tree ``other`` here: its root becomes frame ``at``, every other frame of it
        (moving frames, robot links with joints and trajectories, attached data) is added
        with ``prefix`` before its name (joints and data too), as weldx's ``merge`` does.

        ``at`` defaults to ``prefix + other.root``, which must be a frame of this tree.
        Keyframes counting from ``other``'s reference time keep their absolute times. A
        :class:`Subsystem` named ``name`` (default: ``prefix + other.name``) records the graft; the
        subsystems of ``other`` come along nested in it (with ``record=False`` there is no
        record, and they nest in nothing). A name taken twice is a
        :class:`~pinframes.errors.FrameExistsError`, and any failure leaves both trees as
        they were. Returns the record.
        """
        from .grafting import graft

        return graft(self, other, at, prefix, name, record)

    def subtree(self, frame: str) -> FrameTree:
        """A new tree rooted at ``frame`` with copies of everything below it: poses, joints
        and their trajectories, data, frame metadata and the subsystems inside it. A subsystem
        recording exactly this part (a :meth:`graft`) names the copy, gives its reference
        time and is not kept, so ``subtree`` undoes ``graft``."""
        from .grafting import subtree

        return subtree(self, frame)

    def copy(self) -> FrameTree:
        """An independent copy: frames, joints, trajectories, data, subsystems, metadata."""
        from .grafting import copy_tree

        return copy_tree(self)

    def time_union(self, frames: Sequence[str] | None = None) -> TimeAxis | None:
        """Every keyframe and joint sample time of ``frames`` (default: the whole tree), as
        weldx's ``time_union``: ns offsets after the tree's reference time (else the earliest
        frame reference time); None when none of them moves."""
        from .tree_times import time_union

        return time_union(self, frames)

    def resampled(self, times: Any, time_ref: Any = None) -> FrameTree:
        """A copy whose moving frames and joint trajectories hold samples at ``times`` only
        (interpolated as :meth:`pose` does, held outside), as weldx's ``interp_time``.

        Relative ``times`` count from ``time_ref``, else from the tree's reference time;
        static frames and data stay as they are; frames keep their own reference times.
        """
        from .tree_times import resampled

        return resampled(self, times, time_ref)

    def set_joint_trajectory(
        self, times: Any, positions: Any, joint_names: Sequence[str] | None = None
    ) -> None:
        """Drive robot joints with samples: ``positions`` (T, n) at T ``times``.

        Columns follow ``joint_names`` (default: every actuated joint of the tree, in the
        order the robots were mounted, URDF order within a robot). Values are radians or
        metres, interpolated linearly between samples (continuous joints the short way
        round) and held outside them; the sample times join the default time union of
        :meth:`pose`. Values outside the URDF limits warn (``JointLimitWarning``).
        """
        trajectories = joint_trajectories_from_samples(self.joints, times, positions, joint_names)
        for name, trajectory in trajectories.items():
            self.replace_joint_trajectory(name, trajectory)

    def replace_joint_trajectory(self, joint_name: str, trajectory: JointTrajectory | None
                                 ) -> None:
        """Set (or with None, clear) the trajectory of a robot joint."""
        if not isinstance(joint_name, str) or joint_name not in self._joint_frames:
            raise FrameNotFoundError(
                f"no joint named {joint_name!r} in the tree"
                + near_misses(joint_name, self._joint_frames, "joint"), field="joint_names")
        previous = self._joint_trajectories.pop(joint_name, None)
        if previous is not None:
            self._uncount_reference(previous.reference)
        if trajectory is not None:
            try:
                self._count_reference(trajectory.reference, joint_name)
            except ReferenceTimeError:
                if previous is not None:  # leave the tree as it was
                    self._count_reference(previous.reference, joint_name)
                    self._joint_trajectories[joint_name] = previous
                raise
            self._joint_trajectories[joint_name] = trajectory
        self._invalidate()

    # the names of the two methods above before 0.2 (kept for existing code)
    joint_track = joint_trajectory
    set_joint_track = replace_joint_trajectory

    def remove(self, name: str, recursive: bool = False, drop_data: bool = False) -> None:
        """Remove frame ``name``; with ``recursive``, its whole subtree too.

        Data attached to a removed frame is an error unless ``drop_data`` (then it goes too).
        """
        self._require(name)
        if name == self._root:
            raise TreeStructureError("the root frame cannot be removed", frame=name)
        if self._children[name] and not recursive:
            raise TreeStructureError(
                f"has children ({', '.join(self._children[name])}); pass recursive=True to "
                "remove them too", frame=name)
        doomed = self._subtree(name)
        self._refuse_orphaned_mimics(set(doomed))
        gone = set(doomed)
        attached = [data for data, (frame, _) in self._data.items() if frame in gone]
        if attached and not drop_data:
            raise TreeStructureError(
                f"data is attached to the frames it would remove ({', '.join(attached)}); pass "
                "drop_data=True to remove the data too", frame=name, field="drop_data")
        for data in attached:
            del self._data[data]
        del self._children[self._parent[name]][name]
        for frame in doomed:
            pose = self._local.pop(frame)
            if pose.is_time_dependent:
                self._uncount_reference(pose.reference_time)
            joint = self._joints.pop(frame, None)
            if joint is not None:
                del self._joint_frames[joint.name]
                trajectory = self._joint_trajectories.pop(joint.name, None)
                if trajectory is not None:
                    self._uncount_reference(trajectory.reference)
            for table in (self._parent, self._children, self._depth, self._frame_metadata):
                table.pop(frame, None)
        self.subsystems = [
            _replace_members(s, tuple(m for m in s.members if m not in gone))
            for s in self.subsystems if s.root not in gone
        ]
        self._forget_data(attached)
        self._invalidate()

    def _refuse_orphaned_mimics(self, doomed: set[str]) -> None:
        """Raise a :class:`JointError` if a joint kept mimics one on the ``doomed`` frames."""
        leaving = {self._joints[frame].name for frame in doomed if frame in self._joints}
        for frame, joint in self._joints.items():
            if frame not in doomed and joint.mimic is not None and joint.mimic.joint in leaving:
                raise JointError(
                    f"its joint {joint.name!r} mimics joint {joint.mimic.joint!r}, which the "
                    "removal would take away; remove the mimic joint's frame too",
                    frame=frame, field="mimic")

    def rename(self, old: str, new: str) -> None:
        """Rename frame ``old`` to ``new``, keeping its place, pose, metadata and data."""
        self._require(old)
        _check_name(new)
        if new in self._children:
            raise FrameExistsError("the tree already has a frame of this name", frame=new)

        def renamed(key: str) -> str:
            return new if key == old else key

        self._parent = {renamed(k): renamed(v) for k, v in self._parent.items()}
        self._children = {renamed(k): {renamed(c): None for c in v}
                          for k, v in self._children.items()}
        for table in ("_depth", "_local", "_joints", "_frame_metadata"):
            setattr(self, table, {renamed(k): v for k, v in getattr(self, table).items()})
        self._joint_frames = {k: renamed(v) for k, v in self._joint_frames.items()}
        self._data = {k: (renamed(frame), data) for k, (frame, data) in self._data.items()}
        if old == self._root:
            self._root = new
        self.subsystems = [
            Subsystem(s.name, renamed(s.root), tuple(renamed(m) for m in s.members),
                      s.parent, s.reference_time, s.subsystems, s.data)
            for s in self.subsystems
        ]
        self._invalidate()

    def set_local_pose(self, name: str, pose: Pose) -> None:
        """Replace the pose of ``name`` in its parent (static or moving)."""
        previous = self.local_pose(name)
        if not isinstance(pose, Pose):
            raise ArgumentTypeError(f"expected a pinframes.Pose, got {type(pose).__name__}",
                                    frame=name, field="pose")
        if name in self._joints and pose.is_time_dependent:
            raise InvalidPoseError("a joint origin must be static", frame=name, field="pose")
        if previous.is_time_dependent:
            self._uncount_reference(previous.reference_time)
        if pose.is_time_dependent:
            try:
                self._count_reference(pose.reference_time, name)
            except ReferenceTimeError:
                self._count_reference(previous.reference_time, name)
                raise
        self._local[name] = pose
        self._invalidate()

    # -- data attached to frames (weldx assign_data / get_data) -----------------------------
    @property
    def data_names(self) -> list[str]:
        """Names of the data attached to frames, in the order they were assigned."""
        return list(self._data)

    def assign_data(self, name: str, data: SpatialData | Any, frame: str) -> None:
        """Attach ``data`` (a :class:`SpatialData`, or ``(M, 3)`` points in metres) to ``frame``
        under ``name``; its coordinates are given in ``frame``."""
        if not isinstance(name, str) or not name:
            raise ArgumentTypeError("data names are non-empty strings", field="name")
        if name in self._data:
            raise FrameExistsError(f"the tree already has data named {name!r}", field="name")
        self._require(frame, "frame")
        self._data[name] = (frame, data if isinstance(data, SpatialData) else SpatialData(data))

    def data_frame(self, name: str) -> str:
        """The frame data ``name`` is attached to."""
        if name not in self._data:
            raise FrameNotFoundError(f"no data named {name!r}", field="name")
        return self._data[name][0]

    def delete_data(self, name: str) -> None:
        """Detach and forget data ``name``."""
        self.data_frame(name)
        del self._data[name]
        self._forget_data([name])

    def _forget_data(self, names: list[str]) -> None:
        """Take data ``names`` off the subsystems' data lists (weldx ``delete_data``)."""
        if names:
            self.subsystems = [dataclasses.replace(s, data=tuple(d for d in s.data
                                                                 if d not in names))
                               for s in self.subsystems]

    def get_data(self, name: str, relative_to: str | None = None, times: Any = None,
                 time_ref: Any = None) -> SpatialData:
        """Data ``name`` with its points in ``relative_to`` (default: as stored).

        Time-dependent data is transformed at its own times (``times`` must be None). Static
        data follows :meth:`pose`: with ``times`` None, at the union of the path's keyframe
        times (static points if nothing on the path moves), else at ``times``; moving points
        come back ``(T, M, 3)`` with the pose's times and reference time.
        """
        frame = self.data_frame(name)
        data = self._data[name][1]
        if (relative_to is None or relative_to == frame) and times is None:
            return data
        target = frame if relative_to is None else relative_to
        own = data.times
        if own is not None:
            if times is not None:
                raise InvalidTimeError(f"data {name!r} has times of its own; pass times=None",
                                       frame=frame, field="times")
            reference = data.reference_time
            times = own if reference is None else reference + own
            time_ref = None
        pose = self.pose(frame, target, times, time_ref)
        offsets = None if pose.times is None else pose.times.astype(np.int64)
        return data.with_points(apply_pose(pose, data.points), offsets, pose.reference_time)

    # -- queries ---------------------------------------------------------------------------
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

        Follows weldx ``CoordinateSystemManager.get_cs`` (SPEC section 4): every moving
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
            One pose per requested time; ``reference_time`` set by the rules of SPEC 4.
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
        return evaluate_poses(self._frozen(), frames, references, times, time_ref,
                              extrapolation)

    def transform_points(
        self, points: Any, frame: str, relative_to: str, times: Any = None, *,
        time_ref: Any = None, extrapolation: str = "clamp",
    ) -> np.ndarray:
        """Points given in ``frame`` (metres), returned in ``relative_to``, at ``times``.

        Times follow :meth:`pose` (None: every keyframe and joint sample on the path; a
        static path keeps the points' shape). Shapes follow :meth:`Pose.transform_points`:
        with ``T`` times, ``(T, 3)`` is one point per time (row ``i`` at time ``i``),
        ``(M, 3)`` (``M != T``) the same points at every time giving ``(T, M, 3)``,
        ``(T, M, 3)`` a profile per time; ``(1, M, 3)`` forces the same points at every time
        when ``M == T``. Bad data raise :class:`~pinframes.errors.InvalidDataError` naming
        ``points`` and ``frame``.
        """
        pose = self.pose(frame, relative_to, times, time_ref, extrapolation=extrapolation)
        return _located(pose.transform_points, points, frame)

    def transform_vectors(
        self, vectors: Any, frame: str, relative_to: str, times: Any = None, *,
        time_ref: Any = None, extrapolation: str = "clamp",
    ) -> np.ndarray:
        """Directions given in ``frame``, returned in ``relative_to``: rotated, never moved.

        Arguments, times and shapes as :meth:`transform_points`.
        """
        pose = self.pose(frame, relative_to, times, time_ref, extrapolation=extrapolation)
        return _located(pose.transform_vectors, vectors, frame)

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
        return evaluate_velocity(self._frozen(), frame, relative_to, times, time_ref,
                                 extrapolation, expressed_in)

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
        return evaluate_jacobian(self._frozen(), frame, relative_to, times, time_ref,
                                 extrapolation, joints)

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
        """The whole tree as one Pinocchio model, with name mappings and configurations.

        Beware: Pinocchio's ``createData`` grows with the cube of the number of joints
        (SPEC section 5); :meth:`pose` never builds such a model.
        """
        return PinocchioTree(self._frozen())

    # -- helpers ---------------------------------------------------------------------------
    def _default_reference(self, frame: str, relative_to: str | None) -> str:
        """``relative_to``, or the parent of ``frame`` when it is None."""
        if relative_to is not None:
            return relative_to
        parent = self._parent.get(frame)
        if parent is None:
            raise TreeStructureError("the root frame has no parent; pass relative_to",
                                     frame=frame, field="relative_to")
        return parent

    def _frozen(self) -> TreeDescription:
        """This version of the tree as the kinematics reads it (built once per version)."""
        if self._description is None:
            self._description = TreeDescription.freeze(
                self._root, self._parent, self._depth, self._local, self._joints,
                self.joints, self._joint_trajectories, self._reference,
                self._timed_with_reference > 0)
        return self._description

    def _require(self, name: str, field: str | None = None) -> None:
        if not isinstance(name, str):
            raise ArgumentTypeError(f"frame names are strings, got {type(name).__name__}",
                                    field=field)
        if name not in self._children:
            raise FrameNotFoundError("no frame of this name in the tree"
                                     + near_misses(name, self._children), frame=str(name))

    def _check_new(self, name: str, parent: str) -> None:
        _check_name(name)
        if name in self._children:
            raise FrameExistsError("the tree already has a frame of this name", frame=name)
        if not isinstance(parent, str):
            raise ArgumentTypeError(f"frame names are strings, got {type(parent).__name__}",
                                    frame=name, field="parent")
        if parent not in self._children:
            raise FrameNotFoundError(f"parent frame {parent!r} is not in the tree"
                                     + near_misses(parent, self._children),
                                     frame=name, field="parent")

    def _insert(self, name: str, parent: str, pose: Pose) -> None:
        self._parent[name] = parent
        self._children[name] = {}
        self._children[parent][name] = None
        self._depth[name] = self._depth[parent] + 1
        self._local[name] = pose
        self._invalidate()

    def _subtree(self, name: str) -> list[str]:
        order, stack = [], [name]
        while stack:
            frame = stack.pop()
            order.append(frame)
            stack.extend(self._children[frame])
        return order

    def _count_reference(self, reference: np.datetime64 | None, name: str) -> None:
        if self._reference is None:
            if reference is not None and self._timed_without_reference:
                raise ReferenceTimeError(
                    "has a reference time, but the tree's other moving frames have none and "
                    "the tree has no reference time of its own", frame=name,
                    field="reference_time")
            if reference is None and self._timed_with_reference:
                raise ReferenceTimeError(
                    "has no reference time, but the tree's other moving frames have one and "
                    "the tree has no reference time of its own", frame=name,
                    field="reference_time")
        if reference is None:
            self._timed_without_reference += 1
        else:
            self._timed_with_reference += 1

    def _uncount_reference(self, reference: np.datetime64 | None) -> None:
        if reference is None:
            self._timed_without_reference -= 1
        else:
            self._timed_with_reference -= 1

    def _invalidate(self) -> None:
        """Forget the description of the previous version (the tree changed)."""
        self._description = None


def _check_name(name: object) -> None:
    if not isinstance(name, str):
        raise ArgumentTypeError(f"frame names are strings, got {type(name).__name__}",
                                field="name")
    if not name:
        raise TreeStructureError("frame names must not be empty", field="name")


def _checked_pose(pose: object, frame: str, field: str) -> Pose:
    """``pose``, the identity for None; an :class:`ArgumentTypeError` for a non-Pose."""
    if pose is None:
        return Pose.identity()
    if not isinstance(pose, Pose):
        raise ArgumentTypeError(f"expected a pinframes.Pose or None, got {type(pose).__name__}",
                                frame=frame, field=field)
    return pose


def _located(transform: Callable[[Any], np.ndarray], data: Any, frame: str) -> np.ndarray:
    """``transform(data)``, with its errors naming the frame the data are given in."""
    try:
        return transform(data)
    except PinframesError as exc:
        raise exc.located(frame=frame) from None


def _replace_members(subsystem: Subsystem, members: tuple[str, ...]) -> Subsystem:
    return Subsystem(subsystem.name, subsystem.root, members, subsystem.parent,
                     subsystem.reference_time, subsystem.subsystems, subsystem.data)
