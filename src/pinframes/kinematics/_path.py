"""Preparing a query path: from two frame names to what evaluating it at times needs.

A query between two frames whose anchors (nearest joint or moving frame) coincide has
nothing moving between them and is one cached static transform. Otherwise the frames between
them and their lowest common ancestor are compiled into a
:class:`~pinframes.kinematics._model.CompiledModel` rooted at that ancestor, so the cost of a
query depends on its path, not on the tree. Prepared once per tree version (cached in the
:class:`TreeDescription`).
"""

from __future__ import annotations

from dataclasses import dataclass

from ..values.interpolation import Keyframes
from ..values.joint import Joint, mimic_chain
from ..values.se3 import IDENTITY, Transform, compose, inverse
from ..values.timeline import TimedSource
from ._description import TreeDescription, paths_to_common_ancestor
from ._model import CompiledModel, compile_model

__all__ = ["PreparedPath", "model_sources", "prepare_path"]


@dataclass(frozen=True)
class PreparedPath:
    """A query path prepared for repeated evaluation.

    Either ``static`` (the pose of the frame in the reference frame, when nothing between
    them can move) or ``model`` with, per joint, the moving frame's keyframes with the
    joint placement folded in (None for robot joints), and the moving things it samples.
    """

    frame: str
    relative_to: str
    static: Transform | None
    model: CompiledModel | None = None
    placed_keyframes: tuple[Keyframes | None, ...] = ()
    sources: tuple[TimedSource, ...] = ()


def prepare_path(tree: TreeDescription, frame: str, relative_to: str) -> PreparedPath:
    """The query path from ``frame`` to ``relative_to``, compiled once per tree version."""
    key = (frame, relative_to)
    cached = tree.cached(key)
    if cached is not None:
        return cached
    anchor, placement = tree.anchor(frame)
    reference_anchor, reference_placement = tree.anchor(relative_to)
    if anchor == reference_anchor:
        path = PreparedPath(frame, relative_to, compose(inverse(reference_placement),
                                                        placement))
    else:
        up, _ = paths_to_common_ancestor(tree.parents, tree.depths, frame, relative_to)
        model = compile_model(tree, up[-1], [frame, relative_to])
        keyframes = tuple(
            None if joint.joint is not None else _placed_keyframes(
                tree.local_poses[joint.frame].keyframes, model.joint_placements[position])
            for position, joint in enumerate(model.joints))
        path = PreparedPath(frame, relative_to, None, model, keyframes,
                            tuple(model_sources(tree, model)))
    tree.store(key, path)
    return path


def _placed_keyframes(keyframes: Keyframes, placement: Transform) -> Keyframes:
    """Keyframes of ``placement @ pose``: a static factor on the left commutes with
    linear interpolation and SLERP, so it can be applied to the keyframes once."""
    if placement is IDENTITY:
        return keyframes
    rotation, translation = placement
    return Keyframes(keyframes.times, rotation @ keyframes.rotations,
                     keyframes.translations @ rotation.T + translation)


def model_sources(tree: TreeDescription, model: CompiledModel) -> list[TimedSource]:
    """The moving frames and driven joints whose values a compiled model needs."""
    sources: dict[str, TimedSource] = {}
    for joint in model.joints:
        if joint.joint is None:
            pose = tree.local_poses[joint.frame]
            reference = pose.reference_time if pose.reference_time is not None else (
                tree.reference_time)
            sources[joint.frame] = TimedSource(joint.frame, pose.keyframes.times, reference)
            continue
        for name in _driving_joints(tree, joint.joint):
            trajectory = tree.joint_trajectories.get(name)
            if trajectory is not None:
                reference = trajectory.reference if trajectory.reference is not None else (
                    tree.reference_time)
                sources[name] = TimedSource(name, trajectory.times, reference)
    return list(sources.values())


def _driving_joints(tree: TreeDescription, joint: Joint) -> list[str]:
    """``joint`` and, for a mimic joint, the chain of joints it follows."""
    return [link.name for link in mimic_chain(joint, tree.joints_by_name)]
