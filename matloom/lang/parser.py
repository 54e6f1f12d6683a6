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

Statements, Material and Layers are parsed here, View in :mod:`matloom.lang.parse_view`,
expressions and calls in :mod:`matloom.lang.parse_expr`; the token cursor and diagnostics are
in :mod:`matloom.lang.parse_base` (which lists these layers). Bracket-related errors get their
hints from the bracket analysis of :mod:`matloom.lang.brackets` (which construct's parenthesis
is extra or missing). Arguments are bound to registry parameters by
:mod:`matloom.lang.binding`; value checks live in the checker. The codes of the diagnostics are
:class:`matloom.lang.codes.Code` members.
Syntax errors inside one statement are reported and the parser resynchronises at the next
statement, so one pass reports as many independent problems as possible.
"""

from __future__ import annotations

from matloom.lang import ast as A
from matloom.lang.aliases import channel_alias
from matloom.lang.codes import Code
from matloom.lang.comments import attach_comments
from matloom.lang.diagnostics import Diagnostic, Span, hint_for
from matloom.lang.lexer import MAX_SOURCE_CHARS, LexError, Token
from matloom.lang.parse_base import Bail
from matloom.lang.parse_expr import KEYWORDS, ExpressionParser
from matloom.lang.parse_view import parse_view
from matloom.vocab import CHANNELS, CONSTANTS, FUNCTIONS, LITERALS


class Parser(ExpressionParser):
    """Parses one program. Use :func:`parse_source` rather than this class directly."""

    # ---------------------------------------------------------------- program
    def parse(self) -> A.Program | None:
        if len(self.src) > MAX_SOURCE_CHARS:
            self.diag(
                Code.SIZE_LIMIT,
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
                            Code.VIEW_NOT_FIRST,
                            f"{what}: View must be the first statement",
                            tok.span,
                            expected="View(...) before any Define or Material",
                            hint="move the View line to the top of the program",
                        )
                    v = parse_view(self)
                    view = view or v
                elif tok.text == "Define" and tok.kind == "IDENT":
                    if layers is not None:
                        self.diag(
                            Code.AFTER_MATERIAL,
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
                            Code.AFTER_MATERIAL,
                            "a second Material: a program has exactly one",
                            tok.span,
                            expected="end of input",
                        )
                    parsed = self.parse_material()
                    layers = parsed if layers is None else layers
                elif tok.text == "Layer" and tok.kind == "IDENT":
                    raise self.fail(
                        Code.MISPLACED_LAYER,
                        "Layer outside Material(...)",
                        tok.span,
                        expected="Material(Layer(...), ...)",
                        hint=self.brackets.closed_early(self.i)
                        or "put every Layer inside one Material(...)",
                    )
                else:
                    raise self._unexpected_statement(tok, layers is not None)
            except Bail:
                if tok.text == "Define" and start + 2 < len(self.toks):
                    self.broken_defines.add(self.toks[start + 2].text)  # uses are not re-reported
                self._skip_statement(start)
        if layers is None:
            eof = self.peek()
            if not self.material_started and not any(
                d.code in (Code.UNEXPECTED_INPUT.code, Code.MISPLACED_LAYER.code)
                for d in self.diags
            ):
                self.diag(
                    Code.MISSING_MATERIAL,
                    "missing Material(...)",
                    eof.span,
                    expected="Material(Layer(...), ...) as the last statement",
                )
            return None
        program = A.Program(view, tuple(defines), layers, Span(0, len(self.src), 1, 1))
        return attach_comments(program, self.lexer.comments, self.toks)

    def _unexpected_statement(self, tok: Token, after_material: bool) -> Bail:
        hint = None
        if _is_close(tok):
            hint = self.brackets.extra_close(self.i)
        elif tok.kind == "IDENT" and not after_material:
            hint = hint_for(tok.text, KEYWORDS)  # a misspelt statement
        hint = hint or self.brackets.closed_early(self.i)
        if after_material:
            return self.fail(
                Code.UNEXPECTED_INPUT,
                f"unexpected trailing input {tok.describe()} after Material(...)",
                tok.span,
                expected="end of input",
                hint=hint,
            )
        return self.fail(
            Code.UNEXPECTED_INPUT,
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

    def parse_define(self) -> A.Define | None:
        kw = self.next()
        self.expect("(", "after Define")
        name_tok = self.peek()
        if name_tok.kind != "IDENT":
            raise self.fail(
                Code.EXPECTED_TOKEN,
                f"expected a name for the Define but found {name_tok.describe()}",
                name_tok.span,
                expected="Define(name, expression)",
            )
        self.next()
        params = self._define_params(name_tok) if self.at("(") else ()
        self.expect(",", "after the Define name")
        self.current_define = name_tok.text
        self.params = params
        try:
            expr = self.parse_expr()
        finally:
            self.current_define = None
            self.params = ()
        if self.at(","):
            raise self.fail(
                Code.ARGUMENT_COUNT,
                "Define takes exactly 2 arguments (name, expression)",
                self.peek().span,
                expected="')'",
            )
        self.expect(")", "to close Define(...)")
        name = name_tok.text
        if name in self.defined:
            self.diag(
                Code.DUPLICATE_DEFINE,
                f"Define '{name}' is defined twice",
                name_tok.span,
                expected="a unique name",
                hint="rename one of the Defines",
            )
        elif name in FUNCTIONS or name in CONSTANTS or name in LITERALS or name in KEYWORDS:
            self.diag(
                Code.SHADOWED_DEFINE,
                f"Define name '{name}' is shadowed by a built-in and can never be referenced",
                name_tok.span,
                hint="choose another name",
            )
        self.defined[name] = None
        if params:
            self.macros[name] = params
        return A.Define(name, expr, self.span_from(kw.span), name_tok.span, params=params)

    def _define_params(self, name_tok: Token) -> tuple[str, ...]:
        """The parameter list of ``Define(name(a, b), ...)`` (language 3), from its ``(``."""
        self.next()  # '('
        names: list[str] = []
        while True:
            tok = self.peek()
            if tok.kind != "IDENT":
                raise self.fail(
                    Code.EXPECTED_TOKEN,
                    f"expected a parameter name of Define '{name_tok.text}' but found "
                    f"{tok.describe()}",
                    tok.span,
                    expected=f"Define({name_tok.text}(a, b), expression)",
                )
            self.next()
            problem = None
            if tok.text in names:
                problem = "is repeated"
            elif tok.text in FUNCTIONS or tok.text in CONSTANTS or tok.text in LITERALS:
                problem = "is a built-in name"
            elif tok.text in KEYWORDS:
                problem = "is a keyword"
            elif tok.text in self.defined or tok.text == name_tok.text:
                problem = "is the name of a Define"
            if problem is not None:
                self.diag(
                    Code.DEFINE_PARAMETER,
                    f"parameter '{tok.text}' of Define '{name_tok.text}' {problem}",
                    tok.span,
                    expected="a new name for each parameter",
                    hint="rename the parameter (parameters may not shadow Defines or built-ins)",
                )
            names.append(tok.text)
            if self.at(","):
                self.next()
                continue
            self.expect(")", f"to close the parameters of Define '{name_tok.text}'")
            return tuple(names)

    # ---------------------------------------------------------------- material / layers
    def parse_material(self) -> tuple[A.Layer, ...]:
        kw = self.next()
        self.expect("(", "after Material")
        layers: list[A.Layer] = []
        if self.at(")"):
            self.diag(
                Code.EMPTY_MATERIAL,
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
                        Code.TRAILING_COMMA,
                        "trailing comma after the last layer",
                        tok.span,
                        expected="another Layer(...) or no comma",
                        hint=self.brackets.trailing_comma(self.i - 1),
                    )
                raise self._not_a_layer(tok)
            layers.append(self.parse_layer())
            if self.at(","):
                self.next()
                continue
            break
        if not self.at(")"):
            tok = self.peek()
            hint = "a ',' may be missing between layers" if tok.text == "Layer" else None
            raise self.fail(
                Code.EXPECTED_TOKEN,
                f"expected ',' or ')' after a layer but found {tok.describe()}",
                tok.span,
                expected="',' between layers or ')' to close Material",
                hint=hint or self.missing_close_hint(),
            )
        self.next()
        return tuple(layers)

    def _not_a_layer(self, tok: Token) -> Bail:
        """E025 where a ``Layer(`` should stand in Material(...)."""
        hint = hint_for(tok.text, ["Layer"]) if tok.kind == "IDENT" else None
        if tok.kind == "EOF":
            hint = self.brackets.ends_early(self.i)
        elif tok.kind == "OP" and tok.text == "(":
            hint = f"Material(...) holds only Layer(...) calls: remove the '(' at {tok.span.line}:{tok.span.col}"
        return self.fail(
            Code.MISPLACED_LAYER,
            f"expected Layer(...) but found {tok.describe()}",
            tok.span,
            expected="Layer(...)",
            hint=hint,
        )

    def parse_layer(self) -> A.Layer:
        kw = self.next()
        self.expect("(", "after Layer")
        alpha: A.Node | None = None
        if not self.at(")"):
            alpha = self.parse_expr()
            if self.at(","):
                raise self.fail(
                    Code.LAYER_ARGUMENTS,
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
                    Code.EXPECTED_TOKEN,
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
                    Code.UNKNOWN_CHANNEL,
                    f"unknown layer channel '.{name}'",
                    name_tok.span,
                    expected="one of " + ", ".join(CHANNELS),
                    hint=hint_for(name, CHANNELS) or channel_alias(name),
                )
                continue
            if len(args) != spec.arity:
                self.diag(
                    Code.ARGUMENT_COUNT,
                    f"{name}() expects {spec.arity} argument"
                    f"{'s' if spec.arity != 1 else ''}, got {len(args)}",
                    span,
                    expected=f".{name}({', '.join(spec.arg_names)})",
                )
                continue
            if name in chans:
                self.diag(
                    Code.CHANNEL_SET_TWICE,
                    f"channel '.{name}' is set twice; the last one wins",
                    name_tok.span,
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
                    Code.UNKNOWN_PARAMETER,
                    f"channel .{name_tok.text}() takes positional values, not '{tok.text}='",
                    tok.span,
                    expected="a value",
                    hint=f"write .{name_tok.text}(value)",
                )
            args.append(self.parse_expr())
            if self.at(","):
                comma = self.next()
                if self.at(")"):
                    raise self.trailing_comma(comma, "another argument")
                continue
            break
        self.expect(")", f"to close .{name_tok.text}(...)")
        return args


def _is_close(tok: Token) -> bool:
    return tok.kind == "OP" and tok.text == ")"


def parse_source(source: str) -> tuple[A.Program | None, list[Diagnostic]]:
    """Parse ``source`` into a Program (or ``None``) and the syntax/binding diagnostics."""
    p = Parser(source)
    program = p.parse()
    return program, p.diags


__all__ = ["Parser", "parse_source"]
