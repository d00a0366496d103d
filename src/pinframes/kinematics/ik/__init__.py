"""Inverse kinematics: joint values that put a tool frame on a target frame along a path.

:mod:`.solve_joints` is the query (``FrameTree.solve_joints``) and :mod:`.joint_solution` its
result. Its steps: the solved joints (``_solved_joints``), where the solve starts
(``_starts``), the tracker it picks (``_trackers``: the numeric solver, or a closed form, its
jumps bridged by ``_jump_bridge``) on times made dense enough (``_between_samples``), the
numeric solve chunk by chunk (``_path_chunks``), the solver loop sample by sample
(``_newton_tracking``) with where each sample starts (``_tracking_history``), the tool's
error (``_tool_error``), the step within limits (``_bounded_step``), the secondary objectives
(``_null_space``, ``_flat``), a sample lost on a limit sought along the self-motion
(``_self_motion_escape``), and the batched check of its samples (``_batch_check``). The
planning and sampling it shares with the other queries are the ``_`` modules of
:mod:`pinframes.kinematics`. A 6-axis arm of a closed-form family
(:mod:`pinframes.kinematics.closed_form`) is solved in closed form (``_closed_form_arm``);
:mod:`.ik_solutions` gives all its solutions.
"""

from .ik_solutions import evaluate_ik_solutions
from .joint_solution import JointSolution
from .solve_joints import evaluate_solve_joints

__all__ = ["JointSolution", "evaluate_ik_solutions", "evaluate_solve_joints"]
