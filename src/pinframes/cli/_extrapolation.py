"""``--extrapolation {clamp,error}``: what a command does with times outside the samples of
a moving frame or joint on its path. Before the work, the first and last of the command's
times are asked of each path with ``extrapolation="error"`` (two samples, cheap): under
``error`` that error stops the command, under ``clamp`` (the default) it becomes one warning
and the held poses are computed as before."""

from __future__ import annotations

import argparse
from collections.abc import Sequence
from typing import Any

import numpy as np

from ..errors import ExtrapolationError, ExtrapolationWarning, warn_at_caller
from ..tree import FrameTree
from ..values.timeconv import TimeAxis

__all__ = ["add_extrapolation_argument", "check_extrapolation"]

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
    """Check the command's ``times`` (None: each path's own samples) on each
    ``(frame, relative_to)`` path against ``args.extrapolation``: an
    :class:`~pinframes.errors.ExtrapolationError` under ``error``, one
    :class:`~pinframes.errors.ExtrapolationWarning` under ``clamp``."""
    for frame, relative_to in paths:
        axis, reference = times, time_ref
        if axis is None:
            axis = tree.sample_times(frame, relative_to)
            reference = None if axis is None else axis.reference
        if axis is None or not axis.offsets.shape[0]:
            continue
        ends = TimeAxis(axis.offsets[[int(np.argmin(axis.offsets)),
                                      int(np.argmax(axis.offsets))]], axis.reference)
        try:
            tree.pose(frame, relative_to, ends.as_numpy(), reference, extrapolation="error")
        except ExtrapolationError as exc:
            if args.extrapolation == "error":
                raise
            warn_at_caller(f"times outside the samples of {exc.frame!r}: "
                           f"{exc.message.removesuffix(_ERROR_SUFFIX)}; it holds its first or "
                           "last value there (--extrapolation error refuses such times)",
                           ExtrapolationWarning)
            return
