"""Deep frame chains in weldx ASDF files: the 0.1.0 format nests each frame inside its
parent, the 1.0.0 format lists frames flat. Poses are checked against a plain numpy
composition of the chain."""

from __future__ import annotations

import numpy as np
import pytest

from pinframes import (
    FileFormatError,
    FrameTree,
    Pose,
    UnsupportedFeatureError,
    read_asdf,
    write_asdf,
)
from pinframes.formats.asdf._depth import MAX_GRAPH_DEPTH
from weldx_asdf.weldx_env import weldx_pose

from geometry import homogeneous, rot_x, rot_z


def link(index: int) -> tuple[np.ndarray, np.ndarray]:
    """(rotation, translation in m) of frame ``index`` in frame ``index - 1``."""
    return rot_z(0.1 + 0.01 * index) @ rot_x(0.05), np.array([0.01, 0.002 * (index % 3), 0.0])


def chain(depth: int) -> FrameTree:
    tree = FrameTree("f0", name="deep")
    for index in range(1, depth + 1):
        rotation, translation = link(index)
        tree.add(f"f{index}", f"f{index - 1}", Pose(translation, rotation))
    return tree


def tip_in_root_by_numpy(depth: int) -> np.ndarray:
    matrix = np.eye(4)
    for index in range(1, depth + 1):
        matrix = matrix @ homogeneous(*link(index))
    return matrix


@pytest.mark.slow
@pytest.mark.parametrize("schema", ["0.1.0", "1.0.0"])
def test_deepest_supported_chain_round_trips(tmp_path, schema):
    path = tmp_path / "deep.asdf"
    write_asdf(chain(MAX_GRAPH_DEPTH), path, schema=schema)
    back = read_asdf(path)
    expected = tip_in_root_by_numpy(MAX_GRAPH_DEPTH)
    pose = back.pose(f"f{MAX_GRAPH_DEPTH}", relative_to="f0")
    np.testing.assert_allclose(pose.translation.reshape(3), expected[:3, 3], rtol=0, atol=1e-12)
    np.testing.assert_allclose(pose.rotation.reshape(3, 3), expected[:3, :3], rtol=0,
                               atol=1e-12)


def test_deeper_chain_is_refused_clearly_when_writing_0_1_0(tmp_path):
    path = tmp_path / "too_deep.asdf"
    with pytest.raises(UnsupportedFeatureError, match=r"1\.0\.0") as error:
        write_asdf(chain(MAX_GRAPH_DEPTH + 1), path, schema="0.1.0")
    assert error.value.frame == f"f{MAX_GRAPH_DEPTH + 1}"
    assert str(MAX_GRAPH_DEPTH + 1) in str(error.value)
    assert str(path) in str(error.value)
    assert not path.exists()


@pytest.mark.slow
def test_deeper_chain_written_by_someone_else_is_refused_clearly(tmp_path):
    """asdf itself writes the graph, with Python's recursion limit raised far enough and on a
    thread with a stack large enough (asdf 5 overflows the main thread's C stack)."""
    import subprocess
    import sys

    path = tmp_path / "foreign.asdf"
    depth = 2 * MAX_GRAPH_DEPTH
    script = ("import sys, threading, asdf; sys.setrecursionlimit(200_000); "
              "threading.stack_size(512 * 2**20); "
              "from test_asdf_deep import chain; "
              "from pinframes.formats.asdf._writer import _graph_hierarchy; "
              "asdf.get_config().validate_on_write = False; "
              "write = lambda: asdf.AsdfFile("
              f"{{'h': _graph_hierarchy(chain({depth}))}}).write_to({str(path)!r}); "
              "thread = threading.Thread(target=write); thread.start(); thread.join(); "
              f"sys.exit(not __import__('os').path.isfile({str(path)!r}))")
    subprocess.run([sys.executable, "-c", script], check=True, cwd=__file__.rsplit("/", 1)[0],
                   env={"PYTHONPATH": ":".join(sys.path)})
    with pytest.raises(UnsupportedFeatureError, match=r"1\.0\.0") as error:
        read_asdf(path)
    assert error.value.frame == f"f{depth}"
    assert str(depth) in str(error.value)


def test_weldx_reads_a_chain_as_deep_as_it_handles(tmp_path):
    """weldx 0.8.2 itself stops (RecursionError) between 30 and 40 frames deep."""
    depth = 25
    path = tmp_path / "deep.asdf"
    write_asdf(chain(depth), path, schema="0.1.0")
    answer = weldx_pose(path, f"f{depth}", "f0")
    expected = tip_in_root_by_numpy(depth)
    np.testing.assert_allclose(answer["translation"][0], expected[:3, 3], rtol=0, atol=1e-9)
    np.testing.assert_allclose(answer["rotation"][0], expected[:3, :3], rtol=0, atol=1e-9)


@pytest.mark.slow  # seconds of CPU (subprocesses): CI's slow set
def test_yaml_nested_past_the_parser_is_refused_with_its_problem(tmp_path):
    """Nesting that is no weldx graph: the parser's problem, not its context, is reported
    (libyaml stops at 1,000 levels, the pure-Python parser at the recursion limit)."""
    path = tmp_path / "nested.asdf"
    path.write_text("#ASDF 1.0.0\n#ASDF_STANDARD 1.5.0\n%YAML 1.1\n"
                    "%TAG ! tag:stsci.edu:asdf/\n--- !core/asdf-1.1.0\n"
                    f"deep: {'[' * 1500}{']' * 1500}\n...\n")
    with pytest.raises(FileFormatError, match="nesting depth") as error:
        read_asdf(path)
    assert str(path) in str(error.value)
