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
from matloom.engine.kernels.noise_numba_core import jit_kernel
from matloom.engine.kernels.patterns_numba import _coverage, kernel_takes
from matloom.engine.kernels.threads import parallel_rows

#: The outputs the kernel computes, by code.
KERNEL_OUTPUTS = ("mask", "warp", "weft", "across")


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
    out: np.ndarray,
    first: int,
    last: int,
) -> None:
    """Rows ``first``..``last - 1``; x, y broadcast to ``out``'s shape. consts (coordinate
    dtype): freq_x, freq_y, warp_width / 2, feather / 2, feather, 0, 1, 2, 3, 0.5, warp_width,
    over + under, shift, over."""
    fx, fy, half = consts[0], consts[1], consts[2]
    ramp = (consts[3], consts[4], consts[5], consts[6], consts[7], consts[8])
    zero, one, c05, width = consts[5], consts[6], consts[9], consts[10]
    repeat, shift, over = consts[11], consts[12], consts[13]
    for i in range(first, last):
        x_row, y_row, out_row = x[i], y[i], out[i]
        for j in range(out_row.size):
            u = x_row[j] * fx
            v = y_row[j] * fy
            col = np.floor(u)
            row = np.floor(v)
            top = _floor_mod(col - row * shift, repeat) < over
            if output == 3:  # across
                a = (u - col) if top else (v - row)
                t = (a - c05 + half) / width
                if t == t:
                    t = zero if t < zero else (one if t > one else t)
                out_row[j] = np.float64(t)
                continue
            if top:
                inset = half - abs((u - col) - c05)
            else:
                inset = half - abs((v - row) - c05)
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
    ww, feather = float(kwargs["warp_width"]), float(kwargs["feather"])
    over, under, shift = (int(kwargs[k]) for k in ("over", "under", "shift"))
    values = [kwargs["freq_x"], kwargs["freq_y"], ww / 2, feather / 2, feather, 0, 1, 2, 3, 0.5]
    values += [ww, over + under, shift, over]
    with np.errstate(all="ignore"):  # huge Python floats become inf in float32, as in numpy
        consts = np.array(values, dtype=np.float64).astype(x.dtype)
    shape = np.broadcast_shapes(x.shape, y.shape)
    out = np.empty(shape, dtype=np.float64)
    xb, yb = np.broadcast_to(x, shape), np.broadcast_to(y, shape)
    code, hard = KERNEL_OUTPUTS.index(output), feather == 0
    parallel_rows(
        shape[0], shape[1], lambda a, b: _weave_kernel(xb, yb, consts, code, hard, out, a, b)
    )
    return out
