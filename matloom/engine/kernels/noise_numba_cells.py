"""numba: the Worley cell hash and feature table, and Worley's cell values and border distances.

The hash, the feature-point table and the metric key are shared with the distance loops of
:mod:`.noise_numba_worley` (and the hash with ``patterns_numba``'s brick cell values). The cell
outputs (``WorleyPlan.output`` 1: a value per cell, 2: the distance to the cell border) run
:func:`cells_row` per pixel with the arithmetic of ``noise_numpy._cells`` operation by operation
(bit-identical). Their kernels are separate from the distance kernels so that a program without
them never compiles them (cold start).
"""

from __future__ import annotations

import numpy as np
from numba import prange

from matloom.engine.kernels.noise import WORLEY_CELL_SALT, WORLEY_EDGE_SEARCH
from matloom.engine.kernels.noise_numba_core import jit_kernel
from matloom.engine.kernels.opensimplex import (
    WORLEY_HASH_CX,
    WORLEY_HASH_CY,
    WORLEY_MIX1,
    WORLEY_MIX2,
)

__all__ = ["worley_hash", "fill_table", "metric_key", "cells_kernel", "cells_batch_kernel"]


@jit_kernel(parallel=False, inline=True)
def worley_hash(cx: int, cy: int, seed_term: int, which: int) -> float:
    """The reference's cell hash in [0, 1): wrapping int64 arithmetic, *arithmetic* shifts."""
    t = cx * WORLEY_HASH_CX + cy * WORLEY_HASH_CY + seed_term + which
    t ^= t >> 33
    t *= WORLEY_MIX1
    t ^= t >> 33
    t *= WORLEY_MIX2
    t ^= t >> 33
    return (t & 0xFFFFFFFF) / 4294967296.0


@jit_kernel(parallel=False)
def fill_table(cx0: int, cy0: int, seed_term: int, tx: np.ndarray, ty: np.ndarray) -> None:
    """Feature points of cells (cx0 + c, cy0 + r) into tx[r, c], ty[r, c] (float64)."""
    for r in range(tx.shape[0]):
        cy = cy0 + r
        for c in range(tx.shape[1]):
            cx = cx0 + c
            tx[r, c] = cx + worley_hash(cx, cy, seed_term, 0)
            ty[r, c] = cy + worley_hash(cx, cy, seed_term, 1)


@jit_kernel(parallel=False, inline=True)
def metric_key(dx: float, dy: float, metric: int) -> float:
    """Squared Euclidean (0), Manhattan (1) or Chebyshev (2) length (see ``final_length``)."""
    if metric == 0:
        return dx * dx + dy * dy
    if metric == 1:
        return abs(dx) + abs(dy)
    return max(abs(dx), abs(dy))


@jit_kernel(parallel=False, inline=True)
def _point(
    cx: int,
    cy: int,
    use_table: bool,
    cx0: int,
    cy0: int,
    seed_term: int,
    tx: np.ndarray,
    ty: np.ndarray,
) -> tuple[float, float]:
    """The feature point of cell (cx, cy): from the table (cell (cx0, cy0) at [0, 0]) when
    there is one, else hashed."""
    if use_table:
        return tx[cy - cy0, cx - cx0], ty[cy - cy0, cx - cx0]
    return cx + worley_hash(cx, cy, seed_term, 0), cy + worley_hash(cx, cy, seed_term, 1)


@jit_kernel(parallel=False)
def cells_row(
    u: np.ndarray,
    v: np.ndarray,
    params: tuple,
    seed_term: int,
    tx: np.ndarray,
    ty: np.ndarray,
    out_row: np.ndarray,
) -> None:
    """One row of cell values (output 1) or border distances (output 2), as
    ``noise_numpy._cells``; ``params`` = (output, metric, freq_x, freq_y, use_table, cx0, cy0,
    wrap_x, wrap_y) (a flat tuple of scalars: the seed batch's ``prange`` takes no nested
    tuple; wrap_x > 0: a tileable plan, whose cell values hash the wrapped cell)."""
    output, metric, freq_x, freq_y, use_table, cx0, cy0, wrap_x, wrap_y = params
    key_metric = metric if output == 1 else 0
    for m in range(u.size):
        um, vm = u[m], v[m]
        if not (np.isfinite(um) and np.isfinite(vm)):
            out_row[m] = np.nan
            continue
        cu = np.int64(np.floor(um))
        cv = np.int64(np.floor(vm))
        best, bx, by, p1x, p1y = np.inf, cu, cv, 0.0, 0.0
        for ox in range(-2, 3):
            for oy in range(-2, 3):
                px, py = _point(cu + ox, cv + oy, use_table, cx0, cy0, seed_term, tx, ty)
                key = metric_key(um - px, vm - py, key_metric)
                if key < best:
                    best, bx, by, p1x, p1y = key, cu + ox, cv + oy, px, py
        if output == 1:
            if wrap_x > 0:
                bx, by = bx % wrap_x, by % wrap_y
            out_row[m] = worley_hash(bx, by, seed_term, WORLEY_CELL_SALT)
            continue
        edge = np.inf
        for ox in range(-WORLEY_EDGE_SEARCH, WORLEY_EDGE_SEARCH + 1):
            for oy in range(-WORLEY_EDGE_SEARCH, WORLEY_EDGE_SEARCH + 1):
                if ox == 0 and oy == 0:
                    continue
                px, py = _point(bx + ox, by + oy, use_table, cx0, cy0, seed_term, tx, ty)
                du, dv = um - px, vm - py
                num = ((du * du + dv * dv) - best) * 0.5
                su, sv = (px - p1x) * freq_x, (py - p1y) * freq_y
                den = np.sqrt(su * su + sv * sv)
                d = num / den if den > 0 else np.inf
                if d < edge:
                    edge = d
        out_row[m] = edge


@jit_kernel(parallel=False)
def _layout_row(
    i: int,
    coords: tuple,
    params: tuple,
    seed_term: int,
    tx: np.ndarray,
    ty: np.ndarray,
    out_row: np.ndarray,
) -> None:
    """Row i: ``coords`` = (u, v, ix, iy, separable) as the distance loops' (ix, iy unused)."""
    u, v, _, _, separable = coords
    width = out_row.size
    if separable:
        cells_row(u, np.full(width, v[i]), params, seed_term, tx, ty, out_row)
    else:
        row = slice(i * width, (i + 1) * width)
        cells_row(u[row], v[row], params, seed_term, tx, ty, out_row)


@jit_kernel()
def cells_kernel(
    coords: tuple,
    params: tuple,
    seed_term: int,
    tx: np.ndarray,
    ty: np.ndarray,
    out: np.ndarray,
    first: int,
    last: int,
) -> None:
    """Rows ``first``..``last - 1`` of the (H, W) ``out``; serial and ``nogil`` (the caller
    splits the rows over threads)."""
    for i in range(first, last):
        _layout_row(i, coords, params, seed_term, tx, ty, out[i])


@jit_kernel(parallel=False)
def _batch_seed(
    s: int, coords: tuple, params: tuple, seed_terms: np.ndarray, box: tuple, out: np.ndarray
) -> None:
    """out[s] (H, W) for seed s: rebuild the feature table, then every row."""
    cx0, cy0, nx, ny = box
    tx = np.empty((ny, nx))
    ty = np.empty((ny, nx))
    fill_table(cx0, cy0, seed_terms[s], tx, ty)
    for i in range(out.shape[1]):
        _layout_row(i, coords, params, seed_terms[s], tx, ty, out[s, i])


@jit_kernel(parallel=True)
def cells_batch_kernel(
    coords: tuple, params: tuple, seed_terms: np.ndarray, box: tuple, out: np.ndarray
) -> None:
    """Parallel over seeds; the work is in ``_batch_seed``."""
    for s in prange(out.shape[0]):
        _batch_seed(s, coords, params, seed_terms, box, out)
