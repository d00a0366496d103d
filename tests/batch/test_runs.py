"""Which runs a batch computes, and which files decide whether a run is recomputed."""

from __future__ import annotations

import hashlib
from pathlib import Path

import pytest

from pinframes.batch import find_runs
from pinframes.batch._inputs import MISSING, checksums, run_inputs
from pinframes.errors import FileFormatError, ReadError


def _touch(path: Path, text: str = "") -> Path:
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(text, encoding="utf-8")
    return path


def test_runs_of_same_named_files_are_named_by_their_folders(tmp_path):
    for name in ("r2", "r1", "sub/r3"):
        _touch(tmp_path / name / "scene.yaml")
    runs = find_runs([str(tmp_path / "**" / "scene.yaml")])
    assert sorted(run.run_id for run in runs) == ["r1", "r2", "sub/r3"]
    assert all(run.path.name == "scene.yaml" for run in runs)


def test_runs_of_differently_named_files_are_named_by_their_paths(tmp_path):
    one = _touch(tmp_path / "a" / "weld_1.asdf")
    two = _touch(tmp_path / "weld_2.asdf")
    runs = find_runs([one, str(two)])
    assert [(run.run_id, run.path) for run in runs] == [("a/weld_1", one), ("weld_2", two)]


def test_a_single_run_is_named_by_its_stem(tmp_path):
    assert find_runs([_touch(tmp_path / "weld.asdf")])[0].run_id == "weld"


def test_a_runs_list_names_its_runs_relative_to_itself(tmp_path):
    listing = _touch(tmp_path / "list.csv", "run,file\n\nA-1, x/scene.yaml\nB,y.asdf\n")
    runs = find_runs([listing])
    assert [(run.run_id, run.path) for run in runs] == [
        ("A-1", tmp_path / "x" / "scene.yaml"), ("B", tmp_path / "y.asdf")]


@pytest.mark.parametrize(("text", "field"), [
    ("file,run\nA,a.asdf\n", "header"),
    ("run,file\nA\n", "line 2"),
    ("run,file\nA,a.asdf\n,b.asdf\n", "line 3"),
])
def test_a_malformed_runs_list_names_the_line(tmp_path, text, field):
    listing = _touch(tmp_path / "list.csv", text)
    with pytest.raises(FileFormatError) as error:
        find_runs([listing])
    assert error.value.field == field and error.value.file == str(listing)


def test_two_runs_with_one_id_are_refused(tmp_path):
    listing = _touch(tmp_path / "list.csv", "run,file\nweld,a.asdf\n")
    with pytest.raises(FileFormatError, match="two runs have the id 'weld'"):
        find_runs([listing, _touch(tmp_path / "weld.asdf")])


def test_missing_runs_are_read_errors(tmp_path):
    with pytest.raises(ReadError, match="no such file"):
        find_runs([tmp_path / "nothing.asdf"])
    with pytest.raises(ReadError, match="matches no file"):
        find_runs([str(tmp_path / "*.asdf")])


def test_a_scene_reads_its_layers_robots_and_trajectories(tmp_path):
    scene = _touch(tmp_path / "run" / "scene.yaml", """\
pinframes_scene: 1
layers:
  - {file: ../shared/frames.yaml, mount: world}
  - {file: cell.asdf}
robots:
  - {urdf: ../shared/robot.urdf, parent: world, trajectory: motion.csv}
""")
    shared = tmp_path / "shared"
    _touch(shared / "frames.yaml", "version: 1.0\nframes: {}\n")  # may use tile_maps.yaml
    inputs = run_inputs(scene)
    assert inputs.files == [scene, shared / "frames.yaml", shared / "tile_maps.yaml",
                            tmp_path / "run" / "cell.asdf", shared / "robot.urdf",
                            tmp_path / "run" / "motion.csv"]


def test_checksums_change_with_content_and_mark_missing_files(tmp_path):
    file = _touch(tmp_path / "motion.csv", "time_s,j\n0,1\n")
    before = checksums([file, tmp_path / "absent.csv"])
    assert before[str(tmp_path / "absent.csv")] == MISSING
    assert before[str(file)] == hashlib.sha256(b"time_s,j\n0,1\n").hexdigest()
    file.write_text("time_s,j\n0,2\n", encoding="utf-8")
    assert checksums([file])[str(file)] != before[str(file)]
