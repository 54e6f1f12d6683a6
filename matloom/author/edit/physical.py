"""The physical-size rule: "1 m wide", "make it 50 cm across" (the whole material), and the
size of a feature: "pennies about 3 cm across", "10 cm boards", "stitch rows 1 cm apart",
"50 cm squares, not these 1 m panels".

A size given for the **whole material** (no feature noun, or "the texture should cover 2 m")
spans the View: with ``unit_m`` known the window grows or shrinks (features keep their size),
else ``unit_m`` is set.

A size given for a **feature** is that feature's size: the noun nearest the number names a
part of the program (a layer's coverage, a Define, or the layers a colour named like it
paints; else, for a shape word such as "squares", the material's height map), the part is
measured in texture units (:mod:`matloom.author.edit.measure`: "apart" is its period, "wide"
its width, "across" its extent), and ``unit_m`` is set so that the feature measures the size
asked. The window then keeps its physical span when the old scale is known (``unit_m``, or a
size the request gives as the current one: "not these 1 m panels"), so the feature shows at
its new size; with no scale known, a direction word ("narrower", "closer together", "too
small") zooms the View that way as well (x2 when it tiles), so the change shows.
"""

from __future__ import annotations

import math
import re
from collections.abc import Sequence
from dataclasses import replace

from matloom.author.edit.lexicon import flipped, split_words, stem
from matloom.author.edit.measure import SIZE, feature_size, mask_map
from matloom.author.edit.plan import Context, Plan
from matloom.author.edit.targets import layer_words, overlaps, own_words, param_layers, wanted
from matloom.lang import ast as A
from matloom.lang.tileable import tileable_warnings

SIZE_RE = re.compile(
    r"(\d+(?:\.\d+)?)\s*(mm|millimet(?:er|re)s?|cm|centimet(?:er|re)s?|m|met(?:er|re)s?|"
    r"in|inch(?:es)?|ft|foot|feet)\b"
)

#: Words that make a size the whole material's ("the texture should cover 2 m").
_WHOLE = frozenset(
    {"texture", "material", "whole", "entire", "cover", "covers", "covering", "span", "spans",
     "swatch", "sample", "overall", "image", "everything", "repeat"}
)  # fmt: skip
#: A size of the spacing between features ("1 cm apart"): their period.
_APART = frozenset(
    {"apart", "spacing", "spaced", "pitch", "interval", "intervals", "every", "centres",
     "centers", "between"}
)  # fmt: skip
#: Features that are "apart" across their length (rows are spaced by the larger period).
_ROWS = frozenset({"row", "line", "stripe", "band", "course", "strip", "stitch", "seam"})
_WIDTH = frozenset(
    {"wide", "width", "narrow", "narrower", "thick", "thickness", "thin", "thinner", "wider",
     "thicker", "broad", "broader"}
)  # fmt: skip
_LONG = frozenset({"long", "length", "longer", "shorter", "tall", "height"})
#: Words before a size that make it the current one ("not these 1 m panels").
_CURRENT = frozenset({"not", "these", "those", "from", "currently", "now", "instead", "existing"})
#: Shape words that name a feature even when the program names nothing like them.
#: A shape measured on the whole map smaller than the View's side / this (3 pixels of a
#: 192-pixel preview) is its texture's grain, not the shape the request names.
_FINEST = 64.0
_SHAPES = frozenset(
    {"square", "check", "cell", "panel", "grid", "row", "line", "stripe", "band", "dot", "spot",
     "piece", "strip", "circle", "round", "hexagon", "diamond", "plank", "module"}
)  # fmt: skip
#: Words that are no feature ("about 3 cm", "more like 10 cm", "closer together").
_NOT_NOUNS = frozenset(
    {"about", "around", "roughly", "approximately", "like", "should", "be", "together",
     "these", "those", "read", "reads", "please", "not", "than", "each", "per", "across",
     "apart", "size", "big", "closer", "further", "farther", "we", "re", "need", "needs",
     "want", "instead", "ish", "approx", "scale", "feel", "now", "just"}
)  # fmt: skip
#: Direction words beyond the bigger/smaller/denser/sparser lists.
_CLOSER, _FURTHER = frozenset({"closer", "nearer"}), frozenset({"further", "farther"})


# ---- the View's window -------------------------------------------------------------------------
def window(program: A.Program) -> tuple[float, float, float, float]:
    return program.view_tuple


def tiles(c: Context, win: Sequence[float]) -> bool:
    """Whether the program still tiles (when it did) with the View's window ``win``."""
    if not c.program.tileable:
        return True
    assert c.program.view is not None
    x1, y1, x2, y2 = win
    moved = replace(c.program, view=replace(c.program.view, x1=x1, y1=y1, x2=x2, y2=y2))
    return len(tileable_warnings(moved)) <= len(tileable_warnings(c.program))


def zoomed(c: Context, ratio: float) -> list[float]:
    x1, y1, x2, y2 = window(c.program)
    return [x1, y1, float(f"{x1 + (x2 - x1) * ratio:.6g}"), float(f"{y1 + (y2 - y1) * ratio:.6g}")]


def _ratios(c: Context, ratio: float) -> list[float]:
    """``ratio`` itself, or for a program that tiles the nearest whole or unit-fraction ratio."""
    if not c.program.tileable:
        return [ratio]
    return [float(round(ratio))] if ratio >= 1 else [1 / round(1 / ratio)]


def _fitting(c: Context, ratios: Sequence[float]) -> float | None:
    for r in ratios:
        if r > 0 and abs(r - 1) > 1e-9 and tiles(c, zoomed(c, r)):
            return r
    return None


# ---- reading the request -----------------------------------------------------------------------
def _sizes(c: Context) -> tuple[tuple[float, int] | None, float | None]:
    """The size asked (metres, its offset in the request) and the current size the request
    gives ("not these 1 m panels"), in metres."""
    text = c.request.lower()
    target: tuple[float, int] | None = None
    current: float | None = None
    for m in SIZE_RE.finditer(text):
        metres = float(m.group(1)) * c.vocabulary.units[m.group(2)]
        before = re.findall(r"[a-z']+", text[: m.start()])[-3:]
        if set(before) & _CURRENT:
            current = current if current is not None else metres
        elif target is None:
            target = (metres, m.start())
    return target, current


def _direction(c: Context) -> bool | None:
    """Whether the request asks for the feature bigger (True), smaller (False) or neither
    ("too small" and "not these big" flip the word)."""
    ew = c.ew
    up = ew["bigger"] | ew["sparser"] | ew["width_up"] | _FURTHER
    down = ew["smaller"] | ew["denser"] | (ew["width"] - ew["width_up"]) | _CLOSER
    for i, t in enumerate(c.words):
        if t in up or t in down:
            bigger = t in up
            return not bigger if flipped(c.words, i, ew["flip"] | {"not"}) else bigger
    return None


def _nouns(c: Context, at: int) -> list[str]:
    """The request's feature nouns, the nearest to the size first."""
    ew = c.ew
    skip = _NOT_NOUNS | _WHOLE | _APART | _WIDTH | _LONG | set(c.vocabulary.units)
    skip |= ew["bigger"] | ew["smaller"] | ew["denser"] | ew["sparser"] | ew["width"]
    skip |= ew["flip"] | ew["more"] | ew["less"]
    spans = [
        (m.start(), m.group(0)) for m in re.finditer(r"[a-z0-9]+(?:\.[0-9]+)?", c.request.lower())
    ]
    out = [
        (abs(pos - at), w)
        for pos, w in spans
        if w not in ew["filler"] and w not in skip and not w[0].isdigit() and len(w) >= 3
    ]
    return [w for _, w in sorted(out)]


def _mask_of(c: Context, noun: str) -> A.Node | None:
    """The coverage a noun names: a layer's (above the first; one drawn by the noun alone
    before one it only limits), a Define named like it, or the layer a colour named like it
    paints ("checks": the layers ``check_r`` colours)."""
    program = c.program
    for families in (False, True):
        want = wanted([noun], c.ew, families=families)
        named = [
            i
            for i in range(1, len(program.layers))
            if overlaps(layer_words(program, i, c.ew), want)
        ]
        if named:
            return program.layers[named[0]].alpha
        for d in program.defines:
            if overlaps(split_words(d.name), want) and not _constant(d.expr):
                return A.Ref(d.name)
    want = wanted([noun], c.ew, families=False)
    for p in c.params:
        if p.kind == "colour" and overlaps(own_words(p), want):
            layers = sorted(i for i in param_layers(p, program) if i > 0)
            if layers:
                return program.layers[layers[0]].alpha
    return None


def _repeated(program: A.Program) -> A.Program:
    """``program`` over a window twice as wide and tall when it tiles (else itself)."""
    v = program.view
    if v is None or not v.tileable:
        return program
    view = replace(v, x2=v.x1 + 2 * (v.x2 - v.x1), y2=v.y1 + 2 * (v.y2 - v.y1))
    return replace(program, view=view)


def _constant(node: A.Node) -> bool:
    return not any(isinstance(n, A.Call) or isinstance(n, A.Ref) for n in A.walk(node))


# ---- the rule ----------------------------------------------------------------------------------
def physical_rule(c: Context) -> Plan | None:
    target, current = _sizes(c)
    if target is None or c.ew["joint"] & set(c.words):
        return None
    metres, at = target
    if metres <= 0:
        raise c.refuse("a physical size must be positive")
    if not (_WHOLE & set(c.words)):
        plan = _feature(c, metres, at, current)
        if plan is not None:
            return plan
    return _whole(c, metres)


def _whole(c: Context, metres: float) -> Plan:
    x1, _, x2, _ = window(c.program)
    side = abs(x2 - x1) or 1.0
    unit_m = c.program.unit_m
    if unit_m:  # the scale is known: the window spans the size, features keep theirs
        r = _fitting(c, _ratios(c, metres / unit_m / side))
        if r is None:
            raise c.refuse(
                f"the View spans {side * unit_m:g} m already (or cannot tile at {metres:g} m)"
            )
        return Plan(
            "physical size",
            f"the View spans {side * r * unit_m:g} m (unit_m {unit_m:g} kept): window x{r:.4g}",
            view={"window": zoomed(c, r)},
            intended=("alpha",),
        )
    unit_m = float(f"{metres / side:.6g}")
    return Plan(
        "physical size",
        f"the View spans {metres:g} m: unit_m = {unit_m:g}",
        view={"unit_m": unit_m},
        intended=(),
    )


def _feature(c: Context, metres: float, at: int, current: float | None) -> Plan | None:
    ws = {stem(t) for t in c.words}
    how = "apart" if ws & _APART else "width" if ws & _WIDTH else "length" if ws & _LONG else ""
    how = how or "across"
    x1, y1, x2, y2 = window(c.program)
    sx, sy = abs(x2 - x1) or 1.0, abs(y2 - y1) or 1.0
    size: float | None = None
    noun = ""
    # a tileable program is measured over two repeats each way: a feature the window's edge
    # cuts (a checkerboard's squares, offset from the corner) shows whole there
    whole = _repeated(c.program)
    k = 2.0 if whole is not c.program else 1.0
    for noun in _nouns(c, at):
        mask = _mask_of(c, noun)
        if mask is None:
            continue
        rows = bool({stem(n) for n in c.nouns} & _ROWS)
        size = feature_size(mask_map(whole, mask, int(SIZE * k)), sx * k, sy * k, how, rows)
        if size:
            break
    else:
        shapes = [n for n in _nouns(c, at) if stem(n) in _SHAPES]
        if not shapes:
            return None
        noun = shapes[0]
        rows = stem(noun) in _ROWS
        size = feature_size(mask_map(c.program, None), sx, sy, how, rows)
        if size and size < min(sx, sy) / _FINEST:
            # the whole map's finest pattern (a pile's tufts) is no named shape
            raise c.refuse(f"the {noun} cannot be measured: no part of the program draws them")
    if not size or not math.isfinite(size):
        return None
    unit_m = float(f"{metres / size:.6g}")
    old = c.program.unit_m or (current / size if current else None)
    ratio: float | None = None
    if old:  # the window keeps its physical span: the feature shows at its new size
        ratio = _fitting(c, _ratios(c, old / unit_m))
    else:
        bigger = _direction(c)
        if bigger is not None:
            f = 2.0 if c.program.tileable else c.ew.f("size")
            ratio = _fitting(c, [1 / f if bigger else f])
    what = f"{noun} {how} {size:.4g} units"
    note = f"{what} = {metres:g} m: unit_m = {unit_m:g}"
    view: dict[str, object] = {"unit_m": unit_m}
    if ratio is not None:
        view["window"] = zoomed(c, ratio)
        note += f", window x{ratio:.4g}"
    elif c.program.unit_m is not None and abs(unit_m - c.program.unit_m) < 1e-9:
        raise c.refuse(f"the {noun} measure {metres:g} m already")
    return Plan("physical size", note, view=view, intended=("alpha",) if ratio is not None else ())
