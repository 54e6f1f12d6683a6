"""The numba loops of fBm (OpenSimplex 2014); numbers as ``noise_numpy``'s.

:data:`FBM_LOOPS` (and :data:`WORLEY_LOOPS`, from ``noise_numba_worley``) are run by the one
dispatch of :mod:`matloom.engine.kernels.noise` on its shared plans. Kernels are
``@njit(cache=True, nogil=True, fastmath=False)`` over a range of rows (or of chunks of a flat
grid); the loops run disjoint ranges on threads (``threads.parallel_rows``). Serial kernels
instead of ``prange`` ones keep the first, compiling run short: a parallel kernel costs numba a
parfor pipeline and a second, unsigned-index specialisation of everything it calls (see
docs/performance.md, "Cold start").  They compile lazily on first use and are cached on disk;
see ``noise_numba_core.jit_kernel`` for the read-only-cache fallback.  Importing this module
imports numba.

Coordinate scaling follows the reference exactly (the plan does it): fBm scales each octave in
the coordinate dtype (float32 axes stay float32, then the noise runs in float64).  Separable
axes are scaled per octave on the small 1-D axes only.  Worley lives in ``noise_numba_worley``;
the seed-batched sweeps in ``noise_numba_batch``.
"""

from __future__ import annotations

import numpy as np

from matloom.engine.kernels import noise
from matloom.engine.kernels.noise import FbmLoops, FbmPlan
from matloom.engine.kernels.noise_numba_batch import seed_batch
from matloom.engine.kernels.noise_numba_core import (
    CHUNK,
    finish_fbm,
    jit_kernel,
    new_scratch,
    noise_chunk,
)
from matloom.engine.kernels.noise_numba_tileable import fbm_tiled
from matloom.engine.kernels.noise_numba_worley import WORLEY_LOOPS
from matloom.engine.kernels.opensimplex import FBM_SCALE, gradient_table
from matloom.engine.kernels.threads import parallel_rows

__all__ = ["FBM_LOOPS", "WORLEY_LOOPS", "warm_up"]


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


@jit_kernel()
def _fbm_separable_kernel(
    xs: np.ndarray,
    ys: np.ndarray,
    amps: np.ndarray,
    norm: float,
    to_01: bool,
    grad_table: np.ndarray,
    out: np.ndarray,
    first: int,
    last: int,
) -> None:
    """Rows ``first``..``last - 1`` of the separable fBm (see ``_fbm_segment``); serial and
    ``nogil``: :func:`_fbm_separable` splits the rows over threads."""
    scratch = new_scratch()
    zero = np.int64(0)  # a literal 0 would compile another specialisation of _fbm_segment
    width = np.int64(out.shape[1])
    for i in range(first, last):
        _fbm_segment(i, zero, width, xs, ys, amps, norm, to_01, grad_table, out, scratch)


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
    first: int,
    last: int,
) -> None:
    """Chunks ``first``..``last - 1`` (``CHUNK`` texels each) of the flat-grid fBm;
    ``xg[n] * fxs[k]`` is computed in float64 (``scale_grid``). Serial and ``nogil`` (see above)."""
    scratch = new_scratch()
    values = scratch[3]
    xb = np.empty(CHUNK)
    yb = np.empty(CHUNK)
    total = np.empty(CHUNK)
    for c in range(first, last):
        j0 = c * CHUNK
        n = min(CHUNK, out.size - j0)
        xg_chunk, yg_chunk = xg[j0 : j0 + n], yg[j0 : j0 + n]  # zero-based loops vectorise
        for j in range(n):
            total[j] = 0.0
        for k in range(amps.size):
            for j in range(n):
                xb[j] = np.float64(xg_chunk[j]) * fxs[k]
                yb[j] = np.float64(yg_chunk[j]) * fys[k]
            noise_chunk(xb, yb, n, grad_table, scratch)
            for j in range(n):
                total[j] += values[j] * FBM_SCALE * amps[k]
        out_chunk = out[j0 : j0 + n]
        for j in range(n):
            out_chunk[j] = finish_fbm(total[j], norm, to_01)


#: Flat texels per block of the masked grid kernel.
_MASK_BLOCK = 4096


@jit_kernel()
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
    first: int,
    last: int,
) -> None:
    """Rows ``first``..``last - 1`` of the separable fBm at the texels where ``mask`` is set,
    ``fill`` elsewhere. Serial and ``nogil`` (see ``_fbm_separable_kernel``).

    The runs of set texels of a row (masks are coherent: tiles, mortar lines) are copied into
    one compact row of coordinates per octave, which runs through the dense ``_fbm_segment`` in
    full chunks; the results are copied back run by run. Values equal the dense kernel's.
    """
    width = out.shape[1]
    octaves = amps.size
    starts = np.empty(width, np.int64)
    stops = np.empty(width, np.int64)
    cy = np.empty((octaves, 1))
    scratch = new_scratch()
    zero = np.int64(0)  # a literal 0 would compile another specialisation of _fbm_segment
    for i in range(first, last):
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
        m = zero
        for r in range(runs):
            m += stops[r] - starts[r]
        if m == 0:
            continue
        cx = np.empty((octaves, m))
        for k in range(octaves):
            cy[k, 0] = ys[k, i]
            q = 0
            for r in range(runs):
                for j in range(starts[r], stops[r]):
                    cx[k, q] = xs[k, j]
                    q += 1
        compact = np.empty((1, m))
        _fbm_segment(zero, zero, m, cx, cy, amps, norm, to_01, grad_table, compact, scratch)
        q = 0
        for r in range(runs):
            for j in range(starts[r], stops[r]):
                out[i, j] = compact[0, q]
                q += 1


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
    first: int,
    last: int,
) -> None:
    """Blocks ``first``..``last - 1`` (``_MASK_BLOCK`` texels each) of the flat-grid fBm at the
    texels where ``mask`` is set, ``fill`` elsewhere; coordinates are scaled in float64,
    exactly as in ``_fbm_grid_kernel``. Serial and ``nogil`` (see above)."""
    idx = np.empty(_MASK_BLOCK, np.int64)
    xk = np.empty((amps.size, _MASK_BLOCK))
    yk = np.empty((amps.size, _MASK_BLOCK))
    for b in range(first, last):
        j0 = b * _MASK_BLOCK
        n = min(_MASK_BLOCK, out.size - j0)
        m = 0
        for j in range(n):
            out[j0 + j] = fill
            if mask[j0 + j]:
                idx[m] = j
                m += 1
        for k in range(amps.size):
            for q in range(m):
                xk[k, idx[q]] = np.float64(xg[j0 + idx[q]]) * fxs[k]
                yk[k, idx[q]] = np.float64(yg[j0 + idx[q]]) * fys[k]
        _fbm_points(xk, yk, idx, m, amps, norm, to_01, grad_table, out[j0 : j0 + n])


def _fbm_separable(
    plan: FbmPlan, seed: int, out: np.ndarray, mask: np.ndarray | None, fill: float
) -> None:
    """The separable fBm into ``out`` (H, W), dense or at the texels of ``mask``: row ranges on
    threads."""
    common = (plan.amps, plan.norm, plan.to_01, gradient_table(int(seed)))
    if mask is None:
        args: tuple = (plan.xs, plan.ys, *common, out)
        kernel = _fbm_separable_kernel
    else:
        args = (plan.xs, plan.ys, *common, mask, float(fill), out)
        kernel = _fbm_separable_masked_kernel
    parallel_rows(out.shape[0], out.shape[1], lambda a, b: kernel(*args, a, b))


def _fbm_grid(
    plan: FbmPlan, seed: int, out: np.ndarray, mask: np.ndarray | None, fill: float
) -> None:
    """The flat-grid fBm into ``out`` (N,), dense or at the texels of ``mask``: blocks of
    texels on threads."""
    common = (plan.amps, plan.norm, plan.to_01, gradient_table(int(seed)))
    grids = (plan.layout.x_grid, plan.layout.y_grid, plan.fxs, plan.fys)
    if mask is None:
        args: tuple = (*grids, *common, out)
        kernel, block = _fbm_grid_kernel, CHUNK
    else:
        args = (*grids, *common, mask, float(fill), out)
        kernel, block = _fbm_grid_masked_kernel, _MASK_BLOCK
    blocks = (out.size + block - 1) // block
    parallel_rows(blocks, block, lambda a, b: kernel(*args, a, b))


#: The numba fBm loops: coverage masks, and the seed-batch kernel of ``noise_numba_batch``.
FBM_LOOPS = FbmLoops(
    "numba",
    separable=_fbm_separable,
    grid=_fbm_grid,
    masks=True,
    seed_batch=seed_batch,
    tiled=fbm_tiled,
)


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
        noise.fbm(gx, gy, loops=FBM_LOOPS, seed=0, **fkw)
        noise.worley(gx, gy, loops=WORLEY_LOOPS, seed=0, **wkw)
        if include_batch:
            noise.fbm_seed_batch(gx, gy, loops=FBM_LOOPS, seeds=[0, 1], **fkw)
            noise.worley_seed_batch(gx, gy, loops=WORLEY_LOOPS, seeds=[0, 1], **wkw)
