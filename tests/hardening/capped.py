"""Run a piece of pinframes code in a child process whose memory and CPU time are capped, so
that a test of a bound fails (instead of taking the machine down) when the bound is missing."""

from __future__ import annotations

import os
import resource
import subprocess
import sys
from pathlib import Path

MEMORY_CAP = 1024**3  # bytes of address space: pinframes with its libraries uses ~300 MB
CPU_SECONDS = 30
TESTS = Path(__file__).resolve().parents[1]

_CHILD = """
import sys
from pinframes.errors import PinframesError
try:
    exec(sys.argv[1])
except PinframesError as exc:
    print(type(exc).__name__, exc)
except BaseException as exc:
    print("NOT-A-PINFRAMES-ERROR", repr(exc)[:500])
"""


def _capped() -> None:
    resource.setrlimit(resource.RLIMIT_AS, (MEMORY_CAP, MEMORY_CAP))
    resource.setrlimit(resource.RLIMIT_CPU, (CPU_SECONDS, CPU_SECONDS))


def run_capped(code: str, *arguments: str) -> str:
    """What ``code`` printed (its result, or the pinframes error it raised: class name and
    message) in a capped child; ``sys.argv[2:]`` there are ``arguments``."""
    environment = {**os.environ, "PYTHONPATH": os.pathsep.join([str(TESTS), *sys.path]),
                   "OPENBLAS_NUM_THREADS": "1"}
    done = subprocess.run([sys.executable, "-c", _CHILD, code, *arguments], env=environment,
                          preexec_fn=_capped, capture_output=True, text=True,
                          timeout=CPU_SECONDS * 4)
    assert done.returncode == 0, f"the child died ({done.returncode}): {done.stderr[-2000:]}"
    return done.stdout.strip()
