"""``Hash(x, y, seed)``: a uniform value in [0, 1) per integer cell (floor(x), floor(y)).

The definition (numpy here; :mod:`matloom.engine.kernels.hash_numba` repeats it bit for bit,
integer arithmetic being exact):

* cell indices: ``cx = floor(x)`` and ``cy = floor(y)`` in float64, converted to int64 and
  reinterpreted as uint64 (two's complement). A cell index outside [-2**63, 2**63) -- x or y
  NaN, infinite or of magnitude 2**63 and beyond -- has no int64 value: the result is NaN (the
  CPU's default NaN, as 0/0 gives).
* the seed's key: ``mix64(seed * 0x9E3779B97F4A7C15 + 0x6A09E667F3BCC909)`` over Python
  integers modulo 2**64 (:func:`seed_key`);
* ``h = mix64(key + ix * K_X)``, then ``h = mix64(h + iy * K_Y)`` (uint64, wrapping), where
  ``mix64`` is splitmix64's finaliser (Stafford's mix 13): every input bit flips about half of
  the output bits, so neighbouring cells (and seeds) give independent values;
* the value: the top 24 bits of h times 2**-24, in [0, 1 - 2**-24]: a float32, like the noise
  fields, and exact in every float type (a seed batch may store it as float32).
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import numpy as np

MASK64 = (1 << 64) - 1
GOLDEN = 0x9E3779B97F4A7C15
SEED_SALT = 0x6A09E667F3BCC909
#: Odd multipliers of the x and y cell indices (splitmix64's and xxHash's primes).
K_X = np.uint64(0x9E3779B97F4A7C15)
K_Y = np.uint64(0xC2B2AE3D27D4EB4F)
MIX_1 = np.uint64(0xBF58476D1CE4E5B9)
MIX_2 = np.uint64(0x94D049BB133111EB)
SHIFT_30, SHIFT_27, SHIFT_31 = np.uint64(30), np.uint64(27), np.uint64(31)
#: h >> VALUE_SHIFT are the 24 bits of the value; times UNIT it is in [0, 1).
VALUE_SHIFT = np.uint64(40)
UNIT = np.float32(2.0**-24)
#: The value of a cell without an int64 index: the CPU's default NaN (see ``mathops.NAN``).
NAN32 = np.array(0xFFC00000, dtype=np.uint32).view(np.float32)[()]
#: Cell indices in [CELL_LO, CELL_HI) have an int64 value.
CELL_LO = -(2.0**63)
CELL_HI = 2.0**63


def _mix64_int(z: int) -> int:
    z = ((z ^ (z >> 30)) * 0xBF58476D1CE4E5B9) & MASK64
    z = ((z ^ (z >> 27)) * 0x94D049BB133111EB) & MASK64
    return z ^ (z >> 31)


def seed_key(seed: int) -> int:
    """The uint64 key of a seed (any integer; taken modulo 2**64)."""
    return _mix64_int(((int(seed) * GOLDEN) + SEED_SALT) & MASK64)


def mix64(z: np.ndarray) -> np.ndarray:
    """splitmix64's finaliser on uint64 arrays (wrapping arithmetic)."""
    z = (z ^ (z >> SHIFT_30)) * MIX_1
    z = (z ^ (z >> SHIFT_27)) * MIX_2
    return z ^ (z >> SHIFT_31)


def leaf3(value: Any) -> np.ndarray:
    """A field value as contiguous float64 (S|1, H|1, W|1) (a leading axis only for seed
    batches)."""
    array = np.ascontiguousarray(value, dtype=np.float64)
    if array.ndim > 3:
        raise ValueError(f"Hash: operand of rank {array.ndim}")
    return array.reshape((1,) * (3 - array.ndim) + array.shape)


def _cells(v: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(uint64 cell index, whether it exists) of float64 coordinates."""
    with np.errstate(invalid="ignore"):
        c = np.floor(v)
        valid = (c >= CELL_LO) & (c < CELL_HI)
    return np.where(valid, c, 0.0).astype(np.int64).view(np.uint64), valid


def cell_hash(x: Any, y: Any, keys: Sequence[int]) -> np.ndarray:
    """Hash values (float32) for each key (:func:`seed_key`) at the broadcast x, y: shape
    (len(keys), H, W) from the operands' (S|1, H|1, W|1) forms (:func:`leaf3`)."""
    x3, y3 = leaf3(x), leaf3(y)
    ix, vx = _cells(x3)
    iy, vy = _cells(y3)
    k = np.asarray(keys, dtype=np.uint64).reshape(-1, 1, 1)
    h = mix64(k + ix * K_X)
    h = mix64(h + iy * K_Y)
    out = (h >> VALUE_SHIFT).astype(np.float32) * UNIT
    return np.where(vx & vy, out, NAN32)


def hash_value(x: float, y: float, seed: int) -> float:
    """The Hash of one point (constant folding)."""
    return float(cell_hash(x, y, [seed_key(seed)])[0, 0, 0])
