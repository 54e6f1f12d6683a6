"""Splitting work over threads for kernels that release the GIL (``nogil`` numba, ``_cnoise``).

The numba kernels of the evaluation path (compositing, fBm, Worley, Bricks, paths, relief) are
serial, ``nogil`` and take a range of rows; :func:`parallel_rows` runs them on row ranges from
several threads. ``prange`` is avoided there: it cannot pass tuples of arrays into its parallel
region, and a parallel kernel takes far longer to compile (docs/performance.md, "Cold start").
The thread count follows ``numba.get_num_threads()`` (``NUMBA_NUM_THREADS``), so
``numba.set_num_threads(1)`` also makes these kernels serial. :func:`run_split` is the runner
underneath, also used by the C fBm; importing this module imports neither numba nor an
executor (cold-start path).

The helper threads persist: each waits on a plain lock for its next slice, so a split costs
two lock hand-offs instead of starting a thread (starting one costs about 80 us, which showed
on 256x256 renders: five splits per evaluation). A split made while another split is running
(from another thread: the sweep's shading threads) starts threads of its own instead of waiting.
After ``fork`` the child forgets the parent's helpers (they do not exist there) and makes new
ones on demand.
"""

from __future__ import annotations

import _thread
import os
from collections.abc import Callable

#: Below this many texels per thread the work runs on the calling thread only.
MIN_TEXELS_PER_THREAD = 16384

Work = Callable[[int, int], None]


class _Helper:
    """A thread that runs one slice at a time: ``start`` hands it a slice, ``wait`` joins."""

    def __init__(self) -> None:
        self._go = _thread.allocate_lock()
        self._go.acquire()
        self._done = _thread.allocate_lock()
        self._done.acquire()
        self._task: tuple[Work, int, int] | None = None
        self._error: BaseException | None = None
        _thread.start_new_thread(self._loop, ())

    def _loop(self) -> None:
        while True:
            self._go.acquire()
            work, start, stop = self._task  # type: ignore[misc]
            try:
                work(start, stop)
            except BaseException as exc:  # re-raised on the calling thread
                self._error = exc
            self._task = None
            self._done.release()

    def start(self, work: Work, start: int, stop: int) -> None:
        self._error = None
        self._task = (work, start, stop)
        self._go.release()

    def wait(self) -> BaseException | None:
        self._done.acquire()
        return self._error


class _Pool:
    """The persistent helpers, lent to one split at a time."""

    def __init__(self) -> None:
        self.helpers: list[_Helper] = []
        self.busy = _thread.allocate_lock()

    def borrow(self, n: int) -> list[_Helper] | None:
        """``n`` helpers (made on first use), or None while another split holds them."""
        if not self.busy.acquire(False):
            return None
        while len(self.helpers) < n:
            self.helpers.append(_Helper())
        return self.helpers[:n]


_pool = [_Pool()]


def _forget_after_fork() -> None:
    _pool[0] = _Pool()


if hasattr(os, "register_at_fork"):
    os.register_at_fork(after_in_child=_forget_after_fork)


def run_split(parts: int, work: Work, total: int) -> None:
    """Run ``work(start, stop)`` on ``parts`` contiguous slices of ``range(total)``, the first
    on the calling thread and each other one on a helper thread; the first error is re-raised on
    the calling thread."""
    bounds = [total * k // parts for k in range(parts + 1)]
    if parts <= 1:
        work(bounds[0], bounds[1])
        return
    pool = _pool[0]
    helpers = pool.borrow(parts - 1)
    if helpers is None:
        _run_on_new_threads(bounds, work)
        return
    try:
        for k, helper in enumerate(helpers, start=1):
            helper.start(work, bounds[k], bounds[k + 1])
        first: BaseException | None = None
        try:
            work(bounds[0], bounds[1])
        except BaseException as exc:
            first = exc
        errors = [helper.wait() for helper in helpers]
    finally:
        pool.busy.release()
    error = first or next((e for e in errors if e is not None), None)
    if error is not None:
        raise error


def _run_on_new_threads(bounds: list[int], work: Work) -> None:
    """:func:`run_split` on threads of its own (the helpers are lent to another split)."""
    errors: list[BaseException] = []
    locks = []

    def run(k: int, lock: _thread.LockType | None) -> None:
        try:
            work(bounds[k], bounds[k + 1])
        except BaseException as exc:  # re-raised on the calling thread
            errors.append(exc)
        finally:
            if lock is not None:
                lock.release()

    for k in range(1, len(bounds) - 1):
        lock = _thread.allocate_lock()
        lock.acquire()
        locks.append(lock)
        _thread.start_new_thread(run, (k, lock))
    run(0, None)
    for lock in locks:
        lock.acquire()
    if errors:
        raise errors[0]


def parallel_rows(rows: int, width: int, work: Callable[[int, int], None]) -> None:
    """Call ``work(first, last)`` on disjoint row ranges covering ``range(rows)``, in parallel."""
    import numba

    threads = min(numba.get_num_threads(), max(1, rows * width // MIN_TEXELS_PER_THREAD), rows)
    run_split(max(threads, 1), work, rows)
