"""The Dask engine: a local cluster of worker processes, or an existing scheduler."""

from __future__ import annotations

import contextlib
import importlib.util
import os
from collections.abc import Iterator
from typing import TextIO

from distributed import Client, LocalCluster

__all__ = ["SINGLE_THREAD_ENV", "dask_client"]

SINGLE_THREAD_ENV = {"OMP_NUM_THREADS": "1", "OPENBLAS_NUM_THREADS": "1",
                     "MKL_NUM_THREADS": "1"}
"""Set in every local worker: one process per core, so BLAS must not start threads too."""


@contextlib.contextmanager
def dask_client(scheduler: str | None = None, workers: int | None = None,
                log: TextIO | None = None) -> Iterator[Client]:
    """A client of the scheduler at ``scheduler``, else of a new local cluster.

    The local cluster has ``workers`` worker processes (default: one per core), one thread
    each, on 127.0.0.1 only; its dashboard (needs bokeh) on a free port. Where the dashboard
    is goes to ``log``.
    """
    if scheduler is not None:
        with Client(scheduler) as client:
            _say_dashboard(_remote_dashboard(client), log)
            yield client
        return
    dashboard = importlib.util.find_spec("bokeh") is not None
    with LocalCluster(n_workers=workers or os.cpu_count() or 1, threads_per_worker=1,
                      processes=True, host="127.0.0.1",
                      dashboard_address="127.0.0.1:0",
                      env=SINGLE_THREAD_ENV) as cluster, Client(cluster) as client:
        _say_dashboard(cluster.dashboard_link if dashboard else None, log)
        yield client


def _remote_dashboard(client: Client) -> str | None:
    """The dashboard of a scheduler started elsewhere, None if it serves none."""
    try:
        return client.dashboard_link
    except KeyError:
        return None


def _say_dashboard(link: str | None, log: TextIO | None) -> None:
    if log is None:
        return
    print(f"pinframes: dask dashboard at {link}" if link else
          "pinframes: dask dashboard unavailable (it needs bokeh: pip install bokeh)",
          file=log)
