"""Checking that a robot joint's trajectory can be written as sampled poses.

Writers turn a link driven by a revolute or continuous joint into a moving frame keyed at the
joint's trajectory samples. That is exact only while each step between two samples turns by
less than half a turn: readers interpolate rotations with SLERP, which takes the short way.
"""

from __future__ import annotations

import numpy as np

from ..errors import UnsupportedFeatureError
from ..tree import FrameTree
from ..values.joint import mimic_chain

__all__ = ["check_joint_steps"]


def check_joint_steps(tree: FrameTree, name: str) -> None:
    """Raise :class:`UnsupportedFeatureError` if the joint moving link ``name`` (through any
    mimic chain) turns by half a turn or more between two samples of its trajectory."""
    joint = tree.joint_of(name)
    if joint is None or joint.kind == "prismatic":
        return
    chain = mimic_chain(joint, tree.joints)
    multiplier = float(np.prod([link.mimic.multiplier for link in chain[:-1]
                                if link.mimic is not None]))
    trajectory = tree.joint_trajectory(chain[-1].name)
    if trajectory is not None and np.any(np.abs(np.diff(trajectory.values) * multiplier) >= np.pi):
        raise UnsupportedFeatureError(
            "its joint turns by half a turn or more between two trajectory samples, which "
            "sampled poses cannot represent (interpolation takes the short way); resample "
            "the trajectory more densely", frame=name)
