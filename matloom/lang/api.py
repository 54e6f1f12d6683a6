"""Public entry points of the language layer: parse, check, format."""

from __future__ import annotations

import functools

from matloom.lang.ast import Node, Program
from matloom.lang.checker import check_program
from matloom.lang.diagnostics import Diagnostic, ProgramError
from matloom.lang.parser import parse_source
from matloom.lang.printer import format_program


@functools.lru_cache(maxsize=1024)
def parse_expression(text: str) -> Node:
    """Parse one expression (a preset value such as ``X()``, a bound overlay relief); raise
    ValueError when ``text`` is none."""
    program, diags = parse_source(f"Define(value, {text})\nMaterial(Layer(1).roughness(value))")
    if program is None or not program.defines:
        raise ValueError(f"not an expression: {text!r} ({diags[0] if diags else ''})")
    return program.defines[0].expr


def analyse(text: str) -> tuple[Program | None, list[Diagnostic]]:
    """Parse and check ``text``; return the program (``None`` on syntax errors) and all diagnostics.

    Diagnostics are sorted by position; errors and warnings are both included.
    """
    program, diags = parse_source(text)
    if program is not None:
        diags = diags + check_program(program, text)
    diags.sort(key=lambda d: (d.span.start, d.code))
    return program, diags


def check(text: str) -> list[Diagnostic]:
    """Every diagnostic (errors and warnings) for ``text``."""
    return analyse(text)[1]


def parse(text: str) -> Program:
    """Parse and check ``text``; raise :class:`ProgramError` (with every diagnostic) on errors."""
    program, diags = analyse(text)
    if program is None or any(d.is_error for d in diags):
        raise ProgramError(diags, text)
    return program


def format(program: Program | str, *, comments: bool = False) -> str:  # noqa: A001 - API name
    """Canonical text of a program (or of program text, which is parsed first).

    ``comments=True`` keeps the program's ``#`` comments, as ``matloom fmt`` does; the default
    text is comment-free, as the reference serialiser writes it.
    """
    if isinstance(program, str):
        program = parse(program)
    return format_program(program, comments=comments)
