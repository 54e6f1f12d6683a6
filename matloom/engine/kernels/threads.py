"""A small process-wide thread pool for ``nogil`` numba kernels that take tuples of arrays.

numba's ``prange`` cannot pass tuples of arrays into its parallel region, so such kernels are
serial and release the GIL; :func:`parallel_rows` runs them on row ranges from several threads.
The thread count follows ``numba.get_num_threads()`` (``NUMBA_NUM_THREADS``), so
``numba.set_num_threads(1)`` also makes these kernels serial.
"""

from __future__ import annotations

import threading
from collections.abc import Callable
from concurrent.futures import ThreadPoolExecutor

import numba

#: Below this many texels per thread the work runs on the calling thread only.
MIN_TEXELS_PER_THREAD = 16384

_POOL: list[ThreadPoolExecutor] = []
_LOCK = threading.Lock()


def _pool(workers: int) -> ThreadPoolExecutor:
    with _LOCK:
        if not _POOL or _POOL[0]._max_workers < workers:  # noqa: SLF001 - size check only
            if _POOL:
                _POOL.pop().shutdown(wait=False)
            _POOL.append(ThreadPoolExecutor(workers, thread_name_prefix="matloom-rows"))
        return _POOL[0]


def parallel_rows(rows: int, width: int, work: Callable[[int, int], None]) -> None:
    """Call ``work(first, last)`` on disjoint row ranges covering ``range(rows)``, in parallel."""
    threads = min(numba.get_num_threads(), max(1, rows * width // MIN_TEXELS_PER_THREAD), rows)
    if threads <= 1:
        work(0, rows)
        return
    bounds = [rows * k // threads for k in range(threads + 1)]
    pool = _pool(threads - 1)
    futures = [pool.submit(work, bounds[k], bounds[k + 1]) for k in range(1, threads)]
    work(bounds[0], bounds[1])
    for future in futures:
        future.result()
