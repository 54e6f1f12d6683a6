"""A program as the studio's endpoints take it: checked (422 with the diagnostics when it does
not), its diagnostics as the editor reads them, and the labels the panel gives its layers."""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

from matloom.lang import ast as A
from matloom.lang.api import analyse
from matloom.lang.diagnostics import Diagnostic
from matloom.lang.params import words
from matloom.studio.protocol import ApiError

if TYPE_CHECKING:
    from matloom.engine.session import Session


def _utf16(text: str, offset: int) -> int:
    """A character offset as a JavaScript string index (UTF-16 code units)."""
    head = text[:offset]
    return offset + sum(1 for ch in head if ord(ch) > 0xFFFF)


def _line_col(text: str, offset: int) -> tuple[int, int]:
    line = text.count("\n", 0, offset) + 1
    return line, offset - (text.rfind("\n", 0, offset) + 1) + 1


def diagnostics_json(text: str, diags: list[Diagnostic]) -> list[dict[str, Any]]:
    """The diagnostics as the editor reads them: line/col (1-based), end_line/end_col, and
    ``from``/``to`` as JavaScript string offsets into ``text``."""
    wide = any(ord(ch) > 0xFFFF for ch in text)
    out = []
    for d in diags:
        start = min(max(d.span.start, 0), len(text))
        end = min(max(d.span.end, start), len(text))
        end_line, end_col = _line_col(text, end)
        out.append(
            {
                "code": d.code,
                "severity": d.severity.value,
                "message": d.message,
                "line": d.line,
                "col": d.column,
                "end_line": end_line,
                "end_col": end_col,
                "from": _utf16(text, start) if wide else start,
                "to": _utf16(text, end) if wide else end,
                "hint": d.hint,
                "expected": d.expected,
            }
        )
    return out


def analysed(
    text: str, session: Session | None = None
) -> tuple[A.Program | None, list[Diagnostic]]:
    """``analyse(text)``, remembered in ``session`` (by text) when one is given: a drag sends
    the same program to several endpoints, and a big program takes tens of ms to check."""
    if session is None:
        return analyse(text)
    return session.cached("studio-analysed", text, lambda: analyse(text))


def check_json(text: str, session: Session | None = None) -> dict[str, Any]:
    """``/api/check``: every diagnostic of ``text``."""
    program, diags = analysed(text, session)
    ok = program is not None and not any(d.is_error for d in diags)
    return {"ok": ok, "diagnostics": diagnostics_json(text, diags)}


def refusal(text: str, diags: list[Diagnostic]) -> ApiError:
    """The 422 of a program that does not check: its first error in one line, and its
    errors as :func:`diagnostics_json`."""
    errors = [d for d in diags if d.is_error] or diags
    first = errors[0] if errors else None
    message = (
        f"line {first.line}, col {first.column}: {first.code} {first.message}"
        if first is not None
        else "the program does not parse"
    )
    return ApiError(422, message, diagnostics=diagnostics_json(text, errors))


def checked(text: str, session: Session | None = None) -> A.Program:
    """The program of ``text``; 422 with its diagnostics when it does not check."""
    program, diags = analysed(text, session)
    if program is None or any(d.is_error for d in diags):
        raise refusal(text, diags)
    return program


def layer_label(index: int, layer: A.Layer) -> str:
    """``tile mask`` for ``Layer(tileMask)``, else ``layer N`` (N 1-based)."""
    if isinstance(layer.alpha, A.Ref):
        return words(layer.alpha.name)
    return f"layer {index + 1}"
