"""Slot filling: from an interpretation and a recipe to concrete colours and scalar values.

Order of precedence (later wins): recipe defaults, word presets ("walnut", "copper"), finish
words (roughness, relief), scale words / explicit sizes / counts (View size), then explicit
colours. Every decision appends a short reason, which the explanation prints.
"""

from __future__ import annotations

import colorsys
from dataclasses import dataclass, field

from matloom.author.builtin import colours as C
from matloom.author.builtin import words as W
from matloom.author.builtin.interpret import ColourMention, Interpretation
from matloom.author.builtin.micro import GENERIC_MICRO_WORDS, MICRO_WORDS, MICROS, Micro
from matloom.author.builtin.recipes import Recipe
from matloom.author.builtin.scoring import find_phrase

#: basic colour words whose hue is kept but whose tone is pulled toward the recipe's own colour
#: ("red brick" should look like brick, not like a red plastic).
BASIC_NAMES = frozenset(
    "red green blue brown yellow orange grey gray purple pink white black".split()
)
_GAP_NOUNS = frozenset(
    {
        "gap",
        "gaps",
        "space",
        "spaces",
        "grout",
        "mortar",
        "joint",
        "joints",
        "seam",
        "seams",
        "spacing",
    }
)
VIEW_RANGE = (0.25, 4.0)


@dataclass
class Filled:
    """The resolved slot values of one recipe for one prompt, with the reasons."""

    colours: dict[str, C.RGB]
    scalars: dict[str, float]
    view: float
    micro: Micro | None
    reasons: list[str] = field(default_factory=list)
    absorbed: list[str] = field(default_factory=list)


def _hue_distance(a: C.RGB, b: C.RGB) -> float:
    ha = colorsys.rgb_to_hsv(*(v / 255 for v in a))
    hb = colorsys.rgb_to_hsv(*(v / 255 for v in b))
    d = abs(ha[0] - hb[0])
    return min(d, 1 - d) * 360


#: families whose colours are natural material colours (prints, plastics, glass keep exact hues).
NATURAL_FAMILIES = frozenset(
    {"wood", "stone", "masonry", "concrete", "metal", "ground", "leather", "organic"}
)


def _naturalise(mention: ColourMention, default: C.RGB) -> C.RGB:
    """Pull a plain basic colour ("red") toward the recipe default when their hues agree."""
    if mention.words not in BASIC_NAMES:
        return mention.rgb
    sat = colorsys.rgb_to_hsv(*(v / 255 for v in default))[1]
    if sat < 0.12 or _hue_distance(mention.rgb, default) > 35:
        return mention.rgb
    return C.mix(mention.rgb, default, 0.45)


def assign_colours(
    recipe: Recipe, it: Interpretation, preset_colours: dict[str, C.RGB], reasons: list[str]
) -> dict[str, C.RGB]:
    """Resolve every colour role: presets, then prompt colours by role hint and order."""
    values: dict[str, C.RGB] = {r.name: r.default for r in recipe.colours}
    explicit: set[str] = set()
    for name, rgb in preset_colours.items():
        values[name] = rgb
        explicit.add(name)
    primaries = [r for r in recipe.colours if r.derive is None and r.kind != "material"]
    secondaries = [r for r in recipe.colours if r.derive is not None and r.kind != "grout"]
    taken: set[str] = set()

    def give(mention: ColourMention, role_name: str, why: str) -> None:
        rgb = mention.rgb
        if recipe.family in NATURAL_FAMILIES:
            rgb = _naturalise(mention, recipe.role(role_name).default)
        values[role_name] = rgb
        explicit.add(role_name)
        taken.add(role_name)
        reasons.append(f"colour {role_name} = '{mention.words}' {rgb} ({why})")

    pending: list[ColourMention] = []
    mentions = [m for m in it.colours if m.role != "condition"] or list(it.colours)
    for m in mentions:
        target = next(
            (r.name for r in primaries if m.role and r.kind == m.role and r.name not in taken), None
        )
        if target is None and m.role == "grout":
            target = next(
                (r.name for r in recipe.colours if r.kind == "grout" and r.name not in taken), None
            )
        if target:
            give(m, target, f"role hint '{m.role}'")
        else:
            pending.append(m)
    free = [r.name for r in primaries if r.name not in taken]
    free += [r.name for r in secondaries if r.name not in taken]
    for m, role_name in zip(pending, free, strict=False):
        give(m, role_name, "prompt order")
    for m in pending[len(free) :]:
        reasons.append(f"colour '{m.words}' unused: the recipe has no free colour role")
    _apply_tones(recipe, it, values, explicit, reasons)
    for r in recipe.colours:
        if r.derive is not None and r.name not in explicit:
            src, amount = r.derive[0], r.derive[1]
            if len(r.derive) > 2 and C.luminance(values[src]) < 0.3:
                amount = abs(amount)  # "contrast" roles lighten on dark sources
            values[r.name] = C.shade(values[src], amount)
    return values


_TONE_ROLE_NOUNS = {
    "mortar": "grout",
    "grout": "grout",
    "joint": "grout",
    "background": "base",
    "base": "base",
    "frame": "frame",
    "stripe": "accent",
    "dot": "accent",
}


def _apply_tones(
    recipe: Recipe,
    it: Interpretation,
    values: dict[str, C.RGB],
    explicit: set[str],
    reasons: list[str],
) -> None:
    """Shade roles named by tone words: "pale mortar" lightens the grout role, "dark wood"
    (a tag of the recipe) darkens its main colour."""
    for modifier, noun in it.tones:
        kind = _TONE_ROLE_NOUNS.get(noun)
        target = None
        if kind is not None:
            target = next((r.name for r in recipe.colours if r.kind == kind), None)
        elif noun in recipe.tags or noun in recipe.presets:
            target = recipe.colours[0].name
        if target is None:
            continue
        values[target] = C.apply_tone(values[target], modifier)
        explicit.add(target)
        reasons.append(f"colour {target} made {modifier} ('{modifier} {noun}')")


def _presets(recipe: Recipe, it: Interpretation, reasons: list[str]) -> tuple[dict, dict]:
    colours: dict[str, C.RGB] = {}
    scalars: dict[str, float] = {}
    for word, preset in recipe.presets.items():
        if find_phrase(word, it) is None:
            continue
        for key, value in preset.items():
            if isinstance(value, tuple):
                colours[key] = value  # type: ignore[assignment]
            elif isinstance(value, str):
                scalars[key] = value  # type: ignore[assignment]
            else:
                scalars[key] = float(value)
        reasons.append(f"preset '{word}'")
    return colours, scalars


def _finish(
    recipe: Recipe, it: Interpretation, scalars: dict[str, float], reasons: list[str]
) -> None:
    rough_set = False
    for f in it.finishes:
        if f in W.FINISH_ROUGHNESS and not rough_set:
            scalars["rough"] = W.FINISH_ROUGHNESS[f]
            rough_set = True
            reasons.append(f"rough = {scalars['rough']} (finish '{f}')")
        if f in W.FINISH_RELIEF:
            scalars["relief"] = scalars["relief"] * W.FINISH_RELIEF[f]
            reasons.append(f"relief x{W.FINISH_RELIEF[f]} (finish '{f}')")


def _view(recipe: Recipe, it: Interpretation, reasons: list[str]) -> float:
    view0 = recipe.slots["view"]
    view = view0
    for count in it.counts:
        if count.noun in recipe.count_nouns:
            view = count.value * recipe.repeat
            reasons.append(f"view {view:g} ({count.value} {count.noun}s stated)")
            return max(view0 * VIEW_RANGE[0], min(view0 * VIEW_RANGE[1], view))
    for size in it.sizes:
        if recipe.unit_m > 0 and (
            not size.noun or size.noun in recipe.count_nouns or len(it.sizes) == 1
        ):
            view = view0 * recipe.unit_m / size.metres
            reasons.append(f"view {view:.3g} (size {size.metres:g} m of {size.noun or 'unit'})")
            return max(view0 * VIEW_RANGE[0], min(view0 * VIEW_RANGE[1], view))
    if it.scale != 1.0:
        view = view0 / it.scale
        reasons.append(f"view {view:.3g} (scale words {', '.join(it.scale_words)})")
    return max(view0 * VIEW_RANGE[0], min(view0 * VIEW_RANGE[1], view))


def _gap(it: Interpretation, scalars: dict[str, float], reasons: list[str]) -> None:
    if "gap" not in scalars:
        return
    words = [t.text for t in it.tokens]
    for i, w in enumerate(words):
        if w in _GAP_NOUNS:
            before = set(words[max(0, i - 3) : i])
            if before & {"wide", "large", "big", "huge", "thick", "broad"}:
                scalars["gap"] *= 1.8
                reasons.append("gap x1.8 (wide gaps)")
                return
            if before & {"thin", "narrow", "fine", "tight", "small"}:
                scalars["gap"] *= 0.5
                reasons.append("gap x0.5 (narrow gaps)")
                return


def choose_micro(recipe: Recipe, it: Interpretation, reasons: list[str]) -> Micro | None:
    """The micro-texture for recipes that take one: the first specific material word ("knit",
    "vinyl", "marble"), else the first generic one ("fabric", "cotton"), else the default."""
    if recipe.micro is None:
        return None
    words = [t for t in it.tokens if t.text in MICRO_WORDS and t.index not in it.negated]
    specific = [t for t in words if t.text not in GENERIC_MICRO_WORDS]
    for t in specific or words:
        name = MICRO_WORDS[t.text]
        reasons.append(f"micro-texture {name} (word '{t.text}')")
        return MICROS[name]
    reasons.append(f"micro-texture {recipe.micro} (recipe default)")
    return MICROS[recipe.micro]


def fill(recipe: Recipe, it: Interpretation) -> Filled:
    """Resolve colours, scalars, View and micro-texture for ``recipe``."""
    reasons: list[str] = []
    preset_colours, preset_scalars = _presets(recipe, it, reasons)
    scalars = {**recipe.slots, **preset_scalars}
    _finish(recipe, it, scalars, reasons)
    _gap(it, scalars, reasons)
    absorbed: list[str] = []
    for cond in it.conditions:
        if cond.kind not in recipe.absorbs:
            continue
        absorbed.append(cond.kind)
        if "wear" in scalars:
            scalars["wear"] = max(float(scalars["wear"]), cond.amount)
            reasons.append(f"wear = {scalars['wear']:.2f} ('{cond.word}' handled by the recipe)")
        else:
            reasons.append(f"'{cond.word}' is part of the recipe itself")
    if it.percents and "cover" in scalars:
        scalars["cover"] = max(0.05, min(0.95, it.percents[0]))
        reasons.append(f"cover = {scalars['cover']:.2f} (stated percentage)")
    view = _view(recipe, it, reasons)
    colours = assign_colours(recipe, it, preset_colours, reasons)
    micro = choose_micro(recipe, it, reasons)
    return Filled(colours, scalars, view, micro, reasons, absorbed)
