"""The op table: every registry function's engine rules, one entry each (see :mod:`.op`).

To add an element-wise function: its registry entry (:mod:`matloom.vocab.functions`) and one
:data:`OPS` entry here (numpy implementation, static rule, bounds rule, opcode or NUMPY; its
period rule when it is not element-wise for tiling, :mod:`.period`). Nothing else in the
engine, the checker or the sweep names a function.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any

import matloom.ops.period as P
import matloom.ops.period_rules as PR
import matloom.ops.transform as T
import matloom.ops.work as W
from matloom.ops.op import (
    NUMPY,
    Bounds,
    Interval,
    Kind,
    Op,
    Ref,
    not_constant,
    unbounded,
)
from matloom.ops.table_math import MATH_V2_ENTRIES
from matloom.ops.table_quantize import QUANTIZE_ENTRIES
from matloom.vocab import FUNCTIONS

_MATHOPS = "matloom.engine.kernels.mathops:"
_FIELDS = "matloom.engine.rules.fields:"
_SUPPORT = "matloom.engine.rules.support:"
_INSTANCING = "matloom.engine.rules.instancing:"
_UNION = Ref(_SUPPORT + "union")
_MOVED = Ref(_SUPPORT + "transformed")


# ------------------------------------------------------------------ static (constant) rules
def _unary(fn: Callable[[Any], Any]) -> Callable[[list[Any], bool], Any]:
    def rule(values: list[Any], strict: bool) -> Any:
        return float(fn(values[0])) if len(values) == 1 else None

    return rule


def _binary(fn: Callable[[Any, Any], Any]) -> Callable[[list[Any], bool], Any]:
    def rule(values: list[Any], strict: bool) -> Any:
        return fn(values[0], values[1]) if len(values) == 2 else None

    return rule


def _fold(fn: Callable[[Any, Any], Any]) -> Callable[[list[Any], bool], Any]:
    """Min, Max of two or more values: the binary rule folded left, as the engine computes
    ``Min(a, b, c)`` (``Min(Min(a, b), c)``)."""

    def rule(values: list[Any], strict: bool) -> Any:
        if len(values) < 2:
            return None
        out = fn(values[0], values[1])
        for v in values[2:]:
            out = fn(out, v)
        return out

    return rule


def _coordinate(values: list[Any], strict: bool) -> float | None:
    """X()/Y() are 0 at the origin, where a numeric argument is evaluated (not strict)."""
    return None if strict else 0.0


def _constant(values: list[Any], strict: bool) -> Any:
    return values[0] if values else 0.0


def _portable(name: str, *values: float) -> float:
    """A function of :mod:`~matloom.ops.portable_math` on Python numbers: constant
    folding must give the bits the arrays get, on every CPU (``math.sin`` and ``**`` call the
    C library, which picks its code by CPU)."""
    from matloom.ops import portable_math

    return portable_math.scalar(getattr(portable_math, name), *values)


def _trig(name: str) -> Callable[[Any], float]:
    def rule(v: Any) -> float:
        if math.isinf(v):
            raise ValueError("math domain error")  # as math.sin: the static value is NaN
        return _portable(name, v)

    return rule


def _pow(a: float | int, b: float | int) -> float:
    if a < 0 and not float(b).is_integer():
        return math.nan
    if a == 0 and b < 0:
        return math.inf
    result = _portable("pow_", a, b)
    if math.isinf(result) and math.isfinite(a) and math.isfinite(b):
        raise OverflowError("pow overflows")  # as float ** float
    return result


def _ln(x: float) -> float:
    """Natural log of x > 0 (ValueError below, as ``math.log``)."""
    if not x > 0:
        raise ValueError("math domain error")
    return _portable("log", x)


def _log(values: list[Any], strict: bool) -> float:
    x = float(values[0])
    base = float(values[1]) if len(values) > 1 else math.e
    if x == 0:
        return -math.inf
    if x < 0:
        return math.nan
    if base == 10:
        return _portable("log10", x)
    if base == 2:
        return _portable("log2", x)
    return _ln(x) if base == math.e else _ln(x) / _ln(base)


# ------------------------------------------------------------------ bounds (interval) rules
def _add_bounds(a: Interval, b: Interval) -> Bounds:
    candidates = [a[0] + b[0], a[1] + b[1]]
    return (min(candidates), max(candidates))


def _sub_bounds(a: Interval, b: Interval) -> Bounds:
    candidates = [a[0] - b[1], a[1] - b[0]]
    return (min(candidates), max(candidates))


def _mul_bounds(a: Interval, b: Interval) -> Bounds:
    candidates = [a[i] * b[k] for i in (0, 1) for k in (0, 1)]
    return (min(candidates), max(candidates))


def _div_bounds(a: Interval, b: Interval) -> Bounds:
    if b == (0.0, 0.0):
        return (0.0, 0.0)  # safe division gives 0 wherever the divisor is 0
    if b[0] <= 0.0 <= b[1]:
        return None  # near-zero divisors are unbounded
    quotients = [a[i] / b[k] for i in (0, 1) for k in (0, 1)]
    return (min(quotients), max(quotients))


def _min_bounds(*operands: Interval) -> Bounds:
    return (min(iv[0] for iv in operands), min(iv[1] for iv in operands))


def _max_bounds(*operands: Interval) -> Bounds:
    return (max(iv[0] for iv in operands), max(iv[1] for iv in operands))


def _abs_bounds(a: Interval) -> Bounds:
    lo = 0.0 if a[0] <= 0.0 <= a[1] else min(abs(a[0]), abs(a[1]))
    return (lo, max(abs(a[0]), abs(a[1])))


def _monotone(fn: Callable[[float], float]) -> Callable[[Interval], Bounds]:
    def rule(a: Interval) -> Bounds:
        return (fn(a[0]), fn(a[1]))

    return rule


def _sqrt_bounds(a: Interval) -> Bounds:
    return (math.sqrt(a[0]), math.sqrt(a[1])) if a[0] >= 0.0 else None


def _periodic_bounds(a: Interval) -> Bounds:
    """Sin/Cos of a finite interval (NaN only for infinite input, which has no bounds)."""
    return (-1.0, 1.0)


# ------------------------------------------------------------------ fast-path parameter blocks
def _threshold_block(
    below_at: Any, below_to: Any, above_at: Any, above_to: Any, transition_width: Any
) -> list[float]:
    """The 6 constants of the ``threshold`` opcode (see register_numba)."""
    below, above = below_at, above_at
    return [
        0.0 if below is None else float(below),
        0.0 if below is None else float(below if below_to is None else below_to),
        0.0 if above is None else float(above),
        0.0 if above is None else float(above if above_to is None else above_to),
        float(transition_width),
        float((above is not None) + 2 * (below is not None)),
    ]


# ------------------------------------------------------------------ the table
def _cycle(func: str, param: str) -> float:
    """The registry's cycle of a parameter (``ParamSpec.cycle``: a full turn of an angle)."""
    spec = FUNCTIONS[func].param(param)
    assert spec is not None and isinstance(spec.cycle, float), (func, param)
    return spec.cycle


def _math(
    name: str,
    numpy: str,
    static: Callable[[list[Any], bool], Any],
    bounds: Callable[..., Bounds],
    fast: str | None,
    **extra: Any,
) -> Op:
    return Op(name, Kind.ELEMENTWISE, Ref(numpy), static, bounds, fast, **extra)


def _field(
    name: str,
    rule: str,
    period: P.Period,
    transform: T.Transform | None = None,
    support: Callable[..., Any] | None = None,
    arrays: int = 1,
    work: float | Callable[..., float] = 1,
) -> Op:
    return Op(
        name,
        Kind.FIELD,
        Ref(_FIELDS + rule),
        not_constant,
        unbounded,
        NUMPY,
        transform=transform,
        support=support,
        arrays=arrays,
        work=work,
        period=period,
    )


def _coordinate_field(name: str, rule: str, axis: tuple[float, float]) -> Op:
    period = P.axis(*axis)
    return Op(name, Kind.FIELD, Ref(_FIELDS + rule), _coordinate, unbounded, NUMPY, period=period)


def _geometry(name: str, rule: str, work: float = 1) -> Op:
    """A shape or path segment; its ``work`` is added to the Fill/Stroke that draws it."""
    return Op(name, Kind.GEOMETRY, Ref(_FIELDS + rule), not_constant, unbounded, NUMPY, work=work)


_ENTRIES: tuple[Op, ...] = (
    # coordinates and constants
    _coordinate_field("X", "x", (1.0, 0.0)),
    _coordinate_field("Y", "y", (0.0, 1.0)),
    Op("Constant", Kind.FIELD, Ref(_FIELDS + "constant"), _constant, unbounded, NUMPY),
    # element-wise math: numpy implementation, static rule, bounds rule, opcode or NUMPY
    _math("Add", _MATHOPS + "add", _binary(lambda a, b: a + b), _add_bounds, "add", support=_UNION),
    _math("Sub", _MATHOPS + "sub", _binary(lambda a, b: a - b), _sub_bounds, "sub", support=_UNION),
    _math(
        "Mul",
        _MATHOPS + "mul",
        _binary(lambda a, b: a * b),
        _mul_bounds,
        "mul",
        support=Ref(_SUPPORT + "product"),
    ),
    _math(
        "Div",
        _MATHOPS + "safe_div",
        _binary(lambda a, b: 0.0 if b == 0 else a / b),
        _div_bounds,
        "div",
        divisor=1,
        support=Ref(_SUPPORT + "quotient"),
    ),
    _math("Pow", _MATHOPS + "pow_", _binary(_pow), unbounded, NUMPY, work=W.TRANSCENDENTAL),
    _math(
        "Min",
        _MATHOPS + "minimum",
        _fold(min),
        _min_bounds,
        "min",
        support=_UNION,
    ),
    _math(
        "Max",
        _MATHOPS + "maximum",
        _fold(max),
        _max_bounds,
        "max",
        support=_UNION,
    ),
    _math("Abs", _MATHOPS + "abs_", _unary(abs), _abs_bounds, "abs"),
    _math(
        "Sqrt",
        _MATHOPS + "sqrt",
        _unary(lambda v: math.sqrt(v) if v >= 0 else math.nan),
        _sqrt_bounds,
        "sqrt",
    ),
    _math(
        "Floor",
        _MATHOPS + "floor",
        _unary(math.floor),
        _monotone(math.floor),
        "floor",
        period=P.STEP,
    ),
    _math(
        "Ceil", _MATHOPS + "ceil", _unary(math.ceil), _monotone(math.ceil), "ceil", period=P.STEP
    ),
    _math(
        "Sin",
        _MATHOPS + "sin",
        _unary(_trig("sin")),
        _periodic_bounds,
        NUMPY,
        work=W.TRANSCENDENTAL,
        period=P.wrap(),
    ),
    _math(
        "Cos",
        _MATHOPS + "cos",
        _unary(_trig("cos")),
        _periodic_bounds,
        NUMPY,
        work=W.TRANSCENDENTAL,
        period=P.wrap(),
    ),
    _math("Log", _MATHOPS + "log", _log, unbounded, NUMPY, work=W.TRANSCENDENTAL),
    _math(
        "Threshold",
        _FIELDS + "threshold",
        not_constant,
        unbounded,  # not analysed by culling
        "threshold",
        dtype="float64",
        block=_threshold_block,
        check=Ref(_FIELDS + "check_threshold"),
        work=W.THRESHOLD,
    ),
    # primitive fields (backend kernels); their own periods: lattices, cells, shape images
    _field("fBm", "fbm", P.own(PR.fbm), work=W.fbm),
    _field("Worley", "worley", P.own(PR.worley), arrays=3, work=W.worley),
    _field("Bricks", "bricks", P.own(PR.bricks), arrays=2, work=W.BRICKS),
    _field("Weave", "weave", P.own(PR.weave), arrays=5, work=W.weave),
    _field("Fill", "fill", P.own(), support=Ref(_SUPPORT + "fill"), work=W.SHAPE),
    _field("Stroke", "stroke", P.own(), support=Ref(_SUPPORT + "stroke"), work=W.SHAPE),
    # coordinate transforms of the operand (values, coordinates, frame matrix, warp values,
    # the way back; see matloom.ops.transform) and what they do to the View's periods
    _field(
        "Translate",
        "transformed",
        P.transform(P.translated, warp_keeps=True),
        T.Transform(
            values=T.params("dx", "dy"),
            coords=lambda x, y, a, b: (x - a, y - b),
            matrix=lambda u, v: (1.0, 0.0, -u, 0.0, 1.0, -v),
            warp=T.pair,
            back=lambda u, v, a, b: (u + a, v + b),  # evaluated at p - d: p = q + d
        ),
        support=_MOVED,
    ),
    _field(
        "Scale",
        "transformed",
        P.transform(P.scaled("sx", "sy")),
        T.Transform(
            values=T.params("sx", "sy"),
            coords=lambda x, y, a, b: (x / a, y / b),
            matrix=lambda u, v: (1.0 / u, 0.0, 0.0, 0.0, 1.0 / v, 0.0),
            warp=T.pair,
            back=lambda u, v, a, b: (u * a, v * b),  # at p / s: p = q * s
        ),
        support=_MOVED,
    ),
    _field(
        "Rotate",
        "transformed",
        P.transform(P.rotated("degrees", _cycle("Rotate", "degrees"))),
        T.Transform(
            values=T.turn("degrees"),  # (cos, sin)
            coords=lambda x, y, a, b: (a * x + b * y, -b * x + a * y),
            matrix=lambda u, v: (u, v, 0.0, -v, u, 0.0),
            warp=Ref(_FIELDS + "turned"),
            # at (a x + b y, -b x + a y): p = (a u - b v, b u + a v)
            back=lambda u, v, a, b: (a * u - b * v, b * u + a * v),
        ),
        support=_MOVED,
    ),
    # instancing: the operand in 9 neighbouring instance frames (the registry's instances),
    # which repeat with the instances; its own period: the cells
    _field("Tile", "tile", P.own(PR.tile), arrays=6, work=W.tile_work(9)),
    # language 3: a per-sample choice between fields (operands materialised, numpy selection)
    Op(
        "Choose",
        Kind.FIELD,
        Ref(_INSTANCING + "choose"),
        Ref(_INSTANCING + "choose_static"),
        unbounded,
        NUMPY,
        arrays=3,
        work=W.CHOOSE,
    ),
    # geometry (arguments of Fill/Stroke; not fields)
    _geometry("Rect", "rect"),
    _geometry("Ellipse", "ellipse"),
    _geometry("Path", "path"),
    _geometry("LineTo", "line_to", work=W.PATH_EDGE),
    _geometry("CubicTo", "cubic_to", work=W.PATH_EDGE * W.CUBIC_EDGES),
)

#: Every registry function's :class:`Op`, by function name.
OPS: dict[str, Op] = {op.name: op for op in (*_ENTRIES, *MATH_V2_ENTRIES, *QUANTIZE_ENTRIES)}


def operator_ops() -> dict[str, Op]:
    """The ops of the binary operators (``"+"`` -> Add, ...), from the registry."""
    return {spec.operator: OPS[name] for name, spec in FUNCTIONS.items() if spec.operator}
