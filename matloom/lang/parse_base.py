"""The parser's base: token cursor, diagnostics, the names in scope and the bracket hints of
syntax errors.

The parser is built in layers, each module importing only the public names of the ones before:

1. here, :class:`ParserBase` (the cursor over the tokens, :meth:`ParserBase.fail` raising
   :class:`Bail`) and the span helpers;
2. :mod:`matloom.lang.parse_expr`: :class:`~matloom.lang.parse_expr.ExpressionParser`
   (expressions and calls; arguments bound by :func:`matloom.lang.binding.bind_call`);
3. :mod:`matloom.lang.parse_view`: the View statement, a function of an expression parser;
4. :mod:`matloom.lang.parser`: :class:`~matloom.lang.parser.Parser` (statements, Material,
   Layers, recovery) and :func:`~matloom.lang.parser.parse_source`.
"""

from __future__ import annotations

from matloom.lang import ast as A
from matloom.lang.brackets import Brackets, analyse, construct, pos
from matloom.lang.codes import Code
from matloom.lang.diagnostics import Diagnostic, Reporter, Span
from matloom.lang.lexer import Lexer, Token


class Bail(Exception):
    """Abort the current statement after a syntax error has been recorded (raised by
    :meth:`ParserBase.fail`; the statement loop of the parser resynchronises on it)."""


class ParserBase(Reporter):
    """Token cursor, diagnostics and names in scope of one parse."""

    def __init__(self, source: str) -> None:
        self.src = source
        self.lexer = Lexer(source)
        #: The tokens (set by the statement loop) and the index of the current one.
        self.toks: list[Token] = []
        self.i = 0
        #: Expression nesting depth (bounded by ``parse_expr.MAX_NESTING``).
        self.depth = 0
        self.diags: list[Diagnostic] = []
        #: The Defines parsed so far (an ordered set: O(1) lookups on huge inputs), every
        #: Define name in the program, the Defines whose statement failed (their uses are not
        #: reported again) and the Define whose expression is being parsed.
        self.defined: dict[str, None] = {}
        self.all_define_names: set[str] = set()
        self.broken_defines: set[str] = set()
        self.current_define: str | None = None
        #: Language 3: the parameterised Defines parsed so far (name -> parameters) and the
        #: parameters of the Define whose expression is being parsed.
        self.macros: dict[str, tuple[str, ...]] = {}
        self.params: tuple[str, ...] = ()
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
        self, code: Code, msg: str, span: Span, expected: str | None = None, hint: str | None = None
    ) -> Bail:
        """Record an error and return the :class:`Bail` that the caller raises."""
        self.diag(code, msg, span, expected, hint)
        return Bail()

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
            Code.EXPECTED_TOKEN,
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
