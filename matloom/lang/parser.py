"""Recursive-descent parser: program text -> :mod:`matloom.lang.ast`, with structured diagnostics.

One grammar for the whole program (no regex splitting):

    program  := [view] {define} material EOF
    view     := "View" "(" expr "," expr "," expr "," expr ["," "tileable" "=" BOOL] ")"
    define   := "Define" "(" IDENT "," expr ")"
    material := "Material" "(" [layer {"," layer}] ")"
    layer    := "Layer" "(" [expr] ")" {"." IDENT "(" [expr {"," expr}] ")"}
    expr     := muldiv {("+"|"-") muldiv}
    muldiv   := unary {("*"|"/") unary}
    unary    := ("-"|"+") power | power
    power    := atom ["**" unary]                 (right-associative)
    atom     := NUM | STRING | IDENT "(" [arg {"," arg}] ")" | IDENT | "(" expr ")"
    arg      := IDENT "=" expr | expr

Binding of arguments to registry parameters happens here; value checks live in the checker.
Syntax errors inside one statement are reported and the parser resynchronises at the next
statement, so one pass reports as many independent problems as possible.
"""

from __future__ import annotations

from matloom.lang import ast as A
from matloom.lang.aliases import channel_alias, name_alias
from matloom.lang.comments import attach_comments
from matloom.lang.diagnostics import Diagnostic, Severity, Span, caret_excerpt, hint_for
from matloom.lang.lexer import MAX_SOURCE_CHARS, Lexer, LexError, Token
from matloom.vocab import CHANNELS, CONSTANTS, FUNCTIONS, LITERALS, Returns

MAX_NESTING = 100
"""Maximum expression nesting depth, and maximum depth of an expression tree (documented limit).

It bounds the recursion of the parser and of every recursive tree walker (checker, printer,
evaluator), so hostile inputs such as ``((((...`` or ``1+1+...+1`` fail with E070 instead of
exhausting Python's stack (the parser needs about 6 frames per nesting level)."""

_STATEMENTS = ("View", "Define", "Material", "Layer")
_BINARY_FUNCS = {"Add": "+", "Sub": "-", "Mul": "*", "Div": "/", "Pow": "**"}


class _Bail(Exception):
    """Abort the current statement after a syntax error has been recorded."""


class Parser:
    """Parses one program. Use :func:`parse_source` rather than this class directly."""

    def __init__(self, source: str) -> None:
        self.src = source
        self.lexer = Lexer(source)
        self.toks: list[Token] = []
        self.i = 0
        self.depth = 0
        self.diags: list[Diagnostic] = []
        self.defined: dict[str, None] = {}  # ordered set: O(1) lookups on huge inputs
        self.all_define_names: set[str] = set()
        self.broken_defines: set[str] = set()

    # ---------------------------------------------------------------- diagnostics
    def diag(
        self,
        code: str,
        msg: str,
        span: Span,
        expected: str | None = None,
        hint: str | None = None,
        severity: Severity = Severity.ERROR,
    ) -> None:
        self.diags.append(
            Diagnostic(code, msg, span, severity, expected, hint, caret_excerpt(self.src, span))
        )

    def fail(
        self, code: str, msg: str, span: Span, expected: str | None = None, hint: str | None = None
    ) -> _Bail:
        self.diag(code, msg, span, expected, hint)
        return _Bail()

    # ---------------------------------------------------------------- token helpers
    def peek(self, k: int = 0) -> Token:
        return self.toks[min(self.i + k, len(self.toks) - 1)]

    def next(self) -> Token:
        tok = self.toks[self.i]
        if tok.kind != "EOF":
            self.i += 1
        return tok

    def at(self, text: str, k: int = 0) -> bool:
        t = self.peek(k)
        return t.kind in ("OP", "IDENT") and t.text == text

    def expect(self, text: str, context: str = "") -> Token:
        tok = self.peek()
        if tok.kind in ("OP", "IDENT") and tok.text == text:
            return self.next()
        where = f" {context}" if context else ""
        hint = None
        if text == ")" and tok.kind in ("NUM", "IDENT", "STR"):
            hint = "a ',' may be missing between arguments"
        elif text == "," and tok.text == ")":
            hint = "an argument is missing"
        raise self.fail(
            "E010",
            f"expected '{text}'{where} but found {tok.describe()}",
            tok.span,
            expected=f"'{text}'",
            hint=hint,
        )

    def span_from(self, start: Span) -> Span:
        prev = self.toks[self.i - 1] if self.i > 0 else self.peek()
        return Span(start.start, max(start.end, prev.span.end), start.line, start.col)

    # ---------------------------------------------------------------- program
    def parse(self) -> A.Program | None:
        if len(self.src) > MAX_SOURCE_CHARS:
            self.diag(
                "E070",
                f"program is too large ({len(self.src)} characters)",
                Span(0, 1, 1, 1),
                expected=f"at most {MAX_SOURCE_CHARS} characters",
            )
            return None
        try:
            self.toks = self.lexer.tokens()
        except LexError as e:
            self.diag(e.code, e.message, e.span, e.expected, e.hint)
            return None
        self._prescan_defines()
        view: A.ViewDecl | None = None
        defines: list[A.Define] = []
        layers: tuple[A.Layer, ...] | None = None
        seen_define = False
        while self.peek().kind != "EOF":
            tok = self.peek()
            start = self.i
            try:
                if tok.text == "View" and tok.kind == "IDENT":
                    if layers is not None or seen_define or view is not None:
                        what = (
                            "a second View"
                            if view is not None
                            else "View after " + ("Material" if layers is not None else "a Define")
                        )
                        self.diag(
                            "E020",
                            f"{what}: View must be the first statement",
                            tok.span,
                            expected="View(...) before any Define or Material",
                            hint="move the View line to the top of the program",
                        )
                    v = self.parse_view()
                    view = view or v
                elif tok.text == "Define" and tok.kind == "IDENT":
                    if layers is not None:
                        self.diag(
                            "E023",
                            "Define after Material: nothing may follow Material(...)",
                            tok.span,
                            expected="end of input",
                            hint="move Defines above Material(...)",
                        )
                    seen_define = True
                    d = self.parse_define()
                    if d is not None:
                        defines.append(d)
                elif tok.text == "Material" and tok.kind == "IDENT":
                    self.material_started = True
                    if layers is not None:
                        self.diag(
                            "E023",
                            "a second Material: a program has exactly one",
                            tok.span,
                            expected="end of input",
                        )
                    parsed = self.parse_material()
                    layers = parsed if layers is None else layers
                elif tok.text == "Layer" and tok.kind == "IDENT":
                    raise self.fail(
                        "E025",
                        "Layer outside Material(...)",
                        tok.span,
                        expected="Material(Layer(...), ...)",
                        hint="put every Layer inside one Material(...)",
                    )
                else:
                    raise self._unexpected_statement(tok, layers is not None)
            except _Bail:
                if tok.text == "Define" and start + 2 < len(self.toks):
                    self.broken_defines.add(self.toks[start + 2].text)  # uses are not re-reported
                self._skip_statement(start)
        if layers is None:
            eof = self.peek()
            if not getattr(self, "material_started", False) and not any(
                d.code in ("E012", "E025") for d in self.diags
            ):
                self.diag(
                    "E022",
                    "missing Material(...)",
                    eof.span,
                    expected="Material(Layer(...), ...) as the last statement",
                )
            return None
        program = A.Program(view, tuple(defines), layers, Span(0, len(self.src), 1, 1))
        return attach_comments(program, self.lexer.comments, self.toks)

    def _unexpected_statement(self, tok: Token, after_material: bool) -> _Bail:
        if after_material:
            return self.fail(
                "E012",
                f"unexpected trailing input {tok.describe()} after Material(...)",
                tok.span,
                expected="end of input",
            )
        hint = None
        if tok.kind == "IDENT":
            hint = hint_for(tok.text, _STATEMENTS)
        return self.fail(
            "E012",
            f"unexpected {tok.describe()} at top level",
            tok.span,
            expected="View(...), Define(...) or Material(...)",
            hint=hint,
        )

    def _prescan_defines(self) -> None:
        t = self.toks
        for k in range(len(t) - 2):
            if t[k].text == "Define" and t[k + 1].text == "(" and t[k + 2].kind == "IDENT":
                self.all_define_names.add(t[k + 2].text)

    def _skip_statement(self, start: int) -> None:
        """Resynchronise: skip from ``start`` past the statement's balanced parentheses.

        Skipping stops early at a ``View(``/``Define(``/``Material(`` that starts a line, so an
        unclosed parenthesis does not swallow (and hide errors in) the statements after it.
        """
        self.i = start
        self.next()  # the statement keyword (or stray token)
        self._skip_parens()
        # a stray top-level ',' after a statement is skipped, and so is a method chain such as
        # `.roughness(0.5)` after a misplaced Layer(...)
        while self.peek().text in (",", ".") and self.peek().kind == "OP":
            dot = self.next().text == "."
            if dot and self.peek().kind == "IDENT" and not self._at_statement_start():
                self.next()
                self._skip_parens()

    def _skip_parens(self) -> None:
        if not self.at("("):
            return
        depth = 0
        while self.peek().kind != "EOF":
            if depth > 0 and self._at_statement_start():
                return
            tok = self.next()
            if tok.text == "(":
                depth += 1
            elif tok.text == ")":
                depth -= 1
                if depth == 0:
                    return

    def _at_statement_start(self) -> bool:
        tok = self.peek()
        if tok.kind != "IDENT" or tok.text not in ("View", "Define", "Material"):
            return False
        first_on_line = self.i == 0 or self.toks[self.i - 1].span.line < tok.span.line
        return first_on_line and self.at("(", 1)

    def parse_view(self) -> A.ViewDecl | None:
        from matloom.lang.parse_view import parse_view

        return parse_view(self)

    def parse_define(self) -> A.Define | None:
        kw = self.next()
        self.expect("(", "after Define")
        name_tok = self.peek()
        if name_tok.kind != "IDENT":
            raise self.fail(
                "E010",
                f"expected a name for the Define but found {name_tok.describe()}",
                name_tok.span,
                expected="Define(name, expression)",
            )
        self.next()
        self.expect(",", "after the Define name")
        self.current_define = name_tok.text
        try:
            expr = self.parse_expr()
        finally:
            self.current_define = None
        if self.at(","):
            raise self.fail(
                "E027",
                "Define takes exactly 2 arguments (name, expression)",
                self.peek().span,
                expected="')'",
            )
        self.expect(")", "to close Define(...)")
        name = name_tok.text
        if name in self.defined:
            self.diag(
                "E038",
                f"Define '{name}' is defined twice",
                name_tok.span,
                expected="a unique name",
                hint="rename one of the Defines",
            )
        elif name in FUNCTIONS or name in CONSTANTS or name in LITERALS or name in _STATEMENTS:
            self.diag(
                "W005",
                f"Define name '{name}' is shadowed by a built-in and can never be referenced",
                name_tok.span,
                severity=Severity.WARNING,
                hint="choose another name",
            )
        self.defined[name] = None
        return A.Define(name, expr, self.span_from(kw.span), name_tok.span)

    # ---------------------------------------------------------------- material / layers
    def parse_material(self) -> tuple[A.Layer, ...]:
        kw = self.next()
        self.expect("(", "after Material")
        layers: list[A.Layer] = []
        if self.at(")"):
            self.diag(
                "E024",
                "Material has no layers",
                self.span_from(kw.span),
                expected="at least one Layer(...)",
                hint="add a base layer such as Layer(1).basecolor(128, 128, 128)",
            )
            self.next()
            return ()
        while True:
            tok = self.peek()
            if not (tok.kind == "IDENT" and tok.text == "Layer"):
                if tok.text == ")" and layers:
                    raise self.fail(
                        "E013",
                        "trailing comma after the last layer",
                        tok.span,
                        expected="another Layer(...) or no comma",
                    )
                hint = hint_for(tok.text, ["Layer"]) if tok.kind == "IDENT" else None
                raise self.fail(
                    "E025",
                    f"expected Layer(...) but found {tok.describe()}",
                    tok.span,
                    expected="Layer(...)",
                    hint=hint,
                )
            layers.append(self.parse_layer())
            if self.at(","):
                self.next()
                continue
            break
        if not self.at(")"):
            tok = self.peek()
            raise self.fail(
                "E010",
                f"expected ',' or ')' after a layer but found {tok.describe()}",
                tok.span,
                expected="',' between layers or ')' to close Material",
                hint="a ',' may be missing between layers" if tok.text == "Layer" else None,
            )
        self.next()
        return tuple(layers)

    def parse_layer(self) -> A.Layer:
        kw = self.next()
        self.expect("(", "after Layer")
        alpha: A.Node | None = None
        if not self.at(")"):
            alpha = self.parse_expr()
            if self.at(","):
                raise self.fail(
                    "E028",
                    "Layer takes at most one argument (its alpha)",
                    self.peek().span,
                    expected="')'",
                    hint="set channels with methods: Layer(1).basecolor(r, g, b)",
                )
        self.expect(")", "to close Layer(...)")
        chans: dict[str, A.ChannelSet] = {}
        while self.at("."):
            self.next()
            name_tok = self.peek()
            if name_tok.kind != "IDENT":
                raise self.fail(
                    "E010",
                    f"expected a channel name after '.' but found {name_tok.describe()}",
                    name_tok.span,
                    expected="one of " + ", ".join(CHANNELS),
                )
            self.next()
            args = self._method_args(name_tok)
            name = name_tok.text
            spec = CHANNELS.get(name)
            span = self.span_from(name_tok.span)
            if spec is None:
                self.diag(
                    "E026",
                    f"unknown layer channel '.{name}'",
                    name_tok.span,
                    expected="one of " + ", ".join(CHANNELS),
                    hint=hint_for(name, CHANNELS) or channel_alias(name),
                )
                continue
            if len(args) != spec.arity:
                self.diag(
                    "E027",
                    f"{name}() expects {spec.arity} argument"
                    f"{'s' if spec.arity != 1 else ''}, got {len(args)}",
                    span,
                    expected=f".{name}({', '.join(spec.arg_names)})",
                )
                continue
            if name in chans:
                self.diag(
                    "W006",
                    f"channel '.{name}' is set twice; the last one wins",
                    name_tok.span,
                    severity=Severity.WARNING,
                )
            if name == "alpha":
                alpha = args[0]
                chans.pop("alpha", None)
                chans["alpha"] = A.ChannelSet(name, tuple(args), span)
            else:
                chans[name] = A.ChannelSet(name, tuple(args), span)
        ordered = tuple(chans[n] for n in CHANNELS if n in chans and n != "alpha")
        return A.Layer(alpha, ordered, self.span_from(kw.span))

    def _method_args(self, name_tok: Token) -> list[A.Node]:
        self.expect("(", f"after .{name_tok.text}")
        args: list[A.Node] = []
        if self.at(")"):
            self.next()
            return args
        while True:
            if self.peek().kind == "IDENT" and self.at("=", 1):
                tok = self.peek()
                raise self.fail(
                    "E031",
                    f"channel .{name_tok.text}() takes positional values, not '{tok.text}='",
                    tok.span,
                    expected="a value",
                    hint=f"write .{name_tok.text}(value)",
                )
            args.append(self.parse_expr())
            if self.at(","):
                comma = self.next()
                if self.at(")"):
                    raise self.fail(
                        "E013",
                        "trailing comma in argument list",
                        comma.span,
                        expected="another argument",
                    )
                continue
            break
        self.expect(")", f"to close .{name_tok.text}(...)")
        return args

    # ---------------------------------------------------------------- expressions
    def parse_expr(self) -> A.Node:
        self.depth += 1
        try:
            if self.depth > MAX_NESTING:
                raise self.fail(
                    "E070",
                    f"expression nested deeper than {MAX_NESTING} levels",
                    self.peek().span,
                    expected="a shallower expression",
                    hint="move sub-expressions into Defines",
                )
            left = self.parse_muldiv()
            chain = 0
            while self.peek().kind == "OP" and self.peek().text in "+-" and self.peek().text:
                op = self.next()
                chain += 1
                self._check_chain(chain, op)
                right = self.parse_muldiv()
                left = A.BinOp(op.text, left, right, _join(left, right, op.span))
            if self.depth == 1 and _tree_depth(left) > MAX_NESTING:  # long operator chains
                raise self.fail(
                    "E070",
                    f"expression tree deeper than {MAX_NESTING} levels",
                    node_span(left, self.peek().span),
                    expected="a shallower expression",
                    hint="move sub-expressions into Defines",
                )
            return left
        finally:
            self.depth -= 1

    def _check_chain(self, chain: int, op: Token) -> None:
        """Fail early on an operator chain whose tree alone would exceed :data:`MAX_NESTING`."""
        if chain >= MAX_NESTING:  # the chain alone makes the tree deeper than the limit
            raise self.fail(
                "E070",
                f"expression tree deeper than {MAX_NESTING} levels",
                op.span,
                expected="a shallower expression",
                hint="move sub-expressions into Defines",
            )

    def parse_muldiv(self) -> A.Node:
        left = self.parse_unary()
        chain = 0
        while self.peek().kind == "OP" and self.peek().text in ("*", "/"):
            op = self.next()
            chain += 1
            self._check_chain(chain, op)
            right = self.parse_unary()
            left = A.BinOp(op.text, left, right, _join(left, right, op.span))
        return left

    def parse_unary(self) -> A.Node:
        tok = self.peek()
        if tok.kind == "OP" and tok.text in ("-", "+"):
            self.next()
            nxt = self.peek()
            if nxt.kind == "OP" and nxt.text in ("-", "+"):
                raise self.fail(
                    "E011",
                    f"expected an expression after '{tok.text}' but found {nxt.describe()}",
                    nxt.span,
                    expected="a number, name or '('",
                    hint="a sign cannot follow another sign; write -(-x)",
                )
            operand = self.parse_power()
            if tok.text == "+":
                return operand
            return A.Neg(operand, self.span_from(tok.span))
        return self.parse_power()

    def parse_power(self) -> A.Node:
        base = self.parse_atom()
        if self.at("**"):
            op = self.next()
            self.depth += 1
            try:
                if self.depth > MAX_NESTING:
                    raise self.fail(
                        "E070",
                        f"expression nested deeper than {MAX_NESTING} levels",
                        op.span,
                        expected="a shallower expression",
                    )
                exp = self.parse_unary()
            finally:
                self.depth -= 1
            return A.BinOp("**", base, exp, _join(base, exp, op.span))
        return base

    def parse_atom(self) -> A.Node:
        tok = self.peek()
        if tok.kind == "NUM":
            self.next()
            return A.Num(tok.value, tok.span)  # type: ignore[arg-type]
        if tok.kind == "STR":
            self.next()
            return A.Str(str(tok.value), tok.span)
        if tok.kind == "OP" and tok.text == "(":
            self.next()
            inner = self.parse_expr()
            self.expect(")", "to close '('")
            return inner
        if tok.kind == "IDENT":
            if self.at("(", 1):
                return self.parse_call()
            return self.parse_name()
        if tok.kind == "EOF":
            raise self.fail(
                "E011",
                "expected an expression but found end of input",
                tok.span,
                expected="a number, name, call or '('",
                hint="the program ends early; check for unclosed parentheses",
            )
        hint = "an argument is missing" if tok.text in (",", ")") else None
        if tok.text == ".":
            hint = "write numbers with a digit after the point, e.g. 0.5"
        raise self.fail(
            "E011",
            f"expected an expression but found {tok.describe()}",
            tok.span,
            expected="a number, name, call or '('",
            hint=hint,
        )

    def parse_name(self) -> A.Node:
        tok = self.next()
        name = tok.text
        if name in LITERALS:
            return A.Lit(LITERALS[name], tok.span)
        if name in CONSTANTS:
            return A.Const(name, tok.span)
        if name in FUNCTIONS:
            self.diag(
                "E035",
                f"'{name}' is a function — call it as {name}()",
                tok.span,
                expected=f"{name}(...)",
            )
            return A.Ref(name, tok.span)
        if name in self.defined or name in self.broken_defines:
            return A.Ref(name, tok.span)
        current = getattr(self, "current_define", None)
        if name == current:
            self.diag(
                "E060",
                f"Define '{name}' refers to itself",
                tok.span,
                expected="only earlier Defines",
                hint="Defines form an acyclic graph",
            )
        elif name in self.all_define_names:
            self.diag(
                "E060",
                f"'{name}' is used before its Define",
                tok.span,
                expected="only Defines that appear earlier in the program",
                hint=f"move Define({name}, ...) above this line",
            )
        else:
            hint = hint_for(name, [*self.defined, *CONSTANTS]) or name_alias(name)
            if hint is None and name in _STATEMENTS:
                hint = f"{name}(...) is a statement, not an expression"
            self.diag(
                "E036",
                f"unknown name '{name}'",
                tok.span,
                expected="an earlier Define, pi, e, or a function call",
                hint=hint,
            )
        return A.Ref(name, tok.span)

    def parse_call(self) -> A.Node:
        from matloom.lang.binding import bind_call

        name_tok = self.next()
        self.next()  # '('
        raw: list[tuple[Token | None, A.Node, Span]] = []
        if not self.at(")"):
            while True:
                start = self.peek().span
                key: Token | None = None
                if self.peek().kind == "IDENT" and self.at("=", 1):
                    key = self.next()
                    self.next()
                value = self.parse_expr()
                raw.append((key, value, self.span_from(start)))
                if self.at(","):
                    comma = self.next()
                    if self.at(")"):
                        raise self.fail(
                            "E013",
                            "trailing comma in argument list",
                            comma.span,
                            expected="another argument or no comma",
                        )
                    continue
                break
        self.expect(")", f"to close {name_tok.text}(...)")
        span = self.span_from(name_tok.span)
        return bind_call(self, name_tok, raw, span)


def _tree_depth(node: A.Node) -> int:
    """Depth of an expression tree, computed without recursion."""
    deepest, stack = 0, [(node, 1)]
    while stack:
        cur, d = stack.pop()
        deepest = max(deepest, d)
        stack.extend((c, d + 1) for c in A.children(cur))
    return deepest


def node_span(node: A.Node, fallback: Span) -> Span:
    s = getattr(node, "span", None)
    return s if s is not None and s.end > s.start else fallback


def _join(left: A.Node, right: A.Node, op: Span) -> Span:
    ls, rs = node_span(left, op), node_span(right, op)
    return Span(ls.start, max(rs.end, op.end), ls.line, ls.col)


def parse_source(source: str) -> tuple[A.Program | None, list[Diagnostic]]:
    """Parse ``source`` into a Program (or ``None``) and the syntax/binding diagnostics."""
    p = Parser(source)
    program = p.parse()
    return program, p.diags


__all__ = ["MAX_NESTING", "Parser", "Returns", "parse_source"]
