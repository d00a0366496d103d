"""`pinframes.read` / `pinframes.write`: one registry picks the format from the file."""

from __future__ import annotations

import numpy as np
import pytest

import pinframes
from pinframes import FileFormatError, FrameTree, Pose


def _tree() -> FrameTree:
    tree = FrameTree("world")
    tree.add("table", "world", Pose([1.0, 2.0, 0.5]))
    tree.add("tool", "table", Pose([0.0, 0.0, 0.25], [0.0, 0.0, 1.0, 0.0]))
    return tree


def _named(tree: FrameTree, last: str) -> str:
    (name,) = [frame for frame in tree.frames if frame.split("/")[-1] == last]
    return name


@pytest.mark.parametrize(("name", "expected"), [
    ("cell.yaml", "scene"), ("frames.yaml", "frames.yaml"), ("cell.asdf", "asdf"),
    ("cell.urdf", "urdf"),
])
def test_write_then_read_by_suffix(tmp_path, name, expected):
    path = tmp_path / name
    pinframes.write(_tree(), path)
    assert pinframes.formats.detect_format(path) == expected
    tree = pinframes.read(path)
    tool = _named(tree, "tool")  # frames.yaml names frames by their path ("table/tool")
    pose = tree.pose(tool, tree.root)
    # hand-derived: table at (1, 2, 0.5), tool 0.25 m above it, turned half a turn about z
    np.testing.assert_allclose(pose.translation, [1.0, 2.0, 0.75], atol=1e-12)
    np.testing.assert_allclose(pose.rotation, np.diag([-1.0, -1.0, 1.0]), atol=1e-12)


def test_an_explicit_format_wins_over_the_suffix(tmp_path):
    path = tmp_path / "cell.yaml"
    pinframes.write(_tree(), path, "frames.yaml")
    assert "frames" in pinframes.formats.Peek(path).yaml()
    tree = pinframes.read(path, "frames.yaml")
    assert tree.parent(_named(tree, "tool")) == _named(tree, "table")


def test_unknown_suffix_option_and_format(tmp_path):
    with pytest.raises(FileFormatError, match=r"unknown file type '\.txt'"):
        pinframes.write(_tree(), tmp_path / "cell.txt")
    with pytest.raises(FileFormatError, match="URDF files take no 'schema' option"):
        pinframes.write(_tree(), tmp_path / "cell.urdf", schema="1.0.0")
    with pytest.raises(FileFormatError, match="unknown format 'obj'"):
        pinframes.write(_tree(), tmp_path / "cell.urdf", "obj")
    assert not list(tmp_path.iterdir())
