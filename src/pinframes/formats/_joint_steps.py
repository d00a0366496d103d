"""Checking that a robot joint's trajectory can be written as sampled poses.

Writers turn a link driven by a revolute or continuous joint into a moving frame keyed at the
joint's trajectory samples. Readers give those keyframes the default frame interpolation
(:data:`~pinframes.values.interpolation.DEFAULT_FRAME_INTERPOLATION`), which reproduces a
turn at constant rate only for steps below its ``largest_uniform_turn`` (SLERP's: half a
turn, as it takes the short way).
"""

from __future__ import annotations

import numpy as np

from ..errors import UnsupportedFeatureError
from ..tree import FrameTree
from ..values.interpolation import DEFAULT_FRAME_INTERPOLATION
from ..values.joint import mimic_drive

__all__ = ["check_joint_steps"]


def check_joint_steps(tree: FrameTree, name: str) -> None:
    """Raise :class:`UnsupportedFeatureError` if the joint moving link ``name`` (through any
    mimic chain) turns between two samples of its trajectory by more than keyframes can
    say (half a turn or more)."""
    joint = tree.joint_of(name)
    if joint is None or joint.kind == "prismatic":
        return
    drive = mimic_drive(joint, tree.joints)
    multiplier = drive.multiplier
    trajectory = tree.joint_trajectory(drive.primary)
    largest = DEFAULT_FRAME_INTERPOLATION.largest_uniform_turn
    if trajectory is not None and np.any(np.abs(np.diff(trajectory.values) * multiplier)
                                         >= largest):
        raise UnsupportedFeatureError(
            "its joint turns by half a turn or more between two trajectory samples, which "
            "sampled poses cannot represent (interpolation takes the short way); resample "
            "the trajectory more densely", frame=name)
