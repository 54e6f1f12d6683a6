"""Numba acceleration of the path distance and inside tests (same results as numpy).

:func:`path_distance_inside` is a drop-in for
:func:`matloom.engine.kernels.shapes.path_distance_inside`: it evaluates the identical float64
formulas (same operation order, no fast-math, NaN propagation like ``np.minimum``) per pixel,
with the rows split over threads, and applies the same ``cutoff`` rule (distances above it become +inf).
Culling differs from the numpy backend (per row and per pixel instead of per tile) but only
ever skips edges that provably cannot bring a distance down to ``cutoff``, so the outputs are
identical. Selected with ``backend="numba"`` in ``fill``/``stroke``.
"""

from __future__ import annotations

import numpy as np

from matloom.engine.kernels.jit import jit
from matloom.engine.kernels.shapes import as_grid_2d, cull_margin, path_edges
from matloom.engine.kernels.threads import parallel_rows

MODE_NONE = 0
MODE_NONZERO = 1
MODE_EVENODD = 2
_MODE_CODES = {None: MODE_NONE, "NonZero": MODE_NONZERO, "EvenOdd": MODE_EVENODD}


@jit()
def _segment_dist2(px: float, py: float, ax: float, ay: float, bx: float, by: float) -> float:
    """Squared point-to-segment distance, same operation order as the numpy path."""
    ex = bx - ax
    ey = by - ay
    wx = px - ax
    wy = py - ay
    length2 = ex * ex + ey * ey
    if length2 == 0.0:
        return wx * wx + wy * wy
    t = (wx * ex + wy * ey) / length2
    if t < 0.0:
        t = 0.0
    elif t > 1.0:
        t = 1.0
    qx = wx - t * ex
    qy = wy - t * ey
    return qx * qx + qy * qy


@jit()
def _winding_step(px: float, py: float, ax: float, ay: float, bx: float, by: float) -> int:
    """Winding contribution of one edge: +1 upward with a left turn, -1 downward right turn."""
    side = (bx - ax) * (py - ay) - (px - ax) * (by - ay)
    if ay <= by:
        if ay <= py and by > py and side > 0.0:
            return 1
        return 0
    if by <= py and ay > py and side < 0.0:
        return -1
    return 0


@jit()
def _ray_crosses(px: float, py: float, ax: float, ay: float, bx: float, by: float) -> bool:
    """Whether the +x ray from the point crosses the edge (even-odd rule)."""
    if (ay <= py) == (by <= py):
        return False
    return px < (bx - ax) * (py - ay) / (by - ay) + ax


@jit()
def _gap(value: float, lo: float, hi: float) -> float:
    """Distance from ``value`` to the interval [lo, hi] (0 inside)."""
    return max(lo - value, value - hi, 0.0)


@jit()
def _row_candidates(
    px_row: np.ndarray, py_row: np.ndarray, boxes: np.ndarray, limit: float
) -> tuple[np.ndarray, int, np.ndarray, int, bool]:
    """Edges possibly within ``limit`` of the row, and edges whose y-span meets the row.

    Returns (near, n_near, crossing, n_crossing, cull); ``cull`` is False (keep every edge)
    when the row has non-finite coordinates or ``limit`` is inf.
    """
    x_lo, x_hi = np.min(px_row), np.max(px_row)
    y_lo, y_hi = np.min(py_row), np.max(py_row)
    finite = np.isfinite(x_lo) and np.isfinite(x_hi) and np.isfinite(y_lo) and np.isfinite(y_hi)
    cull = finite and np.isfinite(limit)
    n_edges = boxes.shape[0]
    near = np.empty(n_edges, dtype=np.int64)
    crossing = np.empty(n_edges, dtype=np.int64)
    n_near = 0
    n_crossing = 0
    for k in range(n_edges):
        exmin, exmax, eymin, eymax = boxes[k, 0], boxes[k, 1], boxes[k, 2], boxes[k, 3]
        gap_x = max(exmin - x_hi, x_lo - exmax, 0.0)
        gap_y = max(eymin - y_hi, y_lo - eymax, 0.0)
        if not cull or (gap_x <= limit and gap_y <= limit):
            near[n_near] = k
            n_near += 1
        if eymin != eymax and (not finite or (eymin <= y_hi and eymax > y_lo)):
            crossing[n_crossing] = k
            n_crossing += 1
    return near, n_near, crossing, n_crossing, cull


@jit()
def _generic_row(
    px_row: np.ndarray,
    py_row: np.ndarray,
    edges: np.ndarray,
    boxes: np.ndarray,
    mode: int,
    limit: float,
    best_row: np.ndarray,
    inside_row: np.ndarray,
) -> None:
    """Any row layout: per-pixel loops over the row's candidate edges."""
    near, n_near, crossing, n_crossing, cull = _row_candidates(px_row, py_row, boxes, limit)
    for j in range(px_row.shape[0]):
        x = px_row[j]
        y = py_row[j]
        best = np.inf
        for n in range(n_near):
            k = near[n]
            if cull and (
                _gap(x, boxes[k, 0], boxes[k, 1]) > limit
                or _gap(y, boxes[k, 2], boxes[k, 3]) > limit
            ):
                continue
            d2 = _segment_dist2(x, y, edges[k, 0], edges[k, 1], edges[k, 2], edges[k, 3])
            if best == best and not d2 >= best:
                best = d2
        best_row[j] = best
        if mode == MODE_NONE:
            continue
        winding = 0
        for n in range(n_crossing):
            k = crossing[n]
            ax, ay, bx, by = edges[k, 0], edges[k, 1], edges[k, 2], edges[k, 3]
            if mode == MODE_NONZERO:
                winding += _winding_step(x, y, ax, ay, bx, by)
            elif _ray_crosses(x, y, ax, ay, bx, by):
                winding += 1
        inside_row[j] = winding != 0 if mode == MODE_NONZERO else winding % 2 == 1


@jit()
def _scan_order(px_row: np.ndarray, py_row: np.ndarray) -> int:
    """+1 / -1 for a finite row at one constant y with non-decreasing / non-increasing x
    (separable axes, possibly a mirrored View); 0 for anything else (e.g. after Rotate)."""
    y = py_row[0]
    rising = np.isfinite(y)
    falling = rising
    for j in range(px_row.shape[0]):
        if py_row[j] != y or not np.isfinite(px_row[j]):
            return 0
        if j > 0:
            rising = rising and px_row[j] >= px_row[j - 1]
            falling = falling and px_row[j] <= px_row[j - 1]
    return 1 if rising else (-1 if falling else 0)


@jit()
def _prefix_end(px_row: np.ndarray, y: float, edge: np.ndarray, mode: int) -> int:
    """Length of the pixel prefix for which one crossing edge counts at height ``y``.

    Along a scanline every rounded step of the side/intercept test is monotone in x, so the
    pixels where ``_winding_step``/``_ray_crosses`` fire form a prefix; binary search finds
    its end with the very same per-pixel expressions.
    """
    ax, ay, bx, by = edge[0], edge[1], edge[2], edge[3]
    lo = 0
    hi = px_row.shape[0]
    while lo < hi:
        mid = (lo + hi) // 2
        if mode == MODE_NONZERO:
            fires = _winding_step(px_row[mid], y, ax, ay, bx, by) != 0
        else:
            fires = _ray_crosses(px_row[mid], y, ax, ay, bx, by)
        if fires:
            lo = mid + 1
        else:
            hi = mid
    return lo


@jit()
def _scanline_row(
    px_row: np.ndarray,
    y: float,
    edges: np.ndarray,
    boxes: np.ndarray,
    mode: int,
    limit: float,
    best_row: np.ndarray,
    inside_row: np.ndarray,
) -> None:
    """Sorted-x row at one y: pixel ranges per edge by binary search (same values)."""
    width = px_row.shape[0]
    cull = np.isfinite(limit)
    best_row[:] = np.inf
    counts = np.zeros(width + 1, dtype=np.int64)
    for k in range(edges.shape[0]):
        ax, ay, bx, by = edges[k, 0], edges[k, 1], edges[k, 2], edges[k, 3]
        j0, j1 = 0, width
        if cull:
            if _gap(y, boxes[k, 2], boxes[k, 3]) > limit:
                j1 = 0
            else:
                j0 = np.searchsorted(px_row, boxes[k, 0] - limit, side="left")
                j1 = np.searchsorted(px_row, boxes[k, 1] + limit, side="right")
        for j in range(j0, j1):
            d2 = _segment_dist2(px_row[j], y, ax, ay, bx, by)
            best = best_row[j]
            if best == best and not d2 >= best:
                best_row[j] = d2
        if mode == MODE_NONE or ay == by or not boxes[k, 2] <= y < boxes[k, 3]:
            continue  # an edge only fires on rows with min(ay, by) <= y < max(ay, by)
        end = _prefix_end(px_row, y, edges[k], mode)
        step = -1 if mode == MODE_NONZERO and ay > by else 1
        counts[0] += step
        counts[end] -= step
    if mode != MODE_NONE:
        total = 0
        for j in range(width):
            total += counts[j]
            inside_row[j] = total != 0 if mode == MODE_NONZERO else total % 2 == 1


@jit()
def _load_row(coords: np.ndarray, i: int, out: np.ndarray) -> None:
    """Row ``i`` of a coordinate array that broadcasts to the grid ((1|H), (1|W))."""
    row = np.int64(i) if coords.shape[0] > 1 else np.int64(0)  # one integer type either way
    if coords.shape[1] == 1:
        out[:] = coords[row, 0]
    else:
        out[:] = coords[row, :]


@jit()
def _process_row(
    px: np.ndarray,
    py: np.ndarray,
    i: int,
    edges: np.ndarray,
    boxes: np.ndarray,
    mode: int,
    limit: float,
    cutoff: float,
    distance_row: np.ndarray,
    inside_row: np.ndarray,
) -> None:
    """Fill one output row: scanline algorithm for sorted rows at one y, else per pixel."""
    width = distance_row.shape[0]
    x_row = np.empty(width, dtype=np.float64)
    y_row = np.empty(width, dtype=np.float64)
    _load_row(px, i, x_row)
    _load_row(py, i, y_row)
    best_row = np.empty(width, dtype=np.float64)
    order = _scan_order(x_row, y_row)
    if order == 1:
        _scanline_row(x_row, y_row[0], edges, boxes, mode, limit, best_row, inside_row)
    elif order == -1:  # mirrored View: scan the reversed row, then put it back
        inside_rev = np.zeros(width, dtype=np.bool_)
        _scanline_row(x_row[::-1].copy(), y_row[0], edges, boxes, mode, limit, best_row, inside_rev)
        best_row = best_row[::-1].copy()
        for j in range(width):
            inside_row[j] = inside_rev[width - 1 - j]
    else:
        _generic_row(x_row, y_row, edges, boxes, mode, limit, best_row, inside_row)
    for j in range(width):
        dist = np.sqrt(best_row[j])
        distance_row[j] = np.inf if dist > cutoff else dist


@jit(nogil=True)
def _path_rows(
    px: np.ndarray,
    py: np.ndarray,
    edges: np.ndarray,
    boxes: np.ndarray,
    mode: int,
    limit: float,
    cutoff: float,
    distance: np.ndarray,
    inside: np.ndarray,
    first: int,
    last: int,
) -> None:
    """Rows ``first``..``last - 1`` of the min distance to ``edges`` (M, 4) (inf above
    ``cutoff``) and of the inside mask. Serial and ``nogil``: :func:`path_distance_inside`
    splits the rows over threads.

    ``px``/``py`` broadcast to ``distance``'s shape; each row is copied into contiguous
    buffers so that every helper sees one array type (one compiled specialisation).
    """
    for i in range(first, last):
        _process_row(px, py, i, edges, boxes, mode, limit, cutoff, distance[i], inside[i])


def _kernel_coords(values: np.ndarray) -> np.ndarray:
    """A writable C-contiguous float64 copy when needed (keeps one numba specialisation)."""
    values = np.asarray(values, dtype=np.float64)
    if not (values.flags.c_contiguous and values.flags.writeable):
        values = values.copy(order="C")
    return values


def path_distance_inside(
    points: np.ndarray, x: np.ndarray, y: np.ndarray, mode: str | None, cutoff: float = np.inf
) -> tuple[np.ndarray, np.ndarray | None]:
    """Distance to the polyline and inside mask; same contract as the numpy backend.

    ``mode=None`` measures to the open polyline and returns no mask; "NonZero"/"EvenOdd"
    close the polygon. Distances above ``cutoff`` are +inf.
    """
    code = _MODE_CODES[mode]
    edges = path_edges(points, closed=code != MODE_NONE)
    px, py, shape = as_grid_2d(x, y)
    height, width = np.broadcast_shapes(px.shape, py.shape)
    if height == 0 or width == 0:
        return np.full(shape, np.inf), (np.zeros(shape, dtype=bool) if code else None)
    finite_edges = bool(np.all(np.isfinite(edges)))
    limit = float(cutoff) + cull_margin(edges, px, py) if finite_edges else np.inf
    xs, ys = edges[:, 0::2], edges[:, 1::2]
    boxes = np.ascontiguousarray(
        np.stack([xs.min(axis=1), xs.max(axis=1), ys.min(axis=1), ys.max(axis=1)], axis=1)
    )
    distance = np.empty((height, width), dtype=np.float64)
    inside = np.zeros((height, width), dtype=np.bool_)
    args = (_kernel_coords(px), _kernel_coords(py), edges, boxes, code, limit, float(cutoff))
    parallel_rows(height, width, lambda a, b: _path_rows(*args, distance, inside, a, b))
    return distance.reshape(shape), (inside.reshape(shape) if code != MODE_NONE else None)
