"""``pinframes batch`` as users start it: a subprocess with its own local cluster."""

from __future__ import annotations

import importlib.util
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from pinframes import read_scene

# a Dask cluster per test: in the slow set (CI runs it)
pytestmark = pytest.mark.slow

SRC = Path(__file__).resolve().parents[2] / "src"


def _run(*args: object, timeout: float = 300) -> subprocess.CompletedProcess:
    env = dict(os.environ)
    env["PYTHONPATH"] = os.pathsep.join(filter(None, [str(SRC), env.get("PYTHONPATH")]))
    return subprocess.run([sys.executable, *map(str, args)], capture_output=True, text=True,
                          env=env, timeout=timeout, check=False)


def test_importing_pinframes_and_its_command_line_imports_no_dask():
    result = _run("-c", "import sys, pinframes, pinframes.cli; "
                  "print(sorted({'dask', 'distributed', 'pyarrow'} & set(sys.modules)))")
    assert result.returncode == 0, result.stderr
    assert result.stdout.strip() == "[]"


def test_batch_help():
    result = _run("-m", "pinframes.cli", "batch", "--help")
    assert result.returncode == 0 and "--scheduler ADDRESS" in result.stdout


def test_batch_on_a_runs_list_with_a_local_cluster(tmp_path, make_campaign):
    scenes = make_campaign(tmp_path / "campaign", runs=2, samples=200, seed=3)
    listing = tmp_path / "runs.csv"
    listing.write_text("run,file\nfirst,campaign/run_0000/scene.yaml\n"
                       "second,campaign/run_0001/scene.yaml\nbroken,campaign/none.yaml\n",
                       encoding="utf-8")
    out = tmp_path / "out"
    result = _run("-m", "pinframes.cli", "batch", listing, "--frame", "torch_tcp",
                  "--relative-to", "workpiece", "--step", "0.5s", "--out", out,
                  "--workers", "2")
    assert result.returncode == 1, result.stderr
    lines = result.stderr.splitlines()
    dashboard = [line for line in lines if "dashboard" in line]
    if importlib.util.find_spec("bokeh") is None:  # no dashboard, so no line about one
        assert dashboard == []
    else:
        assert len(dashboard) == 1 and dashboard[0].startswith(
            "pinframes: dask dashboard at http://127.0.0.1:")
    assert (f"pinframes: 3 runs: 2 computed, 1 without poses, 0 unchanged; poses in "
            f"{out / 'poses'}") in lines
    assert f"pinframes: run broken: {tmp_path / 'campaign' / 'none.yaml'}: no such file" in (
        lines)
    assert lines[-1] == ("pinframes: error: 1 of 3 runs has no poses (see "
                         f"{out / 'manifest.jsonl'})")
    table = pd.read_parquet(out / "poses")
    for run, scene in zip(("first", "second"), scenes, strict=True):
        rows = table[table["run"] == run].sort_values("time_s")
        np.testing.assert_allclose(rows["time_s"], np.arange(0.0, 20.0 + 1e-9, 0.5),
                                   rtol=0, atol=1e-12)
        pose = read_scene(scene).pose("torch_tcp", relative_to="workpiece",
                                      times=rows["time_s"].to_numpy())
        np.testing.assert_allclose(rows[["x_m", "y_m", "z_m"]], pose.translation,
                                   rtol=0, atol=1e-12)
        np.testing.assert_allclose(rows[["qx", "qy", "qz", "qw"]], pose.quaternion,
                                   rtol=0, atol=1e-12)
