"""Kinematics: a frozen description of a tree, compiled to Pinocchio and evaluated.

``FrameTree`` hands a :class:`TreeDescription` to :func:`evaluate_pose`, which compiles the
query path (``_model``), plans its times (``_timeline``) and evaluates it (``_evaluate``).
Velocities and Jacobians (:func:`evaluate_velocity`, :func:`evaluate_jacobian`) sample the
same path (``sampled_path``) and add the exact rates of what it interpolates (``rates``)
through the joints' twists (``twists``).
"""

from ._description import TreeDescription, paths_to_common_ancestor
from ._evaluate import default_times, evaluate_pose
from ._many import evaluate_poses
from ._snapshot import Snapshot, snapshot
from .clearance import Clearance, evaluate_clearance
from .jacobian import FrameJacobian, evaluate_jacobian
from .pinocchio_tree import PinocchioTree
from .velocity import Velocity, evaluate_velocity

__all__ = [
    "Clearance",
    "FrameJacobian",
    "PinocchioTree",
    "Snapshot",
    "TreeDescription",
    "Velocity",
    "default_times",
    "evaluate_clearance",
    "evaluate_jacobian",
    "evaluate_pose",
    "evaluate_poses",
    "evaluate_velocity",
    "paths_to_common_ancestor",
    "snapshot",
]
