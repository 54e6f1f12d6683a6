"""Benchmark the optional C fBm kernel (``_cnoise``) against the pure-numpy fBm.

Usage: ``PYTHONPATH=. .venv/bin/python benchmarks/cnoise.py [--sizes 256 1024] [--repeat 5]``

Prints best-of-N wall milliseconds (and process CPU milliseconds) for the three fBm fields of the
paper's tile program (octaves 3 @ freq 7, 5 @ 35, 4 @ 30; View(0, 0, 2, 2), float32 pixel-centre
axes), separable and rotated by 30 degrees, for the C loops and the pure-numpy loops; then
the import time of ``noise_c`` (which loads the extension) and of ``noise_numpy`` in a fresh
process, and the whole tile render (``matloom render``) with and without the C kernel.  Nothing
here asserts.
"""

from __future__ import annotations

import argparse
import os
import subprocess
import sys
import tempfile
import time
from collections.abc import Callable
from functools import partial
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from benchmarks.noise import TILE_FIELDS, best_ms, view_axes  # noqa: E402
from matloom.engine.kernels import noise, noise_c, noise_numpy  # noqa: E402

TILE_PROGRAM = ROOT / "tests" / "data" / "parity" / "tile.mat"


def tile_fields(fbm: Callable[..., np.ndarray], x: np.ndarray, y: np.ndarray) -> None:
    """The tile program's three fBm fields (seeds as in tile.mat)."""
    for (octaves, freq), seed in zip(TILE_FIELDS, (1145088217, 1007923142, 891377204)):
        fbm(x, y, octaves=octaves, lacunarity=2.0, gain=0.5, freq_x=freq, freq_y=freq,
            to_01=True, seed=seed)  # fmt: skip


def bench_fields(sizes: list[int], repeat: int) -> None:
    """C vs numpy on the tile's fields, separable axes and a rotated full grid."""
    kernels = {
        "C": partial(noise.fbm, loops=noise_c.FBM_LOOPS),
        "numpy": partial(noise.fbm, loops=noise_numpy.FBM_LOOPS),
    }
    for size in sizes:
        x, y = view_axes(size, 0.0, 0.0, 2.0, 2.0)
        rad = np.float32(np.radians(30.0))
        cos, sin = np.cos(rad), np.sin(rad)
        layouts = {"separable": (x, y), "rotated": (cos * x + sin * y, -sin * x + cos * y)}
        for layout, (cx, cy) in layouts.items():
            times = {}
            for name, fbm in kernels.items():
                reps = repeat if name == "C" else max(1, repeat // 2)
                times[name] = best_ms(lambda f=fbm, a=cx, b=cy: tile_fields(f, a, b), reps)
                wall, cpu = times[name]
                print(f"tile fBm x3 {layout:9s} {size:5d}^2  {name:5s} {wall:8.1f} ms  "
                      f"(cpu {cpu:8.1f} ms)")  # fmt: skip
            print(f"  speed-up {times['numpy'][0] / times['C'][0]:.1f}x")


_IMPORT_SCRIPT = """
import sys, time
t0 = time.perf_counter()
import numpy
t1 = time.perf_counter()
from matloom.engine.kernels import opensimplex
t2 = time.perf_counter()
from matloom.engine.kernels import _cnoise
t3 = time.perf_counter()
from matloom.engine.kernels import noise_c, noise_numpy
t4 = time.perf_counter()
assert noise_c.available() and "numba" not in sys.modules
print(" ".join(f"{(b - a) * 1e3:.3f}" for a, b in ((t0, t1), (t1, t2), (t2, t3), (t3, t4))))
"""


def bench_import(repeat: int) -> None:
    """Fresh-process import times, in order: numpy, matloom + opensimplex, _cnoise, wrappers."""
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    runs = []
    for _ in range(repeat):
        out = subprocess.run(
            [sys.executable, "-c", _IMPORT_SCRIPT], env=env, capture_output=True, text=True
        )
        if out.returncode != 0:
            print(f"import check failed: {out.stderr.strip()[-300:]}")
            return
        runs.append([float(v) for v in out.stdout.split()])
    best = np.min(np.array(runs), axis=0)
    print(f"fresh-process import (best of {repeat}): numpy {best[0]:.1f} ms, matloom + "
          f"opensimplex {best[1]:.1f} ms, _cnoise {best[2]:.3f} ms, noise_c + noise_numpy "
          f"{best[3]:.2f} ms (numba not imported)")  # fmt: skip


def bench_render(size: int, repeat: int) -> None:
    """``matloom render tile.mat --size N`` as a fresh process, C kernel on and off."""
    with tempfile.TemporaryDirectory() as out_dir:
        for label, pure in (("C fBm", "0"), ("pure numpy", "1")):
            env = {**os.environ, "PYTHONPATH": str(ROOT), "MATLOOM_PURE_NUMPY": pure}
            cmd = [sys.executable, "-m", "matloom.cli.main", "render", str(TILE_PROGRAM),
                   "--size", str(size), "--out", str(Path(out_dir) / "maps")]  # fmt: skip
            walls = []
            for _ in range(repeat):
                w0 = time.perf_counter()
                done = subprocess.run(cmd, env=env, capture_output=True, text=True)
                walls.append(time.perf_counter() - w0)
                if done.returncode != 0:
                    print(f"render failed ({label}): {done.stderr.strip()[-300:]}")
                    return
            print(f"matloom render tile.mat --size {size} ({label:10s}): best of {repeat} "
                  f"{min(walls) * 1e3:.0f} ms, median {np.median(walls) * 1e3:.0f} ms")  # fmt: skip


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--sizes", type=int, nargs="+", default=[256, 1024])
    parser.add_argument("--repeat", type=int, default=5)
    parser.add_argument("--skip-render", action="store_true")
    args = parser.parse_args()
    if not noise_c.available():
        print("the C extension is not built: reinstall with a C compiler (pip install -e .)")
        return
    print(f"numpy {np.__version__}, load average {os.getloadavg()[0]:.2f}")
    bench_fields(args.sizes, args.repeat)
    bench_import(args.repeat)
    if not args.skip_render:
        bench_render(256, args.repeat)


if __name__ == "__main__":
    main()
