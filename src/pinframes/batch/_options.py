"""What a batch computes for every run, checked once, and its digest for resuming."""

from __future__ import annotations

import hashlib
import json
from dataclasses import dataclass
from typing import Any

import numpy as np

from .. import __version__
from ..errors import ArgumentTypeError, InvalidTimeError
from ..values.timeconv import TimeAxis, parse_time_axis, parse_timedelta, parse_timestamp

__all__ = ["DEFAULT_CHUNK_SIZE", "OUTPUT_VERSION", "BatchOptions"]

DEFAULT_CHUNK_SIZE = 100_000
"""Samples evaluated and written (as one Parquet row group) at a time: about 10 MB."""

OUTPUT_VERSION = 2
"""The layout of the output rows; a change recomputes every run (2: velocity columns)."""


@dataclass(frozen=True)
class BatchOptions:
    """The query made on every run.

    Attributes
    ----------
    frame, relative_to : str, str or None
        The pose of ``frame`` in ``relative_to`` (default: ``frame``'s parent).
    times : TimeAxis or None
        The same times for every run; None: each run's own samples on the path.
    step_ns : int or None
        Resample each run's samples on a grid of this step (nanoseconds), from its first
        sample to its last; only without ``times``.
    time_ref : numpy.datetime64 or None
        Reference time that relative ``times`` count from.
    chunk_size : int
        Samples per evaluation and per Parquet row group; does not change the results.
    velocity : bool
        Also the velocity of ``frame`` relative to ``relative_to``, in its axes.
    xacro : bool
        Expand the xacro content of the runs' robot files and scene robots (which runs
        their code); by default none is expanded and such a run is an error naming it.
    """

    frame: str
    relative_to: str | None
    times: TimeAxis | None
    step_ns: int | None
    time_ref: np.datetime64 | None
    chunk_size: int
    velocity: bool = False
    xacro: bool = False

    @classmethod
    def create(cls, frame: str, relative_to: str | None = None, times: Any = None,
               step: Any = None, time_ref: Any = None,
               chunk_size: int = DEFAULT_CHUNK_SIZE, velocity: bool = False,
               xacro: bool = False) -> BatchOptions:
        """Options from user input (times as pinframes reads them: seconds, durations,
        timestamps); a :class:`~pinframes.errors.PinframesError` names the bad field."""
        if not isinstance(frame, str) or (relative_to is not None
                                          and not isinstance(relative_to, str)):
            raise ArgumentTypeError("frame names are strings", field="frame")
        if times is not None and step is not None:
            raise InvalidTimeError("give either times or step, not both", field="step")
        if time_ref is not None and times is None:
            raise InvalidTimeError("time_ref is for explicit times; each run's own samples "
                                   "keep their reference time", field="time_ref")
        step_ns = None
        if step is not None:
            step_ns = int(parse_timedelta(step, field="step").astype(np.int64))
            if step_ns <= 0:
                raise InvalidTimeError(f"must be a positive duration, got {step!r}",
                                       field="step")
        if isinstance(chunk_size, bool) or not isinstance(chunk_size, int) or chunk_size < 1:
            raise ArgumentTypeError(f"must be a positive integer, got {chunk_size!r}",
                                    field="chunk_size")
        for name, flag in (("velocity", velocity), ("xacro", xacro)):
            if not isinstance(flag, bool):
                raise ArgumentTypeError(f"must be True or False, got {flag!r}", field=name)
        return cls(frame, relative_to,
                   None if times is None else parse_time_axis(times, field="times"), step_ns,
                   None if time_ref is None else parse_timestamp(time_ref, field="time_ref"),
                   chunk_size, velocity, xacro)

    def digest(self) -> str:
        """SHA-256 (hex) of everything that changes the output rows, pinframes' version too."""
        times = None if self.times is None else {
            "offsets_ns": self.times.offsets.tolist(),
            "reference": None if self.times.reference is None else str(self.times.reference)}
        described = {"output_version": OUTPUT_VERSION, "pinframes": __version__,
                     "frame": self.frame, "relative_to": self.relative_to, "times": times,
                     "step_ns": self.step_ns, "velocity": self.velocity,
                     "time_ref": None if self.time_ref is None else str(self.time_ref)}
        if self.xacro:  # only when asked: the digests of earlier batches stay valid
            described["xacro"] = True
        return hashlib.sha256(json.dumps(described, sort_keys=True).encode()).hexdigest()
