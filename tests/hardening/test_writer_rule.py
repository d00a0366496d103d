"""Every writer writes a file its own reader accepts with the same meaning, or refuses
before writing, naming the frame and the field.

Trees get names and numbers from the hostile ranges: control characters, YAML and XML
separators, lone surrogates, words YAML 1.1 reads as other types, extreme and tiny floats.
A refusal must be a pinframes error that leaves no file; a file written must read back with
the same frames, parents and poses.
"""

from __future__ import annotations

import tempfile
import warnings
from functools import partial
from pathlib import Path

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import pinframes
from pinframes import FrameTree, Pose
from pinframes.errors import PinframesError, UnitWarning

HOSTILE_CHARACTERS = (
    "\x00\x01\t\n\r\x1b\x7f\x85\u2028\u2029\ufeff"  # control characters and line breaks
    "/:#&*!|>'\"%@`,[]{}?-<=. \\"  # YAML, XML and path separators
    "\ud800\udfff"  # lone surrogates
    "aZ09_é中\U0001f600"  # ordinary letters, digits, non-ASCII
)
YAML_WORDS = ["null", "~", "true", "no", "010", "1:30", "-", "...", "---", ".inf", "0x1F",
              "1e3", "<<", "=", "!tag", "&a", "*a"]
EXTREME_FLOATS = [0.0, -0.0, 5e-324, -1e-300, 0.1, 1e15, -1e300, 1e306]

WRITERS = {
    "urdf": (".urdf", pinframes.write_urdf, pinframes.read_urdf),
    "frames.yaml": (".yaml", pinframes.write_frames_yaml, pinframes.read_frames_yaml),
    "scene": (".yaml", pinframes.write_scene, pinframes.read_scene),
    "asdf-1.0.0": (".asdf", partial(pinframes.write_asdf, schema="1.0.0"), pinframes.read_asdf),
    "asdf-0.1.0": (".asdf", partial(pinframes.write_asdf, schema="0.1.0"), pinframes.read_asdf),
    "mcap": (".mcap", pinframes.write, pinframes.read),
    "ros1 bag": (".bag", pinframes.write, pinframes.read),
}

names = st.one_of(st.text(st.sampled_from(HOSTILE_CHARACTERS), min_size=1, max_size=5),
                  st.sampled_from(YAML_WORDS))
numbers = st.one_of(st.sampled_from(EXTREME_FLOATS),
                    st.floats(-1e6, 1e6, allow_nan=False, allow_infinity=False))


@st.composite
def hostile_trees(draw) -> FrameTree:
    frame_names = draw(st.lists(names, min_size=2, max_size=4, unique=True))
    tree = FrameTree(frame_names[0])
    for position, name in enumerate(frame_names[1:], start=1):
        parent = frame_names[draw(st.integers(0, position - 1))]
        translation = [draw(numbers) for _ in range(3)]
        yaw = draw(st.sampled_from([0.0, 1e-300, 0.5, -3.0]))
        tree.add(name, parent, Pose.from_xyz_rpy(*translation, yaw=yaw))
    return tree


def expected_names(tree: FrameTree, writer: str) -> dict[str, str]:
    """The name each frame gets back: frames.yaml keys are ``/``-joined paths below the root."""
    if writer != "frames.yaml":
        return {name: name for name in tree.frames}
    mapped = {tree.root: "world"}
    for name in tree.frames[1:]:
        parent = tree.parent(name)
        mapped[name] = name if parent == tree.root else f"{mapped[parent]}/{name}"
    return mapped


def check_rule(tree: FrameTree, writer: str, folder: Path) -> None:
    suffix, write, read = WRITERS[writer]
    path = folder / f"{'frames' if writer == 'frames.yaml' else 'tree'}{suffix}"
    path.unlink(missing_ok=True)
    try:
        write(tree, path)
    except PinframesError as refusal:
        assert not path.exists(), f"refused, but wrote {path}: {refusal}"
        assert refusal.frame is not None or refusal.field is not None, str(refusal)
        return
    with warnings.catch_warnings():  # drawn lengths may look like millimetres: not compared
        warnings.simplefilter("ignore", UnitWarning)
        copy = read(path)
    names_back = expected_names(tree, writer)
    assert sorted(copy.frames) == sorted(names_back.values())
    for name in tree.frames[1:]:
        assert copy.parent(names_back[name]) == names_back[tree.parent(name)]
        # Writers may query a frame's pose in its parent, which carries the rounding of the
        # distance from the root (static frames are flattened onto it): 1e15 m away, digits
        # below 0.125 m are gone. The same meaning is the same pose up to that rounding.
        original, again = tree.local_pose(name), copy.local_pose(names_back[name])
        scale = sum(np.abs(tree.pose(frame, tree.root).translation).max()
                    for frame in (name, tree.parent(name)))
        np.testing.assert_allclose(again.translation, original.translation, rtol=1e-12,
                                   atol=1e-12 + 1e-15 * scale, err_msg=f"{writer}: {name!r}")
        np.testing.assert_allclose(again.rotation, original.rotation, atol=1e-12)


@pytest.mark.parametrize("writer", list(WRITERS))
@settings(max_examples=20, deadline=None, derandomize=True, database=None,
          suppress_health_check=[HealthCheck.too_slow, HealthCheck.function_scoped_fixture])
@given(tree=hostile_trees())
def test_a_writer_writes_what_its_reader_reads_or_refuses(writer, tree):
    with tempfile.TemporaryDirectory() as folder:
        check_rule(tree, writer, Path(folder))


@pytest.mark.parametrize("writer", list(WRITERS))
def test_the_issue_examples(writer, tmp_path):
    # each was written and then refused on read, or read back with another meaning
    examples = [
        [("a\x01b", "world")],  # XML cannot hold it
        [("a\x85b", "world")],  # YAML read it back as "a b"
        [("base", "world"), ("/lead", "base")],  # frames.yaml wrote base//lead
        [("a\ud800", "world")],  # a bare UnicodeEncodeError
    ]
    for frames in examples:
        tree = FrameTree("world")
        for name, parent in frames:
            tree.add(name, parent, Pose([0.5, 0.0, 0.0]))
        check_rule(tree, writer, tmp_path)


@pytest.mark.parametrize("writer", ["urdf", "frames.yaml", "scene", "asdf-1.0.0", "mcap"])
def test_writers_that_cannot_hold_data_refuse_it_by_name(tmp_path, writer):
    suffix, write, _ = WRITERS[writer]
    tree = FrameTree("world")
    tree.add("torch", "world", Pose([0.5, 0.0, 0.3]))
    tree.assign_data("seam", pinframes.SpatialData([[0.01, 0.0, 0.0]]), "torch")
    path = tmp_path / f"cell{suffix}"
    with pytest.raises(pinframes.UnsupportedFeatureError, match="'seam' on frame 'torch'") as info:
        write(tree, path)
    assert info.value.file == str(path) and info.value.frame == "torch"
    assert "schema '0.1.0'" in info.value.message
    assert not path.exists()
    tree.delete_data("seam")  # without the data the same tree is written
    write(tree, path)
    assert path.exists()
