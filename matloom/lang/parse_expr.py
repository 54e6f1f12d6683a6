"""Expressions and calls of the grammar (see :mod:`matloom.lang.parser`):

expr     := muldiv {("+"|"-") muldiv}
muldiv   := unary {("*"|"/") unary}
unary    := ("-"|"+") power | power
power    := atom ["**" unary]                 (right-associative)
atom     := NUM | STRING | IDENT "(" [arg {"," arg}] ")" | IDENT | "(" expr ")"
arg      := IDENT "=" expr | expr
"""

from __future__ import annotations

from matloom.lang import ast as A
from matloom.lang.aliases import name_alias
from matloom.lang.binding import bind_call
from matloom.lang.brackets import STATEMENTS, closing_context
from matloom.lang.codes import Code
from matloom.lang.diagnostics import Span, hint_for
from matloom.lang.lexer import Token
from matloom.lang.parse_base import Bail, ParserBase, join_spans, node_span, tree_depth
from matloom.vocab import CONSTANTS, FUNCTIONS, LITERALS

MAX_NESTING = 100
"""Maximum expression nesting depth, and maximum depth of an expression tree (documented limit).

It bounds the recursion of the parser and of every recursive tree walker (checker, printer,
evaluator), so hostile inputs such as ``((((...`` or ``1+1+...+1`` fail with E070 instead of
exhausting Python's stack (the parser needs about 6 frames per nesting level)."""

KEYWORDS = ("View", "Define", "Material", "Layer")
"""The statement names (and Layer): never names of values or functions."""


class ExpressionParser(ParserBase):
    """Expression parsing (:meth:`parse_expr`); :class:`matloom.lang.parser.Parser` adds the
    statements, :func:`matloom.lang.parse_view.parse_view` the View."""

    def parse_expr(self) -> A.Node:
        self.depth += 1
        try:
            if self.depth > MAX_NESTING:
                raise self.fail(
                    Code.SIZE_LIMIT,
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
                left = A.BinOp(op.text, left, right, join_spans(left, right, op.span))
            if self.depth == 1 and tree_depth(left) > MAX_NESTING:  # long operator chains
                raise self.fail(
                    Code.SIZE_LIMIT,
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
                Code.SIZE_LIMIT,
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
            left = A.BinOp(op.text, left, right, join_spans(left, right, op.span))
        return left

    def parse_unary(self) -> A.Node:
        tok = self.peek()
        if tok.kind == "OP" and tok.text in ("-", "+"):
            self.next()
            nxt = self.peek()
            if nxt.kind == "OP" and nxt.text in ("-", "+"):
                raise self.fail(
                    Code.EXPECTED_EXPRESSION,
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
                        Code.SIZE_LIMIT,
                        f"expression nested deeper than {MAX_NESTING} levels",
                        op.span,
                        expected="a shallower expression",
                    )
                exp = self.parse_unary()
            finally:
                self.depth -= 1
            return A.BinOp("**", base, exp, join_spans(base, exp, op.span))
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
                self._check_not_cut(tok)
                return self.parse_call()
            return self.parse_name()
        if tok.kind == "EOF":
            raise self.fail(
                Code.EXPECTED_EXPRESSION,
                "expected an expression but found end of input",
                tok.span,
                expected="a number, name, call or '('",
                hint=self.brackets.ends_early(self.i)
                or "the program ends early; check for unclosed parentheses",
            )
        hint = "an argument is missing" if tok.text in (",", ")") else None
        if tok.text == ".":
            hint = "write numbers with a digit after the point, e.g. 0.5"
        raise self.fail(
            Code.EXPECTED_EXPRESSION,
            f"expected an expression but found {tok.describe()}",
            tok.span,
            expected="a number, name, call or '('",
            hint=hint,
        )

    def _check_not_cut(self, tok: Token) -> None:
        """A ``Layer(`` or a statement in an expression, where the bracket analysis gives up
        the open parenthesis: report the missing ``)`` rather than an unknown function."""
        if tok.text != "Layer" and tok.text not in STATEMENTS:
            return
        o = self.brackets.forced_close(self.i)
        if o is None:
            return
        raise self.fail(
            Code.EXPECTED_TOKEN,
            f"expected ')' to close {closing_context(self.toks, o)} but found '{tok.text}'",
            tok.span,
            expected="')'",
            hint=self.brackets.missing_close(self.i),
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
                Code.FUNCTION_NOT_CALLED,
                f"'{name}' is a function — call it as {name}()",
                tok.span,
                expected=f"{name}(...)",
            )
            return A.Ref(name, tok.span)
        if name in self.params:  # a parameter of the Define being parsed
            return A.Ref(name, tok.span)
        if name in self.macros:
            params = ", ".join(self.macros[name])
            self.diag(
                Code.DEFINE_ARGUMENTS,
                f"Define '{name}' takes parameters ({params}): call it as {name}(...)",
                tok.span,
                expected=f"{name}({params})",
            )
            return A.Ref(name, tok.span)
        if name in self.defined or name in self.broken_defines:
            return A.Ref(name, tok.span)
        if name == self.current_define:
            self.diag(
                Code.DEFINE_ORDER,
                f"Define '{name}' refers to itself",
                tok.span,
                expected="only earlier Defines",
                hint="Defines form an acyclic graph",
            )
        elif name in self.all_define_names:
            self.diag(
                Code.DEFINE_ORDER,
                f"'{name}' is used before its Define",
                tok.span,
                expected="only Defines that appear earlier in the program",
                hint=f"move Define({name}, ...) above this line",
            )
        else:
            hint = hint_for(name, [*self.defined, *CONSTANTS]) or name_alias(name)
            if hint is None and name in KEYWORDS:
                hint = f"{name}(...) is a statement, not an expression"
            self.diag(
                Code.UNKNOWN_NAME,
                f"unknown name '{name}'",
                tok.span,
                expected="an earlier Define, pi, e, or a function call",
                hint=hint,
            )
        return A.Ref(name, tok.span)

    def parse_call(self) -> A.Node:
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
                        raise self.trailing_comma(comma, "another argument or no comma")
                    continue
                break
        self.expect(")", f"to close {name_tok.text}(...)")
        span = self.span_from(name_tok.span)
        if name_tok.text not in FUNCTIONS and self._define_call(name_tok):
            if name_tok.text not in self.macros:  # reported: read as the bare name
                return A.Ref(name_tok.text, span)
            return self._bind_define(name_tok, raw, span)
        return bind_call(self, name_tok, raw, span)

    def _define_call(self, name_tok: Token) -> bool:
        """``name(...)`` names a Define (language 3): a parameterised one is bound by
        :meth:`_bind_define`; any other is reported here (and read as a bare name)."""
        name = name_tok.text
        if name in self.macros:
            return True
        if name in self.defined or name in self.params:
            self.diag(
                Code.DEFINE_ARGUMENTS,
                f"'{name}' takes no arguments: it is "
                + ("a parameter" if name in self.params else "a Define without parameters"),
                name_tok.span,
                expected=name,
                hint=f"use it by its bare name, or write Define({name}(a, ...), ...) to give "
                "it parameters",
            )
            return True
        if name == self.current_define or name in self.all_define_names:
            where = "refers to itself" if name == self.current_define else "is used before it"
            self.diag(
                Code.DEFINE_ORDER,
                f"Define '{name}' {where}",
                name_tok.span,
                expected="only earlier Defines",
                hint="Defines form an acyclic graph: no recursion, move the Define above its "
                "first use",
            )
            return True
        return False

    def _bind_define(
        self, name_tok: Token, raw: list[tuple[Token | None, A.Node, Span]], span: Span
    ) -> A.Node:
        """A use ``name(x, y)`` of a parameterised Define: a Call whose args bind its
        parameters (positionally or by name), each exactly once."""
        name = name_tok.text
        params = self.macros.get(name, ())
        bound: dict[str, A.Arg] = {}
        pos = 0
        for key, value, aspan in raw:
            if key is None:
                pname = params[pos] if pos < len(params) else None
                pos += 1
            else:
                pname = key.text if key.text in params else None
            if pname is None or pname in bound:
                what = "too many arguments" if key is None else f"no parameter '{key.text}'"
                if pname is not None:
                    what = f"'{pname}' given twice"
                self.diag(
                    Code.DEFINE_ARGUMENTS,
                    f"{name}(...): {what}",
                    aspan,
                    expected=f"{name}({', '.join(params)})",
                )
                continue
            bound[pname] = A.Arg(pname, value, key is not None, aspan)
        missing = [p for p in params if p not in bound]
        if missing and name in self.macros:
            self.diag(
                Code.DEFINE_ARGUMENTS,
                f"{name}(...) is missing argument{'s' if len(missing) > 1 else ''}: "
                + ", ".join(missing),
                span,
                expected=f"{name}({', '.join(params)})",
            )
        args = tuple(bound[p] for p in params if p in bound)
        return A.Call(name, args, (), span)

    def trailing_comma(self, comma: Token, expected: str) -> Bail:
        """E013 at ``comma``, the token before the current ``)``."""
        return self.fail(
            Code.TRAILING_COMMA,
            "trailing comma in argument list",
            comma.span,
            expected=expected,
            hint=self.brackets.trailing_comma(self.i - 1),
        )
