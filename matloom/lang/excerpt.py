"""Caret excerpts: the offending source line (and the line before it) with a caret line under
the span.

Lines longer than :data:`MAX_WIDTH` characters are shown as a window around the error whose
ends fall on token boundaries, marked with ``…`` where text was left out, so neither the
offending token nor its neighbours are cut in half and the caret stays under the token.
"""

from __future__ import annotations

import functools
import re
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from matloom.lang.diagnostics import Span

MAX_WIDTH = 100
"""Most characters of a source line shown in an excerpt (not counting the ``…`` markers)."""

MAX_CARET = 80
"""Most carets under one span."""

MORE = "…"
"""Marks text left out at either end of a cut line."""

_NONBLANK = re.compile(r"\S")
_WORD_START = re.compile(r"(?<=\s)\S")


@functools.lru_cache(maxsize=4)
def _source_lines(source: str) -> tuple[str, ...]:
    """Lines of ``source``, cached: a program with many diagnostics is split once, not per
    diagnostic (which was quadratic on large inputs)."""
    return tuple(source.split("\n"))


SCAN = 64
"""How far the search for a token boundary goes from the edge of a window before it gives up
and cuts there; bounds the work per excerpt, so a megabyte-long line with thousands of
diagnostics costs no more than a short one."""

_SINGLE = frozenset("(),=+-*/")
"""Characters that are tokens of their own (bar ``**`` and the sign of an exponent, ``1e-5``):
a token boundary lies on both sides of each."""


def _boundary(text: str, p: int) -> bool:
    """Whether a token ends or starts at ``p`` (blanks count as separators)."""
    before, after = text[p - 1], text[p]
    return before in _SINGLE or after in _SINGLE or before.isspace() != after.isspace()


def _start_from(text: str, at: int, limit: int) -> int:
    """The first token start in ``[at, limit]`` (``limit`` is one), at most :data:`SCAN`
    characters on, preferring one after a blank; else ``at``, cutting the token there."""
    stop = min(limit, at + SCAN)
    word = _WORD_START.search(text, at, stop)  # after a blank: the window starts with a word
    if word is not None:
        return word.start()
    for p in range(at, stop):
        if not text[p].isspace() and _boundary(text, p):
            return p
    return limit if limit - at <= SCAN else at


def _end_until(text: str, at: int, floor: int) -> int:
    """The last token end in ``[floor, at]`` (``floor`` is one), at most :data:`SCAN`
    characters back, preferring one before a blank; else ``at``, cutting the token there."""
    stop = max(floor, at - SCAN)
    blank = text.rfind(" ", stop, at + 1)  # before a blank: the window ends with a word
    while blank > stop and text[blank - 1] == " ":
        blank -= 1
    if blank > stop and not text[blank - 1].isspace():
        return blank
    for p in range(at, stop, -1):
        if not text[p - 1].isspace() and _boundary(text, p):
            return p
    return floor if at - floor <= SCAN else at


def window(text: str, first: int, last: int, width: int = MAX_WIDTH) -> tuple[int, int]:
    """A range ``[lo, hi)`` of ``text`` at most ``width`` long (when that is possible) that
    holds ``[first, last)`` and starts and ends on token boundaries.

    Two thirds of the spare room go before ``first``: what leads up to an error explains it
    better than what follows. A single token wider than ``width`` is cut at ``width``.
    """
    n = len(text)
    if n <= width:
        return 0, n
    first = max(0, min(first, n))
    last = max(first, min(last, n))
    if last - first >= width:
        return first, first + width
    room = width - (last - first)
    lo_target = max(0, first - (2 * room) // 3)
    hi_target = min(n, lo_target + width)
    lo_target = max(0, min(lo_target, hi_target - width))
    lo = _start_from(text, lo_target, first) if lo_target > 0 else 0
    hi = _end_until(text, hi_target, last) if hi_target < n else n
    return lo, hi


def _shown(text: str, lo: int, hi: int) -> tuple[str, int]:
    """``text[lo:hi]`` with ``…`` where non-blank text was left out, and the number of
    characters put in front of ``text[lo]``. Tabs and other blanks print as one space each, so
    the caret line lines up with the text."""
    head = MORE if _NONBLANK.search(text, 0, lo) else ""
    tail = MORE if _NONBLANK.search(text, hi) else ""
    shown = re.sub(r"[\t\r\f\v]", " ", text[lo:hi])
    return head + shown + tail, len(head) - lo


def caret_excerpt(source: str, span: Span, context: int = 1) -> str:
    """The offending line (plus ``context`` lines before it) with a caret line under the span."""
    lines = _source_lines(source)
    idx = max(0, min(span.line - 1, len(lines) - 1))
    width = len(str(idx + 1))
    line_text = lines[idx] if idx < len(lines) else ""
    col0 = span.col - 1
    length = max(1, min(span.end - span.start, max(1, len(line_text) - col0)))
    length = min(length, MAX_CARET)
    lo, hi = window(line_text, col0, col0 + length)
    out = []
    for i in range(max(0, idx - context), idx):
        text = lines[i]
        c_lo, c_hi = window(text, min(col0, len(text)), min(col0, len(text)))
        out.append(f" {str(i + 1).rjust(width)} | {_shown(text, c_lo, c_hi)[0]}")
    shown, shift = _shown(line_text, lo, hi)
    out.append(f" {str(idx + 1).rjust(width)} | {shown}")
    caret_at = col0 + shift
    if hi > col0:
        length = max(1, min(length, hi - col0))
    out.append(f" {' ' * width} | {' ' * caret_at}{'^' * length}")
    return "\n".join(out)
