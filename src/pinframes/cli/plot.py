"""``pinframes plot FILE -o out.png``: frames with their axes and the paths of moving ones."""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

from ..plotting import figure_format, new_figure, plot_frames, save_figure
from ._files import read_tree, require_frames
from ._subcommand import Subparsers, subcommand_parser

__all__ = ["add_parser", "run"]


def add_parser(subparsers: Subparsers, parents: list[argparse.ArgumentParser]) -> None:
    """Register the ``plot`` subcommand."""
    parser = subcommand_parser(
        subparsers, parents, "plot", run,
        help="3-D plot of the frames (PNG, JPEG, SVG, PDF...)",
        description="Draw the frames of FILE in 3-D: each frame's x, y, z axes (red, green, "
        "blue) at the first time, and the path of every frame that moves relative to "
        "--relative-to. Needs matplotlib: pip install \"pinframes[plot]\".")
    parser.add_argument("--frames", nargs="+", metavar="FRAME",
                        help="frames to draw (default: all)")
    parser.add_argument("--relative-to", "-r", metavar="FRAME",
                        help="frame the plot is drawn in (default: the root)")
    parser.add_argument("--at", choices=("start", "end"), default="start",
                        help="draw the axes at the start or the end of the motion (default: "
                        "start)")
    parser.add_argument("-o", "--output", metavar="OUT", required=True,
                        help="image file to write, in the format its suffix names (.png, .jpg, "
                        ".svg, .pdf, ...)")


def run(args: argparse.Namespace) -> int:
    """Draw and save."""
    figure = new_figure()
    figure_format(figure, args.output)  # a bad suffix fails before the work
    tree = read_tree(args.file, args)
    require_frames(tree, args.file, args.relative_to, *(args.frames or []))
    ax = figure.add_subplot(projection="3d")
    plot_frames(tree, args.frames, args.relative_to, ax=ax,
                time_index=0 if args.at == "start" else -1)
    source = Path(args.file)
    ax.set_title(f"{tree.name or source.parent.name + '/' + source.name}: frames in "
                 f"{args.relative_to or tree.root} "
                 f"(axes at the {args.at})")
    save_figure(figure, args.output)
    print(f"pinframes: wrote {args.output}", file=sys.stderr)
    return 0
