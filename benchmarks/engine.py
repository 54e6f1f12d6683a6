"""Benchmark: evaluate the paper's programs to all maps, and the CLI cold start. Prints numbers.

Run: PYTHONPATH=. .venv/bin/python benchmarks/engine.py [--sizes 256 512 1024 2048]
     [--programs tile brick] [--backends numba numpy] [--cli-runs 7] [--repeat N]

For each program, backend and size it prints the wall time (min and median of the repeats), the
process CPU time (all threads; on a loaded machine CPU time is the steadier figure), the share of
CPU spent in the noise kernels, and the peak memory traced by tracemalloc during one evaluation
(numpy reports its buffers to it; numba's small per-thread scratch is not traced). Then it runs
``matloom render tile.mat --size 256 -o DIR`` as fresh processes and prints the median wall and
CPU time of the runs after the first (the first also fills the OS file cache). The machine's load
average is printed first and last: other processes inflate wall times.
"""

from __future__ import annotations

import argparse
import dataclasses
import os
import resource
import statistics
import subprocess
import sys
import tempfile
import time
import tracemalloc
from pathlib import Path
from typing import Any

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

import matloom  # noqa: E402
from matloom.engine.backends import Backend, get_backend  # noqa: E402

PARITY = ROOT / "tests" / "data" / "parity"
MIB = 1024 * 1024
REPEATS = {256: 20, 512: 10, 1024: 6, 2048: 3}


def timed_backend(name: str, clock: list[float]) -> Backend:
    """The backend ``name`` with its noise kernels wrapped to add their CPU time to clock[0]."""
    base = get_backend(name)

    def wrap(kernel: Any) -> Any:
        def run(*args: Any, **kwargs: Any) -> Any:
            start = time.process_time()
            try:
                return kernel(*args, **kwargs)
            finally:
                clock[0] += time.process_time() - start

        return run

    return dataclasses.replace(base, fbm=wrap(base.fbm), worley=wrap(base.worley))


def bench_evaluate(text: str, size: int, backend: str, repeats: int) -> dict[str, float]:
    """Wall/CPU statistics, noise CPU share and traced peak memory of evaluate()."""
    clock = [0.0]
    be = timed_backend(backend, clock)
    matloom.evaluate(text, size, size, backend=be)  # warm-up: kernel loading, caches
    walls, cpus = [], []
    clock[0] = 0.0
    for _ in range(repeats):
        w0, c0 = time.perf_counter(), time.process_time()
        matloom.evaluate(text, size, size, backend=be)
        walls.append(time.perf_counter() - w0)
        cpus.append(time.process_time() - c0)
    noise_share = clock[0] / sum(cpus) if sum(cpus) else 0.0
    tracemalloc.start()
    base = tracemalloc.get_traced_memory()[0]
    maps = matloom.evaluate(text, size, size, backend=be)
    peak = tracemalloc.get_traced_memory()[1] - base
    tracemalloc.stop()
    out_bytes = sum(a.nbytes for a in maps.arrays().values())
    return {
        "wall_min": min(walls),
        "wall_med": statistics.median(walls),
        "cpu_min": min(cpus),
        "cpu_med": statistics.median(cpus),
        "noise": noise_share,
        "peak": peak,
        "maps": out_bytes,
    }


def bench_cli(runs: int, backend: str | None) -> tuple[float, float, float]:
    """(first run wall, median wall, median CPU) of ``matloom render tile.mat --size 256``."""
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    env.pop("MATLOOM_BACKEND", None)
    if backend:
        env["MATLOOM_BACKEND"] = backend
    walls, cpus = [], []
    with tempfile.TemporaryDirectory() as tmp:
        for k in range(runs):
            before = resource.getrusage(resource.RUSAGE_CHILDREN)
            start = time.perf_counter()
            subprocess.run(
                [
                    sys.executable,
                    "-m",
                    "matloom",
                    "render",
                    str(PARITY / "tile.mat"),
                    "--size",
                    "256",
                    "-o",
                    f"{tmp}/out{k}",
                ],
                check=True,
                env=env,
                capture_output=True,
            )
            walls.append(time.perf_counter() - start)
            after = resource.getrusage(resource.RUSAGE_CHILDREN)
            cpus.append(after.ru_utime - before.ru_utime + after.ru_stime - before.ru_stime)
    return walls[0], statistics.median(walls[1:]), statistics.median(cpus[1:])


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--sizes", type=int, nargs="+", default=[256, 512, 1024, 2048])
    parser.add_argument("--programs", nargs="+", default=["tile", "brick"])
    parser.add_argument("--backends", nargs="+", default=["numba", "numpy"])
    parser.add_argument("--repeat", type=int, default=0, help="repeats (default: by size)")
    parser.add_argument("--cli-runs", type=int, default=7)
    args = parser.parse_args()
    print(f"load average at start: {os.getloadavg()}")
    print(
        f"{'program':8} {'backend':7} {'size':>5} {'wall min':>9} {'wall med':>9} "
        f"{'cpu min':>9} {'cpu med':>9} {'noise':>6} {'peak MiB':>9} {'maps MiB':>9}"
    )
    for name in args.programs:
        text = (PARITY / f"{name}.mat").read_text()
        for backend in args.backends:
            for size in args.sizes:
                reps = args.repeat or REPEATS.get(size, 3)
                if backend == "numpy":
                    reps = max(1, reps // 4)
                r = bench_evaluate(text, size, backend, reps)
                print(
                    f"{name:8} {backend:7} {size:5d} {r['wall_min'] * 1e3:8.1f}  "
                    f"{r['wall_med'] * 1e3:8.1f}  {r['cpu_min'] * 1e3:8.1f}  "
                    f"{r['cpu_med'] * 1e3:8.1f}  {r['noise']:5.0%} {r['peak'] / MIB:9.1f} "
                    f"{r['maps'] / MIB:9.1f}",
                    flush=True,
                )
    if args.cli_runs > 1:
        for backend in (None, "numba"):
            first, wall, cpu = bench_cli(args.cli_runs, backend)
            label = "auto" if backend is None else backend
            print(
                f"CLI render tile --size 256 (backend {label}): first {first:.2f} s, median "
                f"of {args.cli_runs - 1} later runs {wall:.2f} s wall, {cpu:.2f} s CPU",
                flush=True,
            )
    print(f"load average at end: {os.getloadavg()}")


if __name__ == "__main__":
    main()
