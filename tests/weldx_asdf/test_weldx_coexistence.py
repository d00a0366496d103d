"""pinframes and weldx 0.8.2 in one process (CI runs this inside the weldx environment, where
pinframes is installed beside weldx; elsewhere it is skipped).

pinframes binds its schemas only while it reads or writes, so weldx's converters never see
pinframes' data and weldx keeps reading and writing its own files unchanged. The checks run
in a fresh interpreter (this file as a script), where pinframes touches asdf before weldx does.
"""

from __future__ import annotations

import os
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np
import pytest

weldx = pytest.importorskip("weldx")

import asdf  # noqa: E402
import pandas as pd  # noqa: E402
from weldx import Q_, CoordinateSystemManager, LocalCoordinateSystem, WeldxFile  # noqa: E402

import pinframes  # noqa: E402

from geometry import rot_z  # noqa: E402

T0 = "2024-03-01T08:00:00"


def pinframes_tree() -> pinframes.FrameTree:
    tree = pinframes.FrameTree("base", name="cell", reference_time=T0)
    tree.add("table", "base", pinframes.Pose([[0.1, 0, 0], [0.3, 0, 0]], rot_z(0.5),
                                             times=[0.0, 10.0]))
    tree.add("tool", "table", pinframes.Pose([0.0, 0.0, 0.2]))
    return tree


def weldx_csm() -> CoordinateSystemManager:
    csm = CoordinateSystemManager("base", "weldx cell", time_ref=pd.Timestamp(T0))
    csm.add_cs("arm", "base", LocalCoordinateSystem(
        orientation=rot_z(0.25), coordinates=Q_([[10.0, 0, 0], [20.0, 0, 0]], "mm"),
        time=pd.to_timedelta([0, 4], unit="s")))
    return csm


def weldx_arm_at_2s(csm: CoordinateSystemManager) -> np.ndarray:
    lcs = csm.get_cs("arm", "base", time=pd.to_timedelta([2], unit="s"))
    return np.asarray(lcs.coordinates.data.to("m").m, dtype=float).reshape(-1, 3)[0]


def test_pinframes_and_weldx_share_one_process():
    tests = str(Path(__file__).parents[1])  # for geometry.py
    path = os.pathsep.join(filter(None, [tests, os.environ.get("PYTHONPATH")]))
    subprocess.run([sys.executable, __file__], check=True, timeout=300,
                   env={**os.environ, "PYTHONPATH": path})


def check_one_process(tmp_path: Path) -> None:
    """pinframes first, then weldx, then both, in this interpreter."""
    tree = pinframes_tree()
    pinframes.write_asdf(tree, tmp_path / "current.asdf", schema="0.1.0")
    pinframes.write_asdf(tree, tmp_path / "legacy.asdf", schema="1.0.0")

    with WeldxFile(tmp_path / "current.asdf", mode="r") as file:
        csm = file["coordinate_system_hierarchy"]
        assert isinstance(csm, CoordinateSystemManager)
        tool = csm.get_cs("tool", "base", time=pd.to_timedelta([5], unit="s"))
    # hand-derived: table halfway (0.2 m along x), tool 0.2 m above it
    np.testing.assert_allclose(np.asarray(tool.coordinates.data.to("m").m).reshape(-1, 3)[0],
                               [0.2, 0.0, 0.2], atol=1e-12)
    for name in ("current.asdf", "legacy.asdf"):
        copy = pinframes.read_asdf(tmp_path / name)
        np.testing.assert_allclose(copy.pose("tool", "base", times=[5.0]).translation[0],
                                   [0.2, 0.0, 0.2], atol=1e-12)

    # weldx's own writing and reading still work, and pinframes reads weldx's file
    with WeldxFile(tmp_path / "weldx.asdf", mode="rw", tree={"csm": weldx_csm()}):
        pass
    with WeldxFile(tmp_path / "weldx.asdf", mode="r") as file:
        np.testing.assert_allclose(weldx_arm_at_2s(file["csm"]), [0.015, 0.0, 0.0],
                                   atol=1e-12)
    arm = pinframes.read_asdf(tmp_path / "weldx.asdf").pose("arm", "base", times=[2.0])
    np.testing.assert_allclose(arm.translation[0], [0.015, 0.0, 0.0], atol=1e-12)
    uris = {e.extension_uri for e in asdf.get_config().extensions}
    assert "asdf://weldx.bam.de/weldx/extensions/weldx-0.1.2" in uris
    assert not any(uri and uri.startswith("asdf://pinframes/") for uri in uris)


if __name__ == "__main__":
    with tempfile.TemporaryDirectory() as folder:
        check_one_process(Path(folder))
