"""Timing joint motions within velocity, acceleration and jerk limits (joint space, numpy).

:mod:`.motion_limits` (``MotionLimits``), :mod:`.timed_joints` (``TimedJoints``: a motion
from rest to rest, sampled with exact rates), :mod:`.point_to_point` (``time_point_to_point``:
all joints arriving together, each in trapezoids or S-curves) and :mod:`.along_path`
(``time_along_path``: along a geometric path, time-optimal by reachability).
"""

from .along_path import PathTiming, time_along_path
from .motion_limits import MotionLimits
from .point_to_point import PointToPoint, time_point_to_point
from .timed_joints import TimedJoints

__all__ = ["MotionLimits", "PathTiming", "PointToPoint", "TimedJoints", "time_along_path",
           "time_point_to_point"]
