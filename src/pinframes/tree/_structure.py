"""`EditableTree`: what a frame tree holds, and every edit of it.

The frames (a parent each, every parent before its children), their poses in their parents,
robot joints and their trajectories, the count of reference times behind the rule of
docs/time-semantics.md (moving frames all with a reference time or all without), frame
metadata, the table of attached data and the subsystems. Every edit checks its input first and
leaves the tree as it was when it fails; the immutable :class:`TreeDescription` that the
kinematics reads is built once per version (:meth:`EditableTree._frozen`).
:class:`~pinframes.FrameTree` adds the queries, the data and the whole-tree operations on top.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Iterator, Sequence
from typing import Any

import numpy as np

from ..errors import (
    ArgumentTypeError,
    DataNotFoundError,
    FrameExistsError,
    FrameNotFoundError,
    InvalidPoseError,
    JointError,
    ReferenceTimeError,
    TreeStructureError,
    joint_not_found,
    near_misses,
)
from ..kinematics import TreeDescription
from ..values.joint import Joint
from ..values.joint_trajectory import JointTrajectory, joint_trajectories_from_samples
from ..values.motion import Motion
from ..values.pose import Pose
from ..values.spatial_data import SpatialData
from ..values.subsystem import Subsystem
from ..values.timeconv import parse_timestamp

__all__ = ["EditableTree"]


class EditableTree:
    """The frames of a :class:`~pinframes.FrameTree` and every edit of them (see there).

    Not used alone: ``FrameTree`` is this class with the queries added.
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

    def __getstate__(self) -> dict[str, Any]:
        """The tree without the description of its current version (a cache, rebuilt on
        the next query), so that a queried tree pickles and deep-copies (to Dask workers,
        through ``multiprocessing``)."""
        state = self.__dict__.copy()
        state["_description"] = None
        return state

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
        """The trajectory of a robot joint, or None when it was never set (a
        :class:`~pinframes.errors.JointNotFoundError` for a joint the tree lacks)."""
        if not isinstance(joint_name, str) or joint_name not in self._joint_frames:
            raise joint_not_found(joint_name, self._joint_frames, field="joint_name")
        return self._joint_trajectories.get(joint_name)

    def frame_metadata(self, name: str) -> dict[str, Any]:
        """A free dictionary kept with frame ``name`` (formats keep their extras there)."""
        self._require(name)
        return self._frame_metadata.setdefault(name, {})

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

    def set_joint_trajectory(
        self, times: Any, positions: Any, joint_names: Sequence[str] | None = None
    ) -> None:
        """Drive robot joints with samples: ``positions`` (T, n) at T ``times``.

        Columns follow ``joint_names`` (default: every actuated joint of the tree, in the
        order the robots were mounted, URDF order within a robot). Values are radians or
        metres (a pint quantity is converted: degrees for revolute joints, millimetres for
        prismatic ones), interpolated linearly between samples (continuous joints the short way
        round) and held outside them; the sample times join the default time union of
        :meth:`pose`. Values outside the URDF limits warn (``JointLimitWarning``).
        """
        trajectories = joint_trajectories_from_samples(self.joints, times, positions, joint_names)
        for name, trajectory in trajectories.items():
            self.replace_joint_trajectory(name, trajectory)

    def set_motion(self, motion: Motion) -> None:
        """Drive the joints of a planned program (``WeldProgram.plan``) with its samples, at
        its times (after its reference time when it has one): ``pose``, ``clearance``,
        ``weld_process`` and the 3-D page then show the whole run."""
        if not isinstance(motion, Motion):
            raise ArgumentTypeError(f"expected a Motion, got {type(motion).__name__}",
                                    field="motion")
        times = motion.absolute_times if motion.reference_time is not None else motion.times
        self.set_joint_trajectory(times, motion.positions, list(motion.joint_names))

    def replace_joint_trajectory(self, joint_name: str, trajectory: JointTrajectory | None
                                 ) -> None:
        """Set (or with None, clear) the trajectory of a robot joint."""
        if not isinstance(joint_name, str) or joint_name not in self._joint_frames:
            raise joint_not_found(joint_name, self._joint_frames, field="joint_names")
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

    # the earlier names of the two methods above (kept for existing code)
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
            raise DataNotFoundError(f"no data named {name!r}"
                                    + near_misses(name, self._data, "data"), field="name")
        return self._data[name][0]

    def get_data(self, name: str) -> SpatialData:
        """Data ``name`` as stored: its points in the frame it is attached to
        (:meth:`pinframes.FrameTree.get_data` gives them in any frame)."""
        self.data_frame(name)
        return self._data[name][1]

    def delete_data(self, name: str) -> None:
        """Detach and forget data ``name``."""
        self.data_frame(name)
        del self._data[name]
        self._forget_data([name])

    # -- helpers ---------------------------------------------------------------------------
    def _forget_data(self, names: list[str]) -> None:
        """Take data ``names`` off the subsystems' data lists (weldx ``delete_data``)."""
        if names:
            self.subsystems = [dataclasses.replace(s, data=tuple(d for d in s.data
                                                                 if d not in names))
                               for s in self.subsystems]

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


def _replace_members(subsystem: Subsystem, members: tuple[str, ...]) -> Subsystem:
    return Subsystem(subsystem.name, subsystem.root, members, subsystem.parent,
                     subsystem.reference_time, subsystem.subsystems, subsystem.data)
