"""Trees written as ROS bags (``pinframes.write``): every message decoded by rosbags and by the
``mcap`` library and checked against ``pose()`` and against the files the tree came from
(Pinocchio's own URDF parser for the descriptions, numpy for the joint CSV), and read back
with ``pinframes.read``."""

from __future__ import annotations

import os
import warnings
from pathlib import Path

import numpy as np
import pinocchio as pin
import pytest

import pinframes
from conftest import SHARED_DATA
from pinframes import FrameTree, Pose

from geometry import rot_z
from ros.bag_decoding import READERS, decode, matrix_from_quaternion, mcap_file

pytest.importorskip("mcap_ros2")

ROOT = Path(__file__).resolve().parents[2]
CELL = ROOT / "models" / "welding_cell" / "scene.yaml"
ROBOT = ROOT / "models" / "welding_robot" / "welding_robot.urdf"
MOTION = ROOT / "models" / "welding_cell" / "robot_motion.csv"
KINDS = ("run.mcap", "run.bag", "run_folder", "run.db3")
REFERENCE = np.datetime64("2024-03-01T08:00:00", "ns")


@pytest.fixture(scope="module")
def cell() -> FrameTree:
    return pinframes.read_scene(CELL)


@pytest.fixture(scope="module")
def cell_bags(cell, tmp_path_factory) -> dict[str, Path]:
    folder = tmp_path_factory.mktemp("cell")
    for name in KINDS:
        pinframes.write(cell, folder / name)
    return {name: folder / name for name in KINDS}


def _query(tree: FrameTree, stamps_ns) -> np.ndarray:
    """The times of ``tree`` that the bag's stamps stand for: instants when the tree has a
    reference time, else durations from 0."""
    stamps = np.asarray(stamps_ns, np.int64)
    union = tree.time_union()
    anchored = tree.reference_time is not None or (union is not None and union.reference)
    return stamps.astype("datetime64[ns]") if anchored else stamps.astype("timedelta64[ns]")


def _check_transforms_against_pose(tree: FrameTree, records: list[dict]) -> int:
    """Each transform (frame ids without a leading slash) equals the pose of its child in
    its parent at its stamp; returns how many were checked."""
    by_child: dict[tuple[str, str], list[dict]] = {}
    for record in records:
        assert not record["child"].startswith("/") and not record["parent"].startswith("/")
        by_child.setdefault((record["child"], record["parent"]), []).append(record)
    for (child, parent), rows in by_child.items():
        assert tree.parent(child) == parent
        stamps = [row["stamp_ns"] for row in rows]
        pose = tree.pose(child, parent, times=_query(tree, stamps))
        translations = np.array([row["translation"] for row in rows])
        rotations = np.array([matrix_from_quaternion(row["quaternion"]) for row in rows])
        np.testing.assert_allclose(translations, pose.translation.reshape(-1, 3), atol=1e-9)
        np.testing.assert_allclose(rotations, pose.rotation.reshape(-1, 3, 3), atol=1e-9)
    return len(records)


def _check_round_trip(tree: FrameTree, path: Path, stamps_ns: np.ndarray) -> FrameTree:
    """``pinframes.read`` of the bag gives every frame's pose in the root at the stamps
    (1e-9 m), and the same frames; the robots' links on tf agree with their descriptions
    (no warning)."""
    with warnings.catch_warnings():
        warnings.simplefilter("error", pinframes.BagWarning)
        back = pinframes.read(path)
    assert sorted(back.frames) == sorted(tree.frames)
    assert back.root == tree.root
    instants = np.asarray(stamps_ns, np.int64).astype("datetime64[ns]")
    original_times = _query(tree, stamps_ns)
    for frame in tree.frames[1:]:
        expected = tree.pose(frame, tree.root, times=original_times)
        got = back.pose(frame, tree.root, times=instants if back.reference_time is not None
                        else original_times)
        np.testing.assert_allclose(got.translation, expected.translation, atol=1e-9,
                                   err_msg=frame)
        np.testing.assert_allclose(got.rotation, expected.rotation, atol=1e-9, err_msg=frame)
    return back


# -- the bundled cell ----------------------------------------------------------------------


@pytest.mark.parametrize("name", KINDS)
def test_cell_reads_back_with_the_same_poses_and_joint_values(cell, cell_bags, name):
    motion = np.loadtxt(MOTION, delimiter=",", skiprows=1)
    back = _check_round_trip(cell, cell_bags[name], np.round(motion[:, 0] * 1e9))
    assert back.reference_time == np.datetime64(0, "ns")  # no reference: stamps from 0
    header = MOTION.read_text().splitlines()[0].split(",")
    for column, joint in enumerate(header[1:], start=1):  # the CSV's own values, exactly
        trajectory = back.joint_trajectory(f"robot/{joint}")
        assert np.array_equal(trajectory.values, motion[:, column])


@pytest.mark.parametrize("reader", READERS)
def test_every_cell_message_decodes_and_matches_pose(cell, cell_bags, reader):
    records = decode(cell_bags["run.mcap"], reader)
    motion = np.loadtxt(MOTION, delimiter=",", skiprows=1)
    stamps = np.round(motion[:, 0] * 1e9).astype(np.int64)
    moving = ["positioner", "seam_point", *(f"robot/link_{i}" for i in range(1, 7))]
    assert [row["stamp_ns"] for row in records["/tf"][::8]] == stamps.tolist()
    assert sorted({row["child"] for row in records["/tf"]}) == sorted(moving)
    # every transform, the robot's links as robot_state_publisher would publish them
    assert _check_transforms_against_pose(cell, records["/tf"]) == 8 * len(stamps)
    static = records["/tf_static"]
    assert {row["child"] for row in static} == {
        "robot_base", "positioner_base", "fixtures", "robot/base_link", "workpiece",
        "faceplate", "torch", "torch_tcp", "contact_tip", "weld_seam", "pipe", "torch_target",
        "robot/flange"}
    _check_transforms_against_pose(cell, static)
    # five robots, one robot_state_publisher each: namespaced by their URDF names
    descriptions = {topic.removesuffix("/robot_description"): rows[0]["text"]
                    for topic, rows in records.items() if topic.endswith("/robot_description")}
    assert sorted(descriptions) == ["/faceplate", "/fixtures", "/pinframes_welding_robot",
                                    "/pipe", "/torch"]
    for namespace, text in descriptions.items():  # each parses in Pinocchio, tree names
        model = pin.buildModelFromXML(text)
        links = {frame.name for frame in model.frames if frame.type == pin.FrameType.BODY}
        assert links <= set(cell.frames), namespace
    states = records["/pinframes_welding_robot/joint_states"]
    assert [row["stamp_ns"] for row in states] == stamps.tolist()
    assert np.array_equal([row["positions"] for row in states], motion[:, 1:])
    _check_description_against_pose(cell, descriptions["/pinframes_welding_robot"], states)


def _check_description_against_pose(tree: FrameTree, urdf: str, states: list[dict]) -> None:
    """Pinocchio's own URDF parser on the written description, at the written joint states,
    places every link where ``pose()`` puts it (relative to the robot's root link)."""
    model = pin.buildModelFromXML(urdf)
    data = model.createData()
    root = model.frames[model.getFrameId(model.frames[1].name)].name
    for row in states[::250]:
        q = pin.neutral(model)
        for name, value in zip(row["names"], row["positions"], strict=True):
            q[model.joints[model.getJointId(name)].idx_q] = value
        pin.framesForwardKinematics(model, data, q)
        for frame in ("robot/link_3", "robot/flange"):
            placement = data.oMf[model.getFrameId(frame)]
            pose = tree.pose(frame, root, times=_query(tree, [row["stamp_ns"]]))
            np.testing.assert_allclose(placement.translation, pose.translation[0], atol=1e-9)
            np.testing.assert_allclose(placement.rotation, pose.rotation[0], atol=1e-9)


def test_mesh_names_in_the_descriptions_are_absolute_and_found(cell, cell_bags):
    """A description is text without a folder: the cell's meshes (relative to their URDF
    files) are written as file:// URIs, so the read-back cell measures the same clearance
    between the torch and pipe meshes."""
    records = decode(cell_bags["run.mcap"], "mcap")
    torch_urdf = records["/torch/robot_description"][0]["text"]
    mesh = ROOT / "models" / "welding_cell" / "geometry" / "meshes" / "torch.stl"
    assert f'filename="{mesh.resolve().as_uri()}"' in torch_urdf
    back = pinframes.read(cell_bags["run.mcap"])
    seconds = np.array([0.0, 7.5])
    written = back.clearance("torch", "pipe", geometry="visual",
                             times=(seconds * 1e9).astype("datetime64[ns]"))
    original = cell.clearance("torch", "pipe", geometry="visual", times=seconds)
    np.testing.assert_allclose(written.distance, original.distance, atol=1e-9)
    # the shapes of frames that are no URDF link (the scene's geometry entries) go out as
    # one-link robots and come back as such
    assert "<box" in records["/fixtures/robot_description"][0]["text"]
    written = back.clearance("robot/link_1", "fixtures",
                             times=(seconds * 1e9).astype("datetime64[ns]"))
    original = cell.clearance("robot/link_1", "fixtures", times=seconds)
    np.testing.assert_allclose(written.distance, original.distance, atol=1e-9)


def test_mcap_holds_ros2msg_schemas_and_cdr_messages(cell_bags):
    from mcap.reader import make_reader

    with open(cell_bags["run.mcap"], "rb") as handle:
        summary = make_reader(handle).get_summary()
    assert {schema.encoding for schema in summary.schemas.values()} == {"ros2msg"}
    assert {schema.name for schema in summary.schemas.values()} == {
        "tf2_msgs/msg/TFMessage", "std_msgs/msg/String", "sensor_msgs/msg/JointState"}
    assert {channel.message_encoding for channel in summary.channels.values()} == {"cdr"}
    # read as a stream, record by record, as a viewer loading it does: the ros2 profile, a
    # well-formed file from header to footer
    from mcap.records import Footer, Header
    from mcap.stream_reader import StreamReader

    with open(cell_bags["run.mcap"], "rb") as handle:
        records = list(StreamReader(handle, validate_crcs=True).records)
    assert isinstance(records[0], Header) and records[0].profile == "ros2"
    assert isinstance(records[-1], Footer)
    folder_mcap = mcap_file(cell_bags["run_folder"])
    assert folder_mcap.name == "run_folder.mcap"  # named after the folder, as ros2 bag does


def test_ros1_bag_has_the_standard_tf_definition_and_latched_static_topics(cell_bags):
    from rosbags.rosbag1 import Reader

    with Reader(cell_bags["run.bag"]) as reader:
        connections = {connection.topic: connection for connection in reader.connections}
    assert connections["/tf"].digest == "94810edda583a504dfda3829e70d7eec"  # tf2's MD5
    assert connections["/tf_static"].ext.latching == 1
    assert connections["/pinframes_welding_robot/robot_description"].ext.latching == 1
    assert connections["/tf"].ext.latching in (None, 0)


# -- moving frames, reference times, times ------------------------------------------------


def _turntables(reference: np.datetime64 | None) -> FrameTree:
    """Two tables turning about z on their own keyframes, one riding on the other, and a
    static frame on top."""
    tree = FrameTree("world", reference_time=reference)
    angles = np.array([0.0, 0.5, 2.0])
    tree.add("table", "world", Pose(translation=[[1, 0, 0], [1, 0, 0.5], [1, 0, 1]],
                                    rotation=[rot_z(a) for a in angles],
                                    times=[0.0, 1.0, 3.0]))
    tree.add("slide", "table", Pose(translation=[[0, 0, 0], [0.3, 0, 0]], times=[0.5, 2.5]))
    tree.add("tip", "slide", Pose(translation=[0.1, 0.2, 0.3]))
    return tree


@pytest.mark.parametrize("reference", [REFERENCE, None])
@pytest.mark.parametrize("name", ["t.mcap", "t.bag"])
def test_moving_frames_at_their_keyframes_read_back(tmp_path, reference, name):
    tree = _turntables(reference)
    pinframes.write(tree, tmp_path / name)
    offsets = np.array([0, 0.5, 1, 2.5, 3]) * 1e9
    start = 0 if reference is None else int(reference.astype(np.int64))
    stamps = (offsets + start).astype(np.int64)
    records = decode(tmp_path / name, "rosbags")
    assert sorted({row["stamp_ns"] for row in records["/tf"]}) == stamps.tolist()
    assert {row["child"] for row in records["/tf"]} == {"table", "slide"}
    assert [row["child"] for row in records["/tf_static"]] == ["tip"]
    # hand-derived: at 0.5 s (the slide's first keyframe) the table is half-way from 0 rad
    # to 0.5 rad about z, and half-way up
    halfway = next(row for row in records["/tf"] if row["child"] == "table"
                   and row["stamp_ns"] == start + 5 * 10**8)
    np.testing.assert_allclose(matrix_from_quaternion(halfway["quaternion"]), rot_z(0.25),
                               atol=1e-12)
    np.testing.assert_allclose(halfway["translation"], [1, 0, 0.25], atol=1e-12)
    back = pinframes.read(tmp_path / name)
    assert back.parent("tip") == "slide" and back.parent("slide") == "table"
    between = np.linspace(0, 3, 31) * 1e9 + start  # also between the written times
    expected = tree.pose("tip", "world", times=_query(tree, between))
    got = back.pose("tip", "world", times=between.astype("datetime64[ns]"))
    np.testing.assert_allclose(got.translation, expected.translation, atol=1e-9)
    np.testing.assert_allclose(got.rotation, expected.rotation, atol=1e-9)


def test_requested_times_are_the_stamps(tmp_path):
    tree = _turntables(REFERENCE)
    pinframes.write(tree, tmp_path / "t.mcap", times=[0.25, 1.75, 2.0])
    records = decode(tmp_path / "t.mcap", "mcap")
    start = int(REFERENCE.astype(np.int64))
    stamps = sorted({row["stamp_ns"] for row in records["/tf"]})
    assert stamps == [start + 250_000_000, start + 1_750_000_000, start + 2_000_000_000]
    _check_transforms_against_pose(tree, records["/tf"])


def test_time_ref_anchors_a_tree_without_reference_time(tmp_path):
    tree = FrameTree("world")
    tree.add("arm", "world", Pose(translation=[[0, 0, 0], [1, 0, 0]], times=[-1.0, 1.0]))
    with pytest.raises(pinframes.InvalidTimeError, match="before 1970") as caught:
        pinframes.write(tree, tmp_path / "t.mcap")
    assert "t.mcap" in str(caught.value)
    assert not list(tmp_path.iterdir())  # nothing written, no temporary left
    pinframes.write(tree, tmp_path / "t.mcap", time_ref="2024-03-01T08:00:00")
    back = pinframes.read(tmp_path / "t.mcap")
    assert back.reference_time == REFERENCE - np.timedelta64(1, "s")
    np.testing.assert_allclose(back.pose("arm", times=[REFERENCE]).translation, [[0.5, 0, 0]],
                               atol=1e-12)


def test_a_static_tree_goes_on_tf_static_only(tmp_path):
    tree = FrameTree("world")
    tree.add("a", "world", Pose.from_xyz_rpy(1, 2, 3, 0.1, 0.2, 0.3))
    tree.add("b", "a", Pose(translation=[0, 0, 1]))
    pinframes.write(tree, tmp_path / "static.mcap")
    records = decode(tmp_path / "static.mcap", "mcap")
    assert sorted(records) == ["/tf_static"]
    _check_transforms_against_pose(tree, records["/tf_static"])
    back = pinframes.read(tmp_path / "static.mcap")
    np.testing.assert_allclose(back.pose("b", "world").matrix, tree.pose("b", "world").matrix,
                               atol=1e-12)


# -- several robots -----------------------------------------------------------------------


def test_several_robots_are_namespaced_and_read_back(tmp_path):
    tree = FrameTree("world", reference_time=REFERENCE)
    tree.add("carriage", "world", Pose(translation=[[0, 0, 0], [2, 0, 0]], times=[0.0, 4.0]))
    tree.attach_urdf(ROBOT, parent="carriage", prefix="left/")
    tree.attach_urdf(ROBOT, parent="world", prefix="right/",
                     pose=Pose.from_xyz_rpy(0, 2, 0, 0, 0, np.pi))
    times = np.linspace(0, 4, 9)
    tree.set_joint_trajectory(times, np.outer(np.sin(times), np.linspace(0.1, 0.6, 6)),
                              [f"left/joint_{i}" for i in range(1, 7)])
    tree.set_joint_trajectory(times[::2], np.outer(times[::2] / 4, np.ones(6)),
                              [f"right/joint_{i}" for i in range(1, 7)])
    tree.add("camera", "right/flange", Pose(translation=[0, 0, 0.1]))
    pinframes.write(tree, tmp_path / "two.mcap")
    records = decode(tmp_path / "two.mcap", "mcap")
    assert {"/pinframes_welding_robot/robot_description",
            "/pinframes_welding_robot_2/robot_description",
            "/pinframes_welding_robot/joint_states",
            "/pinframes_welding_robot_2/joint_states"} <= set(records)
    links = {f"{side}/link_{i}" for side in ("left", "right") for i in range(1, 7)}
    assert {row["child"] for row in records["/tf"]} == {"carriage"} | links
    assert {row["child"] for row in records["/tf_static"]} == {
        "left/base_link", "right/base_link", "camera", "left/flange", "right/flange"}
    _check_transforms_against_pose(tree, records["/tf"] + records["/tf_static"])
    right = records["/pinframes_welding_robot_2/joint_states"]
    assert right[0]["names"] == [f"right/joint_{i}" for i in range(1, 7)]
    start = int(REFERENCE.astype(np.int64))
    _check_round_trip(tree, tmp_path / "two.mcap", start + (times * 1e9).astype(np.int64))


def test_a_namespaced_copy_of_the_robot_is_not_mounted_twice(tmp_path):
    """A recording with the same URDF on /robot_description and /arm/robot_description
    (written by rosbags itself): one robot, one warning naming the second topic."""
    from ros.bag_writing import STRING, Message, string, write_bag

    text = ROBOT.read_text()
    bag = write_bag(tmp_path / "copy", "mcap", [
        Message("/robot_description", STRING, 0, string(2, text)),
        Message("/arm/robot_description", STRING, 0, string(2, text))])
    with pytest.warns(pinframes.BagWarning, match="/arm/robot_description"):
        tree = pinframes.read(bag)
    assert sorted(tree.joints) == [f"joint_{i}" for i in range(1, 7)]


def test_a_robot_alone_uses_the_plain_topics(tmp_path):
    tree = pinframes.read_urdf(ROBOT)
    tree.set_joint_trajectory([0.0, 1.0], [[0.0] * 6, [0.2] * 6])
    pinframes.write(tree, tmp_path / "one.bag")
    records = decode(tmp_path / "one.bag", "rosbags")
    assert sorted(records) == ["/joint_states", "/robot_description", "/tf", "/tf_static"]
    assert records["/joint_states"][1]["positions"] == [0.2] * 6
    _check_round_trip(tree, tmp_path / "one.bag", np.array([0, 10**9]))


# -- weldx files ----------------------------------------------------------------------------

WELDX_FILES = SHARED_DATA / "weldx-files"


@pytest.mark.skipif(not WELDX_FILES.is_dir(), reason="the weldx sample files are not here")
@pytest.mark.parametrize("name", ["absolute_time.asdf", "legacy_subsystems.asdf",
                                  "time_delta.asdf", "static_tree.asdf"])
def test_weldx_files_read_back(tmp_path, name):
    tree = pinframes.read(WELDX_FILES / name)
    for data in tree.data_names:
        tree.delete_data(data)
    union = tree.time_union()
    anchor = None if tree.reference_time is not None or (union and union.reference) \
        else np.datetime64("2024-01-01T00:00:00", "ns")
    pinframes.write(tree, tmp_path / "w.mcap", time_ref=anchor)
    records = decode(tmp_path / "w.mcap", "mcap")
    back = pinframes.read(tmp_path / "w.mcap")
    assert sorted(back.frames) == sorted(tree.frames)
    if union is None:
        for frame in tree.frames[1:]:
            np.testing.assert_allclose(back.pose(frame, tree.root).matrix,
                                       tree.pose(frame, tree.root).matrix, atol=1e-9)
        return
    start = int((anchor if anchor is not None else union.reference).astype(np.int64))
    stamps = sorted({row["stamp_ns"] for row in records["/tf"]})
    assert stamps == (union.offsets + start).tolist()
    for frame in tree.frames[1:]:
        expected = tree.pose(frame, tree.root, times=union.as_numpy())
        got = back.pose(frame, tree.root, times=np.array(stamps).astype("datetime64[ns]"))
        np.testing.assert_allclose(got.translation, expected.translation, atol=1e-9)
        np.testing.assert_allclose(got.rotation, expected.rotation, atol=1e-9)


# -- what cannot go into a bag ----------------------------------------------------------------


def test_a_failed_write_leaves_the_old_bag_and_no_temporaries(tmp_path, cell):
    path = tmp_path / "run.mcap"
    pinframes.write(_turntables(REFERENCE), path)
    before = path.read_bytes()
    tree = _turntables(REFERENCE)
    tree.assign_data("scan", np.zeros((2, 3)), "tip")
    with pytest.raises(pinframes.UnsupportedFeatureError, match="data"):
        pinframes.write(tree, path)
    slash = _turntables(REFERENCE)
    slash.add("/map", "world")
    with pytest.raises(pinframes.UnsupportedFeatureError, match="leading '/'") as caught:
        pinframes.write(slash, path)  # tf2 would read it back as 'map'
    assert caught.value.frame == "/map" and "run.mcap" in str(caught.value)
    assert path.read_bytes() == before
    assert sorted(os.listdir(tmp_path)) == ["run.mcap"]


def test_a_folder_that_is_no_bag_is_not_replaced(tmp_path):
    folder = tmp_path / "results"
    folder.mkdir()
    (folder / "notes.txt").write_text("keep me")
    with pytest.raises(pinframes.WriteError, match="not a ROS 2 bag"):
        pinframes.write(_turntables(REFERENCE), folder)
    assert (folder / "notes.txt").read_text() == "keep me"
    pinframes.write(_turntables(REFERENCE), tmp_path / "bag")
    pinframes.write(_turntables(None), tmp_path / "bag")  # a bag folder is replaced whole
    assert sorted(os.listdir(tmp_path / "bag")) == ["bag.mcap", "metadata.yaml"]
    assert pinframes.read(tmp_path / "bag").reference_time == np.datetime64(0, "ns")


@pytest.mark.parametrize("times", [[1.0, 0.5], [], "soon"])
def test_bad_times_are_refused_naming_the_bag_and_the_field(tmp_path, times):
    with pytest.raises(pinframes.InvalidTimeError) as caught:
        pinframes.write(_turntables(REFERENCE), tmp_path / "t.mcap", times=times)
    assert caught.value.field == "times" and "t.mcap" in str(caught.value)
    assert not list(tmp_path.iterdir())


def test_the_bundled_recording_rewritten_as_ros1_reads_back_the_same(tmp_path):
    """models/welding_cell/cell_run.mcap (written by rosbags, robot frames without the
    scene's prefix, stamps from 2024-03-01T08:00:00) through pinframes into a ROS 1 bag."""
    recording = pinframes.read(ROOT / "models" / "welding_cell" / "cell_run.mcap")
    pinframes.write(recording, tmp_path / "again.bag")
    union = recording.time_union()
    _check_round_trip(recording, tmp_path / "again.bag",
                      union.offsets + int(union.reference.astype(np.int64)))


def test_what_a_killed_writer_left_is_removed_by_the_next_write(tmp_path):
    """A writer killed mid-write leaves its scratch folder and temporary file (named with
    its process id); the next write in that folder removes them, as for every format."""
    import subprocess
    import sys

    finished = subprocess.run([sys.executable, "-c", "import os; print(os.getpid())"],
                              capture_output=True, text=True, check=True)
    dead = int(finished.stdout)
    (tmp_path / f".pinframes-{dead}-0a1b2c-scratch.tmp" / "bag").mkdir(parents=True)
    (tmp_path / f".pinframes-{dead}-0a1b2c-scratch.tmp" / "bag" / "bag.mcap").write_bytes(b"x")
    (tmp_path / f".pinframes-{dead}-3d4e5f.tmp").write_bytes(b"half a bag")
    pinframes.write(_turntables(REFERENCE), tmp_path / "t.mcap")
    assert sorted(os.listdir(tmp_path)) == ["t.mcap"]
