"""The steps of the background kernel compiler of :mod:`matloom.runtime.warmup` (which runs
them as ``python -m matloom.runtime.warmup DIR``) and their runner; run as ``python -m
matloom.runtime.warmup_steps --primitives``, the helper process of :func:`run_steps`.

Each step evaluates a small program on the numba backend, so the kernels are compiled for exactly
the argument types real renders pass; together the steps cover every evaluation kernel (fBm and
Worley on separable axes and rotated grids, with and without coverage masks; both Bricks kernels;
paths; compositing; relief; preview shading; the language-2 primitives). On a machine with two or more cores a helper
process compiles the primitive kernels of the later steps (evaluating them unfused, so without
the compositing kernel) while this process compiles compositing and shading; the later steps
then run fused and mostly load from the cache. Importing this module does not import numba.
"""

from __future__ import annotations

import os
import subprocess
import sys
import time
from collections.abc import Callable

_TILE = """View(0, 0, 2, 2)
Define(tileMask, Bricks(brick_width=0.48, brick_height=0.48, offset=0, mortar=0.02, feather=0.008))
Define(glaze, fBm(octaves=3, base_freq=7, to_01=True, seed=1))
Define(grout, fBm(octaves=4, base_freq=30, to_01=True, seed=2))
Material(Layer(1).basecolor(40 + grout * 12, 42, 45).roughness(0.85 + grout * 0.1),
  Layer(tileMask).basecolor(12, 13, 16).coat(0.95).height(tileMask * 0.016 + glaze * 0.001))"""
_ROTATED = """View(0, 0, 2, 2)
Define(mask, Rotate(Bricks(brick_width=0.5, brick_height=0.25, offset=0.5, mortar=0.02), 15))
Define(grain, Rotate(fBm(octaves=2, base_freq=3, to_01=True, seed=3), 30))
Define(fleck, Rotate(fBm(octaves=2, base_freq=9, to_01=True, seed=6), 30))
Material(Layer(1).basecolor(90 + grain * 40, 80, 70).roughness(0.5 + grain * 0.2),
  Layer(mask).basecolor(140, 95, 60).roughness(0.3 + fleck * 0.2).height(mask * 0.01))"""
_WORLEY = """View(0, 0, 2, 2)
Define(cells, Worley(seed=4))
Define(edges, Rotate(Worley(distance="manhattan", combination="F2-F1", seed=5), 20))
Material(Layer(1).basecolor(100 + cells * 50, 90 + edges * 40, 80).height(edges * 0.01))"""
_COLUMNS = """View(0, 0, 3, 3)
Define(course, Bricks(brick_width=0.25, brick_height=0.9, offset=0.33, mortar=0.03,
  axis="column", feather=0.02))
Material(Layer(1).basecolor(190, 185, 175), Layer(course).basecolor(120, 70, 50))"""
_PATHS = """View(-0.1, -0.1, 1.1, 1.1)
Define(star, Fill(Path(0.5, 0.9, LineTo(0.26, 0.18), LineTo(0.88, 0.62), LineTo(0.12, 0.62)),
  mode="EvenOdd", feather=0.01))
Define(line, Stroke(Path(0.1, 0.1, LineTo(0.9, 0.3), CubicTo(0.5, 0.5, 0.3, 0.9, 0.8, 0.8)), 0.02))
Material(Layer(1).basecolor(240, 240, 240), Layer(star).basecolor(200, 20, 30).height(0.01),
  Layer(line).basecolor(10, 10, 10).emissive(255, 128, 0, 2))"""

_LANGUAGE_2 = """View(0, 0, 4, 4)
Define(warp, fBm(octaves=2, base_freq=0.5, seed=7))
Define(board, Bricks(brick_width=2, brick_height=0.5, offset=0.5, mortar=0.02, output="cell_value",
  seed=8))
Define(dots, Tile(Fill(Ellipse(0, 0, 0.2, 0.2), feather=0.02), 1, 1, jitter=0.2, rotate=30,
  seed=9))
Material(Layer(1).basecolor(120 + board * 60, 90, 60)
    .roughness(Fract(Translate(X(), warp * 0.5, 0) * 3) * Weave(output="warp"))
    .anisotropy(0.5).anisotropy_angle(Atan2(Y() - 2, X() - 2) * 57.3),
  Layer(dots).basecolor(200 * Hash(Floor(X()), Floor(Y()), seed=10), 180, 40)
    .height(Worley(output="edge", seed=11) * 0.01 + Rotate(fBm(seed=12), warp * 30) * 0.002))"""

_TILEABLE = """View(0, 0, 2, 2, tileable=True)
Define(cells, Worley(base_freq=3, output="cell_value", seed=13))
Material(Layer(1).basecolor(100 + cells * 100, 90, 80)
    .height(fBm(octaves=4, base_freq=2, seed=14) * 0.02 + Worley(base_freq=3, seed=13) * 0.01))"""

#: (label, program) of each warm-up step; ``None``: shade the previous step's maps.
STEPS: tuple[tuple[str, str | None], ...] = (
    ("fBm and compositing", _TILE),
    ("preview shading", None),
    ("rotated fBm and Bricks", _ROTATED),
    ("Worley", _WORLEY),
    ("column Bricks", _COLUMNS),
    ("paths", _PATHS),
    ("language 2 (warps, Tile, cells)", _LANGUAGE_2),
    ("tileable output", _TILEABLE),
)

#: The first steps compile every kernel of the paper's tile program (fBm, Bricks rows,
#: compositing, relief, shading): ``matloom demo`` waits for these only.
TILE_STEPS = 2
#: Size of the step renders (the kernels do not depend on it).
STEP_SIZE = 24
#: Index of the first step whose primitives the helper process compiles.
_HELPED_FROM = 2


def run_steps(
    progress: Callable[[int, int, str], None] | None = None, helper: bool = True
) -> float:
    """Compile (or load) every kernel of :data:`STEPS` in this process (with the helper process
    when ``helper`` and there are two or more cores); returns seconds. ``progress(done, total,
    label)`` is called before each step and at the end."""
    from matloom.engine.evaluate import evaluate
    from matloom.render.preview import shade

    start = time.perf_counter()
    helping = _start_helper() if helper and (os.cpu_count() or 1) > 1 else None
    maps = None
    try:
        for k, (label, program) in enumerate(STEPS):
            if progress is not None:
                progress(k, len(STEPS), label)
            if k == _HELPED_FROM and helping is not None:
                helping.wait()
                helping = None
            if program is None:
                shade(maps, backend="numba")
            else:
                maps = evaluate(program, STEP_SIZE, STEP_SIZE, backend="numba")
    finally:
        if helping is not None:
            helping.kill()
    if progress is not None:
        progress(len(STEPS), len(STEPS), "")
    return time.perf_counter() - start


def _start_helper() -> subprocess.Popen[bytes] | None:
    try:
        return subprocess.Popen(  # noqa: S603 - our own module, same interpreter
            [sys.executable, "-m", "matloom.runtime.warmup_steps", "--primitives"],
            stdin=subprocess.DEVNULL,
            stdout=subprocess.DEVNULL,
            stderr=subprocess.DEVNULL,
        )
    except OSError:
        return None


def compile_primitives() -> None:
    """The helper: the primitive kernels of the later steps, evaluated unfused."""
    from dataclasses import replace

    from matloom.engine.backends import get_backend
    from matloom.engine.evaluate import evaluate

    unfused = replace(get_backend("numba"), fused=False)
    for _, program in STEPS[_HELPED_FROM:]:
        if program is not None:
            evaluate(program, STEP_SIZE, STEP_SIZE, backend=unfused)


if __name__ == "__main__":  # the helper (as nice as its parent): ``--primitives``
    if sys.argv[1:] != ["--primitives"]:
        sys.exit("usage: python -m matloom.runtime.warmup_steps --primitives")
    compile_primitives()
