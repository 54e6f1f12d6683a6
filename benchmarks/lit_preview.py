"""Preview shading times: the ``flat`` (reference) and ``lit`` (studio) layouts.

Run: ``PYTHONPATH=. .venv/bin/python benchmarks/lit_preview.py [--reps 15] [--threads N]``

For a few example programs (docs/examples) the maps are evaluated once per size (256, 512,
1024); then each layout shades them ``--reps`` times after a warm-up call (JIT compilation
excluded, reported separately for the lit kernel when it was not cached). Prints the median wall
time and the median CPU time of all threads of the process, in milliseconds: on a busy shared
machine the wall time is inflated by waiting for a core, the CPU time is not. ``--threads``
sets numba's thread count (the lit kernel splits rows over threads; the flat one is serial),
``--backend numpy`` times the numpy paths.
"""

from __future__ import annotations

import argparse
import statistics
import time
from collections.abc import Callable
from pathlib import Path

import numpy as np

import matloom
from matloom.render.lit import shade_lit
from matloom.render.preview import shade

EXAMPLES = Path(__file__).resolve().parents[1] / "docs" / "examples"
PROGRAMS = ("01_plank_floor", "07_cracked_ice", "09_radial_brushed_steel", "12_terrazzo")


def timed(func: Callable[[], object], reps: int) -> tuple[float, float]:
    """(median wall ms, median process CPU ms) over ``reps`` calls after one warm-up call."""
    func()
    walls, cpus = [], []
    for _ in range(reps):
        wall, cpu = time.perf_counter(), time.process_time()
        func()
        cpus.append((time.process_time() - cpu) * 1e3)
        walls.append((time.perf_counter() - wall) * 1e3)
    return statistics.median(walls), statistics.median(cpus)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--reps", type=int, default=15)
    parser.add_argument("--sizes", type=int, nargs="+", default=[256, 512, 1024])
    parser.add_argument("--programs", nargs="+", default=list(PROGRAMS))
    parser.add_argument("--threads", type=int, default=0, help="numba threads (0: default)")
    parser.add_argument("--backend", default="numba", choices=("numba", "numpy"))
    args = parser.parse_args()
    if args.threads:
        import numba

        numba.set_num_threads(args.threads)
    warm = matloom.evaluate("Material(Layer(1).basecolor(128, 128, 128))", 8, 8)
    start = time.perf_counter()
    shade_lit(warm, backend=args.backend)
    print(f"lit kernel load/compile: {time.perf_counter() - start:.2f} s")
    print(f"{'program':<26} {'size':>5}  {'flat wall/cpu ms':>17}  {'lit wall/cpu ms':>17}")
    summary: dict[int, list[tuple[float, float]]] = {size: [] for size in args.sizes}
    for name in args.programs:
        text = (EXAMPLES / f"{name}.mat").read_text(encoding="utf-8")
        for size in args.sizes:
            maps = matloom.evaluate(text, size, size)
            flat = timed(lambda m=maps: shade(m, backend=args.backend), args.reps)
            lit = timed(lambda m=maps: shade_lit(m, backend=args.backend), args.reps)
            summary[size].append((flat[0], lit[0]))
            print(
                f"{name:<26} {size:>5}  {flat[0]:8.1f}/{flat[1]:<8.1f}  {lit[0]:8.1f}/{lit[1]:<8.1f}"
            )
    for size, rows in summary.items():
        flat_ms, lit_ms = np.median(np.array(rows), axis=0)
        print(f"median over programs at {size}: flat {flat_ms:.1f} ms, lit {lit_ms:.1f} ms")


if __name__ == "__main__":
    main()
