"""Portable sin, cos, log and pow: the same bits on every CPU (vectorised numpy).

numpy picks the implementation of ``np.sin``, ``np.log``, ``np.power``, ... by CPU at run time
(AVX-512, AVX2 or baseline SIMD code, or the C library, which glibc in turn picks by CPU), and
the variants differ in the last bit; a last-bit difference flips a ``Floor`` or a ``Threshold``
and moves whole texels. These functions use only operations that IEEE 754 defines exactly
(``+ - * /``, ``sqrt``, ``floor``, ``ldexp``, comparisons, bit manipulation of float64), so every
x86-64 and aarch64 machine computes the same bits, on both backends.

The algorithms are fdlibm's (FreeBSD msun), as :mod:`.mathops` already does for Exp and Atan2:

* **sin/cos**: argument reduction by pi/2 (Cody-Waite with three 33-bit pieces of pi/2 below
  2**19 * pi/2; beyond, exact integer arithmetic with a long 2/pi, per distinct value), then
  ``__kernel_sin``/``__kernel_cos``; errors below 1 ulp.
* **log2** is the first half of fdlibm's ``e_pow.c``: log2(x) as a double-double ``t1 + t2``
  (about 64 correct bits), so ``log2``, ``ln`` (``* ln 2``) and ``log10`` (``* log10 2``, both
  constants split so that the leading product is exact) are almost always correctly rounded,
  and exact at powers of 2 (and of 10 for log10, as far as they are representable).
* **pow** is ``e_pow.c`` whole (error below 1 ulp), with C99's special cases as numpy has them.

Every function takes float64 arrays and returns float64; :mod:`.mathops` rounds to the dtype
numpy would return (float32 stays float32). NaN operands propagate; a NaN made here (log of a
negative number, sin of inf, a negative base to a non-integer power) is
:data:`~matloom.ops.portable_constants.NAN`.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np

from matloom.ops.portable_constants import (
    C1,
    C2,
    C3,
    C4,
    C5,
    C6,
    CP,
    CP_H,
    CP_L,
    DP_H1,
    DP_L1,
    HALF_PI_BITS,
    HALF_PI_INT,
    INVPIO2,
    L1,
    L2,
    L3,
    L4,
    L5,
    L6,
    LG2,
    LG2_H,
    LG2_L,
    LOG10_2,
    LOG10_2_H,
    LOG10_2_L,
    NAN,
    OVT,
    P1,
    P2,
    P3,
    P4,
    P5,
    PIO2_1,
    PIO2_1T,
    PIO2_2,
    PIO2_2T,
    PIO2_3,
    PIO2_3T,
    S1,
    S2,
    S3,
    S4,
    S5,
    S6,
    TWO_OVER_PI_BITS,
    TWO_OVER_PI_INT,
)

_LOW_WORD = np.uint64(0xFFFFFFFF)
_HIGH_WORD = np.uint64(0xFFFFFFFF00000000)
_TWO53 = 9007199254740992.0
#: Above this |x| (fdlibm: high word 0x413921fb) the reduction by pi/2 is exact integer arithmetic.
MEDIUM_LIMIT = float(np.uint64(0x413921FB_FFFFFFFF).view(np.float64))
_TINY_TRIG = 2.0**-27  # sin(x) rounds to x and cos(x) to 1 below this


def _select(mask: np.ndarray, a: np.ndarray | float, b: np.ndarray | float) -> np.ndarray:
    """``np.where(mask, a, b)``, skipped where the mask is all False or all True: special
    values are rare, and ``np.where`` on a mixed mask costs as much as ~30 additions."""
    if np.ndim(mask):
        if np.shape(b) == np.shape(mask) and not mask.any():
            return np.asarray(b)
        if np.shape(a) == np.shape(mask) and mask.all():
            return np.asarray(a)
    return np.where(mask, a, b)


def _bits(x: np.ndarray) -> np.ndarray:
    return np.asarray(x, dtype=np.float64).view(np.uint64)  # same item size: any strides


def _high(x: np.ndarray) -> np.ndarray:
    """The high 32 bits of each float64, as non-negative int64 (sign bit included)."""
    return (_bits(x) >> np.uint64(32)).astype(np.int64)


def _low_zeroed(x: np.ndarray) -> np.ndarray:
    """x with its low 32 bits cleared (fdlibm's ``__LO(x) = 0``): 21 significant bits."""
    return (_bits(x) & _HIGH_WORD).view(np.float64)


def _from_high(high: np.ndarray, low_of: np.ndarray | None = None) -> np.ndarray:
    """float64 with the given high words and low words 0 (or those of ``low_of``)."""
    out = high.astype(np.uint64) << np.uint64(32)
    if low_of is not None:
        out |= _bits(low_of) & _LOW_WORD
    return out.view(np.float64)


# ------------------------------------------------------------------ sin and cos
def _kernel_sin(x: np.ndarray, y: np.ndarray) -> np.ndarray:
    """sin(x + y) for |x + y| <= pi/4 (fdlibm k_sin.c with a tail y)."""
    z = x * x
    w = z * z
    r = S2 + z * (S3 + z * S4) + z * w * (S5 + z * S6)
    v = z * x
    return x - ((z * (0.5 * y - v * r) - y) - v * S1)


def _kernel_cos(x: np.ndarray, y: np.ndarray) -> np.ndarray:
    """cos(x + y) for |x + y| <= pi/4 (fdlibm k_cos.c)."""
    z = x * x
    w = z * z
    r = z * (C1 + z * (C2 + z * C3)) + w * w * (C4 + z * (C5 + z * C6))
    hz = 0.5 * z
    w = 1.0 - hz
    return w + (((1.0 - w) - hz) + (z * r - x * y))


def _reduce_medium(t: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(n, y0, y1) with t - n * pi/2 = y0 + y1 for 0 <= t < 2**19 * pi/2 (Cody-Waite)."""
    fn = np.floor(t * INVPIO2 + 0.5)
    r = t - fn * PIO2_1  # exact: fn < 2**20 and PIO2_1 has 33 bits
    w = fn * PIO2_1T
    for piece, tail in ((PIO2_2, PIO2_2T), (PIO2_3, PIO2_3T)):
        before = r
        w = fn * piece
        r = before - w
        w = fn * tail - ((before - r) - w)
    y0 = r - w
    y1 = (r - y0) - w
    return fn, y0, y1


def _reduce_exact(value: float) -> tuple[int, float, float]:
    """(n mod 4, y0, y1) with value - n * pi/2 = y0 + y1 (y0 + y1 within 2**-200 relative of
    the true remainder, |y0| <= pi/4) for finite value >= 0, by exact integer arithmetic."""
    numerator, denominator = value.as_integer_ratio()  # denominator: a power of 2
    # value * 2/pi = numerator * TWO_OVER_PI_INT / 2**shift
    shift = TWO_OVER_PI_BITS + denominator.bit_length() - 1
    product = numerator * TWO_OVER_PI_INT
    n = product >> shift
    fraction = product - (n << shift)
    if fraction >= 1 << (shift - 1):
        n += 1
        fraction -= 1 << shift
    scaled = fraction * HALF_PI_INT  # the remainder times 2**scale
    scale = shift + HALF_PI_BITS
    y0 = scaled / (1 << scale)  # int / int is correctly rounded
    num0, den0 = y0.as_integer_ratio()
    y1 = (scaled * den0 - (num0 << scale)) / (den0 << scale)
    return n & 3, y0, y1


def _reduce(ax: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(quadrant in 0..3 as int64, y0, y1) for finite ax >= 0."""
    huge = ax > MEDIUM_LIMIT
    fn, y0, y1 = _reduce_medium(_select(huge, 0.0, ax))  # |ax| < pi/4: n = 0, y0 = ax, y1 = 0
    quadrant = np.mod(fn, 4.0).astype(np.int64)
    if huge.any():
        values, where = np.unique(ax[huge], return_inverse=True)
        parts = np.array([_reduce_exact(float(v)) for v in values], dtype=np.float64)
        quadrant[huge] = parts[where, 0].astype(np.int64)
        y0[huge] = parts[where, 1]
        y1[huge] = parts[where, 2]
    return quadrant, y0, y1


def _sin_cos(x: np.ndarray, cosine: bool) -> np.ndarray:
    x = np.asarray(x, dtype=np.float64)
    if x.ndim != 1:  # the exact reduction assigns into 1-d arrays
        return _sin_cos(x.reshape(-1), cosine).reshape(x.shape)
    finite = np.isfinite(x)
    ax = _select(finite, np.abs(x), 0.0)
    quadrant, y0, y1 = _reduce(ax)
    if cosine:
        quadrant = quadrant + 1  # cos(t) = sin(t + pi/2)
    s, c = _kernel_sin(y0, y1), _kernel_cos(y0, y1)
    # select by arithmetic (exact: a product by 0 or 1, a sum with 0); the masks are mixed
    odd = (quadrant & 1).astype(np.float64)
    out = (c * odd + s * (1.0 - odd)) * (1.0 - (quadrant & 2))
    if cosine:
        out = _select(ax < _TINY_TRIG, 1.0, out)
    else:
        out = out * np.copysign(1.0, x)
        out = _select(ax < _TINY_TRIG, x, out)  # keeps -0.0
    return _select(finite, out, np.where(x != x, x, NAN))


def sin(x: np.ndarray) -> np.ndarray:
    """Sine of float64 radians (NaN for +-inf)."""
    return _sin_cos(x, cosine=False)


def cos(x: np.ndarray) -> np.ndarray:
    """Cosine of float64 radians (NaN for +-inf)."""
    return _sin_cos(x, cosine=True)


# ------------------------------------------------------------------ log2 as a double-double
def _log2_parts(ax: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(t1, t2): log2(ax) = t1 + t2 to about 2**-64 relative, t1 with 21 significant bits, for
    finite ax > 0 (fdlibm e_pow.c, the |y| <= 2**31 branch)."""
    subnormal = ax < 2.0**-1022
    if subnormal.any():
        with np.errstate(over="ignore"):
            ax = np.where(subnormal, ax * _TWO53, ax)
    high = _high(ax)
    n = (high >> 20) - 0x3FF - 53 * subnormal
    j = high & 0x000FFFFF
    ix = j | 0x3FF00000
    wide = j >= 0xBB67A  # |x| >= sqrt(3) in [1, 2): use x/2 and n + 1
    k = ((j > 0x3988E) & ~wide).astype(np.int64)
    n = n + wide
    ix = ix - wide * 0x00100000
    ax = _from_high(ix, low_of=ax)
    kf = k.astype(np.float64)  # selections by products with 0 or 1 (exact; the mask is mixed)
    bp = 1.0 + 0.5 * kf
    dp_h = kf * DP_H1
    dp_l = kf * DP_L1
    u = ax - bp
    v = 1.0 / (ax + bp)
    ss = u * v
    s_h = _low_zeroed(ss)
    t_h = _from_high(((ix >> 1) | 0x20000000) + 0x00080000 + (k << 18))
    t_l = ax - (t_h - bp)
    s_l = v * ((u - s_h * t_h) - s_h * t_l)
    s2 = ss * ss
    r = s2 * s2 * (L1 + s2 * (L2 + s2 * (L3 + s2 * (L4 + s2 * (L5 + s2 * L6)))))
    r = r + s_l * (s_h + ss)
    s2 = s_h * s_h
    t_h = _low_zeroed((3.0 + s2) + r)
    t_l = r - ((t_h - 3.0) - s2)
    u = s_h * t_h
    v = s_l * t_h + t_l * ss
    p_h = _low_zeroed(u + v)
    p_l = v - (p_h - u)
    z_h = CP_H * p_h
    z_l = CP_L * p_h + p_l * CP + dp_l
    t = n.astype(np.float64)
    t1 = _low_zeroed(((z_h + z_l) + dp_h) + t)
    t2 = z_l - (((t1 - t) - dp_h) - z_h)
    return t1, t2


def _log_special(x: np.ndarray, out: np.ndarray) -> np.ndarray:
    """log's values at 0 (-inf), below 0 (NaN), +inf and NaN over the computed ``out``."""
    out = _select(x == 0.0, -np.inf, out)
    out = _select(x < 0.0, NAN, out)
    out = _select(x == np.inf, np.inf, out)
    return _select(x != x, x, out)


def _log_scaled(x: np.ndarray, c: float, c_h: float, c_l: float) -> np.ndarray:
    """c * log2(x) with c = c_h + c_l (c_h of 21 bits, so that t1 * c_h is exact)."""
    x = np.asarray(x, dtype=np.float64)
    t1, t2 = _log2_parts(_select((x > 0.0) & (x < np.inf), x, 1.0))
    return _log_special(x, t1 * c_h + (t2 * c + t1 * c_l))


def log2(x: np.ndarray) -> np.ndarray:
    """Base-2 logarithm (exact at powers of 2)."""
    x = np.asarray(x, dtype=np.float64)
    t1, t2 = _log2_parts(_select((x > 0.0) & (x < np.inf), x, 1.0))
    return _log_special(x, t1 + t2)


def log(x: np.ndarray) -> np.ndarray:
    """Natural logarithm."""
    return _log_scaled(x, LG2, LG2_H, LG2_L)


def log10(x: np.ndarray) -> np.ndarray:
    """Base-10 logarithm."""
    return _log_scaled(x, LOG10_2, LOG10_2_H, LOG10_2_L)


def log_scalar(x: float) -> float:
    """Natural logarithm of one float (for the static rules and scalar bases)."""
    return scalar(log, x)


# ------------------------------------------------------------------ pow
def _odd_integer(y: np.ndarray) -> np.ndarray:
    """y is an odd integer (|y| >= 2**53 is always even)."""
    return (np.abs(y) < _TWO53) & (y - 2.0 * np.floor(y * 0.5) == 1.0)


def _exp2_parts(p_h: np.ndarray, p_l: np.ndarray) -> np.ndarray:
    """2 ** (p_h + p_l) for -1075 <= p_h + p_l <= 1024 (e_pow.c's last part)."""
    z = p_l + p_h
    i = _high(z) & 0x7FFFFFFF
    az = np.abs(z)
    whole = np.floor(az)
    # n = the integer nearest z, ties away from 0 (exactly fdlibm's bit manipulation)
    n = np.copysign(whole + (az - whole >= 0.5), z) * (i > 0x3FE00000)
    p_h = p_h - n
    t = _low_zeroed(p_l + p_h)
    u = t * LG2_H
    v = (p_l - (t - p_h)) * LG2 + t * LG2_L
    z = u + v
    w = v - (z - u)
    t = z * z
    t1 = z - t * (P1 + t * (P2 + t * (P3 + t * (P4 + t * P5))))
    r = (z * t1) / (t1 - 2.0) - (w + z * w)
    z = 1.0 - (r - z)
    return np.ldexp(z, n.astype(np.int64))


def _pow_finite(x: np.ndarray, y: np.ndarray) -> np.ndarray:
    """|x| ** y for finite x != 0, |x| != 1 and finite y != 0 (e_pow.c's main path)."""
    ax = np.abs(x)
    huge_y = np.abs(y) > 2.0**31
    close = (ax >= 1.0 - 2.0**-20) & (ax <= 1.0 + 2.0**-20)
    # e_pow.c takes log2 by a series of t = x - 1 here when |y| > 2**31; t * IVLN2_H is not
    # exact then (up to 700 ulps off for results near the underflow): the main path is
    t1, t2 = _log2_parts(ax)
    y1 = _low_zeroed(y)
    p_l = (y - y1) * t1 + y * t2
    p_h = y1 * t1
    z = p_l + p_h
    over = (z > 1024.0) | ((z == 1024.0) & (p_l + OVT > z - p_h))
    under = (z < -1075.0) | ((z == -1075.0) & (p_l <= z - p_h))
    inside = ~(over | under)
    out = _exp2_parts(_select(inside, p_h, 0.0), _select(inside, p_l, 0.0))
    out = _select(under, 0.0, _select(over, np.inf, out))
    # beyond 2**31 (and not close to 1), |x| ** y over- or underflows: inf or 0 by the sides
    flows = huge_y & ~close
    return _select(flows, np.where((ax > 1.0) == (y > 0.0), np.inf, 0.0), out)


def pow_(x: np.ndarray, y: np.ndarray) -> np.ndarray:
    """x ** y with C99's (and numpy's) special cases; error below 1 ulp."""
    if np.ndim(y) == 0 and np.ndim(x) > 0:
        return _pow_scalar_exponent(np.asarray(x, dtype=np.float64), float(y))
    return _pow_general(x, y)


def _pow_exact(x: np.ndarray, y: float) -> np.ndarray | None:
    """x ** y for the exponents whose every case :func:`_pow_general` answers without its main
    path: x ** 2 is ``x * x`` (+-0, +-1 and +-inf included) and x ** 1 is ``x``, NaN staying
    the operand itself in both; None for other exponents."""
    if y == 2.0:
        return np.where(x != x, x, x * x)
    if y == 1.0:
        return x.copy()
    return None


def _pow_scalar_exponent(x: np.ndarray, y: float) -> np.ndarray:
    """:func:`pow_` for one exponent (the sRGB curves): the special cases are decided once, and
    only the elements with a special base go through :func:`_pow_general`."""
    exact = _pow_exact(x, y)
    if exact is not None:
        return exact
    if not np.isfinite(y) or y in (0.0, -1.0, 0.5):
        return _pow_general(x, y)
    ax = np.abs(x)
    regular = (ax > 0.0) & (ax < np.inf) & (ax != 1.0)
    out = _pow_finite(_select(regular, x, 2.0), np.float64(y))
    if y == np.floor(y):
        if abs(y) < _TWO53 and y - 2.0 * np.floor(y * 0.5) == 1.0:
            out = _select(x < 0.0, -out, out)
    else:
        out = _select(x < 0.0, NAN, out)
    special = ~regular
    if special.any():
        out[special] = _pow_general(x[special], y)
    return out


def _pow_general(x: np.ndarray, y: np.ndarray | float) -> np.ndarray:
    """:func:`pow_` for any operands."""
    x, y = np.broadcast_arrays(np.asarray(x, dtype=np.float64), np.asarray(y, dtype=np.float64))
    ax = np.abs(x)
    integer = np.floor(y) == y
    odd = _odd_integer(y)
    negative_odd = (x < 0.0) & odd  # the result takes x's sign
    regular = np.isfinite(x) & np.isfinite(y) & (x != 0.0) & (ax != 1.0) & (y != 0.0)
    body = _pow_finite(np.where(regular, x, 2.0), np.where(regular, y, 1.0))
    out = np.where(negative_odd, -body, body)
    out = np.where((x < 0.0) & ~integer & regular, NAN, out)
    # exact shortcuts of e_pow.c
    out = np.where(y == 1.0, x, out)
    out = np.where(y == -1.0, 1.0 / np.where(y == -1.0, x, 1.0), out)
    out = np.where(y == 2.0, x * x, out)
    out = np.where((y == 0.5) & (x > 0.0), np.sqrt(np.where(x > 0.0, x, 0.0)), out)
    # |x| == 1
    out = np.where(ax == 1.0, np.where(negative_odd, -1.0, 1.0), out)
    out = np.where((x == -1.0) & np.isfinite(y) & ~integer, NAN, out)
    # x == +-0: +-0 or +-inf for odd y (signed like x), else +0 or +inf
    zero = np.where(y < 0.0, np.inf, 0.0)
    out = np.where(x == 0.0, np.where(odd, np.copysign(zero, x), zero), out)
    # x == +-inf
    at_inf = np.where(y > 0.0, np.inf, 0.0)
    out = np.where(np.isinf(x), np.where(negative_odd, -at_inf, at_inf), out)
    # y == +-inf: by |x| against 1 (|x| == 1: 1)
    beyond = np.where((ax > 1.0) == (y > 0.0), np.inf, 0.0)
    out = np.where(np.isinf(y), np.where(ax == 1.0, 1.0, beyond), out)
    out = np.where(x != x, x, np.where(y != y, y, out))
    return np.where((y == 0.0) | (x == 1.0), 1.0, out)


# ------------------------------------------------------------------ array plumbing
#: Elements per block: the ~40 temporaries of a block (~1.3 MiB) stay in the CPU cache and
#: add little to the evaluation's peak memory (engine.limits' estimate).
_BLOCK = 4096


def blockwise(
    fn: Callable[..., np.ndarray], *operands: np.ndarray, dtype: np.dtype | type = np.float64
) -> np.ndarray:
    """``fn`` (float64 in, float64 out, element-wise) over broadcast float64 operands, in blocks
    of :data:`_BLOCK` elements, rounded into an array of ``dtype``; an operand of one element
    stays a scalar."""
    arrays = [np.asarray(a, dtype=np.float64) for a in operands]
    shape = np.broadcast_shapes(*(a.shape for a in arrays))
    flat = [a.reshape(()) if a.size == 1 else np.broadcast_to(a, shape).reshape(-1) for a in arrays]
    out = np.empty(shape, dtype=dtype)
    view = out.reshape(-1)
    with np.errstate(all="ignore"):
        for start in range(0, max(view.size, 1), _BLOCK):
            stop = start + _BLOCK
            view[start:stop] = fn(*(a if a.ndim == 0 else a[start:stop] for a in flat))
    return out


def scalar(fn: Callable[..., np.ndarray], *values: float) -> float:
    """``fn`` of Python numbers, as a Python float (the static rules' constant folding)."""
    with np.errstate(all="ignore"):
        return float(fn(*(np.asarray(float(v), dtype=np.float64) for v in values)))
