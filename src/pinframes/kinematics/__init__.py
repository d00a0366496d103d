"""Kinematics: a frozen description of a tree, compiled to Pinocchio and queried.

The queries, one public module each: :mod:`.pose` (``FrameTree.pose``, ``sample_times``),
:mod:`.poses` (many pairs in one call), :mod:`.snapshot` (the whole tree at one instant),
:mod:`.velocity`, :mod:`.jacobian`, :mod:`.weld_process` (the welding process along a seam)
and :mod:`.pinocchio_tree` (``to_pinocchio``). Two rooms of their own: :mod:`.ik` (inverse
kinematics along a path: ``solve_joints`` and its solution) and :mod:`.collision` (the
clearance between frames' shapes, with coal). Every query is planned once by
:func:`._plan.plan_query` (its path, its timeline, how each joint is sampled) and evaluated
with the steps they all share, the ``_`` modules here: the frozen tree (``_description``),
the plan (``_plan``), its compiled path (``_model``), joint sampling (``_sampling``), the
one-time path (``_one_time``), for velocities and Jacobians the sampled path
(``_sampled_path``) and joint twists (``_twists``) (the exact rates of what moves are its
interpolation scheme's, :mod:`pinframes.values.interpolation`).
"""

from ._description import TreeDescription, paths_to_common_ancestor
from .closed_form.solutions import IkSolutions
from .collision import Clearance, clearance_times, evaluate_clearance
from .ik import JointSolution, evaluate_ik_solutions, evaluate_solve_joints
from .jacobian import FrameJacobian, evaluate_jacobian
from .pinocchio_tree import PinocchioTree
from .pose import default_times, evaluate_pose
from .poses import evaluate_poses
from .snapshot import Snapshot, snapshot
from .velocity import Velocity, evaluate_velocity
from .weld_process import WeldProcess, evaluate_weld_process, welding_positions

__all__ = [
    "Clearance",
    "FrameJacobian",
    "IkSolutions",
    "JointSolution",
    "PinocchioTree",
    "Snapshot",
    "TreeDescription",
    "Velocity",
    "WeldProcess",
    "clearance_times",
    "default_times",
    "evaluate_clearance",
    "evaluate_ik_solutions",
    "evaluate_jacobian",
    "evaluate_pose",
    "evaluate_poses",
    "evaluate_solve_joints",
    "evaluate_velocity",
    "evaluate_weld_process",
    "paths_to_common_ancestor",
    "snapshot",
    "welding_positions",
]
