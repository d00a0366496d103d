"""read_asdf on small hand-written weldx files, one feature each; expected values by hand."""

from __future__ import annotations

import subprocess
import sys

import asdf
import numpy as np
import pytest
from asdf.tagged import TaggedDict

import pinframes
from pinframes.formats.asdf._extension import bound_schemas
from weldx_asdf.asdf_texts import (
    digraph_hierarchy,
    digraph_node,
    lcs,
    legacy_hierarchy,
    time_grid,
    time_values,
    write_asdf_text,
)

from geometry import homogeneous, rot_x, rot_z

SECOND = 1_000_000_000
QUARTER_TURN = rot_z(np.pi / 2)


def test_importing_pinframes_does_not_import_asdf():
    code = "import sys, pinframes; assert 'asdf' not in sys.modules; pinframes.read_asdf"
    subprocess.run([sys.executable, "-c", code], check=True)


def test_legacy_entries_in_any_order_with_a_parent_in_child_entry(tmp_path):
    # root w; b in w; the edge a-b is stored as b in a (defined parent-in-child), listed first.
    path = write_asdf_text(tmp_path / "legacy.asdf", legacy_hierarchy("cell", "w", [
        ("b", "a", lcs(orientations=QUARTER_TURN, coordinates=[10, 0, 0], version="1.0.0")),
        ("b", "w", lcs(coordinates=[0, 0, 1000], version="1.0.0")),
    ]))
    tree = pinframes.read_asdf(path)
    assert (tree.name, tree.root, tree.parent("b"), tree.parent("a")) == ("cell", "w", "w", "b")
    a_in_b = np.linalg.inv(homogeneous(QUARTER_TURN, [0.010, 0, 0]))
    np.testing.assert_allclose(tree.local_pose("a").matrix, a_in_b, atol=1e-15)
    np.testing.assert_allclose(tree.pose("a", "w").matrix,
                               homogeneous(np.eye(3), [0, 0, 1.0]) @ a_in_b, atol=1e-15)


def test_fwd_edge_holds_the_parent_in_the_child(tmp_path):
    node = digraph_node("w", [("fwd", lcs(orientations=rot_x(0.3), coordinates=[1, 2, 3]),
                                digraph_node("c"))])
    tree = pinframes.read_asdf(write_asdf_text(tmp_path / "fwd.asdf",
                                               digraph_hierarchy("h", node)))
    np.testing.assert_allclose(tree.local_pose("c").matrix,
                               np.linalg.inv(homogeneous(rot_x(0.3), [0.001, 0.002, 0.003])),
                               atol=1e-15)


@pytest.mark.parametrize(("freq", "end", "count", "step_ns"), [
    ("500L", "P0DT0H0M2S", 5, SECOND // 2), ("500ms", "P0DT0H0M2S", 5, SECOND // 2),
    ("S", "P0DT0H0M2S", 3, SECOND), ("10s", "P0DT0H0M20S", 3, 10 * SECOND),
    ("T", "P0DT0H2M0S", 3, 60 * SECOND), ("2min", "P0DT0H4M0S", 3, 120 * SECOND),
    ("H", "P0DT2H0M0S", 3, 3600 * SECOND), ("250U", "P0DT0H0M0.001S", 5, 250_000),
    ("100N", "P0DT0H0M0.0000004S", 5, 100), ("20us", "P0DT0H0M0.00008S", 5, 20_000),
    ("3s", "P0DT0H0M7S", 3, 3 * SECOND),  # the end is not on the grid: the grid stops at 6 s
])
@pytest.mark.parametrize("legacy", [False, True])
def test_regular_grids_with_old_and_new_pandas_frequencies(tmp_path, freq, end, count, step_ns,
                                                            legacy):
    version = "1.0.0" if legacy else "0.1.1"
    transformation = lcs(coordinates=np.arange(count * 3).reshape(count, 3),
                         time=time_grid("P0DT0H0M0S", end, freq, legacy=legacy),
                         version=version)
    if legacy:
        body = legacy_hierarchy("h", "w", [("c", "w", transformation)])
    else:
        body = digraph_hierarchy("h", digraph_node("w", [("bwd", transformation,
                                                           digraph_node("c"))]))
    tree = pinframes.read_asdf(write_asdf_text(tmp_path / "grid.asdf", body))
    np.testing.assert_array_equal(tree.local_pose("c").times.astype(np.int64),
                                  np.arange(count) * step_ns)


def test_negative_durations_and_explicit_values(tmp_path):
    grid = lcs(coordinates=[[0, 0, 0], [3, 0, 0], [6, 0, 0]],
               time=time_grid("P-1DT23H59M59S", "P0DT0H0M1S", "1s"))
    explicit = lcs(coordinates=[[0, 0, 0], [0, 3, 0]], time=time_values([-2 * SECOND, 5]))
    body = digraph_hierarchy("h", digraph_node("w", [("bwd", grid, digraph_node("g")),
                                                     ("bwd", explicit, digraph_node("v"))]))
    tree = pinframes.read_asdf(write_asdf_text(tmp_path / "negative.asdf", body))
    np.testing.assert_array_equal(tree.local_pose("g").times.astype(np.int64),
                                  [-SECOND, 0, SECOND])
    np.testing.assert_array_equal(tree.local_pose("v").times.astype(np.int64), [-2 * SECOND, 5])
    # Halfway between -1 s and 0 s the grid frame is halfway between 0 and 3 mm.
    np.testing.assert_allclose(tree.pose("g", "w", times=[-0.5]).translation,
                               [[0.0015, 0, 0]], atol=1e-15)


@pytest.mark.parametrize(("units", "metres"), [("inch", 0.0254), ("meter", 1.0),
                                               ("centimeter", 0.01), ("micrometer", 1e-6),
                                               ("millimeter", 1e-3), (None, 1e-3)])
def test_coordinate_units_become_metres(tmp_path, units, metres):
    body = digraph_hierarchy("h", digraph_node("w", [
        ("bwd", lcs(coordinates=[1, -2, 4], units=units), digraph_node("c"))]))
    tree = pinframes.read_asdf(write_asdf_text(tmp_path / "units.asdf", body))
    np.testing.assert_allclose(tree.local_pose("c").translation,
                               np.array([1, -2, 4]) * metres, rtol=1e-15)


@pytest.mark.parametrize("version", ["0.1.0", "1.0.0"])
def test_unitless_generations_are_millimetres(tmp_path, version):
    transformation = lcs(coordinates=[7, 0, 0], version=version)
    if version == "1.0.0":
        body = legacy_hierarchy("h", "w", [("c", "w", transformation)])
    else:
        body = digraph_hierarchy("h", digraph_node("w", [("bwd", transformation,
                                                          digraph_node("c"))]))
    tree = pinframes.read_asdf(write_asdf_text(tmp_path / "mm.asdf", body))
    np.testing.assert_allclose(tree.local_pose("c").translation, [0.007, 0, 0], rtol=1e-15)


def test_identity_and_broadcast_of_a_static_part(tmp_path):
    moving = lcs(orientations=QUARTER_TURN, coordinates=[[0, 0, 0], [2, 0, 0]],
                 time=time_values([0, SECOND]))
    turning = lcs(orientations=[np.eye(3), QUARTER_TURN], coordinates=[5, 0, 0],
                  time=time_values([0, SECOND]))
    body = digraph_hierarchy("h", digraph_node("w", [
        ("bwd", lcs(), digraph_node("same")), ("bwd", moving, digraph_node("m")),
        ("bwd", turning, digraph_node("t"))]))
    tree = pinframes.read_asdf(write_asdf_text(tmp_path / "parts.asdf", body))
    np.testing.assert_array_equal(tree.local_pose("same").matrix, np.eye(4))
    np.testing.assert_allclose(tree.local_pose("m").rotation, [QUARTER_TURN] * 2, atol=0)
    np.testing.assert_allclose(tree.local_pose("t").translation, [[0.005, 0, 0]] * 2, atol=0)


def test_reference_times_of_the_hierarchy_and_of_single_frames(tmp_path):
    late = lcs(coordinates=[[0, 0, 0], [1, 0, 0]], time=time_values([0, SECOND]),
               reference_time="2024-03-01T08:00:05")
    plain = lcs(coordinates=[[0, 0, 0], [1, 0, 0]], time=time_values([0, SECOND]))
    body = digraph_hierarchy("h", digraph_node("w", [("bwd", late, digraph_node("late")),
                                                     ("bwd", plain, digraph_node("plain"))]),
                             reference_time="2024-03-01T08:00:00")
    tree = pinframes.read_asdf(write_asdf_text(tmp_path / "refs.asdf", body))
    assert tree.reference_time == np.datetime64("2024-03-01T08:00:00")
    assert tree.local_pose("late").reference_time == np.datetime64("2024-03-01T08:00:05")
    assert tree.local_pose("plain").reference_time is None
    # 08:00:05.5 is halfway through the late frame's motion.
    pose = tree.pose("late", "w", times=[np.datetime64("2024-03-01T08:00:05.5")])
    np.testing.assert_allclose(pose.translation, [[0.0005, 0, 0]], atol=1e-15)


def test_legacy_reference_time_objects(tmp_path):
    moving = lcs(coordinates=[[0, 0, 0], [1, 0, 0]], time=time_values([0, SECOND], legacy=True),
                 reference_time="2020-01-01T00:00:01", version="1.0.0")
    path = write_asdf_text(tmp_path / "legacy-refs.asdf", legacy_hierarchy(
        "h", "w", [("c", "w", moving)], reference_time="2020-01-01T00:00:00"))
    tree = pinframes.read_asdf(path)
    assert tree.reference_time == np.datetime64("2020-01-01T00:00:00")
    assert tree.local_pose("c").reference_time == np.datetime64("2020-01-01T00:00:01")


def test_arrays_in_binary_blocks_read_like_inline_ones(tmp_path):
    rotations = np.stack([rot_z(0.1 * k) for k in range(4)])
    coordinates = np.arange(12.0).reshape(4, 3)
    times = np.arange(4, dtype=np.int64) * SECOND

    def tagged(tag, content):
        return TaggedDict(content, f"asdf://weldx.bam.de/weldx/tags/{tag}")

    transformation = tagged("core/transformations/local_coordinate_system-0.1.1", {
        "time": tagged("time/timedeltaindex-0.1.0", {"values": times}),
        "orientations": tagged("core/variable-0.1.1", {
            "name": "orientations", "dimensions": ["time", "c", "v"], "dtype": "<f8",
            "data": rotations}),
        "coordinates": tagged("core/variable-0.1.1", {
            "name": "coordinates", "dimensions": ["time", "c"], "dtype": "<f8",
            "data": coordinates})})
    edge = tagged("core/graph/di_edge-0.1.0", {
        "direction": "bwd", "attributes": {"defined": True, "transformation": transformation},
        "target_node": tagged("core/graph/di_node-0.1.0", {"name": "c",
                                                           "attributes": {"data": {}}})})
    hierarchy = tagged("core/transformations/coordinate_system_hierarchy-0.1.0", {
        "name": "blocks", "graph": tagged("core/graph/di_graph-0.1.0", {
            "root_node": tagged("core/graph/di_node-0.1.0", {
                "name": "w", "attributes": {"data": {}}, "edges": [edge]})})})
    path = tmp_path / "blocks.asdf"
    with bound_schemas():  # pinframes' schemas, not weldx's (if installed), check the write
        asdf.AsdfFile({"deep": {"inside": [hierarchy]}}).write_to(path)
    assert b"source: 0" in path.read_bytes()
    tree = pinframes.read_asdf(path)
    pose = tree.local_pose("c")
    np.testing.assert_array_equal(pose.rotation, rotations)
    np.testing.assert_allclose(pose.translation, coordinates / 1000, rtol=1e-15)
    np.testing.assert_array_equal(pose.times.astype(np.int64), times)


def test_nested_subsystems_of_the_current_format(tmp_path):
    subsystems = ("[{name: robot, common_node: base, root_node: robot_base, "
                  "members: [base, robot_base, tcp], data: [], "
                  "reference_time: !weldx!time/timestamp-0.1.0 '2024-01-01T00:00:00', "
                  "subsystems: [{name: scanner, common_node: tcp, root_node: scanner, "
                  "members: [scanner, tcp], data: [], subsystems: []}]}, "
                  "{name: clamp, common_node: base, root_node: clamp, members: [base, clamp]}]")
    node = digraph_node("base", [
        ("bwd", lcs(), digraph_node("robot_base", [
            ("bwd", lcs(), digraph_node("tcp", [("bwd", lcs(), digraph_node("scanner"))]))])),
        ("bwd", lcs(), digraph_node("clamp"))])
    tree = pinframes.read_asdf(write_asdf_text(
        tmp_path / "subsystems.asdf", digraph_hierarchy("main", node, subsystems=subsystems)))
    assert [(s.name, s.root, s.members, s.parent, s.subsystems) for s in tree.subsystems] == [
        ("robot", "base", ("base", "robot_base", "tcp"), "main", ("scanner",)),
        ("scanner", "tcp", ("scanner", "tcp"), "robot", ()),
        ("clamp", "base", ("base", "clamp"), "main", ()),
    ]
    assert tree.subsystems[0].reference_time == np.datetime64("2024-01-01T00:00:00")


def test_a_hierarchy_holding_only_its_root(tmp_path):
    tree = pinframes.read_asdf(write_asdf_text(tmp_path / "root.asdf",
                                               legacy_hierarchy("alone", "w", [])))
    assert tree.frames == ["w"]


def test_several_hierarchies_need_a_key_which_may_be_nested(tmp_path):
    first = digraph_hierarchy("first", digraph_node("w", [("bwd", lcs(), digraph_node("a"))]))
    second = digraph_hierarchy("second", digraph_node("v", [("bwd", lcs(), digraph_node("b"))]),
                               key="second")
    body = first + "\nnested:\n" + "\n".join("  " + line for line in second.splitlines())
    path = write_asdf_text(tmp_path / "two.asdf", body)
    with pytest.raises(pinframes.FileFormatError, match=r"'csm', 'nested/second'.*key="):
        pinframes.read_asdf(path)
    assert pinframes.read_asdf(path, key="csm").name == "first"
    assert pinframes.read_asdf(path, key="nested/second").frames == ["v", "b"]
    with pytest.raises(pinframes.FileFormatError, match=r"two\.asdf: .*'missing'.*'csm'"):
        pinframes.read_asdf(path, key="missing")
