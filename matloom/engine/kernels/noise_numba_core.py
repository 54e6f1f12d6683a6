"""numba building blocks of the OpenSimplex fBm kernels (compiled into the calling kernels).

* ``jit_kernel``: ``njit(cache=True, fastmath=False)`` that falls back to uncached compilation
  when numba finds no writable cache location (numba raises at decoration time otherwise).
* ``noise_chunk``: OpenSimplex 2-D noise for a chunk of points in three passes -- seed-free
  geometry (vectorised), one gradient-table look-up per vertex (scalar), then attenuation and
  dot products (vectorised).  It is bit-identical to opensimplex 0.4.5.1's ``_noise2``: every
  floating-point operation of the reference is kept, with the same operands in the same order;
  only the branches became selects.
* ``frame``/``vertex_weight``/``decode_dot``: the pieces, shared with the seed-batch kernel.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import numpy as np

from matloom.engine.kernels.jit import jit
from matloom.engine.kernels.opensimplex import NORM_CONSTANT2
from matloom.ops.periodic import SQUISH_CONSTANT2, STRETCH_CONSTANT2

#: Points per chunk in ``noise_chunk`` (keeps the per-thread scratch buffers in L1).
CHUNK = 256
_SQ = SQUISH_CONSTANT2
_ST = STRETCH_CONSTANT2
_NORM = NORM_CONSTANT2
#: |floor| beyond this (or NaN/inf) is replaced by 0 before integer conversion; such points get
#: attenuation NaN/0 and contribute nothing, as in the reference (which converts garbage).
_SAFE_FLOOR = 4.0e18


def jit_kernel(parallel: bool = False, inline: bool = False) -> Callable[[Callable[..., Any]], Any]:
    """:func:`matloom.engine.kernels.jit.jit` with ``fastmath=False`` (bit-exact arithmetic).

    ``error_model="numpy"``: float division by zero gives inf/NaN like numpy instead of raising.
    ``nogil``: callers may run serial kernels on row ranges from several threads.
    ``inline=True`` inlines the function into its callers at numba IR level (small helpers).
    """
    return jit(parallel=parallel, inline=inline, nogil=True, fastmath=False, error_model="numpy")


@jit_kernel(parallel=False, inline=True)
def frame(x: float, y: float) -> tuple[float, float, float, float, float, float, float]:
    """Seed-independent geometry of the reference ``_noise2`` at (x, y).

    Returns (xsb, ysb, dx0, dy0, ext_x, ext_y, base) as floats: the rhombus cell (floored
    stretched coordinates), the displacement from its origin, the extra-vertex offset and the
    base-vertex offset (0 -> vertex (0,0), 1 -> vertex (1,1)).  The four vertices, in the
    reference's summation order, are (1,0), (0,1), (base, base), (ext_x, ext_y).
    """
    stretch_offset = (x + y) * _ST
    xs = x + stretch_offset
    ys = y + stretch_offset
    xsb = np.floor(xs)
    ysb = np.floor(ys)
    squish_offset = (xsb + ysb) * _SQ
    dx0 = x - (xsb + squish_offset)
    dy0 = y - (ysb + squish_offset)
    xins = xs - xsb
    yins = ys - ysb
    in_sum = xins + yins
    z_lo = 1.0 - in_sum
    z_hi = 2.0 - in_sum
    near_lo = (z_lo > xins) | (z_lo > yins)
    near_hi = (z_hi < xins) | (z_hi < yins)
    x_wins = xins > yins
    lower = in_sum <= 1.0
    ext_x_lo = 1.0 if (not near_lo) or x_wins else -1.0
    ext_y_lo = 1.0 if (not near_lo) or (not x_wins) else -1.0
    ext_x_hi = 2.0 if near_hi and x_wins else 0.0
    ext_y_hi = 2.0 if near_hi and (not x_wins) else 0.0
    ext_x = ext_x_lo if lower else ext_x_hi
    ext_y = ext_y_lo if lower else ext_y_hi
    base = 0.0 if lower else 1.0
    xsb = xsb if abs(xsb) < _SAFE_FLOOR else 0.0
    ysb = ysb if abs(ysb) < _SAFE_FLOOR else 0.0
    return xsb, ysb, dx0, dy0, ext_x, ext_y, base


@jit_kernel(parallel=False, inline=True)
def lattice_key(xsb: float, ysb: float, off_x: float, off_y: float) -> int:
    """``((xsb + off_x) & 255) << 8 | ((ysb + off_y) & 255)``: the vertex's gradient-table key."""
    ix = (np.int64(xsb) + np.int64(off_x)) & 0xFF
    iy = (np.int64(ysb) + np.int64(off_y)) & 0xFF
    return (ix << 8) | iy


@jit_kernel(parallel=False, inline=True)
def vertex_weight(
    dx0: float, dy0: float, off_x: float, off_y: float
) -> tuple[float, float, float, bool]:
    """(dx, dy, attn^4, attn > 0) of vertex (off_x, off_y).

    ``(d0 - off) - (off_x + off_y) * SQUISH`` is bit-identical to each of the reference's
    per-vertex formulas (``dx0 - 1 - SQUISH``, ``dx0 - 1 - 2 * SQUISH``, ``dx0 + 1``, ...):
    subtracting 0.0, or a negated small integer, is exact.
    """
    squish = (off_x + off_y) * _SQ
    dx = (dx0 - off_x) - squish
    dy = (dy0 - off_y) - squish
    attn = 2.0 - dx * dx - dy * dy
    attn2 = attn * attn
    return dx, dy, attn2 * attn2, attn > 0.0


@jit_kernel(parallel=False, inline=True)
def decode_dot(grad: int, dx: float, dy: float) -> float:
    """``g1 * dx + g2 * dy`` for gradient number ``grad`` = (perm[...] & 14) >> 1, in 0..7.

    The table (5,2), (2,5), (-5,2), (-2,5), (5,-2), (2,-5), (-5,-2), (-2,-5) is decoded from the
    bits (bit 0 swaps 5/2, bit 1 negates g1, bit 2 negates g2) so the loop stays vectorisable.
    """
    swap = (grad & 1) != 0
    g1 = 2.0 if swap else 5.0
    g2 = 5.0 if swap else 2.0
    g1 = -g1 if (grad & 2) != 0 else g1
    g2 = -g2 if (grad & 4) != 0 else g2
    return g1 * dx + g2 * dy


@jit_kernel(parallel=False)
def _chunk_geometry(
    xb: np.ndarray, yb: np.ndarray, n: int, keys: np.ndarray, geo: np.ndarray
) -> None:
    """Pass A: vertex gradient-table keys and (dx0, dy0, ext_x, ext_y, base) (vectorisable)."""
    for j in range(n):
        xsb, ysb, dx0, dy0, ext_x, ext_y, base = frame(xb[j], yb[j])
        keys[0, j] = lattice_key(xsb, ysb, 1.0, 0.0)
        keys[1, j] = lattice_key(xsb, ysb, 0.0, 1.0)
        keys[2, j] = lattice_key(xsb, ysb, base, base)
        keys[3, j] = lattice_key(xsb, ysb, ext_x, ext_y)
        geo[0, j] = dx0
        geo[1, j] = dy0
        geo[2, j] = ext_x
        geo[3, j] = ext_y
        geo[4, j] = base


@jit_kernel(parallel=False)
def _chunk_grads(n: int, keys: np.ndarray, grad_table: np.ndarray, grads: np.ndarray) -> None:
    """Pass B: gradient numbers from the seed's 256 x 256 table (scalar look-ups)."""
    for v in range(4):
        for j in range(n):
            grads[v, j] = grad_table[keys[v, j]]


@jit_kernel(parallel=False, inline=True)
def _term(dx0: float, dy0: float, off_x: float, off_y: float, grad: int) -> float:
    """One vertex's contribution ``attn^4 * (g . d)``, or 0 where attn <= 0 (or NaN)."""
    dx, dy, weight, active = vertex_weight(dx0, dy0, off_x, off_y)
    term = weight * decode_dot(grad, dx, dy)
    return term if active else 0.0


@jit_kernel(parallel=False)
def _chunk_values(n: int, geo: np.ndarray, grads: np.ndarray, values: np.ndarray) -> None:
    """Pass C: attenuations and dot products, summed in the reference's order (vectorisable)."""
    for j in range(n):
        dx0, dy0, ext_x, ext_y, base = geo[0, j], geo[1, j], geo[2, j], geo[3, j], geo[4, j]
        value = _term(dx0, dy0, 1.0, 0.0, grads[0, j])
        value += _term(dx0, dy0, 0.0, 1.0, grads[1, j])
        value += _term(dx0, dy0, base, base, grads[2, j])
        value += _term(dx0, dy0, ext_x, ext_y, grads[3, j])
        values[j] = value / _NORM


@jit_kernel(parallel=False)
def noise_chunk(
    xb: np.ndarray, yb: np.ndarray, n: int, grad_table: np.ndarray, scratch: tuple
) -> None:
    """OpenSimplex noise at (xb[j], yb[j]) for j < n into ``scratch[3]`` (float64 inputs).

    ``scratch`` = ``new_scratch()``: (keys, geometry, gradient numbers, values) buffers.
    """
    keys, geo, grads, values = scratch
    _chunk_geometry(xb, yb, n, keys, geo)
    _chunk_grads(n, keys, grad_table, grads)
    _chunk_values(n, geo, grads, values)


@jit_kernel(parallel=False, inline=True)
def new_scratch() -> tuple:
    """Per-thread buffers for ``noise_chunk``: keys, geometry, gradient numbers, values."""
    return (
        np.empty((4, CHUNK), dtype=np.uint32),
        np.empty((5, CHUNK)),
        np.empty((4, CHUNK), dtype=np.uint8),
        np.empty(CHUNK),
    )


@jit_kernel(parallel=False, inline=True)
def finish_fbm(total: float, norm: float, to_01: bool) -> float:
    """Divide by the amplitude sum, optionally map to [0, 1], and clamp (like ``np.clip``)."""
    out = total / norm
    low = -1.0
    if to_01:
        out = (out + 1) / 2
        low = 0.0
    if out < low:
        return low
    if out > 1.0:
        return 1.0
    return out
