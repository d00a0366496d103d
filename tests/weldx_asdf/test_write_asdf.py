"""write_asdf: the written YAML, checked field by field against the seed and weldx's files.

Expected numbers are hand-derived (millimetres = metres x 1000, nanoseconds from seconds);
the files are read back as raw YAML (``asdf.util.load_yaml``), never with pinframes' reader.
"""

from __future__ import annotations

import subprocess
import sys

import asdf
import asdf.util
import numpy as np
import pytest

import pinframes
from pinframes import (
    FrameTree,
    Joint,
    Pose,
    Subsystem,
    TreeStructureError,
    UnsupportedFeatureError,
    WriteError,
    write_asdf,
)

from geometry import rot_x, rot_z

LEGACY = "tag:weldx.bam.de:weldx/"
CURRENT = "asdf://weldx.bam.de/weldx/tags/"
KEY = "coordinate_system_hierarchy"


def hierarchy_of(path):
    """The hierarchy node of a written file, tags kept (``node._tag``)."""
    return asdf.util.load_yaml(str(path), tagged=True)[KEY]


def array(node):
    """An inline ``core/ndarray`` node as numpy."""
    assert node._tag.startswith("tag:stsci.edu:asdf/core/ndarray-1.")
    return np.asarray(node["data"]).reshape(node["shape"])


def seed_tree():
    """The seed schema's example: workpiece at the identity, tcp_wire moving along x."""
    tree = FrameTree("base", name="Coordinate system manager 0")
    tree.add("workpiece", "base")
    tree.add("tcp_wire", "workpiece",
             Pose([[0.005, 0.0, 0.002], [0.295, 0.0, 0.002]], rot_x(np.pi), times=[0.0, 29.0]))
    return tree


def test_the_default_is_the_schema_current_weldx_writes(tmp_path):
    write_asdf(seed_tree(), tmp_path / "seed.asdf")
    assert hierarchy_of(tmp_path / "seed.asdf")._tag == (
        CURRENT + "core/transformations/coordinate_system_hierarchy-0.1.0")


def test_schema_1_0_0_writes_the_seed_example(tmp_path):
    write_asdf(seed_tree(), tmp_path / "seed.asdf", schema="1.0.0")
    csm = hierarchy_of(tmp_path / "seed.asdf")
    assert csm._tag == LEGACY + "core/transformations/coordinate_system_hierarchy-1.0.0"
    assert list(csm) == ["name", "root_system_name", "subsystems", "coordinate_systems",
                         "subsystem_names"]
    assert (csm["name"], csm["root_system_name"]) == ("Coordinate system manager 0", "base")
    assert csm["subsystems"] == [] and csm["subsystem_names"] == []
    workpiece, tcp = csm["coordinate_systems"]
    for entry in (workpiece, tcp):
        assert entry._tag == LEGACY + "core/transformations/coordinate_transformation-1.0.0"
    assert (workpiece["name"], workpiece["reference_system"]) == ("workpiece", "base")
    assert workpiece["transformation"]._tag == (
        LEGACY + "core/transformations/local_coordinate_system-1.0.0")
    assert dict(workpiece["transformation"]) == {}
    assert (tcp["name"], tcp["reference_system"]) == ("tcp_wire", "workpiece")
    lcs = tcp["transformation"]
    assert list(lcs) == ["time", "orientations", "coordinates"]
    time = lcs["time"]
    assert time._tag == LEGACY + "time/timedeltaindex-1.0.0"
    assert list(time) == ["values", "start", "end", "min", "max"]
    np.testing.assert_array_equal(array(time["values"]), [0, 29_000_000_000])
    for field, text in (("start", "P0DT0H0M0S"), ("end", "P0DT0H0M29S"),
                        ("min", "P0DT0H0M0S"), ("max", "P0DT0H0M29S")):
        assert time[field]._tag == LEGACY + "time/timedelta-1.0.0"
        assert dict(time[field]) == {"value": text}
    orientations, coordinates = lcs["orientations"], lcs["coordinates"]
    assert orientations._tag == coordinates._tag == LEGACY + "core/variable-1.0.0"
    assert orientations["dimensions"] == ["c", "v"] and orientations["dtype"] == "<f8"
    np.testing.assert_allclose(array(orientations["data"]),
                               [[1, 0, 0], [0, -1, 0], [0, 0, -1]], atol=1e-15)
    assert coordinates["dimensions"] == ["time", "c"] and coordinates["name"] == "coordinates"
    assert "unit" not in coordinates and "units" not in coordinates  # millimetres, unitless
    np.testing.assert_allclose(array(coordinates["data"]), [[5, 0, 2], [295, 0, 2]],
                               rtol=1e-15)


def test_schema_0_1_0_writes_a_graph_as_weldx_0_8_does(tmp_path):
    write_asdf(seed_tree(), tmp_path / "graph.asdf", schema="0.1.0")
    csm = hierarchy_of(tmp_path / "graph.asdf")
    assert csm._tag == CURRENT + "core/transformations/coordinate_system_hierarchy-0.1.0"
    assert list(csm) == ["name", "graph", "subsystems"]
    assert csm["graph"]._tag == CURRENT + "core/graph/di_graph-0.1.0"
    root = csm["graph"]["root_node"]
    assert root._tag == CURRENT + "core/graph/di_node-0.1.0"
    assert (root["name"], root["attributes"]) == ("base", {"data": {}})
    (edge,) = root["edges"]
    assert edge._tag == CURRENT + "core/graph/di_edge-0.1.0"
    assert edge["direction"] == "bwd"  # the target (child) expressed in this node (parent)
    assert edge["attributes"]["defined"] is True
    assert dict(edge["attributes"]["transformation"]) == {}
    workpiece = edge["target_node"]
    assert workpiece["name"] == "workpiece"
    (edge,) = workpiece["edges"]
    leaf = edge["target_node"]
    assert leaf["name"] == "tcp_wire" and "edges" not in leaf
    lcs = edge["attributes"]["transformation"]
    assert lcs._tag == CURRENT + "core/transformations/local_coordinate_system-0.1.1"
    assert lcs["time"]._tag == CURRENT + "time/timedeltaindex-0.1.0"
    assert str(lcs["time"]["end"]) == "P0DT0H0M29S"
    assert lcs["time"]["end"]._tag == CURRENT + "time/timedelta-0.1.0"
    coordinates = lcs["coordinates"]
    assert coordinates._tag == CURRENT + "core/variable-0.1.1"
    assert str(coordinates["units"]) == "millimeter"
    assert coordinates["units"]._tag == CURRENT + "units/units-0.1.0"
    np.testing.assert_allclose(array(coordinates["data"]), [[5, 0, 2], [295, 0, 2]],
                               rtol=1e-15)


@pytest.mark.parametrize("schema", ["1.0.0", "0.1.0"])
def test_times_are_explicit_and_reference_times_are_written(tmp_path, schema):
    tree = FrameTree("world", name="cell", reference_time="2024-03-01T08:00:00")
    tree.add("cart", "world", Pose([[0.0, 0, 0], [1.0, 0, 0], [2.0, 0, 0]],
                                   times=[-1.0, 0.5, 2.0]))  # a regular grid: still values
    tree.add("cam", "world", Pose([[0.0, 0, 0], [0.0, 0, 0.1]],
                                  times=["2024-03-01T07:59:58", "2024-03-01T08:00:01.25"]))
    write_asdf(tree, tmp_path / "t.asdf", schema=schema)
    text = (tmp_path / "t.asdf").read_text(encoding="utf-8")
    assert "freq" not in text
    csm = hierarchy_of(tmp_path / "t.asdf")
    lcs = {}
    if schema == "1.0.0":
        assert dict(csm["reference_time"]) == {"value": "2024-03-01T08:00:00"}
        for entry in csm["coordinate_systems"]:
            assert entry["reference_system"] == "world"
            lcs[entry["name"]] = entry["transformation"]
        stamp = dict(lcs["cam"]["reference_time"])["value"]
        start = dict(lcs["cart"]["time"]["start"])["value"]
    else:
        assert str(csm["reference_time"]) == "2024-03-01T08:00:00"
        for edge in csm["graph"]["root_node"]["edges"]:
            lcs[edge["target_node"]["name"]] = edge["attributes"]["transformation"]
        stamp, start = str(lcs["cam"]["reference_time"]), str(lcs["cart"]["time"]["start"])
    assert "reference_time" not in lcs["cart"]  # counts from the tree's reference time
    assert stamp == "2024-03-01T07:59:58"
    assert start == "P-1DT23H59M59S"  # minus one second, as pandas writes it
    np.testing.assert_array_equal(array(lcs["cart"]["time"]["values"]),
                                  [-1_000_000_000, 500_000_000, 2_000_000_000])
    np.testing.assert_array_equal(array(lcs["cam"]["time"]["values"]), [0, 3_250_000_000])


@pytest.mark.parametrize("schema", ["1.0.0", "0.1.0"])
def test_same_tree_same_bytes(tmp_path, schema):
    tree = seed_tree()
    tree.add("long", "base", Pose(np.linspace([0, 0, 0], [1, 2, 3], 50),
                                  times=np.arange(50) * 0.1))  # big enough for a binary block
    write_asdf(tree, tmp_path / "a.asdf", schema=schema)
    write_asdf(seed_tree(), tmp_path / "b.asdf", schema=schema)
    write_asdf(tree, tmp_path / "b.asdf", schema=schema)
    first = (tmp_path / "a.asdf").read_bytes()
    assert first == (tmp_path / "b.asdf").read_bytes()
    assert b"BLK" in first  # the 50 x 3 coordinates went to a block
    head = asdf.util.load_yaml(str(tmp_path / "a.asdf"), tagged=True)
    assert set(head) == {"asdf_library", "history", KEY}
    assert all("software" in entry for entry in head["history"]["extensions"])


@pytest.mark.parametrize("schema", ["1.0.0", "0.1.0"])
def test_a_tree_holding_only_its_root_is_writable(tmp_path, schema):
    write_asdf(FrameTree("alone"), tmp_path / "root.asdf", schema=schema)
    csm = hierarchy_of(tmp_path / "root.asdf")
    assert csm["name"] == "pinframes"  # the name of a tree without one
    if schema == "1.0.0":
        assert (csm["root_system_name"], csm["coordinate_systems"]) == ("alone", [])
    else:
        assert dict(csm["graph"]["root_node"]) == {"name": "alone", "attributes": {"data": {}}}


def test_unknown_schema_is_refused(tmp_path):
    with pytest.raises(UnsupportedFeatureError, match=r"schema.*'0\.1\.0'"):
        write_asdf(seed_tree(), tmp_path / "x.asdf", schema="0.1.1")
    with pytest.raises(TypeError, match="FrameTree"):
        write_asdf("not a tree", tmp_path / "x.asdf")
    assert list(tmp_path.iterdir()) == []


def test_static_parts_have_no_time_dimension(tmp_path):
    tree = FrameTree("world")
    turns = np.stack([rot_z(angle) for angle in (0.0, 0.5, 1.0)])
    tree.add("turning", "world", Pose([0.1, 0.2, 0.3], turns, times=[0, 1, 2]))
    tree.add("still", "world", Pose([[0.0, 0, 0], [0.0, 0, 0]], times=[0, 1]))
    write_asdf(tree, tmp_path / "p.asdf", schema="1.0.0")
    turning, still = (entry["transformation"]
                      for entry in hierarchy_of(tmp_path / "p.asdf")["coordinate_systems"])
    assert turning["orientations"]["dimensions"] == ["time", "c", "v"]
    assert turning["coordinates"]["dimensions"] == ["c"]
    np.testing.assert_allclose(array(turning["coordinates"]["data"]), [100, 200, 300])
    np.testing.assert_allclose(array(turning["orientations"]["data"])[2], rot_z(1.0),
                               atol=1e-15)
    assert "orientations" not in still  # the identity is left out
    assert still["coordinates"]["dimensions"] == ["time", "c"]  # keeps the frame moving


def joint_tree():
    """A turntable on a revolute z joint 0.5 m above the base, and a link without motion."""
    tree = FrameTree("base", reference_time="2024-03-01T08:00:00")
    tree.attach_joint("table", "base", Joint("turn", "revolute", (0.0, 0.0, 1.0)),
                      Pose([0.0, 0.0, 0.5]))
    tree.attach_joint("arm", "table", Joint("lift", "prismatic", (0.0, 0.0, 1.0)))
    tree.set_joint_trajectory([0.0, 1.0, 2.0], [[0.0], [1.5], [3.0]], ["turn"])
    return tree


@pytest.mark.parametrize("schema", ["1.0.0", "0.1.0"])
def test_joint_driven_links_become_sampled_frames(tmp_path, schema):
    with pytest.warns(UserWarning, match="'lift' has no samples"):
        write_asdf(joint_tree(), tmp_path / "j.asdf", schema=schema)
    csm = hierarchy_of(tmp_path / "j.asdf")
    if schema == "1.0.0":
        table, arm = (entry["transformation"] for entry in csm["coordinate_systems"])
    else:
        edge = csm["graph"]["root_node"]["edges"][0]
        table = edge["attributes"]["transformation"]
        arm = edge["target_node"]["edges"][0]["attributes"]["transformation"]
    np.testing.assert_array_equal(array(table["time"]["values"]), [0, 1e9, 2e9])
    expected = np.stack([rot_z(angle) for angle in (0.0, 1.5, 3.0)])
    np.testing.assert_allclose(array(table["orientations"]["data"]), expected, atol=1e-15)
    np.testing.assert_allclose(array(table["coordinates"]["data"]), [0, 0, 500])
    assert dict(arm) == {}  # a joint without trajectory: its origin, static


def test_half_turn_joint_steps_are_refused_and_the_old_file_kept(tmp_path):
    path = tmp_path / "j.asdf"
    path.write_bytes(b"old")
    tree = joint_tree()
    tree.set_joint_trajectory([0.0, 1.0], [[0.0], [np.pi]], ["turn"])
    with pytest.raises(UnsupportedFeatureError, match="half a turn") as caught:
        write_asdf(tree, path)
    assert caught.value.frame == "table"
    assert path.read_bytes() == b"old"


def test_a_failing_write_leaves_the_existing_file(tmp_path, monkeypatch):
    path = tmp_path / "keep.asdf"
    path.write_bytes(b"old")

    def broken_write(self, handle, **kwargs):
        handle.write(b"#ASDF half")
        raise OSError("disk full")

    monkeypatch.setattr(asdf.AsdfFile, "write_to", broken_write)
    with pytest.raises(OSError, match="disk full"):
        write_asdf(seed_tree(), path)
    assert path.read_bytes() == b"old"
    assert [p.name for p in tmp_path.iterdir()] == ["keep.asdf"]


def subsystem_tree():
    """main <- robot (which nests scanner) and clamp, as in weldx's legacy sample."""
    tree = FrameTree("base", name="main", reference_time="2024-03-01T08:00:00")
    for name, parent in (("robot_base", "base"), ("tcp", "robot_base"), ("flange", "tcp"),
                         ("scanner", "tcp"), ("laser", "scanner"), ("workpiece", "base"),
                         ("clamp1", "workpiece")):
        tree.add(name, parent, Pose([0.0, 0.0, 0.01]))
    tree.subsystems = [
        Subsystem("robot", "robot_base", ("flange", "robot_base", "tcp"), "main",
                  np.datetime64("2024-03-01T07:00:00"), ("scanner",)),
        Subsystem("clamp", "workpiece", ("clamp1", "workpiece"), "main"),
        Subsystem("scanner", "tcp", ("laser", "scanner", "tcp"), "robot"),
    ]
    return tree


def test_legacy_subsystems_are_flattened(tmp_path):
    write_asdf(subsystem_tree(), tmp_path / "s.asdf", schema="1.0.0")
    csm = hierarchy_of(tmp_path / "s.asdf")
    assert csm["subsystem_names"] == ["robot", "clamp"]  # attached directly
    robot, clamp, scanner = csm["subsystems"]
    assert robot._tag == (LEGACY + "core/transformations/"
                          "coordinate_system_hierarchy_subsystem-1.0.0")
    assert dict(robot) == {
        "name": "robot", "parent_system": "main",
        "reference_time": robot["reference_time"], "root_cs": "robot_base",
        "members": ["flange", "robot_base", "tcp"], "subsystem_names": ["scanner"]}
    assert dict(robot["reference_time"]) == {"value": "2024-03-01T07:00:00"}
    assert (clamp["name"], clamp["subsystem_names"]) == ("clamp", [])
    assert (scanner["name"], scanner["parent_system"], scanner["root_cs"]) == (
        "scanner", "robot", "tcp")


def test_current_subsystems_are_nested(tmp_path):
    write_asdf(subsystem_tree(), tmp_path / "s.asdf", schema="0.1.0")
    robot, clamp = hierarchy_of(tmp_path / "s.asdf")["subsystems"]
    assert robot == {"name": "robot", "root_node": "robot_base", "common_node": "robot_base",
                     "reference_time": robot["reference_time"],
                     "members": ["flange", "robot_base", "tcp"], "data": [],
                     "subsystems": [robot["subsystems"][0]]}
    assert robot["reference_time"]._tag == CURRENT + "time/timestamp-0.1.0"
    assert str(robot["reference_time"]) == "2024-03-01T07:00:00"
    assert robot["subsystems"][0]["name"] == "scanner"
    assert robot["subsystems"][0]["members"] == ["laser", "scanner", "tcp"]
    assert (clamp["name"], clamp["subsystems"]) == ("clamp", [])


@pytest.mark.parametrize("nested", [("ghost",), ("robot",)])
def test_subsystems_that_do_not_nest_as_a_forest_are_refused(tmp_path, nested):
    tree = subsystem_tree()
    scanner = tree.subsystems[2]
    tree.subsystems[2] = Subsystem(scanner.name, scanner.root, scanner.members, "robot",
                                   None, nested)  # unknown, or robot <-> scanner cycle
    with pytest.raises(TreeStructureError, match="subsystem"):
        write_asdf(tree, tmp_path / "s.asdf", schema="0.1.0")
    assert not (tmp_path / "s.asdf").exists()


def test_an_invalid_hierarchy_fails_validation_before_writing(tmp_path):
    from pinframes.formats.asdf._encode import LEGACY as generation
    from pinframes.formats.asdf._encode import tagged
    from pinframes.formats.asdf._writer import _write

    broken = tagged(generation, "core/transformations/coordinate_system_hierarchy",
                    {"name": "x", "coordinate_systems": []})  # no root_system_name
    with pytest.raises(WriteError, match="root_system_name"):
        _write(broken, generation, tmp_path / "x.asdf", KEY)
    assert not (tmp_path / "x.asdf").exists()


def test_importing_pinframes_does_not_import_asdf():
    code = ("import sys, pinframes; assert 'asdf' not in sys.modules; "
            "pinframes.write_asdf; assert 'asdf' in sys.modules")
    subprocess.run([sys.executable, "-c", code], check=True)
    assert "write_asdf" in pinframes.__all__
    with pytest.raises(AttributeError):
        pinframes.no_such_function  # noqa: B018
