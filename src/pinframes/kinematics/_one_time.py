"""Queries at one time (or a few): every source sampled in Python floats, then Pinocchio's own
forward kinematics.

The batched kernels of :mod:`pinframes.kinematics.pose` are built for many samples; at
one sample their cost is numpy's overhead per call (about 45 calls on arrays of length one
to interpolate a moving frame, as many again to compose the path). Here, per time, the
configuration ``q`` of the compiled model is set from the interpolated poses of its moving
frames and from its joint values, and ``pinocchio.forwardKinematics`` with
``updateFramePlacement`` yields the two frames in the model's root:

- a free-flyer takes its moving frame's pose in the frame's parent (the raw keyframes; the
  static placement of the joint is in the model) as ``x y z qx qy qz qw``;
- a robot joint its value (radians or metres) from its trajectory (held outside its
  samples), its mimic primary's (``multiplier * primary + offset``) or its rest value; a
  continuous joint about an aligned axis, which Pinocchio stores as ``(cos, sin)``, both.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import pinocchio as pin
from numpy.typing import NDArray

from ..values.interpolation import FrameInterpolation, JointInterpolation, segment_position
from ..values.se3 import Transform
from ._model import CompiledModel
from ._plan import PreparedPath
from ._sampling import MovingFrame

__all__ = ["FEW_TIMES", "MAX_DEGREES_OF_FREEDOM", "OneTimePlan", "one_time_plan",
           "takes_few_times"]

FEW_TIMES = 8
"""Queries with at most this many evaluation times take this path, longer ones the batched
kernels. Measured with benchmarks/bench_few_times.py (shared 2-core machine, both thread
settings alike): this path costs about 7-10 us per time on a frame moving between two static
frames and 20-25 us per time on the Panda on a moving mount, the batched kernels about 90 us
and 320 us whatever the count up to 32; one-time / batched was 0.93 at 8 times and 1.2 at 12
on the light path, 0.48 at 8 and 1.09 at 24 on the Panda."""


MAX_DEGREES_OF_FREEDOM = 32
"""Largest model (``nv``) answered here. ``pinocchio.Data`` holds tensors of ``nv**3``
numbers: in pin 4.1 ``createData`` took 4 MB and 2.3 ms at 32, 20 MB at 64, 139 MB at 128
and 4 GB at 400 degrees of freedom; longer paths take the numpy kernels, which need no
such workspace."""


def takes_few_times(times: NDArray[np.int64] | None, model: CompiledModel) -> bool:
    """Whether a query at ``times`` through ``model`` is answered here: it has at most
    :data:`FEW_TIMES` evaluation times, or none (nothing on its path is sampled: one
    configuration), and at most :data:`MAX_DEGREES_OF_FREEDOM`."""
    return ((times is None or times.shape[0] <= FEW_TIMES)
            and model.model.nv <= MAX_DEGREES_OF_FREEDOM)


@dataclass(frozen=True)
class _MovingFrame:
    """A free-flyer: the moving frame ``source`` and the interpolation of its keyframes in
    its parent."""

    source: str
    keyframes: FrameInterpolation


@dataclass(frozen=True)
class _RobotJoint:
    """A robot joint: driven by the joint ``primary`` (itself unless it mimics one), from
    the interpolation of its ``trajectory``, whose times it shares with the joints of
    ``time_group`` (see :attr:`TreeDescription.time_groups`), or, without one, at ``rest``
    (radians or metres); ``mimics`` are the ``(multiplier, offset)`` of the mimic links from
    the primary out to the joint."""

    primary: str
    trajectory: JointInterpolation | None
    time_group: str
    rest: float
    mimics: tuple[tuple[float, float], ...]
    cos_sin: bool


class OneTimePlan:
    """A compiled query path prepared for evaluation at single times.

    Parameters
    ----------
    path : PreparedPath
        A moving path: its model, and how each of its joints is sampled.
    """

    def __init__(self, path: PreparedPath) -> None:
        model = path.model
        assert model is not None, "a static path has no model to evaluate"
        self.model = model
        self.frame_id = model.frame_ids[path.frame]
        self.reference_id = model.frame_ids[path.relative_to]
        steps: list[_MovingFrame | _RobotJoint] = []
        for position, sampler in enumerate(path.samplers):
            if isinstance(sampler, MovingFrame):
                steps.append(_MovingFrame(sampler.frame, sampler.keyframes.scheme()))
                continue
            trajectory = sampler.trajectory
            # Pinocchio's joint ids count from 1 (0 is the universe)
            cos_sin = model.model.joints[position + 1].nq == 2
            steps.append(_RobotJoint(sampler.primary, None if trajectory is None
                                     else trajectory.scheme(), sampler.time_group,
                                     sampler.rest, sampler.mimics, cos_sin))
        self._steps = tuple(steps)

    def poses(self, times: NDArray[np.int64] | None, shifts: dict[str, int]) -> Transform:
        """The pose of the frame in the reference frame at each of ``times`` (timeline
        basis, ns; None: the one configuration of a path without samples) as ``(N, 3, 3)``
        rotations and ``(N, 3)`` translations (metres).

        ``shifts`` holds, per source, what to subtract from a timeline time to land on the
        source's own time basis.
        """
        moments: list[int] = [0] if times is None else times.tolist()
        rotations = np.empty((len(moments), 3, 3))
        translations = np.empty((len(moments), 3))
        model, data = self.model.model, self.model.data
        for sample, time in enumerate(moments):
            pin.forwardKinematics(model, data, np.array(self._configuration(time, shifts)))
            frame_in_root = pin.updateFramePlacement(model, data, self.frame_id)
            reference_in_root = pin.updateFramePlacement(model, data, self.reference_id)
            frame_in_reference = reference_in_root.actInv(frame_in_root)
            rotations[sample] = frame_in_reference.rotation
            translations[sample] = frame_in_reference.translation
        return rotations, translations

    def _configuration(self, time: int, shifts: dict[str, int]) -> list[float]:
        """Pinocchio's configuration ``q`` of the model at ``time`` (timeline basis, ns)."""
        q: list[float] = []
        # joints driven together (one time group) have equal times: search them once
        positions: dict[str, tuple[int, float]] = {}
        for step in self._steps:
            if isinstance(step, _MovingFrame):
                translation, quaternion = step.keyframes.pose_at(time - shifts[step.source])
                q += translation
                q += quaternion
                continue
            trajectory = step.trajectory
            if trajectory is None:
                value = step.rest
            else:
                shift = shifts[step.primary]
                position = positions.get(step.time_group)
                if position is None:
                    position = positions[step.time_group] = segment_position(
                        trajectory.times, time - shift)
                value = trajectory.value_at(time - shift, position)
            for multiplier, offset in step.mimics:
                value = multiplier * value + offset
            if step.cos_sin:
                q += (math.cos(value), math.sin(value))
            else:
                q.append(value)
        return q


def one_time_plan(path: PreparedPath) -> OneTimePlan:
    """The :class:`OneTimePlan` of a moving ``path``, made once and kept with the path."""
    plan = path.plans.get(OneTimePlan, "one time")
    if plan is None:
        plan = path.plans.keep(OneTimePlan, "one time", OneTimePlan(path))
    return plan
