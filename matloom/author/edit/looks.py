"""The look of an added condition (and whether one mark of it is asked for): the colour a request gives it ("orange rust", "reddish-brown
clay and dirt", "a water stain, that yellow-brown ring"), blended with the condition's own look,
and the words that said it (so no other rule reads them as a recolour of the material)."""

from __future__ import annotations

import re

from matloom.author.edit.clauses import RELATIVE
from matloom.author.edit.lexicon import tokens
from matloom.author.edit.plan import Context
from matloom.author.edit.targets import named_in_program
from matloom.lang.static import static_number
from matloom.library.overlay import Overlay


def condition_look(
    c: Context, word: str, ov: Overlay
) -> tuple[tuple[int, int, int] | None, tuple[str, ...]]:
    """The colour of the condition ``word``'s overlay ``ov`` and the words that said it: a
    colour the request names before it in its noun phrase ("orange rust", "pale grey lichen",
    "reddish-brown clay and dirt": a colour right before it or before another noun of the
    phrase, not past a part of the program nor before "and", "darker grey and a bit wet"),
    else the colour of a clause right after that describes it ("a water stain, that
    yellow-brown ring"); half way from the overlay's own, which a colour name's pure value
    would not resemble (a grey, black or white keeps most of its own: "black mould"); else its
    own look in ``[condition_colours]``."""
    ws = c.words
    first = word.split()[0]
    i = ws.index(first) if first in ws else -1
    own = c.ew.condition_colours.get(word)  # "green patina" on the rust overlay: the patina's
    for j in range(i - 1, max(-1, i - _LOOK_BACK - 1), -1):
        t = ws[j]
        rgb = _colour_of(c, t)
        if rgb is not None:
            if j < i - 1 and not _phrase_noun(c, ws[j + 1]):
                break  # "darker grey and a bit wet": the grey is another wish's
            before = _colour_of(c, ws[j - 1]) if j > 0 else None  # "reddish brown"
            if before is None:
                return _blend(rgb, ov, own), (t,)
            return _blend(_mean(before, rgb), ov, own), (ws[j - 1], t)
        noun = t not in c.vocabulary.tones and t not in c.ew["filler"]
        if noun and not _phrase_noun(c, t):
            break  # "the red tiles and moss": another thing's ("yellow sulphur deposits")
    after = _described_after(c, first)
    for k, t in enumerate(after):
        rgb = _colour_of(c, t)
        if rgb is not None:
            nxt = after[k + 1] if k + 1 < len(after) else ""
            more = _colour_of(c, nxt) if nxt else None  # "yellow-brown"
            if more is None:
                return _blend(rgb, ov, own), (t,)
            return _blend(_mean(rgb, more), ov, own), (t, nxt)
    return c.ew.condition_colours.get(word), ()


def _phrase_noun(c: Context, t: str) -> bool:
    """Whether ``t`` may stand inside a condition's noun phrase ("clay" in "reddish-brown clay
    and dirt"): a word that is no filler, tone, colour or part of the program."""
    return (
        len(t) > 2
        and t not in c.ew["filler"]
        and t not in c.vocabulary.tones
        and _colour_of(c, t) is None
        and not named_in_program(c.program, [t], c.ew)
    )


#: how far back a condition's colour may stand ("reddish brown clay and dirt": four words)
_LOOK_BACK = 4
#: the clause after a condition's that describes it ("a water stain, that yellow-brown ring")
_DESCRIBES = RELATIVE | {"like"}
#: how much of its own a named colour keeps in a condition's look (the rest is the
#: overlay's): a hue half, a grey, black or white most
_NAMED_SHARE, _GREY_SHARE = 0.5, 0.8


def names_colour(c: Context, t: str) -> bool:
    """Whether the word ``t`` names a colour ("brown", "reddish"), not a condition's own."""
    return _colour_of(c, t) is not None


def _colour_of(c: Context, t: str) -> tuple[int, int, int] | None:
    base = c.vocabulary.ish_base(t)
    if base in c.vocabulary.named and base not in c.ew.conditions:
        return c.vocabulary.named[base]
    return None


def _mean(a: tuple[int, int, int], b: tuple[int, int, int]) -> tuple[int, int, int]:
    return (round((a[0] + b[0]) / 2), round((a[1] + b[1]) / 2), round((a[2] + b[2]) / 2))


def _blend(
    rgb: tuple[int, int, int], ov: Overlay, look: tuple[int, int, int] | None = None
) -> tuple[int, int, int]:
    own = look or _own_colour(ov)
    if own is not None:
        k = _GREY_SHARE if max(rgb) - min(rgb) < 24 else _NAMED_SHARE
        rgb = tuple(a * k + b * (1 - k) for a, b in zip(rgb, own, strict=True))  # type: ignore[assignment]
    return (round(rgb[0]), round(rgb[1]), round(rgb[2]))


def _described_after(c: Context, first: str) -> list[str]:
    """The words of the clause right after the one naming the condition ``first``, when that
    clause describes it (it opens with "that", "those", "which", "like", "the kind")."""
    parts = [tokens(s) for s in re.split(r"[,;:]|\s[-–—]\s", c.request.lower())]
    for k, words in enumerate(parts[:-1]):
        after = [w for w in parts[k + 1] if w not in c.ew["articles"] or w == "that"]
        if first in words and after and after[0] in _DESCRIBES:
            return after
    return []


def _own_colour(ov: Overlay) -> tuple[float, float, float] | None:
    """The overlay's own colour (its first colour slot that is not the host's)."""
    slot = ov.accent_slot
    if slot is None:
        return None
    defines = [ov.ast.define(f"{slot}_{ch}") for ch in "rgb"]
    values = [None if d is None else static_number(d.expr) for d in defines]
    return None if None in values else tuple(float(v) for v in values)  # type: ignore[return-value]


def one_mark(c: Context, word: str) -> bool:
    """Whether the request asks for one mark ("a coffee stain", "one big water stain"): a
    singular article before the condition's mark noun, and no plural mark noun."""
    ws = c.words
    marks = [k for k, t in enumerate(ws) if t in c.ew["spots"] or t == word]
    plural = [ws[k] for k in marks if ws[k].endswith("s") and not ws[k].endswith(("ss", "us"))]
    if not marks or plural:  # "a few stains": several ("a moss stain" is one)
        return False
    k = marks[0]
    return any(t in c.ew["single"] for t in ws[max(0, k - 4) : k])
