"""``pinframes convert`` never drops data attached to frames: formats that cannot hold it
refuse, naming the data."""

import pytest

from pinframes import FrameTree, Pose, SpatialData, write_asdf


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
