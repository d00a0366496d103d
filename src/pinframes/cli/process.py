"""``pinframes process SCENE --torch F --seam S``: the welding process along a seam, per time.

Columns ``time_s, travel_speed_m_s, travel_angle_deg, work_angle_deg, offset_along_m,
offset_across_m, offset_normal_m, slope_deg, rotation_deg, position`` (and ``ctwd_m`` with
``--contact-tip``): degrees, because welders read degrees. One summary line on standard
error gives the range of each and the welding positions met.
"""

from __future__ import annotations

import argparse
import sys

import numpy as np

from ..errors import InvalidDataError
from ..kinematics import WeldProcess
from ..tree import FrameTree
from ..values.timeconv import TimeAxis
from ._evaluate import add_time_arguments, in_chunks, terminal_stderr, times_from_options
from ._extrapolation import add_extrapolation_argument, check_query_extrapolation
from ._files import read_tree, require_frames
from ._output import write_text
from ._subcommand import Subparsers, subcommand_parser

__all__ = ["COLUMNS", "add_parser", "process_summary", "process_text", "run"]

COLUMNS = ("time_s", "travel_speed_m_s", "travel_angle_deg", "work_angle_deg",
           "offset_along_m", "offset_across_m", "offset_normal_m", "slope_deg", "rotation_deg",
           "position")
"""The columns of the output; ``ctwd_m`` follows with a contact tip."""


def add_parser(subparsers: Subparsers, parents: list[argparse.ArgumentParser]) -> None:
    """Register the ``process`` subcommand."""
    parser = subcommand_parser(
        subparsers, parents, "process", run,
        help="welding process along a seam, per time",
        description="Print the welding process that the torch produces along the seam, per "
        "time: travel speed relative to the workpiece (m/s, along the seam's x axis), travel "
        "angle (degrees, positive push, negative drag) and work angle (degrees, 90 = square "
        "to the surface) of the torch's z axis (the wire), the torch origin in seam axes "
        "(along, across, normal, metres) and with --contact-tip the contact tip to work "
        "distance (metres), the seam's slope and face rotation against --up (degrees) and "
        "its ISO 6947 welding position (PA flat .. PG vertical down). The seam frame has x "
        "along the travel direction and z out of the material. One summary line on "
        "standard error gives the range of each and the positions met.", tree_file="SCENE")
    parser.add_argument("--torch", required=True, metavar="FRAME",
                        help="the torch's tool centre point; its z axis is the wire axis")
    parser.add_argument("--seam", required=True, metavar="FRAME",
                        help="the seam frame at the weld point (x travel, z surface normal)")
    parser.add_argument("--workpiece", metavar="FRAME",
                        help="the frame the travel speed is relative to (default: the "
                        "seam's parent)")
    parser.add_argument("--contact-tip", metavar="FRAME",
                        help="the contact tip frame: adds the column ctwd_m (default: none)")
    parser.add_argument("--up", nargs=3, type=float, metavar=("X", "Y", "Z"),
                        help="the upward direction in the root frame's axes, for the slope, "
                        "rotation and position (default: 0 0 1)")
    add_time_arguments(parser)
    add_extrapolation_argument(parser)
    parser.add_argument("-o", "--output", metavar="OUT",
                        help="write the CSV to this file (default: standard output)")


def run(args: argparse.Namespace) -> int:
    """Evaluate, write the CSV, print the summary line."""
    tree = read_tree(args.file, args)
    require_frames(tree, args.file, args.torch, args.seam, args.workpiece, args.contact_tip)
    try:
        process = _evaluate(tree, args)
    except InvalidDataError as exc:
        if exc.field != "up":
            raise
        raise InvalidDataError(exc.message, field="--up") from None
    write_text(process_text(process), args.output)
    ranges = "; ".join(f"{name} {span}" for name, span in process_summary(process))
    print(f"pinframes: {args.torch} along {args.seam}: {len(process)} samples; {ranges}",
          file=sys.stderr)
    if process.reference_time is not None:
        print(f"pinframes: time_s counts from {process.reference_time}", file=sys.stderr)
    return 0


def _evaluate(tree: FrameTree, args: argparse.Namespace) -> WeldProcess:
    """The process at the requested times, in chunks with a progress bar on a terminal;
    without time options, at the process's own samples, in one call."""
    def at(times: object = None, time_ref: object = None,
           extrapolation: str = "clamp") -> WeldProcess:
        return tree.weld_process(args.torch, args.seam, times=times, time_ref=time_ref,
                                 workpiece=args.workpiece, contact_tip=args.contact_tip,
                                 up=args.up, extrapolation=extrapolation)

    def own_times() -> TimeAxis | None:
        process = at()
        if process.times is None:
            return None
        return TimeAxis(process.times.astype(np.int64), process.reference_time)

    times = times_from_options(args, own_times)
    check_query_extrapolation(
        args, lambda values, reference: at(values, reference, "error"), own_times, times,
        args.time_ref)
    if times is None:
        return at()
    time_ref = args.time_ref
    parts = in_chunks(lambda values: at(values, time_ref), times, terminal_stderr())
    return parts[0] if len(parts) == 1 else _joined(parts)


def _joined(parts: list[WeldProcess]) -> WeldProcess:
    """One process from consecutive chunks (all on the same reference time)."""
    first = parts[0]

    def joined(name: str) -> np.ndarray:
        return np.concatenate([getattr(part, name) for part in parts])

    return WeldProcess(
        travel_speed=joined("travel_speed"), travel_angle=joined("travel_angle"),
        work_angle=joined("work_angle"), offset=joined("offset"),
        ctwd=None if first.ctwd is None else joined("ctwd"), slope=joined("slope"),
        rotation=joined("rotation"), position=joined("position"), times=joined("times"),
        reference_time=first.reference_time, torch=first.torch, seam=first.seam,
        workpiece=first.workpiece, contact_tip=first.contact_tip)


def process_text(process: WeldProcess) -> str:
    """The process as CSV text: :data:`COLUMNS` (and ``ctwd_m``); a static process has one
    row with the time ``nan``."""
    seconds = process.seconds if process.seconds is not None else np.array([np.nan])
    numbers = [seconds, process.travel_speed, np.degrees(process.travel_angle),
               np.degrees(process.work_angle), *process.offset.T, np.degrees(process.slope),
               np.degrees(process.rotation)]
    names = list(COLUMNS)
    tail = [process.position.tolist()]
    if process.ctwd is not None:
        tail.append([repr(value) for value in process.ctwd.tolist()])
        names.append("ctwd_m")
    rows = [",".join([*map(repr, row), *cells])
            for row, *cells in zip(np.column_stack(numbers).tolist(), *tail, strict=True)]
    return "\n".join([",".join(names), *rows]) + "\n"


def process_summary(process: WeldProcess) -> list[tuple[str, str]]:
    """``(quantity, "low .. high unit")`` for each quantity of ``process``, in the units
    welders read (mm/s, degrees, mm), then ``("positions", ...)``: the welding positions
    met, in ISO 6947 order, with their numbers of samples."""
    quantities = [("travel speed", 1000 * process.travel_speed, "mm/s", 2),
                  ("travel angle", np.degrees(process.travel_angle), "deg", 2),
                  ("work angle", np.degrees(process.work_angle), "deg", 2),
                  ("offset along", 1000 * process.offset[:, 0], "mm", 3),
                  ("offset across", 1000 * process.offset[:, 1], "mm", 3),
                  ("offset normal", 1000 * process.offset[:, 2], "mm", 3),
                  ("slope", np.degrees(process.slope), "deg", 2),
                  ("rotation", np.degrees(process.rotation), "deg", 2)]
    if process.ctwd is not None:
        quantities.append(("ctwd", 1000 * process.ctwd, "mm", 2))
    summary = []
    for name, values, unit, decimals in quantities:
        if np.isnan(values).all():
            summary.append((name, "none (undefined at every sample)"))
            continue
        # rounded first, then + 0.0: a tiny negative value prints as 0.000, not -0.000
        low, high = (round(float(value), decimals) + 0.0
                     for value in (np.nanmin(values), np.nanmax(values)))
        summary.append((name, f"{low:.{decimals}f} .. {high:.{decimals}f} {unit}"))
    met, counts = np.unique(process.position, return_counts=True)
    summary.append(("positions", ", ".join(
        f"{position} {count} of {len(process)}" for position, count in zip(met, counts,
                                                                           strict=True))))
    return summary
