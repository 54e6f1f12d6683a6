"""The primitives' own periods: whether their cells fit a frame's periods (``Period.misfit``).

Each rule reads the primitive's static parameters (``param(name)``, as the evaluator uses them)
and a frame's View periods (Px, Py) and returns the checker's W009 message and hint when the
primitive cannot repeat with them, None when it can. They state what the engine does:

* **fBm, Worley, Tile** (lattices the engine snaps and wraps): too many cells per period to
  wrap (:func:`~matloom.ops.periodic.wraps`; fBm per octave, as the noise plan's
  :func:`~matloom.ops.periodic.simplex_wraps`, Tile as ``TileParams.tiled``).
* **Bricks** and **Weave** (patterns with cells of a given size or frequency): a View period
  that is not a whole number of bricks, courses or thread repeats; the message names the
  nearest parameter value (and, for Bricks, the nearest View) that tiles.

Pure Python (no numpy, no engine).
"""

from __future__ import annotations

import math

from matloom.ops.octaves import octave_schedule
from matloom.ops.period import Param, Periods, whole
from matloom.ops.periodic import MAX_PERIOD_CELLS, simplex_wraps, wraps

__all__ = ["bricks", "fbm", "frequencies", "tile", "weave", "worley"]

Misfit = tuple[str, str | None] | None


def frequencies(param: Param) -> tuple[float, float]:
    """(fx, fy) of a noise: ``base_freq_x``/``base_freq_y``, each defaulting to ``base_freq``."""
    base = float(param("base_freq"))
    fx, fy = param("base_freq_x"), param("base_freq_y")
    return float(base if fx is None else fx), float(base if fy is None else fy)


# ------------------------------------------------------------------ lattices
def _too_many(name: str) -> Misfit:
    return (
        f"{name} has more than {MAX_PERIOD_CELLS:,} cells per View period (or a count past the "
        "float range), too many to wrap, so it does not repeat with the View",
        "use a lower frequency (larger cells) or a smaller View",
    )


def fbm(name: str, param: Param, periods: Periods) -> Misfit:
    """fBm: every octave's lattice must be wrappable (as the noise plan decides)."""
    fx, fy = frequencies(param)
    octaves = int(param("octaves"))
    lacunarity, gain = float(param("lacunarity")), float(param("gain"))
    schedule = octave_schedule(octaves, lacunarity, gain, fx, fy)
    if simplex_wraps(schedule.freqs_x, schedule.freqs_y, periods):
        return None
    return _too_many(name)


def worley(name: str, param: Param, periods: Periods) -> Misfit:
    """Worley: the cells per period must be wrappable (as ``plan_worley`` decides)."""
    fx, fy = frequencies(param)
    if wraps(fx * periods[0]) and wraps(fy * periods[1]):
        return None
    return _too_many(name)


def tile(name: str, param: Param, periods: Periods) -> Misfit:
    """Tile: columns, rows and the row offset over the rows must be wrappable (as
    ``TileParams.tiled`` decides)."""
    px, py = periods
    across = _quotient(px, float(param("width")))
    up = _quotient(py, float(param("height")))
    if wraps(across) and wraps(up) and wraps(float(param("offset")) * max(1, round(up))):
        return None
    return _too_many(name)


# ------------------------------------------------------------------ patterns
def bricks(name: str, param: Param, periods: Periods) -> Misfit:
    """Bricks: whole bricks along and courses across each period, and a course offset that
    adds up to whole bricks over the courses."""
    bw, bh = float(param("brick_width")), float(param("brick_height"))
    offset = float(param("offset"))
    rows = param("axis") == "row"
    along_p, across_p = (periods[0], periods[1]) if rows else (periods[1], periods[0])
    size_a, size_c = (bw, bh) if rows else (bh, bw)
    names = ("brick_width", "brick_height") if rows else ("brick_height", "brick_width")
    n_a, n_c = _quotient(along_p, size_a), _quotient(across_p, size_c)
    bad = []
    fixes = []
    if whole(n_a) is None or not wraps(n_a):
        bad.append(f"{names[0]}={_fmt(size_a)} gives {_fmt(n_a)} bricks per View period")
        fixes.append(_size_fix(names[0], along_p, n_a))
    if whole(n_c) is None or not wraps(n_c):
        bad.append(f"{names[1]}={_fmt(size_c)} gives {_fmt(n_c)} courses per View period")
        fixes.append(_size_fix(names[1], across_p, n_c))
    courses = _nearest_count(n_c) or 1
    shift = offset * courses
    if whole(shift) is None or not wraps(shift):
        bad.append(f"offset={_fmt(offset)} does not repeat over {courses} courses")
        fixes.append(f"offset={_fmt(round(shift) / courses)}" if wraps(shift) else "")
    if not bad:
        return None
    view = _view_hint(along_p, size_a, across_p, size_c, rows)
    hint = f"nearest tiling: {', '.join(f for f in fixes if f) or 'none in range'}"
    return f"{name}: {'; '.join(bad)}", hint + (f" (or {view})" if view else "")


def weave(name: str, param: Param, periods: Periods) -> Misfit:
    """Weave: whole thread repeats across (``over + under`` cells) and up (the rows after
    which the draft repeats) each period."""
    fx, fy = frequencies(param)
    repeat = int(param("over")) + int(param("under"))
    shift = int(param("shift"))
    rows = repeat // math.gcd(shift, repeat) if shift % repeat else 1
    cols_n, rows_n = fx * periods[0] / repeat, fy * periods[1] / rows
    bad, fixes = [], []
    if whole(cols_n) is None or not wraps(cols_n):
        bad.append(f"{_fmt(fx * periods[0])} thread cells across the View (repeat {repeat})")
        fixes.append(_freq_fix("base_freq_x", cols_n, repeat, periods[0]))
    if whole(rows_n) is None or not wraps(rows_n):
        bad.append(f"{_fmt(fy * periods[1])} thread cells up the View (repeat {rows})")
        fixes.append(_freq_fix("base_freq_y", rows_n, rows, periods[1]))
    if not bad:
        return None
    return (
        f"{name}: {'; '.join(bad)}",
        f"nearest tiling: {', '.join(f for f in fixes if f) or 'none in range'}",
    )


def _fmt(v: float) -> str:
    return f"{v:.4g}"


def _quotient(a: float, b: float) -> float:
    """a / b, inf when b is 0 (no whole number of cells of size 0 fill a period)."""
    return a / b if b else math.inf


def _nearest_count(n: float) -> int | None:
    """The whole number (>= 1) of cells nearest to ``n``; None when ``n`` is not finite (a
    size or frequency that over- or underflows the period): no nearest value to suggest."""
    return max(1, round(n)) if math.isfinite(n) else None


def _size_fix(name: str, period: float, count: float) -> str:
    """``name=value``: the size that fits the whole number of cells nearest to ``count`` in
    ``period`` ("" when there is none in range, as for a count past the float range)."""
    k = _nearest_count(count)
    return "" if k is None or not wraps(k) else f"{name}={_fmt(period / k)}"


def _view_hint(along_p: float, size_a: float, across_p: float, size_c: float, rows: bool) -> str:
    """The nearest View (from the origin of the frame's periods) that the pattern tiles ("" when
    a size over- or underflows the period)."""
    ka, kc = _nearest_count(_quotient(along_p, size_a)), _nearest_count(_quotient(across_p, size_c))
    if ka is None or kc is None:
        return ""
    wa, wc = ka * size_a, kc * size_c
    w, h = (wa, wc) if rows else (wc, wa)
    return f"a View {_fmt(w)} x {_fmt(h)} in its frame"


def _freq_fix(name: str, repeats: float, repeat: int, period: float) -> str:
    """``name=value``: the frequency that fits the whole number of repeats nearest to
    ``repeats`` in ``period`` ("" when there is none in range)."""
    k = _nearest_count(repeats)
    return "" if k is None or not wraps(k) else f"{name}={_fmt(k * repeat / period)}"
