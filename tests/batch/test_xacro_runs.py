"""A batch expands no xacro file unless asked (``--xacro``, ``run_batch(xacro=True)``): it
would run every file's code on every worker. ``read_run`` is the one place a run is read."""

from __future__ import annotations

import pytest

from pinframes import FileFormatError, Limits
from pinframes.batch._inputs import read_run, run_inputs
from pinframes.batch._options import BatchOptions

# a Dask cluster per test: in the slow set (CI runs it)
pytestmark = pytest.mark.slow

pytest.importorskip("xacro")

ROBOT = ('<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">'
         '<xacro:property name="p" value="expanded"/><link name="l_${p}"/></robot>')


@pytest.mark.parametrize("name", ["robot.urdf.xacro", "robot.urdf", "scene.yaml"])
def test_a_run_with_xacro_content_is_expanded_only_with_the_opt_in(tmp_path, name):
    (tmp_path / "robot.urdf.xacro").write_text(ROBOT)
    (tmp_path / "robot.urdf").write_text(ROBOT)
    (tmp_path / "scene.yaml").write_text(
        "pinframes_scene: 1\nrobots: [{urdf: robot.urdf.xacro, xacro: true}]\n")
    inputs = run_inputs(tmp_path / name)
    with pytest.raises(FileFormatError, match="runs the file's code") as caught:
        read_run(inputs, Limits())
    assert caught.value.field == "xacro"
    assert "l_expanded" in read_run(inputs, Limits(), xacro=True).frames


def test_the_opt_in_is_part_of_the_options_digest_only_when_given():
    plain = BatchOptions.create("tool")
    assert BatchOptions.create("tool", xacro=False).digest() == plain.digest()
    assert BatchOptions.create("tool", xacro=True).digest() != plain.digest()
