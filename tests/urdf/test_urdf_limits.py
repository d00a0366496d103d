"""URDF reading under :class:`pinframes.Limits`: element count, nesting, mimic chains, DTDs.

The files are generated here; those that exceed a default limit are read in a child process
with capped memory and CPU time (``hardening.test_resource_bounds``), so a reader that
tried to keep them all would fail the test instead of taking the machine down. The tiny
entity bombs are in ``hardening.resource_cases``.
"""

from __future__ import annotations

import os
import pyexpat
import resource
import subprocess
import sys
import warnings
from pathlib import Path

import numpy as np
import pytest

import pinframes
from hardening.test_resource_bounds import read_in_capped_child
from pinframes import FrameTree, Limits, read_scene, read_urdf
from pinframes.errors import FileFormatError

SRC = Path(__file__).resolve().parents[2] / "src"


def _environment() -> dict[str, str]:
    return {**os.environ, "PYTHONPATH": os.pathsep.join(filter(None, [
        str(SRC), os.environ.get("PYTHONPATH")]))}


def _capped_memory() -> None:
    cap = 1536 * 1024**2  # bytes of address space
    resource.setrlimit(resource.RLIMIT_AS, (cap, cap))


def _robot(body: str) -> str:
    return f'<?xml version="1.0"?>\n<robot name="r"><link name="base"/>{body}</robot>\n'


def _deep_link(inner: str) -> str:
    """Link ``deep`` with ``inner`` as its content, fixed to ``base``: 6 more elements."""
    return _robot(f'<link name="deep">{inner}</link><joint name="j" type="fixed">'
                  '<parent link="base"/><child link="deep"/></joint>')


def _nested(levels: int) -> str:
    """A link whose ``<visual>`` holds ``levels`` levels of ``<a>`` (robot and link: 2 more)."""
    return _deep_link(f'<visual>{"<a>" * levels}{"</a>" * levels}</visual>')


def _mimic_chain(joints: int, mimic: bool = True) -> str:
    """Revolute joints about z in a chain, each mimicking the one before (multiplier 1)
    unless ``mimic`` is False."""
    parts = [f'<link name="l{index}"/>' for index in range(1, joints + 1)]
    for index in range(joints):
        follows = f'<mimic joint="j{index - 1}"/>' if index and mimic else ""
        parent = "base" if index == 0 else f"l{index}"
        parts.append(f'<joint name="j{index}" type="revolute"><parent link="{parent}"/>'
                     f'<child link="l{index + 1}"/><axis xyz="0 0 1"/>'
                     f'<limit lower="-10" upper="10" effort="1" velocity="1"/>{follows}</joint>')
    return _robot("".join(parts))


def test_the_parser_is_an_expat_that_stops_entity_amplification():
    # Python documents expat 2.4.1 and newer as safe from billion laughs and quadratic
    # blowup; the DOCTYPE refusal stops the parse early, expat's own limit bounds the rest
    assert pyexpat.version_info >= (2, 4, 1), pyexpat.EXPAT_VERSION


def test_too_many_elements_are_refused_naming_file_limit_and_element(tmp_path):
    path = tmp_path / "robot.urdf"
    path.write_text(_deep_link("<visual>" + "<b/>" * 200 + "</visual>"))
    with pytest.raises(FileFormatError, match="max_xml_elements=203") as info:
        read_urdf(path, limits=Limits(max_xml_elements=203))
    assert info.value.file == str(path) and info.value.field == "b"  # the 204th: the last <b>
    assert "--max-xml-elements" in str(info.value)
    assert len(read_urdf(path, limits=Limits(max_xml_elements=207))) == 2  # 207 elements


@pytest.mark.slow  # seconds of CPU (subprocesses): CI's slow set
def test_a_file_over_the_default_element_count_fails_within_the_caps(tmp_path):
    path = tmp_path / "robot.urdf"  # 4.8 MB: 1.2 million empty elements in one link
    path.write_text(_deep_link("<a/>" * 1_200_000))
    outcome = read_in_capped_child("urdf", path)
    assert outcome.startswith("FileFormatError ") and str(path) in outcome, outcome
    assert "max_xml_elements=1,000,000" in outcome, outcome


def test_nesting_is_bounded_by_max_depth(tmp_path):
    path = tmp_path / "robot.urdf"
    path.write_text(_nested(60))  # robot > link > visual > 60 levels: 63 deep
    with pytest.raises(FileFormatError, match="max_depth=62") as info:
        read_urdf(path, limits=Limits(max_depth=62))
    assert info.value.file == str(path) and info.value.field == "a"
    tree = read_urdf(path, limits=Limits(max_depth=63))
    assert tree.frames == ["base", "deep"]


def test_a_million_levels_fail_within_the_caps(tmp_path):
    path = tmp_path / "robot.urdf"  # 7 MB
    path.write_text(_nested(1_000_000))
    outcome = read_in_capped_child("urdf", path)
    assert outcome.startswith("FileFormatError ") and str(path) in outcome, outcome
    assert "max_depth=1,000" in outcome, outcome


def test_a_doctype_is_refused_even_without_entities(tmp_path):
    path = tmp_path / "robot.urdf"
    path.write_text('<?xml version="1.0"?>\n<!DOCTYPE robot>\n<robot name="r">'
                    '<link name="base"/></robot>\n')
    with pytest.raises(FileFormatError, match="DOCTYPE") as info:
        read_urdf(path)
    assert info.value.file == str(path) and info.value.field == "DOCTYPE"


def test_a_long_mimic_chain_is_read_in_linear_time_and_evaluated():
    # 900 joints, each mimicking the one before: once a cubic check (3 s for 800 joints)
    # and a quadratic one per query (10 s); every joint turns by j0's value. Ten times:
    # the numpy kernels (see test_a_one_time_query_on_hundreds_of_joints_stays_small)
    tree = FrameTree()
    tree.attach_urdf(_mimic_chain(900), "world")
    times = np.arange(10.0)
    angles = 0.0013 * times
    tree.set_joint_trajectory(times, angles[:, None], ["j0"])
    pose = tree.pose("l900", "base", times=times)
    total = 900 * angles  # plain rotations about z, composed by hand
    expected = np.zeros((10, 3, 3))
    expected[:, 0, 0] = expected[:, 1, 1] = np.cos(total)
    expected[:, 1, 0], expected[:, 0, 1], expected[:, 2, 2] = np.sin(total), -np.sin(total), 1
    np.testing.assert_allclose(pose.rotation, expected, rtol=0, atol=1e-12)


def test_a_one_time_query_on_hundreds_of_joints_stays_small(tmp_path):
    """pinocchio.Data of 400 joints would take 4 GB: such a path takes the numpy kernels."""
    path = tmp_path / "robot.urdf"  # 60 kB
    path.write_text(_mimic_chain(400, mimic=False))
    child = ("import sys, warnings; warnings.simplefilter('ignore'); "
             "from pinframes import read_urdf; "
             "print(read_urdf(sys.argv[1]).pose('l400', 'base', times=[0.0]).translation)")
    done = subprocess.run([sys.executable, "-c", child, str(path)], capture_output=True,
                          text=True, env=_environment(), preexec_fn=_capped_memory,
                          timeout=120, check=False)
    assert done.returncode == 0, done.stderr[-500:]


def test_a_mimic_chain_longer_than_max_depth_is_refused(tmp_path):
    path = tmp_path / "robot.urdf"
    path.write_text(_mimic_chain(40))
    with pytest.raises(FileFormatError, match="max_depth=30") as info:
        read_urdf(path, limits=Limits(max_depth=30))
    # j30 is the first joint (root outwards) with 31 joints in its chain: j30 .. j0
    assert (info.value.file, info.value.joint, info.value.field) == (
        str(path), "j30", "mimic.joint")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        assert len(read_urdf(path, limits=Limits(max_depth=40)).joints) == 40


def test_attach_urdf_the_registry_and_a_scene_pass_their_limits_on(tmp_path):
    path = tmp_path / "robot.urdf"
    path.write_text(_nested(60))
    small = Limits(max_depth=10)
    tree = FrameTree()
    with pytest.raises(FileFormatError, match="max_depth=10"):
        tree.attach_urdf(path, "world", limits=small)
    assert tree.frames == ["world"]  # a failed import leaves the tree as it was
    with pytest.raises(FileFormatError, match="max_depth=10"):
        pinframes.read(path, limits=small)
    scene = tmp_path / "scene.yaml"
    scene.write_text("pinframes_scene: 1\nrobots:\n  - {urdf: robot.urdf, parent: world}\n")
    with pytest.raises(FileFormatError, match="max_depth=10") as info:
        read_scene(scene, limits=small)
    assert str(path) in str(info.value)
    assert read_scene(scene).frames == ["world", "base", "deep"]


def test_the_command_line_options_reach_the_urdf_reader(tmp_path):
    path = tmp_path / "robot.urdf"
    path.write_text(_deep_link("<visual>" + "<b/>" * 50 + "</visual>"))
    env = _environment()
    done = subprocess.run([sys.executable, "-m", "pinframes.cli", "--max-xml-elements", "20",
                           "info", str(path)], capture_output=True, text=True, env=env,
                          timeout=120, check=False)
    assert done.returncode == 1, done.stderr
    assert f"pinframes: error: {path}" in done.stderr and "max_xml_elements=20" in done.stderr
    done = subprocess.run([sys.executable, "-m", "pinframes.cli", "info", str(path),
                           "--max-xml-elements", "60"], capture_output=True, text=True,
                          env=env, timeout=120, check=False)
    assert done.returncode == 0, done.stderr
