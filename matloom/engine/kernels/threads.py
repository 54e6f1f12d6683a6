"""Splitting work over threads for kernels that release the GIL (``nogil`` numba, ``_cnoise``).

The numba kernels of the evaluation path (compositing, fBm, Worley, Bricks, paths, relief) are
serial, ``nogil`` and take a range of rows; :func:`parallel_rows` runs them on row ranges from
several threads. ``prange`` is avoided there: it cannot pass tuples of arrays into its parallel
region, and a parallel kernel takes far longer to compile (docs/performance.md, "Cold start").
The thread count follows ``numba.get_num_threads()`` (``NUMBA_NUM_THREADS``), so
``numba.set_num_threads(1)`` also makes these kernels serial. :func:`run_split` is the runner
underneath, also used by the C fBm; importing this module imports neither numba nor an
executor (cold-start path).
"""

from __future__ import annotations

import threading
from collections.abc import Callable

#: Below this many texels per thread the work runs on the calling thread only.
MIN_TEXELS_PER_THREAD = 16384


def run_split(parts: int, work: Callable[[int, int], None], total: int) -> None:
    """Run ``work(start, stop)`` on ``parts`` contiguous slices of ``range(total)``, each but
    the first on its own thread; the first error is re-raised on the calling thread."""
    bounds = [total * k // parts for k in range(parts + 1)]
    errors: list[BaseException] = []

    def run(k: int) -> None:
        try:
            work(bounds[k], bounds[k + 1])
        except BaseException as exc:  # re-raised on the calling thread
            errors.append(exc)

    threads = [threading.Thread(target=run, args=(k,)) for k in range(1, parts)]
    for thread in threads:
        thread.start()
    run(0)
    for thread in threads:
        thread.join()
    if errors:
        raise errors[0]


def parallel_rows(rows: int, width: int, work: Callable[[int, int], None]) -> None:
    """Call ``work(first, last)`` on disjoint row ranges covering ``range(rows)``, in parallel."""
    import numba

    threads = min(numba.get_num_threads(), max(1, rows * width // MIN_TEXELS_PER_THREAD), rows)
    run_split(max(threads, 1), work, rows)
