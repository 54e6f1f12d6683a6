"""Program text after a panel edit, changed as little as possible.

A slider, a colour picker or a seed chip changes only literal numbers. When the edited program
differs from the one the user's text parses to only in such literals, :func:`program_text`
replaces those literals in the user's text, character for character, and keeps every other byte
(spacing, line breaks, comments, names): the editor's cursor and undo history stay meaningful.
Anything else (an argument written or dropped, layers moved) is printed by the canonical printer
with the comments kept, as ``matloom fmt`` does. Either way the result parses back to the
edited program (checked).
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from matloom.lang import ast as A
from matloom.lang.diagnostics import NO_SPAN
from matloom.lang.printer import fmt_num, format_expr, format_program
from matloom.studio.program import analysed
from matloom.vocab import CONSTANTS

if TYPE_CHECKING:
    from matloom.engine.session import Session


class _Mismatch(Exception):
    """The two programs differ in more than literal numbers."""


def program_text(
    text: str, before: A.Program, after: A.Program, session: Session | None = None
) -> str:
    """The text of ``after``: ``text`` (whose program is ``before``) with only the changed
    literals replaced when that is all that changed, else the canonical text with comments.

    The spliced text is checked to parse back to ``after``; with the studio's ``session`` that
    analysis stays in its cache, so the requests that follow an edit do not parse it again."""
    try:
        edits = _program_edits(before, after)
    except _Mismatch:
        edits = None
    spliced = _apply(text, edits) if edits is not None else None
    if spliced is not None:
        parsed, _ = analysed(spliced, session)
        if parsed is not None and format_program(parsed) == format_program(after):
            return spliced
    return format_program(after, comments=True)


def _apply(text: str, edits: list[tuple[int, int, str]]) -> str | None:
    edits.sort()
    out, last = [], 0
    for start, end, new in edits:
        if start < last or end > len(text):
            return None  # overlapping or outside the text: print canonically instead
        out.append(text[last:start])
        out.append(new)
        last = end
    out.append(text[last:])
    return "".join(out)


def _program_edits(a: A.Program, b: A.Program) -> list[tuple[int, int, str]]:
    edits: list[tuple[int, int, str]] = []
    if a.view != b.view or len(a.defines) != len(b.defines) or len(a.layers) != len(b.layers):
        raise _Mismatch
    for da, db in zip(a.defines, b.defines):
        if da.name != db.name:
            raise _Mismatch
        _expr(da.expr, db.expr, edits)
    for la, lb in zip(a.layers, b.layers):
        if (la.alpha is None) != (lb.alpha is None) or len(la.channels) != len(lb.channels):
            raise _Mismatch
        if la.alpha is not None and lb.alpha is not None:
            _expr(la.alpha, lb.alpha, edits)
        for ca, cb in zip(la.channels, lb.channels):
            if ca.name != cb.name or len(ca.args) != len(cb.args):
                raise _Mismatch
            for xa, xb in zip(ca.args, cb.args):
                _expr(xa, xb, edits)
    return edits


def _expr(a: A.Node, b: A.Node, edits: list[tuple[int, int, str]]) -> None:
    """Collect the replacements turning ``a`` into ``b`` (literals only)."""
    if a == b or _same_constant(a, b):
        return
    if _is_number(a) and _is_number(b):
        if a.span == NO_SPAN or a.span.end <= a.span.start:
            raise _Mismatch
        new = fmt_num(b.value) if isinstance(b, A.Num) else format_expr(b)
        edits.append((a.span.start, a.span.end, new))
        return
    if type(a) is not type(b):
        raise _Mismatch
    if isinstance(a, A.Neg) and isinstance(b, A.Neg):
        _expr(a.operand, b.operand, edits)
    elif isinstance(a, A.BinOp) and isinstance(b, A.BinOp):
        if a.op != b.op:
            raise _Mismatch
        _expr(a.left, b.left, edits)
        _expr(a.right, b.right, edits)
    elif isinstance(a, A.Call) and isinstance(b, A.Call):
        if a.func != b.func or [x.param for x in a.args] != [x.param for x in b.args]:
            raise _Mismatch
        if len(a.extra) != len(b.extra):
            raise _Mismatch
        for xa, xb in zip(a.args, b.args):
            _expr(xa.value, xb.value, edits)
        for ea, eb in zip(a.extra, b.extra):
            _expr(ea, eb, edits)
    else:
        raise _Mismatch


def _same_constant(a: A.Node, b: A.Node) -> bool:
    """A named constant (``pi``) and the number it is (as the printer writes it)."""
    if isinstance(a, A.Const) and isinstance(b, A.Num):
        return CONSTANTS.get(a.name) == b.value
    return False


def _is_number(node: A.Node) -> bool:
    """A literal number: ``3`` or ``-0.5``."""
    return isinstance(node, A.Num) or (isinstance(node, A.Neg) and isinstance(node.operand, A.Num))
