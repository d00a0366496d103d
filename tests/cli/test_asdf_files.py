"""ASDF layers in scenes and ASDF on the command line (needs pinframes' ASDF support)."""

import io
import textwrap

import numpy as np
import pytest

import pinframes
from conftest import SHARED_DATA
from pinframes import FrameTree, Pose, read_scene


def needs(*functions: str):
    """Skip until every named pinframes ASDF function is merged."""
    missing = [name for name in functions if not hasattr(pinframes, name)]
    return pytest.mark.skipif(bool(missing), reason=f"pinframes.{', '.join(missing)} not merged")



@needs("read_asdf", "write_asdf")
def test_asdf_layer_keeps_its_absolute_times(tmp_path):
    layer = FrameTree(reference_time="2024-03-01T08:00:00")
    layer.add("cart", "world", Pose([[0.0, 0, 0], [1.0, 0, 0]], times=[0.0, 10.0]))
    pinframes.write_asdf(layer, tmp_path / "cart.asdf")
    scene = tmp_path / "scene.yaml"
    scene.write_text(textwrap.dedent("""\
        pinframes_scene: 1
        frames:
          - {name: hall, parent: world, xyz: [0, 5, 0]}
        layers:
          - {file: cart.asdf, mount: hall, prefix: "a/"}
        """))
    tree = read_scene(scene)
    assert tree.reference_time == np.datetime64("2024-03-01T08:00:00")
    cart = tree.pose("a/cart", relative_to="world",
                     times=[np.datetime64("2024-03-01T08:00:02.5")])
    np.testing.assert_allclose(cart.translation, [[0.25, 5.0, 0.0]], atol=1e-12)


@needs("read_asdf", "write_asdf")
@pytest.mark.parametrize("schema", ["0.1.0", "1.0.0"])
def test_convert_scene_to_asdf_keeps_the_motion(run_cli, turntable, tmp_path, schema):
    out = tmp_path / f"turntable-{schema}.asdf"
    result = run_cli("convert", turntable, out, "--schema", schema)
    assert result.returncode == 0, result.stderr
    result = run_cli("pose", out, "tip", "-r", "world", "--times", "5")
    assert result.returncode == 0, result.stderr
    row = np.loadtxt(io.StringIO(result.stdout), delimiter=",", skiprows=1)
    angle = np.pi / 4  # half of the 90 degree turn, hand-derived
    np.testing.assert_allclose(row[1:4], [1 + 0.2 * np.cos(angle), 0.2 * np.sin(angle), 0.5],
                               atol=1e-9)


@needs("read_asdf")
@pytest.mark.parametrize("name", ["legacy_time.asdf", "time_delta.asdf", "static_tree.asdf"])
def test_info_on_real_weldx_files(run_cli, name):
    path = SHARED_DATA / "weldx-files" / name
    if not path.is_file():
        pytest.skip("shared sample data not present")
    result = run_cli("info", path)
    assert result.returncode == 0, result.stderr
    assert result.stdout.startswith("tree ")
