"""Periodic pattern kernels: ``Bricks`` and ``Weave`` (reference spec §2.5, §2.6).

Both kernels work on coordinate arrays ``x`` and ``y`` that broadcast to the output grid
(usually a float32 row ``(1, W)`` and a float32 column ``(H, 1)``; full ``(H, W)`` grids after a
``Rotate``). Parameters stay Python floats so every intermediate is computed in the coordinate
dtype, exactly as the reference's numpy code does under numpy 2's weak-scalar promotion
(NEP 50). The result is always a materialised float64 array of the broadcast shape.
"""

from __future__ import annotations

import numpy as np

BRICK_AXES: tuple[str, ...] = ("row", "column")


def smooth_coverage(s: np.ndarray, feather: float) -> np.ndarray:
    """Turn a signed inset ``s`` (positive inside) into coverage in [0, 1].

    Shared by Bricks, Weave, Fill and Stroke. With ``feather == 0`` the edge is hard and the
    boundary counts as inside (``s >= 0`` -> 1). Otherwise the smoothstep
    ``t*t*(3 - 2t)`` of ``t = clip((s + f/2)/f, 0, 1)`` is used, which is 0.5 on the boundary.
    The arithmetic happens in ``s``'s dtype; the result is always a new float64 array.
    """
    s = np.asarray(s)
    if feather == 0:
        return np.where(s >= 0, 1.0, 0.0)
    flat = s.reshape(1) if s.ndim == 0 else s  # in-place steps need arrays, not scalars
    t = flat + feather / 2  # the in-place steps keep the rounding of (t * t) * (3 - 2 * t)
    t /= feather
    np.clip(t, 0.0, 1.0, out=t)
    ramp = 2 * t
    np.subtract(3, ramp, out=ramp)
    ramp *= t * t
    return ramp.astype(np.float64, copy=False).reshape(s.shape)


def floor_mod(a: np.ndarray, b: float) -> np.ndarray:
    """Floor-mod written out as ``a - floor(a / b) * b`` (the reference's rounding; np.mod
    rounds differently, which the bricks_column fixture detects)."""
    return a - np.floor(a / b) * b


def _full_float64(coverage: np.ndarray, shape: tuple[int, ...]) -> np.ndarray:
    """``coverage`` (a fresh array from smooth_coverage) as a float64 array of ``shape``,
    copying only when it still needs broadcasting."""
    coverage = np.asarray(coverage, dtype=np.float64)
    return coverage if coverage.shape == shape else np.array(np.broadcast_to(coverage, shape))


def _grid_shape(x: np.ndarray, y: np.ndarray) -> tuple[int, ...]:
    """Broadcast shape of the two coordinate arrays."""
    return np.broadcast_shapes(np.shape(x), np.shape(y))


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
) -> np.ndarray:
    """Running-bond brick mask: 1 on brick, 0 in mortar (spec §2.5).

    ``axis="row"`` shifts each course (row of height ``brick_height``) right by
    ``offset * brick_width`` per row; ``axis="column"`` shifts each column up by
    ``offset * brick_height``. The inset distance is the min of the four axis distances
    to the mortar lines (not a true SDF); the half mortar ``mortar / 2`` is taken from each side.
    """
    if axis not in BRICK_AXES:
        raise ValueError(f"axis must be one of {BRICK_AXES}, got {axis!r}")
    bw, bh = float(brick_width), float(brick_height)
    x, y = np.asarray(x), np.asarray(y)
    with np.errstate(all="ignore"):  # non-finite coordinates give NaN quietly
        inset = _brick_inset(x, y, bw, bh, offset, mortar / 2, axis)
        return _full_float64(smooth_coverage(inset, feather), _grid_shape(x, y))


def _brick_inset(
    x: np.ndarray, y: np.ndarray, bw: float, bh: float, offset: float, half_mortar: float, axis: str
) -> np.ndarray:
    """Signed inset of each sample inside its brick (min of the four axis distances)."""
    if axis == "row":
        row = np.floor(y / bh)
        lx = floor_mod(x - row * offset * bw, bw)
        ly = floor_mod(y, bh)
    else:
        col = np.floor(x / bw)
        lx = floor_mod(x, bw)
        ly = floor_mod(y - col * offset * bh, bh)
    return np.minimum(
        np.minimum(lx - half_mortar, bw - half_mortar - lx),
        np.minimum(ly - half_mortar, bh - half_mortar - ly),
    )


def weave(
    x: np.ndarray,
    y: np.ndarray,
    *,
    over: int,
    under: int,
    shift: int,
    freq_x: float,
    freq_y: float,
    warp_width: float,
    feather: float,
) -> np.ndarray:
    """Woven thread mask: 1 on whichever thread is on top, 0 in the gaps (spec §2.6).

    Cell (col, row) = floor of (x * freq_x, y * freq_y). The warp (a vertical band centred
    in the cell) is on top where ``(col - row * shift) mod (over + under) < over``; otherwise
    the weft (a horizontal band). Band half-width is ``warp_width / 2`` in cell units and the
    feather is in cell-fraction units. Warp and weft both give 1.
    """
    x, y = np.asarray(x), np.asarray(y)
    with np.errstate(all="ignore"):  # non-finite coordinates give NaN quietly
        inset = _weave_inset(x * freq_x, y * freq_y, over, under, shift, warp_width / 2)
        return _full_float64(smooth_coverage(inset, feather), _grid_shape(x, y))


def _weave_inset(
    u: np.ndarray, v: np.ndarray, over: int, under: int, shift: int, half: float
) -> np.ndarray:
    """Signed inset into the thread on top at cell coordinates (u, v)."""
    col = np.floor(u)
    row = np.floor(v)
    repeat = int(over) + int(under)
    warp_on_top = np.mod(col - row * int(shift), repeat) < int(over)
    warp_inset = half - np.abs((u - col) - 0.5)
    weft_inset = half - np.abs((v - row) - 0.5)
    return np.where(warp_on_top, warp_inset, weft_inset)
