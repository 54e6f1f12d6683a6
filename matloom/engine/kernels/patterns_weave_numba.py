"""numba ``Weave``: the same numbers as :func:`matloom.engine.kernels.patterns.weave` for the
outputs ``mask``, ``warp``, ``weft`` and ``across``, in one pass per texel.

Exactness: every operation of the numpy version is kept, in the same order and in the
coordinate dtype (the parameters converted to it first, as numpy 2's weak-scalar promotion
does). The draft place uses numpy's floor-remainder (``fmod``, then the divisor's sign), which is
exact for the integer-valued operands here. ``output="along"`` (a per-draft-place search, see
:mod:`.patterns_weave`) and inputs the kernel does not take (other ranks, mixed or non-float
dtypes) go to the numpy version.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from matloom.engine.kernels import patterns
from matloom.engine.kernels.noise_numba_cells import worley_hash
from matloom.engine.kernels.noise_numba_core import jit_kernel
from matloom.engine.kernels.opensimplex import worley_seed_term
from matloom.engine.kernels.patterns_numba import _cell_int, _coverage, kernel_takes
from matloom.engine.kernels.threads import parallel_rows

#: The outputs the kernel computes, by code.
KERNEL_OUTPUTS = ("mask", "warp", "weft", "across", "thread_value")
_WARP_SALT = patterns.WARP_SALT
_WEFT_SALT = patterns.WEFT_SALT


@jit_kernel(parallel=False, inline=True)
def _floor_mod(a: float, b: float) -> float:
    """``np.mod(a, b)`` for floats: ``fmod`` moved to the divisor's sign (numpy's divmod)."""
    mod = np.fmod(a, b)
    if mod != 0:
        if (b < 0) != (mod < 0):
            mod += b
    else:
        mod = np.copysign(0.0, b)
    return mod


@jit_kernel()
def _weave_kernel(
    x: np.ndarray,
    y: np.ndarray,
    consts: np.ndarray,
    output: int,
    hard: bool,
    seed_term: int,
    out: np.ndarray,
    first: int,
    last: int,
) -> None:
    """Rows ``first``..``last - 1``; x, y broadcast to ``out``'s shape. consts (coordinate
    dtype): freq_x, freq_y, warp_width / 2, feather / 2, feather, 0, 1, 2, 3, 0.5, warp_width,
    over + under, shift, over, weft_width / 2, weft_width, columns and rows per period of
    the thread values (0: no wrap), the index limit 2**62."""
    fx, fy, half = consts[0], consts[1], consts[2]
    ramp = (consts[3], consts[4], consts[5], consts[6], consts[7], consts[8])
    zero, one, c05, width = consts[5], consts[6], consts[9], consts[10]
    repeat, shift, over = consts[11], consts[12], consts[13]
    weft_half, weft_width, ncols, nrows, limit = (
        consts[14],
        consts[15],
        consts[16],
        consts[17],
        consts[18],
    )
    for i in range(first, last):
        x_row, y_row, out_row = x[i], y[i], out[i]
        for j in range(out_row.size):
            u = x_row[j] * fx
            v = y_row[j] * fy
            col = np.floor(u)
            row = np.floor(v)
            top = _floor_mod(col - row * shift, repeat) < over
            if output == 4:  # thread value
                if top:
                    k = col if ncols == zero else col - np.floor(col / ncols) * ncols
                    value = worley_hash(_cell_int(k, limit), 0, seed_term, _WARP_SALT)
                else:
                    k = row if nrows == zero else row - np.floor(row / nrows) * nrows
                    value = worley_hash(0, _cell_int(k, limit), seed_term, _WEFT_SALT)
                out_row[j] = np.nan if k != k else value
                continue
            if output == 3:  # across
                if top:
                    t = ((u - col) - c05 + half) / width
                else:
                    t = ((v - row) - c05 + weft_half) / weft_width
                if t == t:
                    t = zero if t < zero else (one if t > one else t)
                out_row[j] = np.float64(t)
                continue
            if top:
                inset = half - abs((u - col) - c05)
            else:
                inset = weft_half - abs((v - row) - c05)
            value = _coverage(inset, ramp, hard)
            if (output == 1 and not top) or (output == 2 and top):
                value = 0.0
            out_row[j] = value


def weave(x: np.ndarray, y: np.ndarray, **kwargs: Any) -> np.ndarray:
    """Woven thread mask (or another output): :func:`patterns.weave` with the same keywords and
    the same numbers."""
    x, y = np.asarray(x), np.asarray(y)
    output = kwargs.get("output", "mask")
    if output not in KERNEL_OUTPUTS or not kernel_takes(x, y):
        return patterns.weave(x, y, **kwargs)
    if output == "thread_value" and kwargs.get("seed") is None:
        return patterns.weave(x, y, **kwargs)  # raises
    ww, feather = float(kwargs["warp_width"]), float(kwargs["feather"])
    weft = kwargs.get("weft_width")
    weft = ww if weft is None else float(weft)
    over, under, shift = (int(kwargs[k]) for k in ("over", "under", "shift"))
    values = [kwargs["freq_x"], kwargs["freq_y"], ww / 2, feather / 2, feather, 0, 1, 2, 3, 0.5]
    values += [ww, over + under, shift, over, weft / 2, weft]
    values += [*(kwargs.get("wrap") or (0, 0)), patterns.CELL_INDEX_LIMIT]
    seed_term = int(worley_seed_term(int(kwargs.get("seed") or 0)))
    with np.errstate(all="ignore"):  # huge Python floats become inf in float32, as in numpy
        consts = np.array(values, dtype=np.float64).astype(x.dtype)
    shape = np.broadcast_shapes(x.shape, y.shape)
    out = np.empty(shape, dtype=np.float64)
    xb, yb = np.broadcast_to(x, shape), np.broadcast_to(y, shape)
    code, hard = KERNEL_OUTPUTS.index(output), feather == 0
    parallel_rows(
        shape[0],
        shape[1],
        lambda a, b: _weave_kernel(xb, yb, consts, code, hard, seed_term, out, a, b),
    )
    return out
