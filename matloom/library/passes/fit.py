"""The fit pass: how a request reads against the chosen entry, as annotations beside the
(unchanged) request.

* overlays the entry already shows are **absorbed** (their amount raises its wear slot; a size
  word on them, "fine cracks" on cracked earth, sizes the entry's own features); the others are
  **applied** (at most ``MAX_OVERLAYS``);
* the colour before an overlay word that no applied overlay takes ("orange painted" metal,
  where the entry shows the paint) goes to the entry's slot named after the overlay;
* a metal colour name ("silver fabric") the entry neither shows nor takes as a preset is the
  entry's colour;
* colours that describe a noun the entry does not show ("a yellow-and-black hazard stripe" on
  diamond plate) are dropped, so they do not recolour the main material.

:meth:`Fit.reading` gives the request as the adapter reads it: its colours, scale and used
words replaced by the fit's.
"""

from __future__ import annotations

import functools
from collections.abc import Mapping
from dataclasses import dataclass, replace
from types import MappingProxyType

from matloom.library.data import Words
from matloom.library.entry import Entry, PresetValue
from matloom.library.index import Library
from matloom.library.parts_words import parts_words, vocabulary
from matloom.library.passes.cover import patterned
from matloom.library.query import ColourMention, OverlayMention, Request, plural_stem

MAX_OVERLAYS = 3


@dataclass(frozen=True)
class Fit:
    """The request fitted to one entry (see the module docstring)."""

    #: (overlay name, amount) of the overlays the entry already shows
    absorbed: tuple[tuple[str, float], ...]
    #: the overlays to compose onto the entry, in request order
    applied: tuple[OverlayMention, ...]
    #: the names of the overlays past ``MAX_OVERLAYS``
    dropped: tuple[str, ...]
    colours: tuple[ColourMention, ...]
    scale: float
    scale_words: tuple[str, ...]
    #: the request's used tokens, with the metal colour names the entry takes
    used: Mapping[int, str]
    #: the dropped colours, described ("yellow (the colour of 'stripe')"): reported as ignored
    foreign: tuple[str, ...]

    @property
    def notes(self) -> tuple[str, ...]:
        if not self.dropped:
            return ()
        return (f"dropped overlays (at most {MAX_OVERLAYS}): " + ", ".join(self.dropped),)

    def reading(self, req: Request) -> Request:
        """``req`` as the adapter reads it for this entry."""
        return replace(
            req,
            colours=self.colours,
            scale=self.scale,
            scale_words=self.scale_words,
            used=self.used,
        )


def fit(
    req: Request,
    entry: Entry,
    lib: Library,
    words: Words,
    presets: dict[str, dict[str, PresetValue]],
    *,
    matched: bool,
) -> Fit:
    """Fit ``req`` to ``entry``; ``matched`` is False for the fallback entry (whose words the
    request does not share: no colour is foreign to it)."""
    idx = lib.index
    terms = idx.terms.get(entry.name, frozenset())
    absorbed: list[tuple[str, float]] = []
    apply: list[OverlayMention] = []
    scale, scale_words = req.scale, list(req.scale_words)
    for m in req.overlays:
        if m.name in entry.absorbs or idx.stem(m.word.split()[0]) in terms:
            absorbed.append((m.name, m.amount))
            if m.scale != 1.0:  # "fine cracks" on cracked earth: the entry's own features
                scale *= m.scale
                scale_words.append(f"{m.word} x{m.scale:g}")
        elif m.name in lib.overlays:
            apply.append(m)
    applied = {m.name for m in apply[:MAX_OVERLAYS]}
    by_index = {c.index: c for c in req.colours}
    for m in req.overlays:
        takes = m.name in applied and any(
            c != lib.overlays[m.name].host for c in lib.overlays[m.name].colours
        )
        if m.colour_at in by_index and not takes:  # (a motif's colour is taken out before)
            by_index[m.colour_at] = _entry_colour(by_index[m.colour_at], m, entry)
    colours = [by_index[c.index] for c in req.colours]
    used = dict(req.used)
    for i, word in req.words_at():  # metal colour names: the entry's colour
        if i in used or word not in words.metal_colours or word in presets:
            continue
        rgb = words.colour(word)
        if rgb is None or idx.stem(word) in terms:
            continue
        colours.append(ColourMention(rgb, word, i))
        used[i] = "colour"
    colours.sort(key=lambda m: m.index)
    foreign: list[str] = []
    if matched:
        colours, foreign = _foreign_colours(req, colours, used, terms, entry, lib, words)
    return Fit(
        absorbed=tuple(absorbed),
        applied=tuple(apply[:MAX_OVERLAYS]),
        dropped=tuple(m.name for m in apply[MAX_OVERLAYS:]),
        colours=tuple(colours),
        scale=scale,
        scale_words=tuple(scale_words),
        used=MappingProxyType(used),
        foreign=tuple(foreign),
    )


def _entry_colour(cm: ColourMention, m: OverlayMention, entry: Entry) -> ColourMention:
    """The colour before an overlay word that no added overlay takes ("orange painted" metal,
    where the entry shows the paint itself) goes to the entry's slot named after the overlay
    (``paint_col`` for "painted", ``rust_col`` for "rusty"), else to the entry's colours like
    any other colour of the request (a colour no slot takes is reported as ignored)."""
    names = (m.name, *m.word.split())
    cm = replace(cm, role=None)
    for slot in entry.colours:
        parts = [p for p in slot.split("_") if len(p) >= 4]
        if any(w.startswith(p) or p.startswith(w) for p in parts for w in names):
            return replace(cm, slot=slot)
    for slot in entry.colours:  # the colour word names the slot itself ("oil" stains)
        if cm.words in slot.split("_"):
            return replace(cm, slot=slot)
    return cm


@functools.cache
def _pattern_nouns() -> frozenset[str]:
    pw = parts_words()
    return pw.figures | pw.motif_adjectives | frozenset(vocabulary("motifs"))


def _pattern_noun(noun: str) -> bool:
    """Does ``noun`` name a motif or a figure ("floral", "flowers", "motifs", "pattern")?"""
    return bool({noun, plural_stem(noun)} & _pattern_nouns())


def _slot_named(noun: str, entry: Entry) -> str | None:
    """The entry's colour slot ``noun`` names ("bole" for ``bole``, "grout" for
    ``grout_col``): a slot name part of four letters or more that the noun or its singular is."""
    said = {noun, plural_stem(noun)}
    for slot in entry.colours:
        if any(len(p) >= 4 and p in said for p in slot.split("_")):
            return slot
    return None


#: how many unknown modifiers may stand between a colour and the material it colours
#: ("forest green polar fleece", "lilac mohair knit")
MODIFIERS = 2


def _modifies_material(
    tokens: tuple[str, ...] | list[str],
    j: int,
    known: frozenset[str],
    terms: frozenset[str],
    lib: Library,
    w: Words,
) -> bool:
    """Does the unknown word at ``j`` only modify a material noun right after it (at most
    :data:`MODIFIERS` words, none a stop word or punctuation: "polar fleece", "mohair knit"),
    so a colour before it is that material's ("red leaves on stone" is not)?"""
    for k in range(j + 1, min(j + 1 + MODIFIERS, len(tokens))):
        t = tokens[k]
        if not t.isalpha() or t in w.stop_words:
            return False
        if t in known or lib.index.stem(t) in terms:
            return True
    return False


def _foreign_colours(
    req: Request,
    colours: list[ColourMention],
    used: dict[int, str],
    terms: frozenset[str],
    entry: Entry,
    lib: Library,
    w: Words,
) -> tuple[list[ColourMention], list[str]]:
    """(kept colours, dropped colours' descriptions): a colour is dropped when it describes a
    noun the entry does not show ("a yellow-and-black hazard stripe" on diamond plate, "dark
    oil stains" on a sidewalk). A colour keeps its place when its noun is a material, a
    category word, a role noun or one of the entry's own words."""
    known = w.materials | frozenset().union(*w.category_words.values()) | w.no_thing
    tokens = req.tokens
    keep, dropped = [], []

    def colourish(k: int) -> bool:
        t = tokens[k]
        return w.colour(t) is not None or t in w.tones or used.get(k) == "colour"

    for m in colours:
        j = m.index + len(m.words.split())
        while j < len(tokens) and (
            (tokens[j] in w.colour_join and j + 1 < len(tokens) and colourish(j + 1))
            or used.get(j) in {"colour", "finish", "tone"}
            or colourish(j)
        ):
            j += 1
        noun = tokens[j] if j < len(tokens) else ""
        slot = _slot_named(noun, entry) if m.slot is None and noun.isalpha() else None
        if slot is not None:  # "red bole underneath" on gilding: the entry's bole
            keep.append(replace(m, slot=slot))
            continue
        if _pattern_noun(noun) and patterned(entry):  # "blue floral motifs" on azulejo
            keep.append(m)
            continue
        roleless = m.role is None or (
            m.role not in {"grout", "overlay"}
            and not any(entry.role(s) == m.role for s in entry.colours)
        )

        foreign = (  # a noun the entry does not show, that no rule took and no table knows
            roleless
            and m.slot is None
            and noun.isalpha()
            and j not in used
            and noun not in w.stop_words
            and noun not in known
            and noun not in w.roles
            and not noun.endswith(("ed", "ing", "ly"))
            and lib.index.stem(noun) not in terms
        )
        metal = m.words in w.metal_colours  # "copper carbonate mineral": the metal itself
        if foreign and not metal and _modifies_material(tokens, j, known, terms, lib, w):
            foreign = False  # "forest green polar fleece", "lilac mohair knit": the material's
        if foreign:
            dropped.append(f"{m.words} (the colour of '{noun}')")
        else:
            keep.append(m)
    return keep, dropped
