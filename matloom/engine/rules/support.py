"""Support rules: where a field can be non-zero (referenced by the op table's ``support``).

The support of a field is a box (x0, y0, x1, y1) in its coordinates outside which its value is
exactly 0 at every point; ``None`` means "anywhere" (unknown). Only ops whose zeros are exact
have a rule: coverage of shapes (0 past the edge's reach), sums, differences, minima and maxima
of two supported fields (0 where both are), products with a supported factor and a finite
constant or another supported factor, and constant transforms of a supported field. Tile uses it
to evaluate its motif only where an instance can show (:func:`matloom.engine.rules.fields.tile`).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any

from matloom.engine.kernels import shapes
from matloom.lang import ast as A

Box = tuple[float, float, float, float]


class Context:
    """What a rule may ask: the support and the constant value of an operand, and the
    interpreter (for shapes and static parameters)."""

    def __init__(self, ev: Any, box: Callable[[A.Node], Box | None]) -> None:
        self.ev = ev
        self.box = box

    def constant(self, node: A.Node) -> float | None:
        """The operand's value if it is a finite constant."""
        from matloom.lang.static import is_static, static_number

        if not is_static(node):
            return None
        value = static_number(node)
        return float(value) if value is not None and math.isfinite(value) else None


def _grow(box: Box, margin: float) -> Box:
    """``box`` grown by ``margin`` plus a relative safety margin for float rounding."""
    x0, y0, x1, y1 = box
    reach = max(abs(x0), abs(y0), abs(x1), abs(y1), 1.0)
    pad = margin * (1.0 + 1e-6) + 1e-9 * reach
    return (x0 - pad, y0 - pad, x1 + pad, y1 + pad)


def _shape_box(geom: shapes.Shape) -> Box:
    if isinstance(geom, shapes.RectGeom):
        xs = (geom.x, geom.x + geom.width)
        ys = (geom.y, geom.y + geom.height)
    elif isinstance(geom, shapes.EllipseGeom):
        xs = (geom.cx - abs(geom.rx), geom.cx + abs(geom.rx))
        ys = (geom.cy - abs(geom.ry), geom.cy + abs(geom.ry))
    else:  # a path lies in the hull of its points and control points
        pts = [(geom.start_x, geom.start_y)]
        for seg in geom.segments:
            if isinstance(seg, shapes.CubicSeg):
                pts += [(seg.c1x, seg.c1y), (seg.c2x, seg.c2y)]
            pts.append((seg.x, seg.y))
        xs = tuple(p[0] for p in pts)
        ys = tuple(p[1] for p in pts)
    return (min(xs), min(ys), max(xs), max(ys))


def _finite(box: Box | None) -> Box | None:
    return box if box is not None and all(math.isfinite(v) for v in box) else None


def fill(ctx: Context, call: A.Call, operands: list[A.Node]) -> Box | None:
    geom = ctx.ev.shape(call.arg("shape"))
    return _finite(_grow(_shape_box(geom), float(ctx.ev.num(call, "feather")) / 2))


def stroke(ctx: Context, call: A.Call, operands: list[A.Node]) -> Box | None:
    geom = ctx.ev.shape(call.arg("shape"))
    reach = float(ctx.ev.num(call, "width")) / 2 + float(ctx.ev.num(call, "feather")) / 2
    return _finite(_grow(_shape_box(geom), abs(reach)))


def union(ctx: Context, call: A.Node, operands: list[A.Node]) -> Box | None:
    """Add, Sub, Min, Max: 0 where every operand is (Min(a, b, c, ...) has more than two)."""
    boxes = [ctx.box(n) for n in operands]
    if any(b is None for b in boxes):
        return None
    return (
        min(b[0] for b in boxes),  # type: ignore[index]
        min(b[1] for b in boxes),  # type: ignore[index]
        max(b[2] for b in boxes),  # type: ignore[index]
        max(b[3] for b in boxes),  # type: ignore[index]
    )


def product(ctx: Context, call: A.Node, operands: list[A.Node]) -> Box | None:
    """Mul: 0 where a supported factor is 0 and the other is finite."""
    a, b = (ctx.box(n) for n in operands)
    if a is not None and b is not None:
        return (max(a[0], b[0]), max(a[1], b[1]), min(a[2], b[2]), min(a[3], b[3]))
    if a is not None and ctx.constant(operands[1]) is not None:
        return a
    if b is not None and ctx.constant(operands[0]) is not None:
        return b
    return None


def quotient(ctx: Context, call: A.Node, operands: list[A.Node]) -> Box | None:
    """Div: a supported dividend over a constant (0 / c is 0; division by 0 gives 0)."""
    a = ctx.box(operands[0])
    return a if a is not None and ctx.constant(operands[1]) is not None else None


def transformed(ctx: Context, call: A.Call, operands: list[A.Node]) -> Box | None:
    """A constant transform: the operand's box mapped back to this frame (the transform's
    ``back`` rule, :mod:`matloom.ops.transform`)."""
    from matloom.lang.cost import field_params, transform_values
    from matloom.ops import OPS

    inner = ctx.box(call.arg("expr"))  # type: ignore[arg-type]
    rule = OPS[call.func].transform
    if inner is None or rule is None or field_params(call):
        return None
    a, b = transform_values(call)
    x0, y0, x1, y1 = inner
    corners = [(x0, y0), (x0, y1), (x1, y0), (x1, y1)]
    mapped = [rule.back(u, v, a, b) for u, v in corners]
    xs = [p[0] for p in mapped]
    ys = [p[1] for p in mapped]
    return _finite(_grow((min(xs), min(ys), max(xs), max(ys)), 0.0))


def support(ev: Any, node: A.Node, rules: dict[str, Any], operators: dict[str, Any]) -> Box | None:
    """The support of ``node`` (Defines followed; memoised per node)."""
    memo: dict[int, Box | None] = {}
    defines = ev.defines

    def box(n: A.Node) -> Box | None:
        key = id(n)
        if key not in memo:
            memo[key] = None  # a cycle (there is none in checked programs) stays unknown
            memo[key] = _box(n)
        return memo[key]

    ctx = Context(ev, box)

    def _box(n: A.Node) -> Box | None:
        if isinstance(n, A.Ref):
            return box(defines[n.name]) if n.name in defines else None
        if isinstance(n, A.Neg):
            return box(n.operand)
        if isinstance(n, A.BinOp):
            rule = operators[n.op].support
            return rule(ctx, n, [n.left, n.right]) if rule is not None else None
        if isinstance(n, A.Call):
            op = rules.get(n.func)
            if op is None or op.support is None:
                return None
            operands = [n.arg(name) for name in _operand_names(n.func)]
            if n.extra and op.kind.value == "elementwise":  # Min(a, b, c, ...)
                operands += list(n.extra)
            if any(o is None for o in operands):
                return None
            return op.support(ctx, n, operands)
        return None

    return box(node)


def _operand_names(func: str) -> tuple[str, ...]:
    from matloom.vocab import FUNCTIONS, Kind

    return tuple(p.name for p in FUNCTIONS[func].params if p.kind is Kind.EXPR)
