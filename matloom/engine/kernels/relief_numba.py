"""numba normals and cavity AO, bit-identical to :mod:`matloom.engine.relief`.

Both kernels repeat the float32 operations of the numpy reference path in the same order (the
same divisors rounded to float32, the AO taps summed in ascending offset order with the same
weights), so their results are identical; they only avoid the temporaries and run the rows on
threads (serial ``nogil`` kernels over row ranges: a ``prange`` kernel takes far longer to
compile). AO windows wider than ``relief.EXACT_TAP_LIMIT`` taps stay on the numpy path.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np

from matloom.engine import relief
from matloom.engine.kernels.composite_numba import _jit
from matloom.engine.kernels.threads import parallel_rows


@_jit(inline=True)
def _clip01(v: np.float32) -> np.float32:
    if v < np.float32(0.0):
        return np.float32(0.0)
    if v > np.float32(1.0):
        return np.float32(1.0)
    return v


@_jit()
def normals_kernel(h, dx1, dx2, dy1, dy2, out, first, last):  # type: ignore[no-untyped-def]
    """out[i, j] = normalise(-dH/dX, -dH/dY, 1) from central differences (one-sided at edges),
    for rows ``first``..``last - 1`` (serial and ``nogil``: :func:`normals` splits the rows
    over threads).

    ``dx1``/``dx2`` are float32(dx) and float32(2 dx) (likewise for y), as numpy rounds them.
    Neighbours are read through shifted slices so that the loops vectorise. ``sx``/``sy`` are
    reused across rows: every row writes the same entries, the others stay 0.
    """
    rows, cols = h.shape
    one = np.float32(1.0)
    sx = np.zeros(cols, np.float32)
    sy = np.zeros(cols, np.float32)
    for i in range(first, last):
        row = h[i]
        if cols > 2:
            right, left, mid = row[2:], row[:-2], sx[1:-1]
            for j in range(cols - 2):
                mid[j] = (right[j] - left[j]) / dx2
        if cols > 1:
            sx[0] = (row[1] - row[0]) / dx1
            sx[cols - 1] = (row[cols - 1] - row[cols - 2]) / dx1
        if rows > 1:
            below, above = h[min(i + 1, rows - 1)], h[max(i - 1, 0)]
            div = dy2 if (0 < i < rows - 1) else dy1
            for j in range(cols):
                sy[j] = (below[j] - above[j]) / div
        normal = out[i]
        for j in range(cols):
            inv = one / np.sqrt(sx[j] * sx[j] + sy[j] * sy[j] + one)
            normal[j, 0] = -sx[j] * inv
            normal[j, 1] = sy[j] * inv
            normal[j, 2] = inv


@_jit()
def _box_row(src, weights, divisor, acc):  # type: ignore[no-untyped-def]
    """acc = edge-clamped weighted window sums of the 1-D ``src`` (ascending taps) / divisor."""
    width = src.size
    reach = (weights.size - 1) // 2
    acc[:] = np.float32(0.0)
    for o in range(weights.size):
        off = o - reach
        w = weights[o]
        lo = min(max(-off, 0), width)
        hi = max(min(width - off, width), lo)
        edge0 = src[0] * w
        edge1 = src[width - 1] * w
        for j in range(lo):
            acc[j] += edge0
        inner, shifted = acc[lo:hi], src[lo + off : hi + off]  # slices keep the loop vectorised
        for j in range(hi - lo):
            inner[j] += shifted[j] * w
        for j in range(hi, width):
            acc[j] += edge1
    for j in range(width):
        acc[j] = acc[j] / divisor


@_jit()
def _ao_rows(h, wx, div_x, mean, first, last):  # type: ignore[no-untyped-def]
    """Pass 1 of the AO, rows ``first``..``last - 1``: horizontal box means of h into mean."""
    for i in range(first, last):
        _box_row(h[i], wx, div_x, mean[i])


@_jit()
def _ao_columns(h, wy, div_y, depth, strength, mean, out, first, last):  # type: ignore[no-untyped-def]
    """Pass 2, rows ``first``..``last - 1``: vertical box of ``mean`` (all rows of pass 1),
    then ao = clip(1 - s clip((m - h) / d))."""
    rows, cols = h.shape
    reach = (wy.size - 1) // 2
    for i in range(first, last):
        acc = out[i]
        acc[:] = np.float32(0.0)
        for o in range(wy.size):
            src = mean[min(max(i + o - reach, 0), rows - 1)]
            w = wy[o]
            for j in range(cols):
                acc[j] += src[j] * w
        for j in range(cols):
            cavity = _clip01((acc[j] / div_y - h[i, j]) / depth)
            acc[j] = _clip01(np.float32(1.0) - strength * cavity)


#: Below this many texels the kernels run on the calling thread only (starting threads costs
#: more than it saves, and far more on a machine whose cores are busy with other processes).
PARALLEL_MIN_TEXELS = 1 << 18


def _split_rows(h: np.ndarray, work: Callable[[int, int], None]) -> None:
    """``work(first, last)`` over the rows of h: on threads from PARALLEL_MIN_TEXELS up."""
    if h.size >= PARALLEL_MIN_TEXELS:
        parallel_rows(h.shape[0], h.shape[1], work)
    else:
        work(0, h.shape[0])


def tap_weights(radius: float) -> tuple[np.ndarray, np.float32] | None:
    """(float32 tap weights, float32 divisor) of the reference box, or None past the tap limit."""
    whole, frac = relief._split_radius(radius)
    edge = [frac] if frac > 0 else []
    weights = edge + [1.0] * (2 * whole + 1) + edge
    if len(weights) > relief.EXACT_TAP_LIMIT:
        return None
    divisor = 2 * whole + 1 if frac == 0 else 2 * radius + 1
    return np.array(weights, dtype=np.float32), np.float32(divisor)


def normals(height: np.ndarray, dx: float, dy: float) -> np.ndarray:
    """Same as :func:`matloom.engine.relief.normals` (identical float32 results)."""
    h = np.ascontiguousarray(height, dtype=np.float32)
    out = np.empty(h.shape + (3,), dtype=np.float32)
    with np.errstate(all="ignore"):
        steps = (np.float32(dx), np.float32(2.0 * dx), np.float32(dy), np.float32(2.0 * dy))
        _split_rows(h, lambda a, b: normals_kernel(h, *steps, out, a, b))
    return out


def ambient_occlusion(
    height: np.ndarray,
    dx: float,
    radius_x: float = relief.DEFAULT_AO_RADIUS_TEXELS,
    radius_y: float = relief.DEFAULT_AO_RADIUS_TEXELS,
    strength: float = relief.DEFAULT_AO_STRENGTH,
) -> np.ndarray:
    """Same as :func:`matloom.engine.relief.ambient_occlusion` (identical float32 results);
    windows wider than the exact tap limit use the numpy implementation."""
    taps_x, taps_y = tap_weights(radius_x), tap_weights(radius_y)
    if taps_x is None or taps_y is None:
        return relief.ambient_occlusion(height, dx, radius_x, radius_y, strength)
    h = np.ascontiguousarray(height, dtype=np.float32)
    mean = np.empty_like(h)
    out = np.empty_like(h)
    depth = np.float32(max(radius_x, 1) * float(dx))
    (wx, div_x), (wy, div_y) = taps_x, taps_y
    with np.errstate(all="ignore"):
        gain = np.float32(strength)
        _split_rows(h, lambda a, b: _ao_rows(h, wx, div_x, mean, a, b))
        _split_rows(h, lambda a, b: _ao_columns(h, wy, div_y, depth, gain, mean, out, a, b))
    return out
