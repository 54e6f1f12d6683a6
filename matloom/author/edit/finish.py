"""Finish rules: roughness ("rougher", "less shiny", "matte"), single channels ("less sheen",
"more clearcoat", "less metallic") and relief ("deeper", "flatter", "more relief").

Steps are sized to show in a lit preview (``[factors]`` of ``words.toml``): a comparative moves
roughness by at least ``rough_min`` and half the way to its end; a finish adjective ("matte",
"glossy") moves it to the library's value for that finish (``finish_roughness``), or a step
further when it is there already. A word after "less", "not", "too" ... flips ("less shiny"
is rougher). "rough"/"smooth" also mean touch: when the roughness cannot move visibly, the
relief moves with it.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import replace

from matloom.author.edit.lexicon import EditWords, flipped, too_strong
from matloom.author.edit.plan import Context, Plan, Value, assign, clamp
from matloom.author.edit.targets import matching, named_in_program, param_layers
from matloom.lang import ast as A
from matloom.lang.params import Param
from matloom.lang.printer import format_layer

_ROUGH_WORDS = frozenset({"roughness", "roughen", "glossiness", "shininess", "finish"})


def _replaced(ws: list[str], i: int) -> bool:
    """Whether the word at ``i`` names what is to be replaced ("frosted instead of polished",
    "matte rather than glossy", "more satin than glossy"): the finish asked for is the other
    one."""
    if "than" in ws[max(0, i - 2) : i]:
        return True
    return any(
        ws[j : j + 2] in (["instead", "of"], ["rather", "than"])
        for j in range(max(0, i - 4), i - 1)
    )


def _names_feature(c: Context) -> bool:
    """Whether the request names a drawn part of the program ("the brushing lines coarser",
    "coarser granules"): "coarser" is then its size."""
    nouns = [
        t
        for t in c.nouns
        if t not in c.ew.finish and t not in _ROUGH_WORDS and t not in ("surface", "texture")
    ]
    return bool(nouns) and named_in_program(c.program, nouns, c.ew)


def _finish_word(c: Context) -> tuple[int, str, str] | None:
    """(direction, kind, word) of the request's finish word (flips applied). A finish named
    as the one to replace is the other way; a finish word that is neither flipped nor replaced
    ("knock the gloss down to a satin finish": satin) wins over one that is, and over one
    that names the surface's finish ("can the polish be duller": duller)."""
    ws = c.words
    found: list[tuple[int, str, str, int]] = []  # ..., its rank (the best is 0)
    for i, t in enumerate(ws):
        if t in c.ew.finish:
            d, kind = c.ew.finish[t]
            if _replaced(ws, i):  # "frosted instead of polished": any other finish word wins
                found.append(((-d if d else 1), "step", t, 2))
                continue
            if flipped(ws, i, c.ew["flip"]):  # "too matte for satin": the first word leads
                found.append(((-d if d else 1), "step", t, 0))
                continue
            if d and any(w in c.ew["more"] for w in ws[max(0, i - 2) : i]):
                kind = "step"  # "more polished": a step ("more satin" is still satin)
            # "can the polish be duller": after an article, the surface's finish, not the one
            # asked for, and any other finish word wins over it; "knock the gloss down to a
            # satin finish": the finish it goes to wins over the one it leaves
            to = any(w in ("to", "into") for w in ws[max(0, i - 2) : i])
            rank = -1 if to else 1 if i and ws[i - 1] in c.ew["articles"] else 0
            found.append((d, kind, t, rank))
    if found:
        if all(f[2] == "coarser" for f in found) and (set(ws) & c.ew["size"] or _names_feature(c)):
            return None  # "coarser grain, the speckles twice as big", "coarser granules": a size
        if set(ws) & set(c.ew.relief) and all(f[2] in c.ew.tactile for f in found):
            return None  # "flatten the broom texture, nearly smooth": the relief
        d, kind, t, _ = min(found, key=lambda f: f[3])  # the first of the best rank
        return d, kind, t
    if "roughness" in ws or "roughen" in ws:
        if set(ws) & c.ew["lower"]:
            return -1, "step", "roughness"
        return 1, "step", "roughness"
    if {"glossiness", "shininess"} & set(ws):
        return (1 if set(ws) & c.ew["lower"] else -1), "step", "gloss"
    return None


#: Words that push a gloss target further ("a high gloss", "highly polished", "mirror").
_INTENSE = frozenset({"high", "highly", "very", "super", "mirror", "extremely", "ultra"})


def _intense(c: Context, word: str) -> bool:
    ws = c.words
    i = ws.index(word) if word in ws else -1
    return (
        bool(_INTENSE & set(ws[max(0, i - 2) : i]))
        or "mirror" in ws
        or ("high" in ws and "gloss" in ws)
    )


def _rough_params(c: Context) -> list[Param]:
    return [
        p
        for p in c.params
        if p.kind == "scalar"
        and "roughness" in p.affects
        and set(p.affects) <= {"roughness"}
        and ("rough" in p.label.lower() or "rough" in p.address.lower())
    ]


def _step(v: float, d: int, c: Context, hi: float = 1.0) -> float:
    k = c.k
    if d > 0:
        return min(hi, v + max(c.ew.f("rough_min") * k, (hi - v) * c.ew.f("rough_frac") * k))
    floor = min(v, 0.03)
    return max(floor, min(v - c.ew.f("rough_min") * k, v * c.ew.f("gloss_factor") ** k))


def roughness_rule(c: Context) -> Plan | None:
    found = _finish_word(c)
    if found is None:
        return None
    d, kind, word = found
    params = _rough_params(c)
    skip = (
        set(c.ew.finish)
        | _ROUGH_WORDS
        | c.ew["higher"]
        | c.ew["lower"]
        | c.ew["flip"]
        | {"rough", "gloss"}
    )
    nouns = [n for n in c.nouns if n not in skip]
    targets = matching(params, nouns, c.program, c.ew) or params
    if not targets:
        raise c.refuse("no roughness parameter")
    finish = c.vocabulary.finishes.get(word) or c.vocabulary.finishes.get(f"{word}ed")
    target = c.vocabulary.finish_roughness.get(finish) if finish and kind == "target" else None
    if target is not None and d < 0 and _intense(c, word):
        # "a high gloss", "highly polished", "mirror": past the polished value
        target = min(target, c.vocabulary.finish_roughness.get("polished", target)) * 0.6
    new: dict[Param, Value] = {}
    for p in targets:
        v = float(p.value)  # type: ignore[arg-type]
        hi = min(1.0, p.high if p.high is not None else 1.0)
        if target is not None and c.strength == 1.0:
            t = target if d == 0 else (max(v, target) if d > 0 else min(v, target))
            new[p] = clamp(p, t)
        else:
            new[p] = clamp(p, _step(v, d or (1 if (target or 0.5) > v else -1), c, hi))
    if target is not None and all(abs(float(new[p]) - float(p.value)) < 0.1 for p in targets):  # type: ignore[arg-type]
        d = d or 1
        new = {p: clamp(p, _step(float(p.value), d, c)) for p in targets}  # type: ignore[arg-type]
    intended: tuple[str, ...] = ("roughness",)
    note = "rougher" if d > 0 else "glossier" if d < 0 else f"{word} (roughness {target:g})"
    # a finish target ("satin" on a glossy glaze) moves the clear coat the way the roughness
    # moves, or the coat keeps the surface as glossy as it was
    mean_before = sum(float(p.value) for p in targets) / len(targets)  # type: ignore[arg-type]
    mean_after = sum(float(new[p]) for p in targets) / len(targets)  # type: ignore[arg-type]
    coat_d = d or (
        1 if mean_after > mean_before + 0.05 else -1 if mean_after < mean_before - 0.05 else 0
    )
    coats = _coats(c, targets, coat_d)
    if coats:
        new.update(coats)
        intended += ("coat",)
        note += ", clearcoat " + ("down" if coat_d > 0 else "up")
    lines: dict[str, str] = {}
    starts = [float(p.value) for p in targets]  # type: ignore[arg-type]
    mean = sum(starts) / len(starts)
    if word in c.ew.tactile and (mean >= 0.6 if d > 0 else mean <= 0.25):
        # rough to the touch too: an already rough surface gets rougher in relief (and an
        # already glossy one smoother), which a lit preview shows where roughness barely does
        factor = c.ew.f("tactile_relief") ** (c.k if d > 0 else -c.k)
        more, lines = relief_change(c, factor)
        if more or lines:
            new.update(more)
            intended += ("height",)
            note += f", relief x{factor:.3g}"
    return _plan(assign(c, "roughness", note, new, intended) if new else None, lines, c, note)


def _plan(plan: Plan | None, lines: dict[str, str], c: Context, note: str) -> Plan:
    if plan is None:
        if not lines:
            raise c.refuse("nothing to change")
        return Plan("relief", note, lines=lines, intended=("height",), graded=True)
    return replace(plan, lines=lines) if lines else plan


def _coats(c: Context, targets: list[Param], d: int) -> dict[Param, Value]:
    """Clearcoat amounts of the layers the roughness targets feed: a clear coat keeps a
    surface glossy whatever the roughness under it, so "less shiny" lowers it and "glossier"
    raises one that is there."""
    if d == 0:
        return {}
    layers = set().union(*(param_layers(p, c.program) for p in targets))
    out: dict[Param, Value] = {}
    for p in c.params:
        if (
            p.kind != "scalar"
            or set(p.affects) != {"coat"}
            or not param_layers(p, c.program) & layers
        ):
            continue
        v = float(p.value)  # type: ignore[arg-type]
        if d > 0 and v > 0:
            out[p] = clamp(p, v * c.ew.f("coat_factor") ** c.k)
        elif d < 0 and v > 0:
            hi = min(1.0, p.high) if p.high is not None else 1.0
            step = max(c.ew.f("channel_min") * c.k, (hi - v) * c.ew.f("channel_frac") * c.k)
            out[p] = clamp(p, min(hi, v + step))
    return out


# ---- single channels ---------------------------------------------------------------------------
def _dims(words: Sequence[str], ew: EditWords) -> bool:
    """Whether a dim word asks for less ("dim the diodes", "dimmer"), not says it is too weak
    ("the glow is too dim", "the diodes are dim")."""
    return any(
        w in ew["dim"] and (i == 0 or words[i - 1] not in ew["dim_said"])
        for i, w in enumerate(words)
    )


def channel_rule(c: Context) -> Plan | None:
    ws = c.words
    hit = next(((i, c.ew.channel_of(t)) for i, t in enumerate(ws) if c.ew.channel_of(t)), None)
    if hit is None:
        return None
    i, channel = hit
    assert channel is not None
    before = ws[max(0, i - 2) : i]
    zero = any(w in ("no", "without", "remove") for w in before)
    # "less glow", "the glow is too strong", "dim the diodes": less of it
    weaker = too_strong(ws[i:], c.ew) or _dims(ws, c.ew)
    d = -1 if flipped(ws, i, c.ew["flip"]) or weaker else 1
    params = [
        p
        for p in c.params
        if p.kind == "scalar" and channel in p.affects and set(p.affects) <= {channel}
    ]
    if not params:
        if d > 0 and not zero and channel in _ADDED and _asks_coat(c, i, channel):
            return _added_channel(c, channel)  # "give it a clear lacquer": a coat on top
        raise c.refuse(f"no {channel} parameter (no layer writes {channel} as a number)")
    skip = c.ew.channels[channel] | c.ew["more"] | c.ew["flip"] | {channel}
    nouns = [n for n in c.nouns if n not in skip]
    targets = matching(params, nouns, c.program, c.ew) or params
    k = c.k
    new: dict[Param, Value] = {}
    for p in targets:
        v = float(p.value)  # type: ignore[arg-type]
        lo = p.low if p.low is not None else 0.0
        # an open-ended strength over 1 (an emissive 2.5): up to twice it, not down to 1
        hi = min(1.0, p.high) if p.high is not None else max(1.0, 2 * v)
        if zero:
            new[p] = clamp(p, lo)
        elif d > 0:
            step = max(c.ew.f("channel_min") * k, (hi - v) * c.ew.f("channel_frac") * k)
            new[p] = clamp(p, min(hi, v + step))
        else:
            step = max(c.ew.f("channel_min") * k, (v - lo) * c.ew.f("channel_frac") * k)
            new[p] = clamp(p, max(lo, v - step))
    word = "no" if zero else "more" if d > 0 else "less"
    return assign(c, "channel", f"{word} {channel}", new, (channel,), graded=not zero)


#: Channels a request may add where no layer writes them, and the value each layer gets
#: ("give it a clear varnish": a clear coat of 0.8). Not sheen: "a wet sheen", "a slight
#: sheen" on stone mean gloss, and a cloth's sheen lobe would be wrong there.
_ADDED = {"coat": 0.8}


def _asks_coat(c: Context, i: int, channel: str) -> bool:
    """Whether word ``i`` (a word of ``channel`` in ``words.toml``) asks to add it: the bare
    channel name only after "clear" ("a clear coat", not "a bold 1960s coat"), and no part the
    program names ("lighten the desert varnish")."""
    w = c.words[i]
    if w == channel and c.words[i - 1 : i] != ["clear"]:
        return False
    return not named_in_program(c.program, [w], c.ew)


def _added_channel(c: Context, channel: str) -> Plan:
    """Every layer writes ``channel`` at its added value (a clear coat or a sheen asked for on a
    material that has none): the layers' lines are rewritten, nothing else moves."""
    value = round(min(1.0, _ADDED[channel] * min(1.0, c.k)), 3)
    lines: dict[str, str] = {}
    if any(layer.channel(channel) is not None for layer in c.program.layers):
        # a layer writes it as an expression (a wet coat mask): not overwritten
        raise c.refuse(f"the {channel} is an expression of the program; no number to raise")
    for n, layer in enumerate(c.program.layers, start=1):
        added = A.Layer(layer.alpha, (*layer.channels, A.ChannelSet(channel, (A.Num(value),))))
        lines[f"layer:{n}"] = " ".join(x.strip() for x in format_layer(added))
    note = f"{channel} {value:g} added to every layer (none wrote it)"
    return Plan("channel", note, lines=lines, intended=(channel,), exact=True)


# ---- relief ------------------------------------------------------------------------------------
def _relief_params(c: Context) -> list[Param]:
    """Scalars that scale the relief: labelled relief or depth, feeding only height."""
    return [
        p
        for p in c.params
        if p.kind == "scalar"
        and "height" in p.affects
        and set(p.affects) <= {"height", "normal", "ao"}
        and any(k in p.label.lower() for k in ("relief", "depth", "bump", "displacement"))
        and float(p.value) != 0  # type: ignore[arg-type]
    ]


def _relief_direction(c: Context) -> int | None:
    ws = c.words
    w = c.vocabulary
    if any(t in w.named for t in ws) or {"colour", "color"} & set(ws):
        return None  # "deeper red" is a colour
    for i, t in enumerate(ws):
        if t in c.ew.relief:
            d = c.ew.relief[t]
            return -d if flipped(ws, i, c.ew["flip"]) else d
    for i, t in enumerate(ws):
        if t in c.ew.relief_nouns:
            near = ws[max(0, i - 2) : i]
            if any(x in c.ew["flip"] or x in c.ew["lower"] for x in near):
                return -1
            if any(x in c.ew["more"] | c.ew["higher"] | {"stronger", "deeper"} for x in near):
                return 1
            # "make the hammered texture more pronounced", "the texture less visible" (not "too
            # visible", which the contrast rule reads)
            after = ws[i + 1 : i + 4]
            for j in range(1, len(after)):
                if after[j] in c.ew["show_more"] and after[j - 1] in ("more", "less"):
                    return -1 if after[j - 1] == "less" else 1
    return None


def relief_change(c: Context, factor: float) -> tuple[dict[Param, Value], dict[str, str]]:
    """The relief times ``factor``: the relief scalars when the program has some, else every
    varying height channel multiplied (the layers rewritten)."""
    params = _relief_params(c)
    if params:
        return {p: clamp(p, float(p.value) * factor) for p in params}, {}  # type: ignore[arg-type]
    lines: dict[str, str] = {}
    for i, layer in enumerate(c.program.layers):
        chans = []
        for ch in layer.channels:
            if ch.name == "height" and not isinstance(ch.args[0], A.Num):
                num = A.Num(float(f"{factor:.4g}"))
                ch = replace(ch, args=(A.BinOp("*", ch.args[0], num),))
            chans.append(ch)
        if chans != list(layer.channels):
            text = " ".join(x.strip() for x in format_layer(replace(layer, channels=tuple(chans))))
            lines[f"layer:{i + 1}"] = text
    return {}, lines


def relief_rule(c: Context) -> Plan | None:
    d = _relief_direction(c)
    if d is None:
        return None
    factor = c.ew.f("relief") ** (d * c.k)
    new, lines = relief_change(c, factor)
    word = "deeper" if d > 0 else "flatter"
    if new:
        plan = assign(c, "relief", f"relief {word} (x{factor:.3g})", new, ("height",))
        return replace(plan, reduces=d < 0)
    if not lines:
        raise c.refuse("no relief: no layer has a height that varies")
    return Plan(
        "relief",
        f"every layer's varying height x{factor:.3g} ({word})",
        lines=lines,
        intended=("height",),
        graded=True,
        reduces=d < 0,
    )
