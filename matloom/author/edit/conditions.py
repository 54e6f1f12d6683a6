"""The condition rule: "more rust", "less moss", "add dirt", "more worn".

In order:

1. an **amount parameter** of the condition: a scalar labelled with it and "amount"/"cover",
   a constant Define named for it that reaches a layer's coverage (``Define(wear, 0.45)``), or
   the cover of a composed library overlay; it moves by ``amount_step``;
2. a **layer of the condition** (its coverage reads a Define named for it, ``Layer(rust)``):
   the parameters its coverage depends on are tried, those that feed nothing else first, and
   the coverage is *measured* (the mask evaluated on a small grid) until it grows x1.5 (or
   shrinks x0.5), at least ``cover_min``;
3. **absent** and asked for ("add moss", "more scratches"): the library's overlay for the word
   (its triggers) is composed on top as new Defines and layers (the overlay's own amount, or the
   request's amount word), its seeds new, every existing seed kept.

"less X" where the program has no X is refused.
"""

from __future__ import annotations

import functools
import re
from collections.abc import Sequence
from dataclasses import replace

from matloom.author.edit.apply import add_lines, all_params
from matloom.author.edit.colours import describes_part
from matloom.author.edit.lexicon import edit_words, split_words, stem, tokens, too_strong
from matloom.author.edit.looks import condition_look, names_colour, one_mark
from matloom.author.edit.measured import mask_coverage, measured_coverage, measured_layer
from matloom.author.edit.places import place_of
from matloom.author.edit.plan import Context, EditRefused, Plan, Value, affects, assign, clamp
from matloom.author.edit.targets import (
    define_closure,
    main_colour,
    mask_names,
    material_noun,
    named_in_program,
)
from matloom.lang import ast as A
from matloom.lang.api import parse_expression
from matloom.lang.deps import BLENDED, MAXED
from matloom.lang.params import Param
from matloom.lang.printer import format_expr, format_layer
from matloom.lang.tileable import tileable_warnings
from matloom.library.overlay import HOST_HEIGHT, Overlay, constant


def _named(name: str, stems: Sequence[str]) -> bool:
    return any(w.startswith(s) for w in split_words(name) for s in stems)


def _labelled(c: Context, stems: Sequence[str]) -> list[Param]:
    out = []
    for p in c.params:
        if p.kind != "scalar" or p.address.endswith(".base"):
            continue
        label = p.label.lower()
        if any(s in label for s in stems) and any(k in label for k in ("amount", "cover")):
            out.append(p)
        elif (
            re.fullmatch(r"define:\w+", p.address)
            and _named(p.address[7:], stems)
            and "alpha" in p.affects  # an amount moves a coverage (not a colour component)
        ):
            out.append(p)
    return out


def _overlay_covers(c: Context, stems: Sequence[str]) -> list[Param]:
    """Cover amounts of composed overlays: a scalar Define named ``cover*`` that a Define
    named for the condition (``rust``, ``moss``, ``wear``) depends on."""
    closure = define_closure(c.program)
    out = []
    for p in c.params:
        name = p.address.removeprefix("define:")
        if p.kind != "scalar" or "." in name or not name.startswith("cover"):
            continue
        if any(name in deps and _named(d, stems) for d, deps in closure.items()):
            out.append(p)
    # an overlay composed over another reads the lower one's cover through the host's height
    # it follows (rust over moss: "less rust" is the rust's cover, not the moss's too)
    host = set().union(*(deps for d, deps in closure.items() if d.startswith(HOST_HEIGHT)))
    own = [p for p in out if p.address.removeprefix("define:") not in host]
    return own or out


def _condition_layers(c: Context, stems: Sequence[str]) -> list[int]:
    """Layers above the first whose coverage reads a Define named for the condition."""
    out = []
    for i, layer in enumerate(c.program.layers):
        if i == 0 or layer.alpha is None:
            continue
        if any(_named(n, stems) for n in mask_names(layer.alpha)):
            out.append(i)
    return out


def present(c: Context, stems: Sequence[str]) -> bool:
    """Whether the program has a condition of these stems to reduce (an amount, a cover, a
    layer of it)."""
    return bool(_labelled(c, stems) or _overlay_covers(c, stems) or _condition_layers(c, stems))


# ---- overlays ----------------------------------------------------------------------------------
def _seeds(program: A.Program) -> set[int]:
    return {
        int(a.value.value)
        for _, e in A.program_expressions(program)
        for n in A.walk(e)
        if isinstance(n, A.Call)
        for a in n.args
        if a.param == "seed" and isinstance(a.value, A.Num)
    }


def _host_cover(program: A.Program) -> A.Node | None:
    """Where the program covers the surface fully when it has holes (texels no layer covers,
    alpha 0: a lace, a perforated sheet), None when it has none or is sheer everywhere."""
    alphas = [layer.alpha for layer in program.layers]
    if not alphas or any(a is None or (isinstance(a, A.Num) and a.value >= 1) for a in alphas):
        return None
    union = (
        alphas[0]
        if len(alphas) == 1
        else parse_expression(f"Max({', '.join(format_expr(a) for a in alphas if a is not None)})")
    )
    text = format_expr(union)
    holes = mask_coverage(program, parse_expression(f"Smoothstep(0.02, 0, {text})"))
    full = parse_expression(f"Smoothstep(0.998, 1, {text})")
    # holes (alpha 0 somewhere) in a material that covers fully elsewhere: the added layers go
    # only where it covers fully (over a partly covered edge they would raise its alpha); a
    # sheer material, covered partly everywhere, keeps them where it is
    if holes < 0.01 or mask_coverage(program, full) < 0.2:
        return None
    return full


def overlay_lines(
    program: A.Program,
    overlay: Overlay,
    cover: float | None = None,
    scale: float = 1.0,
    within: A.Node | None = None,
    colour: tuple[int, int, int] | None = None,
    streaks: bool = False,
    follow_relief: bool = True,
    ring: bool = False,
) -> tuple[tuple[str, ...], tuple[str, ...]]:
    """The lines that put the library ``overlay`` on top of ``program`` (its Defines renamed
    where a name is taken, its seeds re-derived where one is taken; its host colour bound to
    the program's main colour slot), and the channels a layer on top changes where it covers.
    ``cover``: the overlay's amount (None: its own); ``scale``: its feature size factor;
    ``within``: a mask its layers are confined to (the joints); ``colour``: the colour of what
    it adds (None: its own); ``streaks``: its patches run down as streaks; ``follow_relief``:
    whether it settles by the host's relief as it does on its own (not when the request places
    it on the relief's high or low parts); ``ring``: its marks are rings. ValueError when it
    would break the program's tiling."""
    from matloom.library.overlay import compose
    from matloom.library.passes.compose import reseed

    params = all_params(program)
    colours = [p for p in params if p.kind == "colour"]
    main = None
    if colours:
        name = main_colour(colours, program, edit_words()).address.split(":", 1)[1]
        if program.define(f"{name}_r") is not None:
            main = name
    taken = _seeds(program)

    def fresh(q: A.Program) -> A.Program:
        return reseed(q, f"edit+{overlay.name}", 1) if _seeds(q) & taken else q

    composed = compose(
        program,
        overlay,
        main_colour=main,
        cover=cover,
        colour=colour,
        reseed=fresh,
        scale=scale,
        streaks=streaks,
        follow_relief=follow_relief,
        ring=ring,
    )
    host = _host_cover(program)
    if host is not None:  # a cut-out (lace, perforations): what is added keeps its holes open
        within = host if within is None else A.BinOp("*", within, host)
    if within is not None:  # confined: each new layer covers only where `within` is
        layers = tuple(
            replace(
                layer, alpha=within if layer.alpha is None else A.BinOp("*", layer.alpha, within)
            )
            for layer in composed.layers[len(program.layers) :]
        )
        composed = replace(composed, layers=composed.layers[: len(program.layers)] + layers)
    if program.tileable and len(tileable_warnings(composed)) > len(tileable_warnings(program)):
        raise ValueError(f"the {overlay.name} overlay would not tile with this program")
    defines = composed.defines[len(program.defines) :]
    layers = composed.layers[len(program.layers) :]
    add = tuple(f"Define({d.name}, {format_expr(d.expr)})" for d in defines) + tuple(
        " ".join(x.strip() for x in format_layer(layer)) for layer in layers
    )
    # a layer on top enters every blended channel where it covers (those it does not write
    # take their defaults there) and the height's maximum
    return add, (*BLENDED, *MAXED)


@functools.cache
def _overlays() -> tuple[Overlay, ...]:
    from matloom.library.overlay import OVERLAY_DIR, load_overlay

    return tuple(load_overlay(path) for path in sorted(OVERLAY_DIR.glob("*.mat")))


def library_overlays() -> dict[str, Overlay]:
    """The library's overlays by name (read once)."""
    return {ov.name: ov for ov in _overlays()}


def _subject(c: Context, i: int) -> bool:
    """Whether the condition word at ``i`` names the material itself ("make the snow look
    older": the snow is what ages, not snow to add): after an article, naming a Define or
    layer of the program."""
    word = c.words[i]
    asked = c.ew["more"] | c.ew["less"] | set(c.vocabulary.amounts)
    return (
        i > 0
        and c.words[i - 1] in c.ew["articles"]
        and not asked & set(c.words[max(0, i - 3) : i - 1])  # "less the verdigris": what
        and (named_in_program(c.program, [word], c.ew) or material_noun(c, [word]))
    )


def placed(words: Sequence[str], i: int) -> bool:
    """Whether the word at ``i`` follows a place word ("weeds out of the cracks", "moss between
    the stones": where, not what to add; not "patches of moss", "covered in moss")."""
    ew = edit_words()
    skip = ew["articles"] | {"a", "some"}
    near = [w for w in words[max(0, i - 3) : i] if w not in skip]
    if near[-2:] == ["out", "of"]:
        return True
    covered = len(near) > 1 and near[-2] in ew["covered"]
    return bool(near) and near[-1] in ew["place"] and not covered


def _trigger_word(c: Context) -> tuple[str, tuple[str, ...]] | None:
    """A library overlay's one-word trigger in the request ("wet", "snowy", "faded") when the
    request asks for an amount of it (more, less, add, some ...), is that word alone or leads
    it (its first word that is not filler: "make it look snowy after a storm"), with
    the stems its layers would be named by."""
    direction = c.ew["more"] | c.ew["less"] | c.ew["adding"] | set(c.vocabulary.amounts)
    alone = len([n for n in c.nouns if n not in direction]) == 1
    head = c.nouns[0] if c.nouns else None  # "make it look snowy after a storm": it leads
    # "make the roof look snowy": what it should look like
    said = {b for a, b in zip(c.words, c.words[1:], strict=False) if a in c.ew["look"]}
    for i, t in enumerate(c.words):
        if placed(c.words, i):
            continue
        for ov in _overlays():
            if t in ov.triggers and (alone or t == head or t in said or set(c.words) & direction):
                return t, tuple(dict.fromkeys((stem(t), ov.name.removesuffix("y")[:5])))
    return None


def _overlay_for(word: str, stems: Sequence[str]) -> Overlay | None:
    overlays = library_overlays()
    for ov in overlays.values():
        if word in ov.triggers:
            return ov
    for ov in overlays.values():
        if any(t.startswith(s) for t in ov.triggers for s in stems):
            return ov
    return None


def _add_overlay(c: Context, word: str, stems: Sequence[str]) -> Plan | None:
    ov = _overlay_for(word, stems)
    if ov is None:
        return None
    place = place_of(c, word)  # the joints, the relief's low or high parts, the middle ...
    amounts = [c.vocabulary.amounts[t] for t in c.words if t in c.vocabulary.amounts]
    cover = amounts[0] if amounts else None
    scale, scattered = 1.0, False
    if set(c.words) & c.ew["spots"]:  # "rust spots": small scattered marks, a little cover
        # ("a big wine stain": marks at the overlay's own size; "a coffee stain": one or two
        # large marks per repeat, not a scatter)
        one = one_mark(c, word) and not set(c.words) & c.ew["smaller"]  # not "a tiny stain"
        big = bool(set(c.words) & c.ew["bigger"])
        scale = c.ew.f("single_scale") if one else 1.0 if big else c.ew.f("spot_scale")
        scattered = not (one or big)
        cover = min(cover if cover is not None else 1.0, c.ew.f("spot_cover"))
    ring = bool(ov.ring) and bool(set(c.words) & c.ew["rings"])  # "a coffee ring"
    if ring and not set(c.words) & c.ew["smaller"]:
        scale, scattered = max(scale, 1.0), False  # a mug's ring, not a scatter of small marks
    look, coloured = condition_look(c, word, ov)
    within, where = place.mask, place.where
    # the place asked for is filled ("mould spots from a corner": spots there still)
    if within is not None and not amounts and not scattered:
        cover = c.ew.f("joint_cover")
    if c.strength > 1 and ov.cover:
        # a condition that does not show is added more strongly (the edit escalates it)
        own = constant(ov.ast, ov.cover)
        start = cover if cover is not None else own
        if start is not None:
            cover = round(min(c.ew.f("overlay_max_cover"), start * c.strength), 3)
    streaks = bool(ov.streaks) and bool(set(c.words) & c.vocabulary.streaks)
    try:
        host = add_lines(c.program, place.lines)  # the Defines the place's mask reads
        add, channels = overlay_lines(
            host,
            ov,
            cover,
            scale,
            within,
            look,
            streaks,
            follow_relief=not place.on_relief,
            ring=ring,
        )
    except ValueError as err:
        raise c.refuse(str(err)) from None
    add = (*place.lines, *add)
    amount = f" (amount {cover:g})" if cover is not None else ""
    if look is not None:
        amount += f" coloured {look}"
    if scale != 1.0:
        amount += f" as spots (size x{scale:g})"
    if streaks:
        amount += " in streaks running down"
    if ring:
        amount += " as rings"
    amount += where
    return Plan(
        "overlay",
        f"the library's {ov.name!r} overlay added on top{amount}",
        add=add,
        intended=channels,
        graded=bool(ov.cover),
        said=(*word.split(), *coloured),
    )


def _floored(p: Param, v: float) -> float:
    """``v``, not below 0 for an amount that is not negative (its range may be open)."""
    return max(0.0, v) if float(p.value) >= 0 and (p.low is None or p.low < 0) else v  # type: ignore[arg-type]


def amount_rule(c: Context) -> Plan | None:
    ws = set(c.words)
    sizes = c.ew["bigger"] | c.ew["smaller"] | c.ew["denser"] | c.ew["sparser"] | c.ew["width"]
    # the first clause says what to do ("less peeling, only small chips": an amount)
    head = set(tokens(re.split(r"[,;]", c.request.lower())[0])) or ws
    size_words = sizes - set(c.vocabulary.amounts)  # "a little moss" is an amount
    # "fewer, larger medallions": a size word anywhere makes "fewer" their spacing
    if "fewer" in head and not ws & (size_words - c.ew["sparser"]):
        plan = _more_of_layer(c)  # "fewer blisters": less of the layer they name, not bigger
        if plan is not None:
            return plan
    # a concrete condition before an age word ("older, with some moss": the moss first)
    conds = sorted(
        (
            t
            for i, t in enumerate(c.words)
            if t in c.ew.conditions and not placed(c.words, i) and not _subject(c, i)
        ),
        key=lambda t: t in c.ew["age"],
    )
    sized = head & (size_words - {"fewer"}) or "fewer" in head and ws & (size_words - {"fewer"})
    adds = _added_word(c, conds)
    adding = ws & c.ew["adding"]
    if sized and not (
        adds is not None and adding and _absent(c, *adds) and not _sizes_part(c, size_words)
    ):
        return None  # "bigger chips", "finer cracks", "fewer, larger medallions": a scale
    # ("a big wine stain": the size of a stain to add, not of the program's features)
    if adds is None:
        return _more_of_layer(c)
    word, stems = adds
    channel = c.ew.channel_of(word)
    if channel is not None and any(
        channel in p.affects and set(p.affects) <= {channel} for p in c.params
    ):
        return None  # "the glow is too strong" where a layer glows: its emissive channel
    asked = _direction(c, word)
    found = _labelled(c, stems) or _overlay_covers(c, stems)
    layers = _condition_layers(c, stems)
    absent = not (found or layers or named_in_program(c.program, [word, *stems], c.ew))
    # a condition named as a thing the program lacks ("lichen", "snow") is added; as a look of
    # a part ("the wires look rusty, orange-brown") it is that part's property
    # ("the holes should be deeper": a comparative changes what is there)
    changes = set(c.ew.comparative) | set(c.ew.relief) | c.ew["bigger"] | c.ew["smaller"]
    changes -= set(c.vocabulary.amounts)  # "a little green moss" is an amount
    if ws & c.ew["adding"]:  # "put a big wine stain on it": the size of what is added
        changes -= c.ew["bigger"] | c.ew["smaller"]
    added = absent and not word.endswith(("y", "ed")) and not set(c.words) & changes
    if asked is None and _property_word(c, word) and not added:
        # "drier mud", "a reddish mud", "prints deeper into the mud": the condition's noun
        # names the material (or a part) whose property changes, not more of the condition
        # (one the program does not have is added: "lichen, those pale yellow-green patches",
        # "a dusting of snow with green blades poking through")
        return None
    more = asked if asked is not None else _more(c)
    if found:
        step = c.ew.f("amount_step") * c.k * (1 if more else -1)
        # an amount that starts at 0 or more stays there (no negative wear)
        new: dict[Param, Value] = {
            p: clamp(p, _floored(p, float(p.value) + step))  # type: ignore[arg-type]
            for p in found
        }
        note = f"{'more' if more else 'less'} {word} ({step:+.3g})"
        return assign(c, "amount", note, new, affects(found))
    for index in layers:
        plan = measured_coverage(c, index, more, word)
        if plan is not None:
            return plan
    if layers and not more:
        raise c.refuse(f"no parameter moves the {word} layer's coverage")
    if not more:
        raise c.refuse(f"there is no {word} in this program to reduce")
    # more of something absent, or present with nothing to move it: the overlay on top
    plan = _add_overlay(c, word, stems)
    if plan is None:
        raise c.refuse(f"no {word} amount in this program and no library overlay for it")
    return _more_overlays(c, plan, word, conds)


def _more_overlays(c: Context, plan: Plan, word: str, conds: Sequence[str]) -> Plan:
    """``plan`` and the overlays of the request's other conditions ("some moss and grime in
    the joints": moss and dirt), each composed over the program the ones before made."""
    done = {word}
    names = {_overlay_name(word, c.ew.conditions.get(word, ()))}
    for other in conds:
        stems = c.ew.conditions[other]
        name = _overlay_name(other, stems)
        if other in done or name is None or name in names or other in c.ew["age"]:
            continue
        sub = replace(c, program=add_lines(c.program, plan.add))
        try:
            more = _add_overlay(sub, other, stems)
        except EditRefused:
            continue
        if more is None:
            continue
        done.add(other)
        names.add(name)
        plan = Plan(
            "overlay",
            f"{plan.note}; {more.note}",
            add=[*plan.add, *more.add],
            intended=tuple(dict.fromkeys(plan.intended + more.intended)),
            graded=plan.graded or more.graded,
            said=plan.said + more.said,
        )
    return plan


def _overlay_name(word: str, stems: Sequence[str]) -> str | None:
    ov = _overlay_for(word, stems)
    return None if ov is None else ov.name


def _direction(c: Context, word: str) -> bool | None:
    """More (True) or less (False) when a direction word stands just before the condition's
    word ("less verdigris", "add some moss", "heavier grime"), else None."""
    ws = c.words
    i = ws.index(word)
    near = ws[max(0, i - 3) : i]
    if "too" in near[-2:]:  # "it's too uniformly rusty": less of it
        return False
    if set(ws[:i]) & c.ew["adding"]:  # "add some brownish grease stains", "put moss in ..."
        return True
    for t in reversed(near):
        if _is_property(c, t):
            return None  # "more purple-brown patina": "more" of a colour
        if t in c.ew["less"]:
            return False
        if t in c.ew["more"] or t in c.vocabulary.amounts:
            return True
    return None


def _more(c: Context) -> bool:
    """More of a condition when no direction word stands before its word: a "more" word and
    none of "less", nor a wish that it show less ("too strong; make them more subtle")."""
    ws = set(c.words)
    if ws & (c.ew["show_less"] | c.ew["shows_less"]) or too_strong(c.words, c.ew):
        return False
    return bool(ws & c.ew["more"]) or not (ws & c.ew["less"])


def _added_word(c: Context, conds: Sequence[str]) -> tuple[str, Sequence[str]] | None:
    """The condition a request adds (its word and stems): the first condition word, else an
    overlay's trigger ("put a big wine stain on it")."""
    if conds:
        return conds[0], c.ew.conditions[conds[0]]
    return _trigger_word(c) or _coloured_marks(c)


def _coloured_marks(c: Context) -> tuple[str, Sequence[str]] | None:
    """Marks of a colour added where no condition is named ("add a few dry brown patches",
    "scatter some white spots"): the stain overlay in that colour, the marks' noun as its
    word (an adding verb makes them new things, not a part of the program)."""
    if not set(c.words) & c.ew["adding"]:
        return None
    marks = c.ew["spots"] | c.ew["marks"]
    for i, t in enumerate(c.words):
        near = c.words[max(0, i - 3) : i]
        if t in marks and not placed(c.words, i) and any(names_colour(c, w) for w in near):
            return t, c.ew.conditions["stains"]
    return None


def _sizes_part(c: Context, size_words: set[str] | frozenset[str]) -> bool:
    """Whether a size word sizes a part of the program ("add bigger tiles and some rust"), not
    the condition added ("a big dark wine stain") nor another thing ("a few small dents")."""
    ws = c.words
    return any(
        named_in_program(c.program, ws[j + 1 : j + 4], c.ew)
        for j, t in enumerate(ws)
        if t in size_words
    )


def _absent(c: Context, word: str, stems: Sequence[str] = ()) -> bool:
    """Whether the program has nothing of the condition ``word`` (no labelled amount, layer or
    part of its name): asked for, it is added."""
    stems = stems or c.ew.conditions.get(word, ())
    found = _labelled(c, stems) or _overlay_covers(c, stems) or _condition_layers(c, stems)
    return not (found or named_in_program(c.program, [word, *stems], c.ew))


def _conditions_colour(c: Context, said: Sequence[str], i: int) -> bool:
    """Whether the colour at ``i`` is another condition's own ("black mould", "yellow sulphur
    deposits"): a condition word follows within its noun phrase, past no part of the program
    ("drier mud" is the mud's property)."""
    w, t0 = c.vocabulary, said[i]
    if t0 in c.ew.relief or t0 in c.ew.comparative:  # "deeper cracks": the cracks' property
        return False
    if w.ish_base(t0) not in w.named and t0 not in w.tones:
        return False
    for t in said[i + 1 : i + 4]:
        if t in c.ew.conditions or _overlay_for(t, ()) is not None:
            return True
        if t in c.ew["filler"] or named_in_program(c.program, [t], c.ew):
            return False
    return False


def _property_word(c: Context, word: str) -> bool:
    """Whether the request names a property of something (a colour, a finish, a relief), other
    than the condition's word itself."""
    # another condition's word ("older, with some moss") is no colour, though "moss" names one;
    # the request's own words count, not those a look was read as ("worn and a bit wet":
    # "wet" is read as "darker overall, glossier")
    said = list(c.said) or tokens(c.request)  # as written: a look read as colours is none
    sub = replace(c, words=said)  # "more of the dark flecks": a part's look, no property
    return any(
        t != word
        and t not in c.ew.conditions
        and _is_property(c, t)
        and not describes_part(sub, i)
        and not _conditions_colour(c, said, i)
        for i, t in enumerate(said)
    )


def _is_property(c: Context, t: str) -> bool:
    w = c.vocabulary
    base = w.ish_base(t)
    return (
        base in w.named
        or t in c.ew.comparative
        or t in c.ew.towards
        or t in c.ew.finish
        or t in c.ew.relief
        or t in ("colour", "color", "hue", "tint")
    )


def _more_of_layer(c: Context) -> Plan | None:
    """ "more flecks", "fewer gum spots": the measured coverage of the layer a noun names."""
    ws = set(c.words)
    more = bool(ws & (c.ew["more"] | {"pack"}))
    less = bool(ws & (c.ew["less"] | c.ew["sparser"]))
    if more == less or _property_word(c, "") or any(c.ew.channel_of(t) for t in ws):
        return None  # "less shiny tiles", "more blue", "more sheen": another rule's
    if ws & (set(c.ew.relief_nouns) | set(c.ew.relief) | {"rough", "roughness", "gloss"}):
        return None
    skip = c.ew["more"] | c.ew["less"] | set(c.ew.relief_nouns) | set(c.ew.channels)
    # a simile names no part to measure ("less eroded, like the bricks were laid last week")
    simile = next((i for i, t in enumerate(c.words) if t in ("like", "as")), len(c.words))
    kept = set(c.words[:simile])
    nouns = [t for t in c.nouns if t not in skip and t not in c.ew.finish and t in kept]
    return measured_layer(c, nouns, more)
