"""Shape geometry, signed distances and the Fill/Stroke coverage kernels (spec §2.8).

Shapes are pure geometry (frozen dataclasses). ``fill`` and ``stroke`` turn one into a
[0, 1] coverage field sampled at coordinate arrays ``x``/``y`` that broadcast to the grid.

Precision, as in the reference's numpy code:

* Rect and Ellipse SDFs use the shape numbers as Python floats, so they are computed in the
  coordinate dtype (float32 on exporter axes).
* Paths are flattened to a float64 polyline; distance and inside tests are computed in
  float64 (coordinates are promoted), identically in the numpy and numba backends.

The numpy backend is the reference path; ``backend="numba"`` runs the compiled kernel in
:mod:`matloom.engine.kernels.shapes_numba`, which gives the same results.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from matloom.engine.kernels.patterns import smooth_coverage

#: Points appended per cubic segment (t = k/16, k = 1..16), fixed in the reference.
CUBIC_STEPS = 16
FILL_MODES: tuple[str, ...] = ("NonZero", "EvenOdd")
BACKENDS: tuple[str, ...] = ("numpy", "numba")


@dataclass(frozen=True)
class RectGeom:
    """Axis-aligned rectangle: (x, y) bottom-left corner, size, corner radius (pre-clamped)."""

    x: float
    y: float
    width: float
    height: float
    radius: float = 0.0


def make_rect(x: float, y: float, width: float, height: float, radius: float = 0.0) -> RectGeom:
    """Build a :class:`RectGeom`, clamping the corner radius to ``min(width, height) / 2``."""
    clamped = min(float(radius), min(float(width), float(height)) / 2)
    return RectGeom(float(x), float(y), float(width), float(height), clamped)


@dataclass(frozen=True)
class EllipseGeom:
    """Axis-aligned ellipse with centre (cx, cy) and radii (rx, ry)."""

    cx: float
    cy: float
    rx: float
    ry: float


@dataclass(frozen=True)
class LineSeg:
    """Straight path segment to (x, y)."""

    x: float
    y: float


@dataclass(frozen=True)
class CubicSeg:
    """Cubic Bezier path segment with control points c1, c2, ending at (x, y)."""

    c1x: float
    c1y: float
    c2x: float
    c2y: float
    x: float
    y: float


@dataclass(frozen=True)
class PathGeom:
    """Path starting at (start_x, start_y) followed by line/cubic segments."""

    start_x: float
    start_y: float
    segments: tuple[LineSeg | CubicSeg, ...]


Shape = RectGeom | EllipseGeom | PathGeom


def _cubic_points(p0: tuple[float, float], seg: CubicSeg) -> list[tuple[float, float]]:
    """The CUBIC_STEPS points of a cubic at t = k/CUBIC_STEPS (k >= 1), Bernstein form."""
    points = []
    for k in range(1, CUBIC_STEPS + 1):
        t = k / CUBIC_STEPS
        u = 1.0 - t
        b0, b1, b2, b3 = u * u * u, 3.0 * u * u * t, 3.0 * u * t * t, t * t * t
        px = b0 * p0[0] + b1 * seg.c1x + b2 * seg.c2x + b3 * seg.x
        py = b0 * p0[1] + b1 * seg.c1y + b2 * seg.c2y + b3 * seg.y
        points.append((px, py))
    return points


def flatten_path(path: PathGeom) -> np.ndarray:
    """Flatten a path to an (N, 2) float64 polyline (start point first, no closing point)."""
    points: list[tuple[float, float]] = [(float(path.start_x), float(path.start_y))]
    for seg in path.segments:
        if isinstance(seg, LineSeg):
            points.append((float(seg.x), float(seg.y)))
        elif isinstance(seg, CubicSeg):
            points.extend(_cubic_points(points[-1], seg))
        else:
            raise TypeError(f"path segments must be LineSeg or CubicSeg, got {type(seg).__name__}")
    return np.asarray(points, dtype=np.float64)


def rect_sdf(rect: RectGeom, x: np.ndarray, y: np.ndarray) -> np.ndarray:
    """Rounded-box signed distance (negative inside), in the coordinate dtype."""
    r = rect.radius
    cx, cy = rect.x + rect.width / 2, rect.y + rect.height / 2
    with np.errstate(all="ignore"):  # huge or non-finite coordinates just give inf/NaN
        qx = np.abs(x - cx) - (rect.width / 2 - r)
        qy = np.abs(y - cy) - (rect.height / 2 - r)
        outside = np.sqrt(np.maximum(qx, 0.0) ** 2 + np.maximum(qy, 0.0) ** 2)
        inside = np.minimum(np.maximum(qx, qy), 0.0)
        return outside + inside - r


def ellipse_sdf(ellipse: EllipseGeom, x: np.ndarray, y: np.ndarray) -> np.ndarray:
    """Approximate ellipse SDF ``k1 (k1 - 1) / k2`` (exact for circles), coordinate dtype.

    At the exact centre (k2 == 0) the value is ``-min(rx, ry)``.
    """
    rx, ry = ellipse.rx, ellipse.ry
    with np.errstate(all="ignore"):  # the centre divides by 0; huge coordinates overflow
        px = x - ellipse.cx
        py = y - ellipse.cy
        k1 = np.sqrt((px / rx) ** 2 + (py / ry) ** 2)
        k2 = np.sqrt((px / (rx * rx)) ** 2 + (py / (ry * ry)) ** 2)
        approx = k1 * (k1 - 1.0) / k2
    return np.where(k2 == 0, -min(rx, ry), approx)


def path_edges(points: np.ndarray, closed: bool) -> np.ndarray:
    """(M, 4) float64 edges (ax, ay, bx, by) of a polyline, closing it back if ``closed``."""
    pts = np.asarray(points, dtype=np.float64).reshape(-1, 2)
    if closed:
        pts = np.vstack([pts, pts[:1]])
    return np.ascontiguousarray(np.hstack([pts[:-1], pts[1:]]))


def cull_margin(edges: np.ndarray, px: np.ndarray, py: np.ndarray) -> float:
    """Safety margin for distance culling, far above float64 rounding at these magnitudes."""
    finite = [a[np.isfinite(a)] for a in (edges, px, py)]
    scale = max((float(np.max(np.abs(a))) for a in finite if a.size), default=0.0)
    return 1e-9 * (1.0 + scale)


def as_grid_2d(x: np.ndarray, y: np.ndarray) -> tuple[np.ndarray, np.ndarray, tuple[int, ...]]:
    """float64 coordinates viewed as broadcastable 2-D arrays, plus the broadcast shape."""
    px, py = np.asarray(x, dtype=np.float64), np.asarray(y, dtype=np.float64)
    shape = np.broadcast_shapes(px.shape, py.shape)
    if len(shape) == 2:
        return (
            px.reshape((1,) * (2 - px.ndim) + px.shape),
            py.reshape((1,) * (2 - py.ndim) + py.shape),
            shape,
        )
    rows = int(np.prod(shape[:-1], dtype=np.int64)) if len(shape) > 1 else 1
    grid = (rows, shape[-1] if shape else 1)
    return np.broadcast_to(px, shape).reshape(grid), np.broadcast_to(py, shape).reshape(grid), shape


def _segment_dist2(px: np.ndarray, py: np.ndarray, edge: np.ndarray) -> np.ndarray:
    """Squared distance from the points to one segment (point distance if degenerate)."""
    ax, ay, bx, by = (float(v) for v in edge)
    ex, ey = bx - ax, by - ay
    wx, wy = px - ax, py - ay
    length2 = ex * ex + ey * ey
    if length2 == 0.0:
        return wx * wx + wy * wy
    t = np.clip((wx * ex + wy * ey) / length2, 0.0, 1.0)
    qx = wx - t * ex
    qy = wy - t * ey
    return qx * qx + qy * qy


def _winding_step(px: np.ndarray, py: np.ndarray, edge: np.ndarray) -> np.ndarray:
    """Winding contribution of one edge: +1 upward crossing with the point on the left,
    -1 downward crossing with the point on the right (cross-product sign test)."""
    ax, ay, bx, by = (float(v) for v in edge)
    side = (bx - ax) * (py - ay) - (px - ax) * (by - ay)
    if ay <= by:
        return ((ay <= py) & (by > py) & (side > 0)).astype(np.int32)
    return -((by <= py) & (ay > py) & (side < 0)).astype(np.int32)


def _ray_crossing(px: np.ndarray, py: np.ndarray, edge: np.ndarray) -> np.ndarray:
    """Even-odd rule: the +x ray crosses the edge ((ay <= y) != (by <= y), x < intercept)."""
    ax, ay, bx, by = (float(v) for v in edge)
    straddles = (ay <= py) != (by <= py)
    x_cross = (bx - ax) * (py - ay) / (by - ay) + ax
    return straddles & (px < x_cross)


def _take(a: np.ndarray, rows: slice, cols: slice) -> np.ndarray:
    """Tile of a broadcastable 2-D array (length-1 axes are kept, not sliced)."""
    return a[rows if a.shape[0] != 1 else slice(None), cols if a.shape[1] != 1 else slice(None)]


def _edge_boxes(edges: np.ndarray) -> tuple[np.ndarray, ...]:
    """Per-edge bounding box (xmin, xmax, ymin, ymax)."""
    xs, ys = edges[:, 0::2], edges[:, 1::2]
    return xs.min(axis=1), xs.max(axis=1), ys.min(axis=1), ys.max(axis=1)


def _tile_candidates(
    boxes: tuple[np.ndarray, ...], tx: np.ndarray, ty: np.ndarray, limit: float
) -> tuple[np.ndarray, np.ndarray, bool]:
    """Edges that may lie within ``limit`` of the tile, edges whose y-span meets the tile, and
    whether distance culling applies.

    Only the exact crossing conditions use y, so the crossing cull is exact. Distance culling
    is off (every edge kept) when ``limit`` is inf or the tile has non-finite coordinates,
    so NaN/inf results are exactly those of the uncut computation.
    """
    exmin, exmax, eymin, eymax = boxes
    x_lo, x_hi, y_lo, y_hi = tx.min(), tx.max(), ty.min(), ty.max()
    if not np.all(np.isfinite((x_lo, x_hi, y_lo, y_hi))):
        return np.arange(len(exmin)), np.nonzero(eymin != eymax)[0], False
    crossing = np.nonzero((eymin <= y_hi) & (eymax > y_lo) & (eymin != eymax))[0]
    if not np.isfinite(limit):
        return np.arange(len(exmin)), crossing, False
    gap_x = np.maximum(np.maximum(exmin - x_hi, x_lo - exmax), 0.0)
    gap_y = np.maximum(np.maximum(eymin - y_hi, y_lo - eymax), 0.0)
    return np.nonzero((gap_x <= limit) & (gap_y <= limit))[0], crossing, True


def _span(values: np.ndarray, axis: int, lo: float, hi: float) -> slice:
    """Slice along ``axis`` (0 rows, 1 columns) covering the entries in [lo, hi] (empty if
    none) when ``values`` only varies along that axis; the whole axis otherwise."""
    if values.shape[1 - axis] != 1:
        return slice(None)
    hits = np.nonzero((values.ravel() >= lo) & (values.ravel() <= hi))[0]
    return slice(hits[0], hits[-1] + 1) if hits.size else slice(0, 0)


def _tile_fields(
    tx: np.ndarray,
    ty: np.ndarray,
    edges: np.ndarray,
    boxes: tuple[np.ndarray, ...],
    limit: float,
    mode: str | None,
) -> tuple[np.ndarray, np.ndarray]:
    """Min squared distance (near edges) and inside mask (crossing edges) on one tile.

    On separable tiles each edge only touches the rows (and, for distances, the columns)
    its bounding box can reach; the skipped pixels are provably beyond ``limit`` or cannot
    fire the crossing rules, so every value equals the full computation.
    """
    near, crossing, restrict = _tile_candidates(boxes, tx, ty, limit)
    best = np.full(np.broadcast_shapes(tx.shape, ty.shape), np.inf)
    for k in near:
        exmin, exmax, eymin, eymax = (b[k] for b in boxes)
        rows = _span(ty, 0, eymin - limit, eymax + limit) if restrict else slice(None)
        cols = _span(tx, 1, exmin - limit, exmax + limit) if restrict else slice(None)
        block = best[rows, cols]
        np.minimum(
            block, _segment_dist2(_take(tx, rows, cols), _take(ty, rows, cols), edges[k]), out=block
        )
    counter = np.zeros(best.shape, dtype=np.int32 if mode == "NonZero" else bool)
    for k in crossing if mode is not None else ():
        rows = _span(ty, 0, boxes[2][k], boxes[3][k])
        sub_x, sub_y = _take(tx, rows, slice(None)), _take(ty, rows, slice(None))
        if mode == "NonZero":
            counter[rows] += _winding_step(sub_x, sub_y, edges[k])
        else:
            counter[rows] ^= _ray_crossing(sub_x, sub_y, edges[k])
    return best, counter != 0


def path_distance_inside(
    points: np.ndarray,
    x: np.ndarray,
    y: np.ndarray,
    mode: str | None,
    cutoff: float = np.inf,
    tile: tuple[int, int] = (64, 256),
) -> tuple[np.ndarray, np.ndarray | None]:
    """Distance to the polyline and inside mask (numpy reference backend, float64).

    ``mode=None`` measures to the open polyline and returns no mask; "NonZero"/"EvenOdd"
    close the polygon and also return its inside mask. Distances above ``cutoff`` are returned
    as +inf (NaN stays NaN); this lets whole tiles skip edges that are provably farther than
    ``cutoff``, without changing any value at or below it. Work is done per tile of the
    grid, vectorised over the tile's pixels for each candidate edge.
    """
    with np.errstate(all="ignore"):  # non-finite samples or huge paths give inf/NaN quietly
        return _path_distance_inside(points, x, y, mode, cutoff, tile)


def _path_distance_inside(
    points: np.ndarray,
    x: np.ndarray,
    y: np.ndarray,
    mode: str | None,
    cutoff: float,
    tile: tuple[int, int],
) -> tuple[np.ndarray, np.ndarray | None]:
    """Body of :func:`path_distance_inside` (floating-point warnings already silenced)."""
    edges = path_edges(points, closed=mode is not None)
    px, py, shape = as_grid_2d(x, y)
    height, width = np.broadcast_shapes(px.shape, py.shape)
    limit = cutoff + cull_margin(edges, px, py) if np.all(np.isfinite(edges)) else np.inf
    boxes = _edge_boxes(edges)
    best = np.empty((height, width))
    inside = np.zeros((height, width), dtype=bool)
    for r0 in range(0, height, tile[0]):
        for c0 in range(0, width, tile[1]):
            rows, cols = slice(r0, r0 + tile[0]), slice(c0, c0 + tile[1])
            tx, ty = _take(px, rows, cols), _take(py, rows, cols)
            best[rows, cols], inside[rows, cols] = _tile_fields(tx, ty, edges, boxes, limit, mode)
    distance = np.sqrt(best)
    distance[distance > cutoff] = np.inf
    return distance.reshape(shape), (inside.reshape(shape) if mode is not None else None)


def _path_fields(
    path: PathGeom, x: np.ndarray, y: np.ndarray, mode: str | None, backend: str, cutoff: float
) -> tuple[np.ndarray, np.ndarray | None]:
    """Distance to the path (closed when ``mode`` is set) and the inside mask (or None)."""
    _check_options(mode or FILL_MODES[0], backend)
    points = flatten_path(path)
    if backend == "numba":
        from matloom.engine.kernels import shapes_numba

        return shapes_numba.path_distance_inside(points, x, y, mode, cutoff)
    return path_distance_inside(points, x, y, mode, cutoff)


def signed_distance(
    shape: Shape,
    x: np.ndarray,
    y: np.ndarray,
    *,
    mode: str = "NonZero",
    backend: str = "numpy",
    cutoff: float = np.inf,
) -> np.ndarray:
    """Signed distance of a shape (negative inside). ``mode`` only matters for paths.

    For paths, distances above ``cutoff`` come back as +-inf (see
    :func:`path_distance_inside`); Rect and Ellipse are always exact.
    """
    x, y = np.asarray(x), np.asarray(y)
    if isinstance(shape, RectGeom):
        return rect_sdf(shape, x, y)
    if isinstance(shape, EllipseGeom):
        return ellipse_sdf(shape, x, y)
    if isinstance(shape, PathGeom):
        distance, inside = _path_fields(shape, x, y, mode, backend, cutoff)
        return np.where(inside, -distance, distance)
    raise TypeError(f"expected a Rect, Ellipse or Path geometry, got {type(shape).__name__}")


def _outline_distance(
    shape: Shape, x: np.ndarray, y: np.ndarray, backend: str, cutoff: float
) -> np.ndarray:
    """Unsigned distance to the outline: |SDF| for Rect/Ellipse, open polyline for paths."""
    if isinstance(shape, PathGeom):
        distance, _ = _path_fields(shape, x, y, None, backend, cutoff)
        return distance
    return np.abs(signed_distance(shape, x, y))


def _check_options(mode: str, backend: str) -> None:
    """Reject an unknown fill mode or backend name."""
    if mode not in FILL_MODES:
        raise ValueError(f"mode must be one of {FILL_MODES}, got {mode!r}")
    if backend not in BACKENDS:
        raise ValueError(f"backend must be one of {BACKENDS}, got {backend!r}")


def _saturation_cutoff(reach: float) -> float:
    """A distance beyond which coverage is provably saturated (0 or 1) for edge ``reach``.

    Slightly enlarged so float rounding of ``reach`` itself can never cut a ramp short.
    """
    return reach * (1.0 + 1e-12) + 1e-300 if reach > 0 else 0.0


def _as_grid(coverage: np.ndarray, x: np.ndarray, y: np.ndarray) -> np.ndarray:
    """``coverage`` (a fresh array from smooth_coverage) as a float64 array of the
    coordinates' broadcast shape, copying only when it still needs broadcasting."""
    shape = np.broadcast_shapes(np.shape(x), np.shape(y))
    coverage = np.asarray(coverage, dtype=np.float64)
    return coverage if coverage.shape == shape else np.array(np.broadcast_to(coverage, shape))


def fill(
    shape: Shape,
    x: np.ndarray,
    y: np.ndarray,
    *,
    mode: str = "NonZero",
    feather: float = 0.0,
    backend: str = "numpy",
) -> np.ndarray:
    """Fill coverage: ``s = -SDF`` through :func:`smooth_coverage` (boundary counts as inside).

    ``mode`` ("NonZero" or "EvenOdd") selects the path inside rule; Rect/Ellipse ignore it.
    """
    _check_options(mode, backend)
    x, y = np.asarray(x), np.asarray(y)
    cutoff = _saturation_cutoff(feather / 2)
    if isinstance(shape, PathGeom):  # -(signed distance), in one pass
        distance, inside = _path_fields(shape, x, y, mode, backend, cutoff)
        inset = np.where(inside, distance, -distance)
    else:
        inset = -signed_distance(shape, x, y)
    with np.errstate(all="ignore"):
        return _as_grid(smooth_coverage(inset, feather), x, y)


def stroke(
    shape: Shape,
    x: np.ndarray,
    y: np.ndarray,
    *,
    width: float,
    feather: float = 0.0,
    backend: str = "numpy",
) -> np.ndarray:
    """Stroke coverage: ``s = width/2 - distance`` to the outline (paths are open here)."""
    _check_options(FILL_MODES[0], backend)
    x, y = np.asarray(x), np.asarray(y)
    cutoff = _saturation_cutoff(width / 2 + feather / 2)
    inset = width / 2 - _outline_distance(shape, x, y, backend, cutoff)
    with np.errstate(all="ignore"):
        return _as_grid(smooth_coverage(inset, feather), x, y)
