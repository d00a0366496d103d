"""Collision: the smallest distance between the shapes of frames, measured with coal.

:mod:`.clearance` is the query (``FrameTree.clearance``); :mod:`.coal_objects` makes coal
objects of the shapes recorded on frames; :mod:`.mesh_files` finds mesh files named by
``package://`` or relative paths, for the clearance and the 3-D page.
"""

from .clearance import Clearance, clearance_times, evaluate_clearance

__all__ = ["Clearance", "clearance_times", "evaluate_clearance"]
