"""numba ``Tile`` instances: :func:`matloom.engine.kernels.tile.instance` in one pass per texel
(the hashing is what costs in numpy: five uint64 temporaries per stream).

Every operation of the numpy version is kept in the same order in float64 and uint64 (the
rotation's cosine and sine included, see ``tile.cos_sin``), so the results are bit-identical.
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


_S = tile.SIN_COEFFS
_K = tile.COS_COEFFS


@jit_kernel(parallel=False, inline=True)
def _cos_sin(theta: float) -> tuple[float, float]:
    """:func:`tile.cos_sin` of one angle (the same operations in the same order)."""
    h = theta * 0.5
    h2 = h * h
    acc = _S[7]
    for k in range(6, -1, -1):
        acc = acc * h2 + _S[k]
    s = h * (acc * h2 + 1.0)
    acc = _K[8]
    for k in range(7, -1, -1):
        acc = acc * h2 + _K[k]
    c = acc * h2 + 1.0
    return (c - s) * (c + s), 2.0 * (s * c)


@jit_kernel()
def _instance_kernel(
    x: np.ndarray,
    y: np.ndarray,
    consts: np.ndarray,
    keys: np.ndarray,
    dr: float,
    dc: float,
    rotates: bool,
    box: np.ndarray,
    use_box: bool,
    lx: np.ndarray,
    ly: np.ndarray,
    inside: np.ndarray,
    first: int,
    last: int,
) -> None:
    """Rows ``first``..``last - 1`` of the (H, W) outputs. x and y are float64 and broadcast
    to (H, W) (each of shape (H, W), (1, W) or (H, 1)). A cell's numbers are computed once per
    run of texels in that cell (the same values as computing them per texel)."""
    w, h, shift_w, jit_w, jit_h = consts[0], consts[1], consts[2], consts[3], consts[4]
    smin, srange, prob, rot = consts[5], consts[6], consts[7], consts[8]
    nr, nc, ks = consts[9], consts[10], consts[11]
    x0, y0, x1, y1 = box[0], box[1], box[2], box[3]
    limit = tile.MAX_CELL
    width = lx.shape[1]
    x_rows, x_cols = x.shape[0] > 1, x.shape[1] > 1
    y_rows, y_cols = y.shape[0] > 1, y.shape[1] > 1
    for i in range(first, last):
        have = False
        prev_r = 0.0
        prev_c = 0.0
        cx = cy = scale = cos = sin = 0.0
        valid = kept = False
        for j in range(width):
            xv = x[i if x_rows else 0, j if x_cols else 0]
            yv = y[i if y_rows else 0, j if y_cols else 0]
            r = np.floor(yv / h) + dr
            shift = r * shift_w
            c = np.floor((xv - shift) / w) + dc
            if not (have and r == prev_r and c == prev_c):
                have = r == r and c == c  # a NaN cell is recomputed (and dropped) every time
                prev_r = r
                prev_c = c
                valid = abs(r) < limit and abs(c) < limit
                if valid and nc != 0:
                    kr = np.floor(r / nr)
                    cc = c + kr * ks
                    ri = np.uint64(np.int64(r - kr * nr))
                    ci = np.uint64(np.int64(cc - np.floor(cc / nc) * nc))
                elif valid:
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
                kept = valid and u4 < prob
                cx = (c + 0.5) * w + shift + (2.0 * u0 - 1.0) * jit_w
                cy = (r + 0.5) * h + (2.0 * u1 - 1.0) * jit_h
                scale = smin + srange * u3
                if rotates:
                    cos, sin = _cos_sin((2.0 * u2 - 1.0) * rot)
            if valid:
                dx = xv - cx
                dy = yv - cy
            else:
                dx = np.nan
                dy = np.nan
            if rotates:
                ux = (cos * dx + sin * dy) / scale
                uy = (cos * dy - sin * dx) / scale
            else:
                ux = dx / scale
                uy = dy / scale
            lx[i, j] = ux
            ly[i, j] = uy
            hit = kept
            if use_box:
                hit = hit and ux >= x0 and ux <= x1 and uy >= y0 and uy <= y1
            inside[i, j] = hit


def instance(
    x: np.ndarray,
    y: np.ndarray,
    p: tile.TileParams,
    dr: int,
    dc: int,
    box: tuple[float, ...] | None = None,
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(local x, local y, inside) of neighbour (dr, dc): :func:`tile.instance` on numba."""
    xa, ya = np.asarray(x, np.float64), np.asarray(y, np.float64)
    shape = np.broadcast_shapes(xa.shape, ya.shape)
    if len(shape) != 2 or xa.ndim != 2 or ya.ndim != 2:
        return tile.instance(x, y, p, dr, dc, box)
    xa, ya = np.ascontiguousarray(xa), np.ascontiguousarray(ya)
    lx, ly = np.empty(shape), np.empty(shape)
    inside = np.empty(shape, dtype=np.bool_)
    limits = np.zeros(4) if box is None else np.array(box, dtype=np.float64)
    args = (xa, ya, p.consts(), tile.stream_keys(p.seed), float(dr), float(dc), p.rotates)
    args = (*args, limits, box is not None, lx, ly, inside)
    parallel_rows(shape[0], shape[1], lambda a, b: _instance_kernel(*args, a, b))
    return lx, ly, inside
