"""Preview shading and critic-statistics timings, plus parity and backend-agreement counts.

Run: ``PYTHONPATH=. .venv/bin/python benchmarks/preview.py [--reps 40]``

Maps are the parity fixtures' 64x64 composited arrays, nearest-upsampled to 256 / 512 (the seed
sweep shades at 256, the critic and trajectory selection at 512) and to 128 (the statistics
grid). Times are per call, single thread, over ``--reps`` runs after a warm-up call (JIT
compilation excluded): the best wall time and the median CPU time of the calling thread. Prints: parity with the reference previews (values that differ
and the largest difference) for every backend, how often the two backends differ on random
materials, and the timings.
"""

from __future__ import annotations

import argparse
import json
import statistics
import time
from collections.abc import Callable
from pathlib import Path

import numpy as np
from PIL import Image

from matloom.engine.maps import ARRAY_FIELDS, MaterialMaps
from matloom.render.preview import available_shaders, shade
from matloom.render.stats import material_stats

PARITY = Path(__file__).resolve().parents[1] / "tests" / "data" / "parity"
PROGRAMS = ("bricks", "all_channels", "reptile_scales", "nan_inf_fields")


def load(name: str) -> MaterialMaps:
    with np.load(PARITY / f"{name}_64x64.npz") as arrays:
        return MaterialMaps.from_arrays(dict(arrays))


def upsampled(maps: MaterialMaps, size: int) -> MaterialMaps:
    """Nearest-neighbour upsampling of 64x64 maps to size x size (C-contiguous float32)."""
    factor = size // maps.width
    arrays = {
        name: np.ascontiguousarray(np.repeat(np.repeat(a, factor, axis=0), factor, axis=1))
        for name, a in maps.arrays().items()
    }
    return MaterialMaps.from_arrays(arrays, n_layers=maps.n_layers)


def timed(func: Callable[[], object], reps: int) -> tuple[float, float]:
    """(best wall time, median thread CPU time) in milliseconds after one warm-up call.

    The CPU time of the calling thread excludes time spent waiting for a core, so it stays
    meaningful on a shared, busy machine where wall times are inflated.
    """
    func()
    walls, cpus = [], []
    for _ in range(reps):
        wall, cpu = time.perf_counter(), time.thread_time()
        func()
        cpus.append((time.thread_time() - cpu) * 1e3)
        walls.append((time.perf_counter() - wall) * 1e3)
    return min(walls), statistics.median(cpus)


def parity_report() -> None:
    manifest = json.loads((PARITY / "manifest.json").read_text())["programs"]
    for backend in available_shaders():
        differing, worst, total = 0, 0, 0
        for name in manifest:
            with Image.open(PARITY / f"{name}_preview_64.png") as image:
                ref = np.asarray(image.convert("RGB")).astype(np.int16)
            diff = np.abs(shade(load(name), backend=backend).astype(np.int16) - ref)
            differing += int(np.count_nonzero(diff))
            worst = max(worst, int(diff.max()))
            total += diff.size
        print(
            f"parity {backend:5s}: {len(manifest)} reference previews, {differing} of {total} "
            f"values differ, max {worst} level(s)"
        )


def random_maps(rng: np.random.Generator, size: int) -> MaterialMaps:
    arrays = {name: rng.random((size, size)).astype(np.float32) for name in ARRAY_FIELDS}
    arrays["basecolor_linear"] = (rng.random((size, size, 3)) ** 2).astype(np.float32)
    arrays["emissive_linear"] = (rng.random((size, size, 3)) * 3).astype(np.float32)
    normal = rng.normal(size=(size, size, 3))
    normal[..., 2] = np.abs(normal[..., 2]) + 0.3
    arrays["normal"] = (normal / np.linalg.norm(normal, axis=-1, keepdims=True)).astype(np.float32)
    arrays["ior"] = (1 + rng.random((size, size)) * 2.5).astype(np.float32)
    return MaterialMaps.from_arrays(arrays)


def agreement_report(materials: int = 40, size: int = 128) -> None:
    """How often the numba path (float32 sRGB pow) differs from the all-float64 numpy path."""
    if "numba" not in available_shaders():
        print("agreement: numba not installed, skipped")
        return
    rng = np.random.default_rng(0)
    differing, worst, total = 0, 0, 0
    for _ in range(materials):
        maps = random_maps(rng, size)
        diff = np.abs(
            shade(maps, backend="numba").astype(np.int16)
            - shade(maps, backend="numpy").astype(np.int16)
        )
        differing += int(np.count_nonzero(diff))
        worst = max(worst, int(diff.max()))
        total += diff.size
    print(f"agreement numba vs numpy: {differing} of {total} values differ, max {worst} level(s)")


def timing_report(reps: int) -> None:
    for name in PROGRAMS:
        base = load(name)
        for size in (256, 512):
            maps = upsampled(base, size)
            cells = []
            for backend in available_shaders():
                best, median = timed(lambda m=maps, b=backend: shade(m, backend=b), reps)
                cells.append(f"{backend} {best:7.2f} / {median:7.2f}")
            print(
                f"shade {name:15s} {size}: " + "   ".join(cells) + "  ms (best wall / median CPU)"
            )
        grid = upsampled(base, 128)
        best, median = timed(lambda m=grid: material_stats(m), reps)
        print(f"stats {name:15s} 128: {best:7.2f} / {median:7.2f} ms (best wall / median CPU)")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--reps", type=int, default=40, help="timed runs per measurement")
    args = parser.parse_args()
    parity_report()
    agreement_report()
    timing_report(args.reps)


if __name__ == "__main__":
    main()
