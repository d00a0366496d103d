"""A compiled query path sampled at times: every joint's frame and both ends in the root.

Shared by velocities and Jacobians: both need, per sample, where each joint of the path is
(``oMi``), where the frame and the reference frame are (``oMf``), and which joints move
which end.
"""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import NDArray

from ..values._se3 import Transform
from ..values._timeline import QueryTimeline
from . import _evaluate
from ._description import TreeDescription
from ._model import CompiledModel
from .twists import joint_signs

__all__ = ["PlannedQuery", "SampledPath", "plan_query", "sample_path"]


@dataclass(frozen=True)
class SampledPath:
    """A query path at ``N`` samples, in its model's root ``C``.

    Attributes
    ----------
    model : CompiledModel
        The compiled path.
    joints : list of Transform
        Per joint of the model, its frame in ``C`` (``oMi``).
    frame, relative_to : Transform
        The query frame and the reference frame in ``C``.
    signs : dict of int to float
        +1 for the joints moving the frame, -1 for those moving the reference frame.
    shifts : dict of str to int
        Per moving thing, what to subtract from timeline times to reach its own basis.
    times : ndarray of int64
        The sample times on the timeline's basis.
    """

    model: CompiledModel
    joints: list[Transform]
    frame: Transform
    relative_to: Transform
    signs: dict[int, float]
    shifts: dict[str, int]
    times: NDArray[np.int64]


@dataclass(frozen=True)
class PlannedQuery:
    """A query's compiled path, its timeline and the result's times."""

    evaluation: _evaluate.Evaluation
    timeline: QueryTimeline
    count: int
    offsets: NDArray[np.int64] | None

    @property
    def times(self) -> NDArray[np.timedelta64] | None:
        """Result times after :attr:`reference_time`, ``timedelta64[ns]``; None if static."""
        return None if self.offsets is None else self.offsets.astype("timedelta64[ns]")

    @property
    def reference_time(self) -> np.datetime64 | None:
        return self.timeline.reference

    def chunks(self, tree: TreeDescription) -> Iterator[tuple[slice, SampledPath]]:
        """The path sampled in slices of at most ``_evaluate.CHUNK`` times (moving paths only)."""
        evaluation, timeline = self.evaluation, self.timeline
        assert evaluation.model is not None, "a static path has no model to sample"
        shifts = _evaluate.basis_shifts(list(evaluation.sources), timeline)
        signs = joint_signs(evaluation.model, evaluation.frame, evaluation.relative_to)
        times = timeline.evaluation_times
        if times is None:
            times = np.zeros(1, dtype=np.int64)
        for start in range(0, self.count, _evaluate.CHUNK):
            part = slice(start, start + _evaluate.CHUNK)
            yield part, sample_path(tree, evaluation, signs, shifts, times[part])


def plan_query(tree: TreeDescription, frame: str, relative_to: str, times: Any, time_ref: Any,
               extrapolation: str) -> PlannedQuery:
    """Compile (or reuse) the path and plan its timeline by the rules of ``pose()``."""
    evaluation = _evaluate.prepare_evaluation(tree, frame, relative_to)
    timeline = _evaluate.checked_timeline(tree, evaluation, times, time_ref, extrapolation)
    offsets = timeline.result_offsets
    return PlannedQuery(evaluation, timeline, 1 if offsets is None else offsets.shape[0],
                        offsets)


def sample_path(tree: TreeDescription, evaluation: _evaluate.Evaluation, signs: dict[int, float],
                shifts: dict[str, int], times: NDArray[np.int64]) -> SampledPath:
    """The path of ``evaluation`` (a moving one) at ``times`` (timeline basis)."""
    model = evaluation.model
    assert model is not None, "a static path has no model to sample"
    samples = _evaluate.sample_joints(tree, model, evaluation.placed_keyframes, times, shifts)
    joints = model.joint_placements_in_root(samples)
    frame, relative_to = model.frame_placements_in_root(
        joints, [evaluation.frame, evaluation.relative_to])
    # the twist sums work on (N, 3, 3) / (N, 3) stacks; the evaluator's are samples last
    return SampledPath(model, [_stacked(joint) for joint in joints], _stacked(frame),
                       _stacked(relative_to), signs, shifts, times)


def _stacked(transform: Transform) -> Transform:
    """``(N, 3, 3)`` / ``(N, 3)`` views of a samples-last transform (copying every joint
    frame took a quarter of a velocity query); static parts stay the same objects, so the
    shared identity is still recognised."""
    rotation, translation = transform
    return (np.moveaxis(rotation, -1, 0) if rotation.ndim == 3 else rotation,
            translation.T if translation.ndim == 2 else translation)
