"""Composition: prompt -> interpretation -> recipe -> filled program -> overlays -> canonical text.

:func:`author` never fails. When no recipe scores at least ``MIN_SCORE`` it builds a generic
material from the colours and finish words it did recognise, and says so in the notes. The
result is deterministic for a given (prompt, seed): every noise seed is derived by hashing the
prompt, the user seed, the recipe and the noise's name, and nothing else depends on the seed.
"""

from __future__ import annotations

import hashlib
import re
from dataclasses import dataclass, field

import matloom
from matloom.author.builtin import colours as C
from matloom.author.builtin import modifiers as M
from matloom.author.builtin.generic import GENERIC
from matloom.author.builtin.interpret import Condition, Interpretation, interpret
from matloom.author.builtin.recipes import Recipe
from matloom.author.builtin.scoring import MIN_SCORE, Scored, find_all, rank
from matloom.author.builtin.slots import Filled, fill
from matloom.author.builtin.template import SlotValues, fmt, render

MAX_LINES = 40
MAX_OVERLAYS = 3


@dataclass
class AuthorResult:
    """What the built-in author produced for one prompt, and why."""

    program: str
    explanation: str
    recipe: str
    slots: dict[str, object]
    modifiers: list[str]
    score: float = 0.0
    notes: list[str] = field(default_factory=list)
    runners_up: list[tuple[str, float]] = field(default_factory=list)


def derive_seed(prompt: str, seed: int, recipe: str, name: str) -> int:
    """A noise seed in [0, 2**31) from (prompt, user seed, recipe, noise name)."""
    key = f"{prompt.strip()}\x1f{seed}\x1f{recipe}\x1f{name}".encode()
    return int.from_bytes(hashlib.sha256(key).digest()[:4], "big") & 0x7FFFFFFF


def _values(
    recipe: Recipe,
    filled: Filled,
    prompt: str,
    seed: int,
    colours: dict[str, C.RGB] | None = None,
    view: float | None = None,
) -> SlotValues:
    micro = filled.micro
    return SlotValues(
        colours=colours or filled.colours,
        scalars=filled.scalars,
        view=view if view is not None else filled.view,
        relief_scale=filled.scalars.get("relief", 1.0),
        view_ratio=filled.view / recipe.slots["view"],
        seed_for=lambda name: derive_seed(prompt, seed, recipe.name, name),
        micro_parts=micro.parts() if micro else {},
        micro_colour=micro.colour if micro else None,
    )


def _overlay_colour(cond: Condition, overlay: M.Overlay, base: C.RGB) -> C.RGB:
    if cond.colour is not None:
        return cond.colour
    if cond.kind in M.DERIVED_COLOUR:
        lighten, desat = M.DERIVED_COLOUR[cond.kind]
        return C.desaturate(C.shade(base, lighten), desat)
    return overlay.colour


def _overlay_texts(
    recipe: Recipe, filled: Filled, conds: list[Condition], prompt: str, seed: int
) -> list[tuple[str, str, str]]:
    """(kind, defines, layer) for each condition overlay, rendered."""
    base = filled.colours[recipe.colours[0].name]
    out = []
    for cond in conds:
        overlay = M.OVERLAYS[cond.kind]
        colours = {"_base": base, "_cond": _overlay_colour(cond, overlay, base)}
        values = _values(recipe, filled, prompt, seed, colours, filled.view * cond.scale**0.5)
        values.scalars = {"cut": M.CUT_BASE - M.CUT_SLOPE * cond.amount}
        out.append((cond.kind, render(overlay.defines, values), render(overlay.layer, values)))
    return out


def _inject(text: str, channel: str) -> str:
    """Add ``channel`` (e.g. ``.transmission(0.4)``) to the bottom layer unless it sets it."""
    start = text.find("Layer(1)")
    if start < 0:
        return text
    nxt = text.find("Layer(", start + 8)
    block = text[start : nxt if nxt > 0 else len(text)]
    if channel.split("(")[0] + "(" in block:
        return text
    end = start + len("Layer(1)")
    return text[:end] + "\n    " + channel + text[end:]


_DEFINE_NAME = re.compile(r"Define\((\w+),")


def _dedupe_names(body: str, defines: str, layer: str) -> tuple[str, str]:
    """Rename overlay Defines that clash with the recipe's own names (``crack`` -> ``crack2``)."""
    taken = set(_DEFINE_NAME.findall(body))
    for name in _DEFINE_NAME.findall(defines):
        if name in taken:
            new = f"{name}2"
            pattern = re.compile(rf"\b{name}\b")
            defines, layer = pattern.sub(new, defines), pattern.sub(new, layer)
    return defines, layer


def _assemble(body: str, overlays: list[tuple[str, str, str]]) -> str:
    """Insert overlay Defines before ``Material(`` and overlay layers before its last ``)``."""
    if not overlays:
        return body
    head, _, material = body.partition("Material(")
    inner = material.rstrip()[:-1].rstrip()
    defines = "\n".join(d for _, d, _ in overlays)
    layers = ",\n".join(layer for _, _, layer in overlays)
    return f"{head.rstrip()}\n{defines}\nMaterial({inner},\n{layers}\n)"


def _finish_channels(recipe: Recipe, it: Interpretation, text: str, notes: list[str]) -> str:
    if "translucent" in it.finishes or "transparent" in it.finishes:
        if recipe.family != "glass":
            text = _inject(text, ".transmission(0.35)")
            notes.append("translucent: transmission 0.35 on the base layer")
    if "metallic" in it.finishes and recipe.family != "metal":
        text = _inject(text, ".metallic(0.45)")
        notes.append("metallic: metallic 0.45 on the base layer")
    return text


def _extra_conditions(recipe: Recipe, it: Interpretation) -> list[Condition]:
    conds = list(it.conditions)
    if "glowing" in it.finishes and recipe.family != "emissive":
        conds.append(Condition("glowing", "glowing", 0.5))
    if "iridescent" in it.finishes and "iridescent" not in recipe.patterns:
        conds.append(Condition("iridescent", "iridescent", 0.5))
    return conds


def _build(
    recipe: Recipe, it: Interpretation, prompt: str, seed: int, notes: list[str]
) -> tuple[str, Filled, list[str]]:
    filled = fill(recipe, it)
    body = render(recipe.template, _values(recipe, filled, prompt, seed))
    body = _finish_channels(recipe, it, body, notes)
    conds = [
        c
        for c in _extra_conditions(recipe, it)
        if c.kind in M.OVERLAYS and c.kind not in filled.absorbed
    ]
    if len(conds) > MAX_OVERLAYS:
        notes.append("dropped modifiers (at most 3): " + ", ".join(c.kind for c in conds[3:]))
        conds = conds[:MAX_OVERLAYS]
    overlays = [
        (kind, *_dedupe_names(body, d, layer))
        for kind, d, layer in _overlay_texts(recipe, filled, conds, prompt, seed)
    ]
    while True:
        text = matloom.format(_assemble(body, overlays))
        if text.count("\n") + 1 <= MAX_LINES or not overlays:
            break
        notes.append(f"dropped modifier {overlays[-1][0]} to keep the program short")
        overlays = overlays[:-1]
    return _tileable(text, notes), filled, [kind for kind, _, _ in overlays]


def _tileable(text: str, notes: list[str]) -> str:
    """``text`` with ``View(..., tileable=True)`` when nothing in it keeps it from repeating
    (no W009/W010, see :mod:`matloom.lang.tileable`); otherwise unchanged, with a note saying
    why (e.g. a Rotate of a noise, a radial pattern, bricks that do not divide the View)."""
    from matloom.lang.tileable import make_tileable, tileable_warnings

    program = matloom.parse(text)
    tiled = make_tileable(program)
    warnings = tileable_warnings(tiled, text)
    if warnings:
        notes.append("not tileable: " + warnings[0].message.removeprefix("tileable: "))
        return text
    return matloom.format(tiled)


def _explain(
    prompt: str,
    best: Scored | None,
    ranked: list[Scored],
    recipe: Recipe,
    filled: Filled,
    mods: list[str],
    it: Interpretation,
    notes: list[str],
) -> str:
    lines = [f"prompt: {prompt.strip()}"]
    if best is None:
        lines.append(f"recipe: {recipe.name} (generic fallback: no recipe scored >= {MIN_SCORE})")
    else:
        lines.append(f"recipe: {recipe.name} [{recipe.family}] - {recipe.summary}")
        lines.append(f"  score {best.score:.1f}: " + "; ".join(best.reasons))
        others = [f"{s.recipe.name} {s.score:.1f}" for s in ranked[1:4]]
        if others:
            lines.append("  runners-up: " + ", ".join(others))
    lines.append("slots:")
    lines.append(
        f"  view {fmt(filled.view)}; "
        + "; ".join(
            f"{k} {v if isinstance(v, str) else fmt(v)}"
            for k, v in filled.scalars.items()
            if k != "view"
        )
    )
    lines.append("  colours: " + "; ".join(f"{k} {v}" for k, v in filled.colours.items()))
    lines.extend(f"  - {r}" for r in filled.reasons)
    if mods:
        lines.append("modifiers: " + ", ".join(f"{m} ({M.OVERLAYS[m].summary})" for m in mods))
    lines.extend(f"note: {n}" for n in notes)
    return "\n".join(lines)


def _consume(it: Interpretation, best: Scored | None, recipe: Recipe) -> None:
    if best is not None:
        it.consumed.update(best.matched)
    for word in [*recipe.tags, *recipe.presets]:
        for pos in find_all(word, it):
            it.consumed.update(range(pos, pos + len(word.split())))
    from matloom.author.builtin.micro import MICRO_WORDS

    it.consumed.update(t.index for t in it.tokens if t.text in MICRO_WORDS)


def build_recipe(name: str, prompt: str = "", seed: int = 0) -> str:
    """Canonical program of recipe ``name`` filled from ``prompt`` (its defaults when empty).

    Unlike :func:`author` it does not choose the recipe and lets errors propagate: the tests use
    it to check that every recipe of the library yields a clean program.
    """
    from matloom.author.builtin.recipes import REGISTRY

    recipe = GENERIC if name == GENERIC.name else REGISTRY[name]
    text, _, _ = _build(recipe, interpret(prompt), prompt, seed, [])
    return text


def author(prompt: str, seed: int = 0) -> AuthorResult:
    """Write a MatLoom program for ``prompt`` with the built-in recipe library (no model)."""
    it = interpret(prompt or "")
    ranked = rank(it)
    best = ranked[0] if ranked and ranked[0].score >= MIN_SCORE else None
    recipe = best.recipe if best else GENERIC
    notes: list[str] = []
    try:
        text, filled, mods = _build(recipe, it, prompt, seed, notes)
    except Exception as exc:  # noqa: BLE001 - the author must never fail; fall back
        notes.append(f"recipe {recipe.name} failed ({exc}); used the generic material")
        recipe, best = GENERIC, None
        text, filled, mods = _build(recipe, it, prompt, seed, notes)
    if best is None:
        notes.append(
            "no recipe matched the request; built a generic material from the "
            "recognised colours and finish words"
        )
    _consume(it, best, recipe)
    unknown = it.unknown_words()
    if unknown:
        notes.append("not understood: " + ", ".join(unknown[:12]))
    slots: dict[str, object] = {**filled.scalars, "view": filled.view, **filled.colours}
    if filled.micro:
        slots["micro"] = filled.micro.name
    return AuthorResult(
        program=text,
        explanation=_explain(prompt, best, ranked, recipe, filled, mods, it, notes),
        recipe=recipe.name,
        slots=slots,
        modifiers=mods,
        score=best.score if best else 0.0,
        notes=notes,
        runners_up=[(s.recipe.name, round(s.score, 2)) for s in ranked[1:4]],
    )
