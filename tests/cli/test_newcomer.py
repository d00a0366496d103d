"""What a new user meets first: exit codes, warnings, --help defaults, file kinds, outputs."""

import json
import shutil
import subprocess
import sys

import numpy as np
import pytest
import yaml

from pinframes import read_scene
from pinframes.cli import _parser
from pinframes.cli.demo import bundled_scene

FRAMES_YAML_WITH_UNKNOWN_TARGET = """\
version: 1.0
frames:
  car: {relative_to: ghost, pose: {x: 1.0}}
"""


def test_usage_errors_exit_with_2_and_user_errors_with_1(run_cli, turntable):
    assert run_cli("pose", turntable).returncode == 2  # FRAME missing: argparse usage
    assert run_cli("pose", turntable, "tip", "--format", "xml").returncode == 2
    assert run_cli("pose", turntable, "nope").returncode == 1


def test_a_warning_is_one_line(run_cli, tmp_path):
    path = tmp_path / "frames.yaml"
    path.write_text(FRAMES_YAML_WITH_UNKNOWN_TARGET)
    result = run_cli("info", path)
    assert result.returncode == 0, result.stderr
    lines = result.stderr.splitlines()
    assert len(lines) == 1
    assert lines[0].startswith("pinframes: warning: ") and "'ghost'" in lines[0]


def subcommand_parsers():
    parser = _parser()
    subparsers = next(a for a in parser._actions if a.choices and "pose" in a.choices)
    return [("pinframes", parser), *subparsers.choices.items()]


@pytest.mark.parametrize(("name", "parser"), subcommand_parsers())
def test_every_option_names_its_default(name, parser):
    for action in parser._actions:
        if not action.option_strings or action.help == "==SUPPRESS==":
            continue
        if action.required or action.dest in ("help", "version"):
            continue
        assert "default" in (action.help or ""), f"{name} {action.option_strings}"


def test_help_of_convert_names_the_default_schema(run_cli):
    text = " ".join(run_cli("convert", "--help").stdout.split())
    assert "(default: 0.1.0)" in text


@pytest.mark.slow  # seconds of CPU (subprocesses): CI's slow set
def test_tree_files_are_told_by_content_whatever_their_name(run_cli, tmp_path):
    scene = bundled_scene()
    asdf = tmp_path / "cell.data"
    assert run_cli("convert", scene, tmp_path / "cell.asdf").returncode == 0
    shutil.copy(tmp_path / "cell.asdf", asdf)
    urdf = tmp_path / "robot.xml"
    shutil.copy(scene.parents[1] / "welding_robot" / "welding_robot.urdf", urdf)
    shutil.copytree(scene.parents[1], tmp_path / "models")
    scene_copy = tmp_path / "models" / "welding_cell" / "scene.txt"
    shutil.copy(scene, scene_copy)  # beside the files it names
    cell_frames = len(read_scene(scene))
    for path, frames in ((asdf, cell_frames), (urdf, 8), (scene_copy, cell_frames)):
        result = run_cli("info", path, "-f", "json")
        assert result.returncode == 0, result.stderr
        assert len(json.loads(result.stdout)["frames"]) == frames, path
    result = run_cli("demo", "--scene", asdf, "--out", tmp_path / "demo")
    assert result.returncode == 0, result.stderr
    assert "seam length travelled  344.2 mm" in result.stdout


@pytest.mark.parametrize(("content", "looks_like"), [
    (b"\x89PNG\r\n\x1a\n" + bytes(range(256)), "a PNG image"),
    (b"time_s,joint_1\n0,0.5\n", "a CSV table"),
    (b"PK\x03\x04" + bytes(100), "a ZIP archive"),
    (b'<?xml version="1.0"?>\n<!-- x --><svg></svg>', "root element is <svg>, not a URDF"),
    (b"\x00\x01\x02\xff\xfe" * 50, "binary data"),
    (b"something: 1\n", "neither a scene"),
])
def test_other_files_say_what_they_look_like(run_cli, tmp_path, content, looks_like):
    path = tmp_path / "input.yaml"
    path.write_bytes(content)
    result = run_cli("info", path)
    assert result.returncode == 1
    assert looks_like in result.stderr
    assert ("pinframes reads trees from ASDF, URDF, scene, frames.yaml and ROS bag files"
            in result.stderr)


def test_info_json_describes_frames_and_joints(run_cli):
    result = run_cli("info", bundled_scene(), "--format", "json")
    assert result.returncode == 0, result.stderr
    document = json.loads(result.stdout)
    tree = read_scene(bundled_scene())
    assert document["frames"][0]["name"] == "world"
    assert sorted(frame["name"] for frame in document["frames"]) == sorted(tree.frames)
    by_name = {frame["name"]: frame for frame in document["frames"]}
    assert by_name["positioner"]["kind"] == "moving"
    assert by_name["positioner"]["samples"] == 41
    assert by_name["positioner"]["time_span_s"] == [0.0, 20.0]
    joint = by_name["robot/link_1"]["joint"]
    assert (joint["name"], joint["type"]) == ("robot/joint_1", "revolute")
    assert by_name["robot/link_1"]["samples"] == 2001
    assert by_name["torch_tcp"]["parent"] == "robot/flange"


@pytest.mark.parametrize(("suffix", "magic"), [(".jpg", b"\xff\xd8\xff"), (".svg", b"<?xml"),
                                               (".pdf", b"%PDF")])
def test_plot_writes_the_format_its_suffix_names(run_cli, turntable, tmp_path, suffix, magic):
    out = tmp_path / f"frames{suffix}"
    result = run_cli("plot", turntable, "-o", out)
    assert result.returncode == 0, result.stderr
    assert out.read_bytes().startswith(magic)


def test_plot_refuses_a_suffix_without_an_image_format(run_cli, turntable, tmp_path):
    result = run_cli("plot", turntable, "-o", tmp_path / "frames.txt")
    assert result.returncode == 1
    assert "cannot tell an image format from the suffix '.txt'" in result.stderr
    assert ".png" in result.stderr and ".jpg" in result.stderr
    assert not (tmp_path / "frames.txt").exists()


@pytest.mark.parametrize(("command", "name", "expected"), [
    ("pose", "out.xlsx", "name the file .csv, .json, .npz, or pass --format"),
    ("transform", "out.xlsx", "this command writes CSV: name the file .csv"),
    ("view", "cell.png", "this command writes an HTML page: name the file .html or .htm"),
])
def test_outputs_refuse_a_suffix_that_names_another_format(run_cli, turntable, tmp_path,
                                                           command, name, expected):
    data = tmp_path / "points.csv"
    data.write_text("x_m,y_m,z_m\n0,0,0\n")
    arguments = {"pose": ["tip"], "transform": [data, "tip", "-r", "table"],
                 "view": []}[command]
    result = run_cli(command, turntable, *arguments, "-o", tmp_path / name)
    assert result.returncode == 1, result.stderr
    assert expected in result.stderr and name in result.stderr, result.stderr
    assert not (tmp_path / name).exists()
    if command == "pose":  # the format said outright goes into any name
        result = run_cli("pose", turntable, "tip", "--format", "json", "-o", tmp_path / name)
        assert result.returncode == 0, result.stderr
        assert json.loads((tmp_path / name).read_text())


def test_bundled_cell_exports_to_frames_yaml_with_a_slash_replacement(run_cli, tmp_path):
    out = tmp_path / "frames.yaml"
    result = run_cli("convert", bundled_scene(), out, "--time", "5")
    assert result.returncode == 1
    assert "--slash-replacement" in result.stderr and "'robot/base_link'" in result.stderr
    result = run_cli("convert", bundled_scene(), out, "--time", "5",
                     "--slash-replacement", "_")
    assert result.returncode == 0, result.stderr
    frames = yaml.safe_load(out.read_text())["frames"]
    assert "robot_base/robot_base_link" in frames
    # the flange written at 5 s sits where the scene puts it at 5 s
    tree = read_scene(bundled_scene())
    key = next(k for k in frames if k.endswith("/robot_flange"))
    pose = run_cli("pose", out, key, "-r", "world")
    flange = np.loadtxt(pose.stdout.splitlines()[1:], delimiter=",")
    expected = tree.pose("robot/flange", relative_to="world", times=[5.0]).translation[0]
    np.testing.assert_allclose(flange[1:4], expected, atol=1e-9)


@pytest.mark.slow  # seconds of CPU (subprocesses): CI's slow set
def test_demo_on_the_base_install_writes_the_csv_and_says_what_the_extras_add(
        tmp_path, cli_env):
    # the base install: neither the plot extra (matplotlib) nor the view extra (umsgpack)
    # nor the ros extra (rosbags)
    code = ("import sys; sys.modules['matplotlib'] = None; sys.modules['umsgpack'] = None; "
            "sys.modules['rosbags'] = None; "
            "from pinframes.cli import main; "
            f"sys.exit(main(['demo', '--out', {str(tmp_path / 'out')!r}]))")
    result = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                            env=cli_env, timeout=300)
    assert result.returncode == 0, result.stderr
    assert "seam length travelled  344.2 mm" in result.stdout
    assert (tmp_path / "out" / "torch_poses.csv").exists()
    assert not (tmp_path / "out" / "torch_path.png").exists()
    lines = result.stderr.splitlines()
    assert lines[0] == (f"pinframes: wrote {tmp_path / 'out' / 'torch_poses.csv'}, "
                        f"{tmp_path / 'out' / 'program_run.csv'}")  # the cell's program
    plot_lines = [line for line in lines if "pinframes[plot]" in line]
    assert len(plot_lines) == 1 and 'pip install "pinframes[plot]"' in plot_lines[0]
    assert lines[2:] == ['pinframes: no 3-D page: the 3-D page needs u-msgpack-python: pip '
                         'install "pinframes[view]"',
                         'pinframes: no ROS bag: pip install "pinframes[ros]" adds rosbags, and '
                         'the demo then also writes the run as cell_run.mcap (Foxglove, ros2 '
                         'bag play)']
    assert not (tmp_path / "out" / "cell_run.mcap").exists()
