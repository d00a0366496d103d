"""pinframes batch over bags (a ROS 1 file, ROS 2 folders) on a local Dask cluster: run ids
from the names, checksums of every file of a bag, poses at the keyframes as recorded."""

from __future__ import annotations

import hashlib

import numpy as np
import pytest

from ros.bag_writing import Transform, ros_version_of, tf_messages, write_bag

pytest.importorskip("distributed")
pd = pytest.importorskip("pandas")

from pinframes.batch import find_runs, run_batch  # noqa: E402
from pinframes.batch._inputs import run_inputs  # noqa: E402

# a Dask cluster per test: in the slow set (CI runs it)
pytestmark = pytest.mark.slow

SECOND = 1_000_000_000
START = 1_700_000_000 * SECOND


def _campaign(tmp_path):
    campaign = tmp_path / "campaign"
    campaign.mkdir()
    bags = {}
    for number, storage in enumerate(("ros1", "sqlite3", "mcap")):
        version = ros_version_of(storage)
        transforms = [Transform("world", "tool", START + k * SECOND, (number, k, 0.0))
                      for k in range(3)]
        bags[storage] = write_bag(campaign / f"run_{number}", storage,
                                  tf_messages(version, transforms))
    return campaign, bags


def test_find_runs_and_checksums_take_bag_folders(tmp_path):
    campaign, bags = _campaign(tmp_path)
    runs = find_runs([str(campaign / "run_*")])
    assert [(run.run_id, run.path.name) for run in runs] == [
        ("run_0", "run_0.bag"), ("run_1", "run_1"), ("run_2", "run_2")]
    folder_inputs = run_inputs(bags["mcap"]).files
    assert sorted(path.name for path in folder_inputs) == ["metadata.yaml", "run_2.mcap"]
    assert run_inputs(bags["ros1"]).files == [bags["ros1"].resolve()]


def test_batch_computes_poses_from_bags(tmp_path):
    campaign, bags = _campaign(tmp_path)
    out = tmp_path / "out"
    summary = run_batch([str(campaign / "run_*")], out, "tool", relative_to="world",
                        workers=1)
    assert summary.bad == [] and len(summary.computed) == 3
    poses = pd.read_parquet(out / "poses")
    for number, run in enumerate(("run_0", "run_1", "run_2")):
        rows = poses[poses["run"] == run].sort_values("time_s")
        assert rows["time_s"].tolist() == [0.0, 1.0, 2.0]
        np.testing.assert_array_equal(rows[["x_m", "y_m", "z_m"]].to_numpy(),
                                      [[number, 0, 0], [number, 1, 0], [number, 2, 0]])
    manifest = pd.read_json(out / "manifest.jsonl", lines=True)
    folder = manifest[manifest["run"] == "run_2"].iloc[0]
    storage_file = next(bags["mcap"].glob("*.mcap"))
    assert folder["checksums"][str(storage_file.resolve())] == hashlib.sha256(
        storage_file.read_bytes()).hexdigest()
