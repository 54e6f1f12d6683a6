"""The colour rule: "blue glaze", "darker grout", "make the blue darker", "grey stones".

* A **named colour** (the library's colour table, a word or a phrase, with an absolute tone
  such as "dark green") is set on the colour parameters the request's nouns name, or on the main
  colour when it names none. When the nouns name several colour parameters (``stone`` and
  ``stone_warm``), all of them take the colour, each keeping its lightness offset from the first.
* A **comparative** ("darker", "lighter", "paler", "warmer" ...) moves the current colour in
  CIELAB by the ``[comparative]`` steps of ``words.toml`` (times the step strength), never less
  than ``colour_min_de`` (a change too small to see is pushed further); a hue comparative
  ("greener", "bluer") moves it a share of the way to that colour (``[towards]``).
* A named colour with a comparative whose target is already that colour ("lighter grey" on a
  grey, "make the blue darker" on a delft tile's cobalt) **selects** the parameter: the
  comparative then applies to its current colour instead of repainting it.
"""

from __future__ import annotations

import re
from collections.abc import Sequence
from dataclasses import replace

from matloom.author.edit.families import (
    by_colour,
    colour_value,
    explicit_colours,
    hue_family,
    the_colour,
)
from matloom.author.edit.lab import Lab, delta_e, from_lab, mix, tinted, to_lab
from matloom.author.edit.lexicon import flipped, split_words
from matloom.author.edit.plan import Context, Plan, Value, assign
from matloom.author.edit.targets import (
    layer_colours,
    main_colour,
    matching,
    material_noun,
    named_in_program,
    overlaps,
    param_layers,
    param_words,
    wanted,
)
from matloom.author.edit.wetness import SOAKED, porosity
from matloom.lang import ast as A
from matloom.lang.constants import constant_defines
from matloom.lang.params import Param
from matloom.lang.static import static_number
from matloom.library.colour import RGB, apply_tone, clamp_rgb


def comparative(rgb: Sequence[float], step: tuple[float, float, float], k: float) -> Lab:
    """``rgb`` moved by a comparative step (delta L*, chroma factor, delta b*) times ``k``."""
    L, a, b = to_lab(rgb)
    dl, chroma, db = step
    if dl > 0:  # lighter: at least the step, and a share of the way to white
        L = L + max(dl, 0.3 * (100 - L)) * k
    elif dl < 0:
        L = L + min(dl, -0.3 * L) * k
    f = chroma**k
    return (min(98.0, max(2.0, L)), a * f, b * f + db * k)


def _with_offset(named: Lab, current: Lab, primary: Lab) -> Lab:
    """``named``'s hue and chroma at ``current``'s lightness offset from ``primary``."""
    return (min(98.0, max(2.0, named[0] + current[0] - primary[0])), named[1], named[2])


#: An absolute tone after "less", "not" ... reads as the opposite comparative.
_OPPOSITE = {"dark": "lighter", "light": "darker", "pale": "richer", "bright": "duller"}


# ---- reading the request ---------------------------------------------------------------------
def _tables(c: Context) -> tuple[dict[str, RGB], dict[str, RGB]]:
    """The named colours (single words, phrases): the library's, with ``[colours]`` of
    ``words.toml`` over them."""
    named, phrases = dict(c.vocabulary.named), dict(c.vocabulary.phrases)
    for k, v in c.ew.colours.items():
        rgb: RGB = tuple(int(round(x)) for x in v)  # type: ignore[assignment]
        (phrases if " " in k else named)[k] = rgb
    return named, phrases


def _named_at(c: Context) -> list[tuple[int, int, RGB, bool]]:
    """The named colours of the request: (index, word count, colour, an ``-ish`` form)."""
    w = c.vocabulary
    named, phrases = _tables(c)
    ws = c.words
    exact = explicit_colours(c)
    if exact:  # "around RGB 150, 60, 40", "#D8E0CF": the value given, not the words near it
        return exact
    out: list[tuple[int, int, RGB, bool]] = []
    taken: set[int] = set()
    for n in (3, 2):
        for i in range(len(ws) - n + 1):
            span = set(range(i, i + n))
            if not span & taken and " ".join(ws[i : i + n]) in phrases:
                out.append((i, n, phrases[" ".join(ws[i : i + n])], False))
                taken |= span
    for i, t in enumerate(ws):
        if i in taken:
            continue
        word = w.ish_base(t)
        if word not in named and t[:-1] in c.ew["families"]:  # "swap the blues for amber"
            word = t[:-1]
        if word in w.materialish and ws[i + 1 : i + 2] == ["finish"]:
            continue  # "a satin oil finish": the kind of finish, not a colour
        if word == "powder" and ws[i + 1 : i + 2] and ws[i + 1].startswith("coat"):
            continue  # "powder coat it black": a kind of paint, not powder blue
        if word in named and word not in c.ew.conditions and word not in _NOT_COLOURS:
            out.append((i, 1, named[word], word != t))
    return sorted(out)


#: Words that apply a tone comparative to every colour of the material.
_OVERALL = frozenset({"overall", "everything", "entire", "whole", "all", "colours", "colors"})

#: Words that make a named colour a direction, not a value, beside a comparative ("warmer,
#: more like honey"), and the share of the way the colour moves then.
_LIKE = frozenset({"like", "towards", "toward"})
_LIKE_SHARE = 0.6
#: The share of the way a tint ("a slight blue tint", ``tint`` words of ``words.toml``) moves
#: (times the intensity words: "slight" halves it) and the most it moves.
_TINT_SHARE = 0.6
_TINT_MAX = 0.85
_TINT_STRONGER = 1.4


def _more_before(c: Context) -> bool:
    """Whether "more" stands right before the named colour ("lighter, more honey-yellow")."""
    found = _named_at(c)
    return bool(found) and found[0][0] > 0 and c.words[found[0][0] - 1] == "more"


#: Material words that are also colour names: a noun before a colour, not the colour.
_NOT_COLOURS = frozenset({"sand", "stone", "slate", "metal"})
#: Words after which a colour is the new one ("swap the emerald glaze for cobalt"), and before
#: which it is the old one ("instead of charcoal").
_TO_WORDS = frozenset({"for", "with", "to", "into"})


def describes_part(c: Context, i: int, n: int = 1) -> bool:
    """Whether the colour or tone words ``i .. i+n`` name a part by its look, as an adjective
    after an article ("more of the dark flecks", "the gold pads bigger", "the fresh tan
    needles"): followed by a noun, not by another colour, tone, comparative or a word that
    makes the colour the new one ("the red to blue"); a compound colour before a part's name
    ("the blue-grey background") describes it too."""
    ws = c.words
    before = ws[max(0, i - 2) : i]
    if not before:
        return False
    # "the dark flecks", or "the fresh tan needles" (an adjective between; "the board green"
    # has a part's name there, which the colour is said of)
    adjective = (
        len(before) == 2
        and before[0] in c.ew["articles"]
        and not named_in_program(c.program, [before[1]], c.ew)
    )
    if before[-1] not in c.ew["articles"] and not adjective:
        return False
    v = c.vocabulary
    # "the blue-grey background": a compound colour's first word describes the part too (not
    # "the red blue", a colour run before no part)
    j = i + n + next((k for k in (2, 1) if _colour_run(c, i + n, k)), 0)
    after = ws[j] if j < len(ws) else None
    if after is None or not after.isalpha():
        return False
    return not (
        after in v.named
        or after in v.tones
        or after in c.ew.comparative
        or after in c.ew.towards
        or after in c.ew.finish
        or after in c.ew["filler"]
        or after in _TO_WORDS
        or after in ("instead", "rather", "and", "or", "but", "than", "please", "like", "as")
        or v.ish_base(after) in v.named
    )


def _colour_run(c: Context, j: int, k: int) -> bool:
    """Whether words ``j .. j+k-1`` are colours followed by a part's name."""
    v, ws = c.vocabulary, c.words[j : j + k]
    named = len(ws) == k and all(w in v.named or v.ish_base(w) in v.named for w in ws)
    return named and _names_part(c, j + k)


def _as_verb(c: Context, word: str) -> bool:
    """Whether the colour ``word`` is a verb in the request ("yellow the cream ground", "age
    it: yellow the paper"): first in its clause, before an article."""
    pattern = rf"(?:^|[,:;.!]|\band|\bthen)\s*{re.escape(word)}\s+(?:the|its|their|this)\b"
    return re.search(pattern, c.request.lower()) is not None


def _after_instead_of(c: Context, k: int) -> bool:
    """Whether the word at ``k`` follows "instead of" or "rather than" (with only filler and
    tones between: "instead of the pale blue")."""
    ws = c.words
    for j in range(k, max(0, k - 4), -1):
        if j >= 2 and ws[j - 2 : j] in (["instead", "of"], ["rather", "than"]):
            return True
        if not (ws[j - 1] in c.ew["filler"] or ws[j - 1] in c.vocabulary.tones):
            return False
    return False


def _names_part(c: Context, k: int) -> bool:
    """Whether the word at ``k`` is a noun naming a part of the program (a Define, a layer or
    a parameter): a colour before it says which part ("the red panes")."""
    if k >= len(c.words):
        return False
    word = c.words[k]
    if word in c.ew["filler"] or word in c.vocabulary.tones or word in c.vocabulary.named:
        return False
    return named_in_program(c.program, [word], c.ew) or bool(
        matching(c.params, [word], c.program, c.ew)
    )


def _colour_in(
    c: Context,
) -> tuple[RGB | None, str | None, str | None, set[int], tuple[RGB, ...], bool]:
    """The named colour, the tone word (``tone`` an absolute tone of the library, a comparative
    of ``words.toml``), the word indices used, and the old colours a swap names ("swap the
    yellow for orange", "navy instead of charcoal", "the blues and greens for amber": they
    select the parts to recolour)."""
    w = c.vocabulary
    ws = c.words
    used: set[int] = set()
    rgb: RGB | None = None
    source: RGB | None = None
    sources: tuple[RGB, ...] = ()
    partial = False
    found = []
    for i, n, value, ish in _named_at(c):
        if flipped(ws, i, c.ew["flip"]):  # "less beige": not a colour to paint
            used.add(i)
            continue
        found.append((i, n, value, ish))
    # "give the ice a slight blue tint", "make the brass strips gold": a material word after an
    # article names the part beside another colour, it is not the colour
    nouns = [f for f in found if f[1] == 1 and f[0] and ws[f[0] - 1] in c.ew["articles"]]
    nouns = [f for f in nouns if ws[f[0]] in w.materialish]
    # ... and always when the program has a part of that name ("the brick ... darker")
    named = [f for f in nouns if named_in_program(c.program, [ws[f[0]]], c.ew)]
    if named or (nouns and len(nouns) < len(found)):
        found = [f for f in found if f not in (named or nouns)]
    if found:
        # a colour before "for/with/to/into" or after "instead of" is the one to replace
        old = [
            f
            for f in found
            if _after_instead_of(c, f[0])
            or any(t in _TO_WORDS for t in ws[f[0] + f[1] :])
            and any(g[0] > f[0] and set(ws[f[0] + f[1] : g[0]]) & _TO_WORDS for g in found)
        ]
        # a colour naming a part ("the red panes ... purple"): the part to recolour
        old += [
            f
            for f in found
            if f not in old
            and not f[3]
            and _names_part(c, f[0] + f[1])
            and any(g[0] > f[0] and g not in old for g in found)
        ]
        # a colour naming a part by its look ("more of the dark flecks", "the gold pads
        # bigger"): the part, never the colour to paint
        said = [f for f in found if f not in old and describes_part(c, f[0], f[1])]
        old += said
        new = [f for f in found if f not in old]
        if not new and any(_after_instead_of(c, f[0]) for f in old):
            # "clear tape instead of brown": the colour named is the one to replace, and
            # the new one is no colour the rules know
            return None, None, None, used | {f[0] for f in old}, (), False
        if not new and said:  # no colour to paint: the part it names, for a comparative
            used |= {k for f in said for k in range(f[0], f[0] + f[1])}
            found, source, sources = [], said[0][2], (said[0][2],)
        new = new or found
        if old and new and new is not found:
            source = old[0][2]
            sources = tuple(f[2] for f in old)
            for f in old:
                used |= set(range(f[0], f[0] + f[1]))
            j = old[0][0] - 1  # "the pale blue": the old colour's tone is the old colour's
            if j >= 0 and ws[j] in w.tones and j not in used:
                source = apply_tone(source, ws[j], w.tones[ws[j]])
                sources = (source, *sources[1:])
                used.add(j)
        if new:
            i, n, rgb, ish = new[0]
            used |= set(range(i, i + n))
            rest = [f for f in new[1:] if f[0] <= i + n + 2]
            if rest and rest[0][0] == i + n or (ish and rest):  # "purple brown", "reddish clay
                j, m, other, _ = rest[0]  # brown": the mix (an -ish colour a third of it)
                rgb = mix(rgb, other, 0.67 if ish else 0.5)
                used |= set(range(j, j + m))
            else:
                # "a reddish sandstone" (an -ish colour alone), "yellow the cream ground" (a colour
                # as a verb): part of the way there, not the colour name's pure value
                partial = ish or _as_verb(c, ws[i])
    tone: str | None = None
    comparative_word: str | None = None
    exact = bool(
        explicit_colours(c)
    )  # "a pale sage green, #D8E0CF": the value, not its words' tone
    for i, t in enumerate(ws):
        if i in used or exact:
            continue
        if t in c.ew.towards or t in c.ew.comparative:
            comparative_word = t
            used.add(i)
            break
        if t in _OPPOSITE and flipped(ws, i, c.ew["flip"]):  # "less dark" is lighter
            comparative_word = _OPPOSITE[t]
            used.add(i)
            break
        if (
            t in w.tones
            and t not in ("medium",)
            and (rgb is not None or t in ("dark", "light", "pale", "bright"))
            and not describes_part(c, i, 1)  # "more of the dark soil": a part, not a tone
        ):
            tone = t
            used.add(i)
            break
    return rgb, tone, comparative_word, used, sources, partial


#: Address prefix of a derived colour slot (:func:`_derived`): set by rewriting its lines.
DERIVED = "derived:"


def _derived(c: Context, nouns: list[str]) -> list[Param]:
    """Colour slots the nouns name whose components are constant expressions of other Defines
    (``Define(knot_r, (wood_r * 0.42))``): their current colour, as parameters that the rule
    sets by replacing the three Define lines with the new components."""
    if not nouns:
        return []
    consts = constant_defines(c.program)
    want = wanted(nouns, c.ew)
    out: list[Param] = []
    for d in c.program.defines:
        if not d.name.endswith("_r") or isinstance(d.expr, A.Num):
            continue
        base = d.name[:-2]
        names = [f"{base}_{k}" for k in "rgb"]
        if not all(n in consts for n in names) or not overlaps(split_words(base), want):
            continue
        try:
            value = tuple(float(static_number(consts[n])) for n in names)
        except (TypeError, ValueError):
            continue
        rgb = tuple(min(255.0, max(0.0, v)) for v in value)
        out.append(
            Param(
                f"{DERIVED}{base}",
                rgb,
                "colour",
                0.0,
                255.0,
                "sRGB 0-255",  # type: ignore[arg-type]
                f"{base} colour (derived)",
                ("basecolor",),
                d.span.line,
                d.span.col,
            )  # fmt: skip
        )
    return out


def _targets(
    c: Context, colours: list[Param], nouns: list[str], comparative_all: bool = False
) -> list[Param]:
    targets = matching(colours, nouns, c.program, c.ew)
    if targets:
        return targets
    if comparative_all and _OVERALL & set(c.words):  # "slightly darker overall": every colour
        return list(colours)
    derived = _derived(c, nouns)
    if derived:
        return derived
    if nouns and comparative_all and material_noun(c, nouns):  # "greyer gravel": the material
        joint = c.ew.nouns["joint"]  # itself, every colour but the joints'
        return [p for p in colours if not overlaps(param_words(p, c.program, c.ew), joint)]
    layered = layer_colours(c, colours, nouns)
    if layered:  # "the slabs": the colours of the layer the slab mask draws
        return layered
    if material_noun(c, nouns):  # "dye the leather", "the baseplate": the material itself
        return [main_colour(colours, c.program, c.ew)]
    named_elsewhere = matching(c.params, nouns, c.program, c.ew) if nouns else []
    if named_elsewhere or any(n in c.vocabulary.roles for n in nouns):
        raise c.refuse(f"no colour parameter named like {' '.join(nouns)!r}", colours)
    ws = c.words
    parts = [
        ws[i + 1] for i in range(len(ws) - 1) if ws[i] in ("the", "only") and ws[i + 1] in nouns
    ]
    if parts:  # "make the topstitching white" with no such part: not the whole material
        raise c.refuse(f"no part of the program is named like {' '.join(parts)!r}", colours)
    if nouns and comparative_all:  # "greyer gravel": the material itself, every colour but
        joint = c.ew.nouns["joint"]  # the joints'
        return [p for p in colours if not overlaps(param_words(p, c.program, c.ew), joint)] or [
            main_colour(colours, c.program, c.ew)
        ]
    return [main_colour(colours, c.program, c.ew)]


def _whole_material(c: Context, colours: list[Param], nouns: list[str]) -> list[Param]:
    """ "the whole wall", "all the bricks": every colour of the material but the joints' and
    the conditions' (moss, rust), the main colour first; none when the request does not say
    so."""
    if not ({"whole", "entire", "all", "everything"} & set(c.words)):
        return []
    if nouns and not material_noun(c, nouns):
        return []
    skip = set(c.ew.nouns["joint"]) | {s for v in c.ew.conditions.values() for s in v}
    out = [p for p in colours if not overlaps(param_words(p, c.program, c.ew), skip)]
    if len(out) < 2:
        return []
    main = main_colour(colours, c.program, c.ew)
    return sorted(out, key=lambda p: p is not main)


def _select(c: Context, rgb: RGB, candidates: list[Param]) -> list[Param]:
    """The candidates already close to the named colour (nearest first)."""
    limit = c.ew.f("select_de")
    close = sorted(
        (delta_e(colour_value(p), rgb), i, p)
        for i, p in enumerate(candidates)
        if delta_e(colour_value(p), rgb) < limit
    )
    return [p for _, _, p in close]


def colour_rule(c: Context) -> Plan | None:
    rgb, tone, comp, used, sources, partial = _colour_in(c)
    if rgb is None and tone is None and comp is None:
        return None
    if (
        rgb is not None
        and tone is None
        and comp is None
        and set(c.words) & (c.ew["size"] | c.ew["width"])
        and any(named_in_program(c.program, [c.words[i]], c.ew) for i in used)
    ):
        return None  # "thinner brass strips": the size of the part the colour word names
    if (
        rgb is not None
        and tone is None
        and comp is None
        and set(c.words) & (c.ew["size"] | c.ew["width"] | c.ew["width_up"])
        and any(
            p.kind == "colour"
            and isinstance(p.value, tuple)
            and delta_e(colour_value(p), rgb) < c.ew.f("select_de")
            for p in c.params
        )
    ):
        return None  # "thicker gold wires": the wires are gold already, their size changes
    # three numbers each (a lone component named like a colour, ``tile_r`` beside a Define
    # ``tile``, is a number: not recoloured on its own)
    colours = [p for p in c.params if p.kind == "colour" and isinstance(p.value, tuple)]
    if not colours:
        raise c.refuse("no colour parameter")
    nouns = [t for i, t in enumerate(c.words) if i not in used and t not in c.ew["filler"]]
    if comp is not None and comp in c.ew.towards:
        return _towards(c, colours, nouns, comp)
    step = c.ew.comparative.get(comp) if comp is not None else None
    if rgb is not None and step is not None:
        pool = matching(colours, nouns, c.program, c.ew) if nouns else colours
        chosen = _select(c, rgb, pool)
        if not chosen and the_colour(c):  # "make the blue darker": the part of that hue
            chosen = hue_family(c, rgb, pool)
        main = main_colour(colours, c.program, c.ew)
        if not nouns and main in chosen:  # no noun: the main colour first when it is close
            chosen = [main] + [p for p in chosen if p is not main]
        if chosen:  # "make the blue darker": the comparative on the colour that is blue
            rgb = None
            targets = chosen[:1] if not nouns else chosen
        else:
            targets = _targets(c, colours, nouns)
    elif sources:
        # "swap the yellow for orange", "just the red panes": the part that is that colour now
        # ("the blues and greens": the parts of each)
        targets = list(
            dict.fromkeys(p for source in sources for p in by_colour(c, source, colours, nouns))
        )
        targets = targets or _targets(c, colours, nouns)
    else:
        targets = _whole_material(c, colours, nouns) if rgb is not None else []
        targets = targets or _targets(
            c, colours, nouns, comparative_all=rgb is None and step is not None
        )
    primary = targets[0]
    # "warmer, more like honey", "lighter, more honey-yellow": the named colour is a direction
    towards = rgb is not None and step is not None and bool(_LIKE & set(c.words) or _more_before(c))
    towards = towards or (rgb is not None and partial and tone is None)
    # "a slight blue tint": part of the way to the colour, not the colour ("a slight but
    # deeper tint": a stronger part); a tint asked for plainly is the colour ("tint the glass
    # amber", "a dark smoky grey tint")
    tint = rgb is not None and not towards and bool(c.ew["tint"] & set(c.words)) and c.intensity < 1

    stronger = _TINT_STRONGER if tint and step is not None else 1.0
    share = min(_TINT_MAX, _TINT_SHARE * c.intensity * stronger) if tint else _LIKE_SHARE
    base_lab = to_lab(colour_value(primary))
    # "make it wet": as dark as the surface is porous, unless the request says darker too
    wet = 1.0
    if comp == SOAKED and not {"darker", "dark", "darken"} & set(c.said or c.words):
        wet = porosity(c.program)
    new: dict[Param, Value] = {}
    for p in targets:
        current = colour_value(p)
        if rgb is not None:
            named: RGB = apply_tone(rgb, tone, c.vocabulary.tones[tone]) if tone else rgb
            lab = to_lab(named)
            if tint:  # the hue and chroma move, the lightness stays ("clear ice, a blue tint")
                lab = tinted(current, named, share, c.ew.f("tint_min_de"), _TINT_MAX)
            elif towards:
                # "warmer, more like a honey sandstone": most of the way to the named colour
                # from the current one (a name like "honey" is far more saturated than a stone)
                lab = to_lab(mix(current, named, share))
            elif step is not None:  # "darker, purple-brown": the comparative on the named colour
                lab = comparative(named, step, 1.0)
            if p is not primary:
                lab = _with_offset(lab, to_lab(current), base_lab)
        elif step is not None:
            lab = comparative(current, step, c.k * wet)
        else:  # an absolute tone alone ("dark"): the library's tone on the current colour
            lab = to_lab(apply_tone(clamp_rgb(current), tone or "", c.vocabulary.tones[tone or ""]))
        out = from_lab(lab)
        least = c.ew.f("colour_min_de") * min(1.0, c.intensity)  # "slightly": a smaller least
        if delta_e(current, out) < least and step is not None and not tint and comp != SOAKED:
            lab = comparative(current, step, c.k * 2)
            out = from_lab(lab)
        new[p] = tuple(float(x) for x in out)  # type: ignore[assignment]
    what = ", ".join(f"{p.address} -> {tuple(int(x) for x in new[p])}" for p in targets)  # type: ignore[union-attr]
    graded = step is not None and rgb is None
    if any(p.address.startswith(DERIVED) for p in new):
        return _derived_plan(c, what, new, graded)
    plan = assign(c, "colour", what, new, _channels(new), graded=graded, exact=not graded)
    bare = _painted_over(c, targets) if rgb is not None else {}
    if bare:
        plan = replace(
            plan,
            note=f"{plan.note}; painted: metallic 0",
            assignments={**plan.assignments, **{p.address: v for p, v in bare.items()}},
            intended=(*plan.intended, "metallic"),
        )
    return plan


#: Verbs that put a coat of paint on a surface ("paint it safety yellow", "powder-coat it red").
_PAINT_VERBS = frozenset(
    {"paint", "painted", "repaint", "repainted", "powder", "enamel", "enamelled", "enameled",
     "spray", "sprayed", "lacquer", "lacquered"}
)  # fmt: skip


def _painted_over(c: Context, targets: Sequence[Param]) -> dict[Param, Value]:
    """A coat of paint on a metal: the metallic literals of the recoloured layers go to 0 (a
    yellow metal reads as gold, not as paint). Only when the request paints, and only the
    layers whose colour changes."""
    if not _PAINT_VERBS & set(c.words):
        return {}
    layers: set[int] = set()
    for p in targets:
        layers |= param_layers(p, c.program)
    out: dict[Param, Value] = {}
    for p in c.params:
        if p.kind != "scalar" or set(p.affects) != {"metallic"} or float(p.value) <= 0:  # type: ignore[arg-type]
            continue
        if param_layers(p, c.program) & layers:
            out[p] = 0.0
    return out


def _channels(new: dict[Param, Value]) -> tuple[str, ...]:
    """The colour channels the edit changes: the base colour, and the emissive colour where a
    changed colour feeds it too (a stained glass's glow is its glass colour)."""
    glow = any("emissive" in p.affects for p in new)
    return ("basecolor", "emissive") if glow else ("basecolor",)


def _derived_plan(c: Context, what: str, new: dict[Param, Value], graded: bool) -> Plan:
    """The plan that writes derived colour slots as constants (their lines replaced)."""
    lines: dict[str, str] = {}
    for p, v in new.items():
        base = p.address.removeprefix(DERIVED)
        for k, x in zip("rgb", v, strict=True):  # type: ignore[arg-type]
            lines[f"define:{base}_{k}"] = f"Define({base}_{k}, {round(float(x))})"
    return Plan("colour", what, lines=lines, intended=_channels(new), graded=graded)


def _towards(c: Context, colours: list[Param], nouns: list[str], word: str) -> Plan:
    """ "greener", "bluer": each target colour a share of the way to the word's colour."""
    goal = to_lab(c.vocabulary.named[c.ew.towards[word]])
    t = min(1.0, c.ew.f("towards") * c.k)
    new: dict[Param, Value] = {}
    for p in _targets(c, colours, nouns):
        L, a, b = to_lab(colour_value(p))
        lab = (L + (goal[0] - L) * t / 3, a + (goal[1] - a) * t, b + (goal[2] - b) * t)
        new[p] = tuple(float(x) for x in from_lab(lab))  # type: ignore[assignment]
    what = ", ".join(f"{p.address} -> {tuple(int(x) for x in v)}" for p, v in new.items())  # type: ignore[union-attr]
    return assign(c, "colour", f"{word}: {what}", new, _channels(new))
