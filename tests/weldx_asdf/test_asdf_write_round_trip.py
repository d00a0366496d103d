"""Files written by write_asdf: read back by pinframes (both schemas) and by weldx 0.8.2
(schema 0.1.0), compared with hand-derived poses and with the tree they came from."""

from __future__ import annotations

import numpy as np
import pytest

from conftest import SHARED_DATA
from pinframes import FrameTree, Joint, Pose, Subsystem, read_asdf, write_asdf
from weldx_asdf.weldx_env import ask_weldx, needs_weldx, weldx_poses

from geometry import rot_x, rot_z

T0 = "2024-03-01T08:00:00"
SECOND = 1_000_000_000


def cell() -> FrameTree:
    """Static, moving (own reference time or the tree's), joint-driven and nested frames."""
    tree = FrameTree("base", name="cell", reference_time=T0)
    tree.add("fixture", "base", Pose([0.0, 0.0, 0.01], rot_z(np.pi / 2)))
    tree.add("workpiece", "fixture", Pose([0.1, 0.05, 0.0], rot_x(0.3)))
    tree.add("tcp", "workpiece", Pose([[0.005, 0, 0.002], [0.295, 0, 0.002], [0.3, 0.1, 0]],
                                      np.stack([rot_x(np.pi), rot_x(np.pi), rot_z(0.2)]),
                                      times=[0.0, 29.0, 30.5]))
    tree.add("cam", "base", Pose([[0, 0.1, 0], [0, 0.1, 0.2]],
                                 times=["2024-03-01T07:59:58", "2024-03-01T08:00:06.5"]))
    tree.add("lens", "cam")
    tree.attach_joint("table", "base", Joint("turn", "revolute", (0.0, 0.0, 1.0)),
                      Pose([1.0, 0.0, 0.5]))
    tree.set_joint_trajectory([0.0, 2.0, 4.0], [[0.0], [1.0], [2.5]], ["turn"])
    tree.subsystems = [Subsystem("robot", "workpiece", ("workpiece", "tcp"), "cell",
                                 np.datetime64("2024-03-01T07:00:00"), ("scanner",)),
                       Subsystem("scanner", "tcp", ("tcp",), "robot")]
    return tree


def pose_in_base_by_hand(frame: str, seconds: float) -> tuple[np.ndarray, np.ndarray]:
    """(rotation, translation in m) of ``frame`` in base at a keyframe time (seconds after
    T0), composed with plain numpy from the numbers in :func:`cell`."""
    fixture = (rot_z(np.pi / 2), np.array([0.0, 0.0, 0.01]))
    workpiece = (rot_x(0.3), np.array([0.1, 0.05, 0.0]))
    tcp = {0.0: (rot_x(np.pi), [0.005, 0, 0.002]), 29.0: (rot_x(np.pi), [0.295, 0, 0.002]),
           30.5: (rot_z(0.2), [0.3, 0.1, 0])}
    cam = {-2.0: [0, 0.1, 0], 6.5: [0, 0.1, 0.2]}
    table = {0.0: 0.0, 2.0: 1.0, 4.0: 2.5}

    def chain(*links):
        rotation, translation = np.eye(3), np.zeros(3)
        for link_rotation, link_translation in links:
            translation = rotation @ np.asarray(link_translation) + translation
            rotation = rotation @ link_rotation
        return rotation, translation

    if frame == "tcp":
        return chain(fixture, workpiece, tcp[seconds])
    if frame in ("cam", "lens"):
        return chain((np.eye(3), cam[seconds]))
    return chain((rot_z(table[seconds]), [1.0, 0.0, 0.5]))


KEYFRAMES = [("tcp", [0.0, 29.0, 30.5]), ("cam", [-2.0, 6.5]), ("lens", [-2.0, 6.5]),
             ("table", [0.0, 2.0, 4.0])]


@pytest.mark.parametrize("schema", ["1.0.0", "0.1.0"])
def test_round_trip_keeps_frames_poses_times_and_subsystems(tmp_path, schema):
    tree = cell()
    write_asdf(tree, tmp_path / "cell.asdf", schema=schema)
    copy = read_asdf(tmp_path / "cell.asdf")
    assert (copy.name, copy.root, copy.reference_time) == ("cell", "base", tree.reference_time)
    assert copy.frames[0] == "base" and sorted(copy.frames) == sorted(tree.frames)
    assert all(copy.parent(f) == tree.parent(f) for f in tree.frames[1:])
    cam = copy.local_pose("cam")
    assert cam.reference_time == np.datetime64("2024-03-01T07:59:58")
    np.testing.assert_array_equal(cam.times.astype(np.int64), [0, 8_500_000_000])
    np.testing.assert_array_equal(copy.local_pose("tcp").times.astype(np.int64),
                                  [0, 29 * SECOND, 30_500_000_000])
    assert copy.local_pose("tcp").reference_time is None  # counts from the tree's
    for frame, seconds in KEYFRAMES:
        got = copy.pose(frame, relative_to="base", times=seconds)
        for index, second in enumerate(seconds):
            rotation, translation = pose_in_base_by_hand(frame, second)
            np.testing.assert_allclose(got.translation[index], translation, atol=1e-12)
            np.testing.assert_allclose(got.rotation[index], rotation, atol=1e-12)
    between = np.linspace(-3.0, 35.0, 77)  # interpolated, and held outside the keyframes
    for frame in tree.frames[1:]:
        np.testing.assert_allclose(copy.pose(frame, "base", times=between).matrix,
                                   tree.pose(frame, "base", times=between).matrix, atol=1e-12)
    robot, scanner = sorted(copy.subsystems, key=lambda s: s.name)
    assert (robot.root, robot.members, robot.subsystems) == (
        "workpiece", ("workpiece", "tcp"), ("scanner",))
    assert robot.reference_time == np.datetime64("2024-03-01T07:00:00")
    assert (scanner.root, scanner.members, scanner.parent) == ("tcp", ("tcp",), "robot")


@pytest.mark.parametrize("schema", ["1.0.0", "0.1.0"])
def test_a_lone_root_round_trips(tmp_path, schema):
    write_asdf(FrameTree("alone", name="solo"), tmp_path / "root.asdf", schema=schema)
    copy = read_asdf(tmp_path / "root.asdf")
    assert (copy.frames, copy.name, copy.reference_time) == (["alone"], "solo", None)


@pytest.mark.parametrize("name", ["static_tree.asdf", "time_delta.asdf", "absolute_time.asdf",
                                  "legacy_subsystems.asdf", "legacy_time.asdf"])
@pytest.mark.parametrize("schema", ["1.0.0", "0.1.0"])
def test_weldx_files_read_and_rewritten_give_the_same_poses(tmp_path, name, schema):
    path = SHARED_DATA / "weldx-files" / name
    if not path.is_file():
        pytest.skip("shared sample data not present")
    tree = read_asdf(path)
    write_asdf(tree, tmp_path / name, schema=schema)
    copy = read_asdf(tmp_path / name)
    assert copy.frames[0] == tree.root and sorted(copy.frames) == sorted(tree.frames)
    assert all(copy.parent(f) == tree.parent(f) for f in tree.frames[1:])
    assert copy.reference_time == tree.reference_time
    assert copy.subsystems == tree.subsystems or schema == "0.1.0"
    assert {s.name for s in copy.subsystems} == {s.name for s in tree.subsystems}
    times = np.linspace(-2.0, 35.0, 38)
    for frame in tree.frames[1:]:
        np.testing.assert_allclose(copy.pose(frame, tree.root, times=times).matrix,
                                   tree.pose(frame, tree.root, times=times).matrix, atol=1e-12)


@needs_weldx
def test_weldx_reads_schema_0_1_0_files_and_agrees(tmp_path):
    tree = cell()
    path = tmp_path / "cell.asdf"
    write_asdf(tree, path, schema="0.1.0")
    hierarchy = ask_weldx("hierarchy", path=path)
    assert (hierarchy["name"], hierarchy["root"]) == ("cell", "base")
    assert hierarchy["parents"] == {f: tree.parent(f) for f in tree.frames[1:]}
    assert np.datetime64(hierarchy["reference_time"]) == tree.reference_time
    queries, expected = [], []
    for frame, seconds in KEYFRAMES:
        queries.append({"frame": frame, "relative_to": "base", "time_ref": T0,
                        "times_ns": (np.asarray(seconds) * SECOND).astype(np.int64)})
        expected.append([pose_in_base_by_hand(frame, second) for second in seconds])
    between = (np.linspace(-3.0, 35.0, 39) * SECOND).astype(np.int64)
    pairs = [("tcp", "cam"), ("table", "lens"), ("lens", "workpiece"), ("fixture", "base")]
    for frame, relative_to in pairs:
        queries.append({"frame": frame, "relative_to": relative_to, "time_ref": T0,
                        "times_ns": between})
    answers = weldx_poses(path, queries)
    for answer, poses in zip(answers, expected, strict=False):
        translations, rotations = broadcast(answer, len(poses))
        for index, (rotation, translation) in enumerate(poses):
            np.testing.assert_allclose(translations[index], translation, atol=1e-9)
            np.testing.assert_allclose(rotations[index], rotation, atol=1e-9)
    for answer, (frame, relative_to) in zip(answers[len(expected):], pairs, strict=True):
        ours = tree.pose(frame, relative_to, times=between.astype("timedelta64[ns]"),
                         time_ref=T0)
        translations, rotations = broadcast(answer, len(between))
        np.testing.assert_allclose(translations, ours.translation, atol=1e-9)
        np.testing.assert_allclose(rotations, ours.rotation, atol=1e-9)


def broadcast(answer, count):
    """weldx answers one translation (rotation) when only the other part moves."""
    return (np.broadcast_to(answer["translation"], (count, 3)),
            np.broadcast_to(answer["rotation"], (count, 3, 3)))
