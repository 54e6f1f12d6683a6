"""Element-wise math nodes with the reference's special rules (spec §2.2).

These are the numpy implementations of the element-wise ops (:mod:`matloom.ops`): the
evaluators call them only through ``OPS[name].numpy``.

Every function is plain numpy on its inputs, so the result dtype follows numpy promotion of
the inputs exactly as in the reference (float32 coordinate grids stay float32 until they meet a
float64 grid such as a Constant). No numpy RuntimeWarning leaks out: domain errors simply give
the IEEE result (NaN, +-inf). The special rules are:

* ``safe_div``: 0 wherever the divisor is exactly 0 (including 0/0); the engine reports such
  divisions using :func:`count_zero` (the reference emits a "Division by zero" warning).
* ``log``: base 10 -> log10, base 2 -> log2, base e -> ln, any other base ln(v)/ln(base);
  Log(0) = -inf and Log of a negative number is NaN.
* ``pow_`` with a negative base and non-integer exponent, and ``sqrt`` of a negative number,
  give NaN.
"""

from __future__ import annotations

import math
from collections.abc import Callable

import numpy as np

from matloom.ops import portable_math
from matloom.ops.portable_constants import NAN

ArrayLike = np.ndarray | float


def _quiet() -> np.errstate:
    """Context that silences every floating-point RuntimeWarning."""
    return np.errstate(all="ignore")


def count_zero(b: ArrayLike) -> int:
    """Number of elements of the divisor that are exactly zero (+0.0 or -0.0)."""
    return int(np.count_nonzero(np.asarray(b) == 0))


def safe_div(a: ArrayLike, b: ArrayLike) -> np.ndarray:
    """``a / b`` with the result 0 wherever ``b == 0`` exactly; other inf/NaN propagate."""
    a, b = np.asarray(a), np.asarray(b)
    with _quiet():
        quotient = np.true_divide(a, b)
    return np.where(b == 0, np.zeros((), dtype=quotient.dtype), quotient)


def _portable(ufunc: np.ufunc, fn: Callable[..., np.ndarray], *operands: ArrayLike) -> np.ndarray:
    """``fn`` (a :mod:`.portable_math` function) in float64, returned in the dtype ``ufunc``
    would return for these operands (float32 stays float32), so that the result is the same
    on every CPU (numpy's own ``ufunc`` picks SIMD code by CPU, whose last bit differs)."""
    arrays = [np.asarray(a) for a in operands]
    dtype = ufunc(*(np.empty(0, dtype=a.dtype) for a in arrays)).dtype
    if dtype.kind != "f":  # integer powers: exact in numpy already
        with _quiet():
            return ufunc(*arrays)  # type: ignore[no-any-return]
    out = portable_math.blockwise(fn, *arrays, dtype=dtype)
    return out[()] if out.ndim == 0 else out  # a scalar for 0-d operands, as a ufunc


def log(v: ArrayLike, base: float = math.e) -> np.ndarray:
    """Logarithm with the reference's base dispatch (log10, log2, ln, else ln(v)/ln(base)).

    ln(base) is a Python float, so a float32 ``v`` stays float32 for unusual bases.
    """
    base = float(base)
    if base == 10.0:
        return _portable(np.log10, portable_math.log10, v)
    if base == 2.0:
        return _portable(np.log2, portable_math.log2, v)
    ln = _portable(np.log, portable_math.log, v)
    if base == math.e:
        return ln
    with _quiet():
        return ln / _ln_scalar(base)  # type: ignore[no-any-return]


def _ln_scalar(base: float) -> float:
    """Natural log of a scalar base as numpy defines it: -inf for 0, NaN below 0."""
    if base > 0:
        return portable_math.log_scalar(base)
    return -math.inf if base == 0 else math.nan


def pow_(a: ArrayLike, b: ArrayLike) -> np.ndarray:
    """``a ** b`` (NaN for a negative base with a non-integer exponent, inf for 0 ** -n)."""
    return _portable(np.power, portable_math.pow_, a, b)


def sqrt(v: ArrayLike) -> np.ndarray:
    """Square root; NaN for negative inputs."""
    with _quiet():
        return np.sqrt(np.asarray(v))


def add(a: ArrayLike, b: ArrayLike) -> np.ndarray:
    """``a + b`` (inf - inf gives NaN quietly)."""
    with _quiet():
        return np.add(np.asarray(a), np.asarray(b))


def sub(a: ArrayLike, b: ArrayLike) -> np.ndarray:
    """``a - b``."""
    with _quiet():
        return np.subtract(np.asarray(a), np.asarray(b))


def mul(a: ArrayLike, b: ArrayLike) -> np.ndarray:
    """``a * b`` (0 * inf gives NaN quietly)."""
    with _quiet():
        return np.multiply(np.asarray(a), np.asarray(b))


def minimum(a: ArrayLike, b: ArrayLike) -> np.ndarray:
    """Element-wise minimum (NaN propagates, as ``np.minimum``)."""
    return np.minimum(np.asarray(a), np.asarray(b))


def maximum(a: ArrayLike, b: ArrayLike) -> np.ndarray:
    """Element-wise maximum (NaN propagates, as ``np.maximum``)."""
    return np.maximum(np.asarray(a), np.asarray(b))


def abs_(v: ArrayLike) -> np.ndarray:
    """Absolute value."""
    return np.abs(np.asarray(v))


def floor(v: ArrayLike) -> np.ndarray:
    """Round down to an integer value (float result)."""
    return np.floor(np.asarray(v))


def ceil(v: ArrayLike) -> np.ndarray:
    """Round up to an integer value (float result)."""
    return np.ceil(np.asarray(v))


def sin(v: ArrayLike) -> np.ndarray:
    """Sine of radians (inf gives NaN quietly)."""
    return _portable(np.sin, portable_math.sin, v)


def cos(v: ArrayLike) -> np.ndarray:
    """Cosine of radians (inf gives NaN quietly)."""
    return _portable(np.cos, portable_math.cos, v)


# ------------------------------------------------------------------ language-2 functions
# Atan2, Fract, Mod and Exp compute in float64 and return float64 (their ops have
# dtype="float64", like Threshold), with the operations of the register machine's opcodes
# (kernels.mathops_numba) in the same order, so both backends agree bit for bit on every CPU:
# numpy's own exp/arctan2 run SIMD code whose last bit differs from libm's (and so from numba's).
# Exp is fdlibm's e_exp.c and Atan2 fdlibm's e_atan2.c/s_atan.c (errors below 1 ulp).

#: Fract's largest value: the largest float64 below 1 (x - floor(x) rounds to 1 for tiny x < 0).
FRACT_MAX = 1.0 - 2.0**-53
#: The NaN these functions return for a NaN operand (Atan2) or a missing cell (Hash) is
#: :data:`~matloom.ops.portable_constants.NAN`: the CPU's default NaN, the one 0/0 and
#: inf - inf give (sign bit set), so that every NaN the engine makes is the same and an operation
#: on two of them gives the same bits whatever their order.

#: Exp: above EXP_OVERFLOW the result is inf, below EXP_UNDERFLOW it is 0.
EXP_OVERFLOW = 7.09782712893383973096e02
EXP_UNDERFLOW = -7.45133219101941108420e02
INV_LN2 = 1.44269504088896338700e00
LN2_HI = 6.93147180369123816490e-01  # ln 2 = LN2_HI + LN2_LO; k * LN2_HI is exact
LN2_LO = 1.90821492927058770002e-10
#: (v + ROUND_SHIFT) - ROUND_SHIFT rounds |v| < 2**51 to the nearest integer (ties to even).
ROUND_SHIFT = 6755399441055744.0  # 1.5 * 2**52
EXP_P1 = 1.66666666666666019037e-01
EXP_P2 = -2.77777777770155933842e-03
EXP_P3 = 6.61375632143793436117e-05
EXP_P4 = -1.65339022054652515390e-06
EXP_P5 = 4.13813679705723846039e-08

#: atan(t) = ATAN_HI[i] + ATAN_LO[i] at the break points t = 0.5, 1, 1.5 and infinity.
ATAN_HI = (
    4.63647609000806093515e-01,
    7.85398163397448278999e-01,
    9.82793723247329054082e-01,
    1.57079632679489655800e00,
)
ATAN_LO = (
    2.26987774529616870924e-17,
    3.06161699786838301793e-17,
    1.39033110312309984516e-17,
    6.12323399573676603587e-17,
)
AT0, AT1, AT2, AT3, AT4, AT5 = (
    3.33333333333329318027e-01,
    -1.99999999998764832476e-01,
    1.42857142725034663711e-01,
    -1.11111104054623557880e-01,
    9.09088713343650656196e-02,
    -7.69187620504482999495e-02,
)
AT6, AT7, AT8, AT9, AT10 = (
    6.66107313738753120669e-02,
    -5.83357013379057348645e-02,
    4.97687799461593236017e-02,
    -3.65315727442169155270e-02,
    1.62858201153657823623e-02,
)
ATAN_BIG = 2.0**66  # atan(t) rounds to pi/2 from here
ATAN_TINY = 2.0**-29  # atan(t) rounds to t below this
PI = 3.1415926535897931160e00
PI_LO = 1.2246467991473531772e-16  # pi - PI
HALF_PI = 1.5707963267948965580e00
QUARTER_PI = 7.8539816339744827900e-01
THREE_QUARTER_PI = 3.0 * QUARTER_PI


def _f64(v: ArrayLike) -> np.ndarray:
    return np.asarray(v, dtype=np.float64)


def _atan_nonnegative(t: np.ndarray) -> np.ndarray:
    """atan(t) for t >= 0 (fdlibm's argument reduction and polynomial); NaN-free input."""
    u = np.where(
        t < 0.4375,
        t,
        np.where(
            t < 0.6875,
            (2.0 * t - 1.0) / (2.0 + t),
            np.where(
                t < 1.1875,
                (t - 1.0) / (t + 1.0),
                np.where(t < 2.4375, (t - 1.5) / (1.0 + 1.5 * t), -1.0 / t),
            ),
        ),
    )
    z = u * u
    w = z * z
    s1 = z * (AT0 + w * (AT2 + w * (AT4 + w * (AT6 + w * (AT8 + w * AT10)))))
    s2 = w * (AT1 + w * (AT3 + w * (AT5 + w * (AT7 + w * AT9))))
    s = s1 + s2
    k = (t >= 0.6875).astype(np.int64) + (t >= 1.1875) + (t >= 2.4375)
    hi, lo = np.asarray(ATAN_HI)[k], np.asarray(ATAN_LO)[k]
    reduced = hi - ((u * s - lo) - u)
    small = np.where(t < ATAN_TINY, t, u - u * s)
    out = np.where(t < 0.4375, small, reduced)
    return np.where(t >= ATAN_BIG, ATAN_HI[3] + ATAN_LO[3], out)


def atan2(y: ArrayLike, x: ArrayLike) -> np.ndarray:
    """Angle of (x, y) in radians, in (-pi, pi]: C99/numpy ``atan2`` except that y = -0 counts
    as +0 (so the negative x axis gives pi, never -pi); NaN if either operand is NaN."""
    y, x = _f64(y) + 0.0, _f64(x)  # -0 + 0 = +0
    with _quiet():
        z = _atan_nonnegative(np.abs(y / x))
        out = np.where(x > 0.0, np.where(y > 0.0, z, -z), 0.0)
        out = np.where(x < 0.0, np.where(y > 0.0, PI - (z - PI_LO), (z - PI_LO) - PI), out)
        out = np.where(np.isinf(y), np.copysign(HALF_PI, y), out)
        both_inf = np.isinf(y) & np.isinf(x)
        at_neg_inf = np.where(both_inf, np.copysign(THREE_QUARTER_PI, y), np.copysign(PI, y))
        out = np.where(x == -np.inf, at_neg_inf, out)
        at_pos_inf = np.where(both_inf, np.copysign(QUARTER_PI, y), np.copysign(0.0, y))
        out = np.where(x == np.inf, at_pos_inf, out)
        out = np.where(x == 0.0, np.copysign(HALF_PI, y), out)
        on_axis = np.where((x < 0.0) | ((x == 0.0) & np.signbit(x)), PI, 0.0)
        out = np.where(y == 0.0, on_axis, out)
        return np.where((x != x) | (y != y), NAN, out)


def fract(v: ArrayLike) -> np.ndarray:
    """``x - floor(x)`` in [0, 1): a result that rounds to 1 (x a tiny negative number) is
    :data:`FRACT_MAX`; NaN for NaN and infinite x."""
    x = _f64(v)
    with _quiet():
        f = x - np.floor(x)
    return np.where(f >= 1.0, FRACT_MAX, f)


def mod(x: ArrayLike, m: ArrayLike) -> np.ndarray:
    """``x - m * floor(x / m)`` (the sign of m), 0 wherever ``m == 0`` exactly (as safe
    division); NaN where x or m is infinite or NaN (and m != 0)."""
    x, m = _f64(x), _f64(m)
    with _quiet():
        r = x - m * np.floor(x / m)
    return np.where(m == 0.0, 0.0, r)


def exp_(v: ArrayLike) -> np.ndarray:
    """``e ** x`` (fdlibm's algorithm): inf above :data:`EXP_OVERFLOW`, 0 below
    :data:`EXP_UNDERFLOW`, NaN for NaN."""
    x = _f64(v)
    with _quiet():
        inside = np.where((x >= EXP_UNDERFLOW) & (x <= EXP_OVERFLOW), x, 0.0)
        k = (inside * INV_LN2 + ROUND_SHIFT) - ROUND_SHIFT
        hi = inside - k * LN2_HI
        lo = k * LN2_LO
        r = hi - lo
        t = r * r
        c = r - t * (EXP_P1 + t * (EXP_P2 + t * (EXP_P3 + t * (EXP_P4 + t * EXP_P5))))
        y = 1.0 - ((lo - (r * c) / (2.0 - c)) - hi)
        out = np.ldexp(y, k.astype(np.int64))
    out = np.where(x > EXP_OVERFLOW, np.inf, out)
    out = np.where(x < EXP_UNDERFLOW, 0.0, out)
    return np.where(x != x, x, out)


# The compositions Clamp, Mix and Smoothstep: the interpreter evaluates them as these ops
# (engine.rules.fields_math), so that the fused path runs them on existing opcodes; these array
# versions are their constant-folding rules and the tests' references.
_ZERO, _ONE, _TWO, _THREE = np.float64(0.0), np.float64(1.0), np.float64(2.0), np.float64(3.0)


def clamp(x: ArrayLike, lo: ArrayLike = _ZERO, hi: ArrayLike = _ONE) -> np.ndarray:
    """``Min(Max(x, lo), hi)`` (NaN propagates; hi wins where lo > hi)."""
    return minimum(maximum(x, lo), hi)


def mix(a: ArrayLike, b: ArrayLike, t: ArrayLike) -> np.ndarray:
    """``a + (b - a) * t``."""
    return add(a, mul(sub(b, a), t))


def smoothstep(edge0: ArrayLike, edge1: ArrayLike, x: ArrayLike) -> np.ndarray:
    """GLSL smoothstep with safe division: t = clamp((x - edge0) / (edge1 - edge0), 0, 1),
    ``t * t * (3 - 2 * t)``; 0 where edge0 == edge1."""
    t = clamp(safe_div(sub(x, edge0), sub(edge1, edge0)), _ZERO, _ONE)
    return mul(mul(t, t), sub(_THREE, mul(_TWO, t)))
