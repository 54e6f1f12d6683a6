"""numba scalar versions of the language-2 element-wise functions (Atan2, Fract, Mod, Exp).

The register machine (:mod:`matloom.engine.kernels.register_numba`, its ``_language2``) runs
these per element; they are ordinary (not numba-inlined) functions, compiled once. Each performs the float64 operations of its numpy version in
:mod:`matloom.engine.kernels.mathops` in the same order (branches where numpy selects with
``np.where``), with ``fastmath`` off (no contraction into FMA, no reassociation), so both
backends give the same bits on every CPU.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from matloom.engine.kernels.jit import jit
from matloom.engine.kernels.mathops import (
    AT0,
    AT1,
    AT2,
    AT3,
    AT4,
    AT5,
    AT6,
    AT7,
    AT8,
    AT9,
    AT10,
    ATAN_BIG,
    ATAN_HI,
    ATAN_LO,
    ATAN_TINY,
    EXP_OVERFLOW,
    EXP_P1,
    EXP_P2,
    EXP_P3,
    EXP_P4,
    EXP_P5,
    EXP_UNDERFLOW,
    FRACT_MAX,
    HALF_PI,
    INV_LN2,
    LN2_HI,
    LN2_LO,
    NAN,
    PI,
    PI_LO,
    QUARTER_PI,
    ROUND_SHIFT,
    THREE_QUARTER_PI,
)

_ATAN_HI0, _ATAN_HI1, _ATAN_HI2, _ATAN_HI3 = ATAN_HI
_ATAN_LO0, _ATAN_LO1, _ATAN_LO2, _ATAN_LO3 = ATAN_LO
_INF = math.inf


def _jit() -> Any:
    return jit(nogil=True, error_model="numpy", fastmath=False)


@_jit()
def fract(x: float) -> float:
    """``x - floor(x)``, at most :data:`~matloom.engine.kernels.mathops.FRACT_MAX`."""
    f = x - np.floor(x)
    return FRACT_MAX if f >= 1.0 else f


@_jit()
def mod(x: float, m: float) -> float:
    """``x - m * floor(x / m)``, 0 where ``m == 0``."""
    if m == 0.0:
        return 0.0
    return x - m * np.floor(x / m)


@_jit()
def exp(x: float) -> float:
    """``e ** x`` (fdlibm's e_exp.c, as ``mathops.exp_``)."""
    if x != x:
        return x
    if x > EXP_OVERFLOW:
        return _INF
    if x < EXP_UNDERFLOW:
        return 0.0
    k = (x * INV_LN2 + ROUND_SHIFT) - ROUND_SHIFT
    hi = x - k * LN2_HI
    lo = k * LN2_LO
    r = hi - lo
    t = r * r
    c = r - t * (EXP_P1 + t * (EXP_P2 + t * (EXP_P3 + t * (EXP_P4 + t * EXP_P5))))
    y = 1.0 - ((lo - (r * c) / (2.0 - c)) - hi)
    return math.ldexp(y, int(k))


@_jit()
def _atan_nonnegative(t: float) -> float:
    """atan(t) for t >= 0, not NaN (fdlibm's s_atan.c, as ``mathops._atan_nonnegative``)."""
    if t >= ATAN_BIG:
        return _ATAN_HI3 + _ATAN_LO3
    if t < 0.4375:
        u = t
    elif t < 0.6875:
        u = (2.0 * t - 1.0) / (2.0 + t)
    elif t < 1.1875:
        u = (t - 1.0) / (t + 1.0)
    elif t < 2.4375:
        u = (t - 1.5) / (1.0 + 1.5 * t)
    else:
        u = -1.0 / t
    z = u * u
    w = z * z
    s1 = z * (AT0 + w * (AT2 + w * (AT4 + w * (AT6 + w * (AT8 + w * AT10)))))
    s2 = w * (AT1 + w * (AT3 + w * (AT5 + w * (AT7 + w * AT9))))
    s = s1 + s2
    if t < 0.4375:
        return t if t < ATAN_TINY else u - u * s
    if t < 0.6875:
        hi, lo = _ATAN_HI0, _ATAN_LO0
    elif t < 1.1875:
        hi, lo = _ATAN_HI1, _ATAN_LO1
    elif t < 2.4375:
        hi, lo = _ATAN_HI2, _ATAN_LO2
    else:
        hi, lo = _ATAN_HI3, _ATAN_LO3
    return hi - ((u * s - lo) - u)


@_jit()
def atan2(y: float, x: float) -> float:  # noqa: C901 - one branch per special case, as C99
    """Angle of (x, y) in (-pi, pi] (y = -0 counts as +0), as ``mathops.atan2``."""
    if x != x or y != y:
        return NAN
    y = y + 0.0
    if y == 0.0:
        return PI if (x < 0.0 or (x == 0.0 and math.copysign(1.0, x) < 0.0)) else 0.0
    if x == 0.0:
        return math.copysign(HALF_PI, y)
    if x == _INF:
        if y == _INF or y == -_INF:
            return math.copysign(QUARTER_PI, y)
        return math.copysign(0.0, y)
    if x == -_INF:
        if y == _INF or y == -_INF:
            return math.copysign(THREE_QUARTER_PI, y)
        return math.copysign(PI, y)
    if y == _INF or y == -_INF:
        return math.copysign(HALF_PI, y)
    z = _atan_nonnegative(abs(y / x))
    if x > 0.0:
        return z if y > 0.0 else -z
    return PI - (z - PI_LO) if y > 0.0 else (z - PI_LO) - PI
