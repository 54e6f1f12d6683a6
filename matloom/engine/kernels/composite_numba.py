"""numba kernel: fused channel arithmetic + over-rule compositing, bit-identical to numpy.

One call composites a band of rows. Per row it runs a small register program (the channel
expressions above the primitive fields, compiled by :mod:`matloom.engine.schedules.banded`) and then applies
exactly the float32 compositing of :mod:`matloom.engine.composite`, so no full-size temporary
channel array is ever created.

Exactness: the register ops (+ - * safe-/ min max abs floor ceil sqrt) are IEEE operations whose
results numba and numpy compute identically; a float32 result is the float64 result rounded once
to float32, which equals the float32 operation (double rounding is exact for these ops). The only
transcendental step, the sRGB decode ``((s + 0.055) / 1.055) ** 2.4``, uses a cubic table with an
error far below 2**-44 relative. Its float32-rounded value equals numpy's unless the float64 value
lies within 2**-44 of a float32 rounding boundary; such texels (about 1 in 10**6) are flagged in
``uncertain`` and recomposited by the caller with the numpy reference path.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

from matloom.engine.colour import CERTAINTY_MARGIN
from matloom.engine.kernels.register_numba import _jit, load_leaves, run_code
from matloom.vocab.layout import LAYOUT, Group

# Channel slots of a layer in the layer tables (``chan_reg``/``chan_mode`` columns) and output
# planes (accumulator rows), all from :mod:`matloom.vocab.layout`; numba freezes them as
# constants when it compiles (a change of the layout must recompile these kernels).
#: Input slots per layer and the coverage (alpha) slot.
N_CHANNELS = LAYOUT.n_slots
CH_ALPHA = LAYOUT.coverage.slots[0]
#: Output planes: coverage, the scalars, the max channels (the first N_MAP_PLANES, the 2-D maps),
#: then the colour components.
N_PLANES = LAYOUT.n_planes
N_MAP_PLANES = LAYOUT.n_map_planes
PLANE_COVERAGE = LAYOUT.coverage.planes[0]
#: Over-blended scalars (slot order: the [0, 1] ones, then ior): slot, plane, clamp [lo, hi].
SCALAR_SLOTS = tuple(c.slots[0] for c in LAYOUT.scalars)
SCALAR_PLANES = tuple(c.planes[0] for c in LAYOUT.scalars)
SCALAR_LO = tuple(-np.inf if c.clamp[0] is None else float(c.clamp[0]) for c in LAYOUT.scalars)
SCALAR_HI = tuple(np.inf if c.clamp[1] is None else float(c.clamp[1]) for c in LAYOUT.scalars)
N_SCALARS = len(SCALAR_SLOTS)
#: Colour components (basecolor r g b, emissive r g b): slot, plane, whether x strength.
COLOUR_SLOTS = tuple(s for c in LAYOUT.colours for s in c.slots[:3])
COLOUR_PLANES = tuple(p for c in LAYOUT.colours for p in c.planes)
COLOUR_EMISSIVE = tuple(c.group is Group.COLOUR_STRENGTH for c in LAYOUT.colours for _ in range(3))
N_COLOURS = len(COLOUR_SLOTS)
#: First plane of each colour channel (its interleaved (H, W, 3) output), in ``colours`` order.
COLOUR_OUTPUT_PLANES = tuple(c.planes[0] for c in LAYOUT.colours)
#: Max-blended channels (height): slot, plane.
MAX_SLOTS = tuple(c.slots[0] for c in LAYOUT.maxed)
MAX_PLANES = tuple(c.planes[0] for c in LAYOUT.maxed)
N_MAX = len(MAX_SLOTS)


def _strength_slot() -> int:
    """The slot of the one colour x strength channel's strength (the kernel takes one)."""
    lit = LAYOUT.in_group(Group.COLOUR_STRENGTH)
    if len(lit) > 1:
        raise ValueError("the compositing kernel takes at most one colour+strength channel")
    return lit[0].slots[3] if lit else CH_ALPHA  # no strength: never read as one


CH_STRENGTH = _strength_slot()

#: Channel modes: RAW = evaluate and convert here; READY = register holds the final float32
#: value; DECODED = emissive colour already linear (float64); ZERO = constant 0 after conversion.
RAW, READY, DECODED, ZERO = 0, 1, 2, 3

#: Fixed leaf-slot counts (a fixed tuple length keeps one compiled, cached signature).
MAX_LEAVES64 = 16
MAX_LEAVES32 = 8

#: Relative margin of the certainty test of the sRGB table (see the module docstring): the one
#: the numpy path's decode uses too.
DECODE_MARGIN = CERTAINTY_MARGIN
_LUT_X0 = 0.09
_LUT_INTERVALS = 16384
_LUT_INV_H = _LUT_INTERVALS / (1.0 - _LUT_X0)

#: Intervals of the linear preview table (error < 4e-7, for previews only; 8 KiB stays in L1).
_FAST_INTERVALS = 1024


def fast_decode_table() -> np.ndarray:
    """(N + 1,) decoded values at s = k / N: the linear table of the preview (sweep) mode."""
    from matloom.engine.colour import srgb_to_linear

    return srgb_to_linear(np.arange(_FAST_INTERVALS + 1, dtype=np.float64) / _FAST_INTERVALS)


def decode_table() -> np.ndarray:
    """(N, 4) cubic Hermite coefficients of x ** 2.4 on [0.09, 1] (t in [0, 1) per interval).

    Values and slopes come from long double arithmetic, so each coefficient is correctly
    rounded to float64 up to a few units in the last place of long double.
    """
    ld = np.longdouble
    nodes = ld(_LUT_X0) + np.arange(_LUT_INTERVALS + 1, dtype=ld) * (
        (ld(1) - ld(_LUT_X0)) / ld(_LUT_INTERVALS)
    )
    exponent = ld(2.4)
    values = nodes**exponent
    h = (ld(1) - ld(_LUT_X0)) / ld(_LUT_INTERVALS)
    slopes = exponent * nodes ** (exponent - 1) * h
    f0, f1, d0, d1 = values[:-1], values[1:], slopes[:-1], slopes[1:]
    coefs = np.stack([f0, d0, 3 * (f1 - f0) - 2 * d0 - d1, 2 * (f0 - f1) + d0 + d1], axis=1)
    return np.ascontiguousarray(coefs.astype(np.float64))


@_jit(inline=True)
def _clip01_f32(v: float) -> np.float32:
    """float32 cast then clamp to [0, 1] (NaN passes), like ``np.clip(float32(v), 0, 1)``."""
    x = np.float32(v)
    if x < np.float32(0.0):
        return np.float32(0.0)
    if x > np.float32(1.0):
        return np.float32(1.0)
    return x


@_jit()
def decode_row(src, lut, lin, scaled):  # type: ignore[no-untyped-def]
    """lin = sRGB decode of s = clamp(src / 255, 0, 1) in float64 (``scaled`` receives s).

    Three passes keep the divisions and selects vectorised: s and the table coordinate, the
    cubic table look-up (scalar), then the linear segment s / 12.92 where s <= 0.04045.
    NaN stays NaN.
    """
    n = src.size
    last = np.float64(lut.shape[0] - 1)
    for j in range(n):
        s = src[j] / 255.0
        s = 0.0 if s < 0.0 else s
        s = 1.0 if s > 1.0 else s
        scaled[j] = s
        lin[j] = ((s + 0.055) / 1.055 - _LUT_X0) * _LUT_INV_H
    for j in range(n):
        t = lin[j]
        clamped = t if t > 0.0 else 0.0
        k = np.uint64(clamped if clamped < last else last)
        f = t - np.float64(k)
        lin[j] = lut[k, 0] + f * (lut[k, 1] + f * (lut[k, 2] + f * lut[k, 3]))
    for j in range(n):
        s = scaled[j]
        lin[j] = s / 12.92 if s <= 0.04045 else lin[j]


@_jit()
def decode_row_fast(src, table, lin):  # type: ignore[no-untyped-def]
    """Preview-mode decode: linear interpolation in ``fast_decode_table`` (abs error < 4e-7)."""
    last = table.size - 1
    for j in range(src.size):
        s = src[j] * (1.0 / 255.0)
        s = 0.0 if s < 0.0 else s
        t = (1.0 if s > 1.0 else s) * last
        k = min(np.uint64(t), np.uint64(last - 1))
        f = t - np.float64(k)
        lin[j] = table[k] + f * (table[k + np.uint64(1)] - table[k])


@_jit(inline=True)
def _uncertain(y: float, margin: float) -> bool:
    """True when values within ``margin`` (relative) of a finite-or-inf y round to different
    float32 values (NaN is never uncertain)."""
    return np.float32(y * (1.0 - margin)) != np.float32(y * (1.0 + margin)) and y == y


@_jit()
def _coverage(regs, chan_reg, alphas, weights, running, weight_nan):  # type: ignore[no-untyped-def]
    """Top-down walk: alpha_l, V_l = alpha_l * running, running *= 1 - alpha_l (float32)."""
    running[:] = np.float32(1.0)
    for layer in range(chan_reg.shape[0] - 1, -1, -1):
        src, alpha, weight = regs[chan_reg[layer, CH_ALPHA]], alphas[layer], weights[layer]
        nans = 0  # an integer count (not a boolean "or"), so that the loop vectorises
        for j in range(running.size):
            a = _clip01_f32(src[j])
            w = a * running[j]
            alpha[j] = a
            weight[j] = w
            nans += np.int32(w != w)
            running[j] *= np.float32(1.0) - a
        weight_nan[layer] = nans > 0


@_jit()
def _add_scalar(acc, w, src, mode, lo, hi):  # type: ignore[no-untyped-def]
    """acc += w * converted channel (float32, clamped to [lo, hi]: [0, 1], below at 1 for ior
    with hi = inf, or not at all with [-inf, inf]); NaN passes the clamp."""
    if mode == READY or mode == ZERO:
        for j in range(acc.size):
            acc[j] += w[j] * np.float32(src[j])
    elif lo == 0.0 and hi == 1.0:
        for j in range(acc.size):
            acc[j] += w[j] * _clip01_f32(src[j])
    else:
        low, high = np.float32(lo), np.float32(hi)
        for j in range(acc.size):
            c = np.float32(src[j])
            c = low if c < low else c
            acc[j] += w[j] * (high if c > high else c)


@_jit(inline=True)
def _linear_colour(src, strength, mode, emissive, luts, margin, lin, scaled):  # type: ignore[no-untyped-def]
    """The linear values of a RAW or DECODED colour row (emissive: x max(strength, 0)): ``src``
    itself, ``lin`` or ``scaled`` (``scaled`` is also the exact decode's scratch)."""
    values = src
    if mode == RAW and margin < 0.0:
        decode_row_fast(src, luts[1], lin)
        values = lin
    elif mode == RAW:
        decode_row(src, luts[0], lin, scaled)
        values = lin
    if emissive:
        for j in range(src.size):
            s = strength[j]
            scaled[j] = values[j] * (0.0 if s < 0.0 else s)
        values = scaled
    return values


@_jit()
def _add_colour(acc, w, src, strength, mode, emissive, luts, margin, flags, lin):  # type: ignore[no-untyped-def]
    """acc += w * linear colour (emissive: colour x max(strength, 0)); flags uncertain texels."""
    n = acc.size
    if mode == READY or mode == ZERO:
        for j in range(n):
            acc[j] += w[j] * np.float32(src[j])
        return
    values = _linear_colour(src, strength, mode, emissive, luts, margin, lin[0], lin[1])
    for j in range(n):
        acc[j] += w[j] * np.float32(values[j])
    if (mode == RAW or not emissive) and margin > 0.0:  # branch-free: the loop vectorises
        for j in range(n):
            flags[j] |= np.uint8(_uncertain(values[j], margin))


@_jit()
def _visible_index(w, idx):  # type: ignore[no-untyped-def]
    """Compact the texels with w != 0 (NaN included) into ``idx``; returns their count, or -1
    when they are at least half of the row (the dense loops are faster then)."""
    n = w.size
    count = 0
    for j in range(n):
        count += w[j] != np.float32(0.0)
    if 2 * count >= n:
        return -1
    m = 0
    for j in range(n):
        if w[j] != np.float32(0.0):
            idx[m] = j
            m += 1
    return m


@_jit()
def _all_finite(values, nan_only):  # type: ignore[no-untyped-def]
    """True when no value is NaN (and, unless ``nan_only``, none is +-inf)."""
    bad = False
    for j in range(values.size):
        v = values[j]
        bad |= (v != v) if nan_only else (v - v != v - v)
    return not bad


@_jit()
def _add_colour_visible(acc, w, src, strength, mode, emissive, luts, margin, flags, idx, m, work):  # type: ignore[no-untyped-def]
    """:func:`_add_colour` (RAW or DECODED rows) on the texels ``idx[:m]`` only. Exact when
    every other texel has w == +0 and a finite colour (the caller checks): ``0 * colour`` is
    +0 there. ``work`` (4, W) scratch."""
    gathered, lin, scaled, gathered_strength = work[0, :m], work[1, :m], work[2, :m], work[3, :m]
    for q in range(m):
        gathered[q] = src[idx[q]]
    if emissive:
        for q in range(m):
            gathered_strength[q] = strength[idx[q]]
    values = _linear_colour(gathered, gathered_strength, mode, emissive, luts, margin, lin, scaled)
    for q in range(m):
        j = idx[q]
        acc[j] += w[j] * np.float32(values[q])
    if (mode == RAW or not emissive) and margin > 0.0:
        for q in range(m):
            flags[idx[q]] |= np.uint8(_uncertain(values[q], margin))


@_jit()
def _accumulate(
    regs,
    chan_reg,
    chan_mode,
    alphas,
    weights,
    weight_nan,
    acc,
    touched,
    luts,
    margin,
    flags,
    lin,
    idx,
    work,
):  # type: ignore[no-untyped-def]
    """Bottom-up: add every layer's weighted channels to the row accumulators ``acc``
    (N_PLANES, W), one row per output plane (SCALAR_PLANES the over-blended scalars, MAX_PLANES
    the height max, COLOUR_PLANES the colour components; see :mod:`matloom.vocab.layout`).
    ``touched[p]`` is set for every accumulator row that received a value (others stay 0).
    Colours of a layer visible on under half of the row are decoded only where it is visible
    (``idx``/``work`` scratch), unless a colour could be NaN/inf where it is hidden."""
    for layer in range(chan_reg.shape[0]):
        w = weights[layer]
        skip_zero = not weight_nan[layer]
        m = _visible_index(w, idx)
        strength = regs[chan_reg[layer, CH_STRENGTH]]
        strength_finite = m >= 0 and _all_finite(strength, np.bool_(False))
        for c in range(N_SCALARS):
            ch, p = SCALAR_SLOTS[c], SCALAR_PLANES[c]
            mode = chan_mode[layer, ch]
            if not (mode == ZERO and skip_zero):
                touched[p] = True
                _add_scalar(acc[p], w, regs[chan_reg[layer, ch]], mode, SCALAR_LO[c], SCALAR_HI[c])
        for k in range(N_COLOURS):
            ch, p, emissive = COLOUR_SLOTS[k], COLOUR_PLANES[k], COLOUR_EMISSIVE[k]
            mode = chan_mode[layer, ch]
            if not (mode == ZERO and skip_zero):
                touched[p] = True
                src = regs[chan_reg[layer, ch]]
                if (
                    m >= 0
                    and mode != READY
                    and mode != ZERO
                    and (not emissive or strength_finite)
                    and _all_finite(src, np.bool_(True))
                ):
                    _add_colour_visible(
                        acc[p],
                        w,
                        src,
                        strength,
                        mode,
                        emissive,
                        luts,
                        margin,
                        flags,
                        idx,
                        m,
                        work,
                    )
                    continue
                _add_colour(
                    acc[p],
                    w,
                    src,
                    strength,
                    mode,
                    emissive,
                    luts,
                    margin,
                    flags,
                    lin,
                )
        alpha = alphas[layer]
        for q in range(N_MAX):
            heights, top = regs[chan_reg[layer, MAX_SLOTS[q]]], acc[MAX_PLANES[q]]
            for j in range(top.size):
                h = np.float32(heights[j])
                if alpha[j] > np.float32(0.0) and np.isfinite(h) and h > top[j]:
                    top[j] = h


@_jit(inline=True)
def _is_max_plane(p: int) -> bool:
    """True for the output plane of a max-blended channel (settled apart, not divided)."""
    for q in range(N_MAX):
        if MAX_PLANES[q] == p:
            return True
    return False


@_jit()
def _finish(acc, touched, running, planes, colours, i, zeroed):  # type: ignore[no-untyped-def]
    """Coverage = 1 - running; un-premultiply (0 where not covered); settle the max channels;
    write output row ``i`` (colours interleaved into ``colours`` unless ``planes`` has all
    N_PLANES). The coverage row of ``acc`` is reused for the divisor; untouched accumulators
    are 0 and stay 0 (0 / divisor = 0), so they are not divided, and with ``zeroed`` (outputs
    freshly zero-allocated) not even written: their pages stay untouched."""
    zero, one = np.float32(0.0), np.float32(1.0)
    cover, divisor = planes[PLANE_COVERAGE, i], acc[PLANE_COVERAGE]
    for j in range(running.size):
        c = one - running[j]
        cover[j] = c
        divisor[j] = c if c > zero else one  # divide unconditionally: the loops vectorise
    planar = planes.shape[0] == N_PLANES
    for p in range(N_PLANES):
        if p == PLANE_COVERAGE or _is_max_plane(p):
            continue
        src = acc[p]
        dst = planes[p, i] if (p < N_MAP_PLANES or planar) else src
        if not touched[p]:
            if not zeroed:
                dst[:] = zero
            continue
        for j in range(src.size):
            q = src[j] / divisor[j]
            dst[j] = q if cover[j] > zero else zero
    if not planar:
        for out in range(len(COLOUR_OUTPUT_PLANES)):
            p0, rgb = COLOUR_OUTPUT_PLANES[out], colours[out][i]
            if not zeroed or touched[p0] or touched[p0 + 1] or touched[p0 + 2]:
                for j in range(cover.size):
                    for k in range(3):
                        rgb[j, k] = acc[p0 + k, j]
    for q in range(N_MAX):
        top, height = acc[MAX_PLANES[q]], planes[MAX_PLANES[q], i]
        for j in range(height.size):
            h = top[j]
            height[j] = (zero if h == -np.inf else h) + zero


class CompositeArgs(NamedTuple):
    """The arguments of :func:`composite_rows` but the row range (built by
    :func:`matloom.engine.schedules.banded.kernel_args`): the register program, the candidate, the sRGB
    decode set-up and the outputs."""

    loads: np.ndarray
    code: np.ndarray
    consts: np.ndarray
    n_regs: int
    leaves64: tuple[np.ndarray, ...]
    leaves32: tuple[np.ndarray, ...]
    #: candidate of batched (S, H, W) leaves
    cand: int
    chan_reg: np.ndarray
    chan_mode: np.ndarray
    #: (:func:`decode_table`, :func:`fast_decode_table`)
    luts: tuple[np.ndarray, np.ndarray]
    #: DECODE_MARGIN, or < 0 for the preview mode
    margin: float
    planes: np.ndarray
    #: one (H, W, 3) float32 output per colour channel (basecolor, emissive)
    colours: tuple[np.ndarray, ...]
    #: output row of band row 0
    row0: int
    flags: np.ndarray
    #: the outputs were zero-filled by the caller
    zeroed: bool


@_jit()
def composite_rows(args, first, last):  # type: ignore[no-untyped-def]
    """Evaluate and composite rows ``first``..``last - 1`` of one band (leaf rows and ``flags``
    rows are band-local; output row = ``args.row0`` + band row); ``args`` is a
    :class:`CompositeArgs`.

    Outputs (fully overwritten on those rows, except that with ``zeroed`` -- the caller
    zero-filled them -- channels no layer writes are left alone): ``planes`` (N_MAP_PLANES, H, W)
    float32 = the 2-D maps in plane order (alpha, the scalars, height); ``colours`` = one
    (H, W, 3) array per colour channel (basecolor, emissive);
    ``flags`` (band rows, W) uint8 is set to 1 at uncertain texels (never cleared). Serial and
    ``nogil``: callers run row ranges on threads (numba's parallel loops cannot take tuples
    of arrays).

    Preview mode (``margin`` < 0): the sRGB decode uses the linear table and nothing is flagged;
    with (N_PLANES, H, W) ``planes`` the colours are written as their planes (COLOUR_PLANES)
    instead of interleaved (``colours`` is then not written).
    """
    # Unpacked once: reading a tuple field in the row loop would count references per row.
    loads, code, consts, n_regs = args.loads, args.code, args.consts, args.n_regs
    leaves64, leaves32, cand = args.leaves64, args.leaves32, args.cand
    chan_reg, chan_mode, luts, margin = args.chan_reg, args.chan_mode, args.luts, args.margin
    planes, colours, row0, flags, zeroed = (
        args.planes,
        args.colours,
        args.row0,
        args.flags,
        args.zeroed,
    )
    width = planes.shape[2]
    n_layers = chan_reg.shape[0]
    regs = np.empty((n_regs, width))
    for r in range(consts.size):
        regs[r, :] = consts[r]
    alphas = np.empty((n_layers, width), np.float32)
    weights = np.empty((n_layers, width), np.float32)
    running = np.empty(width, np.float32)
    weight_nan = np.zeros(n_layers, np.bool_)
    acc = np.empty((N_PLANES, width), np.float32)
    touched = np.zeros(N_PLANES, np.bool_)
    lin = np.empty((2, width))
    idx = np.empty(width, np.int64)
    work = np.empty((4, width))
    for i in range(first, last):
        load_leaves(loads, regs, leaves64, leaves32, cand, i)
        run_code(code, consts, regs)
        _coverage(regs, chan_reg, alphas, weights, running, weight_nan)
        acc[:] = np.float32(0.0)
        for q in range(N_MAX):
            acc[MAX_PLANES[q], :] = -np.inf
        touched[:] = False
        _accumulate(
            regs,
            chan_reg,
            chan_mode,
            alphas,
            weights,
            weight_nan,
            acc,
            touched,
            luts,
            margin,
            flags[i],
            lin,
            idx,
            work,
        )
        _finish(acc, touched, running, planes, colours, row0 + i, zeroed)


@_jit()
def frozen_layout():  # type: ignore[no-untyped-def]
    """The layout constants as the compiled kernels see them (a stale on-disk cache would
    show the old ones): (N_CHANNELS, N_PLANES, N_MAP_PLANES, CH_ALPHA, CH_STRENGTH,
    SCALAR_SLOTS, SCALAR_PLANES, COLOUR_SLOTS, COLOUR_PLANES, MAX_SLOTS, MAX_PLANES)."""
    return (
        N_CHANNELS,
        N_PLANES,
        N_MAP_PLANES,
        CH_ALPHA,
        CH_STRENGTH,
        SCALAR_SLOTS,
        SCALAR_PLANES,
        COLOUR_SLOTS,
        COLOUR_PLANES,
        MAX_SLOTS,
        MAX_PLANES,
    )
