"""Kinematics: a frozen description of a tree, compiled to Pinocchio and evaluated.

``FrameTree`` hands a :class:`TreeDescription` to :func:`evaluate_pose`, which compiles the
query path (``_model``), plans its times (``_timeline``) and evaluates it (``_evaluate``).
"""

from ._description import TreeDescription, paths_to_common_ancestor
from ._evaluate import default_times, evaluate_pose
from ._many import evaluate_poses
from .pinocchio_tree import PinocchioTree

__all__ = [
    "PinocchioTree",
    "TreeDescription",
    "default_times",
    "evaluate_pose",
    "evaluate_poses",
    "paths_to_common_ancestor",
]
