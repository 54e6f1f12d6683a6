"""Bracket analysis on the token stream: which parenthesis is extra or missing.

The parser asks this module for the hint of every bracket-related error. Hints name the
construct whose parenthesis is extra or missing (``Define(dash, …``, ``Layer(``,
``.roughness(``, ``Min(`` or a bare ``(``) and where it opened, as ``line:column``, e.g.
"the `)` at 14:370 has no opening; `Define(dash, …` opened at 14:1 was already closed at 14:352".

The tokens are cut into statements where the parser resynchronises after an error (a ``View(``,
``Define(`` or ``Material(`` that starts a line), and each statement's parentheses are matched
with a stack. Inside a ``Material(...)`` with more ``(`` than ``)``, a ``Layer(`` or a
``.channel(`` only ever stands directly inside the Material, so any parenthesis still open there
is taken as the one never closed: the usual slip is a ``)`` missing at the end of a channel's
value, and the hint then points there instead of at the end of the program.

The analysis is linear in the number of tokens and runs only once the parser has met a
bracket-related error (:meth:`matloom.lang.parse_base.ParserBase.brackets`); each hint after
that takes constant time, or a binary search.
"""

from __future__ import annotations

import bisect
from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from matloom.lang.diagnostics import Span
    from matloom.lang.lexer import Token

STATEMENTS = ("View", "Define", "Material")
"""The statements whose keyword, first on a line, starts a new statement for the analysis."""

ROUND_ONLY = "only round parentheses are used in MatLoom programs"


def _is_op(tok: Token, text: str) -> bool:
    return tok.kind == "OP" and tok.text == text


def pos(tok: Token) -> str:
    """``line:column`` of a token."""
    return f"{tok.span.line}:{tok.span.col}"


def starts_statement(toks: Sequence[Token], k: int) -> bool:
    """Whether token ``k`` is a statement keyword that starts a line and opens a ``(``."""
    tok = toks[k]
    if tok.kind != "IDENT" or tok.text not in STATEMENTS:
        return False
    if k + 1 >= len(toks) or not _is_op(toks[k + 1], "("):
        return False
    return k == 0 or toks[k - 1].span.line < tok.span.line


def construct(toks: Sequence[Token], o: int) -> tuple[str, Token]:
    """How to name the construct that the ``(`` at index ``o`` opens, and its first token.

    ``Define(dash, …`` for a Define (its name tells which one), ``.roughness(`` for a layer
    channel, ``Min(`` for any other call and `` `(` `` for a parenthesised group."""
    prev = toks[o - 1] if o > 0 else None
    if prev is None or prev.kind != "IDENT":
        return "`(`", toks[o]
    if o >= 2 and _is_op(toks[o - 2], "."):
        return f"`.{prev.text}(`", toks[o - 2]
    if prev.text == "Define" and o + 2 < len(toks):
        name, comma = toks[o + 1], toks[o + 2]
        if name.kind == "IDENT" and _is_op(comma, ","):
            return f"`Define({name.text}, …`", prev
    return f"`{prev.text}(`", prev


def closing_context(toks: Sequence[Token], o: int) -> str:
    """The parser's words for what the ``)`` of the ``(`` at ``o`` closes: ``Min(...)``,
    ``.roughness(...)`` or ``'('``."""
    prev = toks[o - 1] if o > 0 else None
    if prev is None or prev.kind != "IDENT":
        return "'('"
    dot = "." if o >= 2 and _is_op(toks[o - 2], ".") else ""
    return f"{dot}{prev.text}(...)"


def _opened(toks: Sequence[Token], o: int) -> str:
    name, first = construct(toks, o)
    return f"{name} opened at {pos(first)}"


def _layer_level(toks: Sequence[Token], k: int) -> bool:
    """Whether token ``k`` starts a ``Layer(`` or a ``.channel(``."""
    tok, n = toks[k], len(toks)
    if tok.kind == "IDENT" and tok.text == "Layer":
        return k + 1 < n and _is_op(toks[k + 1], "(")
    if _is_op(tok, "."):
        return k + 2 < n and toks[k + 1].kind == "IDENT" and _is_op(toks[k + 2], "(")
    return False


@dataclass
class Brackets:
    """The parentheses of one token stream, matched statement by statement."""

    toks: Sequence[Token]
    starts: list[int] = field(default_factory=list)
    """Index of the first token of every statement, ascending (``starts[0] == 0``)."""
    closer: dict[int, int] = field(default_factory=dict)
    """Index of each matched ``(`` -> index of its ``)``."""
    unclosed: dict[int, int] = field(default_factory=dict)
    """Index of each ``(`` never closed -> index of the token where it was given up: a cut
    ``Layer(``/``.channel(``, the next statement or the end of input."""
    extra: dict[int, int] = field(default_factory=dict)
    """Index of each ``)`` with no ``(`` -> the ``(`` of the last statement (``View(``,
    ``Define(``, ``Material(``) closed before it, else the last outermost ``(`` closed before
    it, or -1."""
    extras: list[int] = field(default_factory=list)
    """The keys of :attr:`extra`, ascending."""
    open_before: list[int] = field(default_factory=list)
    """For each token, the innermost ``(`` still open just before it, matching every ``)``
    with the latest ``(`` as the parser does (-1: none). At a statement start it is the one
    left open by the statement before."""
    balance: dict[int, int] = field(default_factory=dict)
    """Statement start -> its count of ``(`` minus its count of ``)``."""

    def statement_of(self, k: int) -> tuple[int, int]:
        """``[start, end)`` token range of the statement holding token ``k``."""
        i = bisect.bisect_right(self.starts, k) - 1
        end = self.starts[i + 1] if i + 1 < len(self.starts) else len(self.toks)
        return self.starts[i], end

    def _gave_up_at_end(self, stop: int) -> bool:
        return self.toks[stop].kind == "EOF" or starts_statement(self.toks, stop)

    # ------------------------------------------------------------------ hints
    def missing_close(self, k: int) -> str | None:
        """Hint for "expected ')'" at token ``k``, or ``None`` when the parentheses of the
        statement balance (the ``)`` is then not what is missing)."""
        toks = self.toks
        o = self.open_before[k]
        if o < 0:
            return None
        found = toks[k]
        if construct(toks, o)[0] == "`(`" and _is_op(found, ","):
            return (
                f"the `(` at {pos(toks[o])} groups one expression and cannot hold a ','; "
                "remove it if it is extra, or write the name of the function it should call"
            )
        stop = self.unclosed.get(o)
        if stop is not None:
            if not self._gave_up_at_end(stop):
                return f"{_opened(toks, o)} is not closed before {_at(toks, stop)}"
            return f"{_opened(toks, o)} is never closed"
        start, _ = self.statement_of(max(0, k - 1))
        more = self.balance.get(start, 0)
        if more <= 0:
            return None
        return (
            f"a ')' may be missing before {found.describe()}, or a '(' may be extra: "
            f"{_opened(toks, o)} is still open here, and its statement has {more} more '(' "
            "than ')'"
        )

    def forced_close(self, k: int) -> int | None:
        """The ``(`` still open before token ``k`` (a ``Layer(`` or a statement keyword in an
        expression) when the analysis gives it up at ``k``: that ``)`` is missing."""
        o = self.open_before[k]
        if o >= 0 and self.unclosed.get(o) == k:
            return o
        return None

    def extra_close(self, k: int) -> str | None:
        """Hint for a ``)`` at token ``k`` that the parser did not expect."""
        prev = self.extra.get(k)
        if prev is None:
            return None
        here = f"the `)` at {pos(self.toks[k])} has no opening"
        if prev < 0:
            return f"{here} '('"
        closed = pos(self.toks[self.closer[prev]])
        return f"{here}; {_opened(self.toks, prev)} was already closed at {closed}"

    def closed_early(self, k: int) -> str | None:
        """Hint for an unexpected token ``k`` after a statement that a ``)`` closed too early:
        a ``)`` with no opening follows later in the same statement."""
        _, end = self.statement_of(k)
        i = bisect.bisect_left(self.extras, k)
        if i == len(self.extras) or self.extras[i] >= end:
            return None
        x = self.extras[i]
        prev = self.extra[x]
        if prev < 0 or self.closer[prev] > k:
            return None
        closed = pos(self.toks[self.closer[prev]])
        return (
            f"{_opened(self.toks, prev)} was already closed at {closed}, so the `)` at "
            f"{pos(self.toks[x])} has no opening: one ')' up to {closed} is extra "
            "(or a '(' is missing)"
        )

    def ends_early(self, k: int) -> str | None:
        """Hint for the end of input (token ``k``) where an expression was expected."""
        o = self.open_before[k]
        if o < 0:
            return None
        start, _ = self.statement_of(max(0, k - 1))
        more = self.balance.get(start, 0)
        also = f" ({more} '(' are left open)" if more > 1 else ""
        return f"the program ends early: {_opened(self.toks, o)} is never closed{also}"

    def trailing_comma(self, comma: int) -> str | None:
        """Hint for a ``,`` at token ``comma`` followed by the ``)`` of its call."""
        o = self.open_before[comma]
        if o < 0:
            return None
        return (
            f"remove the ',' at {pos(self.toks[comma])}: the ')' after it closes "
            f"{_opened(self.toks, o)}"
        )


def _at(toks: Sequence[Token], k: int) -> str:
    """A ``Layer(``/``.channel(`` (or any token) at index ``k``, with its position."""
    tok = toks[k]
    if _is_op(tok, ".") and k + 1 < len(toks):
        return f"`.{toks[k + 1].text}(` at {pos(tok)}"
    if tok.kind == "IDENT":
        return f"`{tok.text}(` at {pos(tok)}"
    return f"{tok.describe()} at {pos(tok)}"


def analyse(toks: Sequence[Token]) -> Brackets:
    """Match the parentheses of ``toks`` (ending with the EOF token), statement by statement."""
    n = len(toks)
    b = Brackets(toks, open_before=[-1] * n)
    b.starts = [0] + [k for k in range(1, n) if starts_statement(toks, k)]
    for i, start in enumerate(b.starts):
        end = b.starts[i + 1] if i + 1 < len(b.starts) else n
        left_open = _match_statement(b, start, end)
        if end < n:
            b.open_before[end] = left_open
    b.extras = sorted(b.extra)
    return b


def _match_statement(b: Brackets, start: int, end: int) -> int:
    """Match the parentheses of tokens ``[start, end)``; returns the innermost ``(`` left open
    (by plain matching) or -1."""
    toks = b.toks
    opens = sum(1 for k in range(start, end) if _is_op(toks[k], "("))
    closes = sum(1 for k in range(start, end) if _is_op(toks[k], ")"))
    b.balance[start] = opens - closes
    material = start + 1 < len(toks) and toks[start].text == "Material"
    material = material and toks[start].kind == "IDENT" and _is_op(toks[start + 1], "(")
    cut = material and opens > closes
    stack: list[int] = []  # matching with the Layer/.channel rule
    plain: list[int] = []  # every ')' closes the latest '(' (what the parser does)
    last_top = last_statement = -1
    for k in range(start, end):
        if k > start:
            b.open_before[k] = plain[-1] if plain else -1
        if cut and len(stack) > 1 and stack[0] == start + 1 and _layer_level(toks, k):
            for o in stack[1:]:
                b.unclosed[o] = k
            del stack[1:]
        tok = toks[k]
        if tok.kind != "OP":
            continue
        if tok.text == "(":
            stack.append(k)
            plain.append(k)
        elif tok.text == ")":
            if plain:
                plain.pop()
            if stack:
                o = stack.pop()
                b.closer[o] = k
                if not stack:
                    last_top = o
                    if o > 0 and toks[o - 1].text in STATEMENTS and toks[o - 1].kind == "IDENT":
                        last_statement = o
            else:
                b.extra[k] = last_statement if last_statement >= 0 else last_top
    stop = min(end, len(toks) - 1)
    for o in stack:
        b.unclosed[o] = stop
    return plain[-1] if plain else -1


def wrong_bracket_hint(toks: Sequence[Token], char: str, span: Span) -> str:
    """Hint for a ``[``, ``]``, ``{`` or ``}`` at ``span``, given the tokens before it."""
    at = f"{span.line}:{span.col}"
    if char in "[{":
        closing = "]" if char == "[" else "}"
        return f"{ROUND_ONLY}: write '(' instead of `{char}` and ')' instead of its `{closing}`"
    depth = 0
    for o in range(len(toks) - 1, -1, -1):
        tok = toks[o]
        if _is_op(tok, ")"):
            depth += 1
        elif _is_op(tok, "("):
            if depth == 0:
                return (
                    f"{ROUND_ONLY}: the `{char}` at {at} cannot close {_opened(toks, o)}; write ')'"
                )
            depth -= 1
        elif starts_statement(toks, o) and depth == 0:
            break
    return f"{ROUND_ONLY}: remove the `{char}` at {at}, nothing is open there"
