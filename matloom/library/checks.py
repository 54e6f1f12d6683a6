"""Validation of library entries and overlays (``matloom library check`` and the tests).

An entry passes when its program parses with no errors and no warnings, its front matter
matches the program (every colour slot is three Defines ``<slot>_r/_g/_b``, every scalar slot a
Define, the View's ``tileable`` flag equals the front matter's, presets name existing Defines),
it evaluates to finite maps, and, when tileable, every map's seam ratio (as the render manifest
reports it, :func:`matloom.engine.tiling.manifest_entry`) is at most ``SEAM_LIMIT``.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

import matloom
from matloom.lang import ast as A
from matloom.library.adapt import parse_expression
from matloom.library.data import words
from matloom.library.entry import Entry
from matloom.library.index import Library
from matloom.library.overlay import Overlay, check_overlay

SEAM_LIMIT = 1.2


@dataclass
class EntryReport:
    """The problems found in one entry (empty: it passes) and its seam ratios."""

    name: str
    problems: list[str] = field(default_factory=list)
    seams: dict[str, float] = field(default_factory=dict)

    @property
    def ok(self) -> bool:
        return not self.problems


def static_problems(lib: Library, entry: Entry) -> list[str]:
    """Front matter vs program problems and diagnostics (no evaluation)."""
    _, diags = matloom.analyse(entry.program)
    if diags:
        return [f"{d.severity.name.lower()} {d.code}: {d.message}" for d in diags]
    program = lib.ast(entry.name)
    out: list[str] = []
    if program.tileable != entry.tileable:
        out.append(
            f"front matter says tileable = {str(entry.tileable).lower()} but the View says "
            f"tileable={program.tileable}"
        )
    for slot in entry.colours:
        for ch in "rgb":
            if program.define(f"{slot}_{ch}") is None:
                out.append(f"colour slot {slot!r} has no Define {slot}_{ch}")
    for name in entry.scalars:
        d = program.define(name)
        if d is None:
            out.append(f"scalar slot {name!r} has no Define")
        elif not _constant(d.expr):
            out.append(f"scalar slot {name!r} is not a constant")
    presets = lib.presets(entry, words().preset_sets)
    for word, values in presets.items():
        for slot, value in values.items():
            if isinstance(value, tuple):
                missing = [ch for ch in "rgb" if program.define(f"{slot}_{ch}") is None]
                if missing:
                    out.append(f"preset {word!r}: no colour slot {slot!r}")
            elif program.define(slot) is None:
                out.append(f"preset {word!r}: no Define {slot!r}")
            elif isinstance(value, str):
                try:
                    parse_expression(value)
                except ValueError as exc:
                    out.append(f"preset {word!r}: {exc}")
    return out


def _constant(node: A.Node) -> bool:
    return isinstance(node, A.Num) or (isinstance(node, A.Neg) and isinstance(node.operand, A.Num))


def evaluate_problems(
    program: str | A.Program, size: int, tileable: bool
) -> tuple[list[str], dict[str, float]]:
    """(problems, seam ratios) of evaluating a program at ``size`` x ``size``."""
    from matloom.engine.tiling import manifest_entry
    from matloom.vocab.layout import LAYOUT

    maps = matloom.evaluate(program, size, size, backend="numpy")
    out: list[str] = []
    for name in LAYOUT.map_fields:
        values = np.asarray(getattr(maps, name))
        bad = int(values.size - np.count_nonzero(np.isfinite(values)))
        if bad:
            out.append(f"{bad} non-finite value(s) in {name}")
    seams: dict[str, float] = {}
    if tileable:
        seams = manifest_entry(maps, LAYOUT.maps).get("seam_ratio", {})
        over = {k: v for k, v in seams.items() if v > SEAM_LIMIT}
        if over:
            out.append(
                "seam ratio over "
                + f"{SEAM_LIMIT}: "
                + ", ".join(f"{k} {v:.2f}" for k, v in sorted(over.items()))
            )
    return out, seams


def check_entry(lib: Library, entry: Entry, size: int = 64) -> EntryReport:
    """Every check of one entry."""
    report = EntryReport(entry.name)
    try:
        report.problems = static_problems(lib, entry)
    except (matloom.ProgramError, ValueError) as exc:
        report.problems = [str(exc)]
    if report.problems:
        return report
    problems, seams = evaluate_problems(lib.ast(entry.name), size, entry.tileable)
    report.problems += problems
    report.seams = seams
    return report


def overlay_reports(lib: Library, overlays: list[Overlay] | None = None) -> dict[str, list[str]]:
    """Overlay name -> problems (an empty list when it passes)."""
    out: dict[str, list[str]] = {}
    for ov in overlays or list(lib.overlays.values()):
        try:
            check_overlay(ov)
            out[ov.name] = [f"{d.code}: {d.message}" for d in matloom.check(ov.program)]
        except (ValueError, matloom.ProgramError) as exc:
            out[ov.name] = [str(exc)]
    return out
