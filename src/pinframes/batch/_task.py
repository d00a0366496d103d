"""One run on a worker: skip it if unchanged, else read, evaluate in chunks and write.

Runs in a Dask worker process; takes a :class:`RunTask` and returns a :class:`RunResult`
whose record becomes the run's line in the manifest. Nothing here raises for a bad run:
a pinframes error is the record's ``error`` (status ``"error"``, kept until the input,
the options or the limits change), anything else status ``"failed"`` (tried again by the
next batch).

The task's :class:`~pinframes.Limits` bound every file the worker reads for the run, and
go into the record (``limits``). They decide nothing about the rows a run has, only whether
its files are read at all, and a file within some limits is within any higher ones; so a
run that was read is read again only when a limit is now lower than it was then (the
stricter limits are checked), and a refused run is tried again when any limit changed
(say, raised for it). Records written before limits were recorded were read with the
defaults.
"""

from __future__ import annotations

import datetime
import os
import time
import warnings
from dataclasses import asdict, dataclass
from pathlib import Path
from typing import Any

from .. import FrameTree, Limits
from ..errors import PinframesError
from ..formats.limits import using_limits
from ._compute import output_schema, pose_chunks
from ._inputs import checksums, read_run, run_inputs
from ._options import BatchOptions
from ._partition import PartitionWriter, partition_path
from ._runs import Run

__all__ = ["KILL_ONCE_VARIABLE", "RunResult", "RunTask", "process_run"]

KILL_ONCE_VARIABLE = "PINFRAMES_BATCH_TEST_KILL_ONCE"
"""Test hook: names a marker file. A worker that has written a run's first chunk while the
marker does not exist creates it and kills its own process (``os._exit``), once: the test
of a worker lost in the middle of a run."""

_KEPT_STATUSES = ("ok", "error")


@dataclass(frozen=True)
class RunTask:
    """One run to bring up to date in ``out``; ``previous`` is its last manifest record."""

    run: Run
    out: Path
    options: BatchOptions
    options_digest: str
    previous: dict[str, Any] | None
    limits: Limits


@dataclass(frozen=True)
class RunResult:
    """The run's manifest record, whether it was computed (False: skipped), and the
    warnings reading and evaluating it gave on the worker (category, message; each once),
    for the driver to give again where the user sees them."""

    record: dict[str, Any]
    computed: bool
    warnings: tuple[tuple[type[Warning], str], ...] = ()


def process_run(task: RunTask) -> RunResult:
    """Bring one run's output up to date (see the module docstring); ``computed`` is False
    for a run skipped as unchanged."""
    started = time.perf_counter()
    recorded = _recorded_files(task.previous)
    if recorded and _unchanged(task, checksums(recorded)):
        assert task.previous is not None
        return RunResult(task.previous, computed=False)
    with using_limits(task.limits):
        inputs = run_inputs(task.run.path)
    files = checksums(inputs.files)
    record: dict[str, Any] = {
        "run": task.run.run_id, "file": os.fspath(task.run.path), "input": task.run.input,
        "status": "ok",
        "samples": None, "error": None, "checksums": files, "options": task.options_digest,
        "limits": asdict(task.limits)}
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        try:
            tree = read_run(inputs, task.limits, task.options.xacro)
            record["samples"] = _write_poses(tree, task)
        except PinframesError as exc:
            record.update(status="error", error=_located(exc, task.run.path))
        except Exception as exc:  # a bug or the machine, not the input: try again next time
            record.update(status="failed", error=f"{type(exc).__name__}: {exc}")
    if record["status"] != "ok":  # no stale poses beside a record that has none
        partition_path(task.out, task.run.run_id).unlink(missing_ok=True)
    record["seconds"] = round(time.perf_counter() - started, 6)
    record["finished"] = datetime.datetime.now(datetime.timezone.utc).isoformat()
    given = dict.fromkeys((warning.category, str(warning.message)) for warning in caught)
    return RunResult(record, computed=True, warnings=tuple(given))


def _recorded_files(previous: dict[str, Any] | None) -> list[Path]:
    """The files the previous record has checksums of. When none of them changed, they are
    still the run's files: which files a file reads depends only on its content and place,
    so its format names the same ones again (and the run needs no parsing to be skipped)."""
    recorded = None if previous is None else previous.get("checksums")
    return [Path(file) for file in recorded] if isinstance(recorded, dict) else []


def _unchanged(task: RunTask, files: dict[str, str]) -> bool:
    previous = task.previous
    return (previous is not None and previous.get("status") in _KEPT_STATUSES
            and previous.get("options") == task.options_digest
            and previous.get("checksums") == files
            and _limits_still_hold(previous, task.limits)
            and (previous["status"] != "ok"
                 or partition_path(task.out, task.run.run_id).is_file()))


def _limits_still_hold(previous: dict[str, Any], limits: Limits) -> bool:
    """Whether ``limits`` give the outcome ``previous`` had (see the module docstring)."""
    before: dict[str, Any] = asdict(Limits())
    recorded = previous.get("limits")
    before.update(recorded if isinstance(recorded, dict) else {})
    now = asdict(limits)
    if not all(isinstance(before.get(name), int) for name in now):
        return False  # an edited record: read the run again
    if previous["status"] == "ok":
        return all(now[name] >= before[name] for name in now)
    return before == now


def _write_poses(tree: FrameTree, task: RunTask) -> int:
    with PartitionWriter(task.out, task.run.run_id, output_schema(task.options)) as writer:
        for table in pose_chunks(tree, task.run.run_id, task.options):
            writer.write(table)
            _kill_once_for_tests()
    return writer.rows


def _located(exc: PinframesError, path: Path) -> str:
    """The error's message, naming the run's file when the error names none."""
    return str(exc if exc.file is not None else exc.located(file=path))


def _kill_once_for_tests() -> None:
    marker = os.environ.get(KILL_ONCE_VARIABLE)
    if not marker:
        return
    try:
        os.close(os.open(marker, os.O_CREAT | os.O_EXCL | os.O_WRONLY))
    except FileExistsError:
        return
    os._exit(70)
