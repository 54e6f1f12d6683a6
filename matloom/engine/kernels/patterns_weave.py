"""Weave's ``output="along"``: the position along the visible float of the thread on top.

A float is a run of consecutive cells along one thread where that thread is on top. Along a
weft (row ``row``, columns increasing) the draft place ``w = (col - row * shift) mod R``
(``R = over + under``) rises by 1 per column, so every weft float is ``under`` cells long and
starts where ``w = over``. Along a warp (column ``col``, rows increasing) ``w`` falls by
``shift`` per row, so the run depends on ``shift``: it is found by stepping through the draft
places (closed forms for ``shift = +-1 mod R``); a warp that is on top in every row of its
column (e.g. ``shift = 0``) has a float that never ends, and each cell counts as its own float.

The value is ``(k + f) / n`` in float64: ``k`` the cells of the float before this one, ``n``
the float's length and ``f`` the position in the cell along the thread (``v - row`` for the
warp, ``u - col`` for the weft, in the coordinate dtype). The work is per distinct draft place
present, not per texel. Weave has no numba kernel: both backends run this.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

#: Longest warp float (in cells) searched step by step; a longer one raises ValueError.
MAX_FLOAT_STEPS = 1 << 20


def along(
    u: np.ndarray, v: np.ndarray, cells: tuple, over: int, under: int, shift: int
) -> np.ndarray:
    """Position along the float at cell coordinates (u, v) (float64; NaN where the cell is not
    finite); ``cells`` = ``patterns.weave_cells(u, v, ...)``."""
    col, row, w, warp_on_top = cells
    frac = np.where(warp_on_top, v - row, u - col)
    frac, w, warp = np.broadcast_arrays(frac, w, warp_on_top)
    out = np.full(frac.shape, np.nan)
    finite = np.isfinite(w) & np.isfinite(frac)
    if not finite.any():
        return out
    places, first, inverse = np.unique(w[finite], return_index=True, return_inverse=True)
    before, length = _floats(places, warp[finite][first], over, under, shift)
    out[finite] = (before[inverse] + frac[finite].astype(np.float64)) / length[inverse]
    return out


def _floats(
    places: np.ndarray, warp: np.ndarray, over: int, under: int, shift: int
) -> tuple[np.ndarray, np.ndarray]:
    """(cells before, float length) as float64 for each distinct draft place (``warp``: the
    warp is on top there)."""
    repeat = over + under
    exact = repeat < 2**53
    w = places.astype(np.int64) if exact else np.array([int(p) for p in places], dtype=object)
    w = np.clip(w, 0, repeat - 1)
    before = np.clip(w - over, 0, under - 1)
    length = np.full(w.shape, under, dtype=w.dtype)
    if warp.any():
        kb, n = _warp_floats(w[warp], over, repeat, shift % repeat)
        before[warp], length[warp] = kb, n
    return before.astype(np.float64), length.astype(np.float64)


def _warp_floats(w: np.ndarray, over: int, repeat: int, step: int) -> tuple[Any, Any]:
    """(cells before, length) of the warp floats through draft places ``w`` (< over); a row
    up takes the place ``w`` to ``w - step`` (mod repeat)."""
    if step == 1:
        return over - 1 - w, np.full(w.shape, over, dtype=w.dtype)
    if step == repeat - 1:
        return w, np.full(w.shape, over, dtype=w.dtype)
    period = repeat // math.gcd(step, repeat)  # cells until a warp's draft place repeats
    back = _run(w, over, repeat, step, period)
    ahead = _run(w, over, repeat, repeat - step, period)
    endless = back >= period - 1  # the warp is on top in every row of its column
    zero = np.zeros(w.shape, dtype=w.dtype)
    return np.where(endless, zero, back), np.where(endless, zero + 1, back + 1 + ahead)


def _run(w: np.ndarray, over: int, repeat: int, step: int, period: int) -> np.ndarray:
    """Consecutive cells on top next to each place ``w`` when stepping ``w -> w + step``
    (mod repeat), at most ``period - 1``."""
    count = np.zeros(w.shape, dtype=w.dtype)
    alive = np.ones(w.shape, dtype=bool)
    cur = w.copy()
    for j in range(1, period):
        if j > MAX_FLOAT_STEPS:
            raise ValueError(f"Weave: a warp float longer than {MAX_FLOAT_STEPS} cells")
        cur = (cur + step) % repeat
        alive &= cur < over
        if not alive.any():
            break
        count += alive
    return count
