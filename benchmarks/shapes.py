"""Timing of the pattern and shape kernels at 1024x1024 on float32 exporter axes.

Run: PYTHONPATH=. .venv/bin/python benchmarks/shapes.py [--size 1024] [--repeat 5]

Prints, per case and backend, the first call (includes numba compilation or cache load) and
the best and median of the following calls, in milliseconds. Paths: the fixture pentagram
(5 edges), a 100-edge star, the fixture's line+cubic stroke (17 edges) and the leaf outline
(two cubics, 32 edges). Bricks and Weave are numpy only.
"""

from __future__ import annotations

import argparse
import math
import statistics
import time
from collections.abc import Callable

import numpy as np

from matloom.engine.kernels.patterns import bricks, weave
from matloom.engine.kernels.shapes import (
    CubicSeg,
    EllipseGeom,
    LineSeg,
    PathGeom,
    fill,
    make_rect,
    stroke,
)

PENTAGRAM = PathGeom(
    0.5,
    0.9,
    tuple(
        LineSeg(*p)
        for p in [(0.2649, 0.1764), (0.8804, 0.6236), (0.1196, 0.6236), (0.7351, 0.1764)]
    ),
)
HOOK = PathGeom(0, 0, (LineSeg(1, 1), CubicSeg(1.2, 1.5, -0.5, 2.5, -0.3, 2.7)))
LEAF = PathGeom(
    0.5,
    0.05,
    (CubicSeg(0.95, 0.3, 0.85, 0.8, 0.5, 0.95), CubicSeg(0.15, 0.8, 0.05, 0.3, 0.5, 0.05)),
)


def star_path(n_points: int = 100, outer: float = 0.45, inner: float = 0.2) -> PathGeom:
    """A star polygon with ``n_points`` vertices alternating between two radii (n edges)."""
    vertices = [
        (
            0.5 + (outer if k % 2 == 0 else inner) * math.cos(2 * math.pi * k / n_points),
            0.5 + (outer if k % 2 == 0 else inner) * math.sin(2 * math.pi * k / n_points),
        )
        for k in range(n_points)
    ]
    return PathGeom(*vertices[0], tuple(LineSeg(*v) for v in vertices[1:]))


def exporter_axes(size: int) -> tuple[np.ndarray, np.ndarray]:
    """float32 texel-centre axes of the default View (0, 0, 1, 1), y up."""
    x = (np.arange(size, dtype=np.float32) + 0.5) * np.float32(1 / size)
    y = (np.arange(size, dtype=np.float32) + 0.5) * np.float32(-1 / size) + np.float32(1)
    return x[None, :], y[:, None]


def time_case(run: Callable[[], np.ndarray], repeat: int) -> tuple[float, float, float]:
    """(first, best, median) wall time in milliseconds."""
    times = []
    for _ in range(repeat + 1):
        start = time.perf_counter()
        run()
        times.append((time.perf_counter() - start) * 1e3)
    return times[0], min(times[1:]), statistics.median(times[1:])


def shape_cases(x: np.ndarray, y: np.ndarray) -> dict[str, Callable[[str], np.ndarray]]:
    """Shape benchmarks, each taking the backend name."""
    star100 = star_path()
    return {
        "fill pentagram NonZero": lambda b: fill(PENTAGRAM, x, y, backend=b),
        "fill pentagram EvenOdd f=0.01": lambda b: fill(
            PENTAGRAM, x, y, mode="EvenOdd", feather=0.01, backend=b
        ),
        "fill star100 NonZero": lambda b: fill(star100, x, y, backend=b),
        "fill star100 NonZero f=0.02": lambda b: fill(star100, x, y, feather=0.02, backend=b),
        "fill leaf (32 edges) f=0.01": lambda b: fill(LEAF, x, y, feather=0.01, backend=b),
        "stroke hook cubic w=0.2": lambda b: stroke(HOOK, x, y, width=0.2, backend=b),
        "stroke star100 w=0.01 f=0.005": lambda b: stroke(
            star100, x, y, width=0.01, feather=0.005, backend=b
        ),
        "fill rounded rect f=0.05": lambda b: fill(
            make_rect(0.1, 0.1, 0.8, 0.6, 0.2), x, y, feather=0.05
        ),
        "stroke ellipse w=0.04": lambda b: stroke(
            EllipseGeom(0.5, 0.5, 0.4, 0.3), x, y, width=0.04
        ),
    }


def pattern_cases(x: np.ndarray, y: np.ndarray) -> dict[str, Callable[[], np.ndarray]]:
    """Bricks/Weave benchmarks (numpy only)."""
    brick_args = dict(brick_width=0.1, brick_height=0.05, offset=0.5, mortar=0.005, axis="row")
    weave_args = dict(over=2, under=1, shift=1, freq_x=24.0, freq_y=20.0, warp_width=0.9)
    return {
        "bricks f=0": lambda: bricks(x, y, **brick_args, feather=0.0),
        "bricks f=0.002": lambda: bricks(x, y, **brick_args, feather=0.002),
        "weave f=0": lambda: weave(x, y, **weave_args, feather=0.0),
        "weave f=0.1": lambda: weave(x, y, **weave_args, feather=0.1),
    }


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--size", type=int, default=1024)
    parser.add_argument("--repeat", type=int, default=5)
    args = parser.parse_args()
    x, y = exporter_axes(args.size)
    print(f"{args.size}x{args.size}, ms: first / best / median of {args.repeat}")
    for name, case in shape_cases(x, y).items():
        for backend in ("numpy", "numba"):
            first, best, median = time_case(lambda c=case, b=backend: c(b), args.repeat)
            print(f"{name:32s} {backend:6s} {first:9.1f} {best:9.1f} {median:9.1f}")
    for name, case in pattern_cases(x, y).items():
        first, best, median = time_case(case, args.repeat)
        print(f"{name:32s} {'numpy':6s} {first:9.1f} {best:9.1f} {median:9.1f}")


if __name__ == "__main__":
    main()
