"""Canonical printer, byte-compatible with the reference serialiser (reference-engine.md §5.1).

``format_program(parse(t))`` is a fixed point, and a canonical reference program prints
byte-identically.
"""

from __future__ import annotations

import math

from matloom.lang import ast as A
from matloom.lang.static import static_number
from matloom.vocab import CONSTANTS, FUNCTIONS, Kind, ParamSpec, PrintStyle
from matloom.vocab.spec import format_default


def fmt_num(v: float | int) -> str:
    """Reference number format: integral values as integers, others by shortest repr."""
    if isinstance(v, bool):
        return "True" if v else "False"
    if isinstance(v, int):
        return str(v)
    if math.isnan(v):
        return "nan"
    if math.isinf(v):
        return "inf" if v > 0 else "-inf"
    if v.is_integer():
        return str(int(v))
    return repr(v)


def format_expr(node: A.Node) -> str:
    """Canonical text of one expression."""
    if isinstance(node, A.Num):
        return fmt_num(node.value)
    if isinstance(node, A.Const):
        return fmt_num(CONSTANTS[node.name])
    if isinstance(node, A.Ref):
        return node.name
    if isinstance(node, A.Lit):
        return "None" if node.value is None else ("True" if node.value else "False")
    if isinstance(node, A.Str):
        return f'"{node.value}"'
    if isinstance(node, A.Neg):
        s = format_expr(node.operand)
        return f"-({s})" if s.startswith("-") else f"-{s}"
    if isinstance(node, A.BinOp):
        left = format_expr(node.left)
        if node.op == "**" and left.startswith("-"):
            left = f"({left})"
        return f"({left} {node.op} {format_expr(node.right)})"
    if isinstance(node, A.Call):
        return _format_call(node)
    raise TypeError(f"not an expression node: {node!r}")


def _static_text(node: A.Node | None, p: ParamSpec) -> str:
    if node is None:
        return "None"
    if isinstance(node, A.Str):
        return f'"{node.value}"'
    if isinstance(node, A.Lit):
        return format_expr(node)
    v = static_number(node)
    if v is None:  # not constant: invalid program, print as written
        return format_expr(node)
    if p.kind is Kind.BOOL:
        return "True" if v else "False"
    if p.kind is Kind.INT and math.isfinite(v):
        return str(int(round(v)))
    return fmt_num(v)


def _arg_text(call: A.Call, p: ParamSpec) -> str:
    node = call.arg(p.name)
    if p.kind in (Kind.EXPR, Kind.SHAPE):
        return format_expr(node) if node is not None else "None"
    if node is None and not p.required:  # positional style prints omitted values as defaults
        return format_default(p.default)
    return _static_text(node, p)


def _value(call: A.Call, name: str) -> object:
    """Effective value of a static parameter (the default when not written)."""
    spec = FUNCTIONS[call.func]
    p = spec.param(name)
    assert p is not None
    node = call.arg(name)
    if node is None:
        return p.default
    if isinstance(node, A.Str):
        return node.value
    if isinstance(node, A.Lit):
        return node.value
    v = static_number(node)
    if p.kind is Kind.BOOL and v is not None:
        return bool(v)
    return v


def _format_call(call: A.Call) -> str:  # noqa: C901 - one branch per print style
    spec = FUNCTIONS.get(call.func)
    if spec is None:
        inner = ", ".join(format_expr(a.value) for a in call.args)
        return f"{call.func}({inner})"
    style = spec.print_style
    name = spec.name
    if style is PrintStyle.CONSTANT:
        node = call.arg("value")
        return _static_text(node, spec.params[0]) if node is not None else "0"
    if style is PrintStyle.WRITTEN_KEYWORDS:
        return f"{name}({', '.join(_written_keywords(call))})"
    if style is PrintStyle.NONDEFAULT_KEYWORDS:
        return f"{name}({', '.join(_nondefault_keywords(call))})"
    if style is PrintStyle.THRESHOLD:
        return _format_threshold(call)
    if style is PrintStyle.SHAPE_OP:
        parts = [_arg_text(call, p) for p in spec.params if p.required]
        if name == "Fill" and _value(call, "mode") not in (None, "NonZero"):
            parts.append(f'mode="{_value(call, "mode")}"')
        feather = _value(call, "feather")
        if feather not in (None, 0):
            parts.append(f"feather={fmt_num(feather)}")  # type: ignore[arg-type]
        return f"{name}({', '.join(parts)})"
    if name == "Log":
        base = _value(call, "base")
        x = format_expr(call.arg("expr")) if call.arg("expr") is not None else ""
        return f"Log({x})" if base == math.e or base is None else f"Log({x}, {fmt_num(base)})"  # type: ignore[arg-type]
    if name == "Rect":
        parts = [_arg_text(call, p) for p in spec.params[:4]]
        r, w, h = _value(call, "radius"), _value(call, "width"), _value(call, "height")
        if isinstance(r, int | float) and isinstance(w, int | float) and isinstance(h, int | float):
            r = min(float(r), min(float(w), float(h)) / 2)
            if r != 0:
                parts.append(fmt_num(r))
        return f"Rect({', '.join(parts)})"
    parts = [_arg_text(call, p) for p in spec.params]
    parts += [format_expr(e) for e in call.extra]
    return f"{name}({', '.join(parts)})"


def _written_keywords(call: A.Call) -> list[str]:
    spec = FUNCTIONS[call.func]
    written = call.written()
    both_axes = "base_freq_x" in written and "base_freq_y" in written
    out = []
    for p in spec.params:
        if p.name not in written:
            continue
        if p.name == "base_freq" and both_axes:
            continue
        out.append(f"{p.name}={_arg_text(call, p)}")
    return out


def _nondefault_keywords(call: A.Call) -> list[str]:
    spec = FUNCTIONS[call.func]
    out = []
    has_freq = spec.param("base_freq") is not None
    for p in spec.params:
        if p.is_frequency:
            if p.name == "base_freq" and has_freq:
                out.extend(_weave_freq(call, p))
            continue
        v = _value(call, p.name)
        if v != p.default:
            out.append(f"{p.name}={_arg_text(call, p)}")
    return out


def _weave_freq(call: A.Call, p: ParamSpec) -> list[str]:
    base = _value(call, "base_freq")
    fx = _value(call, "base_freq_x")
    fy = _value(call, "base_freq_y")
    fx = base if fx is None else fx
    fy = base if fy is None else fy
    if fx == fy:
        return [] if fx == p.default else [f"base_freq={fmt_num(fx)}"]  # type: ignore[arg-type]
    return [f"base_freq_x={fmt_num(fx)}", f"base_freq_y={fmt_num(fy)}"]  # type: ignore[arg-type]


def _format_threshold(call: A.Call) -> str:
    parts = [format_expr(call.arg("expr"))] if call.arg("expr") is not None else []
    for side in ("below", "above"):
        at, to = _value(call, f"{side}_at"), _value(call, f"{side}_to")
        if at is not None:
            parts.append(f"{side}_at={fmt_num(at)}")  # type: ignore[arg-type]
        if to is not None and to != at:
            parts.append(f"{side}_to={fmt_num(to)}")  # type: ignore[arg-type]
    w = _value(call, "transition_width")
    if w not in (None, 0):
        parts.append(f"transition_width={fmt_num(w)}")  # type: ignore[arg-type]
    return f"Threshold({', '.join(parts)})"


def format_layer(layer: A.Layer) -> list[str]:
    alpha = format_expr(layer.alpha) if layer.alpha is not None else ""
    lines = [f"  Layer({alpha})"]
    for ch in layer.channels:
        lines.append(f"    .{ch.name}({', '.join(format_expr(a) for a in ch.args)})")
    return lines


def format_program(program: A.Program) -> str:
    """Canonical program text (no trailing newline), as the reference serialiser writes it."""
    lines: list[str] = []
    if program.view is not None:
        lines.append(f"View({', '.join(fmt_num(v) for v in program.view.as_tuple())})")
    for d in program.defines:
        lines.append(f"Define({d.name}, {format_expr(d.expr)})")
    if not program.layers:
        lines.append("Material()")
        return "\n".join(lines)
    lines.append("Material(")
    for i, layer in enumerate(program.layers):
        block = format_layer(layer)
        if i < len(program.layers) - 1:
            block[-1] += ","
        lines.extend(block)
    lines.append(")")
    return "\n".join(lines)
