"""read_asdf on broken input: pinframes errors naming the file, the frame and the field."""

from __future__ import annotations

import numpy as np
import pytest

import pinframes
from weldx_asdf.asdf_texts import (
    digraph_hierarchy,
    digraph_node,
    lcs,
    legacy_hierarchy,
    time_values,
    write_asdf_text,
)

from geometry import rot_z

SECOND = 1_000_000_000


def one_edge(tmp_path, transformation, direction="bwd"):
    body = digraph_hierarchy("h", digraph_node("w", [(direction, transformation,
                                                      digraph_node("c"))]))
    return write_asdf_text(tmp_path / "bad.asdf", body)


def test_missing_file_and_folder_are_read_errors(tmp_path):
    with pytest.raises(pinframes.ReadError, match=r"nothing\.asdf: no such file"):
        pinframes.read_asdf(tmp_path / "nothing.asdf")
    with pytest.raises(OSError, match="folder"):
        pinframes.read_asdf(tmp_path)


def test_a_file_that_is_not_asdf(tmp_path):
    path = tmp_path / "text.asdf"
    path.write_text("just: yaml\n")
    with pytest.raises(pinframes.FileFormatError, match=r"text\.asdf: not a readable ASDF"):
        pinframes.read_asdf(path)


def test_a_file_without_hierarchy(tmp_path):
    path = write_asdf_text(tmp_path / "empty.asdf", "something: 1")
    with pytest.raises(pinframes.FileFormatError, match=r"empty\.asdf: no weldx coordinate"):
        pinframes.read_asdf(path)


@pytest.mark.parametrize(("transformation", "error", "field", "message"), [
    (lcs(orientations=[[1, 0, 0], [0, 1, 0], [0, 0.5, 1]]), pinframes.InvalidPoseError,
     "edge.attributes.transformation.orientations", "not orthonormal"),
    (lcs(orientations=np.diag([1.0, 1.0, -1.0])), pinframes.InvalidPoseError,
     "edge.attributes.transformation.orientations", "reflection"),
    (lcs(coordinates=[[0, 0, 0], [1, 0, 0]], time=time_values([SECOND, 0])),
     pinframes.InvalidTimeError, "edge.attributes.transformation.time", "strictly increasing"),
    (lcs(coordinates=[1, 0, 0], units="furlong"), pinframes.FileFormatError,
     "edge.attributes.transformation.coordinates.units", "unknown length unit 'furlong'"),
    (lcs(coordinates=[[0, 0, 0], [1, 0, 0]]), pinframes.FileFormatError,
     "edge.attributes.transformation", "'time' is missing"),
    (lcs(coordinates=[[0, 0, 0], [1, 0, 0]], time=time_values([0, 1, 2])),
     pinframes.InvalidPoseError, "edge.attributes.transformation.coordinates",
     "2 samples given for 3 times"),
])
def test_bad_transformations_name_file_frame_and_field(tmp_path, transformation, error, field,
                                                       message):
    with pytest.raises(error) as caught:
        pinframes.read_asdf(one_edge(tmp_path, transformation))
    assert (caught.value.file, caught.value.frame, caught.value.field) == (
        str(tmp_path / "bad.asdf"), "c", field)
    assert message in caught.value.message


def test_non_finite_coordinates(tmp_path):
    transformation = lcs(coordinates=[1, 2, 3]).replace("[1.0, 2.0, 3.0]", "[.nan, 2.0, 3.0]")
    with pytest.raises(pinframes.InvalidPoseError, match=r"frame 'c'.*coordinates.*finite"):
        pinframes.read_asdf(one_edge(tmp_path, transformation))


def test_a_fwd_edge_error_names_the_frame_it_leads_to(tmp_path):
    with pytest.raises(pinframes.InvalidPoseError, match=r"frame 'c'.*orientations"):
        pinframes.read_asdf(one_edge(tmp_path, lcs(orientations=2 * np.eye(3)), "fwd"))


def test_an_unknown_edge_direction(tmp_path):
    with pytest.raises(pinframes.FileFormatError, match=r"frame 'c'.*'edge\.direction'.*'up'"):
        pinframes.read_asdf(one_edge(tmp_path, lcs(), "up"))


def test_coordinates_as_a_math_expression_are_refused_clearly(tmp_path):
    series = ("!weldx!core/time_series-0.1.1 {expression: "
              "!weldx!core/mathematical_expression-0.1.0 {expression: a*t, parameters: {}}, "
              "units: !weldx!units/units-0.1.0 millimeter, shape: [3]}")
    transformation = ("!weldx!core/transformations/local_coordinate_system-0.1.1 "
                      f"{{coordinates: {series}}}")
    with pytest.raises(pinframes.UnsupportedFeatureError) as caught:
        pinframes.read_asdf(one_edge(tmp_path, transformation))
    assert caught.value.frame == "c"
    assert caught.value.field == "edge.attributes.transformation.coordinates"
    assert "'a*t'" in caught.value.message and "time_series" in caught.value.message


def test_legacy_required_field_missing(tmp_path):
    body = legacy_hierarchy("h", "w", []).replace("  root_system_name: w\n", "")
    with pytest.raises(pinframes.FileFormatError, match=r"'root_system_name' is missing"):
        pinframes.read_asdf(write_asdf_text(tmp_path / "no-root.asdf", body))


def test_legacy_entry_that_closes_a_loop(tmp_path):
    entries = [("a", "w", lcs(version="1.0.0")), ("b", "a", lcs(version="1.0.0")),
               ("b", "w", lcs(version="1.0.0"))]
    path = write_asdf_text(tmp_path / "loop.asdf", legacy_hierarchy("h", "w", entries))
    with pytest.raises(pinframes.FileFormatError, match=r"frame 'b'.*loop"):
        pinframes.read_asdf(path)


def test_legacy_entry_not_connected_to_the_root(tmp_path):
    entries = [("a", "w", lcs(version="1.0.0")), ("y", "x", lcs(version="1.0.0"))]
    path = write_asdf_text(tmp_path / "island.asdf", legacy_hierarchy("h", "w", entries))
    with pytest.raises(pinframes.FileFormatError,
                       match=r"frame 'y': field 'coordinate_systems\[1\]'.*not connected"):
        pinframes.read_asdf(path)


def test_mixed_frame_reference_times_without_a_tree_reference(tmp_path):
    with_reference = lcs(coordinates=[[0, 0, 0], [1, 0, 0]], time=time_values([0, SECOND]),
                         reference_time="2024-01-01T00:00:00")
    without = lcs(orientations=[np.eye(3), rot_z(0.1)], time=time_values([0, SECOND]))
    body = digraph_hierarchy("h", digraph_node("w", [("bwd", with_reference, digraph_node("a")),
                                                     ("bwd", without, digraph_node("b"))]))
    with pytest.raises(pinframes.ReferenceTimeError, match=r"mixed\.asdf: frame 'b'"):
        pinframes.read_asdf(write_asdf_text(tmp_path / "mixed.asdf", body))


def test_subsystem_naming_a_frame_the_hierarchy_lacks(tmp_path):
    body = digraph_hierarchy("h", digraph_node("w", [("bwd", lcs(), digraph_node("a"))]),
                             subsystems="[{name: s, common_node: w, root_node: a, "
                                        "members: [a, ghost]}]")
    with pytest.raises(pinframes.FileFormatError, match=r"frame 'ghost'.*subsystem 's'"):
        pinframes.read_asdf(write_asdf_text(tmp_path / "ghost.asdf", body))
