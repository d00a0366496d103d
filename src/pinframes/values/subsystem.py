"""`Subsystem`: a named group of frames that was merged into a larger tree (weldx)."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

__all__ = ["Subsystem"]


@dataclass(frozen=True)
class Subsystem:
    """A hierarchy that was merged into a tree, as weldx records it.

    Attributes
    ----------
    name : str
        The subsystem's own name.
    root : str
        Its root frame (the frame it shares with the tree it was merged into).
    members : tuple of str
        The frames that belong to it, its root included.
    parent : str or None
        The name of the hierarchy (or subsystem) it was merged into.
    reference_time : numpy.datetime64 or None
        Its own reference time.
    subsystems : tuple of str
        Names of the subsystems nested directly inside it.
    data : tuple of str
        Names of the data sets (:meth:`FrameTree.assign_data`) that came with it.
    """

    name: str
    root: str
    members: tuple[str, ...]
    parent: str | None = None
    reference_time: np.datetime64 | None = None
    subsystems: tuple[str, ...] = ()
    data: tuple[str, ...] = ()
