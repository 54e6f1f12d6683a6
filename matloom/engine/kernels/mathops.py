"""Element-wise math nodes with the reference's special rules (spec §2.2).

These are the numpy implementations of the element-wise ops (:mod:`matloom.engine.ops`): the
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

import numpy as np

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


def log(v: ArrayLike, base: float = math.e) -> np.ndarray:
    """Logarithm with the reference's base dispatch (log10, log2, ln, else ln(v)/ln(base)).

    ln(base) is a Python float, so a float32 ``v`` stays float32 for unusual bases.
    """
    v = np.asarray(v)
    base = float(base)
    with _quiet():
        if base == 10.0:
            return np.log10(v)
        if base == 2.0:
            return np.log2(v)
        if base == math.e:
            return np.log(v)
        return np.log(v) / _ln_scalar(base)


def _ln_scalar(base: float) -> float:
    """Natural log of a scalar base as numpy defines it: -inf for 0, NaN below 0."""
    if base > 0:
        return math.log(base)
    return -math.inf if base == 0 else math.nan


def pow_(a: ArrayLike, b: ArrayLike) -> np.ndarray:
    """``a ** b`` (NaN for a negative base with a non-integer exponent, inf for 0 ** -n)."""
    with _quiet():
        return np.power(np.asarray(a), np.asarray(b))


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
    with _quiet():
        return np.sin(np.asarray(v))


def cos(v: ArrayLike) -> np.ndarray:
    """Cosine of radians (inf gives NaN quietly)."""
    with _quiet():
        return np.cos(np.asarray(v))
