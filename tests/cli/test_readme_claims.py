"""Numbers the documents state about the bundled cell, measured: the contact tip to work
distance of the documented ``--contact-tip`` command, the size of the demo's page
(docs/welding-process.md, docs/view.md)."""

from __future__ import annotations

import csv
import io
import re
import shlex
from pathlib import Path

import numpy as np
import pytest

ROOT = Path(__file__).resolve().parents[2]
STICK_OUT_M = 0.015  # contact_tip sits 15 mm back from torch_tcp along the wire (scene.yaml)


def test_the_documented_ctwd_command_names_a_contact_tip(run_cli):
    """The robot keeps torch_tcp on the seam (within 1e-6 m), so the contact tip to work
    distance is the stick-out."""
    document = (ROOT / "docs" / "welding-process.md").read_text(encoding="utf-8")
    (line,) = [line for line in document.splitlines()
               if line.startswith("pinframes process") and "--contact-tip" in line]
    arguments = shlex.split(line.split("#")[0])[1:]
    result = run_cli(*arguments, cwd=ROOT)
    assert result.returncode == 0, result.stderr
    rows = list(csv.DictReader(io.StringIO(result.stdout)))  # a text column (position) too
    assert rows
    np.testing.assert_allclose([float(row["ctwd_m"]) for row in rows], STICK_OUT_M, atol=1e-5)


@pytest.mark.slow  # seconds of CPU (subprocesses): CI's slow set
def test_the_view_page_gives_the_size_of_the_demo_page(run_cli, tmp_path):
    pytest.importorskip("meshcat")
    page = (ROOT / "docs" / "view.md").read_text(encoding="utf-8")
    stated = float(re.search(r"The page of the bundled demo \(2001 samples\) is ([0-9.]+) MB",
                             page).group(1))
    result = run_cli("demo", "--out", tmp_path)
    assert result.returncode == 0, result.stderr
    # the page inlines the viewer (three.js) of the installed meshcat: allow its size to vary
    assert abs((tmp_path / "cell.html").stat().st_size / 1e6 - stated) <= 0.15
