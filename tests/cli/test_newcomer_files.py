"""Files a new user hands to the wrong reader, or half right: what the messages say."""

from __future__ import annotations

import textwrap
from pathlib import Path

import pytest

from pinframes import FileFormatError, read, read_frames_yaml

SCENE_WITHOUT_ITS_LINE = """\
    name: turntable
    frames:
      - name: table
        parent: world
        xyz: [1.0, 0.0, 0.5]
    tools:
      - {name: tip, parent: table, xyz: [0.2, 0, 0]}
    """


@pytest.fixture
def scene_without_its_line(tmp_path: Path) -> Path:
    path = tmp_path / "cell.yaml"
    path.write_text(textwrap.dedent(SCENE_WITHOUT_ITS_LINE))
    return path


def test_a_scene_without_its_first_line_is_named_so_on_the_command_line(
        run_cli, scene_without_its_line):
    result = run_cli("info", scene_without_its_line)
    assert result.returncode == 1
    assert result.stderr.count("\n") == 1  # one error line, no frames.yaml warnings
    assert "pinframes: error:" in result.stderr
    assert "scene without its first line 'pinframes_scene: 1'" in result.stderr


def test_a_scene_without_its_first_line_is_named_so_by_read(scene_without_its_line):
    with pytest.raises(FileFormatError, match="'pinframes_scene: 1'"):
        read(scene_without_its_line)
    with pytest.warns(UserWarning), pytest.raises(FileFormatError,
                                                  match="'pinframes_scene: 1'"):
        read_frames_yaml(scene_without_its_line)
    # with the line, the same file is a scene
    fixed = scene_without_its_line.with_name("fixed.yaml")
    fixed.write_text("pinframes_scene: 1\n" + scene_without_its_line.read_text())
    assert "tip" in read(fixed).frames
