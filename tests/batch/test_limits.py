"""Reader limits travel with each run to the Dask workers, and decide re-runs.

A real LocalCluster (2 worker processes on 127.0.0.1), and ``pinframes batch --max-samples``
as users start it. Two runs of the welding cell: ``run_0000``'s trajectory has 2,500 rows,
``run_0001``'s is cut to 100, so ``max_samples=2100`` refuses the first and reads the second
(the cell's seam curve has 2,001 points, which the limit bounds too).
"""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pandas as pd
import pytest
from distributed import LocalCluster

from pinframes import Limits, read_scene
from pinframes.batch import run_batch

# a Dask cluster per test: in the slow set (CI runs it)
pytestmark = pytest.mark.slow

FRAME, RELATIVE_TO = "torch_tcp", "workpiece"
BIG, SMALL = "run_0000", "run_0001"
SRC = Path(__file__).resolve().parents[2] / "src"


@pytest.fixture(scope="module")
def scheduler():
    with LocalCluster(n_workers=2, threads_per_worker=1, processes=True, host="127.0.0.1",
                      dashboard_address="127.0.0.1:0") as cluster:
        yield cluster.scheduler_address


@pytest.fixture
def campaign(tmp_path, make_campaign) -> Path:
    folder = tmp_path / "campaign"
    make_campaign(folder, runs=2, samples=2500, seed=5)
    motion = folder / SMALL / "motion.csv"
    lines = motion.read_text(encoding="utf-8").splitlines()
    motion.write_text("\n".join(lines[:101]) + "\n", encoding="utf-8")  # header, 100 rows
    return folder


def _batch(campaign: Path, out: Path, scheduler: str, limits: Limits | None):
    summary = run_batch([str(campaign / "*" / "scene.yaml")], out, FRAME,
                        relative_to=RELATIVE_TO, scheduler=scheduler, limits=limits)
    return summary, {record["run"]: record for record in summary.records}


def _check_poses(out: Path, campaign: Path, run: str) -> None:
    rows = pd.read_parquet(out / "poses", filters=[("run", "==", run)]).sort_values("time_s")
    pose = read_scene(campaign / run / "scene.yaml").pose(FRAME, relative_to=RELATIVE_TO)
    assert len(rows) == len(pose) > 0
    assert abs(rows[["x_m", "y_m", "z_m"]].to_numpy() - pose.translation).max() < 1e-12


def test_limits_reach_the_workers_and_changed_limits_rerun_what_they_change(
        campaign, scheduler, tmp_path):
    out = tmp_path / "out"
    strict = Limits(max_samples=2100)
    summary, records = _batch(campaign, out, scheduler, strict)
    assert records[BIG]["status"] == "error" and records[SMALL]["status"] == "ok"
    assert "2,500 samples, over the limit max_samples=2,100" in records[BIG]["error"]
    assert str(campaign / BIG / "motion.csv") in records[BIG]["error"]
    assert records[BIG]["limits"]["max_samples"] == 2100
    _check_poses(out, campaign, SMALL)

    # the same limits: nothing to do
    summary, _ = _batch(campaign, out, scheduler, strict)
    assert summary.computed == []

    # the defaults are higher: the refused run is read now, the one read already stays
    summary, records = _batch(campaign, out, scheduler, None)
    assert summary.computed == [BIG] and summary.skipped == [SMALL]
    assert records[BIG]["status"] == "ok"
    _check_poses(out, campaign, BIG)

    # lower again: the run read under the defaults is checked once more, and refused
    summary, records = _batch(campaign, out, scheduler, strict)
    assert summary.without_poses == [BIG] and records[BIG]["status"] == "error"
    assert not (out / "poses" / f"{BIG}.parquet").exists()


def test_the_command_line_max_samples_reaches_the_workers(campaign, tmp_path):
    env = {**os.environ, "PYTHONPATH": os.pathsep.join(filter(None, [
        str(SRC), os.environ.get("PYTHONPATH")]))}
    command = [sys.executable, "-m", "pinframes.cli", "batch", str(campaign / BIG / "scene.yaml"),
               "--frame", FRAME, "--relative-to", RELATIVE_TO, "--workers", "2"]
    limited = subprocess.run([*command, "--out", str(tmp_path / "limited"), "--max-samples",
                              "2100"], capture_output=True, text=True, env=env, timeout=300,
                             check=False)
    assert limited.returncode == 1, limited.stderr
    # one file given: the run is named after it
    assert f"pinframes: run scene: {campaign / BIG / 'motion.csv'}" in limited.stderr
    assert "over the limit max_samples=2,100" in limited.stderr
    manifest = pd.read_json(tmp_path / "limited" / "manifest.jsonl", lines=True)
    assert list(manifest["status"]) == ["error"]
    assert "max_samples=2,100" in manifest["error"][0]
    free = subprocess.run([*command, "--out", str(tmp_path / "free")], capture_output=True,
                          text=True, env=env, timeout=300, check=False)
    assert free.returncode == 0, free.stderr
    assert list(pd.read_json(tmp_path / "free" / "manifest.jsonl", lines=True)["status"]) == [
        "ok"]


def test_a_scene_naming_itself_as_a_layer_is_one_input(tmp_path):
    from pinframes.batch._inputs import run_inputs

    scene = tmp_path / "scene.yaml"  # was a RecursionError in the worker, every batch
    scene.write_text("pinframes_scene: 1\nlayers: [{file: scene.yaml}, {file: ./scene.yaml}]\n")
    assert run_inputs(scene).files == [scene]


def test_a_scene_nested_a_hundred_thousand_levels_does_not_crash_the_worker(tmp_path):
    # libyaml's composer recurses in C: this file once killed the process (SIGSEGV)
    scene = tmp_path / "scene.yaml"
    scene.write_text("pinframes_scene: 1\nx: " + "[" * 100_000 + "]" * 100_000 + "\n")
    env = {**os.environ, "PYTHONPATH": os.pathsep.join(filter(None, [
        str(SRC), os.environ.get("PYTHONPATH")]))}
    done = subprocess.run(
        [sys.executable, "-c", "import sys; from pathlib import Path; "
         "from pinframes.batch._inputs import run_inputs; "
         "print(run_inputs(Path(sys.argv[1])))", str(scene)],
        capture_output=True, text=True, env=env, timeout=120, check=False)
    assert done.returncode == 0, done.stderr[-2000:]
    # not looked into: the reader refuses it and the record says why
    assert done.stdout.strip().startswith(f"RunInputs(files=[{scene!r}], ")
