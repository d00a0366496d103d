"""The path solvers behind one interface: a :class:`Tracker` solves a request
(:class:`._path_chunks.PathToSolve`) on its plan's times from a start, and gives each
sample's solution and, with process windows, its tilts.

``solve_joints`` picks the tracker once: the numeric solver (:data:`NEWTON`, Newton sample
by sample in chunks, :mod:`._path_chunks`) or an arm's closed form (:class:`ClosedForm`),
and has its jumps bridged (:class:`JumpsBridged`, :mod:`._jump_bridge`). The densification
(:mod:`._between_samples`) and the process windows (:mod:`._windows_where_needed`) solve
through the tracker they are given, whichever it is.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Protocol

import numpy as np
from numpy.typing import NDArray

from ..closed_form.arm_shapes import ArmShape
from ._closed_form_arm import solve_in_closed_form
from ._jump_bridge import bridged_jumps
from ._newton_tracking import Tracked
from ._path_chunks import PathToSolve, track_in_chunks
from .joint_jumps import jumps_of

__all__ = ["NEWTON", "ClosedForm", "JumpsBridged", "Tracker"]

FloatArray = NDArray[np.float64]


class Tracker(Protocol):
    """How a request is solved on its plan's times."""

    def __call__(self, request: PathToSolve, start: FloatArray, search_starts: bool,
                 strict: bool, frame: str) -> tuple[Tracked, FloatArray | None]:
        """The solutions of every sample of ``request`` from ``start`` (the first sample's;
        with ``search_starts``, the default of its several starts) and, with a
        :class:`~._tool_error.WindowMatch`, the tilts (T, 2) in radians (else None); with
        ``strict``, :class:`~pinframes.errors.TargetNotReachedError` naming ``frame`` at the
        first sample not reached."""
        ...


NEWTON: Tracker = track_in_chunks
"""The numeric solver: Newton sample after sample, chunk by chunk."""


@dataclass(frozen=True)
class ClosedForm:
    """A :class:`Tracker` on one branch of ``arm``'s closed form: ``branch`` the requested
    configuration (as :func:`..closed_form.configurations.requested_branch` gives it), or
    None, and then where that branch misses a sample or jumps (``jump_factor``, as
    :func:`.joint_jumps.jumps_of` takes it: through a wrist singularity the closed form
    splits a turn between wrists 1 and 3 its own way) the numeric solver instead."""

    arm: ArmShape
    branch: tuple[str, int] | None
    jump_factor: float

    def __call__(self, request: PathToSolve, start: FloatArray, search_starts: bool,
                 strict: bool, frame: str) -> tuple[Tracked, FloatArray | None]:
        with np.errstate(over="ignore", invalid="ignore"):  # a target out of all reach
            solved = solve_in_closed_form(request, self.arm, start, self.branch, strict, frame)
        if solved is not None and (
                self.branch is not None
                or not jumps_of(solved[0].positions, self.jump_factor).shape[0]):
            return solved[0], None
        return NEWTON(request, start, search_starts, strict, frame)


@dataclass(frozen=True)
class JumpsBridged:
    """A :class:`Tracker`: ``tracker``'s solutions with their jumps (``jump_factor``, as
    :func:`.joint_jumps.jumps_of` takes it) bridged where a bridge holds."""

    tracker: Tracker
    jump_factor: float

    def __call__(self, request: PathToSolve, start: FloatArray, search_starts: bool,
                 strict: bool, frame: str) -> tuple[Tracked, FloatArray | None]:
        tracked, tilts = self.tracker(request, start, search_starts, strict, frame)
        return self.bridged(request, tracked, frame), tilts

    def bridged(self, request: PathToSolve, tracked: Tracked, frame: str) -> Tracked:
        """``tracked`` (the solutions of ``request``'s samples, however solved) with its
        jumps bridged; changed in place."""
        return bridged_jumps(request, tracked, self.jump_factor, frame)
