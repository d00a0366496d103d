"""The frame names of a batch, checked on one run before any worker starts.

A mistyped ``--frame`` would otherwise start the cluster and fail in every run; the first
run that reads (of the first :data:`RUNS_TRIED`) tells at once, with near names.
"""

from __future__ import annotations

import warnings

from ..errors import FrameNotFoundError, near_misses
from ..formats.limits import Limits, using_limits
from ._inputs import read_run, run_inputs
from ._options import BatchOptions
from ._runs import Run

__all__ = ["RUNS_TRIED", "check_frame_names"]

RUNS_TRIED = 3
"""Runs read in turn until one reads; when none does, their workers say why."""


def check_frame_names(runs: list[Run], options: BatchOptions, limits: Limits) -> None:
    """Refuse ``options.frame`` or ``options.relative_to`` when the first run that reads
    has no frame of that name (a :class:`FrameNotFoundError` naming the run's file, the
    frame, the field and near names)."""
    for run in runs[:RUNS_TRIED]:
        try:  # its warnings come from its worker, once
            with using_limits(limits), warnings.catch_warnings():
                warnings.simplefilter("ignore")
                tree = read_run(run_inputs(run.path), limits, options.xacro)
        except Exception:  # a bad run: its own record will say what is wrong
            continue
        for field, name in (("frame", options.frame), ("relative_to", options.relative_to)):
            if name is not None and name not in tree:
                raise FrameNotFoundError(
                    f"run {run.run_id!r} has no frame of this name, so no run is started"
                    + near_misses(name, tree.frames), file=run.path, frame=name, field=field)
        return
