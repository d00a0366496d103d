"""Tiny hostile files end with a pinframes error, bounded in memory and time.

Each file is read in a child process whose address space is capped (``RLIMIT_AS``) and
whose CPU time is limited (``RLIMIT_CPU``), so a reader that still tried to expand, allocate
or inflate what the file describes would die of a ``MemoryError`` or be killed, and fail
the test, instead of taking the machine down. The child reports what the read raised.
"""

from __future__ import annotations

import json
import os
import resource
import subprocess
import sys
import tracemalloc
from pathlib import Path

import numpy as np
import pytest
import yaml

from hardening.readers import READERS
from hardening.resource_cases import RESOURCE_CASES, ResourceCase, alias_bomb, asdf_bytes
from pinframes import Limits, read_frames_yaml, read_joint_trajectory, read_scene
from pinframes.errors import FileFormatError, FrameExistsError, ReadError
from pinframes.formats import InputFile
from pinframes.formats.limits import using_limits

MEMORY_CAP = 1024**3  # bytes of address space: pinframes with numpy, pinocchio, asdf uses ~250 MB
CPU_SECONDS = 20
TESTS = Path(__file__).resolve().parents[1]

CHILD = """
import json
import sys
from hardening.readers import READERS
from pinframes import Limits
from pinframes.errors import PinframesError
options = {"limits": Limits(**json.loads(sys.argv[3]))} if len(sys.argv) > 3 else {}
try:
    READERS[sys.argv[1]].read(sys.argv[2], **options)
except PinframesError as exc:
    print(type(exc).__name__, exc)
except BaseException as exc:
    print("NOT-A-PINFRAMES-ERROR", repr(exc)[:500])
else:
    print("READ")
"""


def _capped() -> None:
    resource.setrlimit(resource.RLIMIT_AS, (MEMORY_CAP, MEMORY_CAP))
    resource.setrlimit(resource.RLIMIT_CPU, (CPU_SECONDS, CPU_SECONDS))


def read_in_capped_child(reader: str, path: Path, limits: dict[str, int] | None = None) -> str:
    """What reading ``path`` with ``reader`` (and ``limits``, the fields of a
    :class:`pinframes.Limits`) printed in a child with capped resources."""
    paths = [str(TESTS), *sys.path]
    environment = {**os.environ, "PYTHONPATH": os.pathsep.join(paths),
                   "OPENBLAS_NUM_THREADS": "1"}
    arguments = [reader, str(path)] + ([json.dumps(limits)] if limits is not None else [])
    done = subprocess.run([sys.executable, "-c", CHILD, *arguments], env=environment,
                          preexec_fn=_capped, capture_output=True, text=True,
                          timeout=CPU_SECONDS * 6)
    assert done.returncode == 0, f"the child died ({done.returncode}): {done.stderr[-2000:]}"
    return done.stdout.strip()


@pytest.mark.parametrize("case", RESOURCE_CASES, ids=lambda case: f"{case.reader}-{case.id}")
def test_a_tiny_file_asking_for_huge_work_is_refused(case: ResourceCase, tmp_path):
    path = tmp_path / READERS[case.reader].file_name
    path.write_bytes(case.content)
    assert len(case.content) < 4096
    outcome = read_in_capped_child(case.reader, path)
    assert outcome.startswith(case.error + " "), outcome
    assert str(path) in outcome and case.message in outcome, outcome


_FLAT_LINE = "  - [0, 1, 2, 3, 4, 5, 6, 7, 8, 9]\n"  # 12 nodes in 35 bytes
_LARGE_DOCUMENTS = {
    "scene": lambda lines: f"pinframes_scene: 1\nlarge:\n{lines}".encode(),
    "frames.yaml": lambda lines: (f"version: 1.0\nlarge:\n{lines}"
                                  "frames:\n  m: {relative_to: ~}\n").encode(),
    "asdf": lambda lines: asdf_bytes(f"large:\n{lines}"),
}


@pytest.mark.parametrize("reader", sorted(_LARGE_DOCUMENTS))
def test_a_large_yaml_document_is_refused_when_composing_reaches_the_node_limit(reader,
                                                                                tmp_path):
    # 9 MB of short lists, 3.2 million nodes and no alias: composed whole before the node
    # count was checked, it took 50 s and 1.3 GB; composing must stop at the limit
    path = tmp_path / READERS[reader].file_name
    path.write_bytes(_LARGE_DOCUMENTS[reader](_FLAT_LINE * (9 * 2**20 // len(_FLAT_LINE))))
    outcome = read_in_capped_child(reader, path, {"max_yaml_nodes": 20_000})
    assert outcome.startswith("FileFormatError "), outcome
    assert str(path) in outcome and "max_yaml_nodes=20,000" in outcome, outcome


@pytest.mark.parametrize("reader", ["frames.yaml", "scene", "asdf", "npz", "csv", "urdf"])
@pytest.mark.parametrize("special", ["/dev/zero", "fifo"])
def test_devices_and_fifos_are_refused_without_reading(reader, special, tmp_path):
    # under the name the reader expects: a FIFO, or a symbolic link to /dev/zero
    path = tmp_path / READERS[reader].file_name
    if special == "fifo":
        os.mkfifo(path)
    else:
        if not Path(special).exists():
            pytest.skip(f"{special} does not exist here")
        path.symlink_to(special)
    outcome = read_in_capped_child(reader, path)
    assert outcome.startswith("ReadError ") and "not a regular file" in outcome, outcome


@pytest.mark.filterwarnings("ignore::pinframes.FramesYamlWarning")  # the anchors b0..b2
def test_limits_can_be_raised_for_a_trusted_file(tmp_path):
    # 10 ** 3 scalars through aliases: refused under a limit of 500 nodes, read under 5,000
    path = tmp_path / "frames.yaml"
    path.write_text("version: 1.0\n" + alias_bomb(levels=3)
                    + "frames:\n  m: {relative_to: ~, pose: {x: 2.5}}\n")
    with pytest.raises(FileFormatError, match="max_yaml_nodes=500"):
        read_frames_yaml(path, limits=Limits(max_yaml_nodes=500))
    tree = read_frames_yaml(path, limits=Limits(max_yaml_nodes=5_000))
    np.testing.assert_array_equal(tree.pose("m", "world").translation, [2.5, 0.0, 0.0])


def test_trajectory_limits_count_rows_and_inflated_bytes(tmp_path):
    path = tmp_path / "motion.npz"
    np.savez_compressed(path, times=np.arange(1000.0), positions=np.zeros((1000, 2)),
                        joint_names=np.array(["a", "b"]))
    with pytest.raises(FileFormatError, match="max_samples"):
        read_joint_trajectory(path, limits=Limits(max_samples=999))
    with pytest.raises(FileFormatError, match="max_decompressed_bytes") as info:
        read_joint_trajectory(path, limits=Limits(max_decompressed_bytes=20_000))
    assert info.value.file == str(path)
    times, positions, names = read_joint_trajectory(path, limits=Limits(max_samples=1000))
    assert times.shape == (1000,) and positions.shape == (1000, 2) and names == ["a", "b"]


@pytest.mark.parametrize("bad", [0, -1, 1.5, True, "10"])
def test_a_limit_must_be_a_positive_whole_number(bad):
    from pinframes.errors import ArgumentTypeError

    with pytest.raises(ArgumentTypeError) as info:
        Limits(max_samples=bad)
    assert info.value.field == "max_samples"


def test_a_frames_yaml_key_of_many_segments_is_read_or_refused(tmp_path):
    def layer(segments: int) -> Path:
        key = "/".join(f"s{index}" for index in range(segments))
        path = tmp_path / f"frames-{segments}.yaml"
        path.write_text(f"version: 1.0\nframes:\n  ? {key}\n  : {{relative_to: ~, "
                        f"pose: {{x: 1.0}}}}\n  b: {{relative_to: {key}, pose: {{x: 0.5}}}}\n")
        return path

    tree = read_frames_yaml(layer(999))  # was a RecursionError from about 490 segments on
    # b sits 0.5 m along x from the deepest key, which is 1 m along x from the root
    np.testing.assert_allclose(tree.pose("b", "world").translation, [1.5, 0.0, 0.0])
    with pytest.raises(FileFormatError, match="1,500 path segments") as info:
        read_frames_yaml(layer(1500))
    assert info.value.field is None and info.value.frame.endswith("s1499")
    tree = read_frames_yaml(layer(1500), limits=Limits(max_depth=2000))
    assert len(tree) == 1 + 1500 + 1


@pytest.mark.parametrize("path", [5, None, b"frames.yaml", b"a\0b", object()])
def test_a_path_that_is_no_text_path_is_an_argument_error(path):
    from pinframes import read_asdf, read_scene
    from pinframes.errors import ArgumentTypeError

    for reader in (read_frames_yaml, read_scene, read_joint_trajectory, read_asdf):
        with pytest.raises(ArgumentTypeError) as info:
            reader(path)
        assert info.value.field == "path"


def test_a_nul_character_in_a_text_path_is_an_argument_error():
    from pinframes.errors import ArgumentTypeError

    with pytest.raises(ArgumentTypeError, match="NUL"):
        read_frames_yaml("frames\0.yaml")
    assert issubclass(ReadError, OSError)


_ARM = """<robot name="arm"><link name="base"/><link name="tip"/>
  <joint name="turn" type="continuous"><parent link="base"/><child link="tip"/></joint>
</robot>"""


def test_a_scene_naming_one_trajectory_many_times_reads_it_once(tmp_path):
    # a 163-byte scene of YAML aliases to one robot entry read its trajectory once per alias
    # (12 times, 1.5 GB), before finding that the second robot clashes with the first
    samples = 400_000
    np.savez(tmp_path / "motion.npz", times=np.arange(samples) * 0.01,
             positions=np.zeros((samples, 1)), joint_names=np.array(["turn"]))
    (tmp_path / "arm.urdf").write_text(_ARM)
    scene = tmp_path / "scene.yaml"
    scene.write_text("pinframes_scene: 1\nrobots: [&r {urdf: arm.urdf, trajectory: "
                     "motion.npz}" + ", *r" * 11 + "]\n")
    tracemalloc.start()
    try:
        read_joint_trajectory(tmp_path / "motion.npz")
        once = tracemalloc.get_traced_memory()[1]
        tracemalloc.reset_peak()
        with pytest.raises(FrameExistsError, match="robots\\[1\\]"):
            read_scene(scene)
        whole = tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()
    assert whole < 3 * once, (whole, once)  # 12 reads held at once took 12 times as much


def test_robots_sharing_one_urdf_and_trajectory_file_each_move_with_it(tmp_path):
    # the files are read once for the three robots, which must not share anything else
    np.savez(tmp_path / "motion.npz", times=np.array([0.0, 1.0]),
             positions=np.array([[0.0], [1.0]]), joint_names=np.array(["turn"]))
    (tmp_path / "arm.urdf").write_text(_ARM)
    scene = tmp_path / "scene.yaml"
    scene.write_text("pinframes_scene: 1\nrobots:\n" + "".join(
        f"  - {{urdf: arm.urdf, trajectory: ./motion.npz, prefix: {prefix}/, xyz: [{x}, 0, 0]}}\n"
        for x, prefix in enumerate("abc")))
    tree = read_scene(scene)
    tree.set_joint_trajectory([0.0, 1.0], [[0.0], [-1.0]], ["c/turn"])  # one robot only
    for x, (prefix, turn) in enumerate([("a", 0.5), ("b", 0.5), ("c", -0.5)]):
        pose = tree.pose(f"{prefix}/tip", "world", times=[0.5])  # turned about x, 0.5 rad
        np.testing.assert_allclose(pose.translation[0], [x, 0, 0], atol=1e-12)
        np.testing.assert_allclose(pose.rotation[0], [[1, 0, 0],
                                                      [0, np.cos(turn), -np.sin(turn)],
                                                      [0, np.sin(turn), np.cos(turn)]],
                                   atol=1e-12)


def _expanded(node: yaml.Node) -> tuple[int, int]:
    """Nodes and levels of a node composed by PyYAML, each alias expanded (recursively)."""
    if isinstance(node, yaml.ScalarNode):
        return 1, 1
    children = node.value if isinstance(node, yaml.SequenceNode) else [
        part for pair in node.value for part in pair]
    sizes = [_expanded(child) for child in children]
    return 1 + sum(size for size, _ in sizes), 1 + max((depth for _, depth in sizes), default=0)


@pytest.mark.parametrize("text", [
    "a: &x [1, 2, [3, 4]]\nb: [*x, *x]\nc: {k: *x}\n", "- &a {p: [1, [2, [3]]]}\n- [*a, [*a]]\n",
    "- &s 5\n- *s\n- [*s, *s]\n", "[[[[[]]]]]\n", alias_bomb(levels=3, width=3)])
def test_the_yaml_limits_count_the_document_with_its_aliases_expanded(text, tmp_path):
    # the composer counts as it goes; PyYAML's whole composed graph, expanded, is the yardstick
    nodes, levels = _expanded(yaml.compose(text, Loader=yaml.SafeLoader))
    path = tmp_path / "frames.yaml"
    path.write_text(text)
    for name, needed in (("max_yaml_nodes", nodes), ("max_depth", levels)):
        with pytest.raises(FileFormatError, match=f"{name}={needed - 1:,}"):
            _parse(path, **{name: needed - 1})
        _parse(path, **{name: needed})  # at the limit: read


def _parse(path: Path, **limits: int) -> object:
    with using_limits(Limits(**limits)):
        return InputFile(path).yaml()
