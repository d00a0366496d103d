"""Preparing a query path: from two frame names to what evaluating it at times needs.

A query between two frames whose anchors (nearest joint or moving frame) coincide has
nothing moving between them and is one cached static transform. Otherwise the frames between
them and their lowest common ancestor are compiled into a
:class:`~pinframes.kinematics._model.CompiledModel` rooted at that ancestor, so the cost of a
query depends on its path, not on the tree. Prepared once per tree version (cached in the
:class:`TreeDescription`).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import NDArray

from ..errors import InvalidPoseError
from ..values.interpolation import Keyframes
from ..values.joint import Joint, mimic_chain
from ..values.numbers import require_finite_result
from ..values.se3 import Transform
from ..values.timeline import TimedSource
from ._description import ModelLayout, TreeDescription
from ._model import CompiledModel

__all__ = ["PreparedPath", "model_sources", "prepare_path", "require_finite_pose"]


@dataclass(frozen=True)
class PreparedPath:
    """A query path prepared for repeated evaluation.

    Either ``static`` (the pose of the frame in the reference frame, when nothing between
    them can move) or ``model`` with, per joint, the moving frame's keyframes with the
    joint placement folded in (:meth:`Keyframes.placed`; None for robot joints), and the
    moving things it samples. ``plans`` keeps what queries derive from the path once (the
    one-time plan), so that it lives as long as the path.
    """

    frame: str
    relative_to: str
    static: Transform | None
    model: CompiledModel | None = None
    placed_keyframes: tuple[Keyframes | None, ...] = ()
    sources: tuple[TimedSource, ...] = ()
    plans: dict[str, Any] = field(default_factory=dict, compare=False, repr=False)


def prepare_path(tree: TreeDescription, frame: str, relative_to: str) -> PreparedPath:
    """The query path from ``frame`` to ``relative_to``, compiled once per tree version."""
    key = (frame, relative_to)
    cached = tree.cached(key)
    if cached is not None:
        return cached
    layout = tree.path_layout(frame, relative_to)
    if isinstance(layout, ModelLayout):
        model = CompiledModel(layout)
        keyframes = tuple(
            None if joint.joint is not None
            else tree.local_poses[joint.frame].keyframes.placed(model.joint_placements[position])
            for position, joint in enumerate(model.joints))
        path = PreparedPath(frame, relative_to, None, model, keyframes,
                            tuple(model_sources(tree, model)))
    else:
        require_finite_pose(layout[1], frame, relative_to)
        path = PreparedPath(frame, relative_to, layout)
    tree.store(key, path)
    return path


def require_finite_pose(translation: NDArray[np.float64], frame: str, relative_to: str
                        ) -> None:
    """An :class:`~pinframes.errors.InvalidPoseError` naming the frame when the pose of
    ``frame`` in ``relative_to``, composed from finite poses, overflowed to infinity or NaN
    (two translations of 1e308 m)."""
    require_finite_result(translation, f"the pose of {frame!r} in {relative_to!r}",
                          InvalidPoseError, frame=frame, field="translation")


def model_sources(tree: TreeDescription, model: CompiledModel) -> list[TimedSource]:
    """The moving frames and driven joints whose values a compiled model needs."""
    sources: dict[str, TimedSource] = {}
    for joint in model.joints:
        if joint.joint is None:
            sources[joint.frame] = tree.frame_source(joint.frame)
            continue
        for name in _driving_joints(tree, joint.joint):
            if name in tree.joint_trajectories:
                sources[name] = tree.joint_source(name)
    return list(sources.values())


def _driving_joints(tree: TreeDescription, joint: Joint) -> list[str]:
    """``joint`` and, for a mimic joint, the chain of joints it follows."""
    return [link.name for link in mimic_chain(joint, tree.joints_by_name)]
