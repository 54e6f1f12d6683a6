"""Canonical printer, byte-compatible with the reference serialiser (reference-engine.md §5.1).

``format_program(parse(t))`` is a fixed point, and a canonical reference program prints
byte-identically.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from matloom.lang import ast as A
from matloom.lang.lexer import as_float
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
    if p.field and _static_number(node) is None:  # a field expression
        return format_expr(node)
    v = _static_number(node)
    if p.field and v is not None and not math.isfinite(v):  # e.g. Sqrt(-1): keep it parseable
        return format_expr(node)
    if v is None:  # not constant: invalid program, print as written
        return format_expr(node)
    if p.kind is Kind.BOOL:
        return "True" if v else "False"
    if p.kind is Kind.INT and math.isfinite(v):
        return str(int(round(v)))
    return fmt_num(v)


def _static_number(node: A.Node) -> float | int | None:
    """:func:`static_number`, with exact integers beyond the float range as +-inf (never an
    integer too long to print, even for a program that was not checked)."""
    v = static_number(node)
    if isinstance(v, int) and not math.isfinite(as_float(v)):
        return as_float(v)
    return v


def _arg_text(call: A.Call, p: ParamSpec) -> str:
    node = call.arg(p.name)
    if p.kind in (Kind.EXPR, Kind.SHAPE):
        return format_expr(node) if node is not None else "None"
    if node is None and not p.required:  # positional style prints omitted values as defaults
        return format_default(p.default)
    return _static_text(node, p)


@dataclass(frozen=True)
class _Named:
    """A static value written with Define names (``mortar=grout``): printed as written."""

    text: str


def _num_text(v: object) -> str:
    """A static value as printed: a number, or the expression that names Defines."""
    return v.text if isinstance(v, _Named) else fmt_num(v)  # type: ignore[arg-type]


def _value(call: A.Call, name: str) -> object:
    """Effective value of a static parameter (the default when not written; a :class:`_Named`
    when it names Defines, whose values the printer does not know)."""
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
    v = _static_number(node)
    if v is None and any(isinstance(n, A.Ref) for n in A.walk(node)):
        return _Named(format_expr(node))
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
            parts.append(f"feather={_num_text(feather)}")
        return f"{name}({', '.join(parts)})"
    if name == "Log":
        base = _value(call, "base")
        x = format_expr(call.arg("expr")) if call.arg("expr") is not None else ""
        return f"Log({x})" if base == math.e or base is None else f"Log({x}, {_num_text(base)})"
    if name == "Rect":
        parts = [_arg_text(call, p) for p in spec.params[:4]]
        r, w, h = _value(call, "radius"), _value(call, "width"), _value(call, "height")
        if isinstance(r, int | float) and isinstance(w, int | float) and isinstance(h, int | float):
            r = min(float(r), min(float(w), float(h)) / 2)
            if r != 0:
                parts.append(fmt_num(r))
        elif any(isinstance(v, _Named) for v in (r, w, h)) and r not in (0, None):
            parts.append(_num_text(r))  # named sizes: the radius as written
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
        if p.since > 1 and _value(call, p.name) == p.default:
            continue  # the reference's serialiser has no newer keywords: they print when set
        out.append(f"{p.name}={_arg_text(call, p)}")
    return out


def _nondefault_keywords(call: A.Call) -> list[str]:
    spec = FUNCTIONS[call.func]
    out = []
    has_freq = spec.param("base_freq") is not None
    for p in spec.params:
        if p.required:  # positionally, first (Tile's motif and cell size)
            out.append(_arg_text(call, p))
            continue
        if p.is_frequency:
            if p.name == "base_freq" and has_freq:
                out.extend(_weave_freq(call, p))
            continue
        v = _value(call, p.name)
        if v != p.default and not _unused(call, p):
            out.append(f"{p.name}={_arg_text(call, p)}")
    return out


def _unused(call: A.Call, p: ParamSpec) -> bool:
    """A parameter used only for some values of another (``used_when``) that has none of them
    (e.g. Bricks' seed without output="cell_value"): it has no effect and is not printed."""
    return p.used_when is not None and _value(call, p.used_when[0]) not in p.used_when[1]


def _weave_freq(call: A.Call, p: ParamSpec) -> list[str]:
    base = _value(call, "base_freq")
    fx = _value(call, "base_freq_x")
    fy = _value(call, "base_freq_y")
    fx = base if fx is None else fx
    fy = base if fy is None else fy
    if fx == fy:
        return [] if fx == p.default else [f"base_freq={_num_text(fx)}"]
    return [f"base_freq_x={_num_text(fx)}", f"base_freq_y={_num_text(fy)}"]


def _format_threshold(call: A.Call) -> str:
    parts = [format_expr(call.arg("expr"))] if call.arg("expr") is not None else []
    for side in ("below", "above"):
        at, to = _value(call, f"{side}_at"), _value(call, f"{side}_to")
        if at is None:
            continue  # without its cut-off a side's target has no effect (the reference drops it)
        parts.append(f"{side}_at={_num_text(at)}")
        if to is not None and to != at:
            parts.append(f"{side}_to={_num_text(to)}")
    w = _value(call, "transition_width")
    if w not in (None, 0):
        parts.append(f"transition_width={_num_text(w)}")
    return f"Threshold({', '.join(parts)})"


class _Lines:
    """Program text under construction. Comments are written only when ``comments`` is set."""

    def __init__(self, comments: bool) -> None:
        self.comments = comments
        self.lines: list[str] = []
        self.tails: list[str] = []  # trailing comment of each line ("" for none)
        self.last_code = -1

    def own(self, indent: str, node: A.Commented, slot: str = "leading") -> None:
        """``node``'s comments in ``slot``, each on its own line at ``indent``."""
        for text in _texts(node, slot) if self.comments else ():
            self.lines.append(indent + text)
            self.tails.append("")

    def code(self, indent: str, text: str, node: A.Commented | None = None) -> None:
        """A line of code, preceded by ``node``'s leading comments and ending in its trailing."""
        if node is not None:
            self.own(indent, node)
        self.lines.append(indent + text)
        tails = _texts(node, "trailing") if node is not None and self.comments else []
        self.tails.append("  ".join(tails))
        self.last_code = len(self.lines) - 1

    def trail(self, node: A.Commented, slot: str) -> None:
        """Append ``node``'s ``slot`` comments to the last line of code."""
        texts = _texts(node, slot) if self.comments else []
        k = self.last_code
        self.tails[k] = "  ".join(t for t in (self.tails[k], *texts) if t)

    def comma(self) -> None:
        self.lines[self.last_code] += ","

    def text(self) -> str:
        return "\n".join(
            f"{line}  {tail}" if tail else line for line, tail in zip(self.lines, self.tails)
        )


def _texts(node: A.Commented, slot: str) -> list[str]:
    return [c.text for c in node.comments if c.slot == slot]


def _layer(out: _Lines, layer: A.Layer) -> None:
    alpha = format_expr(layer.alpha) if layer.alpha is not None else ""
    out.code("  ", f"Layer({alpha})", layer)
    for ch in layer.channels:
        out.code("    ", f".{ch.name}({', '.join(format_expr(a) for a in ch.args)})", ch)


def format_layer(layer: A.Layer, *, comments: bool = False) -> list[str]:
    """Lines of one layer as it prints inside ``Material(...)``."""
    out = _Lines(comments)
    _layer(out, layer)
    return out.text().split("\n")


def format_program(program: A.Program, *, comments: bool = False) -> str:
    """Canonical program text (no trailing newline), as the reference serialiser writes it.

    With ``comments=True`` the program's ``#`` comments are printed too (``matloom fmt``):
    leading ones on their own lines at the construct's indentation, trailing ones after it with
    two spaces before ``#``. A program without comments prints the same either way. The default
    stays comment-free, because the reference parser rejects ``#``.
    """
    out = _Lines(comments)
    if program.view is not None:
        corners = ", ".join(fmt_num(v) for v in program.view.as_tuple())
        tiled = ", tileable=True" if program.view.tileable else ""
        if program.view.unit_m is not None:
            tiled += f", unit_m={fmt_num(program.view.unit_m)}"
        out.code("", f"View({corners}{tiled})", program.view)
    for d in program.defines:
        head = f"{d.name}({', '.join(d.params)})" if d.params else d.name
        out.code("", f"Define({head}, {format_expr(d.expr)})", d)
    if not program.layers:
        out.own("", program)
        out.own("", program, "footer")
        out.code("", "Material()")
        out.trail(program, "open")
        out.trail(program, "close")
    else:
        out.code("", "Material(", program)
        out.trail(program, "open")
        for i, layer in enumerate(program.layers):
            _layer(out, layer)
            if i < len(program.layers) - 1:
                out.comma()
        out.own("  ", program, "footer")
        out.code("", ")")
        out.trail(program, "close")
    out.own("", program, "end")
    return out.text()
