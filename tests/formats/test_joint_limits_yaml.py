"""MoveIt ``joint_limits.yaml`` files: moveit_resources' own, and broken ones named precisely."""

from __future__ import annotations

from pathlib import Path

import pytest
import yaml

import pinframes
from pinframes.errors import FileFormatError, ReadError

DATA = Path(__file__).resolve().parents[1] / "data" / "moveit_resources"


def test_the_fanuc_limits_of_moveit_resources():
    limits = pinframes.read_joint_limits(DATA / "fanuc_joint_limits.yaml")
    assert list(limits) == [f"joint_{index}" for index in range(1, 7)]
    assert limits["joint_2"] == pinframes.JointRateLimits(3.32, 0.664, None)
    assert limits["joint_6"].velocity == 10.47 and limits["joint_6"].jerk is None


def test_the_panda_limits_agree_with_plain_yaml():
    path = DATA / "panda_joint_limits.yaml"
    limits = pinframes.read_joint_limits(path)
    entries = yaml.safe_load(path.read_text())["joint_limits"]
    assert set(limits) == set(entries)
    for name, entry in entries.items():
        assert limits[name] == pinframes.JointRateLimits(
            entry["max_velocity"], entry["max_acceleration"], entry["max_jerk"])
    with pytest.raises(TypeError):
        limits["panda_joint1"] = limits["panda_joint2"]  # type: ignore[index]


def test_a_limit_switched_off_is_none_even_with_a_value(tmp_path):
    path = tmp_path / "joint_limits.yaml"
    path.write_text("joint_limits:\n  a:\n    has_velocity_limits: false\n    max_velocity: 2\n"
                    "    has_acceleration_limits: true\n    max_acceleration: 3\n  b: {}\n")
    limits = pinframes.read_joint_limits(path)
    assert limits["a"] == pinframes.JointRateLimits(None, 3.0, None)
    assert limits["b"] == pinframes.JointRateLimits()


@pytest.mark.parametrize(("entry", "field", "message"), [
    ("has_acceleration_limits: true", "max_acceleration", "missing"),
    ("has_velocity_limits: true\n    max_velocity: -1", "max_velocity", "> 0"),
    ("has_jerk_limits: true\n    max_jerk: .nan", "max_jerk", "finite"),
    ("has_jerk_limits: true\n    max_jerk: fast", "max_jerk", "number"),
    ("has_velocity_limits: yes please", "has_velocity_limits", "true or false"),
])
def test_a_bad_limit_names_the_file_joint_and_field(tmp_path, entry, field, message):
    path = tmp_path / "limits.yaml"
    path.write_text(f"joint_limits:\n  elbow:\n    {entry}\n")
    with pytest.raises(FileFormatError, match=message) as caught:
        pinframes.read_joint_limits(path)
    assert (caught.value.file, caught.value.joint, caught.value.field) == (
        str(path), "elbow", field)


def test_files_that_are_not_joint_limits(tmp_path):
    path = tmp_path / "limits.yaml"
    path.write_text("joints:\n  a: {}\n")
    with pytest.raises(FileFormatError, match="joint_limits") as caught:
        pinframes.read_joint_limits(path)
    assert caught.value.file == str(path)
    path.write_text("joint_limits:\n  a: 3\n")
    with pytest.raises(FileFormatError, match="mapping") as caught:
        pinframes.read_joint_limits(path)
    assert caught.value.joint == "a"
    path.write_text("joint_limits:\n  a: {}\n  a: {}\n")
    with pytest.raises(FileFormatError, match="duplicate key"):
        pinframes.read_joint_limits(path)
    path.write_text("joint_limits: !!python/object:os.system {}\n")
    with pytest.raises(FileFormatError):
        pinframes.read_joint_limits(path)
    with pytest.raises(ReadError):
        pinframes.read_joint_limits(tmp_path / "missing.yaml")
