"""numba ``Hash``: the numbers of :func:`matloom.engine.kernels.hashing.cell_hash` in one pass
(integer arithmetic, so the same bits by construction; see that module for the definition)."""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import numpy as np

from matloom.engine.kernels.hashing import (
    CELL_HI,
    CELL_LO,
    K_X,
    K_Y,
    MIX_1,
    MIX_2,
    NAN32,
    SHIFT_27,
    SHIFT_30,
    SHIFT_31,
    UNIT,
    VALUE_SHIFT,
    leaf3,
)
from matloom.engine.kernels.jit import jit

_OPTIONS: dict[str, Any] = {"nogil": True, "error_model": "numpy", "fastmath": False}


@jit(inline=True, **_OPTIONS)
def _mix64(z: np.uint64) -> np.uint64:
    z = (z ^ (z >> SHIFT_30)) * MIX_1
    z = (z ^ (z >> SHIFT_27)) * MIX_2
    return z ^ (z >> SHIFT_31)


@jit(**_OPTIONS)
def _hash_loop(x, y, keys, out):  # type: ignore[no-untyped-def]
    """out[s, i, j] = Hash of the broadcast (S|1, H|1, W|1) x and y with key ``keys[s]``."""
    n_s, n_i, n_j = out.shape
    for s in range(n_s):
        key = keys[s]
        xs = s if x.shape[0] > 1 else 0
        ys = s if y.shape[0] > 1 else 0
        for i in range(n_i):
            xi = i if x.shape[1] > 1 else 0
            yi = i if y.shape[1] > 1 else 0
            for j in range(n_j):
                cx = np.floor(x[xs, xi, j if x.shape[2] > 1 else 0])
                cy = np.floor(y[ys, yi, j if y.shape[2] > 1 else 0])
                if not (cx >= CELL_LO and cx < CELL_HI and cy >= CELL_LO and cy < CELL_HI):
                    out[s, i, j] = NAN32
                    continue
                h = _mix64(key + np.uint64(np.int64(cx)) * K_X)
                h = _mix64(h + np.uint64(np.int64(cy)) * K_Y)
                out[s, i, j] = np.float32(h >> VALUE_SHIFT) * UNIT


def cell_hash(x: Any, y: Any, keys: Sequence[int]) -> np.ndarray:
    """:func:`matloom.engine.kernels.hashing.cell_hash`, computed by numba."""
    x3, y3 = leaf3(x), leaf3(y)
    if x3.shape[0] > 1 and y3.shape[0] > 1 and x3.shape[0] != y3.shape[0]:
        raise ValueError("Hash: operands with different seed batches")
    shape = np.broadcast_shapes(x3.shape[1:], y3.shape[1:])
    out = np.empty((len(keys), *shape), dtype=np.float32)
    _hash_loop(x3, y3, np.asarray(keys, dtype=np.uint64), out)
    return out
