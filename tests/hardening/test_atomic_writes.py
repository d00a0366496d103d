"""Every writer replaces its file atomically: a failed write leaves the old bytes, no temporary
file and no new folder behind."""

from __future__ import annotations

import errno
import os
import stat
from pathlib import Path

import numpy as np
import pinocchio as pin
import pytest

from hardening.file_cases import joint, urdf
from pinframes import FrameTree, Joint, Mimic, Pose, write_frames_yaml, write_scene, write_urdf
from pinframes.cli import main
from pinframes.cli._output import output_poses
from pinframes.errors import JointError, UnsupportedFeatureError, WriteError
from pinframes.formats.atomic import atomic_write

OLD = b"old content \x00\xff kept byte for byte\n"


def static_tree() -> FrameTree:
    tree = FrameTree("world", name="cell")
    tree.add("table", "world", Pose.from_xyz_rpy(1.0, 0.0, 0.8, yaw=0.3))
    tree.add("tool", "table", Pose([0.0, 0.1, 0.2]))
    return tree


def poses_writer(fmt: str):
    def write(tree: FrameTree, path: Path) -> None:
        output_poses(tree.pose("tool", "world", times=[0.0, 1.0]), fmt, str(path), frame="tool",
                    relative_to="world")
    return write


WRITERS = {
    "cell.urdf": write_urdf,
    "frames.yaml": write_frames_yaml,
    "scene.yaml": write_scene,
    "poses.csv": poses_writer("csv"),
    "poses.json": poses_writer("json"),
    "poses.npz": poses_writer("npz"),
}


def fail_on_fsync(monkeypatch) -> None:
    """The disk fills up after the content was handed over, before the rename."""
    def no_space(fd):
        raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC))
    monkeypatch.setattr("pinframes.formats.atomic.os.fsync", no_space)


def assert_untouched(folder: Path, path: Path) -> None:
    assert path.read_bytes() == OLD
    assert sorted(p.name for p in folder.iterdir()) == [path.name]


@pytest.mark.parametrize("name", WRITERS)
def test_a_write_that_fails_midway_keeps_the_old_file(name, tmp_path, monkeypatch):
    path = tmp_path / name
    path.write_bytes(OLD)
    fail_on_fsync(monkeypatch)
    with pytest.raises(WriteError, match="No space left") as info:
        WRITERS[name](static_tree(), path)
    assert info.value.file == str(path)
    assert_untouched(tmp_path, path)


@pytest.mark.parametrize("name", WRITERS)
def test_a_write_into_a_missing_folder_creates_no_folder(name, tmp_path):
    with pytest.raises(WriteError, match="does not exist"):
        WRITERS[name](static_tree(), tmp_path / "missing" / name)
    assert list(tmp_path.iterdir()) == []


@pytest.mark.parametrize("name", WRITERS)
def test_a_write_succeeds_after_a_failed_one(name, tmp_path):
    path = tmp_path / name
    path.write_bytes(OLD)
    WRITERS[name](static_tree(), path)
    assert path.read_bytes() != OLD
    assert [p.name for p in tmp_path.iterdir()] == [name]


def moving_tree() -> FrameTree:
    tree = static_tree()
    tree.add("slide", "world", Pose([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0]], times=[0.0, 1.0]))
    return tree


def tree_with_orphaned_mimic() -> FrameTree:
    # j2 follows j1, which was never attached (joints may be attached in any order).
    tree = FrameTree()
    tree.attach_joint("c", "world", Joint("j2", "revolute", mimic=Mimic("j1")))
    return tree


def tree_with_half_turn_step() -> FrameTree:
    tree = FrameTree()
    tree.attach_urdf(urdf(joint("j1", "a", "b"), "a b"), "world")
    tree.set_joint_trajectory([0.0, 1.0], [[0.0], [3.5]])
    return tree


@pytest.mark.parametrize(("writer", "tree", "error", "frame"), [
    (write_frames_yaml, moving_tree, UnsupportedFeatureError, "slide"),
    (write_urdf, tree_with_orphaned_mimic, JointError, "j2"),
    (write_scene, tree_with_half_turn_step, UnsupportedFeatureError, "b"),
], ids=["frames.yaml-motion", "urdf-orphaned-mimic", "scene-half-turn"])
def test_a_tree_the_format_cannot_hold_leaves_the_old_file(writer, tree, error, frame, tmp_path):
    path = tmp_path / "out.file"
    path.write_bytes(OLD)
    with pytest.raises(error) as info:
        writer(tree(), path)
    # the frame, or for a robot joint's error the joint
    assert (info.value.frame if info.value.frame is not None else info.value.joint) == frame
    assert_untouched(tmp_path, path)


def test_write_urdf_turns_a_mimic_chain_into_mimics_of_the_driven_joint(tmp_path):
    # j3 = -1 * j2 + 0.2 and j2 = 2 * j1 + 0.1, so j3 = -2 * j1 + 0.1 (by hand).
    tree = FrameTree()
    tree.attach_urdf(urdf(
        joint("j1", "a", "b")
        + joint("j2", "b", "c", inner='<mimic joint="j1" multiplier="2" offset="0.1"/>')
        + joint("j3", "c", "d", inner='<mimic joint="j2" multiplier="-1" offset="0.2"/>'),
        "a b c d"), "world")
    path = tmp_path / "chain.urdf"
    with pytest.warns(UserWarning, match="no samples"):
        write_urdf(tree, path)
    model = pin.buildModelFromXML(path.read_text(), mimic=True)  # refuses mimics of mimics
    assert model.njoints == 4
    text = path.read_text()
    assert '<mimic joint="j1" multiplier="2.0" offset="0.1" />' in text
    assert '<mimic joint="j1" multiplier="-2.0" offset="0.1" />' in text
    tree.set_joint_trajectory([0.0], [[0.3]])
    expected_d_in_c = -2 * 0.3 + 0.1  # rotation about z by the value of j3
    rotation = tree.pose("d", "c").rotation[0]
    np.testing.assert_allclose(np.arctan2(rotation[1, 0], rotation[0, 0]), expected_d_in_c)


# -- the command line --------------------------------------------------------------------

def test_cli_outputs_fail_without_touching_files(tmp_path, monkeypatch, capsys):
    source = tmp_path / "in" / "scene.yaml"
    source.parent.mkdir()
    write_scene(static_tree(), source)
    out = tmp_path / "out"
    out.mkdir()
    targets = {"pose": out / "poses.csv", "convert": out / "cell.urdf", "plot": out / "p.png"}
    commands = {
        "pose": ["pose", str(source), "tool", "-r", "world", "-o", str(targets["pose"])],
        "convert": ["convert", str(source), str(targets["convert"])],
        "plot": ["plot", str(source), "-o", str(targets["plot"])],
    }
    for target in targets.values():
        target.write_bytes(OLD)
    fail_on_fsync(monkeypatch)
    for name, argv in commands.items():
        assert main(argv) == 1, name
        assert "No space left" in capsys.readouterr().err
    assert sorted(out.iterdir()) == sorted(targets.values())
    assert all(target.read_bytes() == OLD for target in targets.values())


def test_cli_demo_creates_its_output_folder_but_no_parents(tmp_path, capsys):
    out = tmp_path / "missing" / "results"
    assert main(["demo", "--out", str(out)]) == 1
    assert "cannot create the output folder" in capsys.readouterr().err
    assert list(tmp_path.iterdir()) == []


# -- atomic_write itself -----------------------------------------------------------------

def test_a_folder_at_the_path_is_refused(tmp_path):
    (tmp_path / "taken").mkdir()
    with pytest.raises(WriteError, match="is a folder"), atomic_write(tmp_path / "taken"):
        pass
    assert [p.name for p in tmp_path.iterdir()] == ["taken"]


@pytest.mark.skipif(os.name != "posix" or os.geteuid() == 0,
                    reason="needs POSIX permissions that apply (root ignores them)")
def test_a_read_only_folder_is_a_write_error(tmp_path):
    folder = tmp_path / "locked"
    folder.mkdir()
    folder.chmod(0o500)
    try:
        with pytest.raises(WriteError, match="cannot create a file here"):
            with atomic_write(folder / "x.txt", "w") as handle:
                handle.write("x")
        assert list(folder.iterdir()) == []
    finally:
        folder.chmod(0o700)


def test_failing_to_make_the_temporary_file_is_a_write_error(tmp_path, monkeypatch):
    # What a read-only folder does for users who are not root.
    def refuse(*args, **kwargs):
        raise PermissionError(errno.EACCES, os.strerror(errno.EACCES))
    monkeypatch.setattr("pinframes.formats.atomic._create_temporary", refuse)
    with pytest.raises(WriteError, match="Permission denied"), atomic_write(tmp_path / "x"):
        pass
    assert list(tmp_path.iterdir()) == []


def test_a_symbolic_link_is_kept_and_its_target_replaced(tmp_path):
    real = tmp_path / "data" / "real.txt"
    real.parent.mkdir()
    real.write_text("old")
    real.chmod(0o640)
    link = tmp_path / "link.txt"
    link.symlink_to(real)
    with atomic_write(link, "w") as handle:
        handle.write("new")
    assert link.is_symlink() and os.readlink(link) == str(real)
    assert real.read_text() == "new"
    assert stat.S_IMODE(real.stat().st_mode) == 0o640
    assert sorted(p.name for p in real.parent.iterdir()) == ["real.txt"]


def test_a_failed_write_through_a_symbolic_link_keeps_the_target(tmp_path):
    real = tmp_path / "real.txt"
    real.write_bytes(OLD)
    link = tmp_path / "link.txt"
    link.symlink_to(real)
    with pytest.raises(RuntimeError), atomic_write(link, "wb") as handle:
        handle.write(b"half")
        raise RuntimeError("boom")
    assert real.read_bytes() == OLD and link.is_symlink()
    assert sorted(p.name for p in tmp_path.iterdir()) == ["link.txt", "real.txt"]
