"""``pinframes solve SCENE --frame F --target T``: the joint values that put a tool on a
target frame at each time (``FrameTree.solve_joints``), as a joint trajectory CSV."""

from __future__ import annotations

import argparse
import sys
import warnings
from typing import Any

import numpy as np

from ..errors import JointError, JointWithoutSamplesWarning, joint_not_found
from ..formats.joint_trajectory import joint_trajectory_csv
from ..formats.joint_trajectory_writer import write_joint_trajectory
from ..kinematics import JointSolution
from ..kinematics.ik.joint_speeds import speed_unit
from ..tree import FrameTree
from ._evaluate import add_time_arguments, requested_times
from ._extrapolation import add_extrapolation_argument, check_extrapolation
from ._files import read_tree, require_frames
from ._output import write_text
from ._subcommand import Subparsers, subcommand_parser

__all__ = ["add_parser", "run", "summary"]


def add_parser(subparsers: Subparsers, parents: list[argparse.ArgumentParser]) -> None:
    """Register the ``solve`` subcommand."""
    parser = subcommand_parser(
        subparsers, parents, "solve", run,
        help="joint values that put a tool frame on a target frame",
        description="Solve for the robot joints that put --frame (a tool) on --target (a frame "
        "of the tree, which may move) at each time, each sample starting from the one before, "
        "within the URDF position limits. Writes a joint trajectory CSV (time_s, then one "
        "column per joint, radians or metres) that a scene robot's 'trajectory' and "
        "pinframes.read_joint_trajectory read: when the joints belong to one robot, columns "
        "carry its URDF joint names (without the scene's prefix). Prints one summary line on "
        "standard error. Exit status 0 even when samples are out of reach (the summary says "
        "how many were reached); with --strict, 1 at the first one.", tree_file="SCENE")
    parser.add_argument("--frame", required=True, metavar="F",
                        help="the tool frame, e.g. torch_tcp")
    parser.add_argument("--target", required=True, metavar="T",
                        help="the frame the tool must coincide with at each time")
    parser.add_argument("--free-axis", choices=("x", "y", "z"),
                        help="an axis of the tool about which its rotation is free (a welding "
                        "torch: z); only the position and that axis must match (default: the "
                        "whole pose)")
    parser.add_argument("--joints", nargs="+", metavar="J",
                        help="the joints to solve for, as the tree names them, or one joint "
                        "group of a robot's SRDF (default: every robot joint between the tool "
                        "and the lowest common ancestor of the two frames); may name a "
                        "positioner's joints to solve both together; it replaces the default "
                        "set (see --add-joints)")
    parser.add_argument("--add-joints", nargs="+", metavar="J",
                        help="joints solved for beside the default set (or beside --joints): "
                        "a positioner's joints added to the robot's (default: none)")
    parser.add_argument("--flat", metavar="FRAME",
                        help="a frame the solved joints move (a seam on a positioner solved "
                        "with the robot): with the tool on its target, the joints left over "
                        "turn its z up as far as they can (flat welding, PA; default: no "
                        "such wish, the smallest motion)")
    parser.add_argument("--up", nargs=3, type=float, metavar=("X", "Y", "Z"),
                        help="the direction --flat turns its frame's z toward, in the root's "
                        "axes (default: 0 0 1)")
    parser.add_argument("--tilt", nargs=2, type=float, metavar=("ABOUT_X", "ABOUT_Y"),
                        help="process windows in radians, as --orientation-tolerance: the "
                        "tool's z may tilt from the target's by up to ABOUT_X about the "
                        "target's x and ABOUT_Y about its y; the summary gives the largest "
                        "tilt used (default: none, the target's z exactly)")
    parser.add_argument("--configuration", metavar="FLAGS",
                        help="for a 6-axis OPW or UR-type arm: the branch the whole path keeps, "
                             "as flags (front,up,noflip) or a KUKA Status 0..7 "
                             "(docs/closed-form-ik.md); default: the branch nearest the seed "
                             "or start")
    parser.add_argument("--position-tolerance", type=float, default=1e-6, metavar="M",
                        help="metres (default: 1e-6)")
    parser.add_argument("--orientation-tolerance", type=float, default=1e-6, metavar="RAD",
                        help="radians (default: 1e-6)")
    parser.add_argument("--path-tolerance", nargs=2, type=float, metavar=("M", "RAD"),
                        help="without --times/--step: how far the tool may stray from its "
                        "target between two samples while the joints move linearly from the "
                        "one to the other, metres and radians; samples are added where it "
                        "strays further (default: 1e-4 0.001745, 0.1 mm and 0.1 degree)")
    parser.add_argument("--jump-threshold", type=float, metavar="FACTOR",
                        help="a sample whose largest joint change from the one before is "
                        "more than FACTOR times the path's median step (and 0.1 rad or m) "
                        "is a jump: the summary counts them, --strict fails at the first "
                        "(default: 10)")
    parser.add_argument("--flat-tolerance", type=float, metavar="RAD",
                        help="with --flat: radians the frame's z may stray from up where the "
                        "joints could turn it up; a sample beyond it is not reached "
                        "(default: 0.008727, 0.5 degree)")
    parser.add_argument("--seed", nargs="+", metavar="NAME=VALUE", type=_seed_value,
                        help="joint values (radians or metres) the first sample starts from, "
                        "by joint name as 'pinframes info' lists them, e.g. "
                        "robot/joint_3=-0.6; may name some of the joints only (default: "
                        "the joints' trajectories at the first time, else their rest values)")
    parser.add_argument("--strict", action="store_true",
                        help="fail at the first time the target is out of reach or a joint "
                        "moves faster than its URDF velocity limit (default: keep the "
                        "closest configuration there and go on; the summary names the "
                        "fastest joint against its limit)")
    add_time_arguments(parser)
    add_extrapolation_argument(parser)
    parser.add_argument("-o", "--output", metavar="OUT",
                        help="write to this file: .csv, .npz, or a ROS bag (.mcap, .bag, "
                        ".db3, or a folder): a trajectory_msgs/JointTrajectory and the joint "
                        "states (default: CSV on standard output)")


def run(args: argparse.Namespace) -> int:
    """Solve, write the CSV, print the summary."""
    tree = read_tree(args.file, args)
    require_frames(tree, args.file, args.frame, args.target, args.flat)
    with warnings.catch_warnings():
        # the joints being solved have no samples, nor need any: the solve itself warns
        # of every other joint that has none
        warnings.simplefilter("ignore", JointWithoutSamplesWarning)
        times = requested_times(args, tree, args.frame, args.target)
        if args.target != tree.root:  # the target's own motion (the solved joints have none)
            check_extrapolation(args, tree, [(args.target, tree.root)], times, args.time_ref)
    solution = tree.solve_joints(
        args.frame, args.target, times=None if times is None else times.as_numpy(),
        time_ref=args.time_ref, joints=_joints_or_group(tree, args.joints),
        seed=_seed(tree, args.seed), free_axis=args.free_axis, flat=args.flat, up=args.up,
        tilt=args.tilt, add_joints=args.add_joints, position_tolerance=args.position_tolerance,
        orientation_tolerance=args.orientation_tolerance, strict=args.strict,
        configuration=args.configuration, **_path_options(args))
    if args.output is not None:
        write_joint_trajectory(solution, args.output)
    else:  # timestamps when the solution has a reference time, else seconds
        moments: np.ndarray | None = solution.absolute_times
        if moments is None:
            moments = solution.seconds
        assert moments is not None  # a solution has a time per sample
        write_text(joint_trajectory_csv(moments, solution.positions,
                                        solution.urdf_joint_names or solution.joint_names), None)
    print(f"pinframes: {summary(tree, solution)}", file=sys.stderr)
    return 0


def _path_options(args: argparse.Namespace) -> dict[str, Any]:
    """``--path-tolerance``, ``--jump-threshold``, ``--flat-tolerance`` as ``solve_joints``'
    keywords, those given only (the others keep its defaults)."""
    given = {"path_tolerance": None if args.path_tolerance is None else tuple(
        args.path_tolerance), "jump_threshold": args.jump_threshold,
        "flat_tolerance": args.flat_tolerance}
    return {name: value for name, value in given.items() if value is not None}


def _joints_or_group(tree: FrameTree, joints: list[str] | None) -> list[str] | str | None:
    """``--joints``: joint names, or the name of an SRDF group when it is one name that no
    joint has."""
    if joints is not None and len(joints) == 1 and joints[0] not in tree.joints:
        return joints[0]
    return joints


def _seed_value(text: str) -> tuple[str, float]:
    """``NAME=VALUE`` as ``(name, value)``; a usage error when it is not."""
    name, equals, value = text.rpartition("=")
    try:
        number = float(value)
    except ValueError:
        number = None
    if not equals or not name or number is None:
        raise argparse.ArgumentTypeError(f"expected NAME=VALUE (a joint name, a number in "
                                         f"radians or metres), got {text!r}")
    return name, number


def _seed(tree: FrameTree, given: list[tuple[str, float]] | None) -> dict[str, float] | None:
    """The ``--seed`` values by joint name; a joint the tree does not hold, or one given
    twice, is a user error naming it."""
    if given is None:
        return None
    joints = tree.joints
    seed: dict[str, float] = {}
    for name, value in given:
        if name not in joints:
            raise joint_not_found(name, joints, field="--seed")
        if name in seed:
            raise JointError(f"joint {name!r} is given twice", field="--seed")
        seed[name] = value
    return seed


def summary(tree: FrameTree, solution: JointSolution) -> str:
    """One line: samples, reached, the largest errors, how far the joint-interpolated tool
    strays between samples, the jumps, the flat frame's largest angle from up (with --flat), the
    largest tilt (with process windows), the smallest distance
    to a position limit, the fastest joint against its velocity limit."""
    count, reached = len(solution), int(solution.reached.sum())
    line = (f"{count} samples, {reached} reached; largest errors "
            f"{solution.position_error.max():.2g} m, {solution.orientation_error.max():.2g} "
            "rad")
    joints = tree.joints
    margins = []
    for column, name in enumerate(solution.joint_names):
        joint = joints[name]
        values = solution.positions[:, column]
        if joint.kind != "continuous" and joint.lower is not None:
            margins.append((float(np.min(values - joint.lower)), name))
        if joint.kind != "continuous" and joint.upper is not None:
            margins.append((float(np.min(joint.upper - values)), name))
    if solution.path_deviation is not None and count > 1:
        assert solution.path_angle_deviation is not None  # set with path_deviation
        line += (f"; between samples within {solution.path_deviation.max():.2g} m, "
                 f"{solution.path_angle_deviation.max():.2g} rad")
    if solution.jumps is not None and solution.jumps.shape[0]:
        assert solution.seconds is not None  # a solution has a time per sample
        line += (f"; {solution.jumps.shape[0]} jumps (the first at "
                 f"{solution.seconds[solution.jumps[0]]:.6g} s)")
    if solution.flat_error is not None and count:
        line += f"; --flat frame at most {solution.flat_error.max():.2g} rad from up"
    if solution.tilt is not None and count:
        largest = np.abs(solution.tilt).max(axis=0)
        line += f"; largest tilt {largest[0]:.3g} rad about x, {largest[1]:.3g} rad about y"
    if margins:
        margin, name = min(margins)
        unit = "m" if joints[name].kind == "prismatic" else "rad"
        line += f"; closest to a joint limit: {margin:.3g} {unit} ({name})"
    if solution.configurations is not None and count:
        branches = list(dict.fromkeys(solution.configurations.tolist()))
        line += f"; configuration {' then '.join(branches[:3])}" + (
            "..." if len(branches) > 3 else "")
    return line + "; " + _fastest(tree, solution)


def _fastest(tree: FrameTree, solution: JointSolution) -> str:
    """The joint that comes closest to (or goes furthest past) its velocity limit: its
    speed, the limit, the share and the time."""
    if len(solution) < 2:
        return "one sample, so no joint speeds"
    if not np.isfinite(solution.velocity_limits).any():
        return "no joint velocity limits in the URDF"
    ratios = solution.joint_speed_ratios
    index, column = np.unravel_index(int(np.argmax(ratios)), ratios.shape)
    ratio = float(ratios[index, column])
    joint = tree.joints[solution.velocity_limit_joints[column]]
    limit = joint.velocity
    assert limit is not None  # a finite velocity limit came from it
    unit = speed_unit(joint)
    text = (f"fastest joint {joint.name}: {ratio * limit:.3g} of {limit:.3g} {unit} "
            f"({ratio:.0%} of its limit) at "
            f"{int(solution.times[index].astype(np.int64)) / 1e9:.6g} s")
    return text + (": faster than the robot can move" if ratio > 1.0 else "")
