"""`TreeDescription`: what the evaluator needs of a frame tree, frozen at one tree version,
and what that version's shape says about a query path (its :class:`ModelLayout`).

``FrameTree`` builds one when a query needs it and keeps it until the tree changes; the
evaluator reads nothing else of the tree. Besides the frames, it holds what the tree's
version has learnt: the anchor of each frame (its nearest joint frame and its static
placement there) and what queries worked out once (its :class:`~._memo.Memo`: the
prepared query paths, the clearance's shape loaders), so a cache dies with the version it
belongs to.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from functools import cached_property
from types import MappingProxyType

import numpy as np

from ..values.joint import Drive, Joint, mimic_drives
from ..values.joint_trajectory import JointTrajectory
from ..values.pose import Pose
from ..values.se3 import IDENTITY, Transform, compose, inverse
from ..values.timeline import source_reference
from ._memo import Memo

__all__ = ["ModelJoint", "ModelLayout", "TreeDescription", "paths_to_common_ancestor"]


@dataclass(frozen=True)
class ModelJoint:
    """One joint of a model of (part of) the tree.

    Attributes
    ----------
    frame : str
        The tree frame whose edge to its parent the joint moves.
    parent : int
        Index of the parent joint in the model's joints; -1 for the model's root.
    placement : Transform
        The joint frame in the parent joint's frame, static.
    joint : Joint or None
        The robot joint, or None for a free-flyer that carries a moving frame's pose.
    """

    frame: str
    parent: int
    placement: Transform
    joint: Joint | None

    @property
    def name(self) -> str:
        """Joint name in the Pinocchio model."""
        return self.frame if self.joint is None else self.joint.name


@dataclass(frozen=True)
class ModelLayout:
    """What a model of some frames below ``root`` holds: the joints between them and
    ``root``, parents first, and each frame's placement on its nearest joint ``(joint index
    or -1 for the root, placement)``."""

    root: str
    joints: tuple[ModelJoint, ...]
    frames: dict[str, tuple[int, Transform]]


@dataclass(frozen=True)
class TreeDescription:
    """The frames, poses and joints of a tree at one version; never changes.

    Attributes
    ----------
    root : str
        The root frame.
    parents, depths : mapping
        Parent and depth (root 0) of every frame (the root has no parent).
    local_poses : mapping of str to Pose
        Pose of every frame but the root in its parent (a joint's origin for a joint link).
    joints : mapping of str to Joint
        Robot joint by the link frame it moves.
    joints_by_name : mapping of str to Joint
        The same joints by joint name.
    joint_trajectories : mapping of str to JointTrajectory
        Trajectories of driven joints by joint name.
    reference_time : numpy.datetime64 or None
        The tree's reference time.
    has_frame_references : bool
        Whether the tree's moving frames and joints carry reference times of their own.
    time_groups : mapping of str to str
        Per driven joint, the first driven joint whose trajectory has the same times,
        counted from the same reference time: joints driven together (one
        ``set_joint_trajectory`` call, a robot's trajectory file) hold equal times arrays,
        and a query searches their segments once per group.
    memo : Memo
        What queries work out once for this version, each kind under its type: the
        prepared query paths (``_plan``), the clearance's shape loaders.
    """

    root: str
    parents: Mapping[str, str]
    depths: Mapping[str, int]
    local_poses: Mapping[str, Pose]
    joints: Mapping[str, Joint]
    joints_by_name: Mapping[str, Joint]
    joint_trajectories: Mapping[str, JointTrajectory]
    reference_time: np.datetime64 | None
    has_frame_references: bool
    time_groups: Mapping[str, str]
    _anchors: dict[str, tuple[str, Transform]] = field(
        default_factory=dict, init=False, repr=False, compare=False)
    memo: Memo = field(default_factory=Memo, init=False, repr=False, compare=False)
    # the warnings this version has given (each is given once per version)
    _warned: set[str] = field(default_factory=set, init=False, repr=False, compare=False)

    @classmethod
    def freeze(
        cls, root: str, parents: Mapping[str, str], depths: Mapping[str, int],
        local_poses: Mapping[str, Pose], joints: Mapping[str, Joint],
        joints_by_name: Mapping[str, Joint], joint_trajectories: Mapping[str, JointTrajectory],
        reference_time: np.datetime64 | None, has_frame_references: bool,
    ) -> TreeDescription:
        """A description holding read-only copies of the given tables."""
        return cls(root, MappingProxyType(dict(parents)), MappingProxyType(dict(depths)),
                   MappingProxyType(dict(local_poses)), MappingProxyType(dict(joints)),
                   MappingProxyType(dict(joints_by_name)),
                   MappingProxyType(dict(joint_trajectories)), reference_time,
                   has_frame_references,
                   MappingProxyType(_time_groups(joint_trajectories, reference_time)))

    @cached_property
    def drives(self) -> Mapping[str, Drive]:
        """Per joint name, the actuated joint that finally drives it and how
        (:func:`~pinframes.values.joint.mimic_drives`), once per version."""
        return MappingProxyType(mimic_drives(self.joints_by_name))

    @property
    def frames(self) -> list[str]:
        """Every frame, root first, every parent before its children."""
        return list(self.depths)

    def is_moving(self, name: str) -> bool:
        """True when the pose of ``name`` in its parent is time-dependent."""
        return name != self.root and self.local_poses[name].is_time_dependent

    def anchor(self, name: str) -> tuple[str, Transform]:
        """The nearest joint frame at or above ``name`` and ``name``'s placement in it.

        A joint frame is a robot joint's link or a moving frame; the root anchors itself.
        """
        anchors = self._anchors
        cached = anchors.get(name)
        if cached is not None:
            return cached
        if not anchors:
            anchors[self.root] = (self.root, IDENTITY)
        pending = []
        frame = name
        while frame not in anchors:
            if frame in self.joints or self.is_moving(frame):
                anchors[frame] = (frame, IDENTITY)
                break
            pending.append(frame)
            frame = self.parents[frame]
        for frame in reversed(pending):
            anchor, placement = anchors[self.parents[frame]]
            pose = self.local_poses[frame]
            anchors[frame] = (anchor, compose(placement, (pose.rotation, pose.translation)))
        return anchors[name]

    def path_layout(self, frame: str, relative_to: str, also: Sequence[str] = ()
                    ) -> Transform | ModelLayout:
        """The path between two frames: the static pose of ``frame`` in ``relative_to``
        when nothing between them moves and no other frame is asked for, else the layout of
        a model rooted at the lowest common ancestor of both and the frames ``also``,
        holding them all."""
        anchor, placement = self.anchor(frame)
        reference_anchor, reference_placement = self.anchor(relative_to)
        if anchor == reference_anchor and not also:
            return compose(inverse(reference_placement), placement)
        frames = [frame, relative_to, *also]
        common = frame
        for other in frames[1:]:
            common = paths_to_common_ancestor(self.parents, self.depths, common, other)[0][-1]
        return self.model_layout(common, frames)

    def model_layout(self, root: str, frames: list[str]) -> ModelLayout:
        """The layout of a model rooted at ``root`` holding ``frames`` (``root`` or below it)
        and every joint above them."""
        root_anchor, root_placement = self.anchor(root)
        root_depth = self.depths[root]
        from_root_anchor = inverse(root_placement)
        joint_frames: set[str] = set()
        for frame in frames:
            anchor = self.anchor(frame)[0]
            while self.depths[anchor] > root_depth and anchor not in joint_frames:
                joint_frames.add(anchor)
                anchor = self.anchor(self.parents[anchor])[0]
        # by depth (parents first), then name: the same joint order in every process
        ordered = sorted(joint_frames, key=lambda frame: (self.depths[frame], frame))
        index = {frame: position for position, frame in enumerate(ordered)}

        def placed(anchor: str, placement: Transform) -> tuple[int, Transform]:
            if anchor in index:
                return index[anchor], placement
            if anchor != root_anchor:
                raise AssertionError(f"{anchor!r} is not below {root!r}")
            return -1, compose(from_root_anchor, placement)

        joints = []
        for frame in ordered:
            parent, placement = placed(*self.anchor(self.parents[frame]))
            joint = self.joints.get(frame)
            if joint is not None:
                origin = self.local_poses[frame]
                placement = compose(placement, (origin.rotation, origin.translation))
            joints.append(ModelJoint(frame, parent, placement, joint))
        placements = {frame: placed(*self.anchor(frame)) for frame in frames}
        return ModelLayout(root, tuple(joints), placements)

    def first_warning(self, kind: str) -> bool:
        """True the first time this version is asked about the warning ``kind``: a
        warning about the tree is given once per version."""
        if kind in self._warned:
            return False
        self._warned.add(kind)
        return True


def _time_groups(trajectories: Mapping[str, JointTrajectory],
                 tree_reference: np.datetime64 | None) -> dict[str, str]:
    """Per driven joint, the first one whose trajectory has the same times counted from
    the same reference time (see :attr:`TreeDescription.time_groups`)."""
    groups: dict[str, str] = {}
    leaders: list[tuple[str, JointTrajectory, np.datetime64 | None]] = []
    for name, trajectory in trajectories.items():
        times = trajectory.times
        reference = source_reference(trajectory.reference, tree_reference)
        groups[name] = next(
            (leader for leader, known, known_reference in leaders
             if known_reference == reference
             and (known.times is times or (known.times.shape == times.shape
                                           and np.array_equal(known.times, times)))),
            name)
        if groups[name] == name:
            leaders.append((name, trajectory, reference))
    return groups


def paths_to_common_ancestor(
    parents: Mapping[str, str], depths: Mapping[str, int], a: str, b: str
) -> tuple[list[str], list[str]]:
    """Frames from ``a`` and from ``b`` up to and including their lowest common ancestor."""
    up_a, up_b = [a], [b]
    while depths[up_a[-1]] > depths[up_b[-1]]:
        up_a.append(parents[up_a[-1]])
    while depths[up_b[-1]] > depths[up_a[-1]]:
        up_b.append(parents[up_b[-1]])
    while up_a[-1] != up_b[-1]:
        up_a.append(parents[up_a[-1]])
        up_b.append(parents[up_b[-1]])
    return up_a, up_b
