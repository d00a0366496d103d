"""A batch against inputs that used to hang it, duplicate runs, or fail every time: devices
and FIFOs named by a scene, growing campaigns, broken manifests, huge resampling grids, long
run ids, a mistyped frame. A real Dask LocalCluster (2 worker processes on 127.0.0.1)."""

from __future__ import annotations

import concurrent.futures
import json
import os
import shutil
from pathlib import Path

import numpy as np
import pandas as pd
import pytest
from distributed import LocalCluster

from pinframes import read_scene
from pinframes.batch import partition_path, run_batch
from pinframes.batch._compute import MAX_GRID_SAMPLES
from pinframes.errors import FrameNotFoundError, ManifestWarning

# a Dask cluster per test: in the slow set (CI runs it)
pytestmark = pytest.mark.slow

FRAME, RELATIVE_TO = "torch_tcp", "workpiece"
SECONDS_ALLOWED = 180  # a batch that hangs fails here instead of hanging the suite


@pytest.fixture(scope="module")
def scheduler():
    with LocalCluster(n_workers=2, threads_per_worker=1, processes=True, host="127.0.0.1",
                      dashboard_address="127.0.0.1:0") as cluster:
        yield cluster.scheduler_address


@pytest.fixture(scope="module")
def campaign(tmp_path_factory, make_campaign) -> Path:
    folder = tmp_path_factory.mktemp("campaign")
    make_campaign(folder, runs=3, samples=60, seed=5)
    return folder


def batch(runs, out, scheduler, **options):
    """``run_batch`` in a thread, so that a batch that never ends fails the test."""
    pool = concurrent.futures.ThreadPoolExecutor(1)
    try:
        future = pool.submit(run_batch, runs, out, options.pop("frame", FRAME),
                             relative_to=RELATIVE_TO, scheduler=scheduler, **options)
        return future.result(timeout=SECONDS_ALLOWED)
    finally:
        pool.shutdown(wait=False)  # a batch still running is left behind, not waited for


def dataset_runs(out: Path) -> list[str]:
    return sorted(pd.read_parquet(out / "poses")["run"].unique())


def copy_run(campaign: Path, run: str, into: Path) -> Path:
    shutil.copytree(campaign / run, into / run)
    return into / run / "scene.yaml"


def test_a_scene_naming_a_device_or_a_fifo_is_an_error_record_and_the_batch_ends(
        campaign, scheduler, tmp_path):
    device = copy_run(campaign, "run_0000", tmp_path)
    text = device.read_text(encoding="utf-8")
    device.write_text(text.replace("robots:", "layers:\n- file: /dev/zero\nrobots:", 1),
                      encoding="utf-8")
    fifo = copy_run(campaign, "run_0001", tmp_path)
    (fifo.parent / "motion.csv").unlink()
    os.mkfifo(fifo.parent / "motion.csv")  # nobody ever writes to it
    good = copy_run(campaign, "run_0002", tmp_path)
    summary = batch([str(tmp_path / "*" / "scene.yaml")], tmp_path / "out", scheduler)
    records = {record["run"]: record for record in summary.records}
    assert summary.computed == ["run_0002"] and records["run_0002"]["status"] == "ok"
    assert records["run_0000"]["status"] == "error"
    assert "/dev/zero" in records["run_0000"]["error"]
    assert records["run_0001"]["status"] == "error"
    assert str(fifo.parent / "motion.csv") in records["run_0001"]["error"]
    assert "regular file" in records["run_0001"]["error"]
    assert dataset_runs(tmp_path / "out") == ["run_0002"]
    assert good.is_file()


def test_a_growing_campaign_keeps_its_run_ids(campaign, scheduler, tmp_path):
    grown = tmp_path / "campaign"
    copy_run(campaign, "run_0000", grown)
    pattern = str(grown / "*" / "scene.yaml")
    out = tmp_path / "out"
    assert batch([pattern], out, scheduler).computed == ["run_0000"]
    for run in ("run_0001", "run_0002"):
        copy_run(campaign, run, grown)
    summary = batch([pattern], out, scheduler)
    assert sorted(summary.computed) == ["run_0001", "run_0002"]
    assert summary.skipped == ["run_0000"]
    assert dataset_runs(out) == ["run_0000", "run_0001", "run_0002"]


def test_files_named_one_by_one_keep_the_ids_an_output_folder_gave_them(
        campaign, scheduler, tmp_path):
    """As a shell expands an unquoted pattern: the first batch sees one file, named by its
    stem; later batches see more files, and the first file keeps its id."""
    scenes = [campaign / f"run_{index:04d}" / "scene.yaml" for index in range(3)]
    out = tmp_path / "out"
    assert batch(scenes[:1], out, scheduler).computed == ["scene"]
    summary = batch(scenes, out, scheduler)
    assert summary.skipped == ["scene"]
    assert sorted(summary.computed) == ["run_0001", "run_0002"]
    table = pd.read_parquet(out / "poses")
    assert sorted(table["run"].unique()) == ["run_0001", "run_0002", "scene"]
    assert len(table) == sum(len(read_scene(scene).pose(FRAME, relative_to=RELATIVE_TO))
                             for scene in scenes)

    # a runs list gives the first file another id: its poses move there, none stay behind
    listing = tmp_path / "runs.csv"
    listing.write_text(f"run,file\nfirst,{scenes[0]}\n", encoding="utf-8")
    assert batch([listing], out, scheduler).computed == ["first"]
    assert dataset_runs(out) == ["first", "run_0001", "run_0002"]
    manifest = pd.read_json(out / "manifest.jsonl", lines=True)
    assert sorted(manifest["run"]) == ["first", "run_0001", "run_0002"]


def test_a_torn_or_edited_manifest_recomputes_only_the_unreadable_runs(
        campaign, scheduler, tmp_path):
    pattern = str(campaign / "*" / "scene.yaml")
    out = tmp_path / "out"
    batch([pattern], out, scheduler)
    manifest = out / "manifest.jsonl"
    lines = manifest.read_text(encoding="utf-8").splitlines()
    assert [json.loads(line)["run"] for line in lines] == ["run_0000", "run_0001", "run_0002"]
    edited = [lines[0], "{'run': 'run_0001', edited by hand}", lines[2][:40]]  # torn last
    manifest.write_text("\n".join(edited), encoding="utf-8")
    with pytest.warns(ManifestWarning, match="lines 2, 3 are no run record"):
        summary = batch([pattern], out, scheduler)
    assert summary.skipped == ["run_0000"]
    assert sorted(summary.computed) == ["run_0001", "run_0002"]
    records = [json.loads(line) for line in manifest.read_text(encoding="utf-8").splitlines()]
    assert [record["run"] for record in records] == ["run_0000", "run_0001", "run_0002"]


def test_a_resampling_grid_too_large_is_an_error_naming_step_and_is_not_retried(
        campaign, scheduler, tmp_path):
    scene = campaign / "run_0000" / "scene.yaml"
    seconds = 20.0  # the bundled weld motion's length
    assert seconds * 1e9 > MAX_GRID_SAMPLES
    out = tmp_path / "out"
    summary = batch([scene], out, scheduler, step="1ns")
    (record,) = summary.records
    assert record["status"] == "error" and "step" in record["error"]
    assert f"{int(seconds * 1e9) + 1:,} times" in record["error"]
    again = batch([scene], out, scheduler, step="1ns")
    assert again.skipped == ["scene"] and again.computed == again.without_poses == []


@pytest.mark.parametrize("run_id", ["溶接" * 14, "w" * 248],
                         ids=["28 CJK characters", "248 ASCII characters"])
def test_long_run_ids_are_written_under_a_short_name_and_kept_whole_in_the_rows(
        campaign, scheduler, tmp_path, run_id):
    scene = campaign / "run_0001" / "scene.yaml"
    listing = tmp_path / "runs.csv"
    listing.write_text(f"run,file\n{run_id},{scene}\n", encoding="utf-8")
    out = tmp_path / "out"
    summary = batch([listing], out, scheduler)
    assert summary.computed == [run_id], summary.records
    path = partition_path(out, run_id)
    assert path.is_file() and len(path.name.encode()) <= 255
    rows = pd.read_parquet(path)
    assert set(rows["run"]) == {run_id}
    expected = read_scene(scene).pose(FRAME, relative_to=RELATIVE_TO)
    np.testing.assert_allclose(rows.sort_values("time_s")[["x_m", "y_m", "z_m"]],
                               expected.translation, rtol=0, atol=1e-12)
    assert batch([listing], out, scheduler).skipped == [run_id]


def test_a_mistyped_frame_is_refused_before_any_cluster_with_near_names(campaign, tmp_path):
    out = tmp_path / "out"
    unreachable = "tcp://127.0.0.1:9"  # connecting here would fail: no cluster is asked
    with pytest.raises(FrameNotFoundError) as error:
        run_batch([str(campaign / "*" / "scene.yaml")], out, "torch_tpc",
                  relative_to=RELATIVE_TO, scheduler=unreachable)
    assert error.value.frame == "torch_tpc" and error.value.field == "frame"
    assert "did you mean frame 'torch_tcp'" in str(error.value)
    assert error.value.file == str(campaign / "run_0000" / "scene.yaml")
    with pytest.raises(FrameNotFoundError, match=r"'workpeice'.*did you mean frame "
                       r"'workpiece'"):
        run_batch([str(campaign / "*" / "scene.yaml")], out, FRAME, relative_to="workpeice",
                  scheduler=unreachable)
    assert not out.exists()
