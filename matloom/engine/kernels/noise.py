"""The noise primitives by concept: a shared *plan* and one dispatch over per-backend loops.

For fBm and for Worley, everything about a call that no backend does differently is computed
once, here, into a plan: parameter validation, the octave schedule (fBm) or metric codes and
norm (Worley), the coordinate layout (separable axes or full grids), the per-octave coordinates
scaled in the coordinate dtype as the reference does. A backend contributes only its inner
loops, as an :class:`FbmLoops` / :class:`WorleyLoops` record:

* ``noise_numpy.FBM_LOOPS`` / ``WORLEY_LOOPS``: vectorised numpy (portable);
* ``noise_c.FBM_LOOPS``: the optional C extension's fBm (numpy's numbers, cheap to import);
* ``noise_numba.FBM_LOOPS`` / ``WORLEY_LOOPS``: numba (coverage masks, seed batches).

:func:`fbm`, :func:`fbm_seed_batch`, :func:`worley` and :func:`worley_seed_batch` are the only
entry points; which loops they run is chosen in one place, the ``Backend`` table of
:mod:`matloom.engine.backends`. Seed batches fall back to one loop call per seed (sharing the
plan) when the loops have no batch kernel or it declines a call. Importing this module imports
neither numba nor the C extension.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from matloom.engine.kernels.opensimplex import (
    CoordLayout,
    coord_layout,
    octave_axes,
    scale_grid,
    worley_codes,
)
from matloom.ops.octaves import OctaveSchedule, octave_schedule
from matloom.ops.periodic import (
    MAX_PERIOD_CELLS,
    simplex_octave,
    simplex_wraps,
    snap_frequency,
    wraps,
)

__all__ = [
    "FbmPlan",
    "FbmLoops",
    "WorleyPlan",
    "WorleyLoops",
    "plan_fbm",
    "plan_worley",
    "run_fbm",
    "run_worley",
    "fbm",
    "fbm_seed_batch",
    "worley",
    "worley_seed_batch",
    "WORLEY_OUTPUTS",
    "WORLEY_CELL_SALT",
    "WORLEY_EDGE_SEARCH",
]


def _flat_shape2d(layout: CoordLayout, size: int) -> tuple[int, int]:
    """(rows, width) of a flat grid of ``size`` texels: the last axis of the output shape is a
    row (a 0-D/1-D or empty-width shape is one row of all texels)."""
    shape = layout.shape
    width = shape[-1] if len(shape) >= 2 and shape[-1] > 0 else max(size, 1)
    return size // width, width


# --- fBm ---------------------------------------------------------------------------------------


@dataclass
class FbmPlan:
    """The backend-independent part of an fBm call (see the module docstring); read-only.

    Separable layouts carry the per-octave float64 axes ``xs`` (O, W) and ``ys`` (O, H), each
    scaled in the axes' dtype; full grids carry the float64 per-octave frequencies ``fxs``/``fys``
    (O,): the loops widen the grid to float64 and then multiply (``scale_grid``).
    """

    schedule: OctaveSchedule
    to_01: bool
    layout: CoordLayout
    amps: np.ndarray
    xs: np.ndarray | None = None
    ys: np.ndarray | None = None
    fxs: np.ndarray | None = None
    fys: np.ndarray | None = None
    #: Tileable plans (``period`` given): per-octave coordinate maps (O, 4) and sublattices
    #: (O, 5) of :func:`simplex_tiling`; the loops' ``tiled``
    #: kernel samples the flat float64 grids ``grid_x``, ``grid_y``.
    tile_maps: np.ndarray | None = None
    tile_lattices: np.ndarray | None = None

    @property
    def tiled(self) -> bool:
        return self.tile_maps is not None

    def grids64(self) -> tuple[np.ndarray, np.ndarray]:
        """The flat float64 coordinates of every texel (separable axes broadcast)."""
        lay = self.layout
        if lay.separable:
            h, w = lay.y_axis.size, lay.x_axis.size
            gx = np.broadcast_to(lay.x_axis.astype(np.float64)[None, :], (h, w))
            gy = np.broadcast_to(lay.y_axis.astype(np.float64)[:, None], (h, w))
            return np.ascontiguousarray(gx).reshape(-1), np.ascontiguousarray(gy).reshape(-1)
        return lay.x_grid.astype(np.float64), lay.y_grid.astype(np.float64)

    @property
    def norm(self) -> float:
        return self.schedule.norm

    def octave_coords(self) -> tuple[np.ndarray, np.ndarray, int, int]:
        """(xs, ys, H, W) for the seed-batch kernels: the separable axes, or each octave's
        float64 coordinates of the flat grids (O, H * W) (computed on demand)."""
        lay = self.layout
        if lay.separable:
            assert self.xs is not None and self.ys is not None
            return self.xs, self.ys, self.ys.shape[1], self.xs.shape[1]
        sched = self.schedule
        xs = np.stack([scale_grid(lay.x_grid, f) for f in sched.freqs_x])
        ys = np.stack([scale_grid(lay.y_grid, f) for f in sched.freqs_y])
        return (xs, ys, *_flat_shape2d(lay, lay.x_grid.size))


def plan_fbm(
    x: np.ndarray,
    y: np.ndarray,
    *,
    octaves: int,
    lacunarity: float,
    gain: float,
    freq_x: float,
    freq_y: float,
    to_01: bool,
    period: tuple[float, float] | None = None,
) -> FbmPlan:
    """The :class:`FbmPlan` of an fBm on the broadcast of x and y; with ``period`` (Px, Py)
    the fBm repeats with those periods (:mod:`matloom.ops.periodic`), unless an octave has too
    many cells per period to wrap (:func:`~matloom.ops.periodic.simplex_wraps`, the predicate
    of fBm's period rule and the checker's W009): then it is unwrapped."""
    sched = octave_schedule(octaves, lacunarity, gain, freq_x, freq_y)
    amps = np.array(sched.amps, dtype=np.float64)
    lay = coord_layout(x, y)
    if period is not None and simplex_wraps(sched.freqs_x, sched.freqs_y, period):
        maps, lattices = simplex_tiling(sched.freqs_x, sched.freqs_y, period)
        plan = FbmPlan(sched, bool(to_01), lay, amps)
        plan.tile_maps, plan.tile_lattices = maps, lattices
        return plan
    if lay.separable:
        xs, ys = octave_axes(lay.x_axis, lay.y_axis, sched.freqs_x, sched.freqs_y)
        return FbmPlan(sched, bool(to_01), lay, amps, xs, ys)
    fxs = np.array(sched.freqs_x, dtype=np.float64)
    fys = np.array(sched.freqs_y, dtype=np.float64)
    return FbmPlan(sched, bool(to_01), lay, amps, fxs=fxs, fys=fys)


#: ``loop(plan, seed, out, mask, fill)``: fill ``out`` (float64; (H, W) for separable axes, the
#: flat (N,) grid otherwise) with the fBm; with a boolean ``mask`` of out's shape (loops with
#: ``masks`` only) the texels where it is clear get ``fill`` instead.
FbmLoop = Callable[[FbmPlan, int, np.ndarray, "np.ndarray | None", float], None]
#: ``seed_batch(plan, seeds, mask)``: float32 (S, H, W), or None to decline (per-seed calls).
FbmBatch = Callable[[FbmPlan, list[int], "np.ndarray | None"], "np.ndarray | None"]


@dataclass(frozen=True)
class FbmLoops:
    """One backend's inner loops of the fBm (the plan is shared)."""

    name: str
    separable: FbmLoop
    grid: FbmLoop
    #: The loops take a coverage mask (``Backend.fbm_masked``).
    masks: bool = False
    seed_batch: FbmBatch | None = None
    #: The tileable fBm (``loop(plan, seed, out, mask, fill)`` on the flat (N,) ``out``); the
    #: C loops run numpy's (``noise_numpy.fbm_tiled``).
    tiled: FbmLoop | None = None


def run_fbm(
    plan: FbmPlan,
    loops: FbmLoops,
    seed: int,
    mask: np.ndarray | None = None,
    fill: float = 0.0,
) -> np.ndarray:
    """The fBm of ``plan`` for ``seed`` on ``loops`` (float64, the layout's shape)."""
    lay = plan.layout
    where = None
    if mask is not None:
        if not loops.masks:
            raise ValueError(f"the {loops.name} fBm loops take no coverage mask")
        where = np.ascontiguousarray(np.broadcast_to(mask, lay.shape), dtype=np.bool_)
    if plan.tiled:
        if loops.tiled is None:
            raise ValueError(f"the {loops.name} fBm loops have no tileable fBm")
        flat = np.empty(int(np.prod(lay.shape, dtype=np.int64)), dtype=np.float64)
        loops.tiled(plan, seed, flat, None if where is None else where.reshape(-1), fill)
        return flat.reshape(lay.shape)
    if lay.separable:
        out = np.empty((lay.y_axis.size, lay.x_axis.size), dtype=np.float64)
        rows_mask = None if where is None else where.reshape(out.shape)
        loops.separable(plan, seed, out, rows_mask, fill)
    else:
        out = np.empty(lay.x_grid.size, dtype=np.float64)
        loops.grid(plan, seed, out, None if where is None else where.reshape(-1), fill)
    return out.reshape(lay.shape)


def fbm(
    x: np.ndarray,
    y: np.ndarray,
    *,
    loops: FbmLoops,
    seed: int,
    mask: np.ndarray | None = None,
    fill: float = 0.0,
    **params: Any,
) -> np.ndarray:
    """fBm of OpenSimplex noise on the broadcast of x and y (float64 result), on ``loops``;
    ``params`` are :func:`plan_fbm`'s (octaves, lacunarity, gain, freq_x, freq_y, to_01).

    Per octave k the coordinates are ``x * f_k``: in the axes' dtype on separable axes (float32
    axes round each octave's coordinates to float32, like the reference), in float64 on full
    grids (like the reference's per-cell kernel); the noise runs in float64. With
    a boolean ``mask`` (the broadcast shape) only the texels where it is set are computed
    (bit-identical to the dense values); the others hold ``fill``.
    """
    return run_fbm(plan_fbm(x, y, **params), loops, seed, mask, fill)


def fbm_seed_batch(
    x: np.ndarray,
    y: np.ndarray,
    *,
    loops: FbmLoops,
    seeds: Sequence[int],
    mask: np.ndarray | None = None,
    **params: Any,
) -> np.ndarray:
    """fBm for every seed in ``seeds``: float32 (S, *broadcast(x, y).shape); ``params`` are
    :func:`fbm`'s. The loops' batch kernel may differ from per-seed :func:`fbm` by 1e-6 (see
    ``noise_numba_batch``); with a ``mask`` it may leave the clear texels at a placeholder
    inside the fBm's range (coverage culling, see matloom.engine.cull)."""
    plan = plan_fbm(x, y, **params)
    seeds = [int(s) for s in seeds]
    batched = loops.seed_batch is not None and not plan.tiled
    batch = loops.seed_batch(plan, seeds, mask) if batched else None  # type: ignore[misc]
    return _stack(plan.layout.shape, seeds, batch, lambda seed: run_fbm(plan, loops, seed))


def _stack(
    shape: tuple[int, ...],
    seeds: list[int],
    batch: np.ndarray | None,
    one: Callable[[int], np.ndarray],
) -> np.ndarray:
    """float32 (S, *shape): the batch kernel's result, or (None: it declined) ``one(seed)``
    for each seed."""
    if batch is not None:
        return batch.reshape((len(seeds), *shape))
    out = np.empty((len(seeds), *shape), dtype=np.float32)
    for s, seed in enumerate(seeds):
        out[s] = one(seed)
    return out


def simplex_tiling(
    freqs_x: tuple[float, ...], freqs_y: tuple[float, ...], period: tuple[float, float]
) -> tuple[np.ndarray, np.ndarray]:
    """Per-octave (O, 4) coordinate maps and (O, 5) sublattices
    (:func:`~matloom.ops.periodic.simplex_octave`)."""
    if not simplex_wraps(freqs_x, freqs_y, period):
        raise ValueError(
            f"tileable periods must be finite and > 0, with at most {MAX_PERIOD_CELLS} cells "
            f"per period in every octave, got {period!r}"
        )
    px, py = (float(v) for v in period)
    rows = [simplex_octave(px, py, fx, fy) for fx, fy in zip(freqs_x, freqs_y, strict=True)]
    maps = np.array([m for m, _ in rows], dtype=np.float64)
    lattices = np.array([lat for _, lat in rows], dtype=np.float64)
    return maps, lattices


# --- Worley ------------------------------------------------------------------------------------

#: Worley's ``output`` names -> codes: 0 the combination of distances (the reference's Worley),
#: 1 a random value per cell, 2 the Euclidean distance to the nearest cell border.
WORLEY_OUTPUTS: dict[str, int] = {"distance": 0, "cell_value": 1, "edge": 2}
#: ``which`` of the cell hash for the cell values (0 and 1 place the feature points).
WORLEY_CELL_SALT = 2
#: Half-width of the cell block around the nearest feature point's cell whose points' bisectors
#: bound the distance to the border ("edge"): a border point z of the nearest point P1's cell
#: is at distance < sqrt(2) (in cells) from both P1 and the neighbour sharing it (every point is
#: within sqrt(2) of its own cell's feature point), so the neighbour lies within 2 sqrt(2) < 3
#: of P1 along each axis: its cell is at most 3 cells from P1's. The minimum over the 7 x 7
#: block's bisectors is the exact distance to the border (a bisector of a non-neighbour is
#: never closer than the cell's border).
WORLEY_EDGE_SEARCH = 3


@dataclass
class WorleyPlan:
    """The backend-independent part of a Worley call: codes, norm and coordinates; read-only.

    ``u = x * freq_x`` and ``v = y * freq_y`` are computed in float64 (unlike fBm, float32 axes
    are widened first -- the fixtures confirm this), on the axes or the flat grids.

    ``output`` (:data:`WORLEY_OUTPUTS`) 1 and 2 ignore combination, norm and to_01. Both find
    the nearest feature point over the 5 x 5 block by the metric's key (squared for Euclidean),
    strict ``<`` in the reference's order: under the call's metric for cell values (the value
    is ``h(cell, seed, WORLEY_CELL_SALT)``), Euclidean for the border distance, which is the
    minimum over the :data:`WORLEY_EDGE_SEARCH` block around the nearest cell of each bisector's
    distance in x/y units: ``(|q - Pk|^2 - |q - P1|^2) / 2 / |((Pk - P1)_u fx, (Pk - P1)_v fy)|``
    (a bisector with a zero denominator is skipped). Non-finite coordinates give NaN.
    """

    metric: int
    combo: int
    norm: float
    to_01: bool
    freq_x: float
    freq_y: float
    layout: CoordLayout
    #: Separable layouts: the scaled axes u (W,), v (H,).
    u_axis: np.ndarray | None = None
    v_axis: np.ndarray | None = None
    #: What the loops compute (:data:`WORLEY_OUTPUTS`).
    output: int = 0
    #: Tileable plans: cells per period (nx, ny); the loops hash cell (cx mod nx, cy mod ny).
    wrap: tuple[int, int] | None = None
    #: Language 3: > 0 replaces F1 by a smooth minimum of the distances (output 0 only; the
    #: loops at the end of :mod:`.noise_numpy` and :mod:`.noise_numba_worley`).
    smoothness: float = 0.0

    @property
    def shape2d(self) -> tuple[int, int]:
        """(H, W) of the loops' output: the axes' lengths, or rows of the flat grid."""
        lay = self.layout
        if lay.separable:
            return lay.y_axis.size, lay.x_axis.size
        return _flat_shape2d(lay, lay.x_grid.size)

    def scaled(self, start: int = 0, stop: int | None = None) -> tuple[np.ndarray, np.ndarray]:
        """(u, v) float64: the whole axes, or texels ``start:stop`` of the flat grids."""
        lay = self.layout
        if lay.separable:
            assert self.u_axis is not None and self.v_axis is not None
            return self.u_axis, self.v_axis
        part = slice(start, stop)
        return (
            lay.x_grid[part].astype(np.float64) * self.freq_x,
            lay.y_grid[part].astype(np.float64) * self.freq_y,
        )


def plan_worley(
    x: np.ndarray,
    y: np.ndarray,
    *,
    distance: str,
    combination: str,
    freq_x: float,
    freq_y: float,
    to_01: bool,
    output: str = "distance",
    period: tuple[float, float] | None = None,
    smoothness: float = 0.0,
) -> WorleyPlan:
    """The :class:`WorleyPlan` of a Worley call on the broadcast of x and y; with ``period``
    (Px, Py) the frequencies are snapped to whole numbers of cells per period and the cells
    wrap (:mod:`matloom.ops.periodic`), unless a period holds too many cells to
    wrap (the checker's W009): then the cells are not wrapped."""
    metric, combo, norm = worley_codes(distance, combination)
    if output not in WORLEY_OUTPUTS:
        raise ValueError(f"unknown Worley output {output!r}; expected {list(WORLEY_OUTPUTS)}")
    lay = coord_layout(x, y)
    wrap = None
    if period is not None and wraps(freq_x * period[0]) and wraps(freq_y * period[1]):
        freq_x, nx = snap_frequency(freq_x, float(period[0]))
        freq_y, ny = snap_frequency(freq_y, float(period[1]))
        wrap = (nx, ny)
    plan = WorleyPlan(metric, combo, float(norm), bool(to_01), freq_x, freq_y, lay)
    plan.wrap = wrap
    plan.output = WORLEY_OUTPUTS[output]
    if not float(smoothness) >= 0.0:
        raise ValueError(f"Worley smoothness must be >= 0, got {smoothness!r}")
    plan.smoothness = float(smoothness) if plan.output == 0 else 0.0
    if lay.separable:
        plan.u_axis = lay.x_axis.astype(np.float64) * freq_x
        plan.v_axis = lay.y_axis.astype(np.float64) * freq_y
    return plan


@dataclass(frozen=True)
class WorleyLoops:
    """One backend's inner loops of Worley noise (the plan is shared)."""

    name: str
    #: ``dense(plan, seed, out)``: fill ``out`` (float64 (H, W) = ``plan.shape2d``, non-empty).
    dense: Callable[[WorleyPlan, int, np.ndarray], None]
    #: ``seed_batch(plan, seeds)``: float32 (S, H, W), or None to decline (per-seed calls).
    seed_batch: Callable[[WorleyPlan, list[int]], np.ndarray | None] | None = None


def run_worley(plan: WorleyPlan, loops: WorleyLoops, seed: int) -> np.ndarray:
    """Worley noise of ``plan`` for ``seed`` on ``loops`` (float64, the layout's shape)."""
    out = np.empty(plan.shape2d, dtype=np.float64)
    if out.size:
        loops.dense(plan, seed, out)
    return out.reshape(plan.layout.shape)


def worley(
    x: np.ndarray, y: np.ndarray, *, loops: WorleyLoops, seed: int, **params: Any
) -> np.ndarray:
    """Worley (cellular) noise on the broadcast of x and y (float64 result), on ``loops``;
    ``params`` are :func:`plan_worley`'s (distance, combination, freq_x, freq_y, to_01, output).

    One feature point per cell at (c + h(c, seed, 0), c' + h(c, seed, 1)); F1/F2 over the
    5 x 5 cell block around (floor u, floor v); combined, normalised and clamped as the
    reference does (output="distance"; the other outputs: see :class:`WorleyPlan`).
    """
    return run_worley(plan_worley(x, y, **params), loops, seed)


def worley_seed_batch(
    x: np.ndarray,
    y: np.ndarray,
    *,
    loops: WorleyLoops,
    seeds: Sequence[int],
    **params: Any,
) -> np.ndarray:
    """Worley for every seed in ``seeds``: float32 (S, *broadcast(x, y).shape), the same
    values as per-seed :func:`worley` rounded to float32; ``params`` are :func:`worley`'s."""
    plan = plan_worley(x, y, **params)
    seeds = [int(s) for s in seeds]
    batch = loops.seed_batch(plan, seeds) if loops.seed_batch is not None else None
    return _stack(plan.layout.shape, seeds, batch, lambda seed: run_worley(plan, loops, seed))
