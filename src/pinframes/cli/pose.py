"""``pinframes pose FILE FRAME --relative-to OTHER``: the pose of a frame per time."""

from __future__ import annotations

import argparse
import sys

from ._evaluate import add_time_arguments, evaluate_poses, requested_times, terminal_stderr
from ._files import read_tree, require_frames
from ._output import OUTPUT_FORMATS, output_format, write_poses

__all__ = ["add_parser", "run"]


def add_parser(subparsers: argparse._SubParsersAction, parents: list) -> None:
    """Register the ``pose`` subcommand."""
    parser = subparsers.add_parser(
        "pose", parents=parents, help="poses of a frame relative to another, per time",
        description="Print the pose of FRAME in --relative-to per time: columns time_s, x, "
        "y, z, qx, qy, qz, qw (seconds after the reference time, metres, unit quaternion "
        "x y z w). The pose maps coordinates in FRAME to coordinates in the other frame.")
    parser.add_argument("file", metavar="FILE", help="scene, frames.yaml, ASDF or URDF file")
    parser.add_argument("frame", metavar="FRAME", help="the frame whose pose is wanted")
    parser.add_argument("--relative-to", "-r", metavar="OTHER",
                        help="the frame the pose is expressed in (default: FRAME's parent)")
    add_time_arguments(parser)
    parser.add_argument("--format", "-f", choices=OUTPUT_FORMATS,
                        help="output format (default: from the -o file name, else csv)")
    parser.add_argument("-o", "--output", metavar="OUT",
                        help="write to this file (default: standard output)")
    parser.set_defaults(run=run)


def run(args: argparse.Namespace) -> int:
    """Evaluate and write the poses."""
    tree = read_tree(args.file)
    require_frames(tree, args.file, args.frame, args.relative_to)
    relative_to = args.relative_to
    if relative_to is None:
        relative_to = tree.parent(args.frame)
    if relative_to is None:
        tree.pose(args.frame)  # raises the error for the root, which has no parent
    times = requested_times(args, tree, args.frame, relative_to)
    pose = evaluate_poses(tree, args.frame, relative_to, times, args.time_ref,
                          progress=terminal_stderr())
    fmt = output_format(args.format, args.output)
    write_poses(pose, fmt, args.output, frame=args.frame, relative_to=relative_to)
    if pose.reference_time is not None and fmt == "csv":
        print(f"pinframes: time_s counts from {pose.reference_time}", file=sys.stderr)
    return 0
