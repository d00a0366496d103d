"""A frame tree, or the part of it on a query path, compiled to a Pinocchio model.

Moving frames become free-flyer joints, robot joints keep their kind, and static frames are
flattened onto their nearest joint as Pinocchio frames (whose placement is relative to the
parent *joint*). :meth:`CompiledModel.forward_kinematics` evaluates the model's kinematics for
many samples at once with numpy, from the placements stored in the ``pinocchio.Model``; it
equals ``pinocchio.framesForwardKinematics`` at every sample (tested to 1e-12).
"""

from __future__ import annotations

import threading
from collections.abc import Iterator, Mapping, Sequence
from typing import Any

import numpy as np
import pinocchio as pin
from numpy.typing import NDArray

from ..values.rotations import quaternion_from_matrix
from ..values.se3 import IDENTITY, Transform, canonical, compose
from ._description import ModelLayout, TreeDescription

__all__ = ["CompiledModel", "compile_model"]


class CompiledModel:
    """Pinocchio model of a :class:`ModelLayout`: its root is Pinocchio's universe, its
    joints the model's joints (:attr:`joints`, parents before children), its frames
    ``OP_FRAME`` frames on their nearest joint.
    """

    def __init__(self, layout: ModelLayout) -> None:
        root, frames = layout.root, layout.frames
        self.root = root
        self.joints = layout.joints
        self.model = pin.Model()
        self.model.name = root
        for joint in self.joints:
            joint_model = pin.JointModelFreeFlyer() if joint.joint is None else (
                joint.joint.pinocchio_joint_model())
            self.model.addJoint(joint.parent + 1, joint_model, _to_se3(joint.placement),
                                joint.name)
        self.frame_ids: dict[str, int] = {}
        for name, (parent, placement) in frames.items():
            self.frame_ids[name] = self.model.addFrame(
                pin.Frame(name, parent + 1, _to_se3(placement), pin.FrameType.OP_FRAME))
        # The kernel reads its numbers back from the Pinocchio model it evaluates.
        self._joint_placements = [_from_se3(self.model.jointPlacements[i + 1])
                                  for i in range(len(self.joints))]
        self._last_child = [-1] * len(self.joints)  # joint index -> its last child joint
        for index, joint in enumerate(self.joints):
            if joint.parent >= 0:
                self._last_child[joint.parent] = index
        self._frame_placements = {}
        for name, fid in self.frame_ids.items():
            frame = self.model.frames[fid]
            self._frame_placements[name] = (frame.parentJoint - 1, _from_se3(frame.placement))
        self._per_thread = threading.local()

    def __getstate__(self) -> dict[str, Any]:
        """Everything but the per-thread ``pinocchio.Data`` (created again where used)."""
        state = self.__dict__.copy()
        del state["_per_thread"]
        return state

    def __setstate__(self, state: dict[str, Any]) -> None:
        self.__dict__.update(state)
        self._per_thread = threading.local()

    @property
    def data(self) -> pin.Data:
        """This thread's ``pinocchio.Data`` of :attr:`model`, created on first use (queries
        may run in several threads at once, and each needs its own workspace)."""
        data = getattr(self._per_thread, "data", None)
        if data is None:
            data = self._per_thread.data = self.model.createData()
        return data

    @property
    def joint_ids(self) -> dict[str, int]:
        """Pinocchio joint id of each joint, by joint name."""
        return {joint.name: index + 1 for index, joint in enumerate(self.joints)}

    @property
    def joint_placements(self) -> tuple[Transform, ...]:
        """Per joint, its static placement in the parent joint frame, read from the model."""
        return tuple(self._joint_placements)

    def joint_frames(self, samples: Sequence[Any]) -> Iterator[tuple[int, Transform]]:
        """Each joint's index and frame in the root (``oMi``), static or samples last, parents
        before children.

        ``samples[i]`` is what :func:`~pinframes.kinematics._sampling.sample_joints` gives:
        a free-flyer's pose in its parent joint, placement included; a robot joint's
        value(s). Pinocchio's recursion ``oMi[j] = oMi[parent(j)] @ placement[j] @
        motion_j(q)``, evaluated left to right so that the static placement meets one
        frame (its zeros and ones cost nothing) and the motion only turns two columns.

        A joint's frame is held here only until its last child joint is placed: a consumer
        that keeps what it needs, not every frame, keeps the memory of a chunk small, which
        glibc then reuses instead of returning it to the system and taking page faults for
        it again (3 us per 4 kB page on our machines; 1,400 per Panda query at 10^4 samples
        when every frame was kept).
        """
        held: dict[int, Transform] = {}
        for index, (joint, placement, sample) in enumerate(
                zip(self.joints, self._joint_placements, samples, strict=True)):
            parent = IDENTITY if joint.parent < 0 else held[joint.parent]
            if joint.joint is None:
                frame = compose(parent, sample)
            else:
                frame = joint.joint.moved(compose(parent, placement), sample)
            if joint.parent >= 0 and self._last_child[joint.parent] == index:
                del held[joint.parent]
            if self._last_child[index] >= 0:
                held[index] = frame
            yield index, frame

    def frame_placements_in_root(self, joint_frames: Mapping[int, Transform],
                                 frames: Sequence[str]) -> list[Transform]:
        """Placements in the root of ``frames`` (``oMf``) from their parent joints' ``oMi``
        (``joint_frames`` by joint index; see :meth:`frame_parents`)."""
        result = []
        for name in frames:
            parent, placement = self._frame_placements[name]
            result.append(placement if parent < 0 else compose(joint_frames[parent], placement))
        return result

    def frame_parents(self, frames: Sequence[str]) -> set[int]:
        """Indices of the joints that ``frames`` hang from (the root's frames: none)."""
        return {parent for parent, _ in map(self._frame_placements.__getitem__, frames)
                if parent >= 0}

    def forward_kinematics(self, samples: Sequence[Any], frames: Sequence[str]
                           ) -> list[Transform]:
        """Placements in the root of ``frames`` from the joints' samples (see
        :meth:`joint_frames`): Pinocchio's ``framesForwardKinematics``, with
        ``oMf = oMi[parent joint] @ placement``."""
        parents = self.frame_parents(frames)
        kept = {index: frame for index, frame in self.joint_frames(samples) if index in parents}
        return self.frame_placements_in_root(kept, frames)

    def configuration(
        self, motions: Sequence[Transform | None],
        values: Sequence[NDArray[np.float64] | float | None], count: int,
    ) -> NDArray[np.float64]:
        """Pinocchio configurations ``(count, nq)`` for motions and joint values, each static
        or one per sample.

        ``motions[i]`` is used for free-flyers (the moving frame's pose, samples first),
        ``values[i]`` (one value or shape (N,)) for robot joints.
        """
        columns = []  # (N, k) entries, or (1, k) and (k,) for static ones
        for joint, motion, value in zip(self.joints, motions, values, strict=True):
            if joint.joint is None:
                assert motion is not None
                rotation, translation = motion
                columns.append(translation)
                columns.append(quaternion_from_matrix(rotation))
            else:
                assert value is not None
                columns.append(joint.joint.configuration(np.atleast_1d(value)))
        configurations = np.empty((count, sum(column.shape[-1] for column in columns)))
        start = 0
        for column in columns:  # a static entry broadcasts down its slots
            configurations[:, start:start + column.shape[-1]] = column
            start += column.shape[-1]
        return configurations


def compile_model(tree: TreeDescription, root: str, frames: list[str]) -> CompiledModel:
    """A Pinocchio model rooted at ``root`` holding ``frames`` and every joint above them
    (:meth:`TreeDescription.model_layout`); every frame must be ``root`` or below it."""
    return CompiledModel(tree.model_layout(root, frames))


def _to_se3(transform: Transform) -> pin.SE3:
    rotation, translation = transform
    return pin.SE3(np.array(rotation, dtype=float), np.array(translation, dtype=float))


def _from_se3(placement: pin.SE3) -> Transform:
    return canonical((np.array(placement.rotation), np.array(placement.translation)))
