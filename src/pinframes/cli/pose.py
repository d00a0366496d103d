"""``pinframes pose FILE FRAME --relative-to OTHER``: the pose of a frame per time."""

from __future__ import annotations

import argparse
import sys

from ._evaluate import (
    add_time_arguments,
    pose_in_chunks,
    pose_velocity,
    requested_times,
    terminal_stderr,
)
from ._extrapolation import add_extrapolation_argument, check_extrapolation
from ._files import read_tree, require_frames
from ._output import OUTPUT_FORMATS, output_format, output_poses
from ._subcommand import Subparsers, subcommand_parser

__all__ = ["add_parser", "run"]


def add_parser(subparsers: Subparsers, parents: list[argparse.ArgumentParser]) -> None:
    """Register the ``pose`` subcommand."""
    parser = subcommand_parser(
        subparsers, parents, "pose", run,
        help="poses of a frame relative to another, per time",
        description="Print the pose of FRAME in --relative-to per time: columns time_s, x, "
        "y, z, qx, qy, qz, qw (seconds after the reference time, metres, unit quaternion "
        "x y z w). The pose maps coordinates in FRAME to coordinates in the other frame. "
        "--velocity adds the exact velocity of FRAME's origin and its angular velocity, "
        "relative to the other frame, in its axes (or those of --expressed-in).")
    parser.add_argument("frame", metavar="FRAME", help="the frame whose pose is wanted")
    parser.add_argument("--relative-to", "-r", metavar="OTHER",
                        help="the frame the pose is expressed in (default: FRAME's parent)")
    parser.add_argument("--velocity", action="store_true",
                        help="add the exact velocity of FRAME relative to the other frame: "
                        "columns vx_m_s, vy_m_s, vz_m_s (its origin, m/s) and wx_rad_s, "
                        "wy_rad_s, wz_rad_s (angular, rad/s) (default: off)")
    parser.add_argument("--expressed-in", metavar="AXES",
                        help="the frame whose axes the velocities are written in (default: "
                        "the --relative-to frame; implies --velocity)")
    add_time_arguments(parser)
    add_extrapolation_argument(parser)
    parser.add_argument("--format", "-f", choices=OUTPUT_FORMATS,
                        help="output format (default: from the -o file name, else csv)")
    parser.add_argument("-o", "--output", metavar="OUT",
                        help="write to this file (default: standard output)")


def run(args: argparse.Namespace) -> int:
    """Evaluate and write the poses."""
    fmt = output_format(args.format, args.output)  # a bad name fails before the work
    tree = read_tree(args.file, args)
    require_frames(tree, args.file, args.frame, args.relative_to)
    relative_to = args.relative_to
    if relative_to is None:
        relative_to = tree.parent(args.frame)
    if relative_to is None:
        tree.pose(args.frame)  # raises the error for the root, which has no parent
    times = requested_times(args, tree, args.frame, relative_to)
    check_extrapolation(args, tree, [(args.frame, relative_to)], times, args.time_ref)
    pose = pose_in_chunks(tree, args.frame, relative_to, times, args.time_ref,
                          progress=terminal_stderr())
    velocity = None
    if args.velocity or args.expressed_in is not None:
        require_frames(tree, args.file, args.expressed_in)
        velocity = pose_velocity(tree, pose, args.frame, relative_to, args.expressed_in)
    output_poses(pose, fmt, args.output, frame=args.frame, relative_to=relative_to,
                velocity=velocity)
    if pose.reference_time is not None and fmt == "csv":
        print(f"pinframes: time_s counts from {pose.reference_time}", file=sys.stderr)
    return 0
