"""Seed-batched fBm for fast seed sweeps (numba).

Everything that does not depend on the seed -- the per-octave coordinates, the simplex cell,
the four vertex displacements and their attenuation weights -- is computed once per pixel and
octave and reused for all S seeds.  Only the gradient choice depends on the seed.  It is read
from a (65536, S) uint8 table ``grads[key, s]`` (gradient number of lattice vertex ``key`` for
seed s), built once per call for the vertex keys the image actually uses, so that the inner
loop over seeds is a contiguous, branch-free, vectorisable accumulation.

The accumulation is fixed point: each vertex's weighted gradient products are rounded to
integers in units of 2**-k and summed exactly in int32 (8 lanes per AVX2 vector instead of 4
float64 lanes).  k is chosen from the octave coefficients so that no sum can overflow; the
rounding error is then at most 4 * octaves units of 2**-k (about 1e-7 for 8 octaves), on top of
the float32 output rounding, so results stay within 1e-6 of per-seed ``fbm``.  If no k meets
that bound (extreme gains), the batch falls back to per-seed ``fbm`` calls.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
from numba import prange

from matloom.engine.kernels.noise import FbmPlan
from matloom.engine.kernels.noise_numba_core import (
    finish_fbm,
    frame,
    jit_kernel,
    lattice_key,
    vertex_weight,
)
from matloom.engine.kernels.opensimplex import FBM_SCALE, NORM_CONSTANT2, perms_for_seeds

__all__ = ["seed_batch", "fixed_point_shift"]

#: Pixels accumulated together before their (seed-major) output is written.
_PIXEL_BLOCK = 16


@jit_kernel(parallel=False, inline=True)
def _point(
    xs: np.ndarray,
    ys: np.ndarray,
    separable: bool,
    k: int,
    i: int,
    j: int,
    width: int,
) -> tuple[float, float]:
    """Octave-k coordinates of pixel (i, j): separable axes or flat (O, H * W) grids."""
    if separable:
        return xs[k, j], ys[k, i]
    return xs[k, i * width + j], ys[k, i * width + j]


@jit_kernel(parallel=False)
def _mark_used_keys(
    xs: np.ndarray,
    ys: np.ndarray,
    separable: bool,
    height: int,
    width: int,
    mask: np.ndarray,
    used: np.ndarray,
) -> None:
    """used[key] = True for every lattice-vertex key any pixel/octave touches (only pixels
    where ``mask`` is set, unless it is the (1, 1) "everywhere" mask)."""
    masked = mask.shape[0] > 1 or mask.shape[1] > 1
    for i in range(height):
        for j in range(width):
            if masked and not mask[i, j]:
                continue
            for k in range(xs.shape[0]):
                x, y = _point(xs, ys, separable, k, i, j, width)
                xsb, ysb, _, _, ext_x, ext_y, base = frame(x, y)
                used[lattice_key(xsb, ysb, 1.0, 0.0)] = True
                used[lattice_key(xsb, ysb, 0.0, 1.0)] = True
                used[lattice_key(xsb, ysb, base, base)] = True
                used[lattice_key(xsb, ysb, ext_x, ext_y)] = True


@jit_kernel(parallel=False)
def _fill_gradient_row(
    key: int,
    perm_cols: np.ndarray,
    grad_half: np.ndarray,
    grads: np.ndarray,
) -> None:
    """grads[key, s] = (perm_s[(perm_s[key >> 8] + (key & 255)) & 255] & 14) >> 1."""
    column = perm_cols[key >> 8]
    low = key & 0xFF
    for s in range(column.size):
        grads[key, s] = grad_half[s, (column[s] + low) & 0xFF]


@jit_kernel(parallel=False, inline=True)
def _accumulate(
    acc: np.ndarray,
    grads: np.ndarray,
    xsb: float,
    ysb: float,
    dx0: float,
    dy0: float,
    off_x: float,
    off_y: float,
    coef: float,
) -> None:
    """acc[s] += round(coef * attn^4 * (g_s . d)) of one vertex, for all seeds s (int32).

    ``coef`` includes the fixed-point scale 2**k.  The four products 5*wx, 2*wx, 5*wy, 2*wy
    are rounded once; each seed picks +-one x product and +-one y product by its gradient
    number's bits (bit 0 swaps 5/2, bit 1 negates x, bit 2 negates y).
    """
    dx, dy, weight, active = vertex_weight(dx0, dy0, off_x, off_y)
    if active:
        wx = weight * coef * dx
        wy = weight * coef * dy
        five_x = np.int32(np.floor(5.0 * wx + 0.5))
        two_x = np.int32(np.floor(2.0 * wx + 0.5))
        five_y = np.int32(np.floor(5.0 * wy + 0.5))
        two_y = np.int32(np.floor(2.0 * wy + 0.5))
        row = grads[lattice_key(xsb, ysb, off_x, off_y)]
        for s in range(acc.size):
            g = row[s]
            swap = (g & 1) != 0
            a = two_x if swap else five_x
            b = five_y if swap else two_y
            a = -a if (g & 2) != 0 else a
            b = -b if (g & 4) != 0 else b
            acc[s] += np.int32(a + b)


@jit_kernel(parallel=False)
def _fbm_batch_row(
    i: int,
    xs: np.ndarray,
    ys: np.ndarray,
    separable: bool,
    coefs: np.ndarray,
    unit: float,
    to_01: bool,
    grads: np.ndarray,
    mask: np.ndarray,
    out: np.ndarray,
) -> None:
    """Row i of out[s, i, j] = fBm for seed s; ``unit`` = 2**-k converts the int32 sums.
    Pixels where ``mask`` is clear (unless it is (1, 1)) get the fBm of 0, a placeholder.

    Pixels are accumulated in blocks of ``_PIXEL_BLOCK`` along the row so that the output for
    each seed is written as contiguous runs (the (S, H, W) layout is seed-major).
    """
    n_seeds, _, width = out.shape
    masked = mask.shape[0] > 1 or mask.shape[1] > 1
    acc = np.empty((_PIXEL_BLOCK, n_seeds), dtype=np.int32)
    for j0 in range(0, width, _PIXEL_BLOCK):
        n = min(_PIXEL_BLOCK, width - j0)
        for jj in range(n):
            row_acc = acc[jj]
            row_acc[:] = 0
            if masked and not mask[i, j0 + jj]:
                continue
            for k in range(coefs.size):
                x, y = _point(xs, ys, separable, k, i, j0 + jj, width)
                xsb, ysb, dx0, dy0, ext_x, ext_y, base = frame(x, y)
                c = coefs[k]
                _accumulate(row_acc, grads, xsb, ysb, dx0, dy0, 1.0, 0.0, c)
                _accumulate(row_acc, grads, xsb, ysb, dx0, dy0, 0.0, 1.0, c)
                _accumulate(row_acc, grads, xsb, ysb, dx0, dy0, base, base, c)
                _accumulate(row_acc, grads, xsb, ysb, dx0, dy0, ext_x, ext_y, c)
        for s in range(n_seeds):
            for jj in range(n):
                out[s, i, j0 + jj] = finish_fbm(acc[jj, s] * unit, 1.0, to_01)


@jit_kernel(parallel=True)
def _fbm_batch_kernel(
    keys: np.ndarray,
    perm_cols: np.ndarray,
    grad_half: np.ndarray,
    grads: np.ndarray,
    xs: np.ndarray,
    ys: np.ndarray,
    separable: bool,
    coefs: np.ndarray,
    unit: float,
    to_01: bool,
    mask: np.ndarray,
    out: np.ndarray,
) -> None:
    """Fill the gradient rows of the used vertex keys, then the rows of the output (parallel)."""
    for r in prange(keys.size):
        _fill_gradient_row(keys[r], perm_cols, grad_half, grads)
    for i in prange(out.shape[1]):
        _fbm_batch_row(i, xs, ys, separable, coefs, unit, to_01, grads, mask, out)


def fixed_point_shift(coefs: Sequence[float]) -> int | None:
    """Largest k such that int32 sums of the rounded vertex terms cannot overflow, or None.

    A vertex term is ``coef * attn^4 * (g . d)`` with attn = 2 - |d|^2 > 0 and |g| = sqrt(29);
    its magnitude peaks at |d|^2 = 2/9: (16/9)^4 * sqrt(2/9) * sqrt(29) < 25.4 * |coef|.  Four
    vertices per octave, plus one unit of rounding each, must stay below 2**30 (2x margin).
    None when the resulting rounding bound 4 * octaves * 2**-k would exceed 2.5e-7.
    """
    worst = sum(4.0 * 25.4 * abs(c) for c in coefs)
    if not np.isfinite(worst):
        return None
    rounding_units = 4.0 * len(coefs)
    k = 40
    while k > 0 and worst * 2.0**k + rounding_units > 2.0**30:
        k -= 1
    if rounding_units * 2.0**-k > 2.5e-7:
        return None
    return k


def seed_batch(plan: FbmPlan, seeds: list[int], mask: np.ndarray | None) -> np.ndarray | None:
    """fBm of ``plan`` for every seed at once: float32 (S, H, W); None (per-seed calls) when no
    fixed-point scale is safe (extreme gains).

    With a boolean ``mask`` (the 2-D broadcast shape of x and y) only the texels where it is
    set are computed; the others hold the fBm of a zero sum (0.5 with ``to_01``, else 0), a
    placeholder inside the fBm's range (coverage culling, see matloom.engine.cull).
    """
    scale = FBM_SCALE / (NORM_CONSTANT2 * plan.norm)
    coefs = np.array([scale * a for a in plan.schedule.amps], dtype=np.float64)
    shift = fixed_point_shift(coefs.tolist())
    if shift is None:  # extreme gains: no safe fixed-point scale, evaluate seed by seed
        return None
    xs, ys, height, width = plan.octave_coords()
    out = np.empty((len(seeds), height, width), dtype=np.float32)
    if out.size == 0:
        return out
    separable = plan.layout.separable
    everywhere = mask is None or np.ndim(mask) != 2
    mask2 = np.ones((1, 1), np.bool_) if everywhere else np.ascontiguousarray(mask, np.bool_)
    used = np.zeros(1 << 16, dtype=np.bool_)
    _mark_used_keys(xs, ys, separable, height, width, mask2, used)
    perms = perms_for_seeds(seeds)
    perm_cols = np.ascontiguousarray(perms.T.astype(np.int32))
    grad_half = np.ascontiguousarray(((perms & 0x0E) >> 1).astype(np.uint8))
    grads = np.empty((1 << 16, len(seeds)), dtype=np.uint8)
    keys = np.flatnonzero(used)
    scaled = coefs * 2.0**shift
    unit = 2.0**-shift
    args = (xs, ys, separable, scaled, unit, plan.to_01, mask2, out)
    _fbm_batch_kernel(keys, perm_cols, grad_half, grads, *args)
    return out
