"""The welding process in ``pinframes demo``: its ranges in the summary, its curves in the PNG."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np

from ..kinematics import WeldProcess
from ..tree import FrameTree
from ._files import require_frames
from .process import process_summary

__all__ = ["DEFAULT_SEAM", "demo_process", "plot_process", "process_table"]

DEFAULT_SEAM = "seam_point"
"""The seam frame the demo follows when the scene has it (the bundled cell does)."""


def demo_process(tree: FrameTree, scene: Path, tool: str, workpiece: str,
                 seam: str | None) -> WeldProcess | None:
    """The process of ``tool`` along ``seam`` (default :data:`DEFAULT_SEAM` when the scene
    has it, else none) relative to ``workpiece``."""
    if seam is None:
        if DEFAULT_SEAM not in tree:
            return None
        seam = DEFAULT_SEAM
    require_frames(tree, scene, seam)
    return tree.weld_process(tool, seam, workpiece=workpiece)


def process_table(process: WeldProcess, width: int) -> str:
    """The ranges of the process and the welding positions met, as rows of the demo's
    two-column summary."""
    return "".join(f"{name.ljust(width)}  {span}\n" for name, span in process_summary(process))


def plot_process(figure: Any, speed_axes: Any, angle_slot: Any, offset_slot: Any,
                 process: WeldProcess) -> None:
    """Travel speed on ``speed_axes`` beside what is there; travel and work angle, and the
    torch offset from the seam, on new axes in the two grid slots."""
    seconds = process.seconds
    if seconds is None:
        seconds = np.zeros(1)
    speed_axes.plot(seconds, 1000 * process.travel_speed, color="tab:green", linestyle=":",
                    linewidth=2.0, label=f"travel speed along {process.seam}")
    speed_axes.legend(loc="lower right")
    angles = figure.add_subplot(angle_slot, sharex=speed_axes)
    angles.plot(seconds, np.degrees(process.travel_angle), label="travel angle (+ push)")
    angles.plot(seconds, np.degrees(process.work_angle), label="work angle")
    angles.set_ylabel("angle [deg]")
    angles.set_title(f"torch angles in the {process.seam} frame")
    angles.legend(loc="center right")
    offsets = figure.add_subplot(offset_slot, sharex=speed_axes)
    for column, name in enumerate(("along", "across", "normal")):
        offsets.plot(seconds, 1000 * process.offset[:, column], label=name)
    low, high = offsets.get_ylim()
    if high - low < 1.0:  # a torch on the seam: show noise of micrometres as the flat line it is
        middle = (low + high) / 2
        offsets.set_ylim(middle - 0.5, middle + 0.5)
    offsets.set_xlabel("time [s]")
    offsets.set_ylabel("offset [mm]")
    offsets.set_title(f"{process.torch} origin relative to {process.seam}")
    offsets.legend(loc="upper right")
