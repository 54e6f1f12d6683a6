"""Tokenizer for MatLoom program text, with line/column positions and ``#`` comments."""

from __future__ import annotations

import bisect
import math
import re
import sys
from dataclasses import dataclass

from matloom.lang.brackets import wrong_bracket_hint
from matloom.lang.codes import Code
from matloom.lang.diagnostics import Span

MAX_SOURCE_CHARS = 2_000_000
"""Inputs longer than this are refused before tokenizing (documented resource limit)."""

MAX_TOKENS = 250_000
"""Programs with more tokens than this are refused while lexing (documented resource limit). It
bounds the work spent on hostile input; the 20,000-node limit of the checker needs far fewer."""

MAX_NUMBER_DIGITS = 400
"""Numeric literals longer than this are refused (avoids pathological int/float conversions)."""

_NUMBER = re.compile(r"(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d*)?")
_TOKEN = re.compile(
    r"(?P<ws>[ \t\r\n\f\v]+)"
    r"|(?P<comment>#[^\n]*)"
    r"|(?P<num>(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d*)?)"
    r"|(?P<str>\"[^\"\n]*\"|'[^'\n]*')"
    r"|(?P<ident>[^\W\d]\w*)"
    r"|(?P<op>\*\*|[-+*/()=,.])"
)
"""One alternative per token class; a single regex keeps lexing linear and fast on huge inputs."""


@dataclass(frozen=True)
class Token:
    kind: str  # NUM, STR, IDENT, OP, EOF (COMMENT only in Lexer.comments)
    text: str
    span: Span
    value: object = None

    def describe(self) -> str:
        if self.kind == "EOF":
            return "end of input"
        if self.kind == "STR":
            return f"string {self.text}"
        return f"'{self.text}'"


class LexError(Exception):
    def __init__(
        self,
        code: Code,
        message: str,
        span: Span,
        expected: str | None = None,
        hint: str | None = None,
    ) -> None:
        super().__init__(message)
        self.code, self.message, self.span = code, message, span
        self.expected, self.hint = expected, hint


class Lexer:
    """Converts source text to tokens. Line starts are recorded so spans carry line/column."""

    def __init__(self, source: str) -> None:
        self.src = source
        self.line_starts = [0]
        self.comments: list[Token] = []  # COMMENT tokens (trailing blanks cut) of tokens()
        for m in re.finditer("\n", source):
            self.line_starts.append(m.end())

    def span(self, start: int, end: int) -> Span:
        line = bisect.bisect_right(self.line_starts, start) - 1
        return Span(start, end, line + 1, start - self.line_starts[line] + 1)

    def tokens(self) -> list[Token]:
        src, n, i = self.src, len(self.src), 0
        out: list[Token] = []
        self.comments = []
        while i < n:
            m = _TOKEN.match(src, i)
            if m is None:
                raise self._bad_character(i, out)
            kind, end = m.lastgroup, m.end()
            if len(out) >= MAX_TOKENS and kind not in ("ws", "comment"):
                raise LexError(
                    Code.SIZE_LIMIT,
                    f"program has more than {MAX_TOKENS} tokens",
                    self.span(i, end),
                    expected=f"at most {MAX_TOKENS} tokens",
                    hint="programs are normally a few hundred tokens long",
                )
            if kind == "num":
                out.append(self._number(i))
            elif kind == "str":
                out.append(Token("STR", m.group(), self.span(i, end), m.group()[1:-1]))
            elif kind == "ident":
                out.append(Token("IDENT", m.group(), self.span(i, end)))
            elif kind == "op":
                out.append(Token("OP", m.group(), self.span(i, end)))
            elif kind == "comment":  # kept aside: the parser's token stream has no comments
                text = m.group().rstrip()
                self.comments.append(Token("COMMENT", text, self.span(i, i + len(text))))
            i = end  # whitespace produces no token
        out.append(Token("EOF", "", self.span(n, n)))
        return out

    def _bad_character(self, i: int, before: list[Token]) -> LexError:
        c = self.src[i]
        if c in "\"'":
            return LexError(
                Code.UNTERMINATED_STRING,
                "unterminated string literal",
                self.span(i, i + 1),
                expected=f"a closing {c} on the same line",
            )
        hint = None
        if c == ";":
            hint = "statements are not separated by ';' — remove it"
        elif c in "[]{}":
            hint = wrong_bracket_hint(before, c, self.span(i, i + 1))
        elif c == "`":
            hint = "remove Markdown code fences around the program"
        return LexError(
            Code.BAD_CHARACTER,
            f"unexpected character {c!r}",
            self.span(i, i + 1),
            expected="a number, name, string, operator or parenthesis",
            hint=hint,
        )

    def _number(self, i: int) -> Token:
        m = _NUMBER.match(self.src, i)
        assert m is not None
        text = m.group()
        span = self.span(i, m.end())
        if len(text) > MAX_NUMBER_DIGITS:
            raise LexError(
                Code.BAD_NUMBER,
                "numeric literal is too long",
                span,
                expected=f"at most {MAX_NUMBER_DIGITS} characters",
            )
        mant, _, exp = text.lower().partition("e")
        if "e" in text.lower() and not exp.lstrip("+-"):
            raise LexError(
                Code.BAD_NUMBER,
                f"malformed number {text!r}: exponent has no digits",
                span,
                expected="digits after 'e', as in 1e-3",
            )
        value = _literal_value(text)
        if value is None:
            raise LexError(
                Code.BAD_NUMBER,
                f"number {_abbreviate(text)} is too large",
                span,
                expected=f"a finite number (at most about {sys.float_info.max:.3g})",
            )
        return Token("NUM", text, span, value)


def _literal_value(text: str) -> int | float | None:
    """The value of a numeric literal, or ``None`` if it is outside the float range.

    Integer literals stay ``int``, but only when they also convert to a float: every evaluator
    computes in floating point, so ``10**309`` written out in digits is as unusable as ``1e309``.
    """
    if "." in text or "e" in text.lower():
        value: int | float = float(text)
        return None if math.isinf(value) else value
    value = int(text)
    try:
        float(value)
    except OverflowError:
        return None
    return value


def as_float(value: int | float) -> float:
    """``float(value)``, except that an integer beyond the float range gives +-inf.

    Constant arithmetic on integer literals stays exact (``int``) and can outgrow the float
    range (``10**200 * 10**200``); every consumer computes in floating point, where such a
    value is infinite, so callers see it as non-finite instead of an ``OverflowError``.
    """
    try:
        return float(value)
    except OverflowError:
        return math.inf if value > 0 else -math.inf


def _abbreviate(text: str, keep: int = 12) -> str:
    """``text`` quoted; a long literal's middle is elided: ``'999...999' (350 characters)``."""
    if len(text) <= 2 * keep + 3:
        return repr(text)
    return f"'{text[:keep]}...{text[-keep:]}' ({len(text)} characters)"
