"""Data attached to frames: SpatialData, FrameTree.assign_data / get_data, rename, remove.

Expected points come from plain numpy: hand-written rotations and translations composed here.
"""

from __future__ import annotations

import numpy as np
import pytest

from pinframes import (
    DataNotFoundError,
    FrameExistsError,
    FrameNotFoundError,
    FrameTree,
    InvalidDataError,
    InvalidTimeError,
    Pose,
    SpatialData,
    TreeStructureError,
)

from geometry import rot_x, rot_z

POINTS = np.array([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 2.0, 0.5]])


def _tree() -> FrameTree:
    """world -> arm (static, turned 90° about z) -> tool (moving along x of arm over 2 s)."""
    tree = FrameTree("world", reference_time="2024-01-01T00:00:00")
    tree.add("arm", "world", Pose([1.0, 0.0, 0.0], rot_z(np.pi / 2)))
    tree.add("tool", "arm", Pose([[0.0, 0.0, 0.0], [2.0, 0.0, 0.0]], rot_x(0.3), times=[0, 2]))
    tree.add("table", "world", Pose([0.0, 0.0, -1.0]))
    return tree


def _tool_in_world(seconds: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Rotation and translation of tool in world at ``seconds``, by hand."""
    rotation = rot_z(np.pi / 2) @ rot_x(0.3)
    translations = [np.array([1.0, 0.0, 0.0]) + rot_z(np.pi / 2) @ [s, 0.0, 0.0]
                    for s in seconds]
    return rotation, np.array(translations)


def test_static_points_through_a_static_path():
    tree = _tree()
    tree.assign_data("cloud", POINTS, "arm")
    data = tree.get_data("cloud", relative_to="table")
    expected = (POINTS @ rot_z(np.pi / 2).T + [1.0, 0.0, 0.0]) - [0.0, 0.0, -1.0]
    np.testing.assert_allclose(data.points, expected, atol=1e-15)
    assert not data.is_time_dependent
    assert tree.get_data("cloud") is tree.get_data("cloud", relative_to="arm")


def test_static_points_on_a_moving_frame_follow_the_path_union_and_given_times():
    tree = _tree()
    tree.assign_data("cloud", SpatialData(POINTS, triangles=[[0, 1, 2]],
                                          attributes={"temperature": [20.0, 21.0, 22.0]}),
                     "tool")
    data = tree.get_data("cloud", relative_to="world")
    rotation, translation = _tool_in_world(np.array([0.0, 2.0]))
    expected = np.stack([POINTS @ rotation.T + t for t in translation])
    np.testing.assert_allclose(data.points, expected, atol=1e-14)
    np.testing.assert_array_equal(data.times.astype(np.int64), [0, 2_000_000_000])
    assert data.reference_time == np.datetime64("2024-01-01T00:00:00", "ns")
    np.testing.assert_array_equal(data.triangles, [[0, 1, 2]])
    np.testing.assert_array_equal(data.attributes["temperature"], [20.0, 21.0, 22.0])
    at = tree.get_data("cloud", relative_to="world", times=[0.5, 1.5])
    rotation, translation = _tool_in_world(np.array([0.5, 1.5]))
    np.testing.assert_allclose(at.points, np.stack([POINTS @ rotation.T + t
                                                    for t in translation]), atol=1e-14)


def test_time_dependent_points_are_moved_at_their_own_times():
    tree = _tree()
    scans = np.stack([POINTS, POINTS + 1.0, POINTS - 2.0])
    tree.assign_data("scan", SpatialData(scans, times=[0.0, 0.5, 3.0]), "tool")
    data = tree.get_data("scan", relative_to="world")
    rotation, translation = _tool_in_world(np.array([0.0, 0.5, 2.0]))  # held after 2 s
    expected = np.stack([scan @ rotation.T + t for scan, t in zip(scans, translation,
                                                                  strict=True)])
    np.testing.assert_allclose(data.points, expected, atol=1e-14)
    np.testing.assert_array_equal(data.times.astype(np.int64), [0, 500_000_000, 3_000_000_000])
    with pytest.raises(InvalidTimeError, match="times of its own"):
        tree.get_data("scan", relative_to="world", times=[1.0])


def test_time_dependent_points_with_their_own_reference_time():
    tree = _tree()
    scans = np.stack([POINTS, POINTS])
    tree.assign_data("scan", SpatialData(scans, times=[0.0, 1.0],
                                         reference_time="2024-01-01T00:00:01"), "tool")
    data = tree.get_data("scan", relative_to="arm")
    _, translation = _tool_in_world(np.array([1.0, 2.0]))
    in_arm = [rot_z(-np.pi / 2) @ (t - [1.0, 0.0, 0.0]) for t in translation]
    expected = np.stack([POINTS @ rot_x(0.3).T + t for t in in_arm])
    np.testing.assert_allclose(data.points, expected, atol=1e-14)


def test_time_fields_of_data_read_as_a_poses_do():
    """times, seconds and absolute_times of SpatialData, written out by hand."""
    static = SpatialData(POINTS)
    assert (static.times, static.seconds, static.absolute_times) == (None, None, None)
    assert not static.is_time_dependent
    data = SpatialData(np.stack([POINTS, POINTS]), times=[0.0, 1.5],
                       reference_time="2024-01-01T00:00:01")
    assert data.is_time_dependent
    np.testing.assert_array_equal(data.times, np.array([0, 1_500_000_000], "timedelta64[ns]"))
    np.testing.assert_array_equal(data.seconds, [0.0, 1.5])
    np.testing.assert_array_equal(data.absolute_times, np.array(
        ["2024-01-01T00:00:01", "2024-01-01T00:00:02.5"], "datetime64[ns]"))
    assert data.reference_time == np.datetime64("2024-01-01T00:00:01", "ns")


def test_pint_points_become_metres():
    pint = pytest.importorskip("pint")
    data = SpatialData(pint.UnitRegistry().Quantity(POINTS, "mm"))
    np.testing.assert_allclose(data.points, POINTS / 1000)


def test_rename_carries_data_and_remove_refuses_it():
    tree = _tree()
    tree.assign_data("cloud", POINTS, "tool")
    tree.rename("tool", "torch")
    assert tree.data_frame("cloud") == "torch"
    with pytest.raises(TreeStructureError, match="drop_data"):
        tree.remove("arm", recursive=True)
    assert "torch" in tree and tree.data_names == ["cloud"]
    tree.remove("arm", recursive=True, drop_data=True)
    assert tree.data_names == [] and "arm" not in tree


def test_data_names_are_unique_and_frames_must_exist():
    tree = _tree()
    tree.assign_data("cloud", POINTS, "arm")
    with pytest.raises(FrameExistsError):
        tree.assign_data("cloud", POINTS, "tool")
    with pytest.raises(FrameNotFoundError):
        tree.assign_data("other", POINTS, "nowhere")
    with pytest.raises(DataNotFoundError):
        tree.get_data("missing")
    tree.delete_data("cloud")
    assert tree.data_names == []


@pytest.mark.parametrize(("arguments", "field"), [
    (dict(points=[[1.0, 2.0]]), "points"),
    (dict(points=[[1.0, 2.0, np.nan]]), "points"),
    (dict(points=np.zeros((2, 3, 3))), "times"),
    (dict(points=np.zeros((2, 3, 3)), times=[0.0, 1.0, 2.0]), "times"),
    (dict(points=POINTS, times=[0.0]), "times"),
    (dict(points=POINTS, triangles=[[0, 1, 3]]), "triangles"),
    (dict(points=POINTS, triangles=[[0.0, 1.0, 2.0]]), "triangles"),
    (dict(points=POINTS, attributes={"t": [1.0, 2.0]}), "attributes.t"),
])
def test_bad_data_names_the_field(arguments, field):
    with pytest.raises(InvalidDataError) as caught:
        SpatialData(**arguments)
    assert caught.value.field == field


def test_deleting_data_takes_it_off_the_subsystems():
    from pinframes import Subsystem

    tree = _tree()
    tree.assign_data("cloud", POINTS, "tool")
    tree.assign_data("mesh", POINTS, "table")
    tree.subsystems = [Subsystem("rig", "arm", ("arm", "tool"), data=("cloud", "mesh"))]
    tree.delete_data("mesh")
    assert tree.subsystems[0].data == ("cloud",)
    tree.remove("tool", drop_data=True)
    assert tree.subsystems[0] == Subsystem("rig", "arm", ("arm",))
