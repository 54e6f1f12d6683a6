"""Tokenizer for MatLoom program text, with line/column positions and ``#`` comments."""

from __future__ import annotations

import re
from dataclasses import dataclass

from matloom.lang.diagnostics import Span

MAX_SOURCE_CHARS = 2_000_000
"""Inputs longer than this are refused before tokenizing (documented resource limit)."""

MAX_NUMBER_DIGITS = 400
"""Numeric literals longer than this are refused (avoids pathological int/float conversions)."""

_NUMBER = re.compile(r"(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d*)?")
_IDENT = re.compile(r"[^\W\d]\w*")
_OPS = ("**", "+", "-", "*", "/", "(", ")", "=", ",", ".")


@dataclass(frozen=True)
class Token:
    kind: str  # NUM, STR, IDENT, OP, EOF
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
    def __init__(self, code: str, message: str, span: Span, expected: str | None = None,
                 hint: str | None = None) -> None:
        super().__init__(message)
        self.code, self.message, self.span = code, message, span
        self.expected, self.hint = expected, hint


class Lexer:
    """Converts source text to tokens. Line starts are recorded so spans carry line/column."""

    def __init__(self, source: str) -> None:
        self.src = source
        self.line_starts = [0]
        for m in re.finditer("\n", source):
            self.line_starts.append(m.end())

    def span(self, start: int, end: int) -> Span:
        import bisect

        line = bisect.bisect_right(self.line_starts, start) - 1
        return Span(start, end, line + 1, start - self.line_starts[line] + 1)

    def tokens(self) -> list[Token]:
        src, n, i = self.src, len(self.src), 0
        out: list[Token] = []
        while i < n:
            c = src[i]
            if c in " \t\r\n\f\v":
                i += 1
                continue
            if c == "#":  # comment to end of line
                j = src.find("\n", i)
                i = n if j < 0 else j
                continue
            if c.isdigit() or (c == "." and i + 1 < n and src[i + 1].isdigit()):
                out.append(self._number(i))
                i = out[-1].span.end
                continue
            if c in "\"'":
                j = src.find(c, i + 1)
                nl = src.find("\n", i + 1)
                if j < 0 or (0 <= nl < j):
                    raise LexError("E002", "unterminated string literal", self.span(i, i + 1),
                                   expected=f"a closing {c} on the same line")
                out.append(Token("STR", src[i : j + 1], self.span(i, j + 1), src[i + 1 : j]))
                i = j + 1
                continue
            m = _IDENT.match(src, i)
            if m:
                out.append(Token("IDENT", m.group(), self.span(i, m.end())))
                i = m.end()
                continue
            for op in _OPS:
                if src.startswith(op, i):
                    out.append(Token("OP", op, self.span(i, i + len(op))))
                    i += len(op)
                    break
            else:
                hint = None
                if c == ";":
                    hint = "statements are not separated by ';' — remove it"
                elif c in "[]{}":
                    hint = "only round parentheses are used in MatLoom programs"
                elif c == "`":
                    hint = "remove Markdown code fences around the program"
                raise LexError("E001", f"unexpected character {c!r}", self.span(i, i + 1),
                               expected="a number, name, string, operator or parenthesis",
                               hint=hint)
        out.append(Token("EOF", "", self.span(n, n)))
        return out

    def _number(self, i: int) -> Token:
        m = _NUMBER.match(self.src, i)
        assert m is not None
        text = m.group()
        span = self.span(i, m.end())
        if len(text) > MAX_NUMBER_DIGITS:
            raise LexError("E003", "numeric literal is too long", span,
                           expected=f"at most {MAX_NUMBER_DIGITS} characters")
        mant, _, exp = text.lower().partition("e")
        if "e" in text.lower() and not exp.lstrip("+-"):
            raise LexError("E003", f"malformed number {text!r}: exponent has no digits", span,
                           expected="digits after 'e', as in 1e-3")
        if "." in text or "e" in text.lower():
            value: int | float = float(text)
        else:
            value = int(text)
        if isinstance(value, float) and value == float("inf"):
            raise LexError("E003", f"number {text!r} is too large", span,
                           expected="a finite number")
        return Token("NUM", text, span, value)
