"""What a batch says: worker warnings as one ``pinframes: warning:`` line each, a summary
whose counts add up, ids in the order of the runs, the extra that the batch page's example
needs."""

from __future__ import annotations

import os
import re
import subprocess
import sys
from pathlib import Path

import pytest
import yaml

from pinframes.batch import BatchSummary, run_batch

# a Dask cluster per test: in the slow set (CI runs it)
pytestmark = pytest.mark.slow

ROOT = Path(__file__).resolve().parents[2]


def _summary(statuses: dict[str, str], computed: list[str], without: list[str],
             skipped: list[str]) -> BatchSummary:
    summary = BatchSummary(Path("out/poses"), Path("out/manifest.jsonl"))
    summary.records = [{"run": run, "status": status} for run, status in statuses.items()]
    summary.computed, summary.without_poses, summary.skipped = computed, without, skipped
    return summary


def test_runs_without_poses_from_an_earlier_batch_are_counted_in_the_summary():
    """A second batch over the same runs: one broken run unchanged since the first."""
    from pinframes.cli.batch import batch_summary

    summary = _summary({"a": "ok", "b": "ok", "broken": "error"}, [], [],
                       ["a", "b", "broken"])
    assert batch_summary(summary) == (
        "3 runs: 0 computed, 0 without poses, 3 unchanged (1 without poses); poses in "
        f"{Path('out/poses')}")
    summary = _summary({"only": "ok"}, ["only"], [], [])
    assert batch_summary(summary).startswith("1 run: 1 computed, 0 without poses, 0 unchanged;")


def test_the_ids_come_in_the_order_of_the_runs(tmp_path, make_campaign):
    """The first run is the longest by far: with two workers the others finish first."""
    slow = make_campaign(tmp_path / "slow", runs=1, samples=60000, seed=1)
    quick = make_campaign(tmp_path / "quick", runs=3, samples=50, seed=2)
    listing = tmp_path / "runs.csv"
    listing.write_text("run,file\n" + "".join(
        f"{name},{path}\n" for name, path in zip(("z_slow", "c", "b", "a"), slow + quick,
                                                 strict=True)), encoding="utf-8")
    summary = run_batch([str(listing)], tmp_path / "out", "torch_tcp",
                        relative_to="workpiece", workers=2)
    assert summary.computed == ["z_slow", "c", "b", "a"]
    assert [record["run"] for record in summary.records] == summary.computed


def test_worker_warnings_are_one_pinframes_line_each(tmp_path, make_campaign):
    scenes = make_campaign(tmp_path / "campaign", runs=2, samples=50, seed=5)
    scene = yaml.safe_load(scenes[1].read_text(encoding="utf-8"))
    scene["frames"].append({"name": "marker", "parent": "workpiece", "rpy": [0, 0, 90]})
    scenes[1].write_text(yaml.safe_dump(scene, sort_keys=False), encoding="utf-8")
    env = dict(os.environ)
    env["PYTHONPATH"] = os.pathsep.join(filter(None, [str(ROOT / "src"),
                                                      env.get("PYTHONPATH")]))
    result = subprocess.run(
        [sys.executable, "-m", "pinframes.cli", "batch", str(tmp_path / "campaign" / "*" /
                                                             "scene.yaml"),
         "--frame", "torch_tcp", "-r", "workpiece", "--out", str(tmp_path / "out"),
         "--workers", "2"], capture_output=True, text=True, env=env, timeout=300)
    assert result.returncode == 0, result.stderr
    warning_lines = [line for line in result.stderr.splitlines() if "degrees" in line]
    assert warning_lines == [line for line in warning_lines
                             if line.startswith("pinframes: warning: run run_0001: ")]
    assert len(warning_lines) == 1 and "frame 'marker'" in warning_lines[0]
    assert "UnitWarning" not in result.stderr and "warnings.warn" not in result.stderr


def test_the_batch_extra_installs_what_the_batch_page_example_imports():
    project = (ROOT / "pyproject.toml").read_text(encoding="utf-8")  # Python 3.10: no tomllib
    batch = re.search(r"^batch = \[(.*?)\]$", project, re.M | re.S)
    assert batch is not None
    page = (ROOT / "docs" / "batch.md").read_text(encoding="utf-8")
    example = page[page.index("from pinframes.batch import run_batch") - 40:]
    assert "import pandas as pd" in example[:200]
    assert '"pandas' in batch.group(1)
