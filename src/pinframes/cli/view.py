"""``pinframes view SCENE -o cell.html``: an animated 3-D page of the tree over time."""

from __future__ import annotations

import argparse
import sys

from ..view import write_view
from ._evaluate import add_time_arguments, requested_times
from ._files import read_tree, require_frames
from ._output import require_suffix
from ._subcommand import Subparsers, subcommand_parser
from .clearance import frame_names

__all__ = ["add_parser", "run"]


def add_parser(subparsers: Subparsers, parents: list[argparse.ArgumentParser]) -> None:
    """Register the ``view`` subcommand."""
    parser = subcommand_parser(
        subparsers, parents, "view", run,
        help="animated 3-D page of the tree (HTML, no server)",
        description="Write one self-contained HTML page that shows FILE in 3-D over time: "
        "the robots' URDF geometry moving with their joint samples, every frame's axes and "
        "name, the paths of moving frames, a time slider with play/pause. It opens from "
        "disk in a browser, without a server or network. Needs meshcat: "
        "pip install \"pinframes[view]\".")
    parser.add_argument("--frames", nargs="+", metavar="FRAME",
                        help="frames drawn with axes and names (default: all)")
    parser.add_argument("--relative-to", "-r", metavar="FRAME",
                        help="frame the scene is drawn in (default: the root)")
    parser.add_argument("--path", nargs=2, action="append", metavar=("FRAME", "IN"),
                        help="draw the path of FRAME in frame IN (repeatable; default: the "
                        "path of each moving frame without children)")
    parser.add_argument("--collision", action="store_true",
                        help="draw the URDF collision geometry instead of the visual one "
                        "(default: off, the visual geometry)")
    parser.add_argument("--clearance", nargs=2, metavar=("A", "B"),
                        help="mark the closest pair between the collision geometry of A and B "
                        "at every time (as pinframes clearance; several names or patterns "
                        "comma-separated): a dot on each closest point, the segment between "
                        "them, the distance beside the time (default: none)")
    parser.add_argument("--exclude", nargs=2, action="append", default=[], metavar=("A", "B"),
                        help="a pair --clearance leaves out, either order (repeatable; "
                        "default: none)")
    add_time_arguments(parser)
    parser.add_argument("-o", "--output", metavar="OUT.html", required=True,
                        help="HTML file to write")


def run(args: argparse.Namespace) -> int:
    """Build and write the page."""
    require_suffix(args.output, (".html", ".htm"), "an HTML page")
    tree = read_tree(args.file, args)
    paths = None if args.path is None else dict(args.path)
    require_frames(tree, args.file, args.relative_to, *(args.frames or []),
                   *(paths or {}), *(paths or {}).values())
    relative_to = args.relative_to or tree.root
    drawn = args.frames or tree.frames
    moving = next((frame for frame in drawn if tree.sample_times(frame, relative_to)), drawn[0])
    times = requested_times(args, tree, moving, relative_to)
    clearance = None if args.clearance is None else (
        frame_names(tree, args.clearance[0]), frame_names(tree, args.clearance[1]))
    size = write_view(tree, args.output, times=times, time_ref=args.time_ref,
                      relative_to=relative_to, frames=args.frames, paths=paths,
                      collision=args.collision, package_dirs=args.package_dir or [],
                      clearance=clearance,
                      clearance_exclude=[tuple(pair) for pair in args.exclude])
    print(f"pinframes: wrote {args.output} ({size / 1e6:.1f} MB)", file=sys.stderr)
    return 0
