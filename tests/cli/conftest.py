"""Fixtures for the command-line tests: running ``pinframes`` in a subprocess, a small scene."""

from __future__ import annotations

import os
import subprocess
import sys
import textwrap
from collections.abc import Callable
from pathlib import Path

import pytest

SRC = Path(__file__).resolve().parents[2] / "src"

TURNTABLE = """\
    pinframes_scene: 1
    name: turntable
    frames:
      - name: table
        parent: world
        xyz: [1.0, 0.0, 0.5]
        keyframes:
          - {time: 0, rpy: [0, 0, 0]}
          - {time: 10, rpy: [0, 0, 1.5707963267948966]}
    tools:
      - {name: tip, parent: table, xyz: [0.2, 0, 0]}
    """


def _environment() -> dict[str, str]:
    env = dict(os.environ)
    env["PYTHONPATH"] = os.pathsep.join(filter(None, [str(SRC), env.get("PYTHONPATH")]))
    return env


def _run_cli(*args: object, cwd: Path | None = None, **kwargs) -> subprocess.CompletedProcess:
    env = _environment()
    return subprocess.run([sys.executable, "-m", "pinframes.cli", *map(str, args)],
                          capture_output=True, text=True, cwd=cwd, env=env, timeout=120,
                          **kwargs)


@pytest.fixture
def run_cli() -> Callable[..., subprocess.CompletedProcess]:
    """``run_cli(*args)``: ``python -m pinframes.cli ARGS`` with this checkout's sources."""
    return _run_cli


@pytest.fixture
def cli_env() -> dict[str, str]:
    """The environment for running this checkout's pinframes in a subprocess."""
    return _environment()


@pytest.fixture
def turntable(tmp_path: Path) -> Path:
    """A table at (1, 0, 0.5) m turning 90 degrees about z in 10 s; ``tip`` 0.2 m out on it."""
    path = tmp_path / "turntable.yaml"
    path.write_text(textwrap.dedent(TURNTABLE))
    return path
