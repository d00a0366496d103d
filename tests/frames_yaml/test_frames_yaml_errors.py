"""Bad frames.yaml files: errors name the file, the key and the field."""

import textwrap
from pathlib import Path

import pytest

from pinframes import FramesYamlWarning, read_frames_yaml
from pinframes.errors import FileFormatError


def layer(folder: Path, text: str, name: str = "frames.yaml") -> Path:
    path = folder / name
    path.write_text(textwrap.dedent(text))
    return path


def read_error(path: Path) -> FileFormatError:
    with pytest.raises(FileFormatError) as info:
        read_frames_yaml(path)
    assert info.value.file == str(path)
    return info.value


def test_yaml_syntax_error_gives_the_line(tmp_path):
    error = read_error(layer(tmp_path, "frames:\n  a: {pose: {x: 1}\n  b: {}\n"))
    assert "YAML syntax error at line 3" in str(error)


def test_duplicate_frame_keys_are_reported(tmp_path):
    error = read_error(layer(tmp_path, """
        frames:
          a: {pose: {x: 1}}
          b: {}
          a: {pose: {x: 2}}
        """))
    assert error.frame == "a"
    assert "duplicate key 'a' at line 5 (first at line 3)" in str(error)


def test_a_mis_indented_key_that_duplicates_fields_is_reported(tmp_path):
    # The shape of a real map-editor file: the next key slipped into the frame above.
    error = read_error(layer(tmp_path, """
        frames:
          a:
            pose: {x: 1}
            relative_to: ''
            a/b:
            pose: {x: 2}
            relative_to: a
        """))
    assert (error.frame, error.field) == ("a", "pose")
    assert "at line 7 (first at line 4)" in str(error)


def test_duplicate_pose_fields_are_reported(tmp_path):
    error = read_error(layer(tmp_path, "frames:\n  a:\n    pose: {x: 1, y: 2, x: 3}\n"))
    assert (error.frame, error.field) == ("a", "pose.x")


@pytest.mark.parametrize(("frames", "frame", "field"), [
    ("a: {pose: {x: abc}}", "a", "pose.x"),
    ("a: {pose: {yaw: '1.0'}}", "a", "pose.yaw"),
    ("a: {pose: {z: true}}", "a", "pose.z"),
    ("a: {pose: [1, 2, 3]}", "a", "pose"),
    ("a: {relative_to: 5}", "a", "relative_to"),
    ("a: {unit: feet}", "a", "unit"),
    ("a: {twist: {v_x: fast}}", "a", "twist.v_x"),
    ("a: [1, 2]", "a", None),
    ("a: ~", "a", None),
    ("1: {}", "1", None),
    ("a//b: {}", "a//b", None),
    ("/a: {}", "/a", None),
])
def test_wrong_types_name_the_key_and_field(tmp_path, frames, frame, field):
    error = read_error(layer(tmp_path, f"frames:\n  {frames}\n"))
    assert (error.frame, error.field) == (frame, field)


@pytest.mark.parametrize("value", [".nan", ".inf", "-.inf"])
def test_non_finite_numbers_are_refused(tmp_path, value):
    error = read_error(layer(tmp_path, f"frames:\n  a: {{pose: {{roll: {value}}}}}\n"))
    assert (error.frame, error.field) == ("a", "pose.roll")
    assert "finite" in str(error)


@pytest.mark.parametrize(("text", "field"), [
    ("[1, 2]", None), ("version: 1.0", "frames"), ("frames: [a, b]", "frames"),
    ("version: [1]\nframes: {}", "version")])
def test_top_level_shape(tmp_path, text, field):
    assert read_error(layer(tmp_path, text + "\n")).field == field


def test_a_main_yaml_is_recognised(tmp_path):
    error = read_error(layer(tmp_path, "main:\n  frames: !include frames.yaml\n"))
    assert "unsupported YAML tag '!include' at line 2" in str(error)
    error = read_error(layer(tmp_path, "main: {}\n"))
    assert "main.yaml" in str(error)


def test_custom_tags_in_frames_are_refused(tmp_path):
    error = read_error(layer(tmp_path, "frames:\n  a: {pose: !pose [1, 2, 3]}\n"))
    assert (error.frame, error.field) == ("a", "pose")
    assert "'!pose'" in str(error)


def test_a_frame_relative_to_itself(tmp_path):
    error = read_error(layer(tmp_path, "frames:\n  a: {relative_to: a}\n"))
    assert (error.frame, error.field) == ("a", "relative_to")
    assert "itself" in str(error)


def test_relative_to_cycles_name_the_frames(tmp_path):
    error = read_error(layer(tmp_path, """
        frames:
          a: {relative_to: c}
          b: {relative_to: a}
          c: {relative_to: b}
          d: {}
        """))
    assert error.field == "relative_to"
    assert error.frame in ("a", "b", "c")
    message = str(error)
    assert all(f"'{name}' is relative to" in message for name in "abc")
    assert "'d'" not in message


def test_relative_to_a_descendant_is_a_cycle(tmp_path):
    error = read_error(layer(tmp_path, "frames:\n  a: {relative_to: a/b}\n  a/b: {}\n"))
    assert (error.frame, error.field) == ("a", "relative_to")
    assert "'a/b' is inside 'a'" in str(error)


def test_unknown_fields_warn(tmp_path):
    path = layer(tmp_path, """
        author: someone
        frames:
          a: {pose: {x: 1, theta: 2}}
        """)
    with pytest.warns(FramesYamlWarning) as record:
        read_frames_yaml(path)
    messages = [str(item.message) for item in record]
    assert any("unknown top-level field 'author'" in m for m in messages)
    assert any("frame 'a'" in m and "'pose.theta'" in m for m in messages)
    assert all(str(path) in m for m in messages)


def test_a_key_named_like_the_root_is_refused(tmp_path):
    path = layer(tmp_path, "frames:\n  world: {}\n")
    assert read_error(path).frame == "world"
    assert read_frames_yaml(path, root="origin").parent("world") == "origin"


def test_tiles_without_tile_maps_yaml(tmp_path):
    error = read_error(layer(tmp_path, "frames:\n  m: {}\n  m/t: {unit: tiles}\n"))
    assert (error.frame, error.field) == ("m/t", "unit")
    assert "tile_maps.yaml" in str(error)


def test_tiles_without_a_listed_ancestor(tmp_path):
    layer(tmp_path, "tile_maps: {other: {tile_size: {x: 1, y: 1}}}\n", name="tile_maps.yaml")
    error = read_error(layer(tmp_path, "frames:\n  m/t: {unit: tiles}\n"))
    assert (error.frame, error.field) == ("m/t", "unit")
    assert "none of its ancestors (m)" in str(error)


def test_a_bad_tile_maps_yaml_is_named(tmp_path):
    tile_maps = layer(tmp_path, "tile_maps: {m: {tile_size: {x: -1, y: 1}}}\n",
                      name="tile_maps.yaml")
    with pytest.raises(FileFormatError) as info:
        read_frames_yaml(layer(tmp_path, "frames:\n  m/t: {unit: tiles}\n"))
    assert (info.value.file, info.value.frame, info.value.field) == (
        str(tile_maps), "m", "tile_size")
