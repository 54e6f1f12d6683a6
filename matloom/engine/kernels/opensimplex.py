"""Shared, backend-independent pieces of the noise kernels (pure numpy, no numba).

* The OpenSimplex (2014, Kurt Spencer) 2-D constants and the seed -> permutation rule, exactly as
  in PyPI ``opensimplex==0.4.5.1`` (``internals._init`` / ``_noise2``), which the reference engine
  calls.  The package itself is never imported here: the reference's behaviour is reproduced.
  The lattice constants (stretch, squish) live with the lattice arithmetic in
  :mod:`matloom.ops.periodic`; the fBm octave schedule in :mod:`matloom.ops.octaves`.
* The Worley hash constants, metric/combination codes and ``to_01`` norms.
* Coordinate-shape helpers that let both backends exploit separable (1 x W, H x 1) axes.

Both ``noise_numpy`` and ``noise_numba`` import from here so that they share one definition of
every constant and every piece of arithmetic that must match the reference bit for bit.
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass

import numpy as np

# --- OpenSimplex 2-D ------------------------------------------------------------------------

NORM_CONSTANT2: float = 47.0
#: 8 gradient pairs, flattened; indexed with ``perm[...] & 0x0E`` then ``[i], [i + 1]``.
GRADIENTS2: np.ndarray = np.array(
    [5, 2, 2, 5, -5, 2, -2, 5, 5, -2, 2, -5, -5, -2, -2, -5], dtype=np.float64
)
GRADIENTS2.setflags(write=False)
#: Rescales the raw OpenSimplex range (about +-0.866) to about +-1 in fBm.
FBM_SCALE: float = 2.0 / math.sqrt(3.0)

_LCG_MUL = 6364136223846793005
_LCG_ADD = 1442695040888963407
_MASK64 = (1 << 64) - 1


def _wrap_int64(value: int) -> int:
    """Two's-complement wrap of a Python int to signed 64 bits (like ``ctypes.c_int64``)."""
    value &= _MASK64
    return value - (1 << 64) if value >= (1 << 63) else value


@functools.lru_cache(maxsize=4096)
def perm_from_seed(seed: int) -> np.ndarray:
    """Return opensimplex 0.4.5.1's permutation table for ``seed`` (read-only int64, (256,)).

    Three warm-up steps of the signed 64-bit LCG, then a Fisher-Yates style draw from 0..255
    with ``r = (s + 31) mod (i + 1)`` (non-negative).  Cached: seed sweeps reuse tables.
    """
    state = int(seed)
    for _ in range(3):
        state = _wrap_int64(state * _LCG_MUL + _LCG_ADD)
    source = list(range(256))
    perm = [0] * 256
    for i in range(255, -1, -1):
        state = _wrap_int64(state * _LCG_MUL + _LCG_ADD)
        r = (state + 31) % (i + 1)  # Python's % is already non-negative here
        perm[i] = source[r]
        source[r] = source[i]
    table = np.array(perm, dtype=np.int64)
    table.setflags(write=False)
    return table


def perms_for_seeds(seeds: list[int] | tuple[int, ...]) -> np.ndarray:
    """Permutation tables of many seeds at once, (S, 256) int64 (same rule as perm_from_seed).

    Vectorised over seeds with wrapping int64 numpy arithmetic: about 100x faster than S calls
    of the scalar Python version, which matters for 1000-seed sweeps.
    """
    state = np.array([_wrap_int64(int(s)) for s in seeds], dtype=np.int64)
    mul, add = np.int64(_LCG_MUL), np.int64(_LCG_ADD)
    for _ in range(3):
        state = state * mul + add
    rows = np.arange(state.size)
    source = np.tile(np.arange(256, dtype=np.int64), (state.size, 1))
    perm = np.empty_like(source)
    for i in range(255, -1, -1):
        state = state * mul + add
        modulus = i + 1
        r = (state % modulus + 31 % modulus) % modulus  # (s + 31) mod (i + 1), no overflow
        perm[:, i] = source[rows, r]
        source[rows, r] = source[:, i]
    return perm


# --- Worley -----------------------------------------------------------------------------------

WORLEY_HASH_CX = 1664525
WORLEY_HASH_CY = 22695477
WORLEY_HASH_SEED = 6364136223846793005
#: The two finaliser multipliers as signed int64 (0xFF51AFD7ED558CCD, 0xC4CEB9FE1A85EC53): the
#: reference hashes in int64, so its ``>> 33`` shifts are *arithmetic* (sign-propagating).
WORLEY_MIX1 = _wrap_int64(0xFF51AFD7ED558CCD)
WORLEY_MIX2 = _wrap_int64(0xC4CEB9FE1A85EC53)
#: Offsets of the 5 x 5 search block (dx outer, dy inner).
WORLEY_SEARCH = 2

DISTANCE_CODES: dict[str, int] = {"euclidean": 0, "manhattan": 1, "chebyshev": 2}
COMBINATION_CODES: dict[str, int] = {"F1": 0, "F2": 1, "F2-F1": 2, "F2+F1": 3}

_WORLEY_NORMS: dict[tuple[str, str], float] = {
    ("euclidean", "F1"): math.sqrt(2.0),
    ("euclidean", "F2"): math.sqrt(2.5),
    ("euclidean", "F2-F1"): math.sqrt(2.5),
    ("euclidean", "F2+F1"): 2.0 * math.sqrt(2.0),
    ("manhattan", "F1"): 2.0,
    ("manhattan", "F2"): 2.0,
    ("manhattan", "F2-F1"): 2.0,
    ("manhattan", "F2+F1"): 4.0,
    ("chebyshev", "F1"): 1.0,
    ("chebyshev", "F2"): 1.5,
    ("chebyshev", "F2-F1"): 1.5,
    ("chebyshev", "F2+F1"): 2.0,
}


def worley_codes(distance: str, combination: str) -> tuple[int, int, float]:
    """Validate the metric/combination names; return (metric code, combination code, norm)."""
    if distance not in DISTANCE_CODES:
        raise ValueError(f"unknown Worley distance {distance!r}; expected {list(DISTANCE_CODES)}")
    if combination not in COMBINATION_CODES:
        raise ValueError(
            f"unknown Worley combination {combination!r}; expected {list(COMBINATION_CODES)}"
        )
    norm = _WORLEY_NORMS[(distance, combination)]
    return DISTANCE_CODES[distance], COMBINATION_CODES[combination], norm


def worley_seed_term(seed: int) -> np.int64:
    """``seed * 6364136223846793005`` wrapped to int64: the seed's share of the Worley hash."""
    return np.int64(_wrap_int64(int(seed) * WORLEY_HASH_SEED))


# --- coordinate shapes ------------------------------------------------------------------------


@dataclass(frozen=True)
class CoordLayout:
    """How x/y were given: separable axes (``x_axis`` (W,), ``y_axis`` (H,)) or full grids.

    ``shape`` is the broadcast output shape the caller expects back.
    """

    shape: tuple[int, ...]
    separable: bool
    x_axis: np.ndarray | None = None
    y_axis: np.ndarray | None = None
    x_grid: np.ndarray | None = None
    y_grid: np.ndarray | None = None


def _as_float_array(a: np.ndarray) -> np.ndarray:
    """Keep float32/float64 arrays as they are; anything else becomes float64 (numpy promotion)."""
    arr = np.asarray(a)
    if arr.dtype == np.float32 or arr.dtype == np.float64:
        return arr
    return arr.astype(np.float64)


def coord_layout(x: np.ndarray, y: np.ndarray) -> CoordLayout:
    """Classify x/y as separable axes (x varies along columns only, y along rows only) or grids.

    Separable when the broadcast shape is 2-D (or less) and x has shape (1, W)/(W,)/(1, 1)/()
    while y has shape (H, 1)/(1, 1)/().  Everything else is broadcast to contiguous full grids,
    flattened to (1, N) for the kernels.
    """
    xa = _as_float_array(x)
    ya = _as_float_array(y)
    shape = np.broadcast_shapes(xa.shape, ya.shape)
    if len(shape) <= 2:
        h, w = (1, 1) if len(shape) == 0 else ((1, shape[0]) if len(shape) == 1 else shape)
        x2 = xa.reshape((1,) * (2 - xa.ndim) + xa.shape)
        y2 = ya.reshape((1,) * (2 - ya.ndim) + ya.shape)
        if x2.shape[0] == 1 and y2.shape[1] == 1:
            x_axis = np.ascontiguousarray(np.broadcast_to(x2, (1, w))[0])
            y_axis = np.ascontiguousarray(np.broadcast_to(y2, (h, 1))[:, 0])
            return CoordLayout(shape, True, x_axis=x_axis, y_axis=y_axis)
    x_grid = np.ascontiguousarray(np.broadcast_to(xa, shape)).reshape(-1)
    y_grid = np.ascontiguousarray(np.broadcast_to(ya, shape)).reshape(-1)
    return CoordLayout(shape, False, x_grid=x_grid, y_grid=y_grid)


def scale_coords(coords: np.ndarray, freq: float) -> np.ndarray:
    """``coords * freq`` with numpy semantics (float32 stays float32), returned as float64.

    For a float32 array numpy 2 rounds the Python float ``freq`` to float32 and multiplies in
    float32 -- the per-octave rounding the reference has.  The noise then runs in float64.
    """
    return np.asarray(coords * freq, dtype=np.float64)


def octave_axes(
    x_axis: np.ndarray, y_axis: np.ndarray, freqs_x: tuple[float, ...], freqs_y: tuple[float, ...]
) -> tuple[np.ndarray, np.ndarray]:
    """Per-octave float64 coordinates of separable axes: (O, W) and (O, H), each octave scaled
    in the axes' dtype (:func:`scale_coords`)."""
    xs = np.stack([scale_coords(x_axis, f) for f in freqs_x])
    ys = np.stack([scale_coords(y_axis, f) for f in freqs_y])
    return xs, ys


def scale_grid(coords: np.ndarray, freq: float) -> np.ndarray:
    """``coords * freq`` for full (non-separable) grids: widened to float64 first, then
    multiplied in float64 -- the reference's per-cell kernel, which takes the float32 rotated
    coordinates and scales them by ``f_k`` without rounding the product (unlike the separable
    axes of :func:`scale_coords`; see docs/compatibility.md)."""
    return np.asarray(coords, dtype=np.float64) * freq


@functools.lru_cache(maxsize=64)
def gradient_table(seed: int) -> np.ndarray:
    """Gradient number of every lattice vertex modulo 256, read-only uint8 (65536,).

    Entry ``(a << 8) | b`` is ``(perm[(perm[a] + b) & 255] & 14) >> 1``, i.e. the reference's
    ``_extrapolate2`` index halved (0..7) for a vertex with ``xsb & 255 == a``, ``ysb & 255 == b``.
    """
    perm = perm_from_seed(seed)
    a = np.arange(256)
    table = ((perm[(perm[a][:, None] + a[None, :]) & 0xFF] & 0x0E) >> 1).astype(np.uint8)
    table = table.reshape(-1)
    table.setflags(write=False)
    return table
