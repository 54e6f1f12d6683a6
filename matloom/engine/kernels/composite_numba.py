"""numba kernel: fused channel arithmetic + over-rule compositing, bit-identical to numpy.

One call composites a band of rows. Per row it runs a small register program (the channel
expressions above the primitive fields, compiled by :mod:`matloom.engine.fused`) and then applies
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

import numpy as np

from matloom.engine.kernels.register_numba import _jit, load_leaves, run_code

#: Channel slots of a layer in the layer tables (``chan_reg``/``chan_mode`` columns).
CH_ALPHA = 0
CH_BASECOLOR = 1  # 1, 2, 3
CH_SCALARS = 4  # 4..10 in SCALAR_CHANNELS order
CH_IOR = 11
CH_EMISSIVE = 12  # 12, 13, 14
CH_STRENGTH = 15
CH_HEIGHT = 16
N_CHANNELS = 17

#: Channel modes: RAW = evaluate and convert here; READY = register holds the final float32
#: value; DECODED = emissive colour already linear (float64); ZERO = constant 0 after conversion.
RAW, READY, DECODED, ZERO = 0, 1, 2, 3

#: Fixed leaf-slot counts (a fixed tuple length keeps one compiled, cached signature).
MAX_LEAVES64 = 16
MAX_LEAVES32 = 8

#: Relative margin of the certainty test of the sRGB table (see the module docstring).
DECODE_MARGIN = 2.0**-44
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
def _add_scalar(acc, w, src, mode, ior):  # type: ignore[no-untyped-def]
    """acc += w * converted channel (clamp to [0, 1], or max(v, 1) for ior) in float32."""
    if mode == READY or mode == ZERO:
        for j in range(acc.size):
            acc[j] += w[j] * np.float32(src[j])
    elif ior:
        for j in range(acc.size):
            c = np.float32(src[j])
            acc[j] += w[j] * (np.float32(1.0) if c < np.float32(1.0) else c)
    else:
        for j in range(acc.size):
            acc[j] += w[j] * _clip01_f32(src[j])


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
    """Bottom-up: add every layer's weighted channels to the row accumulators ``acc`` (16, W):
    rows 1..8 the 7 scalars and ior, 9 the height max, 10..12 basecolor, 13..15 emissive.
    ``touched[p]`` is set for every accumulator row that received a value (others stay 0).
    Colours of a layer visible on under half of the row are decoded only where it is visible
    (``idx``/``work`` scratch), unless a colour could be NaN/inf where it is hidden."""
    for layer in range(chan_reg.shape[0]):
        w = weights[layer]
        skip_zero = not weight_nan[layer]
        m = _visible_index(w, idx)
        strength = regs[chan_reg[layer, CH_STRENGTH]]
        strength_finite = m >= 0 and _all_finite(strength, False)
        for c in range(8):
            ch = CH_SCALARS + c if c < 7 else CH_IOR
            if not (chan_mode[layer, ch] == ZERO and skip_zero):
                touched[1 + c] = True
                _add_scalar(acc[1 + c], w, regs[chan_reg[layer, ch]], chan_mode[layer, ch], c == 7)
        for k in range(6):
            ch = CH_BASECOLOR + k if k < 3 else CH_EMISSIVE + k - 3
            mode = chan_mode[layer, ch]
            if not (mode == ZERO and skip_zero):
                touched[10 + k] = True
                src = regs[chan_reg[layer, ch]]
                if (
                    m >= 0
                    and mode != READY
                    and mode != ZERO
                    and (k < 3 or strength_finite)
                    and _all_finite(src, True)
                ):
                    _add_colour_visible(
                        acc[10 + k],
                        w,
                        src,
                        strength,
                        mode,
                        k >= 3,
                        luts,
                        margin,
                        flags,
                        idx,
                        m,
                        work,
                    )
                    continue
                _add_colour(
                    acc[10 + k],
                    w,
                    src,
                    strength,
                    mode,
                    k >= 3,
                    luts,
                    margin,
                    flags,
                    lin,
                )
        heights, alpha, top = regs[chan_reg[layer, CH_HEIGHT]], alphas[layer], acc[9]
        for j in range(top.size):
            h = np.float32(heights[j])
            if alpha[j] > np.float32(0.0) and np.isfinite(h) and h > top[j]:
                top[j] = h


@_jit()
def _finish(acc, touched, running, planes, basecolor, emissive, i, zeroed):  # type: ignore[no-untyped-def]
    """Coverage = 1 - running; un-premultiply (0 where not covered); settle the height; write
    output row ``i`` (colours interleaved). ``acc[0]`` is reused for the divisor; untouched
    accumulators are 0 and stay 0 (0 / divisor = 0), so they are not divided, and with
    ``zeroed`` (outputs freshly zero-allocated) not even written: their pages stay untouched."""
    zero, one = np.float32(0.0), np.float32(1.0)
    cover, divisor = planes[0, i], acc[0]
    for j in range(running.size):
        c = one - running[j]
        cover[j] = c
        divisor[j] = c if c > zero else one  # divide unconditionally: the loops vectorise
    planar = planes.shape[0] == 16
    for p in range(1, 16):
        if p == 9:
            continue
        src = acc[p]
        dst = planes[p, i] if (p < 9 or planar) else src
        if not touched[p]:
            if not zeroed:
                dst[:] = zero
            continue
        for j in range(src.size):
            q = src[j] / divisor[j]
            dst[j] = q if cover[j] > zero else zero
    if not planar:
        base, emit = basecolor[i], emissive[i]
        for j in range(cover.size):
            for k in range(3):
                base[j, k] = acc[10 + k, j]
        if not zeroed or touched[13] or touched[14] or touched[15]:
            for j in range(cover.size):
                for k in range(3):
                    emit[j, k] = acc[13 + k, j]
    top, height = acc[9], planes[9, i]
    for j in range(height.size):
        h = top[j]
        height[j] = (zero if h == -np.inf else h) + zero


@_jit()
def composite_rows(
    loads,
    code,
    consts,
    n_regs,
    leaves64,
    leaves32,
    cand,
    chan_reg,
    chan_mode,
    luts,
    margin,
    planes,
    basecolor,
    emissive,
    row0,
    flags,
    zeroed,
    first,
    last,
):  # type: ignore[no-untyped-def]
    """Evaluate and composite rows ``first``..``last - 1`` of one band (leaf rows and ``flags``
    rows are band-local; output row = ``row0`` + band row).

    Outputs (fully overwritten on those rows, except that with ``zeroed`` -- the caller
    zero-filled them -- channels no layer writes are left alone): ``planes`` (10, H, W) float32
    = alpha, the 7 scalars, ior, height; ``basecolor`` and ``emissive`` (H, W, 3); ``flags``
    (band rows, W) uint8 is set to 1 at uncertain texels (never cleared). Serial and
    ``nogil``: callers run row ranges on threads (numba's parallel loops cannot take tuples
    of arrays).

    ``luts`` = (:func:`decode_table`, :func:`fast_decode_table`). Preview mode (``margin`` < 0):
    the sRGB decode uses the linear table and nothing is flagged; with (16, H, W) ``planes`` the colours are written as
    planes 10..12 (basecolor) and 13..15 (emissive) instead of interleaved.
    """
    width = planes.shape[2]
    n_layers = chan_reg.shape[0]
    regs = np.empty((n_regs, width))
    for r in range(consts.size):
        regs[r, :] = consts[r]
    alphas = np.empty((n_layers, width), np.float32)
    weights = np.empty((n_layers, width), np.float32)
    running = np.empty(width, np.float32)
    weight_nan = np.zeros(n_layers, np.bool_)
    acc = np.empty((16, width), np.float32)
    touched = np.zeros(16, np.bool_)
    lin = np.empty((2, width))
    idx = np.empty(width, np.int64)
    work = np.empty((4, width))
    for i in range(first, last):
        load_leaves(loads, regs, leaves64, leaves32, cand, i)
        run_code(code, consts, regs)
        _coverage(regs, chan_reg, alphas, weights, running, weight_nan)
        acc[:] = np.float32(0.0)
        acc[9, :] = -np.inf
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
        _finish(acc, touched, running, planes, basecolor, emissive, row0 + i, zeroed)
