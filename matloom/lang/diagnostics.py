"""Structured diagnostics: stable code, position, caret excerpt, expectation and hint.

The codes, their severities and meanings are the table of :mod:`matloom.lang.codes`.

The formatted text of a diagnostic is exactly what the repair loop sends back to a model.
"""

from __future__ import annotations

import difflib
import enum
from collections.abc import Iterable
from dataclasses import dataclass
from typing import TYPE_CHECKING

from matloom.lang.excerpt import caret_excerpt

if TYPE_CHECKING:
    from matloom.lang.codes import Code


class Severity(enum.Enum):
    ERROR = "error"
    WARNING = "warning"


@dataclass(frozen=True)
class Span:
    """A half-open character range [start, end) of the source with the 1-based line/column of start."""

    start: int
    end: int
    line: int
    col: int


NO_SPAN = Span(0, 0, 1, 1)


@dataclass(frozen=True)
class Diagnostic:
    """One problem found in a program."""

    code: str
    message: str
    span: Span
    severity: Severity = Severity.ERROR
    expected: str | None = None
    hint: str | None = None
    excerpt: str = ""

    @property
    def line(self) -> int:
        return self.span.line

    @property
    def column(self) -> int:
        return self.span.col

    @property
    def is_error(self) -> bool:
        return self.severity is Severity.ERROR

    def format(self, filename: str = "<program>") -> str:
        """Multi-line human/LLM readable text: location, message, caret excerpt, expectation, hint."""
        head = f"{filename}:{self.line}:{self.column}: {self.severity.value} {self.code}: {self.message}"
        lines = [head]
        if self.excerpt:
            lines.append(self.excerpt)
        if self.expected:
            lines.append(f"  expected: {self.expected}")
        if self.hint:
            lines.append(f"  hint: {self.hint}")
        return "\n".join(lines)

    def to_dict(self) -> dict[str, object]:
        return {
            "code": self.code,
            "severity": self.severity.value,
            "message": self.message,
            "line": self.line,
            "column": self.column,
            "expected": self.expected,
            "hint": self.hint,
            "excerpt": self.excerpt,
        }

    def __str__(self) -> str:
        return self.format()


def did_you_mean(word: str, candidates: Iterable[str]) -> str | None:
    """The closest candidate to ``word`` (case-insensitive first), or ``None``."""
    cands = list(dict.fromkeys(candidates))
    lower = {c.lower(): c for c in cands}
    if word.lower() in lower and lower[word.lower()] != word:
        return lower[word.lower()]
    match = difflib.get_close_matches(word, cands, n=1, cutoff=0.6)
    if match:
        return match[0]
    match = difflib.get_close_matches(word.lower(), list(lower), n=1, cutoff=0.6)
    return lower[match[0]] if match else None


def hint_for(word: str, candidates: Iterable[str], what: str = "") -> str | None:
    guess = did_you_mean(word, candidates)
    if guess is None:
        return None
    return f"did you mean `{guess}`{what}?"


class ProgramError(ValueError):
    """Raised when a program has errors; carries every diagnostic found."""

    def __init__(self, diagnostics: list[Diagnostic], source: str = "") -> None:
        self.diagnostics = diagnostics
        self.source = source
        errors = [d for d in diagnostics if d.is_error]
        super().__init__(format_diagnostics(errors or diagnostics))


def format_diagnostics(diags: Iterable[Diagnostic], filename: str = "<program>") -> str:
    return "\n\n".join(d.format(filename) for d in diags)


__all__ = [
    "NO_SPAN",
    "Diagnostic",
    "ProgramError",
    "Severity",
    "Span",
    "caret_excerpt",
    "did_you_mean",
    "format_diagnostics",
    "hint_for",
]


class Reporter:
    """Collects diagnostics over one source text (the parser's and the checker's base)."""

    src: str
    diags: list[Diagnostic]

    def diag(
        self,
        code: Code,
        msg: str,
        span: Span,
        expected: str | None = None,
        hint: str | None = None,
    ) -> None:
        """Record one diagnostic of ``code`` (which sets its severity) with its caret excerpt
        of :attr:`src`."""
        self.diags.append(code.diagnostic(msg, span, expected, hint, caret_excerpt(self.src, span)))
