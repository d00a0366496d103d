"""``pinframes convert`` never drops data attached to frames: formats that cannot hold it
refuse, naming the data."""

import numpy as np
import pytest

from pinframes import FrameTree, Pose, SpatialData, read_asdf, write_asdf


@pytest.mark.parametrize("target", ["snapshot.urdf", "frames.yaml", "scene.yaml"])
def test_convert_refuses_to_drop_data(run_cli, tmp_path, target):
    tree = FrameTree("world")
    tree.add("torch", "world", Pose([0.5, 0.0, 0.3]))
    tree.assign_data("seam", SpatialData([[0.01, 0.0, 0.0], [0.02, 0.0, 0.0]]), "torch")
    source = tmp_path / "cell.asdf"
    write_asdf(tree, source, schema="0.1.0")
    result = run_cli("convert", source, tmp_path / target)
    assert result.returncode == 1, result.stderr
    assert "'seam' on frame 'torch'" in result.stderr, result.stderr
    assert not (tmp_path / target).exists()


def test_convert_to_asdf_keeps_data_by_default(run_cli, tmp_path):
    tree = FrameTree("world")
    tree.add("torch", "world", Pose([0.5, 0.0, 0.3]))
    tree.assign_data("seam", SpatialData([[0.01, 0.0, 0.0]]), "torch")
    source = tmp_path / "cell.asdf"
    write_asdf(tree, source)
    result = run_cli("convert", source, tmp_path / "copy.asdf")  # schema 0.1.0 holds data
    assert result.returncode == 0, result.stderr
    seam = read_asdf(tmp_path / "copy.asdf").get_data("seam", relative_to="world")
    np.testing.assert_allclose(seam.points, [[0.51, 0.0, 0.3]], atol=1e-12)
    result = run_cli("convert", source, tmp_path / "legacy.asdf", "--schema", "1.0.0")
    assert result.returncode == 1 and "'seam' on frame 'torch'" in result.stderr
