"""Static evaluation of scalar arguments (a number, or a constant expression at (0, 0)).

The reference evaluates an expression given where a number is expected once at the origin. We do
the same for constant math (and X()/Y(), which are 0 there, with a warning from the checker);
fields such as noise in a numeric slot are rejected by the checker. A Define of a constant there
is its value: :mod:`matloom.lang.constants` writes it out before these functions see it.
"""

from __future__ import annotations

import math
from typing import Any

from matloom.lang import ast as A
from matloom.ops import OPS, Repeats, operator_ops
from matloom.vocab import CONSTANTS, FUNCTIONS

#: The binary operators' ops ("+" -> Add, ...); each op's static rule is its folding rule.
_OPERATORS = operator_ops()
#: The coordinates X(), Y(): the ops whose period rule is an axis.
COORDINATES = frozenset(name for name, op in OPS.items() if op.period.repeats is Repeats.AXIS)


def is_static(node: A.Node) -> bool:
    """True if ``node`` can be evaluated without a sample grid."""
    return _eval(node, strict=True) is not None


def uses_coordinates(node: A.Node) -> bool:
    return any(isinstance(n, A.Call) and n.func in COORDINATES for n in A.walk(node))


def static_number(node: A.Node) -> float | int | None:
    """The value of a constant expression (X()/Y() count as 0), or ``None`` if not constant."""
    return _eval(node, strict=False)


def param_value(call: A.Call, name: str) -> Any:
    """Value of a numeric/enum/bool parameter of ``call`` as the evaluator uses it: its default
    when not written, a rounded int for integer parameters, else a float (or the literal).
    Raises ValueError when the parameter is not a constant."""
    node = call.arg(name)
    p = FUNCTIONS[call.func].param(name)
    assert p is not None
    if node is None:
        return p.default
    if isinstance(node, A.Str | A.Lit):
        return node.value
    v = static_number(node)
    if v is None:
        raise ValueError(f"{call.func}: {name} is not a constant")
    return int(round(v)) if p.kind.value == "int" else float(v)


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
    return _OPERATORS[op].static([a, b], False)  # type: ignore[no-any-return]


def _call(node: A.Call, strict: bool) -> float | int | None:
    """The call's static rule (:mod:`matloom.ops`) over its arguments' values."""
    op = OPS.get(node.func)
    if op is None:
        return None
    vals = [_eval(a.value, strict) for a in node.args]
    vals += [_eval(e, strict) for e in node.extra if FUNCTIONS[node.func].nary]
    if any(v is None for v in vals):
        return None
    return op.static(vals, strict)  # type: ignore[no-any-return]
