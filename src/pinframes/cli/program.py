"""``pinframes program SCENE -o run.mcap``: plan a scene's ``program:`` section, print its
summary and write the motion (``WeldProgram.plan``, ``write_joint_trajectory``)."""

from __future__ import annotations

import argparse
import sys

from ..formats.joint_trajectory_writer import write_joint_trajectory
from ..formats.scene.program_section import scene_program
from ._files import read_tree
from ._program_summary import motion_summary

__all__ = ["add_parser", "run"]


def add_parser(subparsers: argparse._SubParsersAction, parents: list) -> None:
    """Register the ``program`` subcommand."""
    parser = subparsers.add_parser(
        "program", parents=parents, help="plan a scene's program and write its motion",
        description="Plan the moves of a scene's 'program:' section (docs/programs.md): "
        "each timed within the joints' velocity and acceleration limits, one joint "
        "trajectory at a fixed step. Prints a summary on standard output (each move, the "
        "cycle time, the slowest and fastest moves, the collisions) and writes the motion. "
        "A move that names a frame, joint or state the scene does not have is an error "
        "naming the move (exit status 1).")
    parser.add_argument("file", metavar="SCENE", help="a scene file with a program section")
    parser.add_argument("-o", "--output", required=True, metavar="OUT",
                        help="write the motion here: .csv or .npz (a joint trajectory a scene "
                        "robot reads; the NPZ with velocities and accelerations), or a ROS "
                        "bag (.mcap, .bag, .db3, or a folder): a trajectory_msgs/"
                        "JointTrajectory with velocities and accelerations, and the joint "
                        "states")
    parser.add_argument("--check", nargs=2, metavar=("A", "B"),
                        help="measure the clearance between the shapes of frames A and B "
                        "(names or patterns such as 'robot/*') along the whole motion, "
                        "between samples too (default: the program section's check, else "
                        "none)")
    parser.add_argument("--margin", type=float, metavar="M",
                        help="with --check: report moves closer than this, metres "
                        "(default: 0, touching)")
    parser.add_argument("--step", type=float, metavar="S",
                        help="the motion's sample step, seconds (default: the program "
                        "section's step, else 0.004)")
    parser.add_argument("--strict", action="store_true",
                        help="fail at the first target out of reach, limit broken or "
                        "collision (default: report them in the summary)")
    parser.set_defaults(run=run)


def run(args: argparse.Namespace) -> int:
    """Plan, print the summary, write the motion."""
    tree = read_tree(args.file, args)
    program = scene_program(tree, args.file)
    check = None
    if args.check is not None:
        check = {"a": args.check[0], "b": args.check[1], "margin": args.margin or 0.0}
    motion = program.plan(step=args.step, check=check, strict=args.strict)
    write_joint_trajectory(motion, args.output, tree=tree)
    sys.stdout.write(motion_summary(motion, args.step or program.step))
    print(f"pinframes: wrote {args.output}", file=sys.stderr)
    return 0
