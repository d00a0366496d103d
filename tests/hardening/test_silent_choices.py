"""Choices pinframes made silently before: a weave sampled where it crosses its centre line,
a number YAML reads as text, an upward direction too short to be one."""

from __future__ import annotations

import textwrap

import numpy as np
import pytest

import pinframes
from pinframes import FrameTree, Pose
from pinframes.errors import FileFormatError, InvalidDataError, InvalidPoseError


def weave_scene(tmp_path, weave: str):
    path = tmp_path / "weave.yaml"
    path.write_text(textwrap.dedent(f"""\
        pinframes_scene: 1
        frames:
          - name: weave
            parent: world
            weave: {weave}
        """))
    return path


@pytest.mark.parametrize(("frequency", "step"), [(2, 0.25), (2, 0.5), (2, 1.0), (5, 0.1)])
def test_a_weave_stepped_by_its_half_period_is_refused_naming_step_and_frequency(
        tmp_path, frequency, step):
    # frequency 2, step 0.25: every sample on the centre line, while pose.weaving said weave
    path = weave_scene(tmp_path, f"{{amplitude: 0.002, frequency: {frequency}, duration: 2, "
                                 f"step: {step}}}")
    with pytest.raises(FileFormatError, match=rf"weave of {frequency:g} Hz .* every {step:g} s"
                       ) as caught:
        pinframes.read_scene(path)
    assert caught.value.file == str(path) and caught.value.field == "frames[0].weave.step"


@pytest.mark.parametrize("pattern", ["triangle", "sine", "trapezoid", "circle"])
def test_pose_weave_at_whole_half_periods_is_refused(pattern):
    dwell = 0.2 if pattern == "trapezoid" else None
    with pytest.raises(InvalidPoseError, match="straight line") as caught:
        Pose.weave(0.003, 4.0, times=np.arange(9) * 0.125, pattern=pattern, dwell=dwell)
    assert caught.value.field == "times"


def test_a_weave_sampled_four_times_a_period_keeps_its_amplitude(tmp_path):
    path = weave_scene(tmp_path, "{amplitude: 0.002, frequency: 2, duration: 2, step: 0.125}")
    offsets = pinframes.read_scene(path).pose("weave", "world").translation[:, 1]
    # by hand: a triangle of 2 mm at 2 Hz, sampled at 0, 1/8, 1/4, 3/8 of a second...
    np.testing.assert_allclose(offsets[:5], [0.0, 0.002, 0.0, -0.002, 0.0], atol=1e-15)


@pytest.mark.parametrize("written", ["1.0e308", "1e308", "2.5e3"])
def test_a_number_yaml_reads_as_text_says_so(tmp_path, written):
    import yaml

    assert isinstance(yaml.safe_load(f"a: {written}")["a"], str)  # YAML 1.1: text
    path = weave_scene(tmp_path, f"{{amplitude: {written}, frequency: 2, duration: 1, "
                                 "step: 0.05}")
    with pytest.raises(FileFormatError, match=r"YAML reads a number with an exponent as text"
                       ) as caught:
        pinframes.read_scene(path)
    assert caught.value.field == "frames[0].weave.amplitude"
    assert repr(written) in str(caught.value)


def seam_and_torch() -> FrameTree:
    tree = FrameTree("world")
    times = [0.0, 1.0]
    tree.add("seam", "world", Pose([[0.0, 0, 0], [0.1, 0, 0]], times=times))
    tree.add("torch", "world", Pose([[0.0, 0, 0.01], [0.1, 0, 0.01]], times=times))
    return tree


@pytest.mark.parametrize("up", [[1e-320, 0.0, 0.0], [1e-170, 0.0, 0.0], [1e200, 0.0, 0.0]])
def test_weld_process_refuses_an_up_that_solve_joints_refuses(up):
    with pytest.raises(InvalidDataError, match="expected a direction") as caught:
        seam_and_torch().weld_process("torch", "seam", up=up)
    assert caught.value.field == "up"
    # a long up is a direction: seam along world x, up between x and z: a slope of 45 degrees
    process = seam_and_torch().weld_process("torch", "seam", up=[3.0, 0.0, 3.0])
    np.testing.assert_allclose(process.slope, np.pi / 4, atol=1e-12)
