"""The persistent split runner (engine.kernels.threads): slices, errors, concurrency, fork."""

from __future__ import annotations

import os
import threading

import numpy as np
import pytest

from matloom.engine.kernels import threads


@pytest.mark.parametrize("parts", [1, 2, 3, 5])
def test_every_index_runs_exactly_once(parts):
    hits = np.zeros(1000, dtype=np.int64)

    def work(a: int, b: int) -> None:
        hits[a:b] += 1

    for _ in range(20):  # the helpers are reused
        threads.run_split(parts, work, 1000)
    assert (hits == 20).all()


def test_errors_reach_the_caller_and_the_pool_recovers():
    def bad(a: int, b: int) -> None:
        if a > 0:
            raise ValueError("helper failed")

    with pytest.raises(ValueError, match="helper failed"):
        threads.run_split(2, bad, 10)
    seen = []
    threads.run_split(2, lambda a, b: seen.append((a, b)), 10)
    assert sorted(seen) == [(0, 5), (5, 10)]


def test_concurrent_and_nested_splits_do_not_wait_for_each_other():
    """A split made while the helpers are lent (another thread's split, or a split inside a
    split) runs on threads of its own."""
    hits = np.zeros(64, dtype=np.int64)
    barrier = threading.Barrier(3)
    lock = threading.Lock()

    def inner(a: int, b: int) -> None:
        with lock:
            hits[a:b] += 1

    def outer(a: int, b: int) -> None:
        threads.run_split(2, inner, 64)

    def caller() -> None:
        barrier.wait()
        for _ in range(10):
            threads.run_split(2, outer, 4)

    workers = [threading.Thread(target=caller) for _ in range(3)]
    for w in workers:
        w.start()
    for w in workers:
        w.join()
    assert (hits == 3 * 10 * 2).all()  # 3 callers x 10 splits x 2 outer slices


@pytest.mark.skipif(not hasattr(os, "fork"), reason="needs os.fork (POSIX)")
def test_a_forked_child_makes_its_own_helpers():
    threads.run_split(2, lambda a, b: None, 2)  # the parent has helpers now
    pid = os.fork()
    if pid == 0:  # the child: the parent's helper threads do not exist here
        hits = np.zeros(10)

        def work(a: int, b: int) -> None:
            hits[a:b] += 1

        threads.run_split(2, work, 10)
        os._exit(0 if (hits == 1).all() else 1)
    _, status = os.waitpid(pid, 0)
    assert os.WEXITSTATUS(status) == 0
