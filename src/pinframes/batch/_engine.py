"""The Dask engine: a local cluster of worker processes, or an existing scheduler."""

from __future__ import annotations

import contextlib
import importlib.util
import os
from collections.abc import Iterator
from typing import TextIO

import dask.config
from distributed import Client, LocalCluster
from distributed.security import Security

from ..errors import UnsupportedFeatureError

__all__ = ["SINGLE_THREAD_ENV", "cluster_security", "dask_client", "local_cluster",
           "worker_spawn_environment"]

SINGLE_THREAD_ENV = {"OMP_NUM_THREADS": "1", "OPENBLAS_NUM_THREADS": "1",
                     "MKL_NUM_THREADS": "1"}
"""Set in every local worker: one process per core, so BLAS must not start threads too."""

_GLIBC_MALLOC_TUNING = "MALLOC_TRIM_THRESHOLD_"
"""Dask sets it in the workers it spawns to give memory back to the system sooner. Any value
turns off glibc's adaptive mmap threshold, so every numpy temporary of a chunk (hundreds of
kB) is mapped and unmapped anew: measured 1.4x the compute per run of the same work in one
process (benchmarks/bench_batch.py). A run's memory is bounded by its chunks, so the default
allocator behaviour is kept."""


def worker_spawn_environment() -> dict[str, object]:
    """Dask's environment for new worker processes, without the malloc tuning above."""
    environment = dict(dask.config.get("distributed.nanny.pre-spawn-environ"))
    environment.pop(_GLIBC_MALLOC_TUNING, None)
    return environment


@contextlib.contextmanager
def dask_client(scheduler: str | None = None, workers: int | None = None,
                log: TextIO | None = None) -> Iterator[Client]:
    """A client of the scheduler at ``scheduler``, else of a new local cluster.

    The local cluster has ``workers`` worker processes (default: one per core), one thread
    each, on 127.0.0.1 only; its dashboard (needs bokeh) on a free port. Where the dashboard
    is goes to ``log``, when there is one.
    """
    if scheduler is not None:
        with Client(scheduler) as client:
            _say_dashboard(_remote_dashboard(client), log)
            yield client
        return
    dashboard = importlib.util.find_spec("bokeh") is not None
    with local_cluster(workers) as cluster, Client(cluster) as client:
        _say_dashboard(cluster.dashboard_link if dashboard else None, log)
        yield client


@contextlib.contextmanager
def local_cluster(workers: int | None = None) -> Iterator[LocalCluster]:
    """A local cluster of ``workers`` single-threaded worker processes (default: one per
    core) on 127.0.0.1, BLAS limited to one thread and glibc's malloc left as it is in them;
    the dashboard on a free port.

    The scheduler, nanny and workers speak TLS and require a certificate of this cluster's
    own authority, made anew in memory for it (:meth:`Security.temporary`): on a machine
    shared with other users, a process that only reaches 127.0.0.1 can neither connect nor
    run code in a worker. ``Client(cluster)`` takes the cluster's certificate.
    """
    spawn = {"distributed.nanny.pre-spawn-environ": worker_spawn_environment()}
    with dask.config.set(spawn), _unset_in_this_process(_GLIBC_MALLOC_TUNING), LocalCluster(
            n_workers=workers or os.cpu_count() or 1, threads_per_worker=1, processes=True,
            host="127.0.0.1", protocol="tls://", security=cluster_security(),
            dashboard_address="127.0.0.1:0", env=SINGLE_THREAD_ENV) as cluster:
        yield cluster


def cluster_security() -> Security:
    """TLS with a new certificate authority and keys, held in memory only (needs the
    ``cryptography`` package, in the ``batch`` extra)."""
    try:
        return Security.temporary()
    except ImportError as exc:
        raise UnsupportedFeatureError("the local cluster's TLS keys need the cryptography "
                                      f"package (pip install 'pinframes[batch]'): {exc}"
                                      ) from None


@contextlib.contextmanager
def _unset_in_this_process(name: str) -> Iterator[None]:
    """``name`` out of this process's environment while the cluster lives, then back.

    Dask's nanny copies its spawn environment into ``os.environ`` of the process that starts
    it and never takes it back, so after any earlier cluster in this process the variable is
    here, and new worker processes would inherit it.
    """
    saved = os.environ.pop(name, None)
    try:
        yield
    finally:
        if saved is not None:
            os.environ[name] = saved


def _remote_dashboard(client: Client) -> str | None:
    """The dashboard of a scheduler started elsewhere, None if it serves none."""
    try:
        return client.dashboard_link
    except KeyError:
        return None


def _say_dashboard(link: str | None, log: TextIO | None) -> None:
    """One line with the dashboard's address, when there is a dashboard."""
    if log is not None and link:
        print(f"pinframes: dask dashboard at {link}", file=log)
