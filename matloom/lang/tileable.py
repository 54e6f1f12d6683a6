"""Tileable programs: ``make_tileable`` and the warnings of a tileable View (W009, W010).

The engine makes every noise, Hash, Tile and shape repeat with the View (see
docs/tileable.md); what it cannot make periodic is reported here, statically, for
``View(..., tileable=True)`` (the checker) and for ``--tileable`` renders (the CLI):

* **W009**: a noise (fBm, Worley, Hash, Tile), pattern (Bricks, Weave) or shape (Fill,
  Stroke) evaluated under a Rotate (other than by a multiple of 180 degrees) or a domain warp
  other than Translate's: its periods are not the View's; a pattern whose cells do not divide
  the View (naming the nearest parameter value and the nearest View that tile); a Hash whose
  cells do not divide the View.
* **W010**: X()/Y() used non-periodically: not inside Fract, Mod, Sin, Cos or Hash with a whole
  number of cycles per View period (as a term of an affine argument: ``Fract(Y() * 18 +
  noise)`` is periodic when 18 times the View's height is whole).

Tile's motif is evaluated in each instance's own frame and repeats with the instances, so
nothing inside a motif is reported.
"""

from __future__ import annotations

import math
from dataclasses import replace

from matloom.lang import ast as A
from matloom.lang.affine import WRAPPERS, coord_coeffs, periodic_wrap, whole, wrapper_cycles
from matloom.lang.diagnostics import Diagnostic, Severity, Span, caret_excerpt
from matloom.lang.static import is_static, param_value
from matloom.vocab import FUNCTIONS
from matloom.vocab.spec import Returns

__all__ = ["make_tileable", "tileable_warnings"]

#: A frame's View periods (Px, Py), or the name of what made them unknown (Rotate, a warp).
Frame = tuple[float, float] | str
#: From the registry: the seeded primitives (noise, Hash, Tile) and the periodic patterns.
_PATTERNS = tuple(name for name, spec in FUNCTIONS.items() if spec.family == "pattern")
_NOISE = tuple(name for name, spec in FUNCTIONS.items() if spec.is_noise and name not in _PATTERNS)
#: Shapes (Fill, Stroke): the engine draws their images one View period apart, in axis-aligned
#: frames only.
_SHAPES = tuple(
    name
    for name, spec in FUNCTIONS.items()
    if spec.family == "shape" and spec.returns is Returns.FIELD
)
#: What cannot repeat under a Rotate or a Scale/Rotate warp.
_FRAMED = _NOISE + _PATTERNS + _SHAPES


def make_tileable(program: A.Program) -> A.Program:
    """``program`` with ``View(..., tileable=True)`` (a View (0, 0, 1, 1) if it had none)."""
    view = program.view or A.ViewDecl(0.0, 0.0, 1.0, 1.0)
    return replace(program, view=replace(view, tileable=True))


def tileable_warnings(program: A.Program, source: str = "") -> list[Diagnostic]:
    """W009/W010 for ``program`` rendered tileable (whatever its View says)."""
    x1, y1, x2, y2 = program.view_tuple
    return _Walker(program, source).run((abs(x2 - x1), abs(y2 - y1)))


def _fmt(v: float) -> str:
    return f"{v:.4g}"


class _Walker:
    def __init__(self, program: A.Program, source: str) -> None:
        self.program = program
        self.source = source
        self.defines = {d.name: d.expr for d in program.defines}
        self.diags: list[Diagnostic] = []
        self.seen: set[tuple[str, str]] = set()
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

    def warn(self, code: str, msg: str, span: Span, hint: str | None = None) -> None:
        if (code, msg) in self.seen:
            return
        self.seen.add((code, msg))
        excerpt = caret_excerpt(self.source, span) if self.source else ""
        self.diags.append(Diagnostic(code, msg, span, Severity.WARNING, None, hint, excerpt))

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
        if func in ("X", "Y"):
            if not coords_ok:
                where = "a rotated or warped frame" if isinstance(frame, str) else "the View"
                self.warn(
                    "W010",
                    f"tileable: {func}() is used non-periodically, so the output has a seam",
                    node.span,
                    hint=f"wrap it in Fract/Mod/Sin/Cos with whole cycles per {where}",
                )
            return
        if func in ("Translate", "Scale", "Rotate"):
            self.transform(node, frame)
            return
        if isinstance(frame, str) and func in _FRAMED:
            self.warn(
                "W009",
                f"tileable: {func} under {frame} cannot repeat with the View",
                node.span,
                hint="only Translate and Scale (and Translate warps) keep the View's periods",
            )
        elif not isinstance(frame, str) and func in _PATTERNS:
            self.pattern(node, frame)
        if func == "Tile":  # the motif repeats with its instances
            return
        if func in WRAPPERS and not isinstance(frame, str):
            coords_ok = coords_ok or self.wrapper(node, frame)
        for arg in node.args:
            self.walk(arg.value, frame, coords_ok)

    def transform(self, node: A.Call, frame: Frame) -> None:
        fields = [a for a in node.args if a.param != "expr" and not is_static(a.value)]
        for a in fields:
            self.walk(a.value, frame)
        inner: Frame = frame
        if isinstance(frame, str):
            pass
        elif node.func == "Scale":
            if fields:
                inner = "a Scale warp"
            else:
                sx, sy = param_value(node, "sx"), param_value(node, "sy")
                inner = (frame[0] / abs(sx), frame[1] / abs(sy))
        elif node.func == "Rotate":
            if fields:
                inner = "a Rotate warp"
            elif whole(float(param_value(node, "degrees")) / 180.0) is None:
                inner = "Rotate"
        self.walk(node.arg("expr"), inner)

    def wrapper(self, node: A.Call, frame: tuple[float, float]) -> bool:
        """Whether a periodic wrapper accounts for the coordinates in its arguments (warning
        when they are linear but without whole cycles per period)."""
        if periodic_wrap(node, self.defines, frame):
            return True
        for _, coeffs, cycle in wrapper_cycles(node, self.defines, frame):
            if coeffs is None or coeffs == (0.0, 0.0) or cycle <= 0:
                continue
            cycles = (coeffs[0] * frame[0] / cycle, coeffs[1] * frame[1] / cycle)
            what = "cells" if node.func == "Hash" else "cycles"
            self.warn(
                "W009" if node.func == "Hash" else "W010",
                f"tileable: {node.func}(...) has {_fmt(cycles[0])} x {_fmt(cycles[1])} {what}"
                " per View period, not whole numbers, so the output has a seam",
                node.span,
                hint="scale its argument so that the View holds a whole number of "
                f"{what} (e.g. {round(cycles[0])} x {round(cycles[1])})",
            )
            return True
        return False

    # ---------------------------------------------------------------- patterns
    def pattern(self, node: A.Call, frame: tuple[float, float]) -> None:
        if node.func == "Bricks":
            msg, hint = _bricks_advice(node, frame)
        else:
            msg, hint = _weave_advice(node, frame)
        if msg:
            self.warn("W009", f"tileable: {msg}", node.span, hint=hint)


def _bricks_advice(node: A.Call, frame: tuple[float, float]) -> tuple[str, str | None]:
    bw, bh = float(param_value(node, "brick_width")), float(param_value(node, "brick_height"))
    offset = float(param_value(node, "offset"))
    rows = param_value(node, "axis") == "row"
    along_p, across_p = (frame[0], frame[1]) if rows else (frame[1], frame[0])
    size_a, size_c = (bw, bh) if rows else (bh, bw)
    names = ("brick_width", "brick_height") if rows else ("brick_height", "brick_width")
    n_a, n_c = along_p / size_a, across_p / size_c
    bad = []
    fixes = []
    if whole(n_a) is None:
        k = max(1, round(n_a))
        bad.append(f"{names[0]}={_fmt(size_a)} gives {_fmt(n_a)} bricks per View period")
        fixes.append(f"{names[0]}={_fmt(along_p / k)}")
    if whole(n_c) is None:
        k = max(1, round(n_c))
        bad.append(f"{names[1]}={_fmt(size_c)} gives {_fmt(n_c)} courses per View period")
        fixes.append(f"{names[1]}={_fmt(across_p / k)}")
    courses = max(1, round(n_c))
    if whole(offset * courses) is None:
        bad.append(f"offset={_fmt(offset)} does not repeat over {courses} courses")
        fixes.append(f"offset={_fmt(round(offset * courses) / courses)}")
    if not bad:
        return "", None
    view = _view_hint(frame, along_p, size_a, across_p, size_c, rows)
    return f"Bricks: {'; '.join(bad)}", f"nearest tiling: {', '.join(fixes)} (or {view})"


def _view_hint(
    frame: tuple[float, float],
    along_p: float,
    size_a: float,
    across_p: float,
    size_c: float,
    rows: bool,
) -> str:
    """The nearest View (from the origin of the frame's periods) that the pattern tiles."""
    wa = max(1, round(along_p / size_a)) * size_a
    wc = max(1, round(across_p / size_c)) * size_c
    w, h = (wa, wc) if rows else (wc, wa)
    return f"a View {_fmt(w)} x {_fmt(h)} in its frame"


def _weave_advice(node: A.Call, frame: tuple[float, float]) -> tuple[str, str | None]:
    base = float(param_value(node, "base_freq"))
    fx = param_value(node, "base_freq_x")
    fy = param_value(node, "base_freq_y")
    fx, fy = float(base if fx is None else fx), float(base if fy is None else fy)
    repeat = int(param_value(node, "over")) + int(param_value(node, "under"))
    shift = int(param_value(node, "shift"))
    rows = repeat // math.gcd(shift, repeat) if shift % repeat else 1
    cols_n, rows_n = fx * frame[0] / repeat, fy * frame[1] / rows
    bad, fixes = [], []
    if whole(cols_n) is None:
        k = max(1, round(cols_n))
        bad.append(f"{_fmt(fx * frame[0])} thread cells across the View (repeat {repeat})")
        fixes.append(f"base_freq_x={_fmt(k * repeat / frame[0])}")
    if whole(rows_n) is None:
        k = max(1, round(rows_n))
        bad.append(f"{_fmt(fy * frame[1])} thread cells up the View (repeat {rows})")
        fixes.append(f"base_freq_y={_fmt(k * rows / frame[1])}")
    if not bad:
        return "", None
    return f"Weave: {'; '.join(bad)}", f"nearest tiling: {', '.join(fixes)}"
