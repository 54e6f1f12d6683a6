"""The parser's base: token cursor, diagnostics and the bracket hints of syntax errors.

:class:`matloom.lang.parser.Parser` builds on it (statements, Material, Layers) through
:class:`matloom.lang.parse_expr.ExpressionParser` (expressions and calls).
"""

from __future__ import annotations

from matloom.lang import ast as A
from matloom.lang.brackets import Brackets, analyse, construct, pos
from matloom.lang.diagnostics import Diagnostic, Reporter, Span
from matloom.lang.lexer import Lexer, Token


class _Bail(Exception):
    """Abort the current statement after a syntax error has been recorded."""


class ParserBase(Reporter):
    """Token cursor and diagnostics of one parse."""

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
        self.current_define: str | None = None
        self.material_started = False
        self._brackets: Brackets | None = None

    @property
    def brackets(self) -> Brackets:
        """The bracket analysis of the tokens, made on first use (only errors need it)."""
        if self._brackets is None:
            self._brackets = analyse(self.toks)
        return self._brackets

    # ---------------------------------------------------------------- diagnostics

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
        if text == ")":
            hint = self.missing_close_hint()
        elif text == "," and tok.text == ")":
            hint = "an argument is missing"
        raise self.fail(
            "E010",
            f"expected '{text}'{where} but found {tok.describe()}",
            tok.span,
            expected=f"'{text}'",
            hint=hint,
        )

    def missing_close_hint(self) -> str | None:
        """Hint for a ``)`` expected at the current token: the construct left open, or a
        missing ``,`` when the parentheses balance."""
        tok, k = self.peek(), min(self.i, len(self.toks) - 1)
        hint = self.brackets.missing_close(k)
        if hint is None and tok.kind in ("NUM", "IDENT", "STR"):
            hint = "a ',' may be missing between arguments"
            o = self.brackets.open_before[k]
            if o >= 0:
                name, first = construct(self.toks, o)
                hint = (
                    f"a ',' may be missing between the arguments of {name} opened at {pos(first)}"
                )
        return hint

    def span_from(self, start: Span) -> Span:
        prev = self.toks[self.i - 1] if self.i > 0 else self.peek()
        return Span(start.start, max(start.end, prev.span.end), start.line, start.col)


def tree_depth(node: A.Node) -> int:
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


def join_spans(left: A.Node, right: A.Node, op: Span) -> Span:
    ls, rs = node_span(left, op), node_span(right, op)
    return Span(ls.start, max(rs.end, op.end), ls.line, ls.col)
