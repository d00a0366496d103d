"""A real Dask LocalCluster (2 worker processes on 127.0.0.1) on a generated campaign.

20 runs of the bundled welding cell, two of them malformed. The tests share one cluster and
one campaign and run in this order; the last ones change the campaign.
"""

from __future__ import annotations

import os
import shutil
from pathlib import Path

import dask.dataframe as dd
import numpy as np
import pandas as pd
import pyarrow.parquet as pq
import pytest
from distributed import Client, LocalCluster

from pinframes import read_scene
from pinframes.batch import partition_path, run_batch
from pinframes.batch._engine import local_cluster
from pinframes.batch._task import KILL_ONCE_VARIABLE

# a Dask cluster per test: in the slow set (CI runs it)
pytestmark = pytest.mark.slow

FRAME, RELATIVE_TO = "torch_tcp", "workpiece"
CHUNK = 97  # rows per chunk: every run's file has several row groups
BAD_VALUE, MISSING_TRAJECTORY = "run_0004", "run_0011"


@pytest.fixture(scope="module")
def kill_marker(tmp_path_factory) -> Path:
    """The test hook's marker: while it exists, no worker kills itself."""
    marker = tmp_path_factory.mktemp("hook") / "killed-once"
    marker.touch()
    return marker


@pytest.fixture(scope="module")
def scheduler(kill_marker):
    with LocalCluster(n_workers=2, threads_per_worker=1, processes=True, host="127.0.0.1",
                      dashboard_address="127.0.0.1:0",
                      env={KILL_ONCE_VARIABLE: str(kill_marker)}) as cluster:
        yield cluster.scheduler_address


@pytest.fixture(scope="module")
def campaign(tmp_path_factory, make_campaign) -> Path:
    folder = tmp_path_factory.mktemp("campaign")
    make_campaign(folder, runs=20, samples=300, seed=19)
    motion = folder / BAD_VALUE / "motion.csv"
    lines = motion.read_text(encoding="utf-8").splitlines()
    lines[7] = lines[7].replace(",", ",abc,", 1).rsplit(",", 1)[0]
    motion.write_text("\n".join(lines) + "\n", encoding="utf-8")
    (folder / MISSING_TRAJECTORY / "motion.csv").unlink()
    return folder


@pytest.fixture(scope="module")
def first(campaign, scheduler, tmp_path_factory):
    out = tmp_path_factory.mktemp("out")
    summary = run_batch([str(campaign / "*" / "scene.yaml")], out, FRAME,
                        relative_to=RELATIVE_TO, scheduler=scheduler, chunk_size=CHUNK)
    return out, summary


def _expected(scene: Path):
    """The pose asked of FrameTree directly, in one call."""
    return read_scene(scene).pose(FRAME, relative_to=RELATIVE_TO)


def _check_run(rows: pd.DataFrame, scene: Path) -> None:
    pose = _expected(scene)
    rows = rows.sort_values("time_s")
    assert len(rows) == len(pose)
    np.testing.assert_allclose(rows[["x_m", "y_m", "z_m"]].to_numpy(), pose.translation,
                               rtol=0, atol=1e-12)
    np.testing.assert_allclose(rows[["qx", "qy", "qz", "qw"]].to_numpy(), pose.quaternion,
                               rtol=0, atol=1e-12)
    np.testing.assert_array_equal(rows["timestamp"].to_numpy(), pose.absolute_times)
    np.testing.assert_allclose(rows["time_s"].to_numpy(),
                               pose.times.astype(np.int64) / 1e9, rtol=0, atol=1e-12)


def test_every_good_run_has_the_poses_of_frame_tree(first, campaign):
    out, summary = first
    good = [f"run_{i:04d}" for i in range(20)]
    good = [run for run in good if run not in (BAD_VALUE, MISSING_TRAJECTORY)]
    assert sorted(summary.computed) == good
    assert sorted(summary.without_poses) == [BAD_VALUE, MISSING_TRAJECTORY]
    table = pd.read_parquet(out / "poses")
    assert sorted(table["run"].unique()) == good
    for run in good:
        _check_run(table[table["run"] == run], campaign / run / "scene.yaml")
        file = pq.ParquetFile(partition_path(out, run))
        assert file.num_row_groups == -(-file.metadata.num_rows // CHUNK)
    assert [record["samples"] for record in summary.records if record["status"] == "ok"] == [
        len(_expected(campaign / run / "scene.yaml")) for run in good]


def test_bad_runs_are_in_the_manifest_with_their_errors(first, campaign):
    out, summary = first
    bad = {record["run"]: record for record in summary.bad}
    assert set(bad) == {BAD_VALUE, MISSING_TRAJECTORY}
    assert all(record["status"] == "error" and record["samples"] is None
               for record in bad.values())
    assert str(campaign / BAD_VALUE / "motion.csv") in bad[BAD_VALUE]["error"]
    assert "abc" in bad[BAD_VALUE]["error"]
    missing = bad[MISSING_TRAJECTORY]["error"]
    assert "no such file" in missing and "robots[0].trajectory" in missing
    manifest = pd.read_json(out / "manifest.jsonl", lines=True).set_index("run")
    assert manifest.loc[BAD_VALUE, "error"] == bad[BAD_VALUE]["error"]
    assert (manifest["status"] == "ok").sum() == 18
    assert not partition_path(out, BAD_VALUE).exists()


# dask's own reader uses a pandas keyword that pandas 3.1 deprecates
@pytest.mark.filterwarnings("ignore:The inplace keyword")
def test_the_dataset_reads_back_with_dask_dataframe(first):
    out, _ = first
    with_pandas = pd.read_parquet(out / "poses")
    with_dask = dd.read_parquet(out / "poses").compute(scheduler="synchronous")
    key = ["run", "time_s"]
    pd.testing.assert_frame_equal(
        with_dask.sort_values(key).reset_index(drop=True).astype({"run": object}),
        with_pandas.sort_values(key).reset_index(drop=True).astype({"run": object}))


def test_a_second_batch_recomputes_nothing(first, campaign, scheduler):
    out, _ = first
    stamps = {path.name: path.stat().st_mtime_ns for path in (out / "poses").iterdir()}
    summary = run_batch([str(campaign / "*" / "scene.yaml")], out, FRAME,
                        relative_to=RELATIVE_TO, scheduler=scheduler, chunk_size=CHUNK)
    assert summary.computed == [] and len(summary.skipped) == 20
    assert {path.name: path.stat().st_mtime_ns for path in (out / "poses").iterdir()} == stamps


def test_a_changed_input_recomputes_only_that_run(first, campaign, scheduler):
    out, _ = first
    motion = campaign / "run_0007" / "motion.csv"
    header, *lines = motion.read_text(encoding="utf-8").splitlines()
    samples = np.array([[float(value) for value in line.split(",")] for line in lines])
    samples[:, 1] += 0.01  # joint_1 turns 0.01 rad further
    np.savetxt(motion, samples, delimiter=",", header=header, comments="")
    summary = run_batch([str(campaign / "*" / "scene.yaml")], out, FRAME,
                        relative_to=RELATIVE_TO, scheduler=scheduler, chunk_size=CHUNK)
    assert summary.computed == ["run_0007"]
    table = pd.read_parquet(out / "poses", filters=[("run", "==", "run_0007")])
    _check_run(table, campaign / "run_0007" / "scene.yaml")


def test_a_fixed_bad_run_is_computed_next_time(first, campaign, scheduler):
    out, _ = first
    shutil.copyfile(campaign / "run_0000" / "motion.csv",
                    campaign / MISSING_TRAJECTORY / "motion.csv")
    summary = run_batch([str(campaign / "*" / "scene.yaml")], out, FRAME,
                        relative_to=RELATIVE_TO, scheduler=scheduler, chunk_size=CHUNK)
    assert summary.computed == [MISSING_TRAJECTORY]
    _check_run(pd.read_parquet(partition_path(out, MISSING_TRAJECTORY)),
               campaign / MISSING_TRAJECTORY / "scene.yaml")


def test_velocity_recomputes_the_runs_asked_with_the_velocity_of_frame_tree(
        first, campaign, scheduler):
    out, _ = first
    runs = ["run_0003", "run_0007"]
    summary = run_batch([campaign / run / "scene.yaml" for run in runs], out, FRAME,
                        relative_to=RELATIVE_TO, velocity=True, scheduler=scheduler,
                        chunk_size=CHUNK)
    assert sorted(summary.computed) == runs  # other options: not skipped
    for run in runs:
        rows = pd.read_parquet(partition_path(out, run)).sort_values("time_s")
        _check_run(rows, campaign / run / "scene.yaml")
        velocity = read_scene(campaign / run / "scene.yaml").velocity(FRAME, RELATIVE_TO)
        assert np.abs(velocity.linear).max() > 1e-3  # the torch does move
        np.testing.assert_allclose(rows[["vx_m_s", "vy_m_s", "vz_m_s"]].to_numpy(),
                                   velocity.linear, rtol=0, atol=1e-12)
        np.testing.assert_allclose(rows[["wx_rad_s", "wy_rad_s", "wz_rad_s"]].to_numpy(),
                                   velocity.angular, rtol=0, atol=1e-12)


def test_a_run_whose_worker_is_killed_is_not_lost(campaign, scheduler, kill_marker,
                                                  tmp_path):
    kill_marker.unlink()  # the next worker to write a chunk kills itself, once
    scenes = [campaign / f"run_{i:04d}" / "scene.yaml" for i in (1, 2, 3)]
    summary = run_batch(scenes, tmp_path, FRAME, relative_to=RELATIVE_TO,
                        scheduler=scheduler, chunk_size=CHUNK)
    assert kill_marker.exists()  # a worker did die in the middle of a run
    assert summary.bad == [] and sorted(summary.computed) == ["run_0001", "run_0002",
                                                              "run_0003"]
    for scene in scenes:
        _check_run(pd.read_parquet(partition_path(tmp_path, scene.parent.name)), scene)
    assert os.listdir(tmp_path / ".staging") == []


def test_local_workers_run_one_blas_thread_and_glibc_malloc_untuned():
    """Dask's MALLOC_TRIM_THRESHOLD_ in workers made each run 1.4x slower (bench_batch.py)."""
    with local_cluster(1) as cluster, Client(cluster) as client:
        (environment,) = client.run(lambda: {name: os.environ.get(name) for name in
                                             ("MALLOC_TRIM_THRESHOLD_", "OMP_NUM_THREADS")}
                                    ).values()
    assert environment == {"MALLOC_TRIM_THRESHOLD_": None, "OMP_NUM_THREADS": "1"}
