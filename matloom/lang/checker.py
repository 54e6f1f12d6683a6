"""Semantic checks: argument kinds, ranges, enums, shapes/segments placement, limits, warnings."""

from __future__ import annotations

import math
import sys

from matloom.lang import ast as A
from matloom.lang.codes import Code
from matloom.lang.constants import Constants, constant_defines, resolve_static, substitute
from matloom.lang.cost import MAX_EXPANDED_NODES, expanded_cost, over_limit
from matloom.lang.diagnostics import Diagnostic, Reporter, Span, hint_for
from matloom.lang.lexer import as_float
from matloom.lang.parse_expr import MAX_NESTING
from matloom.lang.seeds import uses_seed
from matloom.lang.static import static_number, uses_coordinates
from matloom.vocab import FUNCTIONS, Kind, ParamSpec, Returns

MAX_NODES = 20_000
"""Maximum number of expression nodes in one program (documented limit)."""

MAX_OCTAVES = 16
"""Maximum fBm octaves (documented limit; cost grows linearly with octaves)."""


_MAX_COORD = 3.4028234663852886e38
"""Largest float32: the sample grid is float32 (as in the reference), so a View corner, width
or height beyond it gives infinite coordinates or texel sizes."""

_MIN_SPAN = sys.float_info.min * 8192
"""Smallest View width/height: texel sizes stay normal floats (never 0) up to 8192 pixels."""


class Checker(Reporter):
    def __init__(self, source: str) -> None:
        self.src = source
        self.diags: list[Diagnostic] = []
        self.nodes = 0
        self.consts: Constants = {}  # the program's constant Defines (named static values)

    # ---------------------------------------------------------------- program level
    def check(self, program: A.Program) -> list[Diagnostic]:
        self._check_view(program)
        self.consts = constant_defines(program)
        for d in program.defines:
            self.field(d.expr, f"Define '{d.name}'", in_define=True)
        for i, layer in enumerate(program.layers):
            if layer.alpha is not None:
                self.field(layer.alpha, f"layer {i} alpha")
            for ch in layer.channels:
                for a in ch.args:
                    self.field(a, f"layer {i} .{ch.name}()")
        if self.nodes > MAX_NODES:
            self.diag(
                Code.SIZE_LIMIT,
                f"program has {self.nodes} expression nodes, more than the limit of {MAX_NODES}",
                program.span,
                expected=f"at most {MAX_NODES} nodes",
            )
        self._check_inlined_depth(program)
        self._check_expanded_cost(program)
        self._warn_unused(program)
        self._warn_hidden(program)
        # the tileable analysis reads parameters as the evaluator does: only valid ones
        if program.tileable and not any(d.is_error for d in self.diags):
            from matloom.lang.tileable import tileable_warnings

            resolved = resolve_static(program, self.consts)
            self.diags.extend(tileable_warnings(resolved, self.src))
        return self.diags

    def _check_inlined_depth(self, program: A.Program) -> None:
        """Limit the depth of expressions with their Defines substituted (one error at most).

        A long chain of Defines (``Define(d2, d1 + 1)``, ...) is shallow as written but deep when
        evaluated or inlined; the limit keeps evaluation and ``fmt --inline`` free of deep
        recursion, and the inlined text parseable.
        """
        depth_of: dict[str, int] = {}
        for owner, expr in A.program_expressions(program):
            depth = inlined_depth(expr, depth_of)
            if owner[0] == "define":
                depth_of[owner[1]] = depth
            if depth > MAX_NESTING:
                what = f"Define '{owner[1]}'" if owner[0] == "define" else f"layer {owner[1]}"
                self.diag(
                    Code.SIZE_LIMIT,
                    f"{what} is {depth} levels deep with its Defines substituted, "
                    f"more than the limit of {MAX_NESTING}",
                    _span_of(expr, program.span),
                    expected="a shallower chain of Defines",
                    hint="combine Defines instead of chaining each on the previous one",
                )
                return

    def _check_expanded_cost(self, program: A.Program) -> None:
        """E071: the expression nodes an evaluation visits, each Define once per distinct
        coordinate frame it is used in and each call weighted by its op's work (the loops its
        parameters set, :mod:`matloom.lang.cost`), whatever the image size.
        Checked only when nothing else is wrong (the count then stops at the limit)."""
        if any(d.is_error for d in self.diags):
            return
        # named static values (Bricks(mortar=grout)) as the engine reads them
        program = resolve_static(program, self.consts)
        cost = expanded_cost(program, MAX_EXPANDED_NODES)
        if cost.over:
            message, hint, call = over_limit(program, cost, MAX_EXPANDED_NODES)
            span = program.span if call is None else _span_of(call, program.span)
            self.diag(
                Code.WORK_LIMIT,
                message,
                span,
                expected=f"at most {MAX_EXPANDED_NODES:,} node evaluations",
                hint=hint,
            )

    def _check_view(self, program: A.Program) -> None:
        v = program.view
        if v is None:
            return
        vals = v.as_tuple()
        if not all(math.isfinite(x) for x in vals):
            self.diag(
                Code.BAD_VIEW,
                "View corners must be finite numbers",
                v.span,
                expected="View(x1, y1, x2, y2) with finite values",
            )
        elif v.x1 == v.x2 or v.y1 == v.y2:
            self.diag(
                Code.BAD_VIEW,
                "View has zero width or height",
                v.span,
                expected="x1 != x2 and y1 != y2",
            )
        elif max(*map(abs, vals), abs(v.x2 - v.x1), abs(v.y2 - v.y1)) > _MAX_COORD:
            self.diag(
                Code.BAD_VIEW,
                "View is too large: its sample coordinates or texel size would be infinite",
                v.span,
                expected=f"corners, width and height within +-{_MAX_COORD:.3g}",
                hint="the sample grid is float32; use a smaller window",
            )
        elif min(abs(v.x2 - v.x1), abs(v.y2 - v.y1)) < _MIN_SPAN:
            self.diag(
                Code.BAD_VIEW,
                "View is too small: its texel size would be zero or denormal",
                v.span,
                expected=f"a width and height of at least {_MIN_SPAN:.3g}",
            )
        elif v.x1 > v.x2 or v.y1 > v.y2:
            self.diag(
                Code.REVERSED_VIEW,
                "View is reversed (x1 > x2 or y1 > y2), so the image is mirrored",
                v.span,
                hint="(x1, y1) is the bottom-left corner, (x2, y2) the top-right",
            )

    def _warn_unused(self, program: A.Program) -> None:
        used: set[str] = set()
        roots = [e for owner, e in A.program_expressions(program) if owner[0] == "layer"]
        by_name = {d.name: d for d in program.defines}
        stack = list(roots)
        while stack:
            for n in A.walk(stack.pop()):
                if isinstance(n, A.Ref) and n.name not in used and n.name in by_name:
                    used.add(n.name)
                    stack.append(by_name[n.name].expr)
        for d in program.defines:
            if d.name not in used:
                self.diag(
                    Code.UNUSED_DEFINE,
                    f"Define '{d.name}' is never used by any layer",
                    d.name_span,
                    hint="remove it or reference it in a layer",
                )

    def _warn_hidden(self, program: A.Program) -> None:
        layers = program.layers
        alphas = [_static_alpha(layer) for layer in layers]
        opaque_above: list[int | None] = [None] * len(layers)  # nearest opaque layer above i
        nearest: int | None = None
        for i in range(len(layers) - 1, -1, -1):  # one pass from the top: linear in layers
            opaque_above[i] = nearest
            if alphas[i] is not None and alphas[i] >= 1:  # type: ignore[operator]
                nearest = i
        for i, layer in enumerate(layers):
            alpha = alphas[i]
            if alpha is not None and alpha <= 0:
                self.diag(
                    Code.HIDDEN_LAYER,
                    f"layer {i} has alpha {alpha} and is never visible",
                    layer.span,
                )
                continue
            j = opaque_above[i]
            if j is not None:
                self.diag(
                    Code.HIDDEN_LAYER,
                    f"layer {i} is fully hidden by opaque layer {j} above it",
                    layer.span,
                    hint="lower the upper layer's alpha or reorder",
                )

    # ---------------------------------------------------------------- expressions
    def field(self, node: A.Node, where: str, in_define: bool = False) -> None:
        """``node`` must be a field expression (not a string, bool, shape or segment)."""
        if isinstance(node, A.Str):
            self.diag(
                Code.NOT_A_FIELD,
                f"{where}: expected an expression, got the string {node.value!r}",
                node.span,
                expected="a number or field expression",
            )
            return
        if isinstance(node, A.Lit):
            kind = "None" if node.value is None else "bool"
            self.diag(
                Code.NOT_A_FIELD,
                f"{where}: expected an expression, got {kind}",
                node.span,
                expected="a number or field expression",
            )
            return
        if isinstance(node, A.Call):
            spec = FUNCTIONS.get(node.func)
            if spec is not None and spec.returns is Returns.SHAPE:
                self.diag(
                    Code.SHAPE_OUTSIDE_FILL,
                    f"{where}: the shape {node.func}(...) is only valid inline inside "
                    "Fill(...) or Stroke(...)"
                    + (" and cannot be bound by Define" if in_define else ""),
                    node.span,
                    expected="Fill(shape) or Stroke(shape, width)",
                    hint=f"wrap it: Fill({node.func}(...))",
                )
                self.call(node)
                return
            if spec is not None and spec.returns is Returns.SEGMENT:
                self.diag(
                    Code.SEGMENT_OUTSIDE_PATH,
                    f"{where}: {node.func}(...) is a segment and only valid inside Path(...)",
                    node.span,
                    expected="Path(x, y, LineTo(...), ...)",
                )
                return
        self.expr(node)

    def expr(self, node: A.Node) -> None:
        self.nodes += 1
        if isinstance(node, A.Neg):
            self.field(node.operand, "operand of '-'")
        elif isinstance(node, A.BinOp):
            self.field(node.left, f"left operand of '{node.op}'")
            self.field(node.right, f"right operand of '{node.op}'")
        elif isinstance(node, A.Call):
            self.call(node)

    def call(self, node: A.Call) -> None:
        spec = FUNCTIONS.get(node.func)
        if spec is None:
            for a in node.args:
                self.expr(a.value)
            return
        if uses_seed(node) and node.arg("seed") is None:
            self.diag(
                Code.NO_SEED,
                f"{spec.name}(...) has no seed; one will be drawn at canonicalisation",
                node.span,
                hint="write seed=N so the program is reproducible as written",
            )
        for arg in node.args:
            p = spec.param(arg.param)
            assert p is not None
            self.argument(spec.name, p, arg)
            if p.needs is not None and _absent(node.arg(p.needs)) and not _is_none(arg.value):
                self.diag(
                    Code.NO_EFFECT,
                    f"{spec.name}: {p.name} has no effect without {p.needs}",
                    arg.span,
                    hint=f"write {p.needs}=... or remove {p.name} (fmt drops it)",
                )
        if spec.nary:  # Min(a, b, c, ...): more field operands
            for k, extra in enumerate(node.extra, start=3):
                self.field(extra, f"{spec.name}: operand {k}")
            self._frequency_rule(node)
            return
        for seg in node.extra:
            seg_spec = FUNCTIONS.get(seg.func) if isinstance(seg, A.Call) else None
            if seg_spec is None or seg_spec.returns is not Returns.SEGMENT:
                self.diag(
                    Code.BAD_SEGMENTS,
                    f"{spec.name}(...) segments must be LineTo(...) or CubicTo(...)",
                    getattr(seg, "span", node.span),
                    expected="LineTo(x, y) or CubicTo(c1x, c1y, c2x, c2y, x, y)",
                )
                continue
            self.nodes += 1
            for a in seg.args:
                self.argument(seg_spec.name, seg_spec.param(a.param), a)  # type: ignore[arg-type]
        self._frequency_rule(node)

    def _frequency_rule(self, node: A.Call) -> None:
        bf = node.arg("base_freq")
        if isinstance(bf, A.Lit) and bf.value is None:
            fx, fy = node.arg("base_freq_x"), node.arg("base_freq_y")
            if fx is None or fy is None or _is_none(fx) or _is_none(fy):
                self.diag(
                    Code.BASE_FREQ_AXES,
                    f"{node.func}: base_freq=None requires both base_freq_x and base_freq_y",
                    node.span,
                    expected="base_freq_x=... and base_freq_y=...",
                )

    def argument(self, func: str, p: ParamSpec, arg: A.Arg) -> None:
        v = arg.value
        if p.kind is Kind.EXPR:
            self.field(v, f"{func}({p.name}=...)")
            return
        if p.kind is Kind.SHAPE:
            spec = FUNCTIONS.get(v.func) if isinstance(v, A.Call) else None
            if spec is None or spec.returns is not Returns.SHAPE:
                self.diag(
                    Code.EXPECTED_SHAPE,
                    f"{func} expects a shape (Rect, Ellipse or Path) as '{p.name}'",
                    getattr(v, "span", arg.span),
                    expected="Rect(...), Ellipse(...) or Path(...)",
                    hint="shapes must be written inline; they cannot be Define'd",
                )
                if isinstance(v, A.Call | A.BinOp | A.Neg):
                    self.expr(v)
                return
            self.nodes += 1
            self.call(v)  # type: ignore[arg-type]
            return
        if isinstance(v, A.Lit) and v.value is None and p.nullable:
            return
        if p.kind is Kind.ENUM:
            self._enum(func, p, v)
            return
        if p.kind is Kind.BOOL:
            ok = (isinstance(v, A.Lit) and isinstance(v.value, bool)) or (
                isinstance(v, A.Num) and v.value in (0, 1)
            )
            if not ok:
                self.diag(
                    Code.NOT_A_BOOL,
                    f"{func}: {p.name} must be True or False",
                    v.span,
                    expected="True or False",
                )
            return
        self._number(func, p, v)

    def _enum(self, func: str, p: ParamSpec, v: A.Node) -> None:
        if isinstance(v, A.Str) and v.value in p.choices:
            return
        got = repr(v.value) if isinstance(v, A.Str) else "an expression"
        hint = hint_for(v.value, p.choices) if isinstance(v, A.Str) else None
        if hint is None and isinstance(v, A.Ref) and v.name in p.choices:
            hint = f'quote it: {p.name}="{v.name}"'
        self.diag(
            Code.BAD_CHOICE,
            f"{func}: {p.name} must be {p.constraint_text()}, got {got}",
            getattr(v, "span", None) or Span(0, 0, 1, 1),
            expected=p.constraint_text(),
            hint=hint,
        )

    def _number(self, func: str, p: ParamSpec, v: A.Node) -> None:
        span = v.span
        if isinstance(v, A.Str | A.Lit):
            self.diag(
                Code.NOT_A_NUMBER,
                f"{func}: {p.name} must be a number, got {_describe(v)}",
                span,
                expected=f"a number{', ' + p.constraint_text() if p.constraint_text() else ''}",
            )
            return
        if p.field and static_number(v) is None:  # a field parameter: checked like an operand
            self.expr(v)
            return
        named = "" if p.field else _named(v, self.consts)
        if named:  # constant Defines named in a static parameter: their value (named values)
            v = substitute(v, self.consts)
        raw = static_number(v)
        if raw is None:
            fields = [n.name for n in A.walk(v) if isinstance(n, A.Ref)]
            what = f"; Define '{fields[0]}' is a field" if fields else ", not a field expression"
            self.diag(
                Code.NOT_A_NUMBER,
                f"{func}: {p.name} must be a number{what}",
                span,
                expected="a constant such as 0.5",
                hint=(
                    "a Define named here must be a constant (no noise, pattern, X() or Y())"
                    if fields
                    else "only numbers (and constant arithmetic) are allowed here"
                ),
            )
            self.expr(v)
            return
        value = raw if isinstance(raw, float) else _as_number(raw)
        if uses_coordinates(v):
            self.diag(
                Code.COORDINATES_IN_NUMBER,
                f"{func}: {p.name} uses X()/Y(); it is evaluated once at (0, 0)",
                span,
                hint=(
                    "to vary it per sample, Define the expression and pass the Define's name"
                    if p.field
                    else "numeric parameters are constants, not fields"
                ),
            )
        if isinstance(value, float) and not math.isfinite(value):
            self.diag(
                Code.OUT_OF_RANGE,
                f"{func}: {p.name} must be finite, got {value}{named}",
                span,
                expected="a finite number",
            )
            return
        if p.kind is Kind.INT and not float(value).is_integer():
            self.diag(
                Code.NOT_AN_INTEGER,
                f"{func}: {p.name} must be an integer, got {value}{named}",
                span,
                expected="a whole number",
            )
            return
        problem = p.check_value(value)
        if problem is not None:
            code = Code.ZERO_NOT_ALLOWED if p.nonzero and value == 0 else Code.OUT_OF_RANGE
            self.diag(code, f"{func}: {problem}{named}", span, expected=p.constraint_text())
            return
        if p.name == "octaves" and value > MAX_OCTAVES:
            self.diag(
                Code.SIZE_LIMIT,
                f"{func}: octaves={int(value)}{named} exceeds the limit of {MAX_OCTAVES}",
                span,
                expected=f"octaves <= {MAX_OCTAVES}",
            )


def _named(v: A.Node, consts: Constants) -> str:
    """`` (from Define 'grout')`` when ``v`` names constant Defines, else ``""``."""
    names = list(dict.fromkeys(n.name for n in A.walk(v) if isinstance(n, A.Ref)))
    names = [n for n in names if n in consts]
    if not names:
        return ""
    return f" (from Define{'s' if len(names) > 1 else ''} {', '.join(repr(n) for n in names)})"


def _static_alpha(layer: A.Layer) -> float | None:
    """A layer's alpha if it is a constant (no X()/Y()); 1 when unwritten; else ``None``."""
    if layer.alpha is None:
        return 1.0
    if uses_coordinates(layer.alpha):
        return None
    value = static_number(layer.alpha)
    return None if value is None or isinstance(value, float) else _as_number(value)


def _as_number(value: int) -> int | float:
    """An exact integer as it is, or +-inf if it lies beyond the float range (evaluators compute
    in floating point, so constant integer arithmetic such as ``10**200 * 10**200`` is inf)."""
    as_real = as_float(value)
    return value if math.isfinite(as_real) else as_real


def inlined_depth(node: A.Node, depth_of: dict[str, int]) -> int:
    """Tree depth of ``node`` with each known Define reference counted at its own depth."""
    deepest, stack = 0, [(node, 1)]
    while stack:
        cur, d = stack.pop()
        if isinstance(cur, A.Ref):
            d += depth_of.get(cur.name, 1) - 1
        deepest = max(deepest, d)
        stack.extend((child, d + 1) for child in A.children(cur))
    return deepest


def _span_of(node: A.Node, fallback: Span) -> Span:
    span = getattr(node, "span", None)
    return span if span is not None and span.end > span.start else fallback


def _is_none(node: A.Node) -> bool:
    return isinstance(node, A.Lit) and node.value is None


def _absent(node: A.Node | None) -> bool:
    """Not written, or written as None."""
    return node is None or _is_none(node)


def _describe(v: A.Node) -> str:
    if isinstance(v, A.Str):
        return f"the string {v.value!r}"
    if isinstance(v, A.Lit):
        return repr(v.value)
    return "an expression"


def check_program(program: A.Program, source: str) -> list[Diagnostic]:
    """Every diagnostic of the checks; a program with parameterised Defines is checked
    expanded (:mod:`matloom.lang.macros`), after its expanded size is known to be bounded."""
    from matloom.lang.macros import (
        MAX_EXPANDED_TREE,
        ExpansionTooLarge,
        expand_program,
        expanded_size,
        has_macros,
    )

    if has_macros(program):
        try:
            expanded = expand_program(program)
            size = expanded_size(expanded)
        except ExpansionTooLarge:
            expanded, size = program, MAX_EXPANDED_TREE + 1
        if size > MAX_EXPANDED_TREE:
            return [
                Code.SIZE_LIMIT.diagnostic(
                    "the uses of parameterised Defines expand to more than "
                    f"{MAX_EXPANDED_TREE:,} expression nodes, the limit",
                    program.span,
                    expected=f"at most {MAX_EXPANDED_TREE:,} nodes once expanded",
                    hint="each use of Define(name(a, b), ...) is a copy of its body: nest fewer "
                    "uses, or use a plain Define for a shared sub-expression",
                )
            ]
        program = expanded
    return Checker(source).check(program)
