"""``run_batch``: bring the poses of many runs up to date in one output folder, on Dask."""

from __future__ import annotations

import contextlib
import fcntl
import os
import sys
import threading
from collections.abc import Iterable, Iterator
from dataclasses import asdict, dataclass, field
from pathlib import Path
from typing import Any, TextIO

from distributed import as_completed, progress
from distributed.client import Future

from ..errors import WriteError, warn_at_caller
from ..formats.limits import Limits, checked_limits
from ._engine import dask_client
from ._manifest import Manifest
from ._names import check_frame_names
from ._options import DEFAULT_CHUNK_SIZE, BatchOptions
from ._partition import POSES_FOLDER, clear_staging, partition_path
from ._runs import find_runs, keep_known_ids
from ._task import RunResult, RunTask, process_run

__all__ = ["BatchSummary", "run_batch"]

_LOCK_NAME = ".lock"


@dataclass
class BatchSummary:
    """What a batch did.

    Attributes
    ----------
    dataset : Path
        The Parquet dataset (``OUT/poses``), one file per run.
    manifest : Path
        ``OUT/manifest.jsonl``, one record per run.
    records : list of dict
        This batch's runs' manifest records, in the order of the runs.
    computed : list of str
        Ids of the runs whose poses were computed now, in the order of the runs.
    without_poses : list of str
        Ids of the runs tried now that have no poses (status ``error`` or ``failed``), in
        the order of the runs.
    skipped : list of str
        Ids of the runs unchanged since an earlier batch (with or without poses), in the
        order of the runs.
    """

    dataset: Path
    manifest: Path
    records: list[dict[str, Any]] = field(default_factory=list)
    computed: list[str] = field(default_factory=list)
    without_poses: list[str] = field(default_factory=list)
    skipped: list[str] = field(default_factory=list)

    @property
    def bad(self) -> list[dict[str, Any]]:
        """The records of runs without poses (status ``error`` or ``failed``)."""
        return [record for record in self.records if record["status"] != "ok"]


def run_batch(runs: Iterable[str | os.PathLike[str]], out: str | os.PathLike[str],
              frame: str, *, relative_to: str | None = None, times: Any = None,
              step: Any = None, time_ref: Any = None, velocity: bool = False,
              scheduler: str | None = None, workers: int | None = None,
              chunk_size: int = DEFAULT_CHUNK_SIZE, limits: Limits | None = None,
              progress_bar: bool = False, log: TextIO | None = None,
              xacro: bool = False) -> BatchSummary:
    """The pose of ``frame`` in ``relative_to`` at every sample of every run, on Dask.

    Parameters
    ----------
    runs : files, glob patterns or runs lists (``.csv``: ``run,file``)
        The runs, in any format pinframes reads (see :func:`find_runs` for their ids).
    out : path
        Output folder: ``poses/`` (Parquet, one file per run), ``manifest.jsonl``. Runs
        whose input files and options are unchanged since an earlier batch into the same
        folder are skipped; one batch at a time per folder.
    frame, relative_to : str
        The pose wanted (default ``relative_to``: ``frame``'s parent).
    times, step, time_ref
        The same ``times`` for every run (relative ones count from ``time_ref``), or each
        run's own samples on the path, resampled every ``step`` (seconds or a duration)
        when given.
    velocity : bool
        Also the exact velocity of ``frame`` relative to ``relative_to``, in its axes
        (:meth:`FrameTree.velocity`): columns ``vx_m_s vy_m_s vz_m_s wx_rad_s wy_rad_s
        wz_rad_s``.
    scheduler : str, optional
        Address of a running Dask scheduler; default: a local cluster of ``workers``
        processes (default: one per core) on 127.0.0.1.
    chunk_size : int
        Samples per evaluation and Parquet row group (bounds a worker's memory).
    limits : pinframes.Limits or None
        Bounds on what each run's files may cost the worker that reads them (None: those
        in effect here, e.g. the ``pinframes`` command's ``--max-...`` options, else the
        defaults). A run refused under them is an ``error`` naming the limit; changed
        limits recompute a run only when they could change its outcome (see
        :mod:`pinframes.batch._task`).
    progress_bar, log
        Show Dask's progress bar (on standard error); where to say where the dashboard is.
    xacro : bool
        Expand the xacro content of the runs' robot files and scene robots, which runs their
        code on the workers (default: never; such a run is an ``error`` naming the file).

    Bad runs do not raise: they are in ``summary.bad`` and the manifest with their error.
    Only ``frame`` and ``relative_to`` are checked before the cluster starts, on the first
    run that reads: a name that run lacks is a :class:`~pinframes.errors.FrameNotFoundError`
    suggesting near names.
    """
    options = BatchOptions.create(frame, relative_to, times, step, time_ref, chunk_size,
                                  velocity, xacro)
    limits = checked_limits(limits)
    found = find_runs(runs)
    check_frame_names(found, options, limits)
    out_path = Path(out)
    with _exclusive(out_path):
        clear_staging(out_path)
        manifest = Manifest(out_path)
        all_runs, moved = keep_known_ids(found, manifest.records)
        for run_id in moved:  # the file is another run's now: one file, one set of poses
            manifest.records.pop(run_id)
            partition_path(out_path, run_id).unlink(missing_ok=True)
        digest = options.digest()
        tasks = [RunTask(run, out_path, options, digest, manifest.records.get(run.run_id),
                         limits) for run in all_runs]
        summary = BatchSummary(out_path / POSES_FOLDER, manifest.path)
        try:
            with dask_client(scheduler, workers, log) as client:
                futures = client.map(process_run, tasks, pure=False)
                task_of = dict(zip(futures, tasks, strict=True))
                with _progress(futures, progress_bar):
                    for future in as_completed(futures):
                        result = _result(future, task_of.pop(future))
                        manifest.append(result.record)
                        _count(summary, result)
                        _warn_again(result)
        finally:
            manifest.rewrite(run.run_id for run in all_runs)
            clear_staging(out_path)
    summary.records = [manifest.records[run.run_id] for run in all_runs]
    order = {run.run_id: position for position, run in enumerate(all_runs)}
    for ids in (summary.computed, summary.without_poses, summary.skipped):
        ids.sort(key=order.__getitem__)
    return summary


def _warn_again(result: RunResult) -> None:
    """The warnings a worker caught for a run, given here (where the caller's filters and
    the command line's one-line display apply), each naming the run."""
    for category, message in result.warnings:
        warn_at_caller(f"run {result.record['run']}: {message}", category)


def _count(summary: BatchSummary, result: RunResult) -> None:
    run_id = result.record["run"]
    if not result.computed:
        summary.skipped.append(run_id)
    elif result.record["status"] == "ok":
        summary.computed.append(run_id)
    else:
        summary.without_poses.append(run_id)


def _result(future: Future, task: RunTask) -> RunResult:
    """The future's result; a run whose workers kept dying is a ``failed`` record."""
    try:
        result = future.result()
    except Exception as exc:  # KilledWorker after Dask's retries, a lost connection
        record = {"run": task.run.run_id, "file": os.fspath(task.run.path),
                  "input": task.run.input, "status": "failed", "samples": None, "checksums": None,
                  "error": f"{type(exc).__name__}: {exc}", "options": task.options_digest,
                  "limits": asdict(task.limits)}
        return RunResult(record, computed=True)
    assert isinstance(result, RunResult)
    return result


@contextlib.contextmanager
def _progress(futures: list[Future], show: bool) -> Iterator[None]:
    """Dask's text progress bar on standard error, drawn by a thread while the caller
    collects results."""
    if not show:
        yield
        return
    thread = threading.Thread(target=_draw_progress, args=(futures,), daemon=True)
    thread.start()
    yield
    thread.join(timeout=5.0)


def _draw_progress(futures: list[Future]) -> None:
    with contextlib.redirect_stdout(sys.stderr):
        progress(futures, notebook=False, multi=False)


@contextlib.contextmanager
def _exclusive(out: Path) -> Iterator[None]:
    """Hold ``out``'s lock file: a second batch into the same folder is refused."""
    try:
        out.mkdir(parents=True, exist_ok=True)
        handle = open(out / _LOCK_NAME, "a")  # closed below
    except OSError as exc:
        raise WriteError(f"cannot use this output folder: {exc.strerror or exc}",
                         file=out) from exc
    with handle:
        try:
            fcntl.flock(handle, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except BlockingIOError:
            raise WriteError("another batch is writing into this folder",
                             file=out) from None
        yield
