"""``--tileable`` for render, preview, sweep and generate (see docs/tileable.md)."""

from __future__ import annotations

from typing import Any

import click

from matloom.lang import ast as A


def tileable_option(f: Any) -> Any:
    """The ``--tileable`` flag (the program's ``View(..., tileable=True)`` turns it on too)."""
    return click.option(
        "--tileable",
        is_flag=True,
        help="Make every map repeat seamlessly with the View (as View(..., tileable=True)).",
    )(f)


def apply_tileable(program: A.Program, on: bool, text: str = "", path: str = "") -> A.Program:
    """``program`` made tileable when ``on`` (or already so); prints the tileable warnings
    (W009/W010: what cannot repeat) on stderr."""
    from matloom.lang.diagnostics import format_diagnostics
    from matloom.lang.tileable import make_tileable, tileable_warnings

    if not (on or program.tileable):
        return program
    warnings = tileable_warnings(program, text)
    if warnings:
        click.echo(format_diagnostics(warnings, path or "<program>"), err=True)
    return make_tileable(program)
