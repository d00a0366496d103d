"""Files a new user hands to the wrong reader, or half right: what the messages say."""

from __future__ import annotations

import textwrap
from pathlib import Path

import pytest

from pinframes import FileFormatError, read, read_frames_yaml, read_scene

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


MODELS = Path(__file__).resolve().parents[2] / "models"


def test_yaml_of_another_kind_says_so_not_csv(run_cli):
    """The bundled cell's design data: YAML that starts with a comment holding commas, with
    a ``format`` key of its own and a list of frames."""
    design = MODELS / "welding_cell" / "cell_design.yaml"
    result = run_cli("info", design)
    assert result.returncode == 1
    assert "CSV" not in result.stderr
    assert "format: 'pinframes-welding-cell'" in result.stderr
    assert "no pinframes reader takes" in result.stderr


def test_a_scene_starting_with_a_comment_that_holds_commas_reads(run_cli, tmp_path):
    path = tmp_path / "cell.yaml"
    path.write_text("# turntable and tip, in metres and radians\n"
                    + textwrap.dedent(SCENE_WITHOUT_ITS_LINE).replace(
                        "name: turntable", "pinframes_scene: 1\nname: turntable"))
    result = run_cli("info", path)
    assert result.returncode == 0, result.stderr
    assert "tip" in result.stdout


def test_a_table_of_points_names_the_command_that_takes_it(run_cli):
    result = run_cli("info", MODELS / "welding_cell" / "torch_scan.csv")
    assert result.returncode == 1
    assert "joint values" not in result.stderr
    assert "a CSV table of points" in result.stderr and "'pinframes transform'" in result.stderr


@pytest.mark.parametrize("reader", [read_scene, read_frames_yaml])
def test_a_yaml_reader_given_a_urdf_says_what_it_is_and_what_reads_it(reader):
    urdf = MODELS / "welding_robot" / "welding_robot.urdf"
    with pytest.raises(FileFormatError) as caught:
        reader(urdf)
    message = str(caught.value)
    assert "syntax" not in message
    assert "this is a URDF file" in message and "pinframes.read()" in message
    assert caught.value.file == str(urdf)
