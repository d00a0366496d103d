"""Several threads on one tree (as Dask's threaded workers do): right answers, no bare
errors, and no process-wide setting left changed.

A tiny switch interval makes the interpreter change threads every few bytecodes, so races
that would otherwise show once in thousands of calls show in every run.
"""

from __future__ import annotations

import sys
import threading
from collections.abc import Callable, Iterator

import numpy as np
import pytest

import pinframes.kinematics._memo as memo
from pinframes import FrameTree, Pose, read_asdf, write_asdf

# many threads, seconds each: in the slow set (CI runs it)
pytestmark = pytest.mark.slow

THREADS = 8


@pytest.fixture
def busy_switching() -> Iterator[None]:
    interval = sys.getswitchinterval()
    sys.setswitchinterval(1e-6)
    try:
        yield
    finally:
        sys.setswitchinterval(interval)


def run_in_threads(work: Callable[[int], None]) -> list[BaseException]:
    errors: list[BaseException] = []

    def guarded(seed: int) -> None:
        try:
            work(seed)
        except BaseException as exc:  # collected, so the test reports each failure
            errors.append(exc)

    threads = [threading.Thread(target=guarded, args=(seed,)) for seed in range(THREADS)]
    for thread in threads:
        thread.start()
    for thread in threads:
        thread.join()
    return errors


def test_queries_from_eight_threads_while_the_cache_evicts(busy_switching, monkeypatch):
    # a cache of 4 entries for 400 pairs: nearly every query stores and evicts
    monkeypatch.setattr(memo, "_LIMIT", 4)
    tree = FrameTree("w")
    for index in range(20):
        tree.add(f"f{index}", "w", Pose([float(index), 0.0, 0.0]))
    tree.add("m", "f3", Pose([[0.0, 0.0, 0.0], [0.0, 2.0, 0.0]], times=[0.0, 2.0]))

    def work(seed: int) -> None:
        rng = np.random.default_rng(seed)
        for _ in range(500):
            a, b = (int(v) for v in rng.integers(0, 20, 2))
            # f_a in f_b: both unrotated, so the x offsets subtract
            np.testing.assert_allclose(tree.pose(f"f{a}", f"f{b}").translation,
                                       [a - b, 0.0, 0.0])
            np.testing.assert_allclose(tree.pose("m", f"f{b}", times=[1.0]).translation,
                                       [[3.0 - b, 1.0, 0.0]])

    errors = run_in_threads(work)
    assert not errors, [repr(error) for error in errors[:3]]
    assert len(tree._frozen().memo._entries) <= 4 + THREADS


def test_concurrent_asdf_reads_and_writes_leave_the_recursion_limit_alone(
        busy_switching, tmp_path):
    # a chain 60 frames deep in the nested 0.1.0 format makes every call raise the limit
    tree = FrameTree("base")
    parent = "base"
    for index in range(60):
        tree.add(f"c{index}", parent, Pose([0.001, 0.0, 0.0]))
        parent = f"c{index}"
    source = tmp_path / "chain.asdf"
    write_asdf(tree, source, schema="0.1.0")
    limit = sys.getrecursionlimit()

    def work(seed: int) -> None:
        for round_ in range(1):
            copy = read_asdf(source)
            np.testing.assert_allclose(copy.pose("c59", "base").translation, [0.06, 0.0, 0.0],
                                       atol=1e-12)
            write_asdf(copy, tmp_path / f"out-{seed}-{round_}.asdf", schema="0.1.0")

    errors = run_in_threads(work)
    assert not errors, [repr(error) for error in errors[:3]]
    assert sys.getrecursionlimit() == limit
