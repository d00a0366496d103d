"""One run's poses in chunks, the Parquet file they go to, the manifest file."""

from __future__ import annotations

import json

import numpy as np
import pyarrow as pa
import pyarrow.parquet as pq
import pytest

from pinframes import FrameTree, Pose
from pinframes.batch import partition_path
from pinframes.batch._compute import POSE_SCHEMA, output_schema, pose_chunks
from pinframes.batch._manifest import Manifest
from pinframes.batch._options import BatchOptions
from pinframes.batch._partition import PartitionWriter, clear_staging
from pinframes.errors import FrameNotFoundError, InvalidTimeError, ManifestWarning

REFERENCE = np.datetime64("2024-03-01T08:00:00", "ns")


def _slide_tree(reference=REFERENCE) -> FrameTree:
    """A tool sliding 1 m along world x in 10 s (keyframes every 0.1 s), turned 90 deg
    about z: the tool's pose in the world at t is x = t / 10, quaternion (0, 0, s, s)."""
    tree = FrameTree("world", reference_time=reference)
    times = np.linspace(0.0, 10.0, 101)
    tree.add("slide", "world", Pose(np.column_stack([times / 10, 0 * times, 0 * times]),
                                    times=times))
    half = np.sqrt(0.5)
    tree.add("tool", "slide", Pose(rotation=[0.0, 0.0, half, half]))
    return tree


def _rows(tables) -> pa.Table:
    return pa.concat_tables(list(tables))


def test_chunks_hold_every_sample_once_in_order():
    options = BatchOptions.create("tool", "world", chunk_size=7)
    tables = list(pose_chunks(_slide_tree(), "r1", options))
    assert [table.num_rows for table in tables] == [7] * 14 + [3]
    rows = _rows(tables)
    assert rows.schema == POSE_SCHEMA
    times = np.linspace(0.0, 10.0, 101)
    np.testing.assert_allclose(rows["time_s"].to_numpy(), times, rtol=0, atol=1e-9)
    np.testing.assert_allclose(rows["x_m"].to_numpy(), times / 10, rtol=0, atol=1e-12)
    np.testing.assert_allclose(rows["y_m"].to_numpy(), 0.0, atol=1e-12)
    half = np.sqrt(0.5)
    for name, value in zip(("qx", "qy", "qz", "qw"), (0.0, 0.0, half, half), strict=True):
        np.testing.assert_allclose(rows[name].to_numpy(), value, rtol=0, atol=1e-12)
    stamps = rows["timestamp"].to_numpy()
    assert stamps[0] == REFERENCE and stamps[-1] == REFERENCE + np.timedelta64(10, "s")
    assert set(rows["run"].to_pylist()) == {"r1"}


def test_velocity_columns_follow_the_pose_columns():
    """The slide moves at 0.1 m/s along world x and nothing turns (hand-derived)."""
    options = BatchOptions.create("tool", "world", chunk_size=30, velocity=True)
    rows = _rows(pose_chunks(_slide_tree(), "r", options))
    assert rows.schema == output_schema(options)
    assert rows.column_names[:10] == POSE_SCHEMA.names
    assert rows.column_names[10:] == ["vx_m_s", "vy_m_s", "vz_m_s",
                                      "wx_rad_s", "wy_rad_s", "wz_rad_s"]
    expected = {"vx_m_s": 0.1, "vy_m_s": 0.0, "vz_m_s": 0.0,
                "wx_rad_s": 0.0, "wy_rad_s": 0.0, "wz_rad_s": 0.0}
    for name, value in expected.items():
        np.testing.assert_allclose(rows[name].to_numpy(), value, rtol=0, atol=1e-12)


def test_a_step_resamples_each_run_from_its_first_to_its_last_sample():
    rows = _rows(pose_chunks(_slide_tree(), "r", BatchOptions.create("tool", "world",
                                                                     step="2.5s")))
    np.testing.assert_allclose(rows["time_s"].to_numpy(), [0, 2.5, 5, 7.5, 10], atol=1e-12)
    np.testing.assert_allclose(rows["x_m"].to_numpy(), [0, 0.25, 0.5, 0.75, 1], atol=1e-12)


def test_explicit_times_count_from_time_ref():
    options = BatchOptions.create("tool", "world", times=[1.0, 2.0],
                                  time_ref="2024-03-01T08:00:03")
    rows = _rows(pose_chunks(_slide_tree(), "r", options))
    np.testing.assert_allclose(rows["x_m"].to_numpy(), [0.4, 0.5], atol=1e-12)
    assert rows["timestamp"].to_numpy()[0] == REFERENCE + np.timedelta64(4, "s")


def test_without_a_reference_time_timestamps_are_null():
    rows = _rows(pose_chunks(_slide_tree(reference=None), "r",
                             BatchOptions.create("tool", "world", times=[5.0])))
    assert rows["timestamp"].null_count == 1
    np.testing.assert_allclose(rows["x_m"].to_numpy(), [0.5], atol=1e-12)


def test_bad_queries_are_pinframes_errors():
    with pytest.raises(FrameNotFoundError, match="'torch'"):
        list(pose_chunks(_slide_tree(), "r", BatchOptions.create("torch", "world")))
    with pytest.raises(InvalidTimeError, match="nothing moves between 'tool' and 'slide'"):
        list(pose_chunks(_slide_tree(), "r", BatchOptions.create("tool")))
    with pytest.raises(InvalidTimeError, match="either times or step"):
        BatchOptions.create("tool", times=[1.0], step=1.0)
    with pytest.raises(InvalidTimeError, match="positive"):
        BatchOptions.create("tool", step="-1s")


def test_options_digest_follows_what_changes_the_rows():
    base = BatchOptions.create("tool", "world", times=[1.0, 2.0])
    assert base.digest() == BatchOptions.create("tool", "world", times=["1s", "2000ms"],
                                                chunk_size=3).digest()
    assert base.digest() != BatchOptions.create("tool", "world", times=[1.0, 2.5]).digest()
    assert base.digest() != BatchOptions.create("tool", "slide", times=[1.0, 2.0]).digest()
    assert base.digest() != BatchOptions.create("tool", "world", times=[1.0, 2.0],
                                                velocity=True).digest()


def test_a_partition_is_renamed_into_place_only_when_complete(tmp_path):
    clear_staging(tmp_path)
    chunks = list(pose_chunks(_slide_tree(), "r/1", BatchOptions.create(
        "tool", "world", chunk_size=40)))
    with PartitionWriter(tmp_path, "r/1", POSE_SCHEMA) as writer:
        for table in chunks:
            writer.write(table)
    target = partition_path(tmp_path, "r/1")
    assert target.name == "r%2F1.parquet"
    assert pq.ParquetFile(target).num_row_groups == 3  # one row group per chunk
    before = target.read_bytes()
    with pytest.raises(RuntimeError), PartitionWriter(tmp_path, "r/1", POSE_SCHEMA) as writer:
        writer.write(chunks[0])
        raise RuntimeError("the run breaks after its first chunk")
    assert target.read_bytes() == before
    assert list((tmp_path / ".staging").iterdir()) == []


def test_run_ids_never_become_hidden_file_names(tmp_path):
    assert partition_path(tmp_path, ".x").name == "%2Ex.parquet"
    assert partition_path(tmp_path, "_x").name == "%5Fx.parquet"


def test_the_manifest_keeps_the_last_record_and_ignores_a_torn_last_line(tmp_path):
    manifest = Manifest(tmp_path)
    manifest.append({"run": "a", "status": "failed"})
    manifest.append({"run": "b", "status": "ok"})
    manifest.append({"run": "a", "status": "ok"})
    with open(manifest.path, "a", encoding="utf-8") as handle:
        handle.write('{"run": "c", "sta')
    with pytest.warns(ManifestWarning, match="line 4 is no run record"):
        again = Manifest(tmp_path)
    assert again.records == {"a": {"run": "a", "status": "ok"},
                             "b": {"run": "b", "status": "ok"}}
    again.rewrite(["b", "x"])
    lines = manifest.path.read_text(encoding="utf-8").splitlines()
    assert [json.loads(line)["run"] for line in lines] == ["b", "a"]


def test_a_record_appended_after_a_torn_line_starts_a_line_of_its_own(tmp_path):
    manifest = Manifest(tmp_path)
    manifest.append({"run": "a", "status": "ok"})
    with open(manifest.path, "a", encoding="utf-8") as handle:
        handle.write('{"run": "b", "sta')  # the driver stopped while appending
    with pytest.warns(ManifestWarning, match="line 2"):
        again = Manifest(tmp_path)
    again.append({"run": "c", "status": "ok"})
    lines = manifest.path.read_text(encoding="utf-8").splitlines()
    assert lines[1] == '{"run": "b", "sta' and json.loads(lines[2]) == {"run": "c",
                                                                        "status": "ok"}
    with pytest.warns(ManifestWarning, match="line 2 is"):
        assert set(Manifest(tmp_path).records) == {"a", "c"}
