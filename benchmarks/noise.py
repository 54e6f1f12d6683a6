"""Benchmark the noise kernels: fBm/Worley per call, seed-batch throughput, numba cold start.

Usage: ``PYTHONPATH=. .venv/bin/python benchmarks/noise.py [--sizes 256 1024] [--seeds 1000]``

Prints best-of-N wall milliseconds (and process CPU milliseconds, which are less sensitive to a
busy machine), the seed-sweep time for the three fBm fields of the paper's tile program
(View(0, 0, 2, 2), 256 x 256 float32 axes, 1000 seeds), and the numba import + first-call
compile time versus the cached load time in a fresh process.  Nothing here asserts.
"""

from __future__ import annotations

import argparse
import os
import subprocess
import sys
import tempfile
import time
from collections.abc import Callable
from pathlib import Path
from typing import Any

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from matloom.engine.backends import Backend, get_backend  # noqa: E402
from matloom.engine.grid import sample_axes  # noqa: E402
from matloom.engine.maps import View  # noqa: E402

FBM_KW: dict[str, Any] = dict(
    octaves=4, lacunarity=2.0, gain=0.5, freq_x=8.0, freq_y=8.0, to_01=False, seed=3
)
WORLEY_KW: dict[str, Any] = dict(
    distance="euclidean", combination="F1", freq_x=8.0, freq_y=8.0, to_01=True, seed=4
)
#: (octaves, base_freq) of glazeRipple, glazeGrain, groutNoise in tests/data/parity/tile.mat.
TILE_FIELDS = [(3, 7.0), (5, 35.0), (4, 30.0)]


def view_axes(size: int, x1: float, y1: float, x2: float, y2: float) -> tuple[np.ndarray, ...]:
    """The engine's float32 pixel-centre axes for a View: x (1, W), y (H, 1), row 0 on top."""
    return sample_axes(View(x1, y1, x2, y2), size, size)


def best_ms(fn: Callable[[], Any], repeat: int) -> tuple[float, float]:
    """(best wall ms, best process-CPU ms) over ``repeat`` runs after one warm-up run."""
    fn()
    walls, cpus = [], []
    for _ in range(repeat):
        w0, c0 = time.perf_counter(), time.process_time()
        fn()
        walls.append(time.perf_counter() - w0)
        cpus.append(time.process_time() - c0)
    return min(walls) * 1e3, min(cpus) * 1e3


def bench_calls(backends: dict[str, Backend], sizes: list[int], repeat: int) -> None:
    """fBm and Worley, separable float32 axes and a rotated full grid."""
    for size in sizes:
        x, y = view_axes(size, 0.0, 0.0, 1.0, 1.0)
        rad = np.radians(30.0)
        gx, gy = np.cos(rad) * x + np.sin(rad) * y, -np.sin(rad) * x + np.cos(rad) * y
        cases = (
            ("fbm 4oct", "fbm", (x, y), FBM_KW),
            ("fbm 4oct rotated", "fbm", (gx, gy), FBM_KW),
            ("worley F1", "worley", (x, y), WORLEY_KW),
            ("worley F1 rotated", "worley", (gx, gy), WORLEY_KW),
        )
        for name, mod in backends.items():
            reps = repeat if name == "numba" else max(1, repeat // 3)
            for label, func, coords, kw in cases:
                fn = getattr(mod, func)
                wall, cpu = best_ms(lambda f=fn, c=coords, k=kw: f(*c, **k), reps)
                print(f"{name:6s} {label:18s} {size:5d}^2  {wall:9.1f} ms  (cpu {cpu:9.1f} ms)")


def bench_seed_batch(mod: Backend, n_seeds: int) -> None:
    """The paper tile program's three fBm fields for ``n_seeds`` seeds, plus a Worley field."""
    x, y = view_axes(256, 0.0, 0.0, 2.0, 2.0)
    seeds = list(range(n_seeds))
    for octaves, freq in TILE_FIELDS:  # warm-up / compile with a tiny batch
        mod.fbm_seed_batch(
            x,
            y,
            octaves=octaves,
            lacunarity=2.0,
            gain=0.5,
            freq_x=freq,
            freq_y=freq,
            to_01=True,
            seeds=seeds[:2],
        )
    w0, c0 = time.perf_counter(), time.process_time()
    for octaves, freq in TILE_FIELDS:
        mod.fbm_seed_batch(
            x,
            y,
            octaves=octaves,
            lacunarity=2.0,
            gain=0.5,
            freq_x=freq,
            freq_y=freq,
            to_01=True,
            seeds=seeds,
        )
    wall, cpu = time.perf_counter() - w0, time.process_time() - c0
    print(
        f"seed batch: tile fBm x3, {n_seeds} seeds, 256^2: {wall:.2f} s wall "
        f"(cpu {cpu:.2f} s), {wall / n_seeds * 1e3:.2f} ms per seed"
    )
    per_seed = 20
    w0 = time.perf_counter()
    for seed in seeds[:per_seed]:
        for octaves, freq in TILE_FIELDS:
            mod.fbm(
                x,
                y,
                octaves=octaves,
                lacunarity=2.0,
                gain=0.5,
                freq_x=freq,
                freq_y=freq,
                to_01=True,
                seed=seed,
            )
    loop = (time.perf_counter() - w0) / per_seed
    print(f"  per-seed fbm loop for comparison: {loop * 1e3:.2f} ms per seed")
    wkw = dict(distance="euclidean", combination="F2-F1", freq_x=8.0, freq_y=8.0, to_01=True)
    mod.worley_seed_batch(x, y, seeds=seeds[:2], **wkw)
    w0 = time.perf_counter()
    mod.worley_seed_batch(x, y, seeds=seeds, **wkw)
    wall = time.perf_counter() - w0
    print(
        f"worley batch: {n_seeds} seeds, 256^2: {wall:.2f} s ({wall / n_seeds * 1e3:.2f} ms/seed)"
    )


_COLD_SCRIPT = """
import time
t0 = time.perf_counter()
import numpy as np
from matloom.engine.backends import get_backend
nb = get_backend("numba")
t1 = time.perf_counter()
x = np.linspace(0, 1, 64, dtype=np.float32)[None, :]
y = np.linspace(0, 1, 64, dtype=np.float32)[:, None]
nb.fbm(x, y, octaves=4, lacunarity=2.0, gain=0.5, freq_x=8.0, freq_y=8.0, to_01=True, seed=1)
t2 = time.perf_counter()
nb.worley(x, y, distance="euclidean", combination="F1", freq_x=8.0, freq_y=8.0, to_01=True,
          seed=1)
t3 = time.perf_counter()
print(f"import {t1 - t0:.2f} s, first fbm {t2 - t1:.2f} s, first worley {t3 - t2:.2f} s")
"""


def bench_cold_start() -> None:
    """numba import + compile in a fresh cache dir, then cached load in a second process."""
    with tempfile.TemporaryDirectory() as cache_dir:
        env = {**os.environ, "NUMBA_CACHE_DIR": cache_dir, "PYTHONPATH": str(ROOT)}
        for label in ("cold (compile)", "warm (cached)"):
            out = subprocess.run(
                [sys.executable, "-c", _COLD_SCRIPT],
                env=env,
                cwd=ROOT,
                capture_output=True,
                text=True,
                check=True,
            )
            print(f"numba {label:15s}: {out.stdout.strip()}")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--sizes", type=int, nargs="+", default=[256, 1024])
    parser.add_argument("--seeds", type=int, default=1000)
    parser.add_argument("--repeat", type=int, default=5)
    parser.add_argument("--skip-numpy", action="store_true")
    parser.add_argument("--skip-cold", action="store_true")
    args = parser.parse_args()
    backends: dict[str, Backend] = {}
    try:
        import numba

        backends["numba"] = get_backend("numba")
        print(f"numba {numba.__version__}, threads {numba.get_num_threads()}", end=", ")
    except ImportError:
        print("numba not installed", end=", ")
    if not args.skip_numpy:
        backends["numpy"] = get_backend("numpy")
    print(f"numpy {np.__version__}, load average {os.getloadavg()[0]:.2f}")
    bench_calls(backends, args.sizes, args.repeat)
    if "numba" in backends:
        bench_seed_batch(backends["numba"], args.seeds)
        if not args.skip_cold:
            bench_cold_start()


if __name__ == "__main__":
    main()
