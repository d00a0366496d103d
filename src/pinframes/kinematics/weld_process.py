"""``FrameTree.weld_process``: the welding process a torch produces along a seam, per sample.

The terms are the welders' own (docs/welding-process.md). The seam frame sits at the weld point: x
along the travel direction, z the work surface's normal pointing out of the material,
y = z x x. The torch frame is the tool centre point; its z axis is the wire axis, from the
torch toward the work. With ``a`` the torch z axis and ``p`` the torch origin, both in seam
axes:

- travel angle = asin(a_x): positive pushing (the wire leans ahead), negative dragging;
- work angle = atan2(-a_z, -a_y): across the seam, from the seam's +y axis to the torch axis
  seen from the work; pi/2 is square to the surface;
- offset = p: along, across and normal to the seam, metres;
- travel speed: the velocity of the torch origin relative to the workpiece, along seam x;
- CTWD: from the contact tip's origin ``c`` (seam axes) along the wire axis to the plane
  through the seam point normal to z, c_z / (-a_z).

None of them changes when the torch turns about its own axis.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import NDArray

from ..errors import InvalidTimeError
from ..values.timed import Timed
from ._description import TreeDescription
from ._plan import plan_query
from .pose import planned_transforms
from .velocity import planned_velocity

__all__ = ["WeldProcess", "evaluate_weld_process"]

FloatArray = NDArray[np.float64]


@dataclass(frozen=True)
class WeldProcess(Timed):
    """The welding process of ``torch`` along ``seam``, per sample (docs/welding-process.md).

    Attributes
    ----------
    travel_speed : ndarray, shape (T,)
        Speed of the torch origin relative to ``workpiece`` along the seam's x axis, m/s
        (negative: backwards).
    travel_angle : ndarray, shape (T,)
        asin(a_x), radians: positive push (the wire leans ahead along the travel direction),
        negative drag.
    work_angle : ndarray, shape (T,)
        atan2(-a_z, -a_y), radians: in the plane across the seam, from the seam's +y axis to
        the torch axis seen from the work; pi/2 is square to the surface.
    offset : ndarray, shape (T, 3)
        The torch origin in seam axes, metres: along, across and normal to the seam.
    ctwd : ndarray, shape (T,), or None
        Contact tip to work distance, metres, when a contact tip frame was given: along the
        wire axis from the contact tip's origin to the plane through the seam point normal
        to the seam's z axis. NaN where the wire does not point toward that plane (a_z >= 0).
    times : ndarray of timedelta64[ns] or None
        Sample times after :attr:`reference_time` (as ``pose()``); None for a static path
        queried without times (then T is 1).
    reference_time : numpy.datetime64 or None
        What :attr:`times` count from.
    torch, seam, workpiece : str
        The frames the process was computed for.
    contact_tip : str or None
        The contact tip frame, if given.
    """

    travel_speed: FloatArray
    travel_angle: FloatArray
    work_angle: FloatArray
    offset: FloatArray
    ctwd: FloatArray | None
    times: NDArray[np.timedelta64] | None
    reference_time: np.datetime64 | None
    torch: str
    seam: str
    workpiece: str
    contact_tip: str | None

    def __len__(self) -> int:
        return int(self.travel_speed.shape[0])


def evaluate_weld_process(tree: TreeDescription, torch: str, seam: str, times: Any,
                          time_ref: Any, extrapolation: str, workpiece: str,
                          contact_tip: str | None) -> WeldProcess:
    """``tree.weld_process(...)``; frame names already checked.

    The times are those of ``pose(torch, relative_to=seam, times, time_ref)``; the velocity
    and the contact tip are evaluated at exactly those times.
    """
    plan = plan_query(tree, torch, seam, times, time_ref, extrapolation)
    # the torch relative to the workpiece, and the contact tip, at the same times
    velocity_plan = plan.on(tree, torch, workpiece)
    tip_plan = None if contact_tip is None else plan.on(tree, contact_tip, torch)
    for same in (velocity_plan, tip_plan):
        # without times a static torch-to-seam path gives one sample: the others must not
        # move then, or the samples would not line up
        if same is not None and plan.times is None and same.path.sources:
            raise InvalidTimeError(
                f"{same.path.frame!r} moves relative to {same.path.relative_to!r} while "
                f"nothing moves between the torch and the seam {seam!r}: give times",
                field="times")
    rotation, origin = planned_transforms(tree, plan)
    # in the torch's own axes (no second pose query), then turned into the seam's by the
    # rotation of the torch in the seam: R_ts R_tw^T = R_sw^T
    velocity = planned_velocity(tree, velocity_plan, torch)
    along_seam = np.einsum("tj,tj->t", rotation[:, 0, :], velocity.linear)
    wire = rotation[:, :, 2]  # the torch z axis in seam axes
    ctwd = None
    if tip_plan is not None:
        tip = np.einsum("tij,tj->ti", rotation, planned_transforms(tree, tip_plan)[1]) + origin
        toward_work = -wire[:, 2]
        with np.errstate(divide="ignore", invalid="ignore"):
            ctwd = np.where(toward_work > 0.0, tip[:, 2] / toward_work, np.nan)
    return WeldProcess(
        travel_speed=along_seam,
        travel_angle=np.arcsin(np.clip(wire[:, 0], -1.0, 1.0)),
        work_angle=np.arctan2(-wire[:, 2], -wire[:, 1]),
        offset=origin,
        ctwd=ctwd,
        times=plan.result_times,
        reference_time=plan.reference_time,
        torch=torch,
        seam=seam,
        workpiece=workpiece,
        contact_tip=contact_tip,
    )
