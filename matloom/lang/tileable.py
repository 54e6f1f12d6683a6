"""Tileable programs: ``make_tileable`` and the warnings of a tileable View (W009, W010).

The engine makes every noise, Hash, Tile and shape repeat with the View (see
docs/tileable.md); what it cannot make periodic is reported here, statically, for
``View(..., tileable=True)`` (the checker) and for ``--tileable`` renders (the CLI):

* **W009**: a noise (fBm, Worley, Hash, Tile), pattern (Bricks, Weave) or shape (Fill,
  Stroke) evaluated under a Rotate (other than by a multiple of 180 degrees) or a domain warp
  other than Translate's: its periods are not the View's; a pattern whose cells do not divide
  the View (naming the nearest parameter value and the nearest View that tile); a Hash whose
  cells do not divide the View; an fBm, Worley or Tile with more cells per View period than
  a lattice can wrap (``MAX_PERIOD_CELLS``, or a count past the float range), or under a
  Scale that puts the View's periods past the float range: the engine leaves those unwrapped.
* **W010**: X()/Y() used non-periodically: not inside Fract, Mod, Sin, Cos or Hash with a whole
  number of cycles per View period (as a term of an affine argument: ``Fract(Y() * 18 +
  noise)`` is periodic when 18 times the View's height is whole).

Tile's motif is evaluated in each instance's own frame and repeats with the instances, so
nothing inside a motif is reported.
"""

from __future__ import annotations

import math
from dataclasses import replace

from matloom.engine.kernels.opensimplex import octave_schedule
from matloom.engine.kernels.periodic import MAX_PERIOD_CELLS, simplex_wraps, wraps
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
#: The lattices the engine snaps to whole cells per period and wraps (Hash wraps its operands).
_LATTICES = tuple(name for name in _NOISE if name != "Hash")


def make_tileable(program: A.Program) -> A.Program:
    """``program`` with ``View(..., tileable=True)`` (a View (0, 0, 1, 1) if it had none)."""
    view = program.view or A.ViewDecl(0.0, 0.0, 1.0, 1.0)
    return replace(program, view=replace(view, tileable=True))


def tileable_warnings(program: A.Program, source: str = "") -> list[Diagnostic]:
    """W009/W010 for ``program`` rendered tileable (whatever its View says); none for a View
    without finite, non-zero periods (the checker's E061)."""
    x1, y1, x2, y2 = program.view_tuple
    periods = (abs(x2 - x1), abs(y2 - y1))
    if not _valid_periods(periods):
        return []
    return _Walker(program, source).run(periods)


def _fmt(v: float) -> str:
    return f"{v:.4g}"


def _valid_periods(periods: tuple[float, float]) -> bool:
    return all(math.isfinite(p) and p > 0 for p in periods)


def _quotient(a: float, b: float) -> float:
    """a / b, inf when b is 0 (no whole number of cells of size 0 fill a period)."""
    return a / b if b else math.inf


def _nearest_count(n: float) -> int | None:
    """The whole number (>= 1) of cells nearest to ``n``; None when ``n`` is not finite (a
    size or frequency that over- or underflows the period): no nearest value to suggest."""
    return max(1, round(n)) if math.isfinite(n) else None


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
        elif not isinstance(frame, str) and func in _LATTICES:
            self.lattice(node, frame)
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
                scaled = (_quotient(frame[0], abs(sx)), _quotient(frame[1], abs(sy)))
                inner = scaled if _valid_periods(scaled) else "a Scale past the float range"
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
            nearest = [round(c) if math.isfinite(c) else None for c in cycles]
            example = "" if None in nearest else f" (e.g. {nearest[0]} x {nearest[1]})"
            self.warn(
                "W009" if node.func == "Hash" else "W010",
                f"tileable: {node.func}(...) has {_fmt(cycles[0])} x {_fmt(cycles[1])} {what}"
                " per View period, not whole numbers, so the output has a seam",
                node.span,
                hint=f"scale its argument so that the View holds a whole number of {what}"
                + example,
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

    def lattice(self, node: A.Call, frame: tuple[float, float]) -> None:
        """W009 for an fBm, Worley or Tile whose cells per View period the engine cannot
        wrap (:func:`~matloom.engine.kernels.periodic.wraps`): it is evaluated unwrapped."""
        if _lattice_wraps(node, frame):
            return
        self.warn(
            "W009",
            f"tileable: {node.func} has more than {MAX_PERIOD_CELLS:,} cells per View period "
            "(or a count past the float range), too many to wrap, so it does not repeat with "
            "the View",
            node.span,
            hint="use a lower frequency (larger cells) or a smaller View",
        )


def _bricks_advice(node: A.Call, frame: tuple[float, float]) -> tuple[str, str | None]:
    bw, bh = float(param_value(node, "brick_width")), float(param_value(node, "brick_height"))
    offset = float(param_value(node, "offset"))
    rows = param_value(node, "axis") == "row"
    along_p, across_p = (frame[0], frame[1]) if rows else (frame[1], frame[0])
    size_a, size_c = (bw, bh) if rows else (bh, bw)
    names = ("brick_width", "brick_height") if rows else ("brick_height", "brick_width")
    n_a, n_c = _quotient(along_p, size_a), _quotient(across_p, size_c)
    bad = []
    fixes = []
    if whole(n_a) is None or not wraps(n_a):
        bad.append(f"{names[0]}={_fmt(size_a)} gives {_fmt(n_a)} bricks per View period")
        fixes.append(_size_fix(names[0], along_p, n_a))
    if whole(n_c) is None or not wraps(n_c):
        bad.append(f"{names[1]}={_fmt(size_c)} gives {_fmt(n_c)} courses per View period")
        fixes.append(_size_fix(names[1], across_p, n_c))
    courses = _nearest_count(n_c) or 1
    shift = offset * courses
    if whole(shift) is None or not wraps(shift):
        bad.append(f"offset={_fmt(offset)} does not repeat over {courses} courses")
        fixes.append(f"offset={_fmt(round(shift) / courses)}" if wraps(shift) else "")
    if not bad:
        return "", None
    view = _view_hint(along_p, size_a, across_p, size_c, rows)
    hint = f"nearest tiling: {', '.join(f for f in fixes if f) or 'none in range'}"
    return f"Bricks: {'; '.join(bad)}", hint + (f" (or {view})" if view else "")


def _size_fix(name: str, period: float, count: float) -> str:
    """``name=value``: the size that fits the whole number of cells nearest to ``count`` in
    ``period`` ("" when there is none in range, as for a count past the float range)."""
    k = _nearest_count(count)
    return "" if k is None or not wraps(k) else f"{name}={_fmt(period / k)}"


def _view_hint(along_p: float, size_a: float, across_p: float, size_c: float, rows: bool) -> str:
    """The nearest View (from the origin of the frame's periods) that the pattern tiles ("" when
    a size over- or underflows the period)."""
    ka, kc = _nearest_count(_quotient(along_p, size_a)), _nearest_count(_quotient(across_p, size_c))
    if ka is None or kc is None:
        return ""
    wa, wc = ka * size_a, kc * size_c
    w, h = (wa, wc) if rows else (wc, wa)
    return f"a View {_fmt(w)} x {_fmt(h)} in its frame"


def _weave_advice(node: A.Call, frame: tuple[float, float]) -> tuple[str, str | None]:
    fx, fy = _frequencies(node)
    repeat = int(param_value(node, "over")) + int(param_value(node, "under"))
    shift = int(param_value(node, "shift"))
    rows = repeat // math.gcd(shift, repeat) if shift % repeat else 1
    cols_n, rows_n = fx * frame[0] / repeat, fy * frame[1] / rows
    bad, fixes = [], []
    if whole(cols_n) is None or not wraps(cols_n):
        bad.append(f"{_fmt(fx * frame[0])} thread cells across the View (repeat {repeat})")
        fixes.append(_freq_fix("base_freq_x", cols_n, repeat, frame[0]))
    if whole(rows_n) is None or not wraps(rows_n):
        bad.append(f"{_fmt(fy * frame[1])} thread cells up the View (repeat {rows})")
        fixes.append(_freq_fix("base_freq_y", rows_n, rows, frame[1]))
    if not bad:
        return "", None
    return (
        f"Weave: {'; '.join(bad)}",
        f"nearest tiling: {', '.join(f for f in fixes if f) or 'none in range'}",
    )


def _freq_fix(name: str, repeats: float, repeat: int, period: float) -> str:
    """``name=value``: the frequency that fits the whole number of repeats nearest to
    ``repeats`` in ``period`` ("" when there is none in range)."""
    k = _nearest_count(repeats)
    return "" if k is None or not wraps(k) else f"{name}={_fmt(k * repeat / period)}"


def _lattice_wraps(node: A.Call, frame: tuple[float, float]) -> bool:
    """Whether the engine can wrap the lattice of an fBm, Worley or Tile in a frame of periods
    ``frame`` (:func:`~matloom.engine.kernels.periodic.wraps`; as ``simplex_wraps``,
    ``plan_worley`` and ``TileParams.tiled`` decide)."""
    px, py = frame
    if node.func == "Tile":
        across, up = (
            _quotient(px, float(param_value(node, "width"))),
            _quotient(py, float(param_value(node, "height"))),
        )
        if not (wraps(across) and wraps(up)):
            return False
        return wraps(float(param_value(node, "offset")) * max(1, round(up)))
    fx, fy = _frequencies(node)
    if node.func == "fBm":
        octaves = int(param_value(node, "octaves"))
        lacunarity, gain = float(param_value(node, "lacunarity")), float(param_value(node, "gain"))
        schedule = octave_schedule(octaves, lacunarity, gain, fx, fy)
        return simplex_wraps(schedule.freqs_x, schedule.freqs_y, frame)
    return wraps(fx * px) and wraps(fy * py)


def _frequencies(node: A.Call) -> tuple[float, float]:
    """(fx, fy) of a noise: ``base_freq_x``/``base_freq_y``, each defaulting to ``base_freq``."""
    base = float(param_value(node, "base_freq"))
    fx, fy = param_value(node, "base_freq_x"), param_value(node, "base_freq_y")
    return float(base if fx is None else fx), float(base if fy is None else fy)
