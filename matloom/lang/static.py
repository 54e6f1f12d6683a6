"""Static evaluation of scalar arguments (a number, or a constant expression at (0, 0)).

The reference evaluates an expression given where a number is expected once at the origin. We do
the same for constant math (and X()/Y(), which are 0 there, with a warning from the checker);
fields such as noise or Define references in a numeric slot are rejected by the checker.
"""

from __future__ import annotations

import math

from matloom.lang import ast as A
from matloom.vocab import CONSTANTS

_UNARY = {
    "Abs": abs,
    "Sqrt": lambda v: math.sqrt(v) if v >= 0 else math.nan,
    "Floor": math.floor,
    "Ceil": math.ceil,
    "Sin": math.sin,
    "Cos": math.cos,
}


def is_static(node: A.Node) -> bool:
    """True if ``node`` can be evaluated without a sample grid."""
    return _eval(node, strict=True) is not None


def uses_coordinates(node: A.Node) -> bool:
    return any(isinstance(n, A.Call) and n.func in ("X", "Y") for n in A.walk(node))


def static_number(node: A.Node) -> float | int | None:
    """The value of a constant expression (X()/Y() count as 0), or ``None`` if not constant."""
    return _eval(node, strict=False)


def _eval(node: A.Node, strict: bool) -> float | int | None:  # noqa: C901 - a flat dispatch
    try:
        if isinstance(node, A.Num):
            return node.value
        if isinstance(node, A.Const):
            return CONSTANTS[node.name]
        if isinstance(node, A.Neg):
            v = _eval(node.operand, strict)
            return None if v is None else -v
        if isinstance(node, A.BinOp):
            a, b = _eval(node.left, strict), _eval(node.right, strict)
            if a is None or b is None:
                return None
            return _binop(node.op, float(a) if isinstance(a, float) else a, b)
        if isinstance(node, A.Call):
            return _call(node, strict)
    except (OverflowError, ValueError, ZeroDivisionError):
        return math.nan
    return None


def _binop(op: str, a: float | int, b: float | int) -> float | int:
    if op == "+":
        return a + b
    if op == "-":
        return a - b
    if op == "*":
        return a * b
    if op == "/":
        return 0.0 if b == 0 else a / b
    if a < 0 and not float(b).is_integer():
        return math.nan
    if a == 0 and b < 0:
        return math.inf
    return float(a) ** float(b)


def _call(node: A.Call, strict: bool) -> float | int | None:
    f = node.func
    if f in ("X", "Y"):
        return None if strict else 0.0
    vals = [_eval(a.value, strict) for a in node.args]
    if any(v is None for v in vals):
        return None
    if f == "Constant":
        return vals[0] if vals else 0.0
    if f in _UNARY and len(vals) == 1:
        return float(_UNARY[f](vals[0]))
    if f == "Log":
        x = float(vals[0])
        base = float(vals[1]) if len(vals) > 1 else math.e
        if x == 0:
            return -math.inf
        if x < 0:
            return math.nan
        if base == 10:
            return math.log10(x)
        if base == 2:
            return math.log2(x)
        return math.log(x) if base == math.e else math.log(x) / math.log(base)
    if f in ("Min", "Max") and len(vals) == 2:
        return min(vals) if f == "Min" else max(vals)  # type: ignore[type-var]
    return None
