"""Offline edits: common requests mapped to parameter changes, driven by the parameter list.

A rule reads the request's words, picks parameters by their kind, label, address, the layers
they feed and the channels they affect (:func:`matloom.lang.params.list_params`,
:mod:`matloom.author.edit.targets`), and returns a :class:`Plan`: the assignments, the View
changes, replaced or added lines, and the channels the edit means to change (the locality check
holds the edit to them). Steps are sized to be seen in a lit preview (``words.toml``). The
rules, in the order they are tried:

* **tileable** ("make it tileable", "seamless"): ``View(..., tileable=True)``;
* **physical size** ("1 m wide", "pennies 3 cm across"; :mod:`~matloom.author.edit.physical`):
  the whole material's spans the View; a feature's sets ``unit_m`` from the feature's
  measured size in units;
* **joints** ("wider grout", "narrower mortar joints"): size parameters of mortar, grout, gaps;
* **conditions** ("more rust", "less moss", "add dirt"; :mod:`~matloom.author.edit.conditions`):
  an amount parameter, the measured coverage of the condition's layer, or the library's overlay
  added on top;
* **roughness** ("rougher", "less shiny", "matte"; :mod:`~matloom.author.edit.finish`);
* **single channels** ("less sheen", "more clearcoat", "less metallic");
* **relief** ("deeper", "flatter", "more relief");
* **colour** ("blue glaze", "darker grout", "make the blue darker";
  :mod:`~matloom.author.edit.colours`);
* **scale** ("bigger tiles", "smaller", "denser", "sparser"): size and frequency parameters
  named like the noun, else those that shape the coverage of the noun's layer (all of them when
  no noun); when the noun names a part of the program that has no such parameter (cobbles drawn
  from constants), the View zooms, which scales every feature.

A request no rule maps raises :class:`EditRefused`, listing the parameters that could be
changed: never a silent no-op. So does a rule whose parameters are already at their limit.
"""

from __future__ import annotations

import functools
import math
import re
from collections.abc import Callable, Sequence
from dataclasses import replace

from matloom.author.edit.apply import apply_edit, parse_program, set_view
from matloom.author.edit.clauses import AND_VERB, join_clauses, with_contrast, without_state
from matloom.author.edit.colours import colour_rule
from matloom.author.edit.conditions import amount_rule
from matloom.author.edit.contrast import contrast_rule, feature_rule
from matloom.author.edit.finish import channel_rule, relief_rule, roughness_rule
from matloom.author.edit.lexicon import (
    EditWords,
    edit_words,
    flipped,
    split_words,
    stated_factor,
    tokens,
)
from matloom.author.edit.measured import measured_layer
from matloom.author.edit.physical import SIZE_RE as _SIZE_RE
from matloom.author.edit.physical import physical_rule, tiles, window, zoomed
from matloom.author.edit.plan import (
    Context,
    EditRefused,
    Plan,
    Value,
    affects,
    assign,
    clamp,
    scaled,
)
from matloom.author.edit.reread import reread
from matloom.author.edit.targets import (
    coverage_params,
    material_noun,
    named_in_program,
    overlaps,
    own_words,
    stroke_widths,
    wanted,
)
from matloom.author.edit.targets import param_words as _param_words
from matloom.lang import ast as A
from matloom.lang.params import Param
from matloom.lang.tileable import tileable_warnings
from matloom.library.data import words

__all__ = ["RULES", "Context", "EditRefused", "Plan", "param_words", "plan_edit", "tokens"]


def param_words(p: Param, program: A.Program | None = None) -> set[str]:
    """The words a parameter answers to (:func:`matloom.author.edit.targets.param_words`)."""
    return _param_words(p, program, edit_words())


# ---- View ------------------------------------------------------------------------------------
def _tileable(c: Context) -> Plan | None:
    if not ({"tileable", "seamless", "seamlessly", "tiling", "repeatable"} & set(c.words)):
        return None
    if c.program.view is not None and c.program.view.tileable:
        raise c.refuse("the program is tileable already")
    seams = tileable_warnings(set_view(c.program, {"tileable": True}))
    if seams:  # the flag alone would leave a visible edge: say so, do not pretend
        raise c.refuse(
            f"tileable=True alone would leave a seam ({seams[0].message.removeprefix('tileable: ')}"
            f"{f' and {len(seams) - 1} more' if len(seams) > 1 else ''}); the program's "
            "patterns must repeat with the View (use --model to rewrite them)"
        )
    return Plan(
        "tileable", "View(..., tileable=True)", view={"tileable": True}, intended=("alpha",)
    )


# ---- joints ----------------------------------------------------------------------------------
#: Words that ask for a width whatever colour the joint is ("widen the black seams").
_WIDTH_VERBS = frozenset(
    {"widen", "wider", "broaden", "broader", "thicken", "thicker", "narrow", "narrower", "thin",
     "thinner", "tighten", "tighter"}
)  # fmt: skip


def _joint_params(c: Context) -> list[Param]:
    found = [
        p
        for p in c.params
        if p.kind == "size" and any(k in p.address.lower() for k in c.ew.joint_params)
    ]
    found += [
        p
        for p in c.params
        if p.kind == "size"
        and p not in found
        and ({"grout", "mortar", "joint"} & set(p.label.lower().split()))
    ]
    # a named constant for the joint that shapes a coverage (``Define(gap, 0.06)`` used in
    # ``Threshold(((edge - gap) * 40), ...)``), not a colour component
    found += [
        p
        for p in c.params
        if p.kind == "scalar"
        and p not in found
        and re.fullmatch(r"define:\w+", p.address)
        and split_words(p.address[7:]) & c.ew["joint"]
        and "alpha" in p.affects
    ]
    return found


def _joints(c: Context) -> Plan | None:
    ws = set(c.words)
    size = _SIZE_RE.search(c.request.lower())
    if not (c.ew["joint"] & ws) or not ((c.ew["wider"] | c.ew["narrower"]) & ws or size):
        return None
    tones = ws & set(c.ew.comparative)
    if tones and not ws & _WIDTH_VERBS:
        return None  # "darker grout": a colour
    plan = _joint_width(c, ws, size)
    if plan is None or not tones:
        return plan
    # "wider, darker gaps": the width, and the tone on the joints' own colour (not the tiles')
    joint_words = [t for t in c.words if t in tones or t in c.ew["joint"]]
    try:
        colour = colour_rule(replace(c, words=joint_words))
    except EditRefused:
        return plan
    if colour is None or not all(
        any(k in a.lower() for k in c.ew.joint_params) for a in colour.assignments
    ):
        return plan  # no colour of the joints' own: the width alone
    return Plan(
        "joints+colour",
        f"{plan.note}; {colour.note}",
        assignments={**plan.assignments, **colour.assignments},
        intended=tuple(dict.fromkeys(plan.intended + colour.intended)),
        lines=plan.lines,
        graded=plan.graded,
    )


def _joint_width(c: Context, ws: set[str], size: re.Match[str] | None) -> Plan | None:
    if any(t in c.vocabulary.named for t in ws) and not ws & _WIDTH_VERBS:
        return None  # "white mortar" is a colour; "widen the black seams" a width
    if ws & ((set(c.ew.relief_nouns) - c.ew["joint"]) | set(c.ew.relief)):
        return None  # "stones further out from the mortar, more relief": the relief
    found = _joint_params(c)
    if not found:
        wider = bool(c.ew["wider"] & ws)
        plan = measured_layer(c, [t for t in c.words if t in c.ew["joint"]], wider, joint=True)
        if plan is not None:  # lead came drawn by a distance threshold: its coverage
            return plan
        raise c.refuse("no joint (mortar, grout, gap) width parameter")
    unit_m = c.program.unit_m
    if size is not None and unit_m:  # "5 mm grout": the width itself, in the View's units
        metres = float(size.group(1)) * c.vocabulary.units[size.group(2)]
        width = metres / unit_m
        new: dict[Param, Value] = {p: clamp(p, width) for p in found}
        note = f"joints {metres * 1000:g} mm wide ({width:.4g} units)"
        return assign(c, "joints", note, new, affects(found), graded=False, exact=True)
    wider = _joint_wider(c)
    factor = c.ew.f("joint") ** (c.k if wider else -c.k)
    new = {p: scaled(p, factor) for p in found}
    if wider:  # at least a few preview pixels wide, or a thin joint still reads as a line
        x1, _, x2, _ = window(c.program)
        least = c.ew.f("joint_px") * c.k * abs(x2 - x1) / c.ew.f("preview_px")
        new = {p: clamp(p, max(float(v), least)) if p.kind == "size" else v for p, v in new.items()}
    word = "wider" if wider else "narrower"
    return assign(c, "joints", f"joints {word} (x{factor:.3g})", new, affects(found))


def _joint_wider(c: Context) -> bool:
    """Whether the joints are to be wider: the width word nearest a joint noun ("bigger tiles
    with thinner joints": thinner), else any wider word."""
    widths = [(i, t in c.ew["wider"]) for i, t in enumerate(c.words)]
    widths = [(i, w) for i, w in widths if w or c.words[i] in c.ew["narrower"]]
    joints = [i for i, t in enumerate(c.words) if t in c.ew["joint"]]
    if widths and joints:
        return min(widths, key=lambda iw: min(abs(iw[0] - j) for j in joints))[1]
    return bool(c.ew["wider"] & set(c.words))


# ---- scale -----------------------------------------------------------------------------------
def _zoom(
    c: Context,
    bigger: bool,
    step: float | None = None,
    why: str = "no parameter draws a named feature",
) -> Plan:
    """Every feature bigger or smaller: the View's window shrinks or grows by ``step`` (the
    words' step when None; x2 when the program tiles, so the repeat stays whole)."""
    f = (step or c.ew.f("size")) if not c.program.tileable else 2.0
    ratio = 1 / f if bigger else f
    win = zoomed(c, ratio)
    if not tiles(c, win):
        raise c.refuse("no size parameter of it, and zooming the View would break the tiling")
    word = "bigger" if bigger else "smaller"
    return Plan(
        "scale",
        f"every feature {word}: the View's window x{ratio:.3g} ({why})",
        view={"window": win},
        intended=("alpha",),
    )


def _scale(c: Context) -> Plan | None:
    ws = set(c.words)
    ew = c.ew
    if ws & ew["bigger"] or ws & ew["sparser"] or ws & ew["width_up"]:
        bigger = True
    elif ws & ew["smaller"] or ws & ew["denser"] or ws & ew["width"]:
        bigger = False
    else:
        return None
    # "double their size", "twice as wide", "half the width": x2 (else the words' step)
    # "scale it up about 2x", "three times as big": that factor, not escalated
    stated = stated_factor(c.words, ew)
    step = stated or (2.0 if ws & {"double", "twice", "half", "halve", "doubled"} else ew.f("size"))
    size_f = step ** ((1 if stated else c.k) * (1 if bigger else -1))
    joint = ("mortar", "grout", "gap", "joint", "feather", "seam", "gutter")
    scalable = [
        p
        for p in c.params
        if p.kind in ("size", "frequency") and not any(k in p.address.lower() for k in joint)
    ]
    skip = ew["bigger"] | ew["smaller"] | ew["denser"] | ew["sparser"] | ew["width"]
    skip |= {"feature", "features", "pattern", "scale", "size"} | ew["not_parts"]
    nouns = [t for t in _unlike(c.nouns) if t not in skip]
    # "thinner rune strokes", "thicker scratched lines": the widths of the drawn lines
    strokes = stroke_widths(scalable, nouns, ew) if ws & ew["width"] else []
    if strokes:
        new_widths: dict[Param, Value] = {p: scaled(p, size_f) for p in strokes}
        return assign(c, "scale", f"line widths x{size_f:.3g}", new_widths, affects(strokes))
    # the noun's own parameters (its words, not its family: "tiles" is no glaze noise), else
    # those that shape its layer's coverage
    targets = [p for p in scalable if overlaps(own_words(p), wanted(nouns, ew, families=False))]
    if not targets and nouns:
        targets = coverage_params(scalable, nouns, c.program, ew)
    if ws & (ew["scale_all"] | ew["repeat"]):
        # "scale the whole texture up", "so it repeats more often": every feature
        return _zoom(c, bigger, step, "the whole design scales")
    sized = bool(ws & ((ew["bigger"] | ew["smaller"]) - ew["denser"] - ew["sparser"]))
    if not targets and nouns and ws & (ew["denser"] | ew["sparser"]) and not sized:
        # "fewer veins": a count, which zooming would turn into a size (thicker veins)
        raise c.refuse(
            f"no parameter draws the {' '.join(nouns)} (their number cannot change without "
            "changing their size)"
        )
    if not targets and nouns and not _drawn(c, nouns) and not _known(c, nouns):
        raise c.refuse(f"nothing in the program is named like {' '.join(nouns)!r}")
    if not targets:
        # no parameter draws the named feature (hexagons drawn from constants), or no noun:
        # the View zooms, which scales every feature in step (scaling some noises and not
        # the constants that share their pattern turns a weave into a plaid)
        return _zoom(c, bigger, step)
    targets = _with_copies(targets, scalable)
    new = _tiling_sizes(c, targets, size_f)
    # not graded: a feature x1.5 shows wherever the preview resolves it, and a finer one
    # (a velvet's pile) would not show at any step
    return assign(c, "scale", f"features x{size_f:.3g}", new, affects(targets), graded=False)


def _unlike(words: Sequence[str]) -> list[str]:
    """The words before a simile ("... so it looks like we are seeing it from higher up")."""
    for i, t in enumerate(words):
        if t == "like" or (t == "as" and words[i + 1 : i + 2] in (["if"], ["though"])):
            return list(words[:i])
    return list(words)


def _drawn(c: Context, nouns: Sequence[str]) -> bool:
    """Whether a noun names a Define or layer of the program, or a pattern it calls ("weave"
    for a ``Weave``, "bricks" for ``Bricks``)."""
    if named_in_program(c.program, nouns, c.ew):
        return True
    called = {n.func for d in c.program.defines for n in A.walk(d.expr) if isinstance(n, A.Call)}
    return any(overlaps(split_words(f), wanted(nouns, c.ew)) for f in called)


def _known(c: Context, nouns: Sequence[str]) -> bool:
    """Whether a noun names the material or a feature of a pattern (a material word, a noun
    family, a part role such as "stripes"): with no parameter for it, the View zooms."""
    return material_noun(c, nouns) or any(n in c.vocabulary.roles for n in nouns)


def _with_copies(targets: list[Param], scalable: Sequence[Param]) -> list[Param]:
    """The targets and their copies: the same parameter of the same function at the same value
    in another Define (``board`` and ``boardval`` both ``Bricks(brick_width=2)``; a Tile
    repeated for each part of a knot), so every copy of a pattern scales in step."""

    def key(p: Param) -> tuple[str, object] | None:
        parts = p.address.split(".", 1)
        return (parts[1], p.value) if p.address.startswith("define:") and len(parts) == 2 else None

    keys = {key(p) for p in targets} - {None}
    return targets + [p for p in scalable if p not in targets and key(p) in keys]


def _tiling_sizes(c: Context, targets: list[Param], size_f: float) -> dict[Param, Value]:
    """The targets scaled by ``size_f`` (frequencies by its inverse); for a program that tiles,
    by the nearest factor that keeps it tiling (whole bricks and cells across the View)."""

    def at(f: float) -> dict[Param, Value]:
        return {p: scaled(p, f if p.kind == "size" else 1 / f) for p in targets}

    if not c.program.tileable:
        return at(size_f)
    warned = len(tileable_warnings(c.program))
    options = sorted(
        {size_f, 1.25, 4 / 3, 1.5, 5 / 3, 2.0, 0.8, 0.75, 2 / 3, 0.6, 0.5},
        key=lambda f: abs(math.log(f / size_f)),
    )
    for f in options:
        if (f > 1) != (size_f > 1):
            continue
        new = at(f)
        try:
            text, _ = apply_edit(c.program, {p.address: v for p, v in new.items()})
        except ValueError:
            continue
        if len(tileable_warnings(parse_program(text))) <= warned:
            return new
    return at(size_f)


#: A clause naming what an edit must leave alone ("but keep the tiles white", "don't touch
#: the glaze", "except the joints").
_KEEP_RE = re.compile(
    r"[,;:]?\s*\b(?:but|while|and)?\s*(?:keep|keeping|leave|leaving|don'?t\s+touch|"
    r"do\s+not\s+touch|without\s+touching|not\s+touching|except)\b.*$",
    re.IGNORECASE,
)

#: Phrasal verbs read as the rules' words: "pull the verdigris back" is less verdigris, "scale
#: the tiles up" bigger tiles.
_DOWN_VERBS = r"(?:knock|tone|turn|bring|dial|take)"
_GLOSS_WORDS = r"gloss|shine|shininess|glossiness|reflections?|sheen"
_PHRASES: tuple[tuple[re.Pattern[str], str | Callable[[re.Match[str]], str]], ...] = (
    # "red centres -> mustard yellow": an arrow is "to"
    (re.compile(r"\s*(?:->|=>|\u2192)\s*"), " to "),
    (re.compile(r"\b(?:pull|cut|dial|roll|hold|push)\s+((?:the\s+)?\w+)\s+back\b"), r"less \1"),
    (re.compile(r"\bscale\s+((?:the\s+)?(?:\w+\s+){0,2})up\b"), r"bigger \1"),
    (re.compile(r"\bscale\s+((?:the\s+)?(?:\w+\s+){0,2})down\b"), r"smaller \1"),
    (re.compile(r"\bscale\s+up\b"), "bigger"),
    (re.compile(r"\bscale\s+down\b"), "smaller"),
    # "knock the gloss down", "tone down the shine": less of it
    (re.compile(rf"\b{_DOWN_VERBS}\s+(?:the\s+)?({_GLOSS_WORDS})\s+down\b"), r"less \1"),
    (re.compile(rf"\b{_DOWN_VERBS}\s+down\s+(?:the\s+)?({_GLOSS_WORDS})\b"), r"less \1"),
    # "oil stains", "grease spots": the oily overlay (not a stain coloured like oil)
    (
        re.compile(
            r"\b(?:engine\s+|motor\s+)?(?:oil|grease)\s+(?:stains?|spots?|patches|marks|spills?|drips?)\b"
        ),
        "oily",
    ),
    # "salt stains", "a white salty bloom": efflorescence
    (
        re.compile(r"\b(?:white\s+)?(?:salt|salty)\s+(?:stains?|bloom|deposits?|marks)\b"),
        "efflorescence",
    ),
    # "dark water spots", "rain spots": wet marks (darker and glossier where they are)
    (re.compile(r"\b(?:water|rain|raindrop)\s+(spots?|marks?|splashes)\b"), r"wet \1"),
    # "a layer of grey volcanic ash", "a crust of ash": grey dust (not the colour ash)
    (re.compile(r"\bvolcanic\s+ash\b"), "ash"),
    (
        re.compile(
            r"\b(layer|crust|film|dusting|coat|coating|covering)\s+of\s+"
            r"((?:fine|light|thin|thick|grey|gray|white|black|dark|pale)\s+)?ash\b"
            r"(?!\s+(?:grey|gray|blond|blonde|wood|veneer|paint|colou?r|tone|white|brown))"
        ),
        lambda m: f"{m.group(1)} of {m.group(2) or 'grey '}dust",
    ),
    # "a thin crust of frost", "a light frost", "a light layer of dust": a little of it
    (
        re.compile(
            r"\b(?:a\s+)?(?:light|thin|fine)\s+(layer|coat|film|crust|covering|skin)\s+of\b"
        ),
        r"a little \1 of",
    ),
    (
        re.compile(
            r"\b(?:a\s+)?(?:light|thin)\s+(frost|snow|dust|rust|moss|dirt|grime|mould|mold|algae|soot"
            r"|lichen|patina)\b"
        ),
        r"a little \1",
    ),
    # "a coffee ring", "mug rings": ring stains (not the colour coffee)
    (re.compile(r"\b(coffee|tea|mug|cup|glass|wine|water)\s+(rings?)\b"), r"\1 \2 stains"),
    # "sun-bleached", "sun faded": bleached (the sun is no part of the material)
    (re.compile(r"\bsun[\s-]+(bleached|faded)\b"), r"\1"),
    # "spaced further apart", "space them out": sparser
    (
        re.compile(r"\b(?:spaced?|spread)\s+(?:\w+\s+)?(?:further|farther|more)\s+apart\b"),
        "sparser",
    ),
    (re.compile(r"\bfurther\s+apart\b"), "sparser"),
    # "half the size", "double their size": the direction as well as the factor
    (
        re.compile(
            r"\b(half|halve)\s+(?:the|their|its)\s+(?:\w+\s+)?(?:size|width|diameter|length)\b"
        ),
        r"smaller \1",
    ),
    (
        re.compile(
            r"\b(double|twice)\s+(?:the|their|its)\s+(?:\w+\s+)?(?:size|width|diameter|length)\b"
        ),
        r"bigger \1",
    ),
)


#: A clause that says a part stays as it is ("chips unchanged", "the rest as it is").
_AS_IS_RE = re.compile(
    r"[,;]\s*[^,;]*\b(?:unchanged|untouched|as\s+(?:is|it\s+is|they\s+are))\b[^,;]*",
    re.IGNORECASE,
)


#: A clause saying why, naming what the edit should go with, not what to change ("so it sits
#: better with the red", "to match the grout").
_PURPOSE_RE = re.compile(
    r"\s*,?\s*\b(?:so\s+(?:that\s+)?(?:it|they)\s+(?:sits?|goes?|works?|blends?|pairs?|matches"
    r"|match|fits?|suits?)|to\s+(?:match|go\s+with|suit|complement))\b"
    r"(?:(?![,.;]|\band\b|\bbut\b).)*",
    re.IGNORECASE,
)


def _kept_off(request: str) -> str:
    """The request with what it keeps cut off ("but keep the tiles white", "chips unchanged"),
    the clauses that say what it should go with ("so it sits better with the red") and the
    sentences that describe the material as it is ("The rings look like dull plastic.")."""
    request = without_state(request)
    asked = _KEEP_RE.sub("", request) or request
    asked = re.sub(r"\s+", " ", _PURPOSE_RE.sub(" ", asked)).strip() or asked
    return _AS_IS_RE.sub("", asked) or asked


def normalise(request: str) -> str:
    """The request with what it keeps cut off, its phrasal verbs read as plain words and its
    first look read as what it changes."""
    asked = _kept_off(request).lower()
    for pattern, repl in _PHRASES:
        asked = pattern.sub(repl, asked)
    verbs = edit_words().colour_verbs  # "yellow it with age": yellower
    asked = _colour_verb_re().sub(lambda m: verbs[m.group(1)], asked)
    too = edit_words().too  # "far too big": smaller ("a bit too dark": a bit lighter)
    asked = _too_re().sub(lambda m: too[m.group(1)], asked)
    return _looks(asked)


@functools.cache
def _colour_verb_re() -> re.Pattern[str]:
    """A colour word of ``[colour_verbs]`` used as a verb: "<colour> it|them" (compiled once)."""
    return re.compile(rf"\b({'|'.join(edit_words().colour_verbs)})\s+(?:it|them)\b")


@functools.cache
def _too_re() -> re.Pattern[str]:
    """ "(far) too <adjective>" of ``[too]`` (compiled once)."""
    return re.compile(rf"\b(?:far\s+|way\s+)?too\s+({'|'.join(edit_words().too)})\b")


def _looks(asked: str) -> str:
    """The request with its first look word read as what it changes (``[looks]`` of
    ``words.toml``: "make it look wet" is darker and glossier all over, "faded" paler): a wet
    or faded surface changes everywhere, which an overlay's patches do not show. A flipped look
    ("less bleached") is read as its opposite when it has one, else left as it is; a look word
    that names a finish ("the wet shine") or is no look ("the wet room") is left too."""
    ew = edit_words()
    ws = tokens(asked)
    for i, t in enumerate(ws):
        phrase = ew.looks.get(t)
        if phrase is None:
            continue
        if i + 1 < len(ws) and (ws[i + 1] in ew.finish or ws[i + 1] in ("shine", "sheen")):
            continue
        lead = next((w for w in ws if w not in ew["filler"]), None) == t
        said = bool(ew["look"] & set(ws[max(0, i - 3) : i])) or ws[i + 1 : i + 2] == ["look"]
        # "make it wet", "get them damp", "more wet" ("where it stays damp" is a place)
        # ("add some yellowing": a look no overlay draws; "add some wet patches" are patches)
        verbs = ("make", "get", "more", "less") + (
            ("add", "some") if t in ew["added_looks"] else ()
        )
        made = any(w in verbs for w in ws[max(0, i - 3) : i])
        if not (lead or said or made):
            continue  # "the sample from the wet room"
        if {"than", "instead"} & set(ws[max(0, i - 3) : i]):
            continue  # "more like satin than wet-look": the look it should not have
        if not flipped(ws, i, ew["flip"]):
            return re.sub(rf"\b{re.escape(t)}\b", phrase, asked, count=1)
        flip = next(w for w in reversed(ws[max(0, i - 2) : i]) if w in ew["flip"])
        if t not in ew.unlooks or not re.fullmatch(r"[a-z]+", flip) or len(flip) < 2:
            return asked  # no opposite, or a contraction ("shouldn't be wet"): as it is
        # "less bleached": the flip word and the look give way to the opposite
        span = rf"\b{flip}\s+(?:\w+\s+)?{re.escape(t)}\b"
        return re.sub(span, ew.unlooks[t], asked, count=1)
    return asked


#: The rules, in the order they are tried.
RULES: tuple[Callable[[Context], Plan | None], ...] = (
    _tileable,
    physical_rule,
    _joints,
    amount_rule,
    roughness_rule,
    channel_rule,
    relief_rule,
    contrast_rule,
    colour_rule,
    _scale,
    feature_rule,
)


def plan_edit(
    program: A.Program,
    params: Sequence[Param],
    request: str,
    strength: float = 1.0,
    ew: EditWords | None = None,
) -> Plan:
    """The offline plan for ``request`` on ``program`` (its parameter list ``params``), its
    steps times ``strength``. Raises :class:`EditRefused` when no rule maps the request."""
    # "charcoal grout but keep the tiles white": what is to be kept is not what is to change
    ew = ew or edit_words()
    said = tuple(tokens(_kept_off(request)))

    def context(asked: str) -> Context:
        # "make the tiles blue and make the grout white": the first part leads, the next joins
        lead = re.split(AND_VERB, asked)[0]
        return Context(request, tokens(lead), list(params), program, words(), strength, ew, said)

    asked = normalise(request)
    c = context(asked)
    shined = reread(c, asked)  # "more matte, less oily" on skin: less glossy
    if shined != asked:
        asked, c = shined, context(shined)
    for rule in RULES:
        plan = rule(c)
        if plan is not None:
            plan = join_clauses(c, asked, plan, RULES)
            if plan.rule in ("roughness", "roughness+colour"):  # "satin, more visible grain"
                plan = with_contrast(c, plan, contrast_rule(replace(c, words=tokens(asked))))
            return plan
    raise EditRefused(
        request,
        "no offline rule understands it (colours, rougher/glossier, sheen, clearcoat, metallic, "
        "deeper/flatter relief, bigger/smaller, denser/sparser, wider/narrower joints, "
        "more/less wear, dirt, rust or moss, tileable, a physical size); use --model for "
        "other edits",
        params,
    )
