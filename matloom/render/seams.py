"""Seam ratios of a program pooled over renders with shifted Views (for checks and reports).

The seam ratio of one render (:func:`matloom.engine.tiling.seam_ratio`) is a statistic of one
line of texels: a pattern line that lies on the View's edge (bricks from the origin, cells of
Hash or Weave) makes it high although the map repeats exactly, and a map of a few sharp edges
makes it noisy. :func:`seam_ratios_over_offsets` moves the wrap edge to other places of the
pattern and sums the edge and interior means over the renders before dividing (angle maps
around their period, as in the manifest).
"""

from __future__ import annotations

import math
from typing import Any

from matloom.engine.maps import View
from matloom.engine.tiling import magnitude, map_periods, ratio, seam_parts

__all__ = ["seam_ratios_over_offsets"]

#: The golden ratio's fractional part: shifts that repeat no pattern lattice.
_GOLDEN = (math.sqrt(5.0) - 1.0) / 2.0


def seam_ratios_over_offsets(
    program: Any, width: int, height: int, offsets: int = 4, **kwargs: Any
) -> dict[str, float]:
    """The seam ratio of every map pooled over ``offsets`` tileable renders whose View is
    shifted by fractions of its size (golden-ratio steps, which fall on no lattice of a
    pattern; the periods stay the View's). Only meaningful for programs that repeat in the
    whole plane (a pattern whose cells do not divide the View is cut differently by each
    shifted View). With few shifts the pool still depends on where they put the wrap edge
    relative to a lattice pattern's lines (docs/tileable.md). ``kwargs`` go to ``evaluate``."""
    from matloom.engine.evaluate import evaluate, prepare

    prog = prepare(program)
    x1, y1, x2, y2 = prog.view_tuple
    sums: dict[str, list[float]] = {}
    scale: dict[str, float] = {}
    periods = map_periods()
    for k in range(1, offsets + 1):
        f = (k * _GOLDEN) % 1.0  # 0.618, 0.236, 0.854, ...: off any lattice of a pattern
        sx, sy = (x2 - x1) * f, (y2 - y1) * ((f + 0.5) % 1.0)
        view = View(x1 + sx, y1 + sy, x2 + sx, y2 + sy, tileable=True)
        maps = evaluate(prog, width, height, view=view, **kwargs)
        for name, array in maps.arrays().items():
            period = periods.get(name)
            edge, inner = seam_parts(array, period)
            size = magnitude(array) if period is None else period
            scale[name] = max(scale.get(name, 0.0), size)
            acc = sums.setdefault(name, [0.0, 0.0])
            acc[0] += edge
            acc[1] += inner
    return {name: round(ratio(e, i, scale[name]), 4) for name, (e, i) in sums.items()}
