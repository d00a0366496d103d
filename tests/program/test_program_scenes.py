"""A scene's ``program:`` section: read (inline limits or a real MoveIt joint_limits.yaml),
kept when the scene is written, planned by ``pinframes program``; its errors name the field
or the move."""

from __future__ import annotations

import shutil
from pathlib import Path

import numpy as np
import pytest
import yaml

import pinframes
from pinframes.cli import main
from program_cells import ROBOT_URDF, tool_origins

FANUC_LIMITS = Path(__file__).parents[1] / "data" / "moveit_resources" / \
    "fanuc_joint_limits.yaml"

SCENE = """\
pinframes_scene: 1
frames:
  - name: seam_point
    parent: world
    keyframes:
      - {time: 0, xyz: [0.55, -0.1, 0.3], rpy: [0, 0, 1.5707963267948966]}
      - {time: 10, xyz: [0.55, 0.1, 0.3], rpy: [0, 0, 1.5707963267948966]}
  - name: torch_target
    parent: seam_point
    rpy: [3.141592653589793, 0, 0]
  - name: above
    parent: world
    xyz: [0.6, 0.0, 0.5]
    rpy: [3.141592653589793, 0, 0]
robots:
  - urdf: robot.urdf
    parent: world
    prefix: robot/
tools:
  - name: tcp
    parent: robot/flange
    xyz: [0, 0, 0.2]
program:
  tool: tcp
  limits: {LIMITS}
  start: &home {joint_1: 0.0, joint_2: 0.3, joint_3: -0.3, joint_4: 0.0, joint_5: 0.8, joint_6: 0.0}
  step: 0.008
  moves:
    - move_joints: above
      name: over the part
    - move_linear: torch_target
      speed: 0.2
      name: down
    - weld: seam_point
      torch: torch_target
      speed: 0.05
      approach: 0.03
      name: seam 1
    - wait: 0.5
    - move_joints: *home
      name: home
"""
INLINE = "{" + ", ".join(f"joint_{i}: {{acceleration: 6.0}}" for i in range(1, 7)) + "}"


def _scene(tmp_path: Path, limits: str = INLINE, text: str = SCENE) -> Path:
    shutil.copy(ROBOT_URDF, tmp_path / "robot.urdf")
    shutil.copy(FANUC_LIMITS, tmp_path / "joint_limits.yaml")
    path = tmp_path / "cell.yaml"
    path.write_text(text.replace("{LIMITS}", limits))
    return path


def test_the_section_plans_as_written(tmp_path):
    program = pinframes.read_program(_scene(tmp_path))
    motion = program.plan()
    assert [record.name for record in motion.moves] == [
        "over the part", "down", "seam 1: to approach", "seam 1: approach", "seam 1: seam",
        "seam 1: retract", "wait 4", "home"]
    assert np.diff(motion.seconds).max() == pytest.approx(0.008)
    assert motion.all_reached
    # the tool over the part after the first move, at the seam's end after the seam
    over = round(motion.move("over the part").end_s / 0.008)
    np.testing.assert_allclose(tool_origins(motion.positions[over]), [[0.6, 0.0, 0.5]],
                               atol=1e-5)
    end = round(motion.move("seam 1: seam").end_s / 0.008)
    np.testing.assert_allclose(tool_origins(motion.positions[end]), [[0.55, 0.1, 0.3]],
                               atol=1e-5)
    assert motion.move("seam 1: seam").requested_speed == pytest.approx(0.05)


def test_limits_from_a_moveit_joint_limits_file(tmp_path):
    limits = pinframes.read_joint_limits(FANUC_LIMITS)
    program = pinframes.read_program(_scene(tmp_path, "joint_limits.yaml"))
    for column in range(6):
        record = limits[f"joint_{column + 1}"]
        assert program.limits.velocity[column] == record.velocity  # the file's, not the URDF's
        assert program.limits.acceleration[column] == record.acceleration


@pytest.mark.filterwarnings("ignore::pinframes.JointWithoutSamplesWarning")
def test_write_scene_keeps_the_section(tmp_path):
    tree = pinframes.read_scene(_scene(tmp_path))
    pinframes.write_scene(tree, tmp_path / "written.yaml")
    written = yaml.safe_load((tmp_path / "written.yaml").read_text())
    assert written["program"] == tree.metadata["program"]
    assert [next(iter(move)) for move in written["program"]["moves"]] == [
        "move_joints", "move_linear", "weld", "wait", "move_joints"]


@pytest.mark.parametrize(("change", "message"), [
    ("      speed: 0.2\n      name: down", "program.moves[1].speed': missing"),
    ("    - wait: 0.5", "program.moves[3]"),
    ("  step: 0.008", "program.step"),
])
def test_malformed_sections_name_the_field(tmp_path, change, message):
    broken = {"      speed: 0.2\n      name: down": "      name: down",
              "    - wait: 0.5": "    - wait: 0.5\n      move_linear: above",
              "  step: 0.008": "  step: -1"}[change]
    with pytest.raises(pinframes.FileFormatError, match=message.replace("[", r"\[")
                       .replace("]", r"\]")):
        pinframes.read_scene(_scene(tmp_path, text=SCENE.replace(change, broken)))


def test_command_plans_prints_and_writes(tmp_path, capsys):
    scene = _scene(tmp_path)
    assert main(["program", str(scene), "-o", str(tmp_path / "run.csv"),
                 "--check", "robot/link_6", "robot/base_link", "--step", "0.004"]) == 0
    out = capsys.readouterr().out
    assert "cycle time" in out and "slowest move    seam 1: seam" in out
    assert "seam 1: approach" in out and "collisions      none" in out
    # a check that finds something: the first link turns on the base it touches
    assert main(["program", str(scene), "-o", str(tmp_path / "other.csv"),
                 "--check", "robot/link_1", "robot/base_link"]) == 0
    assert "collision       over the part: robot/link_1 - robot/base_link" in \
        capsys.readouterr().out
    times, _, names = pinframes.read_joint_trajectory(tmp_path / "run.csv")
    assert names == [f"joint_{i}" for i in range(1, 7)]
    assert np.diff(times).max() == pytest.approx(0.004)


@pytest.mark.parametrize(("change", "move"), [
    ("move_linear: torch_target", "down"),
    ("weld: seam_point", "seam 1"),
    ("move_joints: above", "over the part"),
])
def test_a_name_the_scene_lacks_is_an_error_naming_the_move(tmp_path, capsys, change, move):
    text = SCENE.replace(change, change.split(":")[0] + ": no_such_frame")
    scene = _scene(tmp_path, text=text)
    assert main(["program", str(scene), "-o", str(tmp_path / "run.csv")]) == 1
    error = capsys.readouterr().err
    assert f"move {move!r}" in error and "no_such_frame" in error
    assert not (tmp_path / "run.csv").exists()


@pytest.mark.slow
def test_the_bundled_cells_program():
    program = pinframes.read_program(
        Path(pinframes.__file__).parent / "models" / "welding_cell" / "scene.yaml")
    motion = program.plan()
    assert [record.kind for record in motion.moves] == [
        "joints", "joints", "approach", "seam", "retract", "joints"]
    assert motion.all_reached and motion.collisions == ()
    assert 20.0 < motion.cycle_time < 30.0


def _docs_block(language: str) -> str:
    docs = (Path(__file__).parents[2] / "docs" / "programs.md").read_text()
    return docs.split(f"```{language}\n", 1)[1].split("```", 1)[0]


def test_the_docs_scene_section_reads(tmp_path):
    """docs/programs.md's program section, in a scene with the robot, reads as written."""
    scene = _scene(tmp_path).read_text().split("program:")[0] + _docs_block("yaml")
    (tmp_path / "cell.yaml").write_text(scene)
    tree = pinframes.read_scene(tmp_path / "cell.yaml")
    section = tree.metadata["program"]
    assert [next(iter(move)) for move in section["moves"]] == [
        "move_joints", "move_linear", "weld", "wait"]
    assert section["moves"][2]["weave"] == {"amplitude": 0.002, "frequency": 1.5,
                                            "pattern": "triangle"}
    assert section["limits"]["joint_1"]["acceleration"] == pinframes.read_joint_limits(
        FANUC_LIMITS)["joint_1"].acceleration


@pytest.mark.slow
def test_the_docs_python_example_runs(tmp_path, monkeypatch):
    code = _docs_block("python").replace(
        '"models/welding_cell/scene.yaml"',
        repr(str(Path(pinframes.__file__).parent / "models" / "welding_cell" / "scene.yaml")))
    monkeypatch.chdir(tmp_path)
    exec(compile(code, "docs/programs.md", "exec"), {})
    assert (tmp_path / "run.mcap").is_file()
