"""numba ``Tile`` instances: the numbers of :func:`matloom.engine.kernels.tile.instance_parts`
in one pass per texel (the hashing is what costs in numpy: five uint64 temporaries per stream).

Every operation of the numpy version is kept in the same order in float64 and uint64, so the
results are bit-identical; the rotation's cosine and sine are then taken with numpy
(:func:`matloom.engine.kernels.tile.local_coords`) on both backends.
"""

from __future__ import annotations

import numpy as np

from matloom.engine.kernels import tile
from matloom.engine.kernels.noise_numba_core import jit_kernel
from matloom.engine.kernels.threads import parallel_rows

_GOLDEN = np.uint64(0x9E3779B97F4A7C15)
_M1 = np.uint64(0xBF58476D1CE4E5B9)
_M2 = np.uint64(0x94D049BB133111EB)
_S30 = np.uint64(30)
_S27 = np.uint64(27)
_S31 = np.uint64(31)
_S11 = np.uint64(11)
_INV53 = 1.0 / 9007199254740992.0


@jit_kernel(parallel=False, inline=True)
def _mix(z: np.uint64) -> np.uint64:
    z = (z ^ (z >> _S30)) * _M1
    z = (z ^ (z >> _S27)) * _M2
    return z ^ (z >> _S31)


@jit_kernel(parallel=False, inline=True)
def _uniform(key: np.uint64, row: np.uint64, col: np.uint64) -> float:
    z = _mix(key + _GOLDEN)
    z = _mix(z + row)
    z = _mix(z + col)
    return np.float64(z >> _S11) * _INV53


@jit_kernel()
def _parts_kernel(
    x: np.ndarray,
    y: np.ndarray,
    consts: np.ndarray,
    keys: np.ndarray,
    dr: float,
    dc: float,
    dx: np.ndarray,
    dy: np.ndarray,
    scale: np.ndarray,
    theta: np.ndarray,
    keep: np.ndarray,
    first: int,
    last: int,
) -> None:
    """Rows ``first``..``last - 1`` of the (H, W) outputs; x, y are float64 (H, W) grids."""
    w, h, shift_w, jit_w, jit_h = consts[0], consts[1], consts[2], consts[3], consts[4]
    smin, srange, prob, rot = consts[5], consts[6], consts[7], consts[8]
    limit = tile.MAX_CELL
    for i in range(first, last):
        for j in range(x.shape[1]):
            xv = x[i, j]
            yv = y[i, j]
            r = np.floor(yv / h) + dr
            shift = r * shift_w
            c = np.floor((xv - shift) / w) + dc
            valid = abs(r) < limit and abs(c) < limit
            if valid:
                ri = np.uint64(np.int64(r))
                ci = np.uint64(np.int64(c))
            else:
                ri = np.uint64(0)
                ci = np.uint64(0)
            u0 = _uniform(keys[0], ri, ci)
            u1 = _uniform(keys[1], ri, ci)
            u2 = _uniform(keys[2], ri, ci)
            u3 = _uniform(keys[3], ri, ci)
            u4 = _uniform(keys[4], ri, ci)
            keep[i, j] = valid and u4 < prob
            if valid:
                cx = (c + 0.5) * w + shift + (2.0 * u0 - 1.0) * jit_w
                cy = (r + 0.5) * h + (2.0 * u1 - 1.0) * jit_h
                dx[i, j] = xv - cx
                dy[i, j] = yv - cy
            else:
                dx[i, j] = np.nan
                dy[i, j] = np.nan
            scale[i, j] = smin + srange * u3
            theta[i, j] = (2.0 * u2 - 1.0) * rot


def instance(
    x: np.ndarray, y: np.ndarray, p: tile.TileParams, dr: int, dc: int
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(local x, local y, keep) of neighbour (dr, dc): :func:`tile.instance` on numba."""
    x64, y64 = np.broadcast_arrays(np.asarray(x, np.float64), np.asarray(y, np.float64))
    if x64.ndim != 2:
        return tile.instance(x, y, p, dr, dc)
    x64, y64 = np.ascontiguousarray(x64), np.ascontiguousarray(y64)
    shape = x64.shape
    dx, dy, scale, theta = (np.empty(shape) for _ in range(4))
    keep = np.empty(shape, dtype=np.bool_)
    args = (x64, y64, p.consts(), tile.stream_keys(p.seed), float(dr), float(dc))
    outs = (dx, dy, scale, theta, keep)
    parallel_rows(shape[0], shape[1], lambda a, b: _parts_kernel(*args, *outs, a, b))
    lx, ly = tile.local_coords(dx, dy, scale, theta, p.rotates)
    return lx, ly, keep
