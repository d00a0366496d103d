"""read_asdf on the real weldx files of the shared data (skipped when absent).

Expected values are the raw numbers of each file, read here with plain asdf (weldx's tags
left raw), or derived by hand from the file's YAML.
"""

from __future__ import annotations

import warnings

import asdf
import numpy as np
import pytest

import pinframes
from conftest import SHARED_DATA
from pinframes.formats.asdf._asdf_config import temporary_asdf_config

from geometry import homogeneous

FILES = SHARED_DATA / "weldx-files"
SECOND = 1_000_000_000


def sample(name: str):
    path = FILES / name
    if not path.is_file():
        pytest.skip("shared sample data not present")
    return path


def raw_tree(path):
    """The file's YAML tree with plain asdf; arrays are copied while it is open."""
    def copy(node):
        if isinstance(node, dict):
            return {key: copy(value) for key, value in node.items()}
        if isinstance(node, list):
            return [copy(value) for value in node]
        if hasattr(node, "shape") and hasattr(node, "dtype"):
            return np.array(node)
        return node

    # raw data even where weldx is installed (CI runs these tests in weldx's environment)
    with temporary_asdf_config() as config, warnings.catch_warnings():
        config.remove_extension(package="weldx")
        warnings.simplefilter("ignore")
        with asdf.open(path, ignore_unrecognized_tag=True) as file:
            return copy(file.tree)


def matrix(pose, index=None):
    m = pose.matrix
    return m if index is None else m[index]


@pytest.mark.parametrize("name", sorted(p.name for p in FILES.glob("*.asdf"))
                         if FILES.is_dir() else ["absent.asdf"])
def test_every_sample_file_reads_with_its_name_and_without_warnings(name):
    path = sample(name)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        tree = pinframes.read_asdf(path)
    assert tree.name == raw_tree(path)["csm"]["name"]


def test_legacy_static_rebuilds_the_tree_from_the_root_and_inverts_swapped_entries():
    tree = pinframes.read_asdf(sample("legacy_static.asdf"))
    assert tree.root == "base"
    assert {f: tree.parent(f) for f in tree.frames[1:]} == {
        "fixture": "base", "workpiece": "base", "cam": "fixture", "tcp": "workpiece"}
    # The file stores base in fixture: R = Rz(90 deg), t = (0, 0, 10) mm.
    base_in_fixture = homogeneous(np.array([[0.0, -1, 0], [1, 0, 0], [0, 0, 1]]), [0, 0, 0.010])
    cam_in_fixture = homogeneous(np.array([[np.sqrt(0.5), 0, -np.sqrt(0.5)], [0, 1, 0],
                                           [np.sqrt(0.5), 0, np.sqrt(0.5)]]), [-0.020, 0, 0])
    np.testing.assert_allclose(matrix(tree.pose("cam", "base")),
                               np.linalg.inv(base_in_fixture) @ cam_in_fixture, atol=1e-12)


def test_legacy_subsystems_keep_names_members_and_nesting():
    tree = pinframes.read_asdf(sample("legacy_subsystems.asdf"))
    found = {s.name: (s.root, set(s.members), s.parent, s.subsystems) for s in tree.subsystems}
    assert found == {
        "robot": ("robot_base", {"flange", "robot_base", "tcp"}, "main", ("scanner",)),
        "clamp": ("workpiece", {"clamp1", "workpiece"}, "main", ()),
        "scanner": ("tcp", {"laser", "scanner", "tcp"}, "robot", ()),
    }


def test_legacy_subsystems_frequency_alias_s_gives_one_second_steps():
    path = sample("legacy_subsystems.asdf")
    tcp = pinframes.read_asdf(path).local_pose("tcp")
    np.testing.assert_array_equal(tcp.times.astype(np.int64), [0, SECOND, 2 * SECOND])
    entry = next(e for e in raw_tree(path)["csm"]["coordinate_systems"] if e["name"] == "tcp")
    np.testing.assert_allclose(tcp.translation,
                               entry["transformation"]["coordinates"]["data"] / 1000, atol=0)
    np.testing.assert_allclose(tcp.rotation, entry["transformation"]["orientations"]["data"],
                               atol=0)


def test_legacy_time_grid_500L_and_negative_start():
    tree = pinframes.read_asdf(sample("legacy_time.asdf"))
    np.testing.assert_array_equal(tree.local_pose("tool").times.astype(np.int64),
                                  np.arange(9) * SECOND // 2)
    np.testing.assert_array_equal(tree.local_pose("cam").times.astype(np.int64),
                                  [-SECOND, 2 * SECOND, 6 * SECOND])
    cam = tree.local_pose("cam")
    np.testing.assert_allclose(cam.translation, [[0, 0.1, 0]] * 3, atol=0)


@pytest.mark.parametrize(("legacy", "current"), [("legacy_time.asdf", "time_delta.asdf"),
                                                 ("legacy_static.asdf", "static_tree.asdf")])
def test_the_same_scene_in_two_generations_gives_the_same_poses(legacy, current):
    old = pinframes.read_asdf(sample(legacy))
    new = pinframes.read_asdf(sample(current))
    for frame in old.frames[1:]:
        a, b = old.pose(frame, old.root), new.pose(frame, new.root)
        np.testing.assert_allclose(b.matrix, a.matrix, atol=1e-12, err_msg=frame)
        assert (a.times is None) == (b.times is None)
        if a.times is not None:
            np.testing.assert_array_equal(a.times, b.times)


def test_static_tree_fwd_edge_and_identity():
    path = sample("static_tree.asdf")
    tree = pinframes.read_asdf(path)
    root_node = raw_tree(path)["csm"]["graph"]["root_node"]
    edge = root_node["edges"][0]
    assert edge["direction"] == "fwd" and edge["target_node"]["name"] == "fixture"
    stored = edge["attributes"]["transformation"]  # base in fixture
    base_in_fixture = homogeneous(stored["orientations"]["data"],
                                  stored["coordinates"]["data"] / 1000)
    np.testing.assert_allclose(matrix(tree.local_pose("fixture")),
                               np.linalg.inv(base_in_fixture), atol=1e-15)
    np.testing.assert_array_equal(matrix(tree.local_pose("identity_child")), np.eye(4))


def test_absolute_time_keeps_the_reference_times_of_the_tree_and_of_frames():
    path = sample("absolute_time.asdf")
    tree = pinframes.read_asdf(path)
    assert tree.reference_time == np.datetime64("2024-03-01T08:00:00")
    assert tree.local_pose("a").reference_time is None
    np.testing.assert_array_equal(tree.local_pose("a").times.astype(np.int64),
                                  [0, 10 * SECOND, 20 * SECOND])
    assert tree.local_pose("b").reference_time == np.datetime64("2024-03-01T08:00:05")
    np.testing.assert_array_equal(tree.local_pose("b").times.astype(np.int64),
                                  np.arange(4) * 4 * SECOND)
    edge_c = (raw_tree(path)["csm"]["graph"]["root_node"]["edges"][0]["target_node"]
              ["edges"][0]["target_node"]["edges"][0])
    assert edge_c["target_node"]["name"] == "c"
    stored = edge_c["attributes"]["transformation"]
    c = tree.local_pose("c")
    assert c.reference_time == np.datetime64("2024-03-01T07:59:58")
    np.testing.assert_array_equal(c.times.astype(np.int64), stored["time"]["values"])
    np.testing.assert_allclose(c.translation, stored["coordinates"]["data"] / 1000, atol=0)
    np.testing.assert_array_equal(c.rotation, np.broadcast_to(np.eye(3), (3, 3, 3)))
