"""``pinframes convert IN OUT``: between scene, frames.yaml, ASDF and URDF files, and out to
ROS bags (MCAP, ROS 1, ROS 2)."""

from __future__ import annotations

import argparse
import sys

from ..formats import registered_formats
from ._evaluate import add_time_arguments, times_from_options
from ._files import read_tree, write_tree
from ._subcommand import Subparsers, subcommand_parser

__all__ = ["add_parser", "run"]


def add_parser(subparsers: Subparsers, parents: list[argparse.ArgumentParser]) -> None:
    """Register the ``convert`` subcommand."""
    parser = subcommand_parser(
        subparsers, parents, "convert", run,
        help="convert between scene, frames.yaml, ASDF and URDF; write ROS bags",
        description="Read IN and write its tree to OUT; formats are told by the file names: "
        ".asdf, .urdf, and .yaml, which is a scene (key 'pinframes_scene') or a frames.yaml "
        "(key 'frames', or a name starting with 'frames'). A .yaml to be written is a "
        "frames.yaml when its name starts with 'frames', else a scene. ROS bags: .mcap (one "
        "MCAP file, opens in Foxglove), .bag (ROS 1), .db3, or a name without a suffix (a "
        "ROS 2 bag folder): /tf_static, /tf at the times of the time options, and each "
        "robot's description and joint states. OUT is replaced atomically.", tree_file=None)
    parser.add_argument("input", metavar="IN", help="file to read")
    parser.add_argument("output", metavar="OUT", help="file to write")
    parser.add_argument("--to", choices=registered_formats(),
                        help="format of OUT (default: from its name)")
    parser.add_argument("--schema", choices=("1.0.0", "0.1.0"),
                        help="ASDF schema version: 0.1.0 (what weldx 0.6 to 0.8.2 writes) "
                        "or 1.0.0 (legacy, weldx up to 0.4) (default: 0.1.0)")
    parser.add_argument("--time", metavar="T",
                        help="write every frame at its pose at time T (seconds, duration or "
                        "timestamp); needed where OUT holds one pose per frame (URDF, "
                        "frames.yaml) and anything moves (default: none, motion kept)")
    parser.add_argument("--freeze-joints", action="store_true", default=None,
                        help="URDF: write robot joints as fixed joints at their values at "
                        "--time (default: keep them as joints and write their values to "
                        "OUT's name with .joints.csv)")
    parser.add_argument("--slash-replacement", metavar="TEXT",
                        help="frames.yaml only: write TEXT for each '/' of a frame name that "
                        "would put the frame under another one, e.g. _ (default: none, such "
                        "names are refused)")
    add_time_arguments(parser)


def run(args: argparse.Namespace) -> int:
    """Read, then write."""
    tree = read_tree(args.input, args)
    times = times_from_options(args, tree.time_union)
    write_tree(tree, args.output, args.to, schema=args.schema, time=args.time,
               freeze_joints=args.freeze_joints, slash_replacement=args.slash_replacement,
               times=times, time_ref=args.time_ref)
    print(f"pinframes: wrote {args.output} ({len(tree)} frames)", file=sys.stderr)
    return 0
