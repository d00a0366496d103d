"""A downloaded robot file must not run code when read: xacro is expanded only when the
caller asks, in a child process bounded in time and memory, without the environment, with
``$(find)`` answering only real packages; mesh names may not leave their package."""

from __future__ import annotations

import os
import textwrap

import numpy as np
import pytest

import pinframes
from pinframes import FileFormatError, FrameTree, GeometryError, GeometryWarning, Limits, Sphere
from pinframes.cli import main
from pinframes.formats.urdf import expand_xacro
from pinframes.view import load_geometry

pytest.importorskip("xacro")

XACRO_NS = 'xmlns:xacro="http://www.ros.org/wiki/xacro"'


def robot_with(tmp_path, body: str, name: str = "robot.urdf"):
    path = tmp_path / name
    path.write_text(f'<robot name="r" {XACRO_NS}>{body}</robot>')
    return path


def expanding(tmp_path, name: str = "robot.urdf"):
    """A file with a xacro property: its link ``l_expanded`` exists only if it was expanded."""
    body = '<xacro:property name="p" value="expanded"/><link name="l_${p}"/>'
    return robot_with(tmp_path, body, name)


def test_reading_a_file_with_xacro_content_expands_nothing_without_the_opt_in(tmp_path,
                                                                                capsys):
    robot = expanding(tmp_path)
    scene = tmp_path / "scene.yaml"
    scene.write_text(f"pinframes_scene: 1\nrobots: [{{urdf: {robot.name}}}]\n")
    readers = [lambda: pinframes.read(robot), lambda: pinframes.read_urdf(robot),
               lambda: FrameTree().attach_urdf(robot, "world"),
               lambda: pinframes.read(scene)]
    for read in readers:
        with pytest.raises(FileFormatError, match=r"runs the file's code.*xacro=True") as caught:
            read()
        assert caught.value.file == str(robot) and caught.value.field == "xacro"
    assert main(["info", str(robot)]) == 1
    assert "--xacro" in capsys.readouterr().err
    assert "l_expanded" in pinframes.read_urdf(robot, xacro=True).frames


@pytest.mark.parametrize("how", ["suffix", "scene entry", "cli"])
def test_the_ways_to_ask_for_an_expansion(tmp_path, how, capsys):
    robot = expanding(tmp_path, "robot.urdf.xacro" if how == "suffix" else "robot.urdf")
    if how == "suffix":
        assert "l_expanded" in pinframes.read(robot).frames
    elif how == "scene entry":
        scene = tmp_path / "scene.yaml"
        scene.write_text(f"pinframes_scene: 1\nrobots: [{{urdf: {robot.name}, xacro: true}}]\n")
        assert "l_expanded" in pinframes.read(scene).frames
        with pytest.raises(FileFormatError, match="xacro"):  # the caller says never
            pinframes.read(scene, xacro=False)
    else:
        assert main(["info", str(robot), "--xacro"]) == 0, capsys.readouterr().err
        assert "l_expanded" in capsys.readouterr().out


def test_the_help_says_that_expansion_runs_the_files_code(capsys):
    with pytest.raises(SystemExit):
        main(["info", "--help"])
    assert "RUNS THE FILE'S CODE" in " ".join(capsys.readouterr().out.split())


def test_find_answers_only_folders_with_a_package_xml_of_that_name(tmp_path):
    robot = robot_with(tmp_path, '<link name="$(find etc)"/>', "robot.xacro")
    with pytest.raises(FileFormatError, match=r"package 'etc' not found") as caught:
        pinframes.read_urdf(robot)
    assert caught.value.file == str(robot)
    package = tmp_path / "any_folder"
    package.mkdir()
    (package / "package.xml").write_text("<package><name>etc</name></package>")
    assert f'name="{package}"' in expand_xacro(robot)


def test_the_expansion_sees_no_environment(tmp_path, monkeypatch):
    monkeypatch.setenv("PINFRAMES_SECRET", "s3cret")
    robot = robot_with(tmp_path, '<link name="a$(optenv PINFRAMES_SECRET none)"/>',
                       "robot.xacro")
    assert "anone" in pinframes.read_urdf(robot).frames
    robot = robot_with(tmp_path, '<link name="a$(env PINFRAMES_SECRET)"/>', "robot.xacro")
    with pytest.raises(FileFormatError, match=r"PINFRAMES_SECRET.*without the environment"):
        pinframes.read_urdf(robot)


BOMBS = {
    "a macro calling itself twice, 20 levels": (
        '<xacro:macro name="m" params="n"><xacro:if value="${n > 0}"><xacro:m n="${n-1}"/>'
        '<xacro:m n="${n-1}"/></xacro:if></xacro:macro><xacro:m n="20"/>', "max_xacro_seconds"),
    "a huge number": ('<link name="${9**9**8}"/>', "max_xacro_seconds"),
    "a 2 GB string": ("<link name=\"${'x' * 2000000000}\"/>", "max_xacro_bytes"),
}


@pytest.mark.parametrize("body, limit", BOMBS.values(), ids=BOMBS.keys())
def test_xacro_bombs_are_refused_naming_the_bound(tmp_path, body, limit):
    robot = robot_with(tmp_path, body, "bomb.xacro")
    with pytest.raises(FileFormatError, match=f"over the limit {limit}=") as caught:
        pinframes.read_urdf(robot, limits=Limits(max_xacro_seconds=1,
                                                 max_xacro_bytes=512 * 1024**2))
    assert caught.value.file == str(robot) and caught.value.field == "xacro"


@pytest.mark.slow
def test_a_bomb_is_refused_within_a_minute_by_default(tmp_path):
    robot = robot_with(tmp_path, next(iter(BOMBS.values()))[0], "bomb.xacro")
    with pytest.raises(FileFormatError, match="max_xacro_seconds=20"):
        pinframes.read_urdf(robot)


@pytest.mark.skipif(not hasattr(os, "mkfifo"), reason="no FIFOs here")
def test_an_include_of_a_fifo_is_refused_without_waiting(tmp_path):
    os.mkfifo(tmp_path / "pipe")
    robot = robot_with(tmp_path, '<xacro:include filename="pipe"/>', "robot.xacro")
    with pytest.raises(FileFormatError, match="pipe: is not a regular file") as caught:
        pinframes.read_urdf(robot)
    assert caught.value.field == "xacro"


@pytest.mark.parametrize("name", ["package://parts/../../secret.stl",
                                  "package://parts/meshes/../../../secret.stl",
                                  "model://../../secret.stl", "package://parts//secret.stl"])
def test_a_mesh_name_that_leaves_its_package_is_refused(tmp_path, name):
    (tmp_path / "ws" / "parts").mkdir(parents=True)
    (tmp_path / "secret.stl").write_text(textwrap.dedent("""\
        solid s
        facet normal 0 0 1
        outer loop
        vertex 0 0 0
        vertex 1 0 0
        vertex 0 1 0
        endloop
        endfacet
        endsolid s
        """))
    tree = FrameTree()
    tree.attach_urdf(f'<robot name="r"><link name="a"><collision><geometry><mesh '
                     f'filename="{name}"/></geometry></collision></link></robot>', "world",
                     package_dirs=[tmp_path / "ws", tmp_path / "ws" / "parts"])
    tree.add("ball", "world")
    tree.add_geometry("ball", Sphere(0.1))
    with pytest.raises(GeometryError, match=r"leaves its|names no model") as caught:
        tree.clearance("a", "ball")
    assert caught.value.frame == "a" and caught.value.field == "collision[0].mesh"
    with pytest.warns(GeometryWarning, match=r"leaves its|names no model"):
        assert [piece.frame for piece in load_geometry(tree, collision=True)] == ["ball"]


def test_an_absolute_mesh_path_stays_allowed(tmp_path):
    mesh = tmp_path / "part.stl"
    mesh.write_text("solid s\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\n"
                    "vertex 0 1 0\nendloop\nendfacet\nendsolid s\n")
    tree = FrameTree()
    tree.attach_urdf(f'<robot name="r"><link name="a"><collision><geometry><mesh '
                     f'filename="{mesh}"/></geometry></collision></link></robot>', "world")
    tree.add("ball", "world", pinframes.Pose([0.0, 0.0, 0.5]))
    tree.add_geometry("ball", Sphere(0.1))
    np.testing.assert_allclose(tree.clearance("a", "ball").distance, [0.4], atol=1e-9)
