"""``FrameTree.weld_process``: the welding process a torch produces along a seam, per sample.

The terms are the welders' own; docs/welding-process.md defines each. The seam frame sits
at the weld point: x along the travel direction, z the work surface's normal pointing out
of the material, y = z x x. The torch frame is the tool centre point; its z axis is the
wire axis, from the torch toward the work. With ``a`` the torch z axis, ``p`` the torch
origin and ``u`` the unit upward direction, all in seam axes:

- travel angle = asin(a_x): positive pushing (the wire leans ahead), negative dragging;
- work angle = atan2(-a_z, -a_y): across the seam, from the seam's +y axis to the torch axis
  seen from the work; pi/2 is square to the surface; NaN where the wire lies along x;
- offset = p: along, across and normal to the seam, metres;
- weld point w = p + s a with s = -p_z / a_z: where the wire axis meets the seam's plane;
- travel speed: the velocity of the weld point relative to the workpiece, along seam x;
- CTWD: from the contact tip's origin ``c`` (seam axes) along the wire axis to the seam's
  plane, c_z / (-a_z);
- slope = atan2(u_x, hypot(u_y, u_z)), rotation = atan2(u_y, u_z) and the ISO 6947 welding
  position they give (:func:`welding_positions`).

None of them changes when the torch turns about its own axis.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ..values.numbers import require_finite_pose, unit_direction
from ..values.timed import Timed
from ._description import TreeDescription
from ._plan import QueryPlan, plan_query, prepare_path
from ._sampled_path import sampled_parts
from ._twists import rotate
from .pose import planned_transforms
from .velocity import velocities_in_root

__all__ = ["ALONG_TRAVEL_RAD", "WeldProcess", "evaluate_weld_process", "welding_positions"]

FloatArray = NDArray[np.float64]

ALONG_TRAVEL_RAD = 1e-9
"""A direction closer than this (radians) to the seam's x axis has no angle across the seam:
the work angle of such a wire, the rotation of such an upward direction, are NaN."""

_QUARTER = np.pi / 4
_POSITION_BOUNDS = np.radians([22.5, 67.5, 112.5, 157.5])
_POSITIONS = np.array(["PA", "PB", "PC", "PD", "PE", "PF", "PG"])
"""By the face's turn past each bound (0 to 4), then vertical up (5) and down (6)."""


@dataclass(frozen=True)
class WeldProcess(Timed):
    """The welding process of ``torch`` along ``seam``, per sample (docs/welding-process.md).

    Attributes
    ----------
    travel_speed : ndarray, shape (T,)
        Speed of the weld point (where the wire axis meets the seam's x-y plane) relative to
        ``workpiece`` along the seam's x axis, m/s (negative: backwards); NaN where the wire
        does not point toward that plane.
    travel_angle : ndarray, shape (T,)
        asin(a_x), radians: positive push (the wire leans ahead along the travel direction),
        negative drag.
    work_angle : ndarray, shape (T,)
        atan2(-a_z, -a_y), radians: in the plane across the seam, from the seam's +y axis to
        the torch axis seen from the work; pi/2 is square to the surface. NaN where the wire
        lies along the travel direction (within :data:`ALONG_TRAVEL_RAD`).
    offset : ndarray, shape (T, 3)
        The torch origin in seam axes, metres: along, across and normal to the seam.
    ctwd : ndarray, shape (T,), or None
        Contact tip to work distance, metres, when a contact tip frame was given: along the
        wire axis from the contact tip's origin to the plane through the seam point normal
        to the seam's z axis. NaN where the wire does not point toward that plane (a_z >= 0).
    slope : ndarray, shape (T,)
        Angle of the travel direction above the horizontal, radians, positive uphill:
        atan2(u_x, hypot(u_y, u_z)) with ``u`` the unit upward direction in seam axes.
    rotation : ndarray, shape (T,)
        atan2(u_y, u_z), radians: how far the seam's face (its z axis) is turned from looking
        up, about the travel direction; 0 face up, +-pi face down. NaN where the travel
        direction is vertical (within :data:`ALONG_TRAVEL_RAD`).
    position : ndarray of str, shape (T,)
        The ISO 6947 welding position of each sample, from ``slope`` and ``rotation``
        (:func:`welding_positions`).
    times : ndarray of timedelta64[ns] or None
        Sample times after :attr:`reference_time`; None when, queried without times, nothing
        moves the torch or the seam relative to the workpiece or the seam in the root (then
        T is 1).
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
    slope: FloatArray
    rotation: FloatArray
    position: NDArray[np.str_]
    times: NDArray[np.timedelta64] | None
    reference_time: np.datetime64 | None
    torch: str
    seam: str
    workpiece: str
    contact_tip: str | None

    def __len__(self) -> int:
        return int(self.travel_speed.shape[0])


def welding_positions(slope: ArrayLike, rotation: ArrayLike) -> NDArray[np.str_]:
    """ISO 6947 welding positions from the seam's ``slope`` and face ``rotation`` (radians).

    "PF" (vertical up) where slope >= 45 degrees, "PG" (vertical down) where slope <= -45
    degrees; otherwise by |rotation|: below 22.5 degrees "PA" (flat), 67.5 "PB"
    (horizontal-vertical), 112.5 "PC" (horizontal), 157.5 "PD" (horizontal-overhead), else
    "PE" (overhead).
    """
    slope_array = np.asarray(slope, dtype=float)
    turned = np.abs(np.asarray(rotation, dtype=float))
    face = sum(turned >= bound for bound in _POSITION_BOUNDS)  # NaN: past none, flat
    return np.asarray(_POSITIONS[np.where(slope_array >= _QUARTER, 5,
                                          np.where(slope_array <= -_QUARTER, 6, face))])


def evaluate_weld_process(tree: TreeDescription, torch: str, seam: str, times: Any,
                          time_ref: Any, extrapolation: str, workpiece: str,
                          contact_tip: str | None, up: Any = None) -> WeldProcess:
    """``tree.weld_process(...)``; frame names already checked.

    One plan, one sampling: the seam on the workpiece, on a model that also holds the torch
    and the contact tip, rooted at the lowest common ancestor of them all, so that each
    moving thing between them is sampled once for every pose and velocity the process
    reads; the ancestor's turn in the root (mostly none) gives the upward direction. Without
    times, the samples are every keyframe and joint sample that moves one of these frames
    or the seam in the root. ``up`` is the upward direction in the root's axes, default +z.
    """
    upward = _unit_up(up)
    plan = plan_query(tree, seam, workpiece, times, time_ref, extrapolation,
                      also=[torch, *([] if contact_tip is None else [contact_tip])],
                      extra=prepare_path(tree, seam, tree.root).sources)
    model = plan.path.model
    assert model is not None, "a path with other frames is always compiled"
    if model.root != tree.root:  # the ancestor's turn in the root: upward in its axes
        turn = planned_transforms(tree, plan.on(tree, model.root, tree.root))[0]
        upward = rotate(np.swapaxes(turn, 1, 2), upward)
    seen = _SeamAxes.sampled(plan, torch, seam, workpiece, contact_tip, upward)
    wire = seen.wire
    speed = _weld_point_speed(seen.origin, wire, seen.torch_rates, seen.seam_rates)
    ctwd = None if seen.tip is None else _along_wire_to_plane(seen.tip[:, 2], wire[:, 2])
    up_in_seam = seen.up
    slope = np.arctan2(up_in_seam[:, 0], _across_length(up_in_seam[:, 1], up_in_seam[:, 2]))
    face_rotation = _across_angle(up_in_seam[:, 1], up_in_seam[:, 2])
    return WeldProcess(
        travel_speed=speed,
        travel_angle=np.arcsin(np.clip(wire[:, 0], -1.0, 1.0)),
        work_angle=_across_angle(-wire[:, 2], -wire[:, 1]),
        offset=np.ascontiguousarray(seen.origin),
        ctwd=ctwd,
        slope=slope,
        rotation=face_rotation,
        position=welding_positions(slope, face_rotation),
        times=plan.result_times,
        reference_time=plan.reference_time,
        torch=torch,
        seam=seam,
        workpiece=workpiece,
        contact_tip=contact_tip,
    )


@dataclass(frozen=True)
class _SeamAxes:
    """What the process reads, per sample, in the seam's axes (x along the travel): the
    torch's origin (m) and wire axis (its z), the torch's and the seam's velocities
    relative to the workpiece (``(linear, angular)``, m/s and rad/s), the unit upward
    direction, and the contact tip's origin (m) when there is one."""

    origin: FloatArray
    wire: FloatArray
    torch_rates: tuple[FloatArray, FloatArray]
    seam_rates: tuple[FloatArray, FloatArray]
    up: FloatArray
    tip: FloatArray | None

    @classmethod
    def sampled(cls, plan: QueryPlan, torch: str, seam: str, workpiece: str,
                contact_tip: str | None, up: FloatArray) -> _SeamAxes:
        """Each chunk of ``plan`` (on a model holding every frame named) sampled once and
        turned into the seam's axes; ``up`` is the upward direction in the model root's
        axes, static or per sample."""
        def vectors() -> FloatArray:  # (count, 3), each component one contiguous row:
            return np.empty((3, plan.count)).T  # the arithmetic below reads components

        seen = cls(vectors(), vectors(), (vectors(), vectors()), (vectors(), vectors()),
                   vectors(), None if contact_tip is None else vectors())
        for part, path in sampled_parts(plan):
            rates = velocities_in_root(path, [(torch, workpiece), (seam, workpiece)])
            seam_rotation, seam_origin = path.placements[seam]
            torch_rotation, torch_origin = path.placements[torch]
            into_seam = np.swapaxes(seam_rotation, -1, -2)
            seen.origin[part] = rotate(into_seam, torch_origin - seam_origin)
            seen.wire[part] = rotate(into_seam, torch_rotation[..., :, 2])
            for into, (linear, angular) in zip((seen.torch_rates, seen.seam_rates), rates,
                                               strict=True):
                into[0][part], into[1][part] = (rotate(into_seam, linear),
                                                rotate(into_seam, angular))
            seen.up[part] = rotate(into_seam, up if up.ndim == 1 else up[part])
            if seen.tip is not None and contact_tip is not None:
                seen.tip[part] = rotate(into_seam,
                                        path.placements[contact_tip][1] - seam_origin)
        require_finite_pose(seen.origin, torch, seam)
        return seen


def _weld_point_speed(origin: FloatArray, wire: FloatArray,
                      torch_rates: tuple[FloatArray, FloatArray],
                      seam_rates: tuple[FloatArray, FloatArray]) -> FloatArray:
    """Velocity along seam x (m/s) of the weld point ``w = p + s a`` (``s = -p_z / a_z``)
    relative to the workpiece. All in seam axes: the torch origin ``p``, the wire ``a``, and
    the torch's and the seam's velocities relative to the workpiece (linear of the origin,
    angular).

    Relative to the seam (axes turning at ``W``, the seam's angular velocity), the torch
    origin moves at ``dp = v_t - v_s - W x p`` and the wire turns at ``w_r = w_t - W``, so
    ``da = w_r x a``; ``w`` stays in the seam's plane (``d(p_z + s a_z) = 0`` gives ``ds``)
    and moves in it at ``dp + ds a + s da``; the seam carries it at ``v_s + W x w``. Only the
    x and z rows are needed: written out, without ``np.cross``.
    """
    (torch_linear, torch_angular), (seam_linear, seam_angular) = torch_rates, seam_rates
    px, py, pz = origin.T
    ax, ay, az = wire.T
    wx, wy, wz = seam_angular.T
    rx, ry, rz = (torch_angular - seam_angular).T
    along = torch_linear[:, 0] - seam_linear[:, 0] - (wy * pz - wz * py)
    rise = torch_linear[:, 2] - seam_linear[:, 2] - (wx * py - wy * px)
    reach = _along_wire_to_plane(pz, az)
    with np.errstate(divide="ignore", invalid="ignore"):
        reach_rate = -(rise + reach * (rx * ay - ry * ax)) / az
    in_plane = along + reach_rate * ax + reach * (ry * az - rz * ay)
    # W x w along x, with w_z = 0 on the plane
    carried = seam_linear[:, 0] - wz * (py + reach * ay)
    return in_plane + carried


def _along_wire_to_plane(height: FloatArray, wire_z: FloatArray) -> FloatArray:
    """Distance (m) along the wire from points ``height`` above the seam's plane to it; NaN
    where the wire does not point toward the plane (a_z >= 0)."""
    toward_work = -wire_z
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.where(toward_work > 0.0, height / toward_work, np.nan)


def _across_angle(along_y: FloatArray, along_z: FloatArray) -> FloatArray:
    """atan2 of a direction's y and z parts in seam axes; NaN where the direction lies
    along the seam's x axis (its y-z part below sin :data:`ALONG_TRAVEL_RAD`)."""
    return np.where(_across_length(along_y, along_z) > np.sin(ALONG_TRAVEL_RAD),
                    np.arctan2(along_y, along_z), np.nan)


def _across_length(along_y: FloatArray, along_z: FloatArray) -> FloatArray:
    """The length of a unit direction's y-z part in seam axes (no overflow to guard
    against: ``np.hypot``, which guards, took ten times as long)."""
    return np.sqrt(along_y * along_y + along_z * along_z)


def _unit_up(up: Any) -> FloatArray:
    """``up`` (a 3-vector in the root's axes, default +z) as a unit vector."""
    if up is None:
        return np.array([0.0, 0.0, 1.0])
    return unit_direction(up, "up")
