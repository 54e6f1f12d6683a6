"""Op entries of the language-2 math functions (see :mod:`matloom.vocab.functions_math`);
:data:`matloom.ops.table.OPS` includes them.

* **Atan2, Fract, Mod, Exp** are element-wise ops with their own opcodes (``atan2``, ``fract``,
  ``mod``, ``exp``). They compute in float64 and return float64 (``dtype="float64"``, like
  Threshold) with the numpy functions of :mod:`matloom.engine.kernels.mathops`, whose float64
  operations the register machine repeats (:mod:`matloom.engine.kernels.mathops_numba`). Mod
  divides like Div: 0 where the divisor is exactly 0, counted as a division by zero.
* **Clamp, Mix, Smoothstep** take three field operands; a register-machine row has two. They
  are field rules (:mod:`matloom.engine.rules.fields_math`) that compose Min, Max, Add, Sub, Mul
  and Div, so the fused path runs them on those opcodes and culling reads those ops' bounds;
  the bounds rules here state the same intervals for the call as a whole. Their dtype is the
  composed ops' (numpy promotion of the operands).
* **Hash** is a primitive field: a float32 leaf (24-bit values, exact) from the backend's hash
  kernel (:mod:`matloom.engine.kernels.hashing`, :mod:`matloom.engine.kernels.hash_numba`).

Static (constant-folding) rules get the values of the arguments as written, without their
names: a call that omits an optional argument but writes a later one is ambiguous there (e.g.
``Clamp(3, hi=2)``, ``Hash(3, seed=5)``), so it is not a constant (fine in a channel, which the
evaluator computes; rejected where a number is required). Folding uses the numpy functions, so
a folded value has the evaluated value's bits. Importing this module imports neither numpy nor
a kernel (the rules import them on first use).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any

import matloom.ops.period as P
import matloom.ops.work as W
from matloom.ops.op import NUMPY, Bounds, Interval, Kind, Op, Ref

_MATHOPS = "matloom.engine.kernels.mathops:"
_RULES = "matloom.engine.rules.fields_math:"
#: Interval endpoints beyond this magnitude are not analysed (products and sums may overflow).
_LARGE = 1e300


# ------------------------------------------------------------------ static (constant) rules
def _folded(function: str, arity: int, defaults: tuple[float, ...] = ()) -> Callable[..., Any]:
    """Static rule: ``function`` (a mathops array function) on the float values, when there are
    ``arity`` of them, or ``arity - len(defaults)`` (the trailing defaults then fill in)."""
    implementation = Ref(function)

    def rule(values: list[Any], strict: bool) -> float | None:
        if len(values) == arity - len(defaults):
            values = [*values, *defaults]
        if len(values) != arity:
            return None
        return float(implementation(*(float(v) for v in values)))

    return rule


_HASH_VALUE = Ref("matloom.engine.kernels.hashing:hash_value")


def _hash_static(values: list[Any], strict: bool) -> float | None:
    """Hash(x, y, seed) of three written constants (two are ambiguous: y or the seed)."""
    if len(values) != 3:
        return None
    return float(_HASH_VALUE(float(values[0]), float(values[1]), int(round(values[2]))))


# ------------------------------------------------------------------ bounds (interval) rules
def _finite(*intervals: Interval) -> bool:
    return all(abs(v) < _LARGE for iv in intervals for v in iv)


def _atan2_bounds(y: Interval, x: Interval) -> Bounds:
    return (-math.pi, math.pi)


def _fract_bounds(x: Interval) -> Bounds:
    return (0.0, 1.0)


def _mod_bounds(x: Interval, m: Interval) -> Bounds:
    """|x - m floor(x / m)| stays within |m| up to the rounding of x / m and of the product,
    as long as x / m cannot overflow; 0 where m is 0."""
    if m == (0.0, 0.0):
        return (0.0, 0.0)
    if m[0] <= 0.0 <= m[1]:
        return None  # divisors near 0: x / m may overflow
    big_m, small_m = max(abs(m[0]), abs(m[1])), min(abs(m[0]), abs(m[1]))
    big_x = max(abs(x[0]), abs(x[1]))
    if not big_x < small_m * _LARGE:
        return None
    slack = (big_x + big_m) * 2.0**-50
    return (-slack, big_m + slack) if m[0] > 0.0 else (-big_m - slack, slack)


def _exp_bounds(x: Interval) -> Bounds:
    if x[1] > 700.0:
        return None
    widen = 1.0 + 2.0**-50  # exp_ is within 1 ulp of math.exp
    return (math.exp(x[0]) / widen, math.exp(x[1]) * widen)


def _clamp_bounds(x: Interval, lo: Interval = (0.0, 0.0), hi: Interval = (1.0, 1.0)) -> Bounds:
    return (min(max(x[0], lo[0]), hi[0]), min(max(x[1], lo[1]), hi[1]))


def _mix_bounds(a: Interval, b: Interval, t: Interval) -> Bounds:
    if not _finite(a, b, t):
        return None
    d = (b[0] - a[1], b[1] - a[0])
    products = [d[i] * t[k] for i in (0, 1) for k in (0, 1)]
    return (a[0] + min(products), a[1] + max(products))


def _smoothstep_bounds(edge0: Interval, edge1: Interval, x: Interval) -> Bounds:
    return (0.0, 1.0) if _finite(edge0, edge1, x) else None  # NaN only from inf - inf


def _hash_bounds(x: Interval, y: Interval = (0.0, 0.0), **params: Any) -> Bounds:
    inside = all(abs(v) < 2.0**62 for iv in (x, y) for v in iv)
    return (0.0, 1.0) if inside else None  # NaN beyond the int64 cells


# ------------------------------------------------------------------ the entries
def _elementwise(
    name: str,
    function: str,
    arity: int,
    bounds: Callable[..., Bounds],
    work: float = 1,
    period: P.Period = P.KEEP,
) -> Op:
    static = _folded(_MATHOPS + function, arity)
    fast = name.lower()  # the opcode (kernels.register_ops)
    divisor = 1 if name == "Mod" else None
    return Op(
        name,
        Kind.ELEMENTWISE,
        Ref(_MATHOPS + function),
        static,
        bounds,
        fast,
        divisor=divisor,
        dtype="float64",
        work=work,
        period=period,
    )


def _composed(
    name: str,
    rule: str,
    static: Callable[..., Any],
    bounds: Callable[..., Bounds],
    arrays: int,
    work: float = 1,
    period: P.Period = P.KEEP,
) -> Op:
    return Op(
        name,
        Kind.FIELD,
        Ref(_RULES + rule),
        static,
        bounds,
        NUMPY,
        arrays=arrays,
        work=work,
        period=period,
    )


MATH_V2_ENTRIES: tuple[Op, ...] = (
    _elementwise("Atan2", "atan2", 2, _atan2_bounds, W.TRANSCENDENTAL),
    # Fract and Mod repeat every cycle of their argument (ParamSpec.cycle: 1, and Mod's m)
    _elementwise("Fract", "fract", 1, _fract_bounds, period=P.wrap()),
    _elementwise("Mod", "mod", 2, _mod_bounds, period=P.wrap()),
    _elementwise("Exp", "exp_", 1, _exp_bounds, W.TRANSCENDENTAL),
    _composed("Clamp", "clamp", _folded(_MATHOPS + "clamp", 3, (0.0, 1.0)), _clamp_bounds, 3),
    _composed("Mix", "mix", _folded(_MATHOPS + "mix", 3), _mix_bounds, 4),
    _composed(
        "Smoothstep",
        "smoothstep",
        _folded(_MATHOPS + "smoothstep", 3),
        _smoothstep_bounds,
        9,
        W.SMOOTHSTEP,
    ),
    # Hash: the cells of its operands (the engine wraps them modulo the cells per period)
    _composed(
        "Hash",
        "hash_cells",
        _hash_static,
        _hash_bounds,
        3,
        W.HASH,
        period=P.wrap(unit="cells", framed=True),
    ),
)
