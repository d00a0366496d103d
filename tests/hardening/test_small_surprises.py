"""The smaller surprises of the second hardening round, each settled (README, "Hardening"):
an error naming the field, or a documented acceptance; never a silent guess."""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest

from pinframes import FrameTree, Joint, Mimic, Pose, read_asdf, read_frames_yaml
from pinframes.errors import FileFormatError, InvalidTimeError, JointError
from weldx_asdf.asdf_texts import asdf_text, lcs, legacy_hierarchy


def moving_tree() -> FrameTree:
    tree = FrameTree("w")
    tree.add("m", "w", Pose([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0]], times=[0.0, 10.0]))
    tree.add("5", "w")
    return tree


def test_a_string_naming_a_frame_is_that_frame_else_a_time():
    tree = moving_tree()
    # accepted: "4" names no frame, so it is 4 s (0.4 m along the 10 s, 1 m motion)
    np.testing.assert_allclose(tree.pose("m", "w", times="4").translation, [[0.4, 0.0, 0.0]])
    # "5" names a frame, which does not move: an error that says how to pass seconds
    with pytest.raises(InvalidTimeError, match="pass seconds as a number") as info:
        tree.pose("m", "w", times="5")
    assert info.value.field == "times"
    np.testing.assert_allclose(tree.pose("m", "w", times=5).translation, [[0.5, 0.0, 0.0]])


@pytest.mark.parametrize("unit", ["M", "Y"])
def test_durations_in_months_or_years_are_refused(unit):
    with pytest.raises(InvalidTimeError, match="no fixed length") as info:
        moving_tree().pose("m", "w", times=np.array([1], dtype=f"timedelta64[{unit}]"))
    assert info.value.field == "times"
    # a timestamp in months is one instant, and stays accepted
    pose = Pose([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0]],
                times=np.array(["2024-01", "2024-02"], dtype="datetime64[M]"))
    assert pose.reference_time == np.datetime64("2024-01-01T00:00:00", "ns")


@pytest.mark.parametrize("times", [[pd.NaT], [0.0, pd.NaT], pd.Series([pd.NaT])],
                         ids=["NaT", "number-and-NaT", "Series"])
def test_not_a_time_is_an_invalid_time(times):
    with pytest.raises(InvalidTimeError, match="NaT") as info:
        moving_tree().pose("m", "w", times=times)
    assert info.value.field == "times"


@pytest.mark.parametrize("axis", ["abc", None, [1.0, "x", 0.0], [0.0, 0.0]])
def test_a_joint_axis_that_is_no_vector_is_a_joint_error(axis):
    with pytest.raises(JointError) as info:
        Joint("j", "revolute", axis=axis)
    assert (info.value.joint, info.value.field) == ("j", "axis")


@pytest.mark.parametrize("multiplier", ["2", b"2", None, float("nan"), float("inf"), 1e200])
def test_a_mimic_multiplier_must_be_a_bounded_number(multiplier):
    with pytest.raises(JointError) as info:
        Mimic("j1", multiplier)
    assert info.value.field == "mimic.multiplier"
    assert Mimic("j1", np.float32(2.0)).multiplier == 2.0


def test_frames_added_while_iterating_do_not_break_the_iteration():
    tree = moving_tree()
    seen = []
    for name in tree:  # the names at the start; was a RuntimeError
        seen.append(name)
        if name == "w":
            tree.add("new", "w")
    assert seen == ["w", "m", "5"]
    assert list(tree) == ["w", "m", "5", "new"]


@pytest.mark.parametrize("value", ["1:30", "010", "-0:30:00.5", "00"])
def test_yaml_1_1_octal_and_base_60_numbers_are_refused(value, tmp_path):
    path = tmp_path / "frames.yaml"
    path.write_text(f"version: 1.0\nframes:\n  a: {{relative_to: ~, pose: {{x: {value}}}}}\n")
    with pytest.raises(FileFormatError, match="octal or base 60") as info:
        read_frames_yaml(path)
    assert info.value.file == str(path) and "line 3" in info.value.message
    path.write_text("version: 1.0\nframes:\n  a: {relative_to: ~, pose: {x: '010', y: 10, "
                    "z: 0}}\n")
    with pytest.raises(FileFormatError, match="expected a number"):
        read_frames_yaml(path)  # quoted, it is the string it looks like


@pytest.mark.filterwarnings("ignore:Invalid integer literal")  # asdf notes the same value
def test_asdf_unsigned_times_beyond_int64_are_refused(tmp_path):
    times = ("!legacy!time/timedeltaindex-1.0.0 {values: !core/ndarray-1.0.0 "
             "{data: [0, 18446744073709551615], datatype: uint64, shape: [2]}}")
    coordinates = lcs(version="1.0.0", coordinates=[[0.0, 0.0, 0.0], [1.0, 0.0, 0.0]],
                      time=times)
    path = tmp_path / "t.asdf"
    path.write_text(asdf_text(legacy_hierarchy("h", "root", [("a", "root", coordinates)])))
    with pytest.raises(FileFormatError, match="beyond int64") as info:
        read_asdf(path)
    assert info.value.frame == "a" and info.value.field.endswith("time.values")
