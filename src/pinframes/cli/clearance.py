"""``pinframes clearance FILE A B``: the smallest distance between two sets of links per time."""

from __future__ import annotations

import argparse
import dataclasses
import sys
from pathlib import Path
from typing import Any

import numpy as np

from ..formats.limits import current_limits
from ..formats.tables import CLEARANCE_FILE_FORMATS, clearance_text
from ..kinematics import Clearance
from ..tree import FrameTree
from ..values.geometry import GEOMETRY_KINDS
from ..values.timeconv import TimeAxis
from ._evaluate import add_time_arguments, in_chunks, terminal_stderr, times_from_options
from ._extrapolation import add_extrapolation_argument, check_query_extrapolation
from ._files import read_tree
from ._output import write_text
from ._subcommand import Subparsers, subcommand_parser

__all__ = ["add_parser", "clearance_summary", "frame_names", "run"]

CLEARANCE_CHUNK_SIZE = 2_000
"""Samples a clearance takes per call; the progress bar moves once per chunk (a sample
costs 0.05-1 ms)."""


def add_parser(subparsers: Subparsers, parents: list[argparse.ArgumentParser]) -> None:
    """Register the ``clearance`` subcommand."""
    parser = subcommand_parser(
        subparsers, parents, "clearance", run,
        help="smallest distance between the geometry of two sets of links, per time",
        description="The smallest distance between the URDF collision geometry of the links "
        "A and those B at every time (coal, as Pinocchio's computeDistances), the pair "
        "of links it is between and their closest points. One summary line goes to "
        "standard error (smallest distance, the pair, when; the first contact or 'no "
        "contact'), the table to standard output or -o: columns time_s, distance_m "
        "(negative: overlap), frame_a, frame_b, point_a_x_m .. point_b_z_m (metres in the "
        "root's axes).")
    for name, side in (("a", "one side"), ("b", "the other side")):
        parser.add_argument(name, metavar=name.upper(),
                            help=f"{side}: a frame, a glob pattern over frames ('robot/*'), "
                            "or several of them separated by commas")
    parser.add_argument("--exclude", nargs=2, action="append", default=[],
                        metavar=("A", "B"), help="do not check the pairs of these frames or "
                        "patterns, either order (repeatable; default: none)")
    parser.add_argument("--no-srdf-exclude", dest="srdf_exclude", action="store_false",
                        help="check the link pairs the robots' SRDFs disable too (default: "
                        "leave them out)")
    parser.add_argument("--geometry", choices=GEOMETRY_KINDS, default="collision",
                        help="which URDF geometry of the links (default: collision)")
    add_time_arguments(parser)
    add_extrapolation_argument(parser)
    parser.add_argument("--format", "-f", choices=CLEARANCE_FILE_FORMATS,
                        help="table format (default: from the -o file name, else csv)")
    parser.add_argument("-o", "--output", metavar="OUT",
                        help="write the table to this file (default: standard output)")


def run(args: argparse.Namespace) -> int:
    """Evaluate, print the summary and write the table."""
    tree = read_tree(args.file, args)
    a, b = frame_names(tree, args.a), frame_names(tree, args.b)
    options = {"geometry": args.geometry, "package_dirs": args.package_dir or [],
               "exclude": [tuple(pair) for pair in args.exclude],
               "srdf_exclude": args.srdf_exclude,
               "limits": current_limits()}  # --max-triangles (main() sets the limits)
    times = times_from_options(args, lambda: tree.clearance_times(a, b,
                                                                  geometry=args.geometry))
    check_query_extrapolation(
        args, lambda values, reference: tree.clearance(a, b, times=values, time_ref=reference,
                                                       extrapolation="error", **options),
        lambda: tree.clearance_times(a, b, geometry=args.geometry), times, args.time_ref)
    result = _in_chunks(tree, a, b, times, args.time_ref, options)
    print(f"pinframes: {clearance_summary(result)}", file=sys.stderr)
    suffix = Path(args.output).suffix.lstrip(".").lower() if args.output else ""
    fmt = args.format or (suffix if suffix in CLEARANCE_FILE_FORMATS else "csv")
    write_text(clearance_text(result, fmt), args.output)
    return 0


def clearance_summary(result: Clearance, counts: bool = True) -> str:
    """``smallest clearance 12.3 mm between A and B at 4.500 s; first contact at ...``, with
    the numbers of samples and frames when ``counts``."""
    index = result.smallest
    first, second = result.closest[index]
    seconds = result.seconds
    when = "" if seconds is None else f" at {seconds[index]:.3f} s"
    contact = result.first_contact
    touching = "no contact" if contact is None else (
        "in contact" if seconds is None else f"first contact at {contact:.3f} s")
    summary = (f"smallest clearance {1000 * result.distance[index]:.1f} mm between {first} "
               f"and {second}{when}; {touching}")
    if not counts:
        return summary
    fixed = len(result.fixed_together)
    left_out = f", {fixed} pairs fixed to each other left out" if fixed else ""
    return (f"{summary} ({len(result)} samples, {len(result.frames_a)} x "
            f"{len(result.frames_b)} frames{left_out})")


def frame_names(tree: FrameTree, text: str) -> list[str]:
    """The frame named ``text``, else the comma-separated names and patterns in it."""
    return [text] if text in tree else [name.strip() for name in text.split(",")]


def _in_chunks(tree: FrameTree, a: list[str], b: list[str], times: TimeAxis | None,
               time_ref: Any, options: dict[str, Any]) -> Clearance:
    """``tree.clearance`` in chunks of :data:`CLEARANCE_CHUNK_SIZE` samples, with a progress
    bar on a terminal."""
    if times is None:
        times = tree.clearance_times(a, b, geometry=options["geometry"])
        if times is None:
            return tree.clearance(a, b, **options)
        time_ref = times.reference
    parts = in_chunks(lambda values: tree.clearance(a, b, times=values, time_ref=time_ref,
                                                    **options),
                      times, terminal_stderr(), CLEARANCE_CHUNK_SIZE)
    if len(parts) == 1:
        return parts[0]
    def joined(name: str) -> np.ndarray:
        return np.concatenate([getattr(part, name) for part in parts])

    return dataclasses.replace(parts[0], distance=joined("distance"), closest=joined("closest"),
                               point_a=joined("point_a"), point_b=joined("point_b"),
                               times=joined("times"))
