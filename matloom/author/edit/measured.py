"""Measured coverage: more or less of a layer, or of a feature mask drawn inside the channels,
by moving what its coverage depends on until the measured coverage (the mask evaluated on a
small grid) reaches the goal ("more rust", "fewer blisters", "thicker came").

In order: a parameter that moves only this coverage; a threshold of the mask itself
(``Smoothstep`` edges, or a clamping ``Threshold`` moved by its input so its values keep their
range); a parameter shared with other parts. Used by the condition rule
(:mod:`matloom.author.edit.conditions`) and the scale and joint rules.
"""

from __future__ import annotations

import re
from collections.abc import Sequence
from dataclasses import dataclass, replace

import numpy as np

from matloom.author.edit.apply import apply_edit, parse_program
from matloom.author.edit.lexicon import split_words, stem
from matloom.author.edit.plan import Context, Plan, Value, affects, assign, clamp
from matloom.author.edit.targets import define_closure, mask_names, refs_of
from matloom.engine.evaluate import evaluate
from matloom.lang import ast as A
from matloom.lang.params import Param
from matloom.lang.printer import format_expr

#: Grid the coverage of a condition's layer is measured on.
PROBE = 48


@dataclass(frozen=True)
class _Candidate:
    """Parameters moved together by one shift (a Threshold's two edges), whether they feed
    nothing but the condition's layer, and whether they are a named constant."""

    params: tuple[Param, ...]
    exclusive: bool
    constant: bool


#: Static parameters that are the two edges of one ramp: shifting both moves where it falls.
_EDGES = (("below_at", "above_at"), ("lo", "hi"), ("edge0", "edge1"))


_CUTOFF_RE = re.compile(r"define:(\w+)\..*Threshold(?:#(\d+))?\.(below|above)_at$")


def _clamp_cutoff(program: A.Program, address: str) -> bool:
    """Whether the parameter is a ``Threshold`` cutoff with no ``*_to`` value: a clamp, whose
    cutoff is also its output value (``Threshold(x, below_at=0, above_at=1)`` is ``x`` clamped
    to 0..1), so moving it changes every value, not where the mask falls."""
    m = _CUTOFF_RE.match(address)
    d = program.define(m.group(1)) if m is not None else None
    if m is None or d is None:
        return False
    # the n-th Threshold of the Define in source order, as the parameter list numbers them
    calls = sorted(
        (n for n in A.walk(d.expr) if isinstance(n, A.Call) and n.func == "Threshold"),
        key=lambda n: n.span.start,
    )
    k = int(m.group(2) or 1) - 1
    return k < len(calls) and f"{m.group(3)}_to" not in calls[k].written()


def mask_coverage(program: A.Program, mask: A.Node) -> float:
    probe = A.Program(
        program.view,
        program.defines,
        (
            A.Layer(None, (A.ChannelSet("roughness", (A.Num(0),)),)),
            A.Layer(mask, (A.ChannelSet("roughness", (A.Num(1),)),)),
        ),
    )
    maps = evaluate(probe, PROBE, PROBE)
    return float(np.nanmean(maps.roughness))


def _candidates(c: Context, index: int, mask: A.Node | None = None) -> list[_Candidate]:
    """Scalar parameters the coverage of layer ``index`` (0-based; or of ``mask``, a feature
    drawn inside the channels, with ``index`` -1) depends on: those feeding nothing else first,
    a ramp's two edges together before either alone, named constants before parameters inside
    calls."""
    program = c.program
    closure = define_closure(program)
    mask_refs = refs_of(mask if mask is not None else program.layers[index].alpha, closure)
    others: set[str] = set()
    for i, layer in enumerate(program.layers):
        if i == index:  # the layer's own channels go with its coverage
            continue
        for ch in layer.channels:
            others |= {r for a in ch.args for r in refs_of(a, closure)}
        others |= refs_of(layer.alpha, closure)
    singles: list[_Candidate] = []
    for p in c.params:
        if p.kind != "scalar" or p.address.endswith(".base"):
            continue
        m = re.match(r"define:(\w+)(\.|$)", p.address)
        if m is None or m.group(1) not in mask_refs or _clamp_cutoff(program, p.address):
            continue
        singles.append(_Candidate((p,), m.group(1) not in others, m.group(2) == ""))
    by = {k.params[0].address: k for k in singles}
    pairs = []
    for k in singles:
        for lo, hi in _EDGES:
            if k.params[0].address.endswith(f".{lo}"):
                other = by.get(k.params[0].address[: -len(lo)] + hi)
                if other is not None:
                    pairs.append(_Candidate((k.params[0], other.params[0]), k.exclusive, False))
    out = pairs + singles
    out.sort(key=lambda k: (not k.exclusive, not k.constant, len(k.params) == 1))
    return out


def _shift(c: Context, cand: _Candidate, mask: A.Node, now: float, goal: float):  # noqa: ANN202
    """The shift of the candidate's values whose measured coverage is nearest ``goal`` (on
    the side of ``now`` it asks for): (values, coverage), or None."""
    ps = cand.params
    vs = [float(p.value) for p in ps]  # type: ignore[arg-type]
    span = max(max(abs(v) for v in vs), abs(vs[-1] - vs[0]), 0.25)
    best = None
    for f in (0.1, 0.2, 0.35, 0.5, 0.75, 1.0, 1.5, 2.0):
        for sign in (1, -1):
            xs = [clamp(p, v + sign * f * span) for p, v in zip(ps, vs, strict=True)]
            if xs == vs:
                continue
            try:
                text, _ = apply_edit(c.program, {p.address: x for p, x in zip(ps, xs, strict=True)})
                cov = mask_coverage(parse_program(text), mask)
            except ValueError:
                continue
            if (cov - now) * (goal - now) <= 0:
                continue
            if best is None or abs(cov - goal) < abs(best[1] - goal):
                best = (xs, cov)
    return best


def measured_coverage(
    c: Context,
    index: int,
    more: bool,
    word: str,
    grow: tuple[float, float] | None = None,
    prefer: Sequence[str] = (),
    feature: A.Node | None = None,
) -> Plan | None:
    """The coverage of layer ``index`` grown (or shrunk) to its goal by moving a parameter it
    depends on, else by shifting the edges of a ``Smoothstep`` of numbers in a Define it reads
    (those named like ``prefer`` first: "thicker came" moves ``came``'s threshold). ``joint``:
    ``grow``: the coverage factor and least change when not a condition's (a joint's width
    x1.6, at least +0.03; more of a part x2, at least +0.05). ``feature``: a mask drawn inside
    the channels ("fewer blisters"), measured instead of a layer's coverage (``index`` -1)."""
    mask = feature if feature is not None else c.program.layers[index].alpha
    assert mask is not None
    now = mask_coverage(c.program, mask)
    k = c.k
    factor, least = grow or (c.ew.f("cover_more"), c.ew.f("cover_min"))
    if more:
        goal = min(0.95, max(now * factor**k, now + least * k))
        if now >= 0.93:
            raise c.refuse(f"the {word} covers {now:.0%} already")
    else:
        goal = min(now * c.ew.f("cover_less") ** k, now - c.ew.f("cover_min") * k)
        # a sparse feature ("fewer pits" on 4 %) keeps some of it; "remove" or "fill" all
        gone = set(c.words) & {"remove", "fill", "no", "without", "eliminate"}
        goal = 0.0 if gone else max(now * 0.4, goal)
        if now <= 0.005:
            raise c.refuse(f"the {word} covers nothing already")
    cands = _candidates(c, index, feature)
    # a parameter that moves only this coverage, then a threshold of the mask itself, then a
    # parameter shared with other parts ("more rust" moves the rust mask, not the paint's wear)
    for cand in [k for k in cands if k.exclusive]:
        plan = _by_candidate(c, cand, mask, now, goal, more, word)
        if plan is not None:
            return plan
    plan = _by_edges(c, index, prefer or (word,), feature, mask, now, goal, more, word)
    if plan is not None:
        return plan
    for cand in [k for k in cands if not k.exclusive]:
        plan = _by_candidate(c, cand, mask, now, goal, more, word)
        if plan is not None:
            return plan
    return None


def _by_candidate(
    c: Context, cand: _Candidate, mask: A.Node, now: float, goal: float, more: bool, word: str
) -> Plan | None:
    best = _shift(c, cand, mask, now, goal)
    if best is not None and abs(best[1] - now) >= 0.5 * abs(goal - now):
        note = f"{'more' if more else 'less'} {word}: coverage {now:.0%} -> {best[1]:.0%}"
        new: dict[Param, Value] = dict(zip(cand.params, best[0], strict=True))
        return assign(c, "amount", note, new, affects(cand.params), graded=True)
    return None


def _by_edges(
    c: Context,
    index: int,
    prefer: Sequence[str],
    feature: A.Node | None,
    mask: A.Node,
    now: float,
    goal: float,
    more: bool,
    word: str,
) -> Plan | None:
    for name, lines in _edge_shifts(c, index, prefer, feature):
        best_lines = None
        for text in lines:
            try:
                program = parse_program(apply_edit(c.program, {}, None, text)[0])
                cov = mask_coverage(program, mask)
            except ValueError:
                continue
            if (cov - now) * (goal - now) > 0 and (
                best_lines is None or abs(cov - goal) < abs(best_lines[1] - goal)
            ):
                best_lines = (text, cov)
        if best_lines is not None and abs(best_lines[1] - now) >= 0.5 * abs(goal - now):
            note = (
                f"{'more' if more else 'less'} {word}: coverage {now:.0%} -> {best_lines[1]:.0%}"
                f" (the edges of {name}'s threshold moved)"
            )
            # a coverage moves every channel the layer writes
            return Plan("amount", note, lines=best_lines[0], intended=("alpha",), graded=False)
    return None


def _input_shifts(d: A.Define, e: A.Call) -> list[dict[str, str]]:
    """A clamping ``Threshold(x, below_at=a, above_at=b)`` (no ``*_to``) moved by shifting its
    input (``x - s``), by a growing share of ``b - a`` each way: its output keeps its range."""
    named = {a.param: a.value for a in e.args if a.param}
    lo, hi = named.get("below_at"), named.get("above_at")
    if "below_to" in named or "above_to" in named or not e.args or e.args[0].param != "expr":
        return []
    if not (isinstance(lo, A.Num) and isinstance(hi, A.Num)) or hi.value <= lo.value:
        return []
    span = float(hi.value) - float(lo.value)
    out = []
    for f in (0.25, 0.5, 1.0, 1.5, 2.0, 3.0):
        for sign in (1, -1):
            x = A.BinOp("-" if sign > 0 else "+", e.args[0].value, _number(f * span))
            args = (replace(e.args[0], value=x), *e.args[1:])
            out.append(
                {f"define:{d.name}": f"Define({d.name}, {format_expr(replace(e, args=args))})"}
            )
    return out


def _number(v: float) -> A.Node:
    v = float(f"{v:.4g}")
    return A.Num(v) if v >= 0 else A.Neg(A.Num(-v))


def _edge_shifts(
    c: Context, index: int, prefer: Sequence[str], feature: A.Node | None = None
) -> list[tuple[str, list[dict[str, str]]]]:
    """For each Define the layer's coverage reads that is a ``Smoothstep`` with two number
    edges (named like ``prefer`` first): the line rewritten with both edges shifted, by a
    growing share of their scale each way."""
    closure = define_closure(c.program)
    names = refs_of(feature if feature is not None else c.program.layers[index].alpha, closure)
    want = {stem(w) for w in prefer}
    out = []
    for d in c.program.defines:
        e = d.expr
        if d.name in names and isinstance(e, A.Call) and e.func == "Threshold":
            shifted = _input_shifts(d, e)
            if shifted:
                out.append((d.name, shifted))
            continue
        if d.name not in names or not (isinstance(e, A.Call) and e.func == "Smoothstep"):
            continue
        edges = [a.value for a in e.args[:2]]
        if len(e.args) < 3 or not all(isinstance(x, A.Num) for x in edges):
            continue
        lo, hi = (float(x.value) for x in edges)  # type: ignore[union-attr]
        span = max(abs(hi - lo) * 2, 0.5 * max(abs(lo), abs(hi)), 0.01)
        variants = []
        for f in (0.25, 0.5, 1.0, 1.5, 2.0, 3.0, 4.0):
            for sign in (1, -1):
                dv = sign * f * span
                args = (
                    replace(e.args[0], value=_number(lo + dv)),
                    replace(e.args[1], value=_number(hi + dv)),
                    *e.args[2:],
                )
                variants.append(
                    {f"define:{d.name}": f"Define({d.name}, {format_expr(replace(e, args=args))})"}
                )
        out.append((d.name, variants))
    out.sort(key=lambda x: not (split_words(x[0]) & want))
    return out


def measured_layer(
    c: Context, nouns: Sequence[str], more: bool, joint: bool = False
) -> Plan | None:
    """More or less of the layer (above the first) whose coverage a noun names ("more flecks",
    "thicker came"), measured."""
    want = {stem(n) for n in nouns}
    if not want:
        return None
    # the nouns in the request's order: "more weeds out of the cracks" is the weeds' layer
    for noun in dict.fromkeys(stem(n) for n in nouns):
        for i, layer in enumerate(c.program.layers):
            if i == 0 or layer.alpha is None:
                continue
            names = [n for n in mask_names(layer.alpha) if noun in split_words(n)]
            if names:
                grow = (1.6, 0.03) if joint else (2.0, 0.05)
                plan = measured_coverage(c, i, more, names[0], grow, prefer=names)
                if plan is not None:
                    return plan
    if joint:
        return None
    # a feature drawn inside the channels ("fewer blisters": a Define ``blister`` masks them)
    for d in c.program.defines:
        if split_words(d.name) & want and _is_mask(c.program, d.name):
            plan = measured_coverage(c, -1, more, d.name, (2.0, 0.05), [d.name], A.Ref(d.name))
            if plan is not None:
                return plan
    return None


def _is_mask(program: A.Program, name: str) -> bool:
    """Whether the Define is a mask: a field within 0..1 that is 0 or 1 on much of the
    surface (a thresholded feature, not a noise or a colour component)."""
    try:
        probe = A.Program(
            program.view,
            program.defines,
            (A.Layer(None, (A.ChannelSet("roughness", (A.Ref(name),)),)),),
        )
        v = np.asarray(evaluate(probe, PROBE, PROBE).roughness, np.float64)
    except ValueError:
        return False
    if not np.all(np.isfinite(v)) or v.min() < -1e-6 or v.max() > 1 + 1e-6:
        return False
    return float(np.mean((v < 0.02) | (v > 0.98))) >= 0.6 and 0.002 < float(v.mean()) < 0.98
