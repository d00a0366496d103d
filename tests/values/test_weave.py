"""Pose.weave against the definitions of docs/welding-process.md, written out here by hand;
a torch weaving over a seam; the scene's weave entry, read and written."""

import numpy as np
import pytest
import yaml

from pinframes import (
    FrameTree,
    InvalidPoseError,
    InvalidTimeError,
    Pose,
    Weave,
    read_scene,
    write_scene,
)
from pinframes.errors import FileFormatError

from geometry import rot_x

AMPLITUDE, FREQUENCY = 0.003, 2.0  # 3 mm at 2 Hz: a period of 0.5 s


def at_phases(pattern, phases, **options):
    """The weave's offsets at the given fractions of its period (times phase / f)."""
    times = np.asarray(phases) / FREQUENCY
    return Pose.weave(AMPLITUDE, FREQUENCY, times=times, pattern=pattern, **options).translation


def test_triangle_by_hand():
    # up to A at a quarter period, down through 0 at a half to -A at three quarters
    phases = [0.0, 0.125, 0.25, 0.375, 0.5, 0.625, 0.75, 0.875, 1.0, 1.25, 2.75]
    across = [0.0, 0.5, 1.0, 0.5, 0.0, -0.5, -1.0, -0.5, 0.0, 1.0, -1.0]
    offsets = at_phases("triangle", phases)
    np.testing.assert_allclose(offsets[:, 1], AMPLITUDE * np.array(across), atol=1e-15)
    np.testing.assert_array_equal(offsets[:, [0, 2]], 0.0)


def test_sine_by_hand():
    phases = np.linspace(0.0, 3.0, 37)
    offsets = at_phases("sine", phases)
    np.testing.assert_allclose(offsets[:, 1], AMPLITUDE * np.sin(2 * np.pi * phases),
                               atol=1e-15)
    np.testing.assert_array_equal(offsets[:, [0, 2]], 0.0)


def test_trapezoid_dwells_at_the_edges_for_its_fraction():
    """dwell 0.2: the ramp reaches A at phase (1 - 0.2) / 4 = 0.2, holds to 0.3, crosses 0 at
    0.5, holds -A from 0.7 to 0.8, is back at 0 at 1."""
    phases = [0.0, 0.1, 0.2, 0.25, 0.3, 0.4, 0.5, 0.6, 0.7, 0.75, 0.8, 0.9, 1.0]
    across = [0.0, 0.5, 1.0, 1.0, 1.0, 0.5, 0.0, -0.5, -1.0, -1.0, -1.0, -0.5, 0.0]
    offsets = at_phases("trapezoid", phases, dwell=0.2)
    np.testing.assert_allclose(offsets[:, 1], AMPLITUDE * np.array(across), atol=1e-15)


def test_circle_by_hand():
    phases = np.linspace(0.0, 2.0, 25)
    offsets = at_phases("circle", phases)
    np.testing.assert_allclose(offsets[:, 0], AMPLITUDE * np.cos(2 * np.pi * phases),
                               atol=1e-15)
    np.testing.assert_allclose(offsets[:, 1], AMPLITUDE * np.sin(2 * np.pi * phases),
                               atol=1e-15)
    np.testing.assert_array_equal(offsets[:, 2], 0.0)


def test_a_weave_starts_on_the_centre_line_at_its_first_time():
    pose = Pose.weave(AMPLITUDE, FREQUENCY, times=[10.0, 10.125, 10.25],
                      reference_time="2024-03-01T08:00:00")
    np.testing.assert_allclose(pose.translation[:, 1], [0.0, AMPLITUDE, 0.0], atol=1e-15)
    assert pose.reference_time == np.datetime64("2024-03-01T08:00:00")
    np.testing.assert_allclose(pose.seconds, [10.0, 10.125, 10.25])
    np.testing.assert_array_equal(pose.rotation, np.broadcast_to(np.eye(3), (3, 3, 3)))
    assert pose.weaving == Weave(AMPLITUDE, FREQUENCY, "triangle")
    assert pose.inverse().weaving is None  # what an operation returns is a plain pose


def test_between_samples_a_weave_moves_linearly():
    pose = Pose.weave(AMPLITUDE, FREQUENCY, times=[0.0, 0.125], pattern="sine")
    np.testing.assert_allclose(pose.at([0.0625]).translation, [[0.0, AMPLITUDE / 2, 0.0]],
                               atol=1e-15)


def test_a_torch_under_the_weave_weaves_across_the_seam():
    """seam -> weave -> torch target: the offset across the seam is the weave's y."""
    tree = FrameTree("world")
    tree.add("seam", "world", Pose.along_curve([[0, 0, 0], [0.1, 0, 0]], [0, 0, 1],
                                               times=[0.0, 10.0]))
    times = np.linspace(0.0, 10.0, 401)
    tree.add("weave", "seam", Pose.weave(AMPLITUDE, 1.0, times=times, pattern="sine"))
    tree.add("torch", "weave", Pose([0.0, 0.0, 0.012], rot_x(np.pi)))
    process = tree.weld_process("torch", "seam")
    np.testing.assert_allclose(process.seconds, times, atol=1e-9)
    np.testing.assert_allclose(process.offset[:, 1], AMPLITUDE * np.sin(2 * np.pi * times),
                               atol=1e-15)
    np.testing.assert_allclose(process.offset[:, 2], 0.012, atol=1e-15)


@pytest.mark.parametrize(
    ("arguments", "field"),
    [
        ({"amplitude": 0.0}, "amplitude"), ({"amplitude": np.nan}, "amplitude"),
        ({"frequency": -1.0}, "frequency"), ({"frequency": "2"}, "frequency"),
        ({"pattern": "zigzag"}, "pattern"), ({"pattern": "trapezoid"}, "dwell"),
        ({"pattern": "trapezoid", "dwell": 1.0}, "dwell"), ({"dwell": 0.2}, "dwell"),
        ({"times": [0.0]}, "times"), ({"times": [0.0, 0.0]}, "times"),
    ],
)
def test_bad_weaves_name_the_field(arguments, field):
    given = {"amplitude": AMPLITUDE, "frequency": FREQUENCY, "times": [0.0, 1.0], **arguments}
    with pytest.raises((InvalidPoseError, InvalidTimeError)) as caught:
        Pose.weave(given.pop("amplitude"), given.pop("frequency"), **given)
    assert caught.value.field == field


def test_pint_amplitude_and_frequency():
    units = pytest.importorskip("pint").UnitRegistry()
    pose = Pose.weave(3 * units.mm, 120 / units.minute, times=[0.0, 0.125])
    np.testing.assert_allclose(pose.translation[1], [0.0, AMPLITUDE, 0.0], atol=1e-15)


SCENE = """\
pinframes_scene: 1
reference_time: 2024-03-01T07:59:00
frames:
  - {name: seam, parent: world, xyz: [1, 0, 0]}
  - name: weave
    parent: seam
    weave: {amplitude: 0.003, frequency: 2, pattern: trapezoid, dwell: 0.2, duration: 1,
            step: 0.05}
  - name: odd
    parent: seam
    reference_time: 2024-03-01T08:00:00
    weave: {amplitude: 0.002, frequency: 1, pattern: circle, times: [0, 0.25, 0.6]}
tools:
  - {name: torch, parent: weave, xyz: [0, 0, 0.012]}
"""


def test_scene_weave_entries_read_and_write(tmp_path):
    path = tmp_path / "cell.yaml"
    path.write_text(SCENE)
    tree = read_scene(path)
    weave = tree.local_pose("weave")
    np.testing.assert_allclose(weave.seconds, np.arange(21) * 0.05, atol=1e-12)
    assert weave.weaving == Weave(0.003, 2.0, "trapezoid", 0.2)
    # phase 0.1 (t = 0.05 s): half way up the ramp to A at phase 0.2
    assert weave.translation[1, 1] == pytest.approx(0.0015, abs=1e-15)
    odd = tree.local_pose("odd")
    assert odd.reference_time == np.datetime64("2024-03-01T08:00:00")
    np.testing.assert_allclose(odd.translation[:, :2], 0.002 * np.array(
        [[1.0, 0.0], [0.0, 1.0], [np.cos(1.2 * np.pi), np.sin(1.2 * np.pi)]]), atol=1e-15)
    written = tmp_path / "written.yaml"
    write_scene(tree, written)
    entries = {entry["name"]: entry for entry in yaml.safe_load(written.read_text())["frames"]}
    assert entries["weave"]["weave"] == {"amplitude": 0.003, "frequency": 2.0,
                                         "pattern": "trapezoid", "dwell": 0.2,
                                         "duration": 1.0, "step": 0.05}
    assert entries["odd"]["weave"]["times"] == [0.0, 0.25, 0.6]
    assert entries["odd"]["reference_time"] == "2024-03-01T08:00:00.000000000"
    again = read_scene(written)
    for name in ("weave", "odd"):
        assert again.local_pose(name).weaving == tree.local_pose(name).weaving
        np.testing.assert_array_equal(again.local_pose(name).translation,
                                      tree.local_pose(name).translation)
        np.testing.assert_array_equal(again.local_pose(name).times,
                                      tree.local_pose(name).times)


@pytest.mark.parametrize(
    ("weave", "field", "words"),
    [
        ("{frequency: 2, duration: 1, step: 0.1}", "frames[0].weave.amplitude", "missing"),
        ("{amplitude: 0.003, frequency: 2}", "frames[0].weave", "give either times"),
        ("{amplitude: 0.003, frequency: 2, duration: 1}", "frames[0].weave.step", "missing"),
        ("{amplitude: 0.003, frequency: 2, times: [0, 1], step: 1}", "frames[0].weave",
         "give either times"),
        ("{amplitude: -1, frequency: 2, times: [0, 1]}", "frames[0].weave.amplitude",
         "positive"),
        ("{amplitude: 0.003, frequency: 2, times: [0, 1], pattern: zigzag}",
         "frames[0].weave.pattern", "triangle"),
        ("{amplitude: 0.003, frequency: 2, times: [0, 1], pattern: trapezoid}",
         "frames[0].weave.dwell", "dwell"),
        ("{amplitude: 0.003, frequency: 2, duration: 1.0e+9, step: 1.0e-9}",
         "frames[0].weave.step", "max_samples"),
        ("{amplitude: 0.003, frequency: 2, times: [0, 1], wobble: 1}", "frames[0].weave",
         "unknown key"),
        ("{amplitude: 0.003, frequency: 2, times: [0, 1]}\n  xyz: [0, 0, 1]",
         "frames[0].weave", "takes its pose from the weave"),
    ],
)
def test_bad_scene_weaves_name_the_file_frame_and_field(tmp_path, weave, field, words):
    path = tmp_path / "bad.yaml"
    path.write_text(f"pinframes_scene: 1\nframes:\n- name: w\n  parent: world\n  weave: {weave}\n")
    with pytest.raises(FileFormatError) as caught:
        read_scene(path)
    assert caught.value.field == field and caught.value.frame == "w"
    assert str(path) in str(caught.value) and words in caught.value.message


def test_times_that_seconds_cannot_hold_are_written_as_durations(tmp_path):
    """1e7 s and one nanosecond is no double: every time goes as an ISO duration."""
    tree = FrameTree("world")
    times = np.array([0, 10**16 + 1], dtype="timedelta64[ns]")
    tree.add("weave", "world", Pose.weave(AMPLITUDE, FREQUENCY, times=times))
    path = tmp_path / "long.yaml"
    write_scene(tree, path)
    entry = yaml.safe_load(path.read_text())["frames"][0]["weave"]
    assert all(isinstance(value, str) for value in entry["times"])
    np.testing.assert_array_equal(read_scene(path).local_pose("weave").times, times)
