"""Periodic pattern kernels: ``Bricks`` and ``Weave`` (reference spec §2.5, §2.6).

Both kernels work on coordinate arrays ``x`` and ``y`` that broadcast to the output grid
(usually a float32 row ``(1, W)`` and a float32 column ``(H, 1)``; full ``(H, W)`` grids after a
``Rotate``). Parameters stay Python floats so every intermediate is computed in the coordinate
dtype, exactly as the reference's numpy code does under numpy 2's weak-scalar promotion
(NEP 50). The result is always a materialised float64 array of the broadcast shape.

Besides the masks, ``output`` selects per-brick values (cell value, position, distance to the
border; :func:`bricks`) or per-thread ones (warp/weft parts of the mask, position along and
across the thread; :func:`weave`, with the float search in :mod:`.patterns_weave`).
"""

from __future__ import annotations

import numpy as np

from matloom.engine.kernels.noise_numpy import worley_hash
from matloom.engine.kernels.opensimplex import worley_seed_term

BRICK_AXES: tuple[str, ...] = ("row", "column")
#: Bricks' ``output`` values; the numba kernels take their index.
BRICK_OUTPUTS: tuple[str, ...] = ("mask", "cell_value", "u", "v", "edge", "row", "column")
#: Bricks' outputs that are the brick's indices (wrapped in tileable output, as cell values).
BRICK_INDEX_OUTPUTS: tuple[str, ...] = ("row", "column")
#: ``which`` of the (Worley) cell hash for the bricks' cell values.
BRICK_CELL_SALT = 3
#: Brick indices are clamped to +-2**62 before they are hashed (both backends).
CELL_INDEX_LIMIT = float(2**62)
WEAVE_OUTPUTS: tuple[str, ...] = ("mask", "warp", "weft", "along", "across", "thread_value")
#: ``which`` of the (Worley) cell hash for the warp's and the weft's thread values.
WARP_SALT = 4
WEFT_SALT = 5


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
    output: str = "mask",
    seed: int | None = None,
    wrap: tuple[int, int, int] | None = None,
) -> np.ndarray:
    """Running-bond brick mask: 1 on brick, 0 in mortar (spec §2.5).

    ``axis="row"`` shifts each course (row of height ``brick_height``) right by
    ``offset * brick_width`` per row; ``axis="column"`` shifts each column up by
    ``offset * brick_height``. The inset distance is the min of the four axis distances
    to the mortar lines (not a true SDF); the half mortar ``mortar / 2`` is taken from each side.

    The other outputs (:func:`check_bricks`): ``u = lx / bw`` and ``v = ly / bh`` with (lx, ly)
    the position in the brick's cell (the floor-mods of the mask); ``edge`` the inset where it
    is >= 0, else 0 (inside a rectangle the min of the four side distances is the exact distance
    to its border); ``cell_value`` the Worley cell hash (salt :data:`BRICK_CELL_SALT`) of the
    brick's (column, row) indices (clamped to +-2**62), NaN where an index is NaN; ``row`` /
    ``column`` the indices themselves (as float64). With ``wrap`` (tileable output: bricks
    along a course, courses, and the bricks the course shift adds over them,
    :func:`~matloom.ops.periodic.course_wrap`) the indices are wrapped first, as Tile's cells
    are.
    """
    check_bricks(axis, output, seed)
    bw, bh = float(brick_width), float(brick_height)
    x, y = np.asarray(x), np.asarray(y)
    with np.errstate(all="ignore"):  # non-finite coordinates give NaN quietly
        if output == "mask":
            inset = _brick_inset(x, y, bw, bh, offset, mortar / 2, axis)
            return _full_float64(smooth_coverage(inset, feather), _grid_shape(x, y))
        value = _brick_output(x, y, bw, bh, offset, mortar / 2, axis, output, seed, wrap)
        return _full_float64(value, _grid_shape(x, y))


def check_bricks(axis: str, output: str, seed: int | None) -> None:
    """Raise ValueError for an unknown axis or output, or cell values without a seed."""
    if axis not in BRICK_AXES:
        raise ValueError(f"axis must be one of {BRICK_AXES}, got {axis!r}")
    if output not in BRICK_OUTPUTS:
        raise ValueError(f"output must be one of {BRICK_OUTPUTS}, got {output!r}")
    if output == "cell_value" and seed is None:
        raise ValueError('Bricks(output="cell_value") has no seed; canonicalise the program first')


def _brick_output(
    x: np.ndarray,
    y: np.ndarray,
    bw: float,
    bh: float,
    offset: float,
    half_mortar: float,
    axis: str,
    output: str,
    seed: int | None,
    wrap: tuple[int, int, int] | None = None,
) -> np.ndarray:
    """Bricks' cell value, u, v or edge (see :func:`bricks`) in the coordinate dtype (the cell
    value in float64)."""
    if output == "edge":
        inset = _brick_inset(x, y, bw, bh, offset, half_mortar, axis)
        return np.where(inset < 0, 0.0, inset)
    col, row, lx, ly = _brick_cell(x, y, bw, bh, offset, axis)
    if output == "u":
        return lx / bw
    if output == "v":
        return ly / bh
    nan = np.isnan(col) | np.isnan(row)
    if wrap is not None:
        from matloom.engine.kernels.tile import wrap_cell

        along, across, k = (float(v) for v in wrap)
        if axis == "row":
            row, col = wrap_cell(row, col, across, along, k)
        else:
            col, row = wrap_cell(col, row, across, along, k)
    if output in BRICK_INDEX_OUTPUTS:
        return (row if output == "row" else col).astype(np.float64)
    value = worley_hash(
        _cell_int(col), _cell_int(row), worley_seed_term(int(seed or 0)), BRICK_CELL_SALT
    )
    return np.where(nan, np.nan, value)


def _cell_int(c: np.ndarray) -> np.ndarray:
    """Brick indices as int64: clamped to +-2**62, NaN as 0."""
    c = np.clip(c, -CELL_INDEX_LIMIT, CELL_INDEX_LIMIT)
    return np.where(np.isnan(c), 0, c).astype(np.int64)


def _brick_cell(
    x: np.ndarray, y: np.ndarray, bw: float, bh: float, offset: float, axis: str
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """(column, row, lx, ly): the brick's indices and the position in its cell, with the
    floor-mods of :func:`_brick_inset` written out (the same operations)."""
    if axis == "row":
        row = np.floor(y / bh)
        a = x - row * offset * bw
        col = np.floor(a / bw)
        return col, row, a - col * bw, floor_mod(y, bh)
    col = np.floor(x / bw)
    b = y - col * offset * bh
    row = np.floor(b / bh)
    return col, row, floor_mod(x, bw), b - row * bh


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
    output: str = "mask",
    weft_width: float | None = None,
    seed: int | None = None,
    wrap: tuple[int, int] | None = None,
) -> np.ndarray:
    """Woven thread mask: 1 on whichever thread is on top, 0 in the gaps (spec §2.6).

    Cell (col, row) = floor of (x * freq_x, y * freq_y). The warp (a vertical band centred
    in the cell) is on top where ``(col - row * shift) mod (over + under) < over``; otherwise
    the weft (a horizontal band). Band half-widths are ``warp_width / 2`` and ``weft_width /
    2`` (None: the warp's) in cell units and the feather is in cell-fraction units. Warp and
    weft both give 1.

    ``output="warp"``/``"weft"``: the mask where that thread is on top, else 0; ``"across"``:
    ``clip(((u - col) - 0.5 + warp_width / 2) / warp_width, 0, 1)`` for the warp (v, row and
    weft_width for the weft); ``"along"``: see :func:`.patterns_weave.along`;
    ``"thread_value"``: the Worley cell hash of the thread on top, ``(col, 0)`` with salt
    :data:`WARP_SALT` for the warp and ``(0, row)`` with :data:`WEFT_SALT` for the weft (the
    index clamped to +-2**62, NaN where it is NaN); with ``wrap`` (tileable output: columns and
    rows per period, 0 for an axis that does not wrap) the index is taken modulo it first.
    """
    if output not in WEAVE_OUTPUTS:
        raise ValueError(f"output must be one of {WEAVE_OUTPUTS}, got {output!r}")
    if output == "thread_value" and seed is None:
        raise ValueError('Weave(output="thread_value") has no seed; canonicalise the program first')
    weft = warp_width if weft_width is None else weft_width
    x, y = np.asarray(x), np.asarray(y)
    shape = _grid_shape(x, y)
    with np.errstate(all="ignore"):  # non-finite coordinates give NaN quietly
        u, v = x * freq_x, y * freq_y
        cells = weave_cells(u, v, over, under, shift)
        if output in ("mask", "warp", "weft"):
            inset = _weave_inset(u, v, cells, warp_width / 2, weft / 2)
            coverage = smooth_coverage(inset, feather)
            if output != "mask":
                coverage = np.where(cells[3] == (output == "warp"), coverage, 0.0)
            return _full_float64(coverage, shape)
        col, row, _, warp_on_top = cells
        if output == "across":
            warp_a = np.clip((u - col - 0.5 + warp_width / 2) / warp_width, 0.0, 1.0)
            weft_a = np.clip((v - row - 0.5 + weft / 2) / weft, 0.0, 1.0)
            return _full_float64(np.where(warp_on_top, warp_a, weft_a), shape)
        if output == "thread_value":
            value = thread_value(col, row, warp_on_top, int(seed), wrap or (0, 0))  # type: ignore[arg-type]
            return _full_float64(value, shape)
        from matloom.engine.kernels.patterns_weave import along

        return _full_float64(along(u, v, cells, int(over), int(under), int(shift)), shape)


def weave_cells(
    u: np.ndarray, v: np.ndarray, over: int, under: int, shift: int
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """(col, row, w, warp_on_top) at cell coordinates (u, v): the cell, its place in the draft
    ``w = (col - row * shift) mod (over + under)`` and whether the warp is on top."""
    col = np.floor(u)
    row = np.floor(v)
    repeat = int(over) + int(under)
    w = np.mod(col - row * int(shift), repeat)
    return col, row, w, w < int(over)


def thread_value(
    col: np.ndarray, row: np.ndarray, warp_on_top: np.ndarray, seed: int, wrap: tuple[int, int]
) -> np.ndarray:
    """The random value of the thread on top (see :func:`weave`), float64."""
    ncols, nrows = (float(n) for n in wrap)
    if ncols:
        col = floor_mod(col, ncols)
    if nrows:
        row = floor_mod(row, nrows)
    term = worley_seed_term(int(seed))
    zero = np.zeros((), dtype=np.int64)
    warp = worley_hash(_cell_int(col), zero, term, WARP_SALT)
    weft = worley_hash(zero, _cell_int(row), term, WEFT_SALT)
    value = np.where(warp_on_top, warp, weft)
    return np.where(np.isnan(np.where(warp_on_top, col, row)), np.nan, value)


def _weave_inset(
    u: np.ndarray, v: np.ndarray, cells: tuple, half: float, weft_half: float
) -> np.ndarray:
    """Signed inset into the thread on top at cell coordinates (u, v)."""
    col, row, _, warp_on_top = cells
    warp_inset = half - np.abs((u - col) - 0.5)
    weft_inset = weft_half - np.abs((v - row) - 0.5)
    return np.where(warp_on_top, warp_inset, weft_inset)
