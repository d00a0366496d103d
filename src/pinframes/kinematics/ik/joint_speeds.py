"""Joint speeds against the URDF velocity limits: the check of
``solve_joints(..., strict=True)``.

Rates are radians per second (revolute, continuous) or metres per second (prismatic), in
the units of the solved joint's value; each solved joint's limit is its own or a mimic
follower's (:class:`~pinframes.kinematics.ik._solved_joints.SolvedJoints`).
"""

from __future__ import annotations

from collections.abc import Mapping

import numpy as np
from numpy.typing import NDArray

from ...errors import JointSpeedError
from ...values.joint import Joint
from .joint_solution import JointSolution

__all__ = ["require_within_speed", "speed_unit"]

FloatArray = NDArray[np.float64]


def speed_unit(joint: Joint) -> str:
    """``"m/s"`` for a prismatic joint, else ``"rad/s"``."""
    return "m/s" if joint.kind == "prismatic" else "rad/s"


def require_within_speed(solution: JointSolution, joints: Mapping[str, Joint], frame: str
                         ) -> None:
    """Raise :class:`~pinframes.errors.JointSpeedError` at the first sample where a joint
    moves faster than its URDF velocity limit, naming the joint whose limit it passes (a
    mimic follower of a solved joint, where its limit is the tighter one), the time, its
    speed and the ratio to its limit."""
    ratios = solution.joint_speed_ratios
    over = np.flatnonzero(ratios.max(axis=1, initial=0.0) > 1.0)
    if not over.shape[0]:
        return
    index = int(over[0])
    column = int(np.argmax(ratios[index]))
    ratio = float(ratios[index, column])
    solved, limiting = solution.joint_names[column], joints[solution.velocity_limit_joints[column]]
    limit = limiting.velocity
    assert limit is not None  # a finite velocity limit came from it
    unit = speed_unit(limiting)
    when = solution.when(index)
    follows = "" if limiting.name == solved else f" (it follows {solved!r})"
    raise JointSpeedError(
        f"{ratio * limit:.3g} {unit} at {when} (sample {index + 1} of {len(solution)}) is "
        f"{ratio:.3g} times its velocity limit {limit:.3g} {unit}{follows}",
        joint=limiting.name, frame=frame, field="velocity")
