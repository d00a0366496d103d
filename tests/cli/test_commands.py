"""``pinframes`` help, info, convert and plot, run in a subprocess."""

import io
import os
import pty
import subprocess
import sys

import numpy as np
import pinocchio as pin
import pytest
import yaml

from conftest import SHARED_DATA

PNG_SIGNATURE = b"\x89PNG\r\n\x1a\n"


@pytest.mark.parametrize("subcommand", [[], ["demo"], ["info"], ["pose"], ["convert"],
                                        ["plot"]])
def test_help_everywhere(run_cli, subcommand):
    result = run_cli(*subcommand, "--help")
    assert result.returncode == 0
    assert result.stdout.startswith("usage: pinframes")
    assert result.stderr == ""


def test_no_subcommand_is_a_usage_error(run_cli):
    result = run_cli()
    assert result.returncode == 2
    assert "usage: pinframes" in result.stderr


def test_info_lists_frames_with_kind_span_and_reference(run_cli, turntable):
    result = run_cli("info", turntable)
    assert result.returncode == 0, result.stderr
    lines = result.stdout.splitlines()
    assert lines[0] == ("tree turntable: 3 frames, 1 moving, 0 robot joints (0 with samples); "
                        "reference time none")
    assert lines[1].split() == ["FRAME", "KIND", "TIME", "SPAN", "REFERENCE", "TIME"]
    assert lines[2].split() == ["world", "root"]
    assert lines[3].split() == ["`--", "table", "moving", "0", "s", "..", "10", "s", "(2",
                                "keyframes)", "none"]
    assert lines[4].split() == ["`--", "tip", "static"]


def test_info_shows_robot_joints(run_cli, tmp_path):
    (tmp_path / "arm.urdf").write_text(
        "<robot name='arm'><link name='base'/><link name='tip'/>"
        "<joint name='turn' type='continuous'><parent link='base'/><child link='tip'/>"
        "<axis xyz='0 0 1'/></joint></robot>")
    (tmp_path / "motion.csv").write_text("time_s,turn\n1,0\n3,1\n")
    scene = tmp_path / "arm.yaml"
    scene.write_text("pinframes_scene: 1\nreference_time: 2024-03-01T08:00:00\nrobots:\n"
                     "- {urdf: arm.urdf, trajectory: motion.csv}\n")
    result = run_cli("info", scene)
    assert result.returncode == 0, result.stderr
    tip = next(line for line in result.stdout.splitlines() if "tip" in line)
    assert tip.split()[2:] == ["robot", "joint", "turn", "(continuous)", "1", "s", "..", "3",
                               "s", "(2", "samples)", "2024-03-01T08:00:00.000000000",
                               "(tree)"]


def test_convert_scene_to_urdf_at_a_time(run_cli, turntable, tmp_path):
    out = tmp_path / "snapshot.urdf"
    result = run_cli("convert", turntable, out, "--time", "5")
    assert result.returncode == 0, result.stderr
    model = pin.buildModelFromUrdf(str(out))  # read back by Pinocchio itself
    data = model.createData()
    pin.framesForwardKinematics(model, data, pin.neutral(model))
    tip = data.oMf[model.getFrameId("tip")]
    angle = np.pi / 4
    np.testing.assert_allclose(tip.translation,
                               [1 + 0.2 * np.cos(angle), 0.2 * np.sin(angle), 0.5], atol=1e-9)


@pytest.mark.slow  # seconds of CPU (subprocesses): CI's slow set
def test_convert_scene_to_scene_and_errors(run_cli, turntable, tmp_path):
    out = tmp_path / "copy.yaml"
    assert run_cli("convert", turntable, out).returncode == 0
    before = run_cli("pose", turntable, "tip", "-r", "world", "--step", "0.5").stdout
    after = run_cli("pose", out, "tip", "-r", "world", "--step", "0.5").stdout
    np.testing.assert_allclose(np.loadtxt(io.StringIO(after), delimiter=",", skiprows=1),
                               np.loadtxt(io.StringIO(before), delimiter=",", skiprows=1),
                               atol=1e-15)
    out.write_text("keep me")
    result = run_cli("convert", turntable, tmp_path / "x.txt")
    assert result.returncode == 1
    assert "unknown file type '.txt'" in result.stderr
    result = run_cli("convert", turntable, out, "--schema", "1.0.0")
    assert result.returncode == 1
    assert "--schema is for ASDF files, not scene" in result.stderr
    assert out.read_text() == "keep me"  # a failed convert leaves the target untouched


def test_unreadable_yaml_kinds(run_cli, tmp_path):
    neither = tmp_path / "cell.yaml"
    neither.write_text("something: 1\n")
    result = run_cli("info", neither)
    assert result.returncode == 1
    assert "neither a scene" in result.stderr
    broken = tmp_path / "broken.yaml"
    broken.write_text("pinframes_scene: 1\nframes: [\n")
    result = run_cli("info", broken)
    assert result.returncode == 1
    assert result.stderr.startswith(f"pinframes: error: {broken}: YAML syntax error at line")


@pytest.mark.slow  # seconds of CPU (subprocesses): CI's slow set
def test_plot_writes_png(run_cli, turntable, tmp_path):
    out = tmp_path / "frames.png"
    result = run_cli("plot", turntable, "--frames", "table", "tip", "-r", "world", "-o", out)
    assert result.returncode == 0, result.stderr
    assert out.read_bytes()[:8] == PNG_SIGNATURE
    result = run_cli("plot", turntable, "--frames", "nope", "-o", out)
    assert result.returncode == 1
    assert "frame 'nope'" in result.stderr


def test_plot_without_matplotlib_says_how_to_get_it(turntable, tmp_path, cli_env):
    code = ("import sys; sys.modules['matplotlib'] = None; from pinframes.cli import main; "
            f"sys.exit(main(['plot', {str(turntable)!r}, '-o', {str(tmp_path / 'x.png')!r}]))")
    result = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                            env=cli_env, timeout=120)
    assert result.returncode == 1
    assert result.stderr.strip() == ('pinframes: error: plotting needs matplotlib: pip '
                                     'install "pinframes[plot]"')


def test_progress_bar_on_a_terminal_only(run_cli, turntable, cli_env):
    args = ("pose", turntable, "tip", "-r", "world", "--step", "0.0002", "-f", "npz", "-o")
    result = run_cli(*args, turntable.parent / "p.npz")
    assert result.returncode == 0
    assert result.stderr == ""  # not a terminal: no bar
    leader, follower = pty.openpty()
    process = subprocess.run(
        [sys.executable, "-m", "pinframes.cli", *map(str, args), turntable.parent / "q.npz"],
        stdout=subprocess.PIPE, stderr=follower, env=cli_env, timeout=120)
    os.close(follower)
    shown = b""
    while True:
        try:
            chunk = os.read(leader, 4096)
        except OSError:
            break
        if not chunk:
            break
        shown += chunk
    os.close(leader)
    assert process.returncode == 0
    assert b"100%  50001/50001 samples" in shown
    with np.load(turntable.parent / "p.npz") as plain, \
            np.load(turntable.parent / "q.npz") as barred:
        np.testing.assert_array_equal(plain["translation"], barred["translation"])


def test_convert_scene_to_frames_yaml_and_back(run_cli, turntable, tmp_path):
    out = tmp_path / "frames_snapshot.yaml"
    result = run_cli("convert", turntable, out, "--time", "10")
    assert result.returncode == 0, result.stderr
    frames = yaml.safe_load(out.read_text())["frames"]  # read back with plain PyYAML
    table = frames["table"]["pose"]
    assert (table["x"], table["y"], table["z"]) == (1.0, 0.0, 0.5)
    assert table["yaw"] == pytest.approx(np.pi / 2, abs=1e-12)
    assert frames["table/tip"]["pose"]["x"] == pytest.approx(0.2, abs=1e-15)
    result = run_cli("pose", out, "table/tip", "-r", "world")
    assert result.returncode == 0, result.stderr
    row = result.stdout.splitlines()[1].split(",")
    assert row[0] == "nan"  # nothing moves: a static pose, no time
    np.testing.assert_allclose([float(v) for v in row[1:4]], [1.0, 0.2, 0.5], atol=1e-12)
    result = run_cli("convert", turntable, out)
    assert result.returncode == 1  # a moving tree needs --time for frames.yaml
    assert result.stderr.startswith("pinframes: error: ")


def test_info_on_a_real_duckietown_map(run_cli):
    path = SHARED_DATA / "duckietown-maps" / "dt-gui-tools__loop_objects" / "frames.yaml"
    if not path.is_file():
        pytest.skip("shared sample data not present")
    result = run_cli("info", path)
    assert result.returncode == 0, result.stderr
    declared = yaml.safe_load(path.read_text())["frames"]
    listed = result.stdout
    assert all(key.rsplit("/", 1)[-1] in listed for key in declared)


def test_info_lists_subsystems():
    from pinframes import FrameTree, Subsystem
    from pinframes.cli.info import describe

    tree = FrameTree(name="cell")
    tree.add("robot_base", "world")
    tree.add("tcp", "robot_base")
    tree.subsystems.append(Subsystem("robot", "robot_base", ("robot_base", "tcp"),
                                     parent="cell"))
    lines = describe(tree).splitlines()
    assert lines[-1] == "subsystem robot: root robot_base, 2 frames, merged into cell"
