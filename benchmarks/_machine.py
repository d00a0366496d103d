"""What every benchmark prints first, and how it times: the machine, medians of repeats, and
the two thread settings every case runs in (each in a child process of its own).

- ``1 thread``: ``OMP_NUM_THREADS=OPENBLAS_NUM_THREADS=1`` in the child's environment;
- ``busy``: numpy's default threads while a spinning process keeps one core busy, as on a
  machine where a second job runs.
"""

from __future__ import annotations

import argparse
import json
import os
import platform
import statistics
import subprocess
import sys
import time
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from importlib import metadata
from pathlib import Path

import numpy as np

THREAD_VARIABLES = ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS")
SETTINGS = ("1 thread", "busy")


def describe_machine() -> str:
    """One paragraph naming the CPU, core count, Python and the library versions."""
    cpu = platform.processor() or "unknown CPU"
    try:
        with open("/proc/cpuinfo", encoding="utf-8") as handle:
            for line in handle:
                if line.startswith("model name"):
                    cpu = line.split(":", 1)[1].strip()
                    break
    except OSError:
        pass
    versions = ", ".join(f"{name} {_version(name)}" for name in ("pin", "numpy", "pinframes"))
    try:
        blas = np.show_config(mode="dicts")["Build Dependencies"]["blas"]["name"]
    except (KeyError, TypeError):
        blas = "unknown BLAS"
    load = ", ".join(f"{value:.1f}" for value in os.getloadavg())
    return (f"machine: {cpu}, {os.cpu_count()} cores, {platform.system()} "
            f"{platform.release()}, Python {platform.python_version()}; {versions}; numpy "
            f"BLAS {blas}; load average {load} (a shared machine: read ratios, not times)")


def median_time(call: Callable[[], object], repeats: int) -> float:
    """Median wall time of ``call`` in seconds over ``repeats`` runs (after one warm-up)."""
    return statistics.median(repeated_times(call, repeats))


def repeated_times(call: Callable[[], object], repeats: int) -> list[float]:
    """Wall times of ``repeats`` runs of ``call`` in seconds, after one warm-up run."""
    call()
    samples = []
    for _ in range(repeats):
        start = time.perf_counter()
        call()
        samples.append(time.perf_counter() - start)
    return samples


@contextmanager
def busy_core() -> Iterator[None]:
    """Keep one core busy with a spinning child process while the block runs."""
    spinner = subprocess.Popen([sys.executable, "-c", "while True: pass"])
    try:
        time.sleep(0.3)
        yield
    finally:
        spinner.kill()
        spinner.wait()


def quick_or_child(description: str, child: Callable[[bool], None],
                   quick_help: str = "fewer repeats") -> bool | None:
    """Parse a benchmark's ``--quick`` and the hidden ``--child SETTING`` that
    :func:`run_in_settings` passes: in a child, run ``child(quick)`` and return None; in the
    parent, return whether ``--quick`` was given."""
    parser = argparse.ArgumentParser(description=description)
    parser.add_argument("--quick", action="store_true", help=quick_help)
    parser.add_argument("--child", help=argparse.SUPPRESS)
    args = parser.parse_args()
    if args.child:
        child(args.quick)
        return None
    return bool(args.quick)


def run_in_settings(script: str, arguments: list[str]) -> dict[str, list[dict]]:
    """Run ``script --child SETTING arguments`` in both settings; each child prints its rows
    as one JSON list on its last line of output."""
    results = {}
    for setting in SETTINGS:
        environment = {k: v for k, v in os.environ.items() if k not in THREAD_VARIABLES}
        if setting == "1 thread":
            environment |= dict.fromkeys(THREAD_VARIABLES, "1")
        command = [sys.executable, str(Path(script).resolve()), "--child", setting, *arguments]
        if setting == "busy":
            with busy_core():
                output = subprocess.run(command, env=environment, check=True,
                                        stdout=subprocess.PIPE, text=True).stdout
        else:
            output = subprocess.run(command, env=environment, check=True,
                                    stdout=subprocess.PIPE, text=True).stdout
        results[setting] = json.loads(output.strip().splitlines()[-1])
    return results


def row(case: str, method: str, seconds: float, error: float | None = None,
        note: str = "", ratio: float | None = None) -> dict:
    """One measurement: ``error`` is the largest difference to the numpy reference, ``ratio``
    the median over rounds of time / reference time (None: computed from the medians)."""
    return {"case": case, "method": method, "seconds": seconds, "error": error, "note": note,
            "ratio": ratio}


def interleaved(case: str, calls: dict[str, Callable[[], object]], repeats: int,
                reference: str = "numpy reference") -> list[dict]:
    """Rows for ``calls`` timed in alternation, each round running every call once, so a
    burst of load on a shared machine hits all of them; ratios are medians of per-round
    ratios to ``reference``."""
    for call in calls.values():
        call()
    samples: dict[str, list[float]] = {name: [] for name in calls}
    for _ in range(repeats):
        for name, call in calls.items():
            start = time.perf_counter()
            call()
            samples[name].append(time.perf_counter() - start)
    base = samples[reference]
    return [row(case, name, statistics.median(times), ratio=statistics.median(
        t / b for t, b in zip(times, base, strict=True))) for name, times in samples.items()]


def interleaved_per_call(case: str, calls: dict[str, Callable[[], object]], rounds: int,
                         in_a_row: int = 50, reference: str = "numpy reference") -> list[dict]:
    """:func:`interleaved` for calls of a few microseconds: each measurement makes a call
    ``in_a_row`` times in a row, and the rows give the time per call. Timed one call at a
    time, the one-query cases of bench_queries ran 2-3x slower in the one-thread child than
    beside the busy process, pinframes and reference alike (a call that short finds the
    process cold after every switch; likely the scheduler moving it between idle cores);
    in a row, both settings agree."""
    def repeated(call: Callable[[], object]) -> Callable[[], object]:
        def calls_in_a_row() -> None:
            for _ in range(in_a_row):
                call()
        return calls_in_a_row

    measured = interleaved(case, {name: repeated(call) for name, call in calls.items()},
                           rounds, reference)
    return [{**entry, "seconds": entry["seconds"] / in_a_row} for entry in measured]


def print_table(results: dict[str, list[dict]], reference: str = "numpy reference") -> None:
    """Per case and method: median time and ratio to ``reference`` in both settings."""
    first = results[SETTINGS[0]]
    header = "".join(f" {setting + ' time':>15} {'ratio':>6}" for setting in SETTINGS)
    print(f"\n{'case':<44} {'method':<22}{header} {'max|diff|':>9}")
    for index, entry in enumerate(first):
        cells = ""
        for setting in SETTINGS:
            measured = results[setting][index]
            ratio = measured["ratio"]
            if ratio is None:
                ratio = measured["seconds"] / next(
                    r["seconds"] for r in results[setting]
                    if r["case"] == measured["case"] and r["method"] == reference)
            cells += f" {format_seconds(measured['seconds']):>15} {ratio:>6.2f}"
        error = "" if entry["error"] is None else f"{entry['error']:.1e}"
        print(f"{entry['case']:<44} {entry['method']:<22}{cells} {error:>9} {entry['note']}")
    print(f"\nratio = time / {reference} time in the same process and setting (below 1 is "
          "faster), median over rounds that run every method once; times: medians;\n"
          "1 thread: OMP_NUM_THREADS=OPENBLAS_NUM_THREADS=1; busy: default threads beside "
          "a spinning process")


def format_seconds(seconds: float) -> str:
    if seconds < 1e-3:
        return f"{seconds * 1e6:.1f} us"
    if seconds < 1:
        return f"{seconds * 1e3:.2f} ms"
    return f"{seconds:.2f} s"


def _version(name: str) -> str:
    try:
        return metadata.version(name)
    except metadata.PackageNotFoundError:
        return "(source tree)"
