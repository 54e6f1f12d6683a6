"""How strongly a named feature shows: "more visible grain", "less prominent spalt lines",
"subtler veins", "more contrast in the marbling", "less variation in the tile colour", "a more
uniform blue".

The feature is the program's Define the request's noun names (``grain``, ``spalt_line``,
``vein``; "variation" and "uniform" name the tone Defines: ``tone``, ``shade``, ``vary``). Its
values are measured on the program's window and the Define is rewritten to spread around its
mean by a factor: over 1 it shows more (clamped to the range it had, so a mask stays a mask),
under 1 less, 0 would be uniform. Everything the Define feeds changes with it, which is what the
request names; the locality check holds the edit to those channels.
"""

from __future__ import annotations

import numpy as np

from matloom.author.edit.lexicon import EditWords, split_words, stem
from matloom.author.edit.plan import Context, Plan
from matloom.author.edit.targets import define_closure, refs_of
from matloom.engine.evaluate import evaluate
from matloom.lang import ast as A
from matloom.lang.printer import format_expr

# The words (how strongly something shows, degrees, negations, places) are the
# ``show_*``, ``degree*``, ``negation``, ``feature_place``, ``not_feature``, ``tone_defines``
# and ``amount_*`` lists of ``words.toml``.

#: The feature's spread at step 1: shown more (x1.8) or less (x0.45); a stronger step
#: (an escalated edit, "much more") goes further.
_MORE, _LESS_F = 0.8, 0.55
#: Grid the feature is measured on (fine enough for threads and fibres: a coarser one misses
#: the gaps of a weave and reads it as flat).
_PROBE = 192


def _direction(words: list[str], ew: EditWords) -> tuple[int, int] | None:
    """(direction, index of the word) of the first show word said with a degree ("more
    visible", "less prominent", "too busy" is not one) or comparative ("subtler"), or None.
    "Contrast stitching", "a subtle red" and "for more contrast" (a reason for another
    change) are not requests for contrast."""
    degree, less = ew["degree"], ew["degree_less"]
    for i, w in enumerate(words):
        if w in ew["shows_more"] or w in ew["shows_less"]:
            sign = 1 if w in ew["shows_more"] else -1
            if i > 0 and words[i - 1] in less:
                sign = -sign  # "less bold"
            return sign, i
        if w not in ew["show_more"] and w not in ew["show_less"]:
            continue
        j = i - 1
        if w in ew["show_nouns"] and j > 0 and words[j] not in degree and words[j - 1] in degree:
            j -= 1  # "more colour variation", "less grain contrast"
        while j >= 0 and words[j] in ew["degree_soft"]:
            j -= 1
        if j < 0 or words[j] not in degree:
            continue  # no degree: an adjective ("contrast stitching", "a subtle red")
        if j > 0 and words[j - 1] == "for":
            continue  # "... for more contrast": the reason for another change
        if j > 0 and "so" in words[max(0, j - 4) : j]:
            continue  # "shallower so the hammering is more subtle": the reason
        if w == "even" and words[i + 1 : i + 2] and words[i + 1] not in ("tone", "colour", "color"):
            continue  # "even more grain": no evenness
        sign = 1 if w in ew["show_more"] else -1
        # "less visible"; "too subtle", "too bold": less of what it is, the other way;
        # "not so prominent", "shouldn't be so visible": the other way too
        if words[j] in less or words[j] == "too":
            sign = -sign
        if ew["negation"] & set(words[max(0, j - 3) : j]):
            sign = -sign
        return sign, i
    return None


def _feature_words(words: list[str], ew: EditWords) -> set[str]:
    """The stemmed words that may name the feature: not degree, direction or filler words,
    and none that follow a place word ("barely visible between the tiles")."""
    skip = (
        ew["not_feature"] | ew["degree"] | ew["degree_soft"] | ew["show_more"] | ew["show_less"]
    ) | (ew["shows_more"] | ew["shows_less"])
    out: set[str] = set()
    place = False
    for w in words:
        place = place or w in ew["feature_place"]
        if not place and w not in skip:
            out.add(stem(w))
    return out


def _candidates(
    program: A.Program, nouns: set[str], tone: frozenset[str]
) -> list[tuple[int, A.Define]]:
    """(score, Define) of the field Defines the nouns name (a Define named by a ``tone`` word
    scores 2 more: the request speaks of variation or uniformity), best first."""
    scored: list[tuple[int, int, A.Define]] = []
    painted = _painted(program)
    for k, d in enumerate(program.defines):
        if d.params or not any(isinstance(n, A.Call) for n in A.walk(d.expr)):
            continue  # a constant or a parameterised Define is no feature of the surface
        parts = split_words(d.name)
        if parts & {"r", "g", "b"} and len(parts) <= 2:
            continue  # a colour component
        hits = len(parts & nouns) + (2 if parts & tone else 0)
        if hits and painted.get(d.name, set()) & nouns:
            hits += 1  # the coverage of a layer whose colour the noun names ("line_r")
        if hits:
            scored.append((-hits, k, d))
    scored.sort(key=lambda t: (t[0], t[1]))
    return [(-h, d) for h, _, d in scored]


def _painted(program: A.Program) -> dict[str, set[str]]:
    """Coverage Define -> the words of the colour Defines its layer paints with (a layer
    ``Layer(zone_line).basecolor(line_r, line_g, line_b)``: zone_line -> {line})."""
    out: dict[str, set[str]] = {}
    for layer in program.layers:
        if not isinstance(layer.alpha, A.Ref):
            continue
        colour = layer.channel("basecolor")
        names = {n.name for a in (colour.args if colour else ()) for n in A.walk(a)
                 if isinstance(n, A.Ref)}  # fmt: skip
        words = {w for n in names for w in split_words(n)} - {"r", "g", "b", "col", "colour"}
        out.setdefault(layer.alpha.name, set()).update(words)
    return out


def _top(program: A.Program, scored: list[tuple[int, A.Define]]) -> A.Define | None:
    """Of the best-scored Defines, the first that none of the others reads (the whole
    feature, not one of its parts)."""
    if not scored:
        return None
    best = [d for h, d in scored if h == scored[0][0]]
    closure = define_closure(program)
    for d in best:
        if not any(o is not d and d.name in closure.get(o.name, ()) for o in best):
            return d
    return best[0]


def _channels(program: A.Program, name: str) -> tuple[str, ...]:
    """The channels the Define feeds; "alpha" when it draws a layer's coverage (a coverage
    change may move every map)."""
    closure = define_closure(program)
    out: dict[str, None] = {}
    for layer in program.layers:
        if name in refs_of(layer.alpha, closure):
            out["alpha"] = None
        for ch in layer.channels:
            if any(name in refs_of(a, closure) for a in ch.args):
                out[ch.name] = None
    return tuple(out)


#: A feature whose values span more than this is a coordinate or an index (a ply number, a
#: phase), not a look: spreading it would scramble the pattern.
_MAX_SPAN = 3.0
#: A feature with this share of its samples at its two ends is a hard mask: spreading it
#: more changes nothing.
_HARD = 0.99


def _measure(program: A.Program, name: str, sign: int) -> tuple[float, float, float] | None:
    """(mean, min, max) of the Define over the window, or None when it cannot be shown more
    or less by spreading it (flat, a coordinate or index, or a hard mask asked to show more)."""
    probe = A.Program(
        program.view,
        program.defines,
        (A.Layer(None, (A.ChannelSet("height", (A.Ref(name),)),)),),
    )
    h = np.asarray(evaluate(probe, _PROBE, _PROBE).height, np.float64)
    span = float(np.ptp(h)) if np.isfinite(h).all() else 0.0
    if span < 1e-6 or span > _MAX_SPAN:
        return None
    lo, hi = float(h.min()), float(h.max())
    ends = np.mean((h < lo + 0.02 * span) | (h > hi - 0.02 * span))
    if sign > 0 and ends >= _HARD:
        return None
    if lo >= 0 and hi <= 1:  # a mask or a share: it may use the whole of [0, 1]
        return float(h.mean()), 0.0, 1.0
    return float(h.mean()), lo - 0.1 * span, hi + 0.1 * span


def _num(v: float) -> str:
    return f"{v:.4g}"


def contrast_rule(c: Context) -> Plan | None:
    """Show a named feature more or less (module docstring); None when the request says
    nothing of how strongly something shows, or names no feature of the program."""
    found = _direction(c.words, c.ew)
    if found is None:
        return None
    sign, at = found
    # a condition's amount is the amount rule's ("less visible rust": less rust)
    nouns = _feature_words(c.words, c.ew) - {stem(w) for w in c.ew.conditions}
    tone = c.ew["tone_defines"] if c.words[at] in c.ew["show_tone"] else frozenset()
    scored = _candidates(c.program, nouns, tone)
    target, measured = None, None
    while scored and measured is None:
        target = _top(c.program, scored)
        assert target is not None
        measured = _measure(c.program, target.name, sign)
        scored = [(h, d) for h, d in scored if d is not target]
    if target is None or measured is None:
        return None
    mean, lo, hi = measured
    k = 1 + _MORE * c.k if sign > 0 else _LESS_F**c.k
    spread = f"({_num(mean)} + (({format_expr(target.expr)}) - {_num(mean)}) * {_num(k)})"
    if sign > 0:  # spread further, clamped to its range (a mask stays a mask)
        spread = f"Clamp(x={spread}, lo={_num(lo)}, hi={_num(hi)})"
    text = f"Define({target.name}, {spread})"
    how = "shows more" if sign > 0 else "shows less"
    note = f"{target.name} {how} (its spread around {mean:.3g} x{k:.2f})"
    intended = _channels(c.program, target.name)
    return Plan(
        "contrast",
        note,
        lines={f"define:{target.name}": text},
        intended=intended,
        graded=True,
        said=(c.words[at],),
    )


def feature_rule(c: Context) -> Plan | None:
    """ "less crystal speckle", "more mottling", "more pucker": a feature of the program (a
    field Define the noun names) shown less or more, when no other rule read the request (it
    comes last). Only a mass noun: "more pebbles", "more creases" ask for a count, which
    showing them more does not give (refused as before)."""
    ew = c.ew
    for i, w in enumerate(c.words):
        if w not in ew["amount_more"] and w not in ew["amount_less"]:
            continue
        if c.words[i + 1 : i + 2] and c.words[i + 1] in ew["amount_not_after"]:
            continue  # "more like birch ply", "cover more of the wall", "more than"
        following = [x for x in c.words[i + 1 : i + 4] if x not in ew["not_feature"]]
        if not following or following[0] in ew["amount_not_feature"]:
            continue
        if any(stem(x) != x for x in following[:2]):
            continue  # a plural: a count
        word = "visible" if w in ew["amount_more"] else "subtle"
        sub = Context(
            c.request, ["more", word, *c.words[i + 1 : i + 4]], c.params, c.program, c.vocabulary,
            c.strength, c.ew, c.said,
        )  # fmt: skip
        plan = contrast_rule(sub)
        if plan is not None:
            return plan
    return None
