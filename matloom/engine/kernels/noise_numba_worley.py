"""The numba loops of Worley (cellular) noise, single-seed and seed-batched (:data:`WORLEY_LOOPS`,
run by :mod:`matloom.engine.kernels.noise`); numbers as ``noise_numpy``'s.

The reference hashes every one of the 25 cells around each pixel.  Here the feature points of
all cells the image can touch are tabulated once per call (and once per seed in a batch) when
that table is not much larger than the image; otherwise cells are hashed per pixel.  Each
feature point is ``cx + h(cx, cy, seed, 0)`` computed exactly as the reference does.

Consecutive pixels of a row that share their centre cell (a "run": typically many pixels per
cell) share the 25 candidate points, so the search loops over cells outside and pixels inside,
which vectorises.  Candidates are visited in the reference's order (dx outer, dy inner) with its
strict-``<`` F1/F2 update written as selects; Euclidean candidates are compared squared and
rooted once (sqrt is correctly rounded and monotone, so F1/F2 are bit-identical).

The cell values and border distances (``plan.output`` 1 and 2, see ``noise.WorleyPlan``) run
the kernels of :mod:`.noise_numba_cells` (which also holds the hash and the feature table) on
the same coordinates and table; for the border distances the table reaches
:data:`~matloom.engine.kernels.noise.WORLEY_EDGE_SEARCH` more cells.
"""

from __future__ import annotations

import numpy as np
from numba import prange

from matloom.engine.kernels.mathops_numba import exp
from matloom.engine.kernels.noise import WORLEY_EDGE_SEARCH, WorleyLoops, WorleyPlan
from matloom.engine.kernels.noise_numba_cells import (
    cells_batch_kernel,
    cells_kernel,
    fill_table,
    metric_key,
    worley_hash,
)
from matloom.engine.kernels.noise_numba_core import jit_kernel
from matloom.engine.kernels.opensimplex import worley_seed_term
from matloom.engine.kernels.threads import parallel_rows

__all__ = ["WORLEY_LOOPS", "worley_cell_box", "worley_hash", "fill_table"]

#: Largest feature-point table (cells) built per call; beyond it cells are hashed per pixel.
_MAX_TABLE_CELLS = 1 << 22
#: Shortest run of pixels sharing a centre cell that takes the vectorised path.
_MIN_RUN = 4


@jit_kernel(parallel=False, inline=True)
def final_length(key: float, metric: int) -> float:
    """Undo the squaring of ``metric_key`` for the Euclidean metric."""
    return np.sqrt(key) if metric == 0 else key


@jit_kernel(parallel=False, inline=True)
def update(f1: float, f2: float, d: float) -> tuple[float, float]:
    """The reference's ``if d < f1: f2, f1 = f1, d elif d < f2: f2 = d`` as selects."""
    closer = d < f1
    return (d if closer else f1), (f1 if closer else (d if d < f2 else f2))


@jit_kernel(parallel=False, inline=True)
def finish_worley(f1: float, f2: float, combo: int, norm: float, to_01: bool) -> float:
    """F1/F2/F2-F1/F2+F1, optional ``min(x / norm, 1)``, then clamp at 0 (NaN passes)."""
    if combo == 0:
        out = f1
    elif combo == 1:
        out = f2
    elif combo == 2:
        out = f2 - f1
    else:
        out = f2 + f1
    if to_01:
        out = out / norm
        if out > 1.0:
            out = 1.0
    if out < 0.0:
        out = 0.0
    return out


@jit_kernel(parallel=False)
def _run_keys(
    u: np.ndarray,
    v: np.ndarray,
    start: int,
    stop: int,
    ix: int,
    iy: int,
    metric: int,
    tx: np.ndarray,
    ty: np.ndarray,
    f1s: np.ndarray,
    f2s: np.ndarray,
) -> None:
    """F1/F2 keys of pixels start..stop-1, all with centre cell (iy, ix): cells outside.

    The pixel loops run over zero-based slice views: with a runtime ``start`` numba must allow
    for negative indices, which blocks vectorisation (measured ~6x slower).
    """
    run_u, run_v = u[start:stop], v[start:stop]
    run_f1, run_f2 = f1s[start:stop], f2s[start:stop]
    for m in range(run_u.size):
        run_f1[m] = np.inf
        run_f2[m] = np.inf
    for ox in range(-2, 3):
        for oy in range(-2, 3):
            px = tx[iy + oy, ix + ox]
            py = ty[iy + oy, ix + ox]
            for m in range(run_u.size):
                d = metric_key(run_u[m] - px, run_v[m] - py, metric)
                run_f1[m], run_f2[m] = update(run_f1[m], run_f2[m], d)


@jit_kernel(parallel=False)
def _row_keys_table(
    u: np.ndarray,
    v: np.ndarray,
    ix: np.ndarray,
    iy: np.ndarray,
    metric: int,
    tx: np.ndarray,
    ty: np.ndarray,
    f1s: np.ndarray,
    f2s: np.ndarray,
) -> None:
    """F1/F2 keys of one row from the feature table (ix/iy < 0 marks a non-finite pixel)."""
    j = 0
    while j < u.size:
        cx, cy = ix[j], iy[j]
        stop = j + 1
        while stop < u.size and ix[stop] == cx and iy[stop] == cy:
            stop += 1
        if cx < 0 or cy < 0:
            for m in range(j, stop):
                f1s[m] = np.inf
                f2s[m] = np.inf
        elif stop - j >= _MIN_RUN:
            _run_keys(u, v, j, stop, cx, cy, metric, tx, ty, f1s, f2s)
        else:
            for m in range(j, stop):
                f1, f2 = np.inf, np.inf
                for ox in range(-2, 3):
                    for oy in range(-2, 3):
                        dx = u[m] - tx[cy + oy, cx + ox]
                        f1, f2 = update(f1, f2, metric_key(dx, v[m] - ty[cy + oy, cx + ox], metric))
                f1s[m], f2s[m] = f1, f2
        j = stop


@jit_kernel(parallel=False)
def _row_keys_hash(
    u: np.ndarray, v: np.ndarray, metric: int, seed_term: int, f1s: np.ndarray, f2s: np.ndarray
) -> None:
    """F1/F2 keys of one row, hashing the 25 cells around every pixel (huge cell boxes)."""
    for m in range(u.size):
        f1, f2 = np.inf, np.inf
        if np.isfinite(u[m]) and np.isfinite(v[m]):
            cu = np.int64(np.floor(u[m]))
            cv = np.int64(np.floor(v[m]))
            for ox in range(-2, 3):
                for oy in range(-2, 3):
                    cx, cy = cu + ox, cv + oy
                    dx = u[m] - (cx + worley_hash(cx, cy, seed_term, 0))
                    dy = v[m] - (cy + worley_hash(cx, cy, seed_term, 1))
                    f1, f2 = update(f1, f2, metric_key(dx, dy, metric))
        f1s[m], f2s[m] = f1, f2


@jit_kernel(parallel=False)
def _worley_row(
    u: np.ndarray,
    v: np.ndarray,
    ix: np.ndarray,
    iy: np.ndarray,
    params: tuple,
    seed_term: int,
    tx: np.ndarray,
    ty: np.ndarray,
    out_row: np.ndarray,
) -> None:
    """One row of Worley values; ``params`` = (metric, combo, norm, to_01, use_table)."""
    metric, combo, norm, to_01, use_table = params
    f1s = np.empty(u.size)
    f2s = np.empty(u.size)
    if use_table:
        _row_keys_table(u, v, ix, iy, metric, tx, ty, f1s, f2s)
    else:
        _row_keys_hash(u, v, metric, seed_term, f1s, f2s)
    for m in range(u.size):
        f1 = final_length(f1s[m], metric)
        out_row[m] = finish_worley(f1, final_length(f2s[m], metric), combo, norm, to_01)


@jit_kernel(parallel=False)
def _layout_row(
    i: int,
    coords: tuple,
    params: tuple,
    seed_term: int,
    tx: np.ndarray,
    ty: np.ndarray,
    out_row: np.ndarray,
) -> None:
    """Row i: ``coords`` = (u, v, ix, iy, separable); separable u/ix are (W,), v/iy (H,);
    otherwise all four are flat (H * W,) grids."""
    u, v, ix, iy, separable = coords
    width = out_row.size
    if separable:
        v_row = np.full(width, v[i])
        iy_row = np.full(width, iy[i])
        _worley_row(u, v_row, ix, iy_row, params, seed_term, tx, ty, out_row)
    else:
        row = slice(i * width, (i + 1) * width)
        _worley_row(u[row], v[row], ix[row], iy[row], params, seed_term, tx, ty, out_row)


@jit_kernel()
def _worley_kernel(
    coords: tuple,
    params: tuple,
    seed_term: int,
    tx: np.ndarray,
    ty: np.ndarray,
    out: np.ndarray,
    first: int,
    last: int,
) -> None:
    """Rows ``first``..``last - 1`` of the (H, W) ``out``; serial and ``nogil``:
    :func:`_dense` splits the rows over threads."""
    for i in range(first, last):
        _layout_row(i, coords, params, seed_term, tx, ty, out[i])


@jit_kernel(parallel=False)
def _batch_seed(
    s: int, coords: tuple, params: tuple, seed_terms: np.ndarray, box: tuple, out: np.ndarray
) -> None:
    """out[s] (H, W) for seed s: rebuild the feature table, then every row."""
    cx0, cy0, nx, ny = box
    tx = np.empty((ny, nx))
    ty = np.empty((ny, nx))
    fill_table(cx0, cy0, seed_terms[s], tx, ty)
    for i in range(out.shape[1]):
        _layout_row(i, coords, params, seed_terms[s], tx, ty, out[s, i])


@jit_kernel(parallel=True)
def _batch_kernel(
    coords: tuple, params: tuple, seed_terms: np.ndarray, box: tuple, out: np.ndarray
) -> None:
    """Parallel over seeds; the work is in ``_batch_seed``."""
    for s in prange(out.shape[0]):
        _batch_seed(s, coords, params, seed_terms, box, out)


def worley_cell_box(
    u: np.ndarray, v: np.ndarray, n_pixels: int, reach: int = 2
) -> tuple[int, int, int, int]:
    """(cx0, cy0, nx, ny): the cells a search ``reach`` cells around finite (u, v) can touch
    (2: the 5 x 5 block).

    Returns nx = ny = 0 when that box exceeds the table budget (then cells are hashed).
    """
    fu = u[np.isfinite(u)]
    fv = v[np.isfinite(v)]
    if fu.size == 0 or fv.size == 0:
        return 0, 0, 1, 1
    lo_u, hi_u = np.floor(fu.min()) - reach, np.floor(fu.max()) + reach
    lo_v, hi_v = np.floor(fv.min()) - reach, np.floor(fv.max()) + reach
    nx, ny = hi_u - lo_u + 1, hi_v - lo_v + 1
    limit = min(_MAX_TABLE_CELLS, (2 * reach + 1) ** 2 * n_pixels + 4096)
    if max(abs(lo_u), abs(hi_u), abs(lo_v), abs(hi_v)) > 2.0**52 or nx * ny > limit:
        return 0, 0, 0, 0
    return int(lo_u), int(lo_v), int(nx), int(ny)


def _cell_index(w: np.ndarray, origin: int) -> np.ndarray:
    """Table index of each coordinate's cell (floor(w) - origin), -1 where w is not finite."""
    finite = np.isfinite(w)
    index = np.floor(np.where(finite, w, origin)) - origin
    return np.where(finite, index, -1).astype(np.int64)


def _prepare(plan: WorleyPlan) -> tuple[tuple, tuple[int, int, int, int]]:
    """The kernels' coordinates and cell box: (coords, box) with coords = (u, v, ix, iy,
    separable): the plan's float64 u/v (axes or flat grids) and each one's table index."""
    u, v = plan.scaled()
    height, width = plan.shape2d
    reach = 2 + (WORLEY_EDGE_SEARCH if plan.output == 2 else 0)
    box = worley_cell_box(u, v, height * width, reach)
    coords = (u, v, _cell_index(u, box[0]), _cell_index(v, box[1]), plan.layout.separable)
    return coords, box


def _params(plan: WorleyPlan, box: tuple[int, int, int, int]) -> tuple:
    """The row kernels' params for the plan and its cell box (nx = 0: no table): the distance
    loops' (``_worley_row``), or ``noise_numba_cells.cells_row``'s for the other outputs."""
    cx0, cy0, nx, _ = box
    if plan.output == 0:
        return (plan.metric, plan.combo, plan.norm, plan.to_01, nx > 0)
    freqs = (float(plan.freq_x), float(plan.freq_y))
    wrap = tuple(np.int64(n) for n in (plan.wrap or (0, 0)))
    return (plan.output, plan.metric, *freqs, nx > 0, np.int64(cx0), np.int64(cy0), *wrap)


def _fill_wrapped(
    box: tuple[int, int, int, int],
    seed_term: np.int64,
    wrap: tuple[int, int],
    tx: np.ndarray,
    ty: np.ndarray,
) -> None:
    """The feature table of a tileable plan: each cell's point hashed as its wrapped cell
    (``noise_numpy._point``'s numbers)."""
    from matloom.engine.kernels.noise_numpy import _point

    cx0, cy0, nx, ny = box
    cx = np.arange(cx0, cx0 + nx, dtype=np.int64)[None, :]
    cy = np.arange(cy0, cy0 + ny, dtype=np.int64)[:, None]
    px, py = _point(*np.broadcast_arrays(cx, cy), seed_term, wrap)
    tx[...] = px
    ty[...] = py


def _dense(plan: WorleyPlan, seed: int, out: np.ndarray) -> None:
    """Worley noise into ``out`` (H, W): feature table (when small enough), then row ranges
    on threads."""
    if plan.output == 0 and plan.smoothness > 0:  # language 3: a smooth F1
        smooth_dense(plan, seed, out)
        return
    seed_term = worley_seed_term(seed)
    coords, box = _prepare(plan)
    cx0, cy0, nx, ny = box
    if plan.wrap is not None and nx == 0:  # a tileable plan needs the (wrapped) table
        from matloom.engine.kernels import noise_numpy

        noise_numpy.WORLEY_LOOPS.dense(plan, seed, out)
        return
    tx = np.empty((max(ny, 1), max(nx, 1)), dtype=np.float64)
    ty = np.empty_like(tx)
    if plan.wrap is not None:
        _fill_wrapped(box, seed_term, plan.wrap, tx, ty)
    elif nx > 0:
        fill_table(np.int64(cx0), np.int64(cy0), seed_term, tx, ty)
    params = _params(plan, box)
    kernel = _worley_kernel if plan.output == 0 else cells_kernel
    parallel_rows(
        out.shape[0],
        out.shape[1],
        lambda a, b: kernel(coords, params, seed_term, tx, ty, out, a, b),
    )


def _seed_batch(plan: WorleyPlan, seeds: list[int]) -> np.ndarray | None:
    """Every seed at once, float32 (S, H, W); None (per-seed calls) when the feature table
    would be too large, or the image is empty.

    Coordinates and per-pixel cells are derived once; per seed only the feature-point table is
    rebuilt.  Parallel over seeds.
    """
    height, width = plan.shape2d
    if plan.wrap is not None or plan.smoothness > 0:  # per-seed calls (wrapped tables, or
        return None  # the smooth loops)
    coords, box = _prepare(plan)
    cx0, cy0, nx, ny = box
    if nx == 0 or height * width == 0:
        return None
    seed_terms = np.array([worley_seed_term(s) for s in seeds], dtype=np.int64)
    out = np.empty((len(seeds), height, width), dtype=np.float32)
    params = _params(plan, box)
    box = (np.int64(cx0), np.int64(cy0), nx, ny)
    (_batch_kernel if plan.output == 0 else cells_batch_kernel)(
        coords, params, seed_terms, box, out
    )
    return out


#: The numba Worley loops (with a seed-batch kernel).
WORLEY_LOOPS = WorleyLoops("numba", dense=_dense, seed_batch=_seed_batch)


# ------------------------------------------------------------- Worley's smooth F1 (language 3)
# numba loops of Worley's smooth F1 (see the end of :mod:`.noise_numpy`): per texel, F1, F2 and the sum
# of ``exp(-(d_k - F1) / s)`` over the 5 x 5 feature points, with the operations of the numpy
# loops in the same order (cells hashed per texel, wrapped in tileable plans); the finish (log,
# combination) is the shared numpy code, so the backends give the same bits.


@jit_kernel()
def _smooth_kernel(
    u: np.ndarray,
    v: np.ndarray,
    metric: int,
    s: float,
    seed_term: int,
    nx: int,
    ny: int,
    f1s: np.ndarray,
    f2s: np.ndarray,
    totals: np.ndarray,
    first: int,
    last: int,
) -> None:
    """Rows ``first``..``last - 1`` of the (H, W) outputs; u, v float64 (H, W); nx, ny the
    wrap's cell counts (0: no wrap)."""
    for i in range(first, last):
        for j in range(u.shape[1]):
            uu, vv = u[i, j], v[i, j]
            if not (np.isfinite(uu) and np.isfinite(vv)):
                f1s[i, j] = np.inf
                f2s[i, j] = np.inf
                totals[i, j] = np.nan
                continue
            cu, cv = np.int64(np.floor(uu)), np.int64(np.floor(vv))
            f1 = np.inf
            f2 = np.inf
            for ox in range(-2, 3):
                for oy in range(-2, 3):
                    cx, cy = cu + ox, cv + oy
                    hx, hy = (cx % nx, cy % ny) if nx > 0 else (cx, cy)
                    dx = uu - (cx + worley_hash(hx, hy, seed_term, 0))
                    dy = vv - (cy + worley_hash(hx, hy, seed_term, 1))
                    f1, f2 = update(f1, f2, final_length(metric_key(dx, dy, metric), metric))
            total = 0.0
            for ox in range(-2, 3):
                for oy in range(-2, 3):
                    cx, cy = cu + ox, cv + oy
                    hx, hy = (cx % nx, cy % ny) if nx > 0 else (cx, cy)
                    dx = uu - (cx + worley_hash(hx, hy, seed_term, 0))
                    dy = vv - (cy + worley_hash(hx, hy, seed_term, 1))
                    d = final_length(metric_key(dx, dy, metric), metric)
                    total = total + exp(-(d - f1) / s)
            f1s[i, j] = f1
            f2s[i, j] = f2
            totals[i, j] = total


def smooth_dense(plan: WorleyPlan, seed: int, out: np.ndarray) -> None:
    """The smooth-F1 Worley of ``plan`` into ``out`` (H, W)."""
    from matloom.engine.kernels.noise_numpy import finish

    height, width = out.shape
    if plan.layout.separable:
        u_axis, v_axis = plan.scaled()
        u = np.ascontiguousarray(np.broadcast_to(u_axis[None, :], (height, width)))
        v = np.ascontiguousarray(np.broadcast_to(v_axis[:, None], (height, width)))
    else:
        u, v = (np.ascontiguousarray(a.reshape(height, width)) for a in plan.scaled(0, None))
    f1s, f2s, totals = (np.empty((height, width)) for _ in range(3))
    nx, ny = plan.wrap or (0, 0)
    args = (u, v, plan.metric, float(plan.smoothness), int(worley_seed_term(seed)), nx, ny)
    parallel_rows(height, width, lambda a, b: _smooth_kernel(*args, f1s, f2s, totals, a, b))
    out[...] = finish(f1s, f2s, totals, plan)
