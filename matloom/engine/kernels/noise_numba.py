"""numba fBm (OpenSimplex 2014) and Worley noise; same API and numbers as ``noise_numpy``.

Kernels are ``@njit(cache=True, parallel=True, fastmath=False)`` with ``prange`` over rows (or
over chunks of a flat grid).  They compile lazily on first use and are cached on disk; see
``noise_numba_core.jit_kernel`` for the read-only-cache fallback.  Importing this module imports
numba.

Coordinate scaling follows the reference exactly: fBm scales each octave in the coordinate dtype
(float32 axes stay float32, then the noise runs in float64).  Separable axes are scaled per
octave on the small 1-D axes only.  Worley lives in ``noise_numba_worley``; the seed-batched
sweeps in ``noise_numba_batch``.
"""

from __future__ import annotations

from typing import Any

import numpy as np
from numba import prange

from matloom.engine.kernels.noise_numba_batch import fbm_seed_batch
from matloom.engine.kernels.noise_numba_core import (
    CHUNK,
    finish_fbm,
    jit_kernel,
    new_scratch,
    noise_chunk,
)
from matloom.engine.kernels.noise_numba_worley import worley, worley_seed_batch
from matloom.engine.kernels.opensimplex import (
    FBM_SCALE,
    coord_layout,
    freq_in_dtype,
    gradient_table,
    octave_axes,
    octave_schedule,
)

__all__ = ["fbm", "fbm_masked", "worley", "fbm_seed_batch", "worley_seed_batch", "warm_up"]


@jit_kernel(parallel=False)
def _fbm_segment(
    i: int,
    first: int,
    stop: int,
    xs: np.ndarray,
    ys: np.ndarray,
    amps: np.ndarray,
    norm: float,
    to_01: bool,
    grad_table: np.ndarray,
    out: np.ndarray,
    scratch: tuple,
) -> None:
    """Texels ``first``..``stop - 1`` of row i of the separable fBm: pre-scaled float64
    per-octave axes xs (O, W), ys (O, H); ``scratch`` from ``new_scratch``."""
    values = scratch[3]
    yb = np.empty(CHUNK)
    total = np.empty(CHUNK)
    for j0 in range(first, stop, CHUNK):
        n = min(CHUNK, stop - j0)
        for j in range(n):
            total[j] = 0.0
        for k in range(amps.size):
            for j in range(n):
                yb[j] = ys[k, i]
            noise_chunk(xs[k, j0 : j0 + n], yb, n, grad_table, scratch)
            for j in range(n):
                total[j] += values[j] * FBM_SCALE * amps[k]
        out_chunk = out[i, j0 : j0 + n]
        for j in range(n):
            out_chunk[j] = finish_fbm(total[j], norm, to_01)


@jit_kernel(parallel=False)
def _fbm_row(
    i: int,
    xs: np.ndarray,
    ys: np.ndarray,
    amps: np.ndarray,
    norm: float,
    to_01: bool,
    grad_table: np.ndarray,
    out: np.ndarray,
) -> None:
    """Row i of the separable fBm (see ``_fbm_segment``)."""
    _fbm_segment(i, 0, out.shape[1], xs, ys, amps, norm, to_01, grad_table, out, new_scratch())


@jit_kernel()
def _fbm_separable_kernel(
    xs: np.ndarray,
    ys: np.ndarray,
    amps: np.ndarray,
    norm: float,
    to_01: bool,
    grad_table: np.ndarray,
    out: np.ndarray,
) -> None:
    """Parallel over rows; the work is in ``_fbm_row`` (keeps the parfor cheap to compile)."""
    for i in prange(out.shape[0]):
        _fbm_row(i, xs, ys, amps, norm, to_01, grad_table, out)


@jit_kernel(parallel=False)
def _fbm_grid_chunk(
    c: int,
    xg: np.ndarray,
    yg: np.ndarray,
    fxs: np.ndarray,
    fys: np.ndarray,
    amps: np.ndarray,
    norm: float,
    to_01: bool,
    grad_table: np.ndarray,
    out: np.ndarray,
) -> None:
    """Chunk c of the flat-grid fBm; ``xg[n] * fxs[k]`` is computed in the grid dtype."""
    j0 = c * CHUNK
    n = min(CHUNK, out.size - j0)
    scratch = new_scratch()
    values = scratch[3]
    xb = np.empty(CHUNK)
    yb = np.empty(CHUNK)
    total = np.zeros(CHUNK)
    xg_chunk, yg_chunk = xg[j0 : j0 + n], yg[j0 : j0 + n]  # zero-based loops vectorise
    for k in range(amps.size):
        for j in range(n):
            xb[j] = np.float64(xg_chunk[j] * fxs[k])
            yb[j] = np.float64(yg_chunk[j] * fys[k])
        noise_chunk(xb, yb, n, grad_table, scratch)
        for j in range(n):
            total[j] += values[j] * FBM_SCALE * amps[k]
    out_chunk = out[j0 : j0 + n]
    for j in range(n):
        out_chunk[j] = finish_fbm(total[j], norm, to_01)


@jit_kernel()
def _fbm_grid_kernel(
    xg: np.ndarray,
    yg: np.ndarray,
    fxs: np.ndarray,
    fys: np.ndarray,
    amps: np.ndarray,
    norm: float,
    to_01: bool,
    grad_table: np.ndarray,
    out: np.ndarray,
) -> None:
    """Parallel over chunks of the flat grid; the work is in ``_fbm_grid_chunk``."""
    for c in prange((out.size + CHUNK - 1) // CHUNK):
        _fbm_grid_chunk(c, xg, yg, fxs, fys, amps, norm, to_01, grad_table, out)


#: Flat texels per parallel block of the masked grid kernel.
_MASK_BLOCK = 4096


@jit_kernel(parallel=False)
def _fbm_points(
    xk: np.ndarray,
    yk: np.ndarray,
    idx: np.ndarray,
    m: int,
    amps: np.ndarray,
    norm: float,
    to_01: bool,
    grad_table: np.ndarray,
    out: np.ndarray,
) -> None:
    """fBm at the points ``idx[:m]`` of the flat ``out``; ``xk``/``yk`` (O, N) hold each
    octave's float64 coordinates of every point (the same values the dense kernels use)."""
    scratch = new_scratch()
    values = scratch[3]
    xb = np.empty(CHUNK)
    yb = np.empty(CHUNK)
    total = np.empty(CHUNK)
    for j0 in range(0, m, CHUNK):
        n = min(CHUNK, m - j0)
        for j in range(n):
            total[j] = 0.0
        for k in range(amps.size):
            for j in range(n):
                xb[j] = xk[k, idx[j0 + j]]
                yb[j] = yk[k, idx[j0 + j]]
            noise_chunk(xb, yb, n, grad_table, scratch)
            for j in range(n):
                total[j] += values[j] * FBM_SCALE * amps[k]
        for j in range(n):
            out[idx[j0 + j]] = finish_fbm(total[j], norm, to_01)


@jit_kernel(parallel=False)
def _fbm_row_masked(
    i: int,
    xs: np.ndarray,
    ys: np.ndarray,
    amps: np.ndarray,
    norm: float,
    to_01: bool,
    grad_table: np.ndarray,
    mask: np.ndarray,
    fill: float,
    out: np.ndarray,
) -> None:
    """Row i of the separable fBm at the texels where ``mask`` is set, ``fill`` elsewhere.

    The runs of set texels (masks are coherent: tiles, mortar lines) are copied into one
    compact row of coordinates per octave, which runs through the dense ``_fbm_segment`` in
    full chunks; the results are copied back run by run. Values equal the dense kernel's.
    """
    width = out.shape[1]
    starts = np.empty(width, np.int64)
    stops = np.empty(width, np.int64)
    runs = 0
    j = 0
    while j < width:
        if not mask[i, j]:
            out[i, j] = fill
            j += 1
            continue
        starts[runs] = j
        while j < width and mask[i, j]:
            j += 1
        stops[runs] = j
        runs += 1
    m = 0
    for r in range(runs):
        m += stops[r] - starts[r]
    if m == 0:
        return
    octaves = amps.size
    cx = np.empty((octaves, m))
    cy = np.empty((octaves, 1))
    for k in range(octaves):
        cy[k, 0] = ys[k, i]
        q = 0
        for r in range(runs):
            for j in range(starts[r], stops[r]):
                cx[k, q] = xs[k, j]
                q += 1
    compact = np.empty((1, m))
    _fbm_segment(0, 0, m, cx, cy, amps, norm, to_01, grad_table, compact, new_scratch())
    q = 0
    for r in range(runs):
        for j in range(starts[r], stops[r]):
            out[i, j] = compact[0, q]
            q += 1


@jit_kernel()
def _fbm_separable_masked_kernel(
    xs: np.ndarray,
    ys: np.ndarray,
    amps: np.ndarray,
    norm: float,
    to_01: bool,
    grad_table: np.ndarray,
    mask: np.ndarray,
    fill: float,
    out: np.ndarray,
) -> None:
    """Parallel over rows; the work is in ``_fbm_row_masked``."""
    for i in prange(out.shape[0]):
        _fbm_row_masked(i, xs, ys, amps, norm, to_01, grad_table, mask, fill, out)


@jit_kernel(parallel=False)
def _fbm_grid_block_masked(
    b: int,
    xg: np.ndarray,
    yg: np.ndarray,
    fxs: np.ndarray,
    fys: np.ndarray,
    amps: np.ndarray,
    norm: float,
    to_01: bool,
    grad_table: np.ndarray,
    mask: np.ndarray,
    fill: float,
    out: np.ndarray,
) -> None:
    """Block b of the flat-grid fBm at the texels where ``mask`` is set; ``fill`` elsewhere.
    Coordinates are scaled in the grid dtype, exactly as in ``_fbm_grid_chunk``."""
    j0 = b * _MASK_BLOCK
    n = min(_MASK_BLOCK, out.size - j0)
    idx = np.empty(n, np.int64)
    m = 0
    for j in range(n):
        out[j0 + j] = fill
        if mask[j0 + j]:
            idx[m] = j
            m += 1
    xk = np.empty((amps.size, n))
    yk = np.empty((amps.size, n))
    for k in range(amps.size):
        for q in range(m):
            xk[k, idx[q]] = np.float64(xg[j0 + idx[q]] * fxs[k])
            yk[k, idx[q]] = np.float64(yg[j0 + idx[q]] * fys[k])
    _fbm_points(xk, yk, idx, m, amps, norm, to_01, grad_table, out[j0 : j0 + n])


@jit_kernel()
def _fbm_grid_masked_kernel(
    xg: np.ndarray,
    yg: np.ndarray,
    fxs: np.ndarray,
    fys: np.ndarray,
    amps: np.ndarray,
    norm: float,
    to_01: bool,
    grad_table: np.ndarray,
    mask: np.ndarray,
    fill: float,
    out: np.ndarray,
) -> None:
    """Parallel over blocks of the flat grid; the work is in ``_fbm_grid_block_masked``."""
    for b in prange((out.size + _MASK_BLOCK - 1) // _MASK_BLOCK):
        _fbm_grid_block_masked(b, xg, yg, fxs, fys, amps, norm, to_01, grad_table, mask, fill, out)


def fbm(
    x: np.ndarray,
    y: np.ndarray,
    *,
    octaves: int,
    lacunarity: float,
    gain: float,
    freq_x: float,
    freq_y: float,
    to_01: bool,
    seed: int,
    mask: np.ndarray | None = None,
    fill: float = 0.0,
) -> np.ndarray:
    """fBm of OpenSimplex noise on the broadcast of x and y (float64); see ``noise_numpy.fbm``.

    With a boolean ``mask`` (the broadcast shape of x and y) only the texels where it is set are
    computed (bit-identical to the unmasked values); the others hold ``fill``.
    """
    sched = octave_schedule(octaves, lacunarity, gain, freq_x, freq_y)
    table = gradient_table(int(seed))
    amps = np.array(sched.amps, dtype=np.float64)
    common = (amps, sched.norm, bool(to_01), table)
    lay = coord_layout(x, y)
    where = None
    if mask is not None:
        where = np.ascontiguousarray(np.broadcast_to(mask, lay.shape), dtype=np.bool_)
    if lay.separable:
        xs, ys = octave_axes(lay.x_axis, lay.y_axis, sched.freqs_x, sched.freqs_y)
        out = np.empty((lay.y_axis.size, lay.x_axis.size), dtype=np.float64)
        if where is None:
            _fbm_separable_kernel(xs, ys, *common, out)
        else:
            _fbm_separable_masked_kernel(
                xs, ys, *common, where.reshape(out.shape), float(fill), out
            )
        return out.reshape(lay.shape)
    fxs = freq_in_dtype(sched.freqs_x, lay.x_grid.dtype)
    fys = freq_in_dtype(sched.freqs_y, lay.y_grid.dtype)
    flat = np.empty(lay.x_grid.size, dtype=np.float64)
    grids = (lay.x_grid, lay.y_grid, fxs, fys)
    if where is None:
        _fbm_grid_kernel(*grids, *common, flat)
    else:
        _fbm_grid_masked_kernel(*grids, *common, where.reshape(-1), float(fill), flat)
    return flat.reshape(lay.shape)


def fbm_masked(x: np.ndarray, y: np.ndarray, mask: np.ndarray, **kw: Any) -> np.ndarray:
    """:func:`fbm` with a mask (the backend's ``fbm_masked`` entry point)."""
    return fbm(x, y, mask=mask, **kw)


def warm_up(*, include_batch: bool = False) -> None:
    """Compile (or load from the on-disk cache) the kernels for the common argument types.

    Calls every entry point once on tiny float32 separable axes and rotated float32 grids, so
    a CLI can pay numba's first-call cost up front (e.g. at install time or in a warm-up step).
    """
    x = np.linspace(0.0, 1.0, 4, dtype=np.float32)[None, :]
    y = np.linspace(1.0, 0.0, 3, dtype=np.float32)[:, None]
    grid_x, grid_y = np.float32(0.8) * x + np.float32(0.6) * y, np.float32(0.8) * y - x
    fkw = dict(octaves=2, lacunarity=2.0, gain=0.5, freq_x=2.0, freq_y=2.0, to_01=True)
    wkw = dict(distance="euclidean", combination="F1", freq_x=2.0, freq_y=2.0, to_01=True)
    for gx, gy in ((x, y), (grid_x, grid_y)):
        fbm(gx, gy, seed=0, **fkw)
        worley(gx, gy, seed=0, **wkw)
        if include_batch:
            fbm_seed_batch(gx, gy, seeds=[0, 1], **fkw)
            worley_seed_batch(gx, gy, seeds=[0, 1], **wkw)
