"""Benchmark: composite + relief (normals, AO) + export at 1024 and 2048; prints numbers.

Run: PYTHONPATH=. .venv/bin/python benchmarks/relief.py [--sizes 1024 2048] [--repeat 3]

Inputs are synthetic full-resolution float64 channel arrays for 3 layers (as an evaluator
returns them); they exist before measuring, so the memory numbers are what compositing adds.
Peak memory is measured with tracemalloc (numpy reports its buffers to it): "peak" is the
highest traced allocation above the pre-call baseline, "overhead" subtracts the returned maps.
"""

from __future__ import annotations

import argparse
import gc
import tempfile
import time
import tracemalloc
from collections.abc import Callable
from pathlib import Path
from typing import Any

import numpy as np

from matloom.engine import relief
from matloom.engine.composite import RawLayer, composite
from matloom.engine.maps import MaterialMaps, View
from matloom.runtime.export import export_maps

MIB = 1024 * 1024


def synthetic_layers(size: int) -> list[RawLayer]:
    """Three layers with spatially varying alpha, colour, roughness and height (float64)."""
    axis = (np.arange(size) + 0.5) / size
    x, y = axis[None, :], axis[:, None]
    ripple = np.sin(x * 40) * np.cos(y * 30)
    layers = []
    for index in range(3):
        phase = ripple * (index + 1)
        layers.append(
            RawLayer(
                alpha=np.clip(0.5 + phase, 0, 1) if index else 1.0,
                basecolor=(128 + 100 * phase, 90 + 0 * phase, 200 - 50 * phase),
                roughness=0.5 + 0.4 * phase,
                metallic=float(index == 1),
                emissive=(255.0, 128.0, 0.0, np.maximum(phase, 0)),
                height=0.01 * phase + 0.002 * index,
            )
        )
    return layers


def timed(function: Callable[[], Any], repeat: int) -> tuple[str, Any]:
    """Best wall and process-CPU time over ``repeat`` runs (formatted) and the last result.

    CPU time is reported too because wall time is inflated on a shared, loaded machine.
    """
    best_wall, best_cpu, result = float("inf"), float("inf"), None
    for _ in range(repeat):
        gc.collect()
        wall, cpu = time.perf_counter(), time.process_time()
        result = function()
        best_wall = min(best_wall, time.perf_counter() - wall)
        best_cpu = min(best_cpu, time.process_time() - cpu)
    return f"{best_wall * 1000:8.1f} ms wall {best_cpu * 1000:8.1f} ms cpu", result


def traced_peak(function: Callable[[], Any]) -> tuple[float, Any]:
    """Peak traced memory (MiB) above the baseline while ``function`` runs, and its result."""
    gc.collect()
    tracemalloc.start()
    baseline = tracemalloc.get_traced_memory()[0]
    result = function()
    peak = tracemalloc.get_traced_memory()[1] - baseline
    tracemalloc.stop()
    return peak / MIB, result


def map_bytes(maps: MaterialMaps) -> float:
    return sum(array.nbytes for array in maps.arrays().values()) / MIB


def bench_size(size: int, repeat: int, out_root: Path) -> None:
    layers = synthetic_layers(size)
    view = View()

    def run() -> MaterialMaps:
        return composite(layers, size, size, view)

    t_all, maps = timed(run, repeat)
    dx, dy = view.texel_size(size, size)
    t_normals, _ = timed(lambda: relief.normals(maps.height, dx, dy), repeat)
    t_ao, _ = timed(lambda: relief.ambient_occlusion(maps.height, dx), repeat)
    t_ao_units, _ = timed(lambda: composite(layers, size, size, view, ao_radius_units=0.02), 1)
    peak, _ = traced_peak(run)
    outputs = map_bytes(maps)
    t_exr, _ = timed(lambda: export_maps(maps, out_root / f"exr{size}"), repeat)
    t_png16, _ = timed(
        lambda: export_maps(maps, out_root / f"p16_{size}", float_format="png16"), repeat
    )
    export_peak, _ = traced_peak(lambda: export_maps(maps, out_root / f"mem{size}"))
    print(f"--- {size}x{size} (3 layers, best of {repeat})")
    print(f"composite+relief     {t_all}")
    print(f"  normals alone      {t_normals}")
    print(f"  ao alone (R=8)     {t_ao}")
    print(f"  composite+relief, AO 0.02 units (R={0.02 / dx:.1f} texels): {t_ao_units}")
    print(f"export (exr)         {t_exr}")
    print(f"export (png16)       {t_png16}")
    print(f"peak traced, composite+relief: {peak:7.1f} MiB (returned maps {outputs:.1f} MiB,")
    print(f"  overhead above the maps {peak - outputs:.1f} MiB)")
    print(f"peak traced, export: {export_peak:7.1f} MiB")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--sizes", type=int, nargs="+", default=[1024, 2048])
    parser.add_argument("--repeat", type=int, default=3)
    args = parser.parse_args()
    with tempfile.TemporaryDirectory() as folder:
        for size in args.sizes:
            bench_size(size, args.repeat, Path(folder))


if __name__ == "__main__":
    main()
