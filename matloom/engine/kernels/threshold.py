"""Threshold grid kernel and the channel clamp (reference spec §2.7).

The reference evaluates Threshold with a compiled kernel that does its arithmetic in float64
and stores into an array of the input's dtype. A float32 input therefore yields float64
arithmetic rounded once to float32 (the parity fixtures confirm this: ``0.8703703880310059``
for ``Threshold(Y(), above_at=0.6, above_to=1, transition_width=0.3)`` at y = 0.5f).
This module reproduces that and returns float64 arrays holding those values.

NaN passes through every rule unchanged because all comparisons with NaN are false.
"""

from __future__ import annotations

import numpy as np


def _smoothstep(t: np.ndarray) -> np.ndarray:
    """Cubic Hermite ``t*t*(3 - 2t)`` (no clipping; callers pass 0 < t < 1)."""
    return t * t * (3.0 - 2.0 * t)


def _apply_above(
    v: np.ndarray, result: np.ndarray, at: float, to: float, width: float
) -> np.ndarray:
    """Step 1: clamp or ramp towards ``to`` for v near or above ``at`` (ramp in [at-w, at])."""
    if width == 0:
        return np.where(v >= at, to, result)
    t = (v - (at - width)) / width
    ramp = (1.0 - _smoothstep(t)) * v + _smoothstep(t) * to
    result = np.where((t > 0) & (t < 1), ramp, result)
    return np.where(t >= 1, to, result)


def _apply_below(
    v: np.ndarray, result: np.ndarray, at: float, to: float, width: float
) -> np.ndarray:
    """Step 2: clamp or ramp towards ``to`` for v near or below ``at`` (ramp in [at, at+w]).

    Uses the original ``v`` in the ramp, and wins over step 1 where both apply.
    """
    if width == 0:
        return np.where(v <= at, to, result)
    t = (v - at) / width
    ramp = (1.0 - _smoothstep(t)) * to + _smoothstep(t) * v
    result = np.where((t > 0) & (t < 1), ramp, result)
    return np.where(t <= 0, to, result)


def threshold(
    v: np.ndarray,
    *,
    below_at: float | None,
    below_to: float | None,
    above_at: float | None,
    above_to: float | None,
    transition_width: float,
) -> np.ndarray:
    """Grid-path Threshold of spec §2.7; returns float64 (float32-rounded for float32 ``v``).

    ``below_to``/``above_to`` default to their cut-off values. Hard cut-offs are inclusive and
    the below rule wins where both rules apply (so ``below_at == above_at == c`` gives the
    below value at exactly ``c``). This is the grid kernel's behaviour, not the reference's
    inconsistent scalar path.
    """
    v = np.asarray(v)
    store_dtype = np.float32 if v.dtype == np.float32 else np.float64
    v64 = v.astype(np.float64)
    width = float(transition_width)
    if width < 0:
        raise ValueError(f"transition_width must be >= 0, got {transition_width}")
    result = v64
    with np.errstate(invalid="ignore", over="ignore"):
        if above_at is not None:
            target = float(above_at if above_to is None else above_to)
            result = _apply_above(v64, result, float(above_at), target, width)
        if below_at is not None:
            target = float(below_at if below_to is None else below_to)
            result = _apply_below(v64, result, float(below_at), target, width)
    return np.asarray(result, dtype=store_dtype).astype(np.float64)


def clamp(v: np.ndarray, lo: float | None, hi: float | None) -> np.ndarray:
    """Channel clamp = Threshold with hard cut-offs at ``lo`` and ``hi`` (NaN passes through).

    Unlike ``np.clip`` this keeps NaN and matches the reference's clamp exactly
    (``v <= lo -> lo``, ``v >= hi -> hi``).
    """
    return threshold(v, below_at=lo, below_to=lo, above_at=hi, above_to=hi, transition_width=0.0)
