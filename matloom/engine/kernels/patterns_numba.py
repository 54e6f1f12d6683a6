"""numba ``Bricks``: the same numbers as :func:`matloom.engine.kernels.patterns.bricks`.

One pass per texel instead of about a dozen full-size numpy temporaries. Exactness: every
operation of the numpy version is kept, in the same order and in the coordinate dtype (the
parameters are converted to that dtype first, as numpy 2's weak-scalar promotion does; the
Python-float sums ``bw - mortar / 2`` stay float64 sums converted afterwards, as in numpy).
``np.minimum`` and ``np.clip`` propagate NaN, so the helpers here do too. Inputs the kernel does
not take (other ranks, mixed or non-float dtypes) go to the numpy version.

The other outputs (cell value, u, v, edge) run :func:`_bricks_out_kernel`, with the operations
of ``patterns._brick_output`` (bit-identical).
"""

from __future__ import annotations

import numpy as np

from matloom.engine.kernels import patterns
from matloom.engine.kernels.noise_numba_cells import worley_hash
from matloom.engine.kernels.noise_numba_core import jit_kernel
from matloom.engine.kernels.opensimplex import worley_seed_term
from matloom.engine.kernels.threads import parallel_rows

_CELL_SALT = patterns.BRICK_CELL_SALT


@jit_kernel(parallel=False, inline=True)
def _nan_min(a: float, b: float) -> float:
    """``np.minimum(a, b)`` for scalars: NaN if either is NaN."""
    if a != a:
        return a
    if b != b:
        return b
    return a if a < b else b


@jit_kernel(parallel=False, inline=True)
def _floor_mod(a: float, b: float) -> float:
    """``a - floor(a / b) * b`` (see ``patterns.floor_mod``)."""
    return a - np.floor(a / b) * b


@jit_kernel(parallel=False, inline=True)
def _coverage(s: float, ramp_consts: tuple, hard: bool) -> float:
    """``patterns.smooth_coverage`` of one inset; ``ramp_consts`` = (feather / 2, feather, 0, 1,
    2, 3) in the coordinate dtype (consts[4:10], read once per call of a kernel: reading them
    from the array per texel kept the loops from vectorising)."""
    half_feather, feather, zero, one, two, three = ramp_consts
    if hard:
        return 1.0 if s >= zero else 0.0
    t = (s + half_feather) / feather
    if t == t:  # np.clip keeps NaN
        t = zero if t < zero else (one if t > one else t)
    ramp = three - two * t
    return np.float64(ramp * (t * t))


@jit_kernel()
def _bricks_kernel(
    x: np.ndarray,
    y: np.ndarray,
    consts: np.ndarray,
    by_row: bool,
    hard: bool,
    out: np.ndarray,
    first: int,
    last: int,
) -> None:
    """Coverage of each texel of rows ``first``..``last - 1``; x, y broadcast to ``out``'s
    shape. consts (coordinate dtype): bw, bh, offset, mortar / 2, feather / 2, feather, 0, 1,
    2, 3, bw - mortar / 2, bh - mortar / 2. Serial and ``nogil``: :func:`bricks` splits the
    rows over threads."""
    bw, bh, offset, half = consts[0], consts[1], consts[2], consts[3]
    bw_in, bh_in = consts[10], consts[11]
    ramp = (consts[4], consts[5], consts[6], consts[7], consts[8], consts[9])
    for i in range(first, last):
        x_row, y_row, out_row = x[i], y[i], out[i]  # zero-based rows: the loop vectorises
        for j in range(out_row.size):
            xv, yv = x_row[j], y_row[j]
            if by_row:
                row = np.floor(yv / bh)
                lx = _floor_mod(xv - row * offset * bw, bw)
                ly = _floor_mod(yv, bh)
            else:
                col = np.floor(xv / bw)
                lx = _floor_mod(xv, bw)
                ly = _floor_mod(yv - col * offset * bh, bh)
            inset = _nan_min(
                _nan_min(lx - half, bw_in - lx),
                _nan_min(ly - half, bh_in - ly),
            )
            out_row[j] = _coverage(inset, ramp, hard)


@jit_kernel(parallel=False, inline=True)
def _cell_int(c: float, limit: float) -> int:
    """A brick index as int64, clamped to +-limit (``patterns._cell_int``; not NaN)."""
    c = -limit if c < -limit else (limit if c > limit else c)
    return np.int64(c)


@jit_kernel()
def _bricks_out_kernel(
    x: np.ndarray,
    y: np.ndarray,
    consts: np.ndarray,
    by_row: bool,
    output: int,
    seed_term: int,
    out: np.ndarray,
    first: int,
    last: int,
) -> None:
    """Output ``output`` (index in ``patterns.BRICK_OUTPUTS``: 1 cell value, 2 u, 3 v, 4 edge,
    5 row, 6 column)
    of rows ``first``..``last - 1``; consts as :func:`_bricks_kernel`'s, then the index limit
    2**62."""
    bw, bh, offset, half = consts[0], consts[1], consts[2], consts[3]
    zero, bw_in, bh_in, limit = consts[6], consts[10], consts[11], consts[12]
    for i in range(first, last):
        x_row, y_row, out_row = x[i], y[i], out[i]
        for j in range(out_row.size):
            xv, yv = x_row[j], y_row[j]
            if by_row:
                row = np.floor(yv / bh)
                a = xv - row * offset * bw
                col = np.floor(a / bw)
                lx = a - col * bw
                ly = _floor_mod(yv, bh)
            else:
                col = np.floor(xv / bw)
                b = yv - col * offset * bh
                row = np.floor(b / bh)
                lx = _floor_mod(xv, bw)
                ly = b - row * bh
            if output == 1:
                if col != col or row != row:
                    out_row[j] = np.nan
                else:
                    ci, ri = _cell_int(col, limit), _cell_int(row, limit)
                    out_row[j] = worley_hash(ci, ri, seed_term, _CELL_SALT)
            elif output == 2:
                out_row[j] = lx / bw
            elif output == 3:
                out_row[j] = ly / bh
            elif output == 5:
                out_row[j] = np.float64(row)
            elif output == 6:
                out_row[j] = np.float64(col)
            else:
                inset = _nan_min(_nan_min(lx - half, bw_in - lx), _nan_min(ly - half, bh_in - ly))
                out_row[j] = zero if inset < zero else inset


@jit_kernel()
def _bricks_rows_kernel(
    x_axis: np.ndarray,
    y_axis: np.ndarray,
    consts: np.ndarray,
    hard: bool,
    out: np.ndarray,
    first: int,
    last: int,
) -> None:
    """``_bricks_kernel`` for axis="row" on a separable grid (x row, y column, as 1-D axes):
    the row's course, its offset and its y distances are computed once per row."""
    bw, bh, offset, half = consts[0], consts[1], consts[2], consts[3]
    bw_in, bh_in = consts[10], consts[11]
    ramp = (consts[4], consts[5], consts[6], consts[7], consts[8], consts[9])
    for i in range(first, last):
        yv = y_axis[i]
        row = np.floor(yv / bh)
        shift = row * offset * bw
        ly = _floor_mod(yv, bh)
        y_inset = _nan_min(ly - half, bh_in - ly)
        out_row = out[i]
        for j in range(out.shape[1]):
            lx = _floor_mod(x_axis[j] - shift, bw)
            out_row[j] = _coverage(_nan_min(_nan_min(lx - half, bw_in - lx), y_inset), ramp, hard)


def kernel_takes(x: np.ndarray, y: np.ndarray) -> bool:
    """Whether the pattern kernels take these coordinates: 2-D arrays of one float dtype
    (anything else goes to the numpy version)."""
    return x.ndim == 2 and y.ndim == 2 and y.dtype == x.dtype and x.dtype in _FLOATS


_FLOATS = (np.dtype(np.float32), np.dtype(np.float64))


def bricks(
    x: np.ndarray,
    y: np.ndarray,
    *,
    brick_width: float,
    brick_height: float,
    offset: float,
    mortar: float,
    axis: str,
    feather: float,
    output: str = "mask",
    seed: int | None = None,
) -> np.ndarray:
    """Running-bond brick mask (or another output), as :func:`patterns.bricks` (same arguments,
    same numbers)."""
    kwargs = dict(
        brick_width=brick_width,
        brick_height=brick_height,
        offset=offset,
        mortar=mortar,
        axis=axis,
        feather=feather,
        output=output,
        seed=seed,
    )
    patterns.check_bricks(axis, output, seed)
    x, y = np.asarray(x), np.asarray(y)
    dtype = x.dtype
    if axis not in patterns.BRICK_AXES or not kernel_takes(x, y):
        return patterns.bricks(x, y, **kwargs)
    bw, bh, half, feather = float(brick_width), float(brick_height), mortar / 2, float(feather)
    values = [bw, bh, offset, half, feather / 2, feather, 0, 1, 2, 3, bw - half, bh - half]
    values.append(patterns.CELL_INDEX_LIMIT)
    with np.errstate(all="ignore"):  # huge Python floats become inf in float32, as in numpy
        consts = np.array(values, dtype=np.float64).astype(dtype)
    shape = np.broadcast_shapes(x.shape, y.shape)
    out = np.empty(shape, dtype=np.float64)
    if output != "mask":
        code = patterns.BRICK_OUTPUTS.index(output)
        seed_term = worley_seed_term(int(seed or 0))
        xb, yb, by_row = np.broadcast_to(x, shape), np.broadcast_to(y, shape), axis == "row"
        parallel_rows(
            shape[0],
            shape[1],
            lambda a, b: _bricks_out_kernel(xb, yb, consts, by_row, code, seed_term, out, a, b),
        )
        return out
    if axis == "row" and x.shape == (1, shape[1]) and y.shape == (shape[0], 1):
        x_axis, y_axis, hard = x[0], y[:, 0], feather == 0
        parallel_rows(
            shape[0],
            shape[1],
            lambda a, b: _bricks_rows_kernel(x_axis, y_axis, consts, hard, out, a, b),
        )
        return out
    xb, yb = np.broadcast_to(x, shape), np.broadcast_to(y, shape)
    by_row, hard = axis == "row", feather == 0
    parallel_rows(
        shape[0], shape[1], lambda a, b: _bricks_kernel(xb, yb, consts, by_row, hard, out, a, b)
    )
    return out
