"""The numpy loops of fBm (OpenSimplex 2014) and Worley noise, bit-compatible with the reference.

This is the portable backend (no numba): :data:`FBM_LOOPS` and :data:`WORLEY_LOOPS` are run by
the one dispatch of :mod:`matloom.engine.kernels.noise` on its shared plans. The numba and C
loops must agree with these to <= 1e-12 (the C fBm bit for bit).  The arithmetic of
:func:`noise2` mirrors opensimplex 0.4.5.1's ``internals._noise2`` operation by operation (same
operands, same order), vectorised with ``np.where`` in place of the branches.  Work is done in
flat chunks to keep temporaries in cache.

Reference facts the fixtures pinned down beyond the spec text: Worley scales coordinates in
float64 (fBm scales each octave in the coordinate dtype), and its hash runs on wrapping int64,
so the ``>> 33`` shifts are arithmetic (sign-propagating), not logical.
"""

from __future__ import annotations

import numpy as np

from matloom.engine.kernels.mathops import exp_
from matloom.engine.kernels.noise import (
    WORLEY_CELL_SALT,
    WORLEY_EDGE_SEARCH,
    FbmLoops,
    FbmPlan,
    WorleyLoops,
    WorleyPlan,
)
from matloom.engine.kernels.opensimplex import (
    FBM_SCALE,
    GRADIENTS2,
    NORM_CONSTANT2,
    WORLEY_HASH_CX,
    WORLEY_HASH_CY,
    WORLEY_MIX1,
    WORLEY_MIX2,
    WORLEY_SEARCH,
    gradient_table,
    perm_from_seed,
    scale_grid,
    worley_seed_term,
)
from matloom.ops import portable_math
from matloom.ops.periodic import SQUISH_CONSTANT2, STRETCH_CONSTANT2

__all__ = ["FBM_LOOPS", "WORLEY_LOOPS", "fbm_tiled", "noise2", "noise2_tiled", "worley_hash"]

_CHUNK = 1 << 15  # elements per vectorised block
_TWO_SQUISH = 2.0 * SQUISH_CONSTANT2


# --- OpenSimplex 2-D --------------------------------------------------------------------------


def _vertex_term(
    perm: np.ndarray,
    xsb: np.ndarray,
    ysb: np.ndarray,
    off_x: np.ndarray | int,
    off_y: np.ndarray | int,
    dx0: np.ndarray,
    dy0: np.ndarray,
) -> np.ndarray:
    """Contribution of lattice vertex (xsb + off_x, ysb + off_y), 0 where attenuation <= 0.

    The displacement is ``(dx0 - off_x) - (off_x + off_y) * SQUISH`` which reproduces every
    vertex formula of the reference (e.g. ``dx0 - 1 - SQUISH``, ``dx0 - 1 - 2 * SQUISH``,
    ``dx0 + 1``) exactly: subtracting 0.0 or a negated integer is exact in IEEE arithmetic.
    """
    squish = (off_x + off_y) * SQUISH_CONSTANT2
    dx = (dx0 - off_x) - squish
    dy = (dy0 - off_y) - squish
    attn = 2 - dx * dx - dy * dy
    index = perm[(perm[(xsb + off_x) & 0xFF] + (ysb + off_y)) & 0xFF] & 0x0E
    extrapolated = GRADIENTS2[index] * dx + GRADIENTS2[index + 1] * dy
    positive = attn > 0
    attn = attn * attn
    return np.where(positive, attn * attn * extrapolated, 0.0)


def _ext_offsets(
    xins: np.ndarray, yins: np.ndarray, in_sum: np.ndarray
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Offsets of the extra vertex and of the base vertex (0,0)/(1,1), as in the reference."""
    lower = in_sum <= 1
    x_wins = xins > yins
    z_lo = 1 - in_sum
    z_hi = 2 - in_sum
    near_lo = (z_lo > xins) | (z_lo > yins)
    near_hi = (z_hi < xins) | (z_hi < yins)
    ext_x = np.where(
        lower,
        np.where(near_lo, np.where(x_wins, 1, -1), 1),
        np.where(near_hi, np.where(x_wins, 2, 0), 0),
    )
    ext_y = np.where(
        lower,
        np.where(near_lo, np.where(x_wins, -1, 1), 1),
        np.where(near_hi, np.where(x_wins, 0, 2), 0),
    )
    base = np.where(lower, 0, 1)
    return ext_x, ext_y, base


def noise2(
    x: np.ndarray, y: np.ndarray, perm: np.ndarray, skew_sum: np.ndarray | None = None
) -> np.ndarray:
    """OpenSimplex 2-D noise at float64 points (x, y broadcast together), raw range ~+-0.866.

    Non-finite inputs give 0 (every attenuation test fails), as in the reference. ``skew_sum``
    replaces the skew's ``x + y`` (exact in float64 by default); the parity tests pass the sum
    rounded to float32 to reproduce the reference's compiled kernel (docs/compatibility.md).
    """
    x = np.asarray(x, dtype=np.float64)
    y = np.asarray(y, dtype=np.float64)
    with np.errstate(invalid="ignore"):
        stretch_offset = (x + y if skew_sum is None else skew_sum) * STRETCH_CONSTANT2
        xs = x + stretch_offset
        ys = y + stretch_offset
        xsb_f = np.floor(xs)
        ysb_f = np.floor(ys)
        squish_offset = (xsb_f + ysb_f) * SQUISH_CONSTANT2
        dx0 = x - (xsb_f + squish_offset)
        dy0 = y - (ysb_f + squish_offset)
        xins = xs - xsb_f
        yins = ys - ysb_f
        xsb = xsb_f.astype(np.int64)
        ysb = ysb_f.astype(np.int64)
    ext_x, ext_y, base = _ext_offsets(xins, yins, xins + yins)
    value = _vertex_term(perm, xsb, ysb, 1, 0, dx0, dy0)
    value = value + _vertex_term(perm, xsb, ysb, 0, 1, dx0, dy0)
    value = value + _vertex_term(perm, xsb, ysb, base, base, dx0, dy0)
    value = value + _vertex_term(perm, xsb, ysb, ext_x, ext_y, dx0, dy0)
    return value / NORM_CONSTANT2


# --- fBm ----------------------------------------------------------------------------------------


def _finish_fbm(total: np.ndarray, norm: float, to_01: bool) -> np.ndarray:
    """Normalise by the amplitude sum, map to [0, 1] if asked, and clamp."""
    out = total / norm
    if to_01:
        return np.clip((out + 1) / 2, 0.0, 1.0)
    return np.clip(out, -1.0, 1.0)


def _row_blocks(height: int, width: int) -> list[slice]:
    """Row slices holding about ``_CHUNK`` elements each."""
    rows = max(1, _CHUNK // max(width, 1))
    return [slice(r, min(r + rows, height)) for r in range(0, height, rows)]


def _fbm_separable(
    plan: FbmPlan, seed: int, out: np.ndarray, mask: np.ndarray | None, fill: float
) -> None:
    """The separable fBm into ``out`` (H, W), in row blocks of about ``_CHUNK`` texels."""
    perm = perm_from_seed(seed)
    xs, ys, amps = plan.xs, plan.ys, plan.schedule.amps
    for rows in _row_blocks(*out.shape):
        total = np.zeros((rows.stop - rows.start, out.shape[1]))
        for k, amp in enumerate(amps):
            n = noise2(xs[k][None, :], ys[k][rows, None], perm)
            total = total + n * FBM_SCALE * amp
        out[rows] = _finish_fbm(total, plan.norm, plan.to_01)


def _fbm_grid(
    plan: FbmPlan, seed: int, out: np.ndarray, mask: np.ndarray | None, fill: float
) -> None:
    """The flat-grid fBm into ``out`` (N,), in chunks of ``_CHUNK`` texels; each octave's
    coordinates are widened to float64 and scaled (``scale_grid``)."""
    perm = perm_from_seed(seed)
    sched, lay = plan.schedule, plan.layout
    for start in range(0, out.size, _CHUNK):
        part = slice(start, start + _CHUNK)
        total = np.zeros(out[part].size)
        for k, amp in enumerate(sched.amps):
            xk = scale_grid(lay.x_grid[part], sched.freqs_x[k])
            yk = scale_grid(lay.y_grid[part], sched.freqs_y[k])
            total = total + noise2(xk, yk, perm) * FBM_SCALE * amp
        out[part] = _finish_fbm(total, plan.norm, plan.to_01)


# --- tileable fBm ------------------------------------------------------------------------------
# Per octave k the noise runs at ``p = M_k (x, y)`` (float64: ``m00 x + m01 y``, ``m10 x +
# m11 y``) with each vertex's gradient taken from its index reduced modulo the octave's
# sublattice (:mod:`.periodic`). The geometry is :func:`noise2`'s, operation by operation; the
# numba kernel (:mod:`.noise_numba_tileable`) repeats every operation in the same order.

#: As ``noise_numba_core._SAFE_FLOOR``: larger (or non-finite) lattice indices become 0.
_SAFE_FLOOR = 4.0e18


def wrapped_key(iv: np.ndarray, jv: np.ndarray, lattice: np.ndarray) -> np.ndarray:
    """Gradient-table key of lattice vertices (float64 integer indices) modulo the sublattice
    ``lattice`` = (p, q, r, 1/p, 1/r): ``(i' r + j') & 0xFFFF`` of the canonical representative
    (0 <= i' < p, 0 <= j' < r)."""
    p, q, r, inv_p, inv_r = (float(v) for v in lattice)
    k = np.floor((iv + 0.5) * inv_p)
    i2 = iv - k * p
    j2 = jv - k * q
    kj = np.floor((j2 + 0.5) * inv_r)
    j3 = j2 - kj * r
    return (i2 * r + j3).astype(np.int64) & 0xFFFF


def _term(
    table: np.ndarray,
    key: np.ndarray,
    off_x: np.ndarray | float,
    off_y: np.ndarray | float,
    dx0: np.ndarray,
    dy0: np.ndarray,
) -> np.ndarray:
    """One vertex's contribution (``noise_numpy._vertex_term`` with a table key)."""
    squish = (off_x + off_y) * SQUISH_CONSTANT2
    dx = (dx0 - off_x) - squish
    dy = (dy0 - off_y) - squish
    attn = 2 - dx * dx - dy * dy
    index = table[key].astype(np.int64) * 2
    extrapolated = GRADIENTS2[index] * dx + GRADIENTS2[index + 1] * dy
    positive = attn > 0
    attn = attn * attn
    return np.where(positive, attn * attn * extrapolated, 0.0)


def noise2_tiled(
    x: np.ndarray, y: np.ndarray, table: np.ndarray, lattice: np.ndarray
) -> np.ndarray:
    """OpenSimplex 2-D noise at float64 points with vertex indices wrapped by ``lattice``."""
    with np.errstate(invalid="ignore"):
        stretch_offset = (x + y) * STRETCH_CONSTANT2
        xs = x + stretch_offset
        ys = y + stretch_offset
        xsb = np.floor(xs)
        ysb = np.floor(ys)
        squish_offset = (xsb + ysb) * SQUISH_CONSTANT2
        dx0 = x - (xsb + squish_offset)
        dy0 = y - (ysb + squish_offset)
        xins = xs - xsb
        yins = ys - ysb
        xsb = np.where(np.abs(xsb) < _SAFE_FLOOR, xsb, 0.0)
        ysb = np.where(np.abs(ysb) < _SAFE_FLOOR, ysb, 0.0)
    ext_x, ext_y, base = _ext_offsets(xins, yins, xins + yins)
    ext_x, ext_y, base = (v.astype(np.float64) for v in (ext_x, ext_y, base))
    value = _term(table, wrapped_key(xsb + 1.0, ysb, lattice), 1.0, 0.0, dx0, dy0)
    value = value + _term(table, wrapped_key(xsb, ysb + 1.0, lattice), 0.0, 1.0, dx0, dy0)
    key = wrapped_key(xsb + base, ysb + base, lattice)
    value = value + _term(table, key, base, base, dx0, dy0)
    key = wrapped_key(xsb + ext_x, ysb + ext_y, lattice)
    value = value + _term(table, key, ext_x, ext_y, dx0, dy0)
    return value / NORM_CONSTANT2


def fbm_tiled(
    plan: FbmPlan, seed: int, out: np.ndarray, mask: np.ndarray | None, fill: float
) -> None:
    """The tileable fBm of ``plan`` into the flat ``out`` (N,); with a ``mask`` only its set
    texels are computed, the others get ``fill``."""
    assert plan.tile_maps is not None and plan.tile_lattices is not None
    table = gradient_table(int(seed))
    gx, gy = plan.grids64()
    idx = None if mask is None else np.flatnonzero(mask)
    if idx is not None:
        out[...] = fill
        gx, gy = gx[idx], gy[idx]
    values = np.empty(gx.size)
    for start in range(0, gx.size, _CHUNK):
        part = slice(start, start + _CHUNK)
        x, y = gx[part], gy[part]
        total = np.zeros(x.size)
        for k, amp in enumerate(plan.schedule.amps):
            m00, m01, m10, m11 = (float(v) for v in plan.tile_maps[k])
            px = m00 * x + m01 * y
            py = m10 * x + m11 * y
            n = noise2_tiled(px, py, table, plan.tile_lattices[k])
            total = total + n * FBM_SCALE * amp
        values[part] = _finish_fbm(total, plan.norm, plan.to_01)
    if idx is None:
        out[...] = values
    else:
        out[idx] = values


#: The pure-numpy fBm loops (what the numpy backend runs without the C extension).
FBM_LOOPS = FbmLoops("numpy", separable=_fbm_separable, grid=_fbm_grid, tiled=fbm_tiled)


# --- Worley -----------------------------------------------------------------------------------


def worley_hash(cx: np.ndarray, cy: np.ndarray, seed_term: np.int64, which: int) -> np.ndarray:
    """The reference's cell hash in [0, 1): a murmur-style finaliser on wrapping int64.

    The reference works in signed int64, so ``>> 33`` is an arithmetic shift (not the logical
    shift of a uint64 hash); the fixtures confirm this.  numpy int64 arrays wrap silently.
    """
    t = cx * np.int64(WORLEY_HASH_CX) + cy * np.int64(WORLEY_HASH_CY)
    t = t + seed_term + np.int64(which)
    t ^= t >> 33
    t *= np.int64(WORLEY_MIX1)
    t ^= t >> 33
    t *= np.int64(WORLEY_MIX2)
    t ^= t >> 33
    return (t & 0xFFFFFFFF).astype(np.float64) / 4294967296.0


def _metric(dx: np.ndarray, dy: np.ndarray, metric: int) -> np.ndarray:
    """Euclidean (0), Manhattan (1) or Chebyshev (2) length of (dx, dy)."""
    if metric == 0:
        return np.sqrt(dx * dx + dy * dy)
    if metric == 1:
        return np.abs(dx) + np.abs(dy)
    return np.maximum(np.abs(dx), np.abs(dy))


def _combine(f1: np.ndarray, f2: np.ndarray, combo: int, norm: float, to_01: bool) -> np.ndarray:
    """F1/F2/F2-F1/F2+F1, optional division by the fixed norm (clipped at 1), clamp >= 0."""
    with np.errstate(invalid="ignore"):
        out = (f1, f2, f2 - f1, f2 + f1)[combo]
        if to_01:
            out = np.minimum(out / norm, 1.0)
        return np.maximum(out, 0.0)


def _wrapped(
    cx: np.ndarray, cy: np.ndarray, wrap: tuple[int, int] | None
) -> tuple[np.ndarray, np.ndarray]:
    """The cell whose hash a cell takes: itself, or (tileable plans) its indices modulo
    ``wrap``'s cell counts."""
    if wrap is None:
        return cx, cy
    return np.mod(cx, np.int64(wrap[0])), np.mod(cy, np.int64(wrap[1]))


def _worley_points(
    u: np.ndarray,
    v: np.ndarray,
    seed_term: np.uint64,
    metric: int,
    wrap: tuple[int, int] | None = None,
) -> tuple[np.ndarray, np.ndarray]:
    """F1 and F2 over the 5 x 5 cell block around (floor u, floor v) (flat float64 inputs)."""
    finite = np.isfinite(u) & np.isfinite(v)
    cu = np.floor(np.where(finite, u, 0.0)).astype(np.int64)
    cv = np.floor(np.where(finite, v, 0.0)).astype(np.int64)
    f1 = np.full(u.shape, np.inf)
    f2 = np.full(u.shape, np.inf)
    for off_x in range(-WORLEY_SEARCH, WORLEY_SEARCH + 1):
        cx = cu + off_x
        for off_y in range(-WORLEY_SEARCH, WORLEY_SEARCH + 1):
            cy = cv + off_y
            hx, hy = _wrapped(cx, cy, wrap)
            px = cx + worley_hash(hx, hy, seed_term, 0)
            py = cy + worley_hash(hx, hy, seed_term, 1)
            d = _metric(u - px, v - py, metric)
            d = np.where(finite, d, np.nan)
            closer = d < f1
            f2 = np.where(closer, f1, np.where(d < f2, d, f2))
            f1 = np.where(closer, d, f1)
    return f1, f2


def _metric_key(dx: np.ndarray, dy: np.ndarray, metric: int) -> np.ndarray:
    """Squared Euclidean (0), Manhattan (1) or Chebyshev (2) length: the numba loops' key."""
    if metric == 0:
        return dx * dx + dy * dy
    return _metric(dx, dy, metric)


def _point(
    cx: np.ndarray, cy: np.ndarray, seed_term: np.int64, wrap: tuple[int, int] | None = None
) -> tuple[np.ndarray, np.ndarray]:
    """The feature point of cell (cx, cy) (hashed as its wrapped cell, see ``_wrapped``)."""
    hx, hy = _wrapped(cx, cy, wrap)
    return cx + worley_hash(hx, hy, seed_term, 0), cy + worley_hash(hx, hy, seed_term, 1)


def _nearest(
    u: np.ndarray,
    v: np.ndarray,
    seed_term: np.int64,
    metric: int,
    wrap: tuple[int, int] | None = None,
) -> tuple[np.ndarray, ...]:
    """(key, cx, cy, px, py): the nearest feature point over the 5 x 5 block by the metric's
    key (strict ``<``, the reference's order), its cell and position (finite u, v only)."""
    cu = np.floor(u).astype(np.int64)
    cv = np.floor(v).astype(np.int64)
    best = np.full(u.shape, np.inf)
    bx, by = cu.copy(), cv.copy()
    px, py = np.zeros(u.shape), np.zeros(u.shape)
    for off_x in range(-WORLEY_SEARCH, WORLEY_SEARCH + 1):
        cx = cu + off_x
        for off_y in range(-WORLEY_SEARCH, WORLEY_SEARCH + 1):
            cy = cv + off_y
            hx, hy = _point(cx, cy, seed_term, wrap)
            key = _metric_key(u - hx, v - hy, metric)
            closer = key < best
            best = np.where(closer, key, best)
            bx, by = np.where(closer, cx, bx), np.where(closer, cy, by)
            px, py = np.where(closer, hx, px), np.where(closer, hy, py)
    return best, bx, by, px, py


def _edge(
    u: np.ndarray,
    v: np.ndarray,
    seed_term: np.int64,
    freq_x: float,
    freq_y: float,
    wrap: tuple[int, int] | None = None,
) -> np.ndarray:
    """Distance in x/y units to the nearest border of the Euclidean cell (see WorleyPlan)."""
    key1, bx, by, p1x, p1y = _nearest(u, v, seed_term, 0, wrap)
    edge = np.full(u.shape, np.inf)
    reach = range(-WORLEY_EDGE_SEARCH, WORLEY_EDGE_SEARCH + 1)
    for off_x in reach:
        for off_y in reach:
            if off_x == 0 and off_y == 0:
                continue
            pkx, pky = _point(bx + off_x, by + off_y, seed_term, wrap)
            du, dv = u - pkx, v - pky
            num = ((du * du + dv * dv) - key1) * 0.5
            su, sv = (pkx - p1x) * freq_x, (pky - p1y) * freq_y
            den = np.sqrt(su * su + sv * sv)
            with np.errstate(divide="ignore", invalid="ignore"):
                d = np.where(den > 0, num / den, np.inf)
            edge = np.where(d < edge, d, edge)
    return edge


def _cells(u: np.ndarray, v: np.ndarray, seed_term: np.int64, plan: WorleyPlan) -> np.ndarray:
    """Cell values (output 1) or border distances (output 2) at flat u, v; NaN where either
    is not finite."""
    out = np.full(u.shape, np.nan)
    finite = np.isfinite(u) & np.isfinite(v)
    uf, vf = u[finite], v[finite]
    if plan.output == 1:
        _, bx, by, _, _ = _nearest(uf, vf, seed_term, plan.metric, plan.wrap)
        bx, by = _wrapped(bx, by, plan.wrap)
        out[finite] = worley_hash(bx, by, seed_term, WORLEY_CELL_SALT)
    else:
        out[finite] = _edge(uf, vf, seed_term, plan.freq_x, plan.freq_y, plan.wrap)
    return out


def _worley_values(
    u: np.ndarray, v: np.ndarray, seed_term: np.int64, plan: WorleyPlan
) -> np.ndarray:
    """The plan's output at flat float64 u, v."""
    if plan.output != 0:
        return _cells(u, v, seed_term, plan)
    if plan.smoothness > 0:  # language 3: a smooth F1
        return smooth_values(u, v, seed_term, plan)
    f1, f2 = _worley_points(u, v, seed_term, plan.metric, plan.wrap)
    return _combine(f1, f2, plan.combo, plan.norm, plan.to_01)


def _worley_dense(plan: WorleyPlan, seed: int, out: np.ndarray) -> None:
    """Worley noise into ``out`` (H, W): separable axes in row blocks, flat grids in chunks
    of ``_CHUNK`` texels."""
    seed_term = worley_seed_term(seed)
    if plan.layout.separable:
        u_axis, v_axis = plan.scaled()
        for rows in _row_blocks(*out.shape):
            u, v = np.broadcast_arrays(u_axis[None, :], v_axis[rows, None])
            out[rows] = _worley_values(u.ravel(), v.ravel(), seed_term, plan).reshape(u.shape)
        return
    flat = out.reshape(-1)
    for start in range(0, flat.size, _CHUNK):
        u, v = plan.scaled(start, start + _CHUNK)
        flat[start : start + _CHUNK] = _worley_values(u, v, seed_term, plan)


#: The numpy Worley loops.
WORLEY_LOOPS = WorleyLoops("numpy", dense=_worley_dense)


# ------------------------------------------------------------- Worley's smooth F1 (language 3)
# Worley's smooth F1 (language 3, ``Worley(smoothness=s)``), numpy loops and the shared finish.
#
# F1 is replaced by the smooth minimum of the distances ``d_k`` to the 25 feature points of the
# 5 x 5 cell block (the points Worley searches)::
#
#     F1_s = F1 - s * ln(sum_k exp(-(d_k - F1) / s))
#
# (log-sum-exp, shifted by F1 so that every term is in (0, 1] and the sum in [1, 25]): rounded
# cells, smooth across the Voronoi borders, at most F1 and at least F1 - s ln 25, and F1 itself
# where no other point is within a few s. Points outside the block are at least 2 cells away, so
# leaving them out changes the value by less than ``s * 25 * exp(-(2 - F1) / s)`` (below 1e-3
# for s <= 0.25 wherever F1 < 0.8, i.e. almost everywhere). F2 is unchanged; the combination,
# to_01 and the clamp at 0 then apply as usual.
#
# Bit-identical on every backend: the distances are the Worley loops' (the same operations), the
# sum runs in the same order (x offset outer, y offset inner), ``exp`` is the portable
# :func:`~matloom.engine.kernels.mathops.exp_` (``mathops_numba.exp`` in the numba loops of
# :mod:`.noise_numba_worley`) and the finish (:func:`finish`, with the portable log) is this
# module's numpy code on both.


def smooth_values(
    u: np.ndarray, v: np.ndarray, seed_term: np.int64, plan: WorleyPlan
) -> np.ndarray:
    """The plan's smooth-F1 output at flat float64 u, v (numpy loops)."""
    f1, f2 = _worley_points(u, v, seed_term, plan.metric, plan.wrap)
    s = plan.smoothness
    finite = np.isfinite(u) & np.isfinite(v)
    cu = np.floor(np.where(finite, u, 0.0)).astype(np.int64)
    cv = np.floor(np.where(finite, v, 0.0)).astype(np.int64)
    total = np.zeros(u.shape)
    with np.errstate(all="ignore"):
        for off_x in range(-WORLEY_SEARCH, WORLEY_SEARCH + 1):
            cx = cu + off_x
            for off_y in range(-WORLEY_SEARCH, WORLEY_SEARCH + 1):
                cy = cv + off_y
                hx, hy = (cx, cy) if plan.wrap is None else _wrap(cx, cy, plan.wrap)
                px = cx + worley_hash(hx, hy, seed_term, 0)
                py = cy + worley_hash(hx, hy, seed_term, 1)
                d = _metric(u - px, v - py, plan.metric)
                total = total + exp_(-(d - f1) / s)
    total = np.where(finite, total, np.nan)
    return finish(f1, f2, total, plan)


def _wrap(cx: np.ndarray, cy: np.ndarray, wrap: tuple[int, int]) -> tuple[np.ndarray, np.ndarray]:
    return np.mod(cx, np.int64(wrap[0])), np.mod(cy, np.int64(wrap[1]))


def finish(f1: np.ndarray, f2: np.ndarray, total: np.ndarray, plan: WorleyPlan) -> np.ndarray:
    """Combine F1_s (from F1 and the sum; F1 itself where the sum is not finite: non-finite
    coordinates, as the exact loops give them) and F2 as Worley does (both backends)."""
    f1 = np.asarray(f1, np.float64)
    ok = np.isfinite(total)
    with np.errstate(all="ignore"):
        log = portable_math.log(np.where(ok, total, 1.0))
        smooth = np.where(ok, f1 - plan.smoothness * log, f1)
    return _combine(smooth, np.asarray(f2, np.float64), plan.combo, plan.norm, plan.to_01)
