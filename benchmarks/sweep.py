"""Benchmark: seed sweeps (render only, no scorer). Prints candidates/second and memory.

Run: PYTHONPATH=. .venv/bin/python benchmarks/sweep.py [--variants 1000] [--size 256]
     [--jobs 2] [--programs tile brick reptile_scales terrain_thresholds paving_manhattan]

For each program: wall and process CPU time of ``run_sweep(text, variants=K, size=S, jobs=J)``
(original + K variants), candidates per second, the summed wall time of the seed-batched noise
kernels (they run on the preparation thread, overlapped with the shading of the previous chunk),
the peak memory traced by tracemalloc during a second sweep of two chunks, and the process's
maximum resident set size. A small warm-up sweep first loads the compiled kernels.
"""

from __future__ import annotations

import argparse
import dataclasses
import os
import resource
import sys
import time
import tracemalloc
from pathlib import Path
from typing import Any

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

import matloom.engine.backends as backends  # noqa: E402
from matloom.engine.evaluate import prepare  # noqa: E402
from matloom.engine.schedules import sweep  # noqa: E402
from matloom.render.preview import ShadeParams  # noqa: E402

PARITY = ROOT / "tests" / "data" / "parity"
MIB = 1024 * 1024
PROGRAMS = ["tile", "brick", "reptile_scales", "terrain_thresholds", "paving_manhattan"]


def install_noise_clock(clock: list[float]) -> None:
    """Make the sweep's numba backend add the wall time of its seed-batched noise to clock[0]
    (CPU time cannot be told apart: the shading threads run at the same time)."""
    base = backends.get_backend("numba")

    def wrap(kernel: Any) -> Any:
        def run(*args: Any, **kwargs: Any) -> Any:
            start = time.perf_counter()
            try:
                return kernel(*args, **kwargs)
            finally:
                clock[0] += time.perf_counter() - start

        return run

    timed = dataclasses.replace(
        base,
        fbm_seed_batch=wrap(base.fbm_seed_batch),
        worley_seed_batch=wrap(base.worley_seed_batch),
    )
    backends.get_backend = lambda name="auto", **_: timed if name in ("numba", "auto") else base


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--variants", type=int, default=1000)
    parser.add_argument("--size", type=int, default=256)
    parser.add_argument("--jobs", type=int, default=2)
    parser.add_argument("--programs", nargs="+", default=PROGRAMS)
    args = parser.parse_args()
    clock = [0.0]
    install_noise_clock(clock)
    shading = ShadeParams.of()
    print(f"load average at start: {os.getloadavg()}")
    print(
        f"{'program':20} {'cands':>6} {'wall s':>7} {'cpu s':>7} {'cand/s':>7} "
        f"{'ms cpu/cand':>11} {'noise s':>7} {'chunk':>5} {'peak MiB':>9}"
    )
    for name in args.programs:
        text = (PARITY / f"{name}.mat").read_text()
        # warm-up
        sweep.run_sweep(text, variants=3, shading=shading, size=args.size, jobs=args.jobs)
        clock[0] = 0.0
        wall0, cpu0 = time.perf_counter(), time.process_time()
        result = sweep.run_sweep(
            text, variants=args.variants, shading=shading, size=args.size, jobs=args.jobs, keep=1
        )
        wall, cpu = time.perf_counter() - wall0, time.process_time() - cpu0
        noise = clock[0]
        chunk = sweep.chunk_size(prepare(text), args.size)
        tracemalloc.start()
        sweep.run_sweep(
            text,
            variants=min(args.variants, 2 * chunk),
            shading=shading,
            size=args.size,
            jobs=args.jobs,
            keep=1,
        )
        peak = tracemalloc.get_traced_memory()[1]
        tracemalloc.stop()
        n = result.n_candidates
        print(
            f"{name:20} {n:6d} {wall:7.2f} {cpu:7.2f} {n / wall:7.1f} {cpu / n * 1e3:11.2f} "
            f"{noise:7.2f} {chunk:5d} {peak / MIB:9.1f}",
            flush=True,
        )
    rss = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024
    print(f"max resident set size of this process: {rss:.0f} MiB")
    print(f"load average at end: {os.getloadavg()}")


if __name__ == "__main__":
    main()
