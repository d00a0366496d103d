"""Ask weldx 0.8.2, installed in a separate environment, about ASDF files.

``.ci/run`` builds that environment and sets ``PINFRAMES_WELDX_PYTHON`` to its interpreter;
without the variable the interop tests are skipped (a developer's machine), with a broken one
they fail. The weldx side is ``weldx_side.py``; see its docstring for the requests.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path
from typing import Any

import numpy as np
import pytest

WELDX_PYTHON = os.environ.get("PINFRAMES_WELDX_PYTHON")
WELDX_SIDE = Path(__file__).with_name("weldx_side.py")

needs_weldx = pytest.mark.skipif(WELDX_PYTHON is None,
                                 reason="PINFRAMES_WELDX_PYTHON is not set (.ci/run sets it)")


def ask_weldx(op: str, **request: Any) -> dict[str, Any]:
    """Run one request in the weldx environment and return its JSON answer."""
    if WELDX_PYTHON is None:
        pytest.skip("PINFRAMES_WELDX_PYTHON is not set")
    request = {"op": op, **{k: str(v) if isinstance(v, Path) else v for k, v in request.items()}}
    done = subprocess.run([WELDX_PYTHON, "-W", "ignore", str(WELDX_SIDE)],
                          input=json.dumps(request), capture_output=True, text=True,
                          timeout=300, check=False)
    if done.returncode != 0:
        sys.stderr.write(done.stderr)
        raise AssertionError(f"weldx failed on {request}: {done.stderr.strip().splitlines()[-1:]}")
    return json.loads(done.stdout)


def weldx_pose(path: Path, frame: str, relative_to: str, times_ns: Any = None,
               time_ref: str | None = None) -> dict[str, Any]:
    """weldx's ``get_cs`` answer as numpy arrays: translation (T, 3) in metres, rotation
    (T, 3, 3), ``times_ns`` (T,) int64 or None, ``reference_time`` datetime64[ns] or None."""
    return _as_arrays(ask_weldx("get_cs", **_query(frame, relative_to, times_ns, time_ref),
                                path=path))


def weldx_poses(path: Path, queries: list[dict[str, Any]]) -> list[dict[str, Any]]:
    """Many ``get_cs`` answers from one weldx process (its import is slow).

    Each query is ``{frame, relative_to, times_ns (optional), time_ref (optional)}``; each
    answer is as for :func:`weldx_pose`, or ``{"error": message}`` where weldx raised."""
    requests = [_query(q["frame"], q["relative_to"], q.get("times_ns"), q.get("time_ref"))
                for q in queries]
    answers = ask_weldx("get_cs_many", path=path, queries=requests)["answers"]
    return [answer if "error" in answer else _as_arrays(answer) for answer in answers]


def _query(frame: str, relative_to: str, times_ns: Any, time_ref: str | None) -> dict:
    times = None if times_ns is None else np.asarray(times_ns, dtype=np.int64).tolist()
    return {"frame": frame, "relative_to": relative_to, "times_ns": times,
            "time_ref": time_ref}


def _as_arrays(answer: dict[str, Any]) -> dict[str, Any]:
    reference = answer["reference_time"]
    return {"translation": np.asarray(answer["translation"], dtype=float).reshape(-1, 3),
            "rotation": np.asarray(answer["rotation"], dtype=float).reshape(-1, 3, 3),
            "times_ns": None if answer["times_ns"] is None
            else np.asarray(answer["times_ns"], dtype=np.int64),
            "reference_time": None if reference is None
            else np.datetime64(reference.replace("+00:00", ""), "ns")}
