"""Benchmark: the language-2 primitives as fields, in nanoseconds per pixel. Prints numbers.

Run: PYTHONPATH=. .venv/bin/python benchmarks/language_v2.py [--size 1024] [--repeat 7]
     [--backends numba numpy]

Each case evaluates one field (``Evaluator.field``, no compositing or relief) on a size x size
grid over an 8 x 8 View, after one warm-up evaluation, and prints the median wall time per pixel.
The last lines compare Tile of a Fill(Ellipse) motif with one Fill(Ellipse) (the issue's target:
at most 12x), with the defaults and with jitter, rotation, scale and dropped cells.
"""

from __future__ import annotations

import argparse
import os
import statistics
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from matloom.engine.backends import available_backends, get_backend  # noqa: E402
from matloom.engine.evaluate import Evaluator, prepare  # noqa: E402
from matloom.engine.grid import View, sample_axes  # noqa: E402

VIEW = (0.0, 0.0, 8.0, 8.0)
MOTIF = "Fill(Ellipse(0, 0, 0.3, 0.2), feather=0.02)"
CASES = {
    "fBm (6 octaves)": "fBm(octaves=6, base_freq=2, seed=1)",
    "warped fBm": "Translate(fBm(octaves=6, base_freq=2, seed=1), "
    "fBm(octaves=3, base_freq=0.5, seed=2) * 0.6, fBm(octaves=3, base_freq=0.5, seed=3) * 0.6)",
    "swirled Bricks": "Rotate(Bricks(), fBm(octaves=3, base_freq=0.3, seed=4) * 60)",
    "Worley distance": "Worley(base_freq=2, seed=5)",
    "Worley edge": 'Worley(base_freq=2, output="edge", seed=5)',
    "Fill(Ellipse)": f"Translate({MOTIF}, 0.5, 0.5)",
    "Tile (defaults)": f"Tile({MOTIF}, 1, 1, seed=6)",
    "Tile (jitter, rotate, scale, p)": f"Tile({MOTIF}, 1, 1, jitter=0.25, rotate=90, "
    "scale_min=0.6, scale_max=1.3, probability=0.8, seed=6)",
    "Tile (unbounded motif)": "Tile(fBm(octaves=2, seed=7), 1, 1, jitter=0.25, seed=6)",
}


def field_seconds(
    expr: str, size: int, backend: str, repeat: int, periods: tuple[float, float] | None = None
) -> float | None:
    """Median wall seconds of one evaluation of ``expr`` (``periods``: tileable, with the View's
    periods); None if it cannot be evaluated."""
    try:
        program = prepare(f"View{VIEW}\nMaterial(Layer(1).height({expr}))")
    except Exception as exc:  # a primitive this checkout lacks
        print(f"  ({expr[:40]}...: {exc})")
        return None
    node = program.layers[0].channel("height").args[0]
    x, y = sample_axes(View(*VIEW), size, size)
    be = get_backend(backend)
    times = []
    for k in range(repeat + 1):
        ev = Evaluator(program, x, y, be, periods=periods)
        start = time.perf_counter()
        ev.field(node)
        if k:
            times.append(time.perf_counter() - start)
    return statistics.median(times)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--size", type=int, default=1024)
    ap.add_argument("--repeat", type=int, default=7)
    ap.add_argument("--backends", nargs="+", default=available_backends())
    args = ap.parse_args()
    pixels = args.size * args.size
    print(
        f"load average {os.getloadavg()[0]:.2f}; {args.size}x{args.size}, median of {args.repeat}"
    )
    for backend in args.backends:
        print(f"\nbackend {backend}")
        seconds = {}
        for name, expr in CASES.items():
            t = field_seconds(expr, args.size, backend, args.repeat)
            seconds[name] = t
            if t is not None:
                print(f"  {name:34s} {t * 1e9 / pixels:8.1f} ns/pixel  ({t * 1e3:7.1f} ms)")
        one = seconds["Fill(Ellipse)"]
        for name in ("Tile (defaults)", "Tile (jitter, rotate, scale, p)"):
            if one and seconds[name]:
                print(f"  {name} / Fill(Ellipse): {seconds[name] / one:.1f}x (target <= 12x)")
    print(f"\nload average {os.getloadavg()[0]:.2f}")


if __name__ == "__main__":
    main()
