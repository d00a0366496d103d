"""``pinframes info`` and ``pose`` on bags, as users run them (a subprocess)."""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

from ros.bag_writing import JOINT_STATE, Message, Transform, joint_state, tf_messages, write_bag

ROOT = Path(__file__).resolve().parents[2]
BUNDLED = ROOT / "models" / "welding_cell" / "cell_run.mcap"
START = 1_700_000_000 * 1_000_000_000


def _run(*args: object) -> subprocess.CompletedProcess:
    env = dict(os.environ)
    env["PYTHONPATH"] = os.pathsep.join(filter(None, [str(ROOT / "src"),
                                                      env.get("PYTHONPATH")]))
    return subprocess.run([sys.executable, "-m", "pinframes.cli", *map(str, args)],
                          capture_output=True, text=True, env=env, timeout=300, check=False)


def test_info_lists_topics_used_and_ignored_and_the_time_span():
    result = _run("info", BUNDLED)
    assert result.returncode == 0, result.stderr
    lines = result.stdout.splitlines()
    # the bag's joint states carry samples of all six joints
    assert lines[0].startswith("tree cell_run: 15 frames, 1 moving, 6 robot joints (6 with "
                               "samples)")
    assert "MCAP" in result.stdout and "stamps 2024-03-01T08:00:00 .. 2024-03-01T08:00:20" \
        in result.stdout
    assert any(line.startswith("topics ignored: /weld_current (std_msgs/msg/Float64")
               for line in lines)
    described = json.loads(_run("info", BUNDLED, "-f", "json").stdout)
    uses = {topic["name"]: topic["use"] for topic in described["rosbag"]["topics"]}
    assert uses == {"/joint_states": "joint states", "/robot_description": "robot description",
                    "/tf": "tf", "/tf_static": "tf static", "/weld_current": None}


def test_info_on_a_folder_lists_joint_states_without_a_robot(tmp_path):
    messages = tf_messages(2, [Transform("world", "tool", START)])
    messages.append(Message("/joint_states", JOINT_STATE, START,
                            joint_state(2, START, ["j1", "j2"], [0.1, 0.2])))
    bag = write_bag(tmp_path / "run", "sqlite3", messages)
    result = _run("info", bag)
    assert result.returncode == 0, result.stderr
    assert "joint states not used (no robot description drives them): j1, j2" in result.stdout


def test_pose_on_a_bag_and_a_bad_folder(tmp_path):
    result = _run("pose", BUNDLED, "positioner", "--times", "2024-03-01T08:00:10", "-f", "json")
    assert result.returncode == 0, result.stderr
    pose = json.loads(result.stdout)["poses"][0]
    # the positioner's keyframe at 10 s (scene.yaml): a quarter turn about z
    assert abs(pose["qz"] + 0.707106781187) < 1e-9 and abs(pose["qw"] - 0.707106781187) < 1e-9
    empty = tmp_path / "empty"
    empty.mkdir()
    result = _run("info", empty)
    assert result.returncode == 1
    assert result.stderr == (f"pinframes: error: {empty}: is a folder, not a file (a ROS 2 "
                             "bag folder holds a metadata.yaml)\n")


def test_robot_description_option(tmp_path):
    messages = tf_messages(2, [Transform("world", "base_link", START)])
    messages.append(Message("/joint_states", JOINT_STATE, START,
                            joint_state(2, START, ["joint_1"], [0.25])))
    bag = write_bag(tmp_path / "run", "mcap", messages)
    urdf = ROOT / "models" / "welding_robot" / "welding_robot.urdf"
    described = json.loads(_run("info", bag, "--robot-description", urdf, "-f", "json").stdout)
    joint_1 = next(frame for frame in described["frames"] if frame["name"] == "link_1")
    assert joint_1["joint"]["name"] == "joint_1" and joint_1["samples"] == 1
    result = _run("info", ROOT / "models" / "welding_cell" / "scene.yaml",
                  "--robot-description", urdf)
    assert result.returncode == 1 and "--robot-description is for ROS bags" in result.stderr


def test_info_shows_names_that_would_act_on_the_terminal_escaped(tmp_path):
    # tf2 takes any frame name; the names are kept, their control characters shown escaped
    names = ["clear\x1b[2J", "nul\x00byte", "two\nlines", "rlo\u202eelif", "back\\slash"]
    bag = write_bag(tmp_path / "names", "mcap", tf_messages(2, [
        Transform("world", name, START + k) for k, name in enumerate(names)]))
    result = _run("info", bag)
    assert result.returncode == 0, result.stderr
    shown = result.stdout
    assert not any(char in shown for char in "\x1b\x00\u202e\r")
    for name in ("clear\\x1b[2J", "nul\\x00byte", "two\\nlines", "rlo\\u202eelif",
                 "back\\slash"):
        assert f"-- {name}  " in shown, shown
    rows = [line for line in shown.splitlines() if line.startswith(("|-- ", "`-- "))]
    assert len(rows) == len(names)  # one line per frame: no name broke its row
    described = json.loads(_run("info", bag, "-f", "json").stdout)
    assert [frame["name"] for frame in described["frames"]][1:] == names
