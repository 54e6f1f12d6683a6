"""Validation of library entries and overlays (``matloom library check`` and the tests).

An entry passes when its program parses with no errors and no warnings, its front matter
matches the program (every colour slot is three Defines ``<slot>_r/_g/_b``, every scalar slot a
Define, the View's ``tileable`` flag equals the front matter's, presets name existing Defines),
it evaluates to finite maps, and, when tileable, every map repeats with the View
(:func:`period_problems`: the View moved by one period gives the same maps) and every map's seam
ratio (as the render manifest reports it, :func:`matloom.engine.tiling.manifest_entry`) is at
most ``SEAM_LIMIT``. The tileable checks evaluate the View the author writes for the entry
(:func:`matloom.library.adapt.place_origin`), which may start elsewhere than the file's.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from matloom.engine.maps import View
from matloom.lang import ast as A
from matloom.lang.api import analyse, check, parse, parse_expression
from matloom.lang.diagnostics import ProgramError
from matloom.library.adapt import place_origin
from matloom.library.data import words
from matloom.library.entry import Entry
from matloom.library.index import Library
from matloom.library.overlay import Overlay, check_overlay

SEAM_LIMIT = 1.2
#: the periodicity check: evaluation size, texel tolerance (a share of the map's range: the
#: float32 coordinates one period further round differently, which on the steep edges of fine
#: threads reaches 0.1 % of a small map's range) and the share of texels allowed beyond it
#: (a texel centre on a cell boundary can fall in either cell)
PERIOD_SIZE = 40
PERIOD_TOLERANCE = 0.01
PERIOD_SHARE = 0.005
#: the corner of the periodicity check's View: small binary fractions, so that the View and the
#: View moved by its width have exactly the same width in float arithmetic, off the cell
#: boundaries of the patterns (from (0, 0) the texel centres (i + 0.5) W / 40 fall on the
#: boundaries of every multiple of 16 cells per View) and different in x and y (equal ones put
#: the diagonal texels on every diagonal line through the origin)
PERIOD_CORNER = (3 / 512, 5 / 512)


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
    _, diags = analyse(entry.program)
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
    from matloom.engine.evaluate import evaluate
    from matloom.engine.tiling import manifest_entry
    from matloom.vocab.layout import LAYOUT

    maps = evaluate(program, size, size, backend="numpy")
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


def period_problems(program: str | A.Program, size: int = PERIOD_SIZE) -> list[str]:
    """Does every map repeat with the View? The program is evaluated at ``size`` x ``size`` on
    a View of its width W and height H and on that View moved by exactly W, then H; a map fails
    when more than ``PERIOD_SHARE`` of its texels differ by more than ``PERIOD_TOLERANCE`` of
    its range. Cheap, and not fooled by where the wrap edge falls (periodicity does not depend
    on it). The View starts at ``PERIOD_CORNER``, binary fractions whose sums with W and 2W are
    exact, so that the moved View has exactly the same size in float arithmetic: a size one
    rounding step off can pick another noise lattice for the same periods, which is no seam."""
    from matloom.engine.evaluate import evaluate
    from matloom.vocab.layout import LAYOUT

    prog = parse(program) if isinstance(program, str) else program
    x1, y1, x2, y2 = prog.view_tuple
    # sizes on a 2**-40 grid (a change below 1e-12): every sum below is then exact
    w, h = (round(abs(v) * 2.0**40) / 2.0**40 for v in (x2 - x1, y2 - y1))
    cx, cy = PERIOD_CORNER
    v = View(cx, cy, cx + w, cy + h, tileable=True)
    base = evaluate(prog, size, size, backend="numpy", view=v)
    out: list[str] = []
    for what, dx, dy in (("width", w, 0.0), ("height", 0.0, h)):
        moved = View(v.x1 + dx, v.y1 + dy, v.x2 + dx, v.y2 + dy, tileable=True)
        other = evaluate(prog, size, size, backend="numpy", view=moved)
        bad = []
        for name in LAYOUT.map_fields:
            a = np.asarray(getattr(base, name), dtype=np.float64)
            b = np.asarray(getattr(other, name), dtype=np.float64)
            finite = np.isfinite(a) & np.isfinite(b)
            if not finite.any():
                continue
            tol = PERIOD_TOLERANCE * max(float(np.ptp(a[finite])), 1e-4)
            share = float(np.mean(~finite | (np.abs(np.where(finite, a - b, 0.0)) > tol)))
            if share > PERIOD_SHARE:
                bad.append(f"{name} {share:.1%}")
        if bad:
            out.append(
                f"does not repeat: the View moved by its {what} changes texels of " + ", ".join(bad)
            )
    return out


def check_entry(
    lib: Library, entry: Entry, size: int = 128, period_size: int = PERIOD_SIZE
) -> EntryReport:
    """Every check of one entry: static, finite maps and, when tileable, the periodicity
    (:func:`period_problems` at ``period_size``) and the seam ratio at ``size``, on the View
    the author writes (:func:`matloom.library.adapt.place_origin`)."""
    report = EntryReport(entry.name)
    try:
        report.problems = static_problems(lib, entry)
    except (ProgramError, ValueError) as exc:
        report.problems = [str(exc)]
    if report.problems:
        return report
    program = lib.ast(entry.name)
    if entry.tileable:
        program = place_origin(program, entry)
        report.problems += period_problems(program, period_size)
    problems, seams = evaluate_problems(program, size, entry.tileable)
    report.problems += problems
    report.seams = seams
    return report


def overlay_reports(lib: Library, overlays: list[Overlay] | None = None) -> dict[str, list[str]]:
    """Overlay name -> problems (an empty list when it passes)."""
    out: dict[str, list[str]] = {}
    for ov in overlays or list(lib.overlays.values()):
        try:
            check_overlay(ov)
            out[ov.name] = [f"{d.code}: {d.message}" for d in check(ov.program)]
        except (ValueError, ProgramError) as exc:
            out[ov.name] = [str(exc)]
    return out
