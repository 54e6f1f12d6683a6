"""Tileable programs: ``make_tileable`` and the warnings of a tileable View (W009, W010).

The engine makes every noise, Hash, Tile and shape repeat with the View (see
docs/tileable.md); what it cannot make periodic is reported here, statically, for
``View(..., tileable=True)`` (the checker) and for ``--tileable`` renders (the CLI). Each
function's part is its op's period rule (``Op.period``, :mod:`matloom.ops.period`); no function
is named here:

* **W009**: a primitive that needs the View's periods (``Period.framed``: noise, Hash, Tile,
  patterns, shapes) evaluated under a transform that breaks them (a Rotate other than by a
  multiple of 180 degrees, a Scale or Rotate warp, a Scale past the float range); a primitive
  whose own cells do not fit the periods (``Period.misfit``: a pattern whose cells do not
  divide the View, naming the nearest parameter value and the nearest View that tile; an fBm,
  Worley or Tile with more cells per View period than a lattice can wrap, ``MAX_PERIOD_CELLS``):
  the engine leaves those unwrapped; a Hash whose cells do not divide the View.
* **W010**: X()/Y() used non-periodically: not inside a periodic wrapper (Fract, Mod, Sin, Cos
  or Hash: ``Repeats.WRAP``) with a whole number of cycles per View period (as a term of an
  affine argument: ``Fract(Y() * 18 + noise)`` is periodic when 18 times the View's height is
  whole).

Tile's motif is evaluated in each instance's own frame and repeats with the instances, so
nothing inside a motif is reported.
"""

from __future__ import annotations

import math
from dataclasses import replace

from matloom.lang import ast as A
from matloom.lang.affine import coord_coeffs, period_of, periodic_wrap, wrapper_cycles
from matloom.lang.codes import Code
from matloom.lang.constants import resolve_static
from matloom.lang.diagnostics import Diagnostic, Span, caret_excerpt
from matloom.lang.static import is_static, param_value
from matloom.ops import Period, Repeats
from matloom.ops.period import Frame, valid
from matloom.vocab import FUNCTIONS

__all__ = ["make_tileable", "tileable_warnings"]


def make_tileable(program: A.Program) -> A.Program:
    """``program`` with ``View(..., tileable=True)`` (a View (0, 0, 1, 1) if it had none)."""
    view = program.view or A.ViewDecl(0.0, 0.0, 1.0, 1.0)
    return replace(program, view=replace(view, tileable=True))


def tileable_warnings(program: A.Program, source: str = "") -> list[Diagnostic]:
    """W009/W010 for ``program`` rendered tileable (whatever its View says); none for a View
    without finite, non-zero periods (the checker's E061). Named static values are read as
    the evaluator reads them (:func:`~matloom.lang.constants.resolve_static`)."""
    program = resolve_static(program)
    x1, y1, x2, y2 = program.view_tuple
    periods = (abs(x2 - x1), abs(y2 - y1))
    if not valid(periods):
        return []
    return _Walker(program, source).run(periods)


def _fmt(v: float) -> str:
    return f"{v:.4g}"


class _Walker:
    def __init__(self, program: A.Program, source: str) -> None:
        self.program = program
        self.source = source
        self.defines = {d.name: d.expr for d in program.defines}
        self.diags: list[Diagnostic] = []
        self.seen: set[tuple[Code, str]] = set()
        self.visited: set[tuple[str, Frame, bool]] = set()
        self.memos: dict[tuple[float, float], dict] = {}

    def run(self, periods: tuple[float, float]) -> list[Diagnostic]:
        for layer in self.program.layers:
            if layer.alpha is not None:
                self.walk(layer.alpha, periods)
            for ch in layer.channels:
                for a in ch.args:
                    self.walk(a, periods)
        return self.diags

    def warn(self, code: Code, msg: str, span: Span, hint: str | None = None) -> None:
        if (code, msg) in self.seen:
            return
        self.seen.add((code, msg))
        excerpt = caret_excerpt(self.source, span) if self.source else ""
        self.diags.append(code.diagnostic(msg, span, hint=hint, excerpt=excerpt))

    # ---------------------------------------------------------------- the walk
    def walk(self, node: A.Node | None, frame: Frame, coords_ok: bool = False) -> None:
        """Report what under ``node`` cannot repeat (``coords_ok``: X()/Y() here are inside a
        periodic wrapper that accounts for them)."""
        if node is None or is_static(node):
            return
        if not coords_ok and not isinstance(frame, str):
            memo = self.memos.setdefault(frame, {})
            coords_ok = coord_coeffs(node, self.defines, frame, memo=memo) == (0.0, 0.0)
        if isinstance(node, A.Ref):
            key = (node.name, frame, coords_ok)
            if node.name in self.defines and key not in self.visited:
                self.visited.add(key)
                self.walk(self.defines[node.name], frame, coords_ok)
            return
        if isinstance(node, A.Call):
            self.call(node, frame, coords_ok)
            return
        for child in A.children(node):
            self.walk(child, frame, coords_ok)

    def call(self, node: A.Call, frame: Frame, coords_ok: bool) -> None:
        func = node.func
        period = period_of(func)
        if period.repeats is Repeats.AXIS:
            if not coords_ok:
                where = "a rotated or warped frame" if isinstance(frame, str) else "the View"
                self.warn(
                    Code.COORDINATE_SEAM,
                    f"tileable: {func}() is used non-periodically, so the output has a seam",
                    node.span,
                    hint=f"wrap it in Fract/Mod/Sin/Cos with whole cycles per {where}",
                )
            return
        if period.repeats is Repeats.FRAME:
            self.transform(node, frame, period)
            return
        if isinstance(frame, str) and period.framed:
            self.warn(
                Code.DOES_NOT_TILE,
                f"tileable: {func} under {frame} cannot repeat with the View",
                node.span,
                hint="only Translate and Scale (and Translate warps) keep the View's periods",
            )
        elif not isinstance(frame, str) and period.misfit is not None:
            self.own(node, frame, period)
        spec = FUNCTIONS.get(func)
        if spec is not None and spec.instances:  # the motif repeats with its instances
            return
        if period.repeats is Repeats.WRAP and not isinstance(frame, str):
            coords_ok = coords_ok or self.wrapper(node, frame, period)
        for arg in node.args:
            self.walk(arg.value, frame, coords_ok)
        if spec is not None and spec.nary:  # Min(a, b, c, ...)
            for extra in node.extra:
                self.walk(extra, frame, coords_ok)

    def transform(self, node: A.Call, frame: Frame, period: Period) -> None:
        """Walk a transform: its field parameters in ``frame``, its operand in the frame its
        period rule gives (a domain warp keeps the periods only where ``warp_keeps``)."""
        fields = [a for a in node.args if a.param != "expr" and not is_static(a.value)]
        for a in fields:
            self.walk(a.value, frame)
        inner: Frame = frame
        if isinstance(frame, str):
            pass
        elif fields:
            inner = frame if period.warp_keeps else f"a {node.func} warp"
        else:
            assert period.frame is not None
            inner = period.frame(node.func, lambda name: param_value(node, name), frame)
        self.walk(node.arg("expr"), inner)

    def wrapper(self, node: A.Call, frame: tuple[float, float], period: Period) -> bool:
        """Whether a periodic wrapper accounts for the coordinates in its arguments (warning
        when they are linear but without whole cycles per period: W009 for cells, W010 for
        the cycles of a phase)."""
        if periodic_wrap(node, self.defines, frame):
            return True
        for _, coeffs, cycle in wrapper_cycles(node, self.defines, frame):
            if coeffs is None or coeffs == (0.0, 0.0) or cycle <= 0:
                continue
            cycles = (coeffs[0] * frame[0] / cycle, coeffs[1] * frame[1] / cycle)
            what = period.unit
            nearest = [round(c) if math.isfinite(c) else None for c in cycles]
            example = "" if None in nearest else f" (e.g. {nearest[0]} x {nearest[1]})"
            self.warn(
                Code.DOES_NOT_TILE if what == "cells" else Code.COORDINATE_SEAM,
                f"tileable: {node.func}(...) has {_fmt(cycles[0])} x {_fmt(cycles[1])} {what}"
                " per View period, not whole numbers, so the output has a seam",
                node.span,
                hint=f"scale its argument so that the View holds a whole number of {what}"
                + example,
            )
            return True
        return False

    def own(self, node: A.Call, frame: tuple[float, float], period: Period) -> None:
        """W009 for a primitive whose own period does not fit the frame's (its period rule's
        ``misfit``: a pattern's cells, a lattice with too many cells to wrap): the engine
        evaluates it unwrapped."""
        assert period.misfit is not None
        found = period.misfit(node.func, lambda name: param_value(node, name), frame)
        if found is not None:
            msg, hint = found
            self.warn(Code.DOES_NOT_TILE, f"tileable: {msg}", node.span, hint=hint)
