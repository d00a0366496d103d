"""``--extrapolation {clamp,error}``: what a command does with times outside the samples of
a moving frame or joint on its path. Before the work, the first and last of the command's
times are asked of its query with ``extrapolation="error"`` (two samples, cheap): under
``error`` that error stops the command, under ``clamp`` (the default) it becomes one warning
and the held poses are computed as before."""

from __future__ import annotations

import argparse
from collections.abc import Callable, Sequence
from typing import Any

import numpy as np

from ..errors import ExtrapolationError, ExtrapolationWarning, warn_at_caller
from ..tree import FrameTree
from ..values.timeconv import TimeAxis

__all__ = ["add_extrapolation_argument", "check_extrapolation", "check_query_extrapolation"]

_ERROR_SUFFIX = " (extrapolation='error')"


def add_extrapolation_argument(parser: argparse.ArgumentParser) -> None:
    """Register ``--extrapolation``."""
    parser.add_argument("--extrapolation", choices=("clamp", "error"), default="clamp",
                        help="at times outside the samples of a moving frame or joint on "
                        "the path: hold its first or last pose and warn once (clamp), or "
                        "stop with an error naming it (error); default: clamp")


def check_extrapolation(args: argparse.Namespace, tree: FrameTree,
                        paths: Sequence[tuple[str, str]], times: TimeAxis | None,
                        time_ref: Any) -> None:
    """:func:`check_query_extrapolation` of the pose of each ``(frame, relative_to)`` path
    at the command's ``times`` (None: the path's own samples)."""
    for frame, relative_to in paths:
        def ask(values: Any, reference: Any, frame: str = frame,
                relative_to: str = relative_to) -> object:
            return tree.pose(frame, relative_to, values, reference, extrapolation="error")

        def own(frame: str = frame, relative_to: str = relative_to) -> TimeAxis | None:
            return tree.sample_times(frame, relative_to)

        if not check_query_extrapolation(args, ask, own, times, time_ref):
            return


def check_query_extrapolation(args: argparse.Namespace, ask: Callable[[Any, Any], object],
                              own_times: Callable[[], TimeAxis | None],
                              times: TimeAxis | None, time_ref: Any) -> bool:
    """Ask ``ask(values, time_ref)`` (the query with ``extrapolation="error"``) at the first
    and last of ``times`` (None: ``own_times()``, the query's own samples): under
    ``--extrapolation error`` its :class:`~pinframes.errors.ExtrapolationError` is raised,
    under ``clamp`` it is one :class:`~pinframes.errors.ExtrapolationWarning`. False once
    it warned."""
    reference = time_ref
    if times is None:
        times = own_times()
        reference = None if times is None else times.reference
    if times is None or not times.offsets.shape[0]:
        return True
    ends = TimeAxis(times.offsets[[int(np.argmin(times.offsets)),
                                   int(np.argmax(times.offsets))]], times.reference)
    try:
        ask(ends.as_numpy(), reference)
    except ExtrapolationError as exc:
        if args.extrapolation == "error":
            raise
        warn_at_caller(f"times outside the samples of {exc.frame!r}: "
                       f"{exc.message.removesuffix(_ERROR_SUFFIX)}; it holds its first or "
                       "last value there (--extrapolation error refuses such times)",
                       ExtrapolationWarning)
        return False
    return True
