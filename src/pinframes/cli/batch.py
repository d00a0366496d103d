"""``pinframes batch RUNS... --frame F --out DIR``: poses of many runs on Dask, to Parquet."""

from __future__ import annotations

import argparse
import sys
from typing import TYPE_CHECKING

from ..errors import PinframesError, UnsupportedFeatureError
from ..formats.limits import current_limits
from ._evaluate import terminal_stderr
from ._subcommand import Subparsers, subcommand_parser

if TYPE_CHECKING:
    from ..batch import BatchSummary

__all__ = ["add_parser", "batch_summary", "run"]


def add_parser(subparsers: Subparsers, parents: list[argparse.ArgumentParser]) -> None:
    """Register the ``batch`` subcommand."""
    parser = subcommand_parser(
        subparsers, parents, "batch", run,
        help="poses of a frame in many runs, on Dask, to Parquet",
        description="Compute the pose of --frame in --relative-to at every sample of every "
        "run and write OUT/poses/<run>.parquet (columns run, time_s, timestamp, x_m, y_m, "
        "z_m, qx, qy, qz, qw: seconds, metres, unit quaternion x y z w; with --velocity "
        "also vx_m_s, vy_m_s, vz_m_s, wx_rad_s, wy_rad_s, wz_rad_s) and "
        "OUT/manifest.jsonl (per run: status, samples, error, input checksums). Runs whose "
        "input files and options did not change since an earlier batch into OUT are "
        "skipped. The workers read every run under the --max-... limits given before or "
        "after 'batch'; a run read under higher limits is skipped, one refused under other "
        "limits is tried again. No xacro file is expanded unless --xacro is given (it runs "
        "the files' code on every worker). Needs pinframes[batch].", tree_file=None)
    parser.add_argument("runs", nargs="+", metavar="RUNS",
                        help="run files (scene, ASDF, ...), glob patterns (quote them), or "
                        "runs lists (.csv with header 'run,file')")
    parser.add_argument("--frame", required=True, metavar="FRAME",
                        help="the frame whose pose is wanted (the tool)")
    parser.add_argument("--relative-to", "-r", metavar="OTHER",
                        help="the frame the pose is expressed in (default: FRAME's parent)")
    parser.add_argument("--velocity", action="store_true",
                        help="add the exact velocity of FRAME relative to the other frame, "
                        "in its axes: columns vx_m_s, vy_m_s, vz_m_s (its origin, m/s) and "
                        "wx_rad_s, wy_rad_s, wz_rad_s (angular, rad/s) (default: off)")
    group = parser.add_argument_group(
        "times", "Default: every keyframe and joint sample on the path, per run.")
    group.add_argument("--times", nargs="+", metavar="T",
                       help="these times in every run (seconds, durations, timestamps; "
                       "default: every sample on the path)")
    group.add_argument("--step", metavar="DT",
                       help="resample each run from its first to its last sample every DT "
                       "(default: none, no resampling)")
    group.add_argument("--time-ref", metavar="TIMESTAMP",
                       help="reference time that relative --times count from (default: "
                       "each run's own)")
    parser.add_argument("--out", "-o", required=True, metavar="DIR", help="output folder")
    parser.add_argument("--scheduler", metavar="ADDRESS",
                        help="address of a running Dask scheduler (default: a local "
                        "cluster on 127.0.0.1)")
    parser.add_argument("--workers", type=int, metavar="N",
                        help="worker processes of the local cluster (default: one per core)")
    parser.add_argument("--chunk-size", type=int, metavar="N", default=None,
                        help="samples evaluated and written at a time (default 100000)")


def run(args: argparse.Namespace) -> int:
    """Run the batch; exit status 1 when a run has no poses."""
    if args.robot_description is not None:
        raise UnsupportedFeatureError("pinframes batch reads each bag's own "
                                      "/robot_description; --robot-description is for the "
                                      "commands that read one file", field="robot_description")
    try:
        from ..batch import MANIFEST_NAME, run_batch
    except ImportError as exc:
        raise UnsupportedFeatureError(f"pinframes batch needs dask.distributed and pyarrow "
                                      f"(pip install 'pinframes[batch]'): {exc}") from None
    extra = {} if args.chunk_size is None else {"chunk_size": args.chunk_size}
    summary = run_batch(args.runs, args.out, args.frame, relative_to=args.relative_to,
                        times=args.times, step=args.step, time_ref=args.time_ref,
                        velocity=args.velocity, scheduler=args.scheduler, workers=args.workers,
                        limits=current_limits(),  # --max-... (main() sets them), to the workers
                        progress_bar=terminal_stderr() is not None, log=sys.stderr,
                        xacro=bool(getattr(args, "xacro", None)), **extra)
    print(f"pinframes: {batch_summary(summary)}", file=sys.stderr)
    if summary.bad:
        for record in summary.bad:
            print(f"pinframes: run {record['run']}: {record['error']}", file=sys.stderr)
        bad, total = len(summary.bad), len(summary.records)
        raise PinframesError(f"{bad} of {_count(total, 'run')} {'has' if bad == 1 else 'have'} "
                             f"no poses (see {summary.dataset.parent / MANIFEST_NAME})")
    return 0


def batch_summary(summary: BatchSummary) -> str:
    """``3 runs: 1 computed, 1 without poses, 1 unchanged (1 without poses); poses in
    OUT/poses``: what was done now, and of the runs unchanged since an earlier batch those
    that have no poses, so that the runs without poses add up to ``summary.bad``."""
    unchanged_bad = len(summary.bad) - len(summary.without_poses)
    unchanged = f"{len(summary.skipped)} unchanged" + (
        f" ({unchanged_bad} without poses)" if unchanged_bad else "")
    return (f"{_count(len(summary.records), 'run')}: {len(summary.computed)} computed, "
            f"{len(summary.without_poses)} without poses, {unchanged}; poses in "
            f"{summary.dataset}")


def _count(number: int, noun: str) -> str:
    """``1 run``, ``2 runs``."""
    return f"{number} {noun}" + ("" if number == 1 else "s")
