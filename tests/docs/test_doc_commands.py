"""The shell commands of README.md and of every docs/*.md page run as written.

Every ``pinframes`` line of a ``bash`` block runs, page by page and in order, in a scratch
folder that sees the repository's ``models/`` and ``tests/data/`` (so the paths are the
pages'), with ``pinframes`` being this checkout's command line. The other lines install
pinframes or run its development tools; they are listed below, and CI (``.ci/run``) runs
the install and test commands itself.
"""

import os
import re
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
DOCUMENTS = [ROOT / "README.md", *sorted((ROOT / "docs").glob("*.md"))]
# run by CI, or long-running development tools (a 10-minute fuzz run, a fresh venv)
NOT_RUN_HERE = (
    "python3 -m venv .venv && .venv/bin/pip install",
    ".venv/bin/ruff check",
    ".venv/bin/python -m pytest",
    ".venv/bin/python benchmarks/",
    "python3 -m venv .venv-weldx",
    "PINFRAMES_WELDX_PYTHON=",
    "PYTHONPATH=src .venv/bin/python tests/hardening/fuzz.py",
    ".venv/bin/mypy src",
    ".venv/bin/python docs/make_api_reference.py",
)
# examples that need files or services a checkout does not have: a campaign of recorded runs,
# a remote Dask scheduler (tests/batch runs pinframes batch on runs it writes itself)
NEEDS_DATA = ("pinframes batch ",)


def shell_commands(path):
    blocks = re.findall(r"```(?:bash|sh|shell)\n(.*?)```", path.read_text(), re.S)
    lines = [line.strip() for block in blocks for line in block.splitlines()]
    return [line for line in lines if line and not line.startswith("#")]


def test_every_documented_command_is_run_here_or_by_ci():
    commands = [line for path in DOCUMENTS for line in shell_commands(path)]
    assert any(line.startswith("pinframes ") for line in commands)
    for line in commands:
        assert line.startswith("pinframes ") or line.startswith(NOT_RUN_HERE), line


@pytest.mark.slow
def test_documented_pinframes_commands_run_as_written(tmp_path):
    (tmp_path / "models").symlink_to(ROOT / "models")
    (tmp_path / "tests").mkdir()
    (tmp_path / "tests" / "data").symlink_to(ROOT / "tests" / "data")
    bin_folder = tmp_path / "bin"
    bin_folder.mkdir()
    shim = bin_folder / "pinframes"
    shim.write_text(f'#!/bin/sh\nexec "{sys.executable}" -m pinframes.cli "$@"\n')
    shim.chmod(0o755)
    env = dict(os.environ)
    env["PATH"] = f"{bin_folder}{os.pathsep}{env['PATH']}"
    env["PYTHONPATH"] = os.pathsep.join(filter(None, [str(ROOT / "src"),
                                                      env.get("PYTHONPATH")]))
    command_line = (ROOT / "docs" / "command-line.md").read_text()
    for path in DOCUMENTS:
        for line in shell_commands(path):
            if not line.startswith("pinframes ") or line.startswith(NEEDS_DATA):
                continue
            result = subprocess.run(["bash", "-c", line], cwd=tmp_path, env=env,
                                    capture_output=True, text=True, timeout=600)
            assert result.returncode == 0, f"{path.name}: {line}\n{result.stderr}"
            for sign_of_failure in ("error:", "Traceback"):
                assert sign_of_failure not in result.stderr, f"{path.name}: {line}\n{result.stderr}"
            if line.startswith("pinframes demo"):
                # the summary docs/command-line.md shows is the one the demo prints
                assert result.stdout in command_line, result.stdout
    assert (tmp_path / "frames.png").read_bytes()[:4] == b"\x89PNG"
