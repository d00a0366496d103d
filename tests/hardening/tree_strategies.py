"""Hypothesis strategies for random trees of static, moving and robot frames (as TreeSpec)."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
from hypothesis import strategies as st

from hardening.tree_model import (
    FrameItem,
    Keyframes,
    RobotItem,
    TreeSpec,
    axis_rotation,
    homogeneous,
    shifted_to_absolute,
    urdf_joints,
)

WELDING_ROBOT = (Path(__file__).resolve().parents[2] / "models" / "welding_robot"
                 / "welding_robot.urdf").read_text()
_LARGEST_STEP = math.pi - 1e-3
"""Keyframe rotation steps stay below half a turn (SLERP takes the short way)."""

coordinates = st.floats(-3.0, 3.0, allow_nan=False)
unit_axes = st.one_of(
    st.sampled_from([(1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 1.0), (0.0, 0.0, -1.0)]),
    st.tuples(coordinates, coordinates, coordinates).filter(
        lambda v: np.linalg.norm(v) > 0.1)).map(lambda v: np.array(v) / np.linalg.norm(v))
angles = st.one_of(st.floats(0.0, math.pi), st.sampled_from([0.0, math.pi - 1e-9, math.pi]),
                   st.floats(math.pi - 1e-4, math.pi))
"""Rotation angles, radians, with many near half a turn."""
step_angles = st.one_of(st.floats(0.0, _LARGEST_STEP), st.just(_LARGEST_STEP),
                        st.floats(_LARGEST_STEP - 1e-3, _LARGEST_STEP), st.just(1e-9))
"""Keyframe rotation steps, radians: below half a turn, some close to it or tiny."""


@st.composite
def rotations(draw) -> np.ndarray:
    return axis_rotation(draw(unit_axes), draw(angles))[0]


@st.composite
def static_matrices(draw) -> np.ndarray:
    return homogeneous(draw(rotations()), np.array(draw(st.tuples(*[coordinates] * 3))))


@st.composite
def sample_times(draw, count: int) -> np.ndarray:
    """``count`` strictly increasing times, ns: gaps of a nanosecond to ten seconds."""
    start = draw(st.integers(-5 * 10**9, 5 * 10**9))
    gaps = draw(st.lists(st.integers(1, 10**10), min_size=count - 1, max_size=count - 1))
    return np.cumsum([start, *gaps]).astype(np.int64)


@st.composite
def keyframes(draw) -> Keyframes:
    count = draw(st.integers(1, 5))
    return Keyframes(
        times=draw(sample_times(count)), reference=None,
        translations=np.array(draw(st.lists(st.tuples(*[coordinates] * 3), min_size=count,
                                            max_size=count))),
        start_rotation=draw(rotations()),
        step_axes=np.array(draw(st.lists(unit_axes, min_size=count - 1,
                                         max_size=count - 1))).reshape(-1, 3),
        step_angles=np.array(draw(st.lists(step_angles, min_size=count - 1,
                                           max_size=count - 1))))


@st.composite
def small_urdfs(draw) -> str:
    """A URDF of 1 to 5 joints: revolute, prismatic, continuous, fixed and mimic joints."""
    count = draw(st.integers(1, 5))
    links = ["base"]
    joints, actuated = [], []
    for index in range(count):
        kind = draw(st.sampled_from(["revolute", "prismatic", "continuous", "fixed"]))
        if index == 0:
            kind = draw(st.sampled_from(["revolute", "prismatic", "continuous"]))
        parent = draw(st.sampled_from(links))
        xyz = draw(st.tuples(*[coordinates] * 3))
        rpy = draw(st.tuples(*[st.floats(-math.pi, math.pi)] * 3))
        axis = draw(unit_axes)
        parts = [f'<parent link="{parent}"/><child link="l{index}"/>',
                 f'<origin xyz="{" ".join(map(repr, xyz))}" rpy="{" ".join(map(repr, rpy))}"/>',
                 f'<axis xyz="{" ".join(map(repr, axis.tolist()))}"/>']
        if kind in ("revolute", "prismatic"):
            parts.append('<limit lower="-100" upper="100" effort="1" velocity="1"/>')
        if kind != "fixed" and actuated and draw(st.booleans()):
            parts.append(f'<mimic joint="{draw(st.sampled_from(actuated))}" '
                         f'multiplier="{draw(st.floats(-2.0, 2.0))!r}" '
                         f'offset="{draw(st.floats(-1.0, 1.0))!r}"/>')
        elif kind != "fixed":
            actuated.append(f"j{index}")
        joints.append(f'<joint name="j{index}" type="{kind}">{"".join(parts)}</joint>')
        links.append(f"l{index}")
    link_xml = "".join(f'<link name="{link}"/>' for link in links)
    return f'<robot name="small">{link_xml}{"".join(joints)}</robot>'


@st.composite
def robots(draw, parent: str, prefix: str) -> RobotItem:
    """A robot (small URDF or the bundled welding robot) with random joint samples.

    Turning joints step by less than 1.2 rad between samples (times mimic multipliers of at
    most 2: below half a turn, which a scene file can hold), prismatic ones by 0.5 m.
    """
    urdf = draw(st.one_of(small_urdfs(), st.just(WELDING_ROBOT)))
    driven = [j for j in urdf_joints(urdf) if j.kind != "fixed" and j.mimic is None]
    count = draw(st.integers(1, 5))
    columns = []
    for joint in driven:
        size = 0.5 if joint.kind == "prismatic" else 1.2
        start = draw(st.floats(-3.0, 3.0))
        steps = draw(st.lists(st.floats(-size, size), min_size=count - 1, max_size=count - 1))
        columns.append(np.cumsum([start, *steps]))
    return RobotItem(urdf=urdf, parent=parent, prefix=prefix, mount=draw(static_matrices()),
                     times=draw(sample_times(count)), reference=None,
                     driven=tuple(j.name for j in driven),
                     positions=np.array(columns).T.reshape(count, len(driven)))


@st.composite
def trees(draw, moving: bool = True, robot_count: tuple[int, int] = (0, 2),
          frame_count: tuple[int, int] = (1, 6)) -> TreeSpec:
    """A relative TreeSpec: frames hang from any earlier frame, robot links included."""
    names = ["world"]
    items = []
    robots_left = draw(st.integers(*robot_count))
    frames_left = draw(st.integers(*frame_count))
    while robots_left or frames_left:
        parent = draw(st.sampled_from(names))
        if robots_left and (not frames_left or draw(st.booleans())):
            robot = draw(robots(parent, f"r{robots_left}/"))
            items.append(robot)
            names += sorted(robot.link_matrices(np.zeros(1)))
            robots_left -= 1
            continue
        name = f"f{frames_left}"
        motion = draw(keyframes()) if moving and draw(st.booleans()) else None
        items.append(FrameItem(name, parent, draw(static_matrices()), motion))
        names.append(name)
        frames_left -= 1
    return TreeSpec("world", None, tuple(items))


@st.composite
def absolute_trees(draw, **kwargs) -> TreeSpec:
    """A tree of :func:`trees` whose moving frames and robots all have reference times.

    Each gets its own reference time, some before and some after the instants it moves at;
    the tree has a reference time of its own or none.
    """
    spec = draw(trees(**kwargs))
    start = draw(st.integers(1_600_000_000 * 10**9, 1_900_000_000 * 10**9))
    shifts = draw(st.lists(st.integers(-10**11, 10**11), min_size=len(spec.moving_items()),
                           max_size=len(spec.moving_items())))
    tree_reference = draw(st.none() | st.integers(start - 10**11, start + 10**11))
    return shifted_to_absolute(spec, start, shifts, tree_reference)
