"""How expressions depend on the coordinates, for tileable output.

:func:`coord_coeffs` writes an expression as ``a X() + b Y() + (terms that repeat with the
View)`` and returns (a, b), or None when X()/Y() enter it otherwise (a product of coordinates,
a square root of X(), ...). Terms that repeat with the View are those without coordinates
(noise, patterns, constants: the engine makes them periodic) and periodic wrappers of
coordinates with a whole number of cycles per View period.

Each function's part is its op's period rule (``Op.period``, :mod:`matloom.ops.period`): a
coordinate (X(), Y()) gives its axis; a periodic wrapper (``Fract``, ``Mod`` by a constant,
``Sin``/``Cos``, ``Hash``) repeats over the cycles of its arguments (``ParamSpec.cycle``); a
step (``Floor``/``Ceil``) passes the coefficients through when its argument advances by a whole
number per period (else the steps do not repeat); a transform or an instancing (Tile) evaluates
its operands in frames of their own. No function is named here.

The engine's Hash wraps its cells modulo ``a * Px`` (``b * Py``) when that is a whole number
(``matloom.engine.rules.fields_math``); the checker warns about the rest
(:mod:`matloom.lang.tileable`).
"""

from __future__ import annotations

from collections.abc import Mapping

from matloom.lang import ast as A
from matloom.lang.static import is_static, static_number
from matloom.ops import OPS, Period, Repeats
from matloom.ops.period import KEEP, Coeffs, whole
from matloom.vocab import FUNCTIONS

__all__ = ["WRAPPERS", "coord_coeffs", "period_of", "periodic_wrap", "wrapper_cycles"]

#: Periodic wrappers (ops whose period rule is WRAP): function -> ((argument, cycle), ...), the
#: arguments with a ``ParamSpec.cycle``: a length, or the parameter holding it (Mod's ``m``).
WRAPPERS: dict[str, tuple[tuple[str, float | str], ...]] = {
    name: tuple((p.name, p.cycle) for p in FUNCTIONS[name].params if p.cycle is not None)
    for name, op in OPS.items()
    if op.period.repeats is Repeats.WRAP
}


def period_of(func: str) -> Period:
    """The period rule of ``func`` (``Op.period``; an unknown function keeps the periods)."""
    op = OPS.get(func)
    return KEEP if op is None else op.period


def own_frames(func: str) -> bool:
    """``func`` evaluates its operands in frames of their own: a transform (its operand's frame
    is its period rule's) or an instancing (Tile: the instances' frames, which repeat with the
    instances; ``FunctionSpec.instances``)."""
    spec = FUNCTIONS.get(func)
    return period_of(func).repeats is Repeats.FRAME or (spec is not None and spec.instances > 0)


def wrapper_cycles(
    call: A.Call, defines: Mapping[str, A.Node], periods: tuple[float, float]
) -> list[tuple[str, Coeffs | None, float]]:
    """(argument, its coefficients, cycle length) of each wrapped argument of a periodic
    wrapper; a cycle held by a parameter (Mod's ``m``) is its constant value (0 when it is not
    a constant)."""
    out = []
    for name, cycle in WRAPPERS[call.func]:
        if isinstance(cycle, str):
            node = call.arg(cycle)
            value = static_number(node) if node is not None and is_static(node) else None
            cycle = abs(float(value)) if value else 0.0
        out.append((name, coord_coeffs(call.arg(name), defines, periods), cycle))
    return out


def periodic_wrap(
    call: A.Call, defines: Mapping[str, A.Node], periods: tuple[float, float]
) -> bool:
    """The wrapper repeats with the View: every wrapped argument has a whole number of
    cycles per period (a coordinate-free argument always does), and a parameter holding a
    cycle (Mod's ``m``) is free of coordinates."""
    for _, cycle in WRAPPERS[call.func]:
        if isinstance(cycle, str) and not _coordinate_free(call.arg(cycle), defines, periods):
            return False
    for _, coeffs, cycle in wrapper_cycles(call, defines, periods):
        if coeffs is None:
            return False
        if coeffs == (0.0, 0.0):
            continue
        if cycle <= 0:
            return False
        for k, p in zip(coeffs, periods, strict=True):
            if whole(k * p / cycle) is None:
                return False
    return True


def _coordinate_free(
    node: A.Node | None, defines: Mapping[str, A.Node], periods: tuple[float, float]
) -> bool:
    return coord_coeffs(node, defines, periods) == (0.0, 0.0)


def coord_coeffs(
    node: A.Node | None,
    defines: Mapping[str, A.Node],
    periods: tuple[float, float],
    depth: int = 0,
    memo: dict[int, Coeffs | None] | None = None,
) -> Coeffs | None:
    """(a, b) of ``node`` (see the module docstring); ``periods`` are the View's in the
    coordinates ``node`` is evaluated in (``memo``: results by node id, for repeated calls
    on one program with the same periods)."""
    if node is None or depth > 64 or is_static(node):
        return (0.0, 0.0)
    if memo is not None:
        key = id(node)
        if key not in memo:
            memo[key] = _coeffs(node, defines, periods, depth, memo)
        return memo[key]
    return _coeffs(node, defines, periods, depth, None)


def _coeffs(
    node: A.Node,
    defines: Mapping[str, A.Node],
    periods: tuple[float, float],
    depth: int,
    memo: dict[int, Coeffs | None] | None,
) -> Coeffs | None:
    if isinstance(node, A.Ref):
        return coord_coeffs(defines.get(node.name), defines, periods, depth + 1, memo)
    if isinstance(node, A.Neg):
        c = coord_coeffs(node.operand, defines, periods, depth + 1, memo)
        return None if c is None else (-c[0], -c[1])
    if isinstance(node, A.BinOp):
        return _binop(node, defines, periods, depth, memo)
    if isinstance(node, A.Num | A.Str | A.Lit | A.Const):  # literals never vary with X/Y
        return (0.0, 0.0)
    if not isinstance(node, A.Call):
        return None
    period = period_of(node.func)
    if period.repeats is Repeats.AXIS:
        assert period.axis is not None
        return period.axis
    if period.repeats is Repeats.STEP:  # repeats when its argument steps by whole numbers
        inner = coord_coeffs(node.arg("expr"), defines, periods, depth + 1, memo)
        if inner is None or any(whole(k * p) is None for k, p in zip(inner, periods)):
            return None
        return inner
    if period.repeats is Repeats.WRAP:
        return (0.0, 0.0) if periodic_wrap(node, defines, periods) else None
    if own_frames(node.func):
        return (0.0, 0.0)  # their operands are checked in their own frames
    for value in A.children(node):  # operands, and Min(a, b, c, ...)'s extra ones
        if coord_coeffs(value, defines, periods, depth + 1, memo) != (0.0, 0.0):
            return None
    return (0.0, 0.0)


def _binop(
    node: A.BinOp,
    defines: Mapping[str, A.Node],
    periods: tuple[float, float],
    depth: int,
    memo: dict[int, Coeffs | None] | None,
) -> Coeffs | None:
    left = coord_coeffs(node.left, defines, periods, depth + 1, memo)
    right = coord_coeffs(node.right, defines, periods, depth + 1, memo)
    if left is None or right is None:
        return None
    if node.op in ("+", "-"):
        sign = 1.0 if node.op == "+" else -1.0
        return (left[0] + sign * right[0], left[1] + sign * right[1])
    if left == right == (0.0, 0.0):
        return (0.0, 0.0)
    if node.op == "*":
        for const, other in ((node.left, right), (node.right, left)):
            if is_static(const):
                k = float(static_number(const) or 0.0)
                return (k * other[0], k * other[1])
    if node.op == "/" and is_static(node.right):
        k = float(static_number(node.right) or 0.0)
        return None if k == 0 else (left[0] / k, left[1] / k)
    return None
