"""How expressions depend on the coordinates, for tileable output.

:func:`coord_coeffs` writes an expression as ``a X() + b Y() + (terms that repeat with the
View)`` and returns (a, b), or None when X()/Y() enter it otherwise (a product of coordinates,
a square root of X(), ...). Terms that repeat with the View are those without coordinates
(noise, patterns, constants: the engine makes them periodic) and periodic wrappers of
coordinates with a whole number of cycles per View period (``Fract``, ``Mod`` by a constant,
``Sin``/``Cos`` and ``Hash``); ``Floor``/``Ceil`` pass the coefficients through when their
argument advances by a whole number per period (else the floor does not repeat).

The engine's Hash wraps its cells modulo ``a * Px`` (``b * Py``) when that is a whole number
(``matloom.engine.ops.fields_math``); the checker warns about the rest
(:mod:`matloom.lang.tileable`).
"""

from __future__ import annotations

import math
from collections.abc import Mapping

from matloom.lang import ast as A
from matloom.lang.static import is_static, static_number

__all__ = ["Coeffs", "coord_coeffs", "whole", "WRAPPERS"]

#: (a, b): the expression is a X() + b Y() + terms that repeat with the View.
Coeffs = tuple[float, float]
#: Periodic wrappers: function -> ((argument, cycle length), ...); Mod's cycle is its ``m``.
WRAPPERS: dict[str, tuple[tuple[str, float], ...]] = {
    "Fract": (("x", 1.0),),
    "Sin": (("expr", 2 * math.pi),),
    "Cos": (("expr", 2 * math.pi),),
    "Hash": (("x", 1.0), ("y", 1.0)),
    "Mod": (("x", 0.0),),
}
_TRANSFORMS = ("Translate", "Scale", "Rotate", "Tile")
#: How far (in cycles or cells per period) from a whole number still counts as whole: a
#: thousandth of a cycle is a phase error no one sees (programs print pi as 3.1416).
WHOLE_TOLERANCE = 1e-3


def whole(value: float) -> int | None:
    """``value`` as a whole number when it is one (within :data:`WHOLE_TOLERANCE`)."""
    if not math.isfinite(value):
        return None
    n = round(value)
    return int(n) if abs(value - n) <= WHOLE_TOLERANCE else None


def wrapper_cycles(
    call: A.Call, defines: Mapping[str, A.Node], periods: tuple[float, float]
) -> list[tuple[str, Coeffs | None, float]]:
    """(argument, its coefficients, cycle length) of each wrapped argument of a periodic
    wrapper; Mod's cycle is its constant ``m`` (0 when m is not a constant)."""
    out = []
    for name, cycle in WRAPPERS[call.func]:
        if call.func == "Mod":
            m = call.arg("m")
            value = static_number(m) if m is not None and is_static(m) else None
            cycle = abs(float(value)) if value else 0.0
        out.append((name, coord_coeffs(call.arg(name), defines, periods), cycle))
    return out


def periodic_wrap(
    call: A.Call, defines: Mapping[str, A.Node], periods: tuple[float, float]
) -> bool:
    """The wrapper repeats with the View: every wrapped argument has a whole number of
    cycles per period (a coordinate-free argument always does)."""
    if call.func == "Mod" and not _coordinate_free(call.arg("m"), defines, periods):
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
    func = node.func
    if func == "X":
        return (1.0, 0.0)
    if func == "Y":
        return (0.0, 1.0)
    if func in ("Floor", "Ceil"):  # repeats when its argument steps by whole numbers
        inner = coord_coeffs(node.arg("expr"), defines, periods, depth + 1, memo)
        if inner is None or any(whole(k * p) is None for k, p in zip(inner, periods)):
            return None
        return inner
    if func in WRAPPERS:
        return (0.0, 0.0) if periodic_wrap(node, defines, periods) else None
    if func in _TRANSFORMS:
        return (0.0, 0.0)  # their operands are checked in their own frames
    for arg in node.args:
        if coord_coeffs(arg.value, defines, periods, depth + 1, memo) != (0.0, 0.0):
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
