"""Many runs on Dask: runs per second with 1 and 2 worker processes beside a plain loop.

Case (issue 19): a generated campaign of the bundled welding cell
(``models/welding_cell/make_campaign.py``: its own trajectory per run, 10^4 joint samples
each), the torch tip in the workpiece frame at every sample of every run, written as one
Parquet file per run. The reference is a plain loop in this process doing the same work
per run (read the scene, evaluate in chunks, write the Parquet file) without Dask. The
engine's overhead per run is (1-worker time - loop time) / runs; the scaling is the
1-worker time over the 2-worker time. As the machine is shared, the 1-worker overhead is
also given as its wall time minus the compute time the workers measured (manifest
``seconds``), which other load affects less. A second batch over the same output (every run
unchanged, so only checksums are computed) is timed too.

Run: ``python benchmarks/bench_batch.py [--runs 200] [--samples 10000]``.
"""

from __future__ import annotations

import argparse
import importlib.util
import shutil
import tempfile
import time
from pathlib import Path

from _machine import describe_machine
from pinframes.batch import run_batch
from pinframes.batch._engine import local_cluster
from pinframes.batch._options import BatchOptions
from pinframes.batch._partition import clear_staging
from pinframes.batch._runs import find_runs
from pinframes.batch._task import RunTask, process_run

ROOT = Path(__file__).resolve().parents[1]
FRAME, RELATIVE_TO = "torch_tcp", "workpiece"
TARGET_RUNS, TARGET_CORES = 100_000, 64


def make_campaign(out: Path, runs: int, samples: int) -> list[Path]:
    spec = importlib.util.spec_from_file_location(
        "make_campaign", ROOT / "models" / "welding_cell" / "make_campaign.py")
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module.make_campaign(out, runs, samples)


def plain_loop(scenes: list[Path], out: Path) -> float:
    """Seconds for the per-run work of a batch, one run after the other, no Dask (after
    one run as warm-up, as the workers get)."""
    clear_staging(out)
    options = BatchOptions.create(FRAME, RELATIVE_TO)
    digest = options.digest()
    process_run(RunTask(find_runs(scenes[:1])[0], out, options, digest, None))
    start = time.perf_counter()
    for run in find_runs(scenes):
        result = process_run(RunTask(run, out, options, digest, None))
        assert result.record["status"] == "ok", result.record
    return time.perf_counter() - start


def on_cluster(scenes: list[Path], out: Path, workers: int
               ) -> tuple[float, float, float, float]:
    """(cluster start, batch, unchanged re-run, in-worker compute) seconds with ``workers``
    processes."""
    start = time.perf_counter()
    with local_cluster(workers) as cluster:
        started = time.perf_counter() - start
        address = cluster.scheduler_address
        run_batch(scenes[:workers], out / "warm-up", FRAME, relative_to=RELATIVE_TO,
                  scheduler=address)  # imports pinframes, pinocchio, pyarrow on each worker
        start = time.perf_counter()
        summary = run_batch(scenes, out / "poses", FRAME, relative_to=RELATIVE_TO,
                            scheduler=address)
        batch = time.perf_counter() - start
        assert not summary.bad and len(summary.computed) == len(scenes), summary.bad
        compute = sum(record["seconds"] for record in summary.records)
        start = time.perf_counter()
        summary = run_batch(scenes, out / "poses", FRAME, relative_to=RELATIVE_TO,
                            scheduler=address)
        rerun = time.perf_counter() - start
        assert len(summary.skipped) == len(scenes)
    return started, batch, rerun, compute


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--runs", type=int, default=200, help="runs in the campaign")
    parser.add_argument("--samples", type=int, default=10_000, help="joint samples per run")
    args = parser.parse_args()
    print(describe_machine())
    folder = Path(tempfile.mkdtemp(prefix="bench_batch_"))
    try:
        scenes = make_campaign(folder / "campaign", args.runs, args.samples)
        print(f"campaign: {args.runs} runs x {args.samples} joint samples "
              f"({FRAME} in {RELATIVE_TO})\n")
        loop = plain_loop(scenes, folder / "loop")
        one = on_cluster(scenes, folder / "one", 1)
        two = on_cluster(scenes, folder / "two", 2)
        report(args.runs, loop, one, two)
    finally:
        shutil.rmtree(folder, ignore_errors=True)


def report(runs: int, loop: float, one: tuple[float, float, float, float],
           two: tuple[float, float, float, float]) -> None:
    print(f"{'engine':<22}{'start s':>9}{'batch s':>9}{'runs/s':>9}{'ms/run':>9}"
          f"{'re-run s':>10}{'vs loop':>9}")
    print(f"{'plain loop, 1 process':<22}{'-':>9}{loop:>9.2f}{runs / loop:>9.1f}"
          f"{1000 * loop / runs:>9.1f}{'-':>10}{1.0:>9.2f}")
    for name, (start, batch, rerun, _) in (("dask, 1 worker", one), ("dask, 2 workers", two)):
        print(f"{name:<22}{start:>9.2f}{batch:>9.2f}{runs / batch:>9.1f}"
              f"{1000 * batch / runs:>9.1f}{rerun:>10.2f}{batch / loop:>9.2f}")
    compute = loop / runs
    overhead = (one[1] - loop) / runs
    scaling = one[1] / two[1]
    print(f"\ncompute per run (loop): {1000 * compute:.1f} ms; engine overhead per run "
          f"(1 worker - loop): {1000 * overhead:.1f} ms = {100 * overhead / compute:.1f} % "
          "of the compute")
    in_worker = (one[1] - one[3]) / runs
    print(f"1 worker: wall - in-worker compute = {1000 * in_worker:.1f} ms per run = "
          f"{100 * in_worker / (one[3] / runs):.1f} % of its in-worker compute "
          f"({1000 * one[3] / runs:.1f} ms per run)")
    print(f"scaling 1 -> 2 workers: {scaling:.2f}x (goal >= 1.7x; efficiency "
          f"{100 * scaling / 2:.0f} %)")
    per_core = one[1] / runs / min(1.0, scaling / 2)
    ideal = one[1] / runs  # 1 worker: compute + engine overhead per run
    print(f"projection, {TARGET_RUNS} runs on {TARGET_CORES} cores: "
          f"{TARGET_RUNS * per_core / TARGET_CORES / 60:.1f} min at the 2-worker efficiency "
          f"measured here ({1000 * per_core:.1f} ms per run per core); "
          f"{TARGET_RUNS * ideal / TARGET_CORES / 60:.1f} min if each core gives a worker the "
          f"1-worker time per run ({1000 * ideal:.1f} ms); plus one cluster start")

if __name__ == "__main__":
    main()
