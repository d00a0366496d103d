"""What every benchmark prints first, and how it times: the machine, medians of repeats."""

from __future__ import annotations

import os
import platform
import statistics
import time
from collections.abc import Callable
from importlib import metadata


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
    return (f"machine: {cpu}, {os.cpu_count()} cores, {platform.system()} "
            f"{platform.release()}, Python {platform.python_version()}; {versions}")


def median_time(call: Callable[[], object], repeats: int) -> float:
    """Median wall time of ``call`` in seconds over ``repeats`` runs (after one warm-up)."""
    call()
    samples = []
    for _ in range(repeats):
        start = time.perf_counter()
        call()
        samples.append(time.perf_counter() - start)
    return statistics.median(samples)


def _version(name: str) -> str:
    try:
        return metadata.version(name)
    except metadata.PackageNotFoundError:
        return "(source tree)"
