"""Writers fail with a pinframes error naming the path (and the joint), never a library's
traceback: a bag written to ``.``, a name too long, a full disk, joint names no file holds
unchanged; and nothing is left half-written."""

from __future__ import annotations

import os
import subprocess
import sys
import textwrap
from pathlib import Path

import numpy as np
import pytest

import pinframes
from hardening.capped import TESTS
from pinframes import FrameTree, Pose
from pinframes.errors import InvalidDataError, UnsupportedFeatureError, WriteError

SCENE = """\
    pinframes_scene: 1
    frames:
      - {name: table, parent: world, xyz: [1.0, 0.0, 0.5]}
    """
BAGS = ["run.mcap", "run.db3", "run.bag", "run"]


def small_tree() -> FrameTree:
    tree = FrameTree("world")
    tree.add("table", "world", Pose([1.0, 0.0, 0.8]))
    return tree


def test_converting_into_the_current_folder_names_it(tmp_path):
    (tmp_path / "scene.yaml").write_text(textwrap.dedent(SCENE))
    environment = {**os.environ, "PYTHONPATH": os.pathsep.join(sys.path)}
    done = subprocess.run([sys.executable, "-m", "pinframes.cli", "convert", "scene.yaml", "."],
                          cwd=tmp_path, capture_output=True, text=True, env=environment,
                          timeout=120)
    assert done.returncode != 0 and "Traceback" not in done.stderr, done.stderr
    assert "names the current folder" in done.stderr, done.stderr
    assert os.listdir(tmp_path) == ["scene.yaml"]


@pytest.mark.parametrize("name", [".", ".."])
def test_an_empty_current_folder_is_not_a_bag_name(tmp_path, monkeypatch, name):
    # rosbags' WriterError traceback before (its scratch folder took the name '')
    inner = tmp_path / "empty"
    inner.mkdir()
    monkeypatch.chdir(inner)
    with pytest.raises(WriteError, match="names the current folder") as caught:
        pinframes.write(small_tree(), name)
    assert caught.value.file == name
    assert os.listdir(inner) == [] and os.listdir(tmp_path) == ["empty"]


@pytest.mark.parametrize("suffix", [".mcap", ".db3", ".bag", ""])
def test_a_name_too_long_is_a_write_error_naming_it(tmp_path, suffix):
    path = tmp_path / ("n" * 300 + suffix)
    with pytest.raises(WriteError, match="File name too long") as caught:
        pinframes.write(small_tree(), path)
    assert caught.value.file == str(path)
    with pytest.raises(WriteError, match="File name too long") as caught:
        pinframes.write_joint_trajectory(([0.0, 1.0], [[0.0], [1.0]], ["j"]), path)
    assert caught.value.file == str(path)
    assert os.listdir(tmp_path) == []


FULL_DISK = """
import resource, signal
import numpy as np
import pinframes
signal.signal(signal.SIGXFSZ, signal.SIG_IGN)  # a write past the bound fails (EFBIG)
tree = pinframes.FrameTree("world")
times = np.arange(20_000) * 0.01
tree.add("tool", "world", pinframes.Pose(np.c_[times, 0 * times, 0 * times], times=times))
resource.setrlimit(resource.RLIMIT_FSIZE, (200_000, 200_000))  # no file past 200 kB
pinframes.write(tree, sys.argv[2])
"""


@pytest.mark.parametrize("name", BAGS)
def test_a_full_disk_is_a_write_error_naming_the_bag(tmp_path, name):
    # a .db3 gave sqlite3.OperationalError; the disk is full for files past 200 kB
    environment = {**os.environ, "PYTHONPATH": os.pathsep.join([str(TESTS), *sys.path])}
    done = subprocess.run([sys.executable, "-c", "import sys\n" + FULL_DISK, str(tmp_path),
                           name], cwd=tmp_path, capture_output=True, text=True,
                          env=environment, timeout=120)
    last = done.stderr.strip().splitlines()[-1]
    assert last.startswith(f"pinframes.errors.WriteError: {name}: cannot write the "), last
    assert os.listdir(tmp_path) == []  # no bag, no temporary


@pytest.mark.parametrize("suffix", [".csv", ".npz", ".mcap"])
@pytest.mark.parametrize("name", ["j\ud800", "j\nk", "j\x1b[31m", "j\x00"])
def test_joint_names_no_file_holds_are_refused_naming_the_joint(tmp_path, suffix, name):
    path = tmp_path / ("motion" + suffix)
    with pytest.raises(UnsupportedFeatureError, match=r"control character|lone surrogate"
                       ) as caught:
        pinframes.write_joint_trajectory(([0.0, 1.0], [[0.0], [1.0]], [name]), path)
    assert caught.value.file == str(path) and caught.value.field == "joint_names"
    assert caught.value.joint is not None and "j" in caught.value.joint
    str(caught.value).encode("utf-8")  # the message itself prints
    assert os.listdir(tmp_path) == []


@pytest.mark.parametrize("name", [" a ", "a ", "=cmd|' /C calc'!A0", "+1", "-x", "@SUM(A1)"])
def test_csv_headers_that_do_not_read_back_or_run_as_formulas_are_refused(tmp_path, name):
    path = tmp_path / "motion.csv"
    with pytest.raises(UnsupportedFeatureError, match=r"space|formula") as caught:
        pinframes.write_joint_trajectory(([0.0, 1.0], [[0.0], [1.0]], [name]), path)
    assert caught.value.joint == name and caught.value.file == str(path)
    assert os.listdir(tmp_path) == []
    pinframes.write_joint_trajectory(([0.0, 1.0], [[0.0], [1.0]], [name]),
                                     tmp_path / "motion.npz")  # NPZ keeps any name
    assert list(np.load(tmp_path / "motion.npz")["joint_names"]) == [name]


@pytest.mark.parametrize("suffix", [".csv", ".npz", ".mcap"])
def test_a_trajectory_without_joints_is_refused(tmp_path, suffix):
    path = tmp_path / ("motion" + suffix)
    with pytest.raises(InvalidDataError, match="no joints") as caught:
        pinframes.write_joint_trajectory(([0.0, 1.0], np.zeros((2, 0)), []), path)
    assert caught.value.file == str(path)
    assert os.listdir(tmp_path) == []


def test_a_plain_name_still_reads_back(tmp_path):
    path = tmp_path / "motion.csv"
    pinframes.write_joint_trajectory(([0.0, 1.0], [[0.0], [1.0]], ["joint_1"]), path)
    _, positions, names = pinframes.read_joint_trajectory(path)
    assert names == ["joint_1"] and positions.tolist() == [[0.0], [1.0]]
    assert Path(path).read_text().startswith("time_s,joint_1\n")


@pytest.mark.parametrize("name", [" j1", "=cmd|' /C calc'!A0"])
def test_a_urdf_writes_no_joint_name_its_joints_csv_would_change_or_run(tmp_path, name):
    tree = FrameTree("world")
    tree.attach_urdf(f'<robot name="r"><link name="base"/><link name="arm"/>'
                     f'<joint name="{name}" type="revolute"><parent link="base"/>'
                     '<child link="arm"/><axis xyz="0 0 1"/><limit lower="-1" upper="1" '
                     'effort="1" velocity="1"/></joint></robot>', "world")
    tree.set_joint_trajectory([0.0, 1.0], [[0.0], [0.5]], [name])
    path = tmp_path / "cell.urdf"
    with pytest.raises(UnsupportedFeatureError, match=r"space|formula") as caught:
        pinframes.write_urdf(tree, path, time=0.5)
    assert caught.value.joint == name and caught.value.file == str(tmp_path / "cell.joints.csv")
    assert os.listdir(tmp_path) == []  # neither file written
