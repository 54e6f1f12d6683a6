"""numba: the tileable fBm (:func:`fbm_tiled`), the same numbers as ``noise_numpy.fbm_tiled``'s.

The geometry, gradient look-up and value passes of ``noise_numba_core.noise_chunk``, with
each vertex's key reduced modulo the octave's sublattice (:mod:`.periodic`) and the octave's
coordinates ``M_k (x, y)`` computed per texel in float64, in numpy's order of operations.
"""

from __future__ import annotations

import numpy as np

from matloom.engine.kernels.noise import FbmPlan
from matloom.engine.kernels.noise_numba_core import (
    CHUNK,
    _chunk_grads,
    _chunk_values,
    finish_fbm,
    frame,
    jit_kernel,
    new_scratch,
)
from matloom.engine.kernels.opensimplex import FBM_SCALE, gradient_table
from matloom.engine.kernels.threads import parallel_rows

__all__ = ["fbm_tiled"]


@jit_kernel(parallel=False, inline=True)
def _key(iv: float, jv: float, lat: np.ndarray) -> int:
    """``noise_numpy.wrapped_key`` of one vertex; ``lat`` = (p, q, r, 1/p, 1/r)."""
    k = np.floor((iv + 0.5) * lat[3])
    i2 = iv - k * lat[0]
    j2 = jv - k * lat[1]
    kj = np.floor((j2 + 0.5) * lat[4])
    j3 = j2 - kj * lat[2]
    return np.int64(i2 * lat[2] + j3) & 0xFFFF


@jit_kernel(parallel=False)
def _geometry(
    xb: np.ndarray, yb: np.ndarray, n: int, lat: np.ndarray, keys: np.ndarray, geo: np.ndarray
) -> None:
    """Pass A of ``noise_chunk`` with wrapped vertex keys."""
    for j in range(n):
        xsb, ysb, dx0, dy0, ext_x, ext_y, base = frame(xb[j], yb[j])
        keys[0, j] = _key(xsb + 1.0, ysb, lat)
        keys[1, j] = _key(xsb, ysb + 1.0, lat)
        keys[2, j] = _key(xsb + base, ysb + base, lat)
        keys[3, j] = _key(xsb + ext_x, ysb + ext_y, lat)
        geo[0, j] = dx0
        geo[1, j] = dy0
        geo[2, j] = ext_x
        geo[3, j] = ext_y
        geo[4, j] = base


@jit_kernel()
def _tiled_kernel(
    gx: np.ndarray,
    gy: np.ndarray,
    idx: np.ndarray,
    maps: np.ndarray,
    lats: np.ndarray,
    amps: np.ndarray,
    norm: float,
    to_01: bool,
    grad_table: np.ndarray,
    out: np.ndarray,
    first: int,
    last: int,
) -> None:
    """Chunks ``first``..``last - 1`` (``CHUNK`` points of ``idx`` each) of the tileable fBm
    into ``out[idx]``. Serial and ``nogil``: :func:`fbm_tiled` splits the chunks over threads."""
    keys, geo, grads, values = new_scratch()
    scratch_x = np.empty(CHUNK)
    scratch_y = np.empty(CHUNK)
    xs = np.empty(CHUNK)
    ys = np.empty(CHUNK)
    total = np.empty(CHUNK)
    for c in range(first, last):
        j0 = c * CHUNK
        n = min(CHUNK, idx.size - j0)
        for j in range(n):
            scratch_x[j] = gx[idx[j0 + j]]
            scratch_y[j] = gy[idx[j0 + j]]
            total[j] = 0.0
        for k in range(amps.size):
            m00, m01, m10, m11 = maps[k, 0], maps[k, 1], maps[k, 2], maps[k, 3]
            for j in range(n):
                xs[j] = m00 * scratch_x[j] + m01 * scratch_y[j]
                ys[j] = m10 * scratch_x[j] + m11 * scratch_y[j]
            _geometry(xs, ys, n, lats[k], keys, geo)
            _chunk_grads(n, keys, grad_table, grads)
            _chunk_values(n, geo, grads, values)
            for j in range(n):
                total[j] += values[j] * FBM_SCALE * amps[k]
        for j in range(n):
            out[idx[j0 + j]] = finish_fbm(total[j], norm, to_01)


def fbm_tiled(
    plan: FbmPlan, seed: int, out: np.ndarray, mask: np.ndarray | None, fill: float
) -> None:
    """The tileable fBm into the flat ``out`` (N,), dense or at the set texels of ``mask``
    (the others get ``fill``): chunks of points on threads."""
    gx, gy = plan.grids64()
    if mask is None:
        idx = np.arange(out.size, dtype=np.int64)
    else:
        out[...] = fill
        idx = np.flatnonzero(mask).astype(np.int64)
    if idx.size == 0:
        return
    args = (gx, gy, idx, plan.tile_maps, plan.tile_lattices, plan.amps, plan.norm, plan.to_01)
    table = gradient_table(int(seed))
    chunks = (idx.size + CHUNK - 1) // CHUNK
    parallel_rows(chunks, CHUNK, lambda a, b: _tiled_kernel(*args, table, out, a, b))
