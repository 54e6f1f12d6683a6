"""Which colour parameters a colour names: the part that is that colour now ("swap the yellow
for orange", "just the red panes") and every colour of its family ("switch the teal for a deep
burgundy", "the blues and greens"); colours given as values ("#D8E0CF", "RGB 150, 60, 40")."""

from __future__ import annotations

import math
from collections.abc import Sequence

from matloom.author.edit.lab import to_lab
from matloom.author.edit.plan import Context
from matloom.author.edit.targets import matching
from matloom.lang.params import Param
from matloom.library.colour import RGB


def colour_value(p: Param) -> tuple[float, float, float]:
    """A colour parameter's value as three floats."""
    return tuple(float(x) for x in p.value)  # type: ignore[return-value,union-attr]


def hue_distance(a: Sequence[float], b: Sequence[float]) -> float:
    """CIELAB distance with lightness at half weight: a colour word names a hue family more
    than a lightness ("the orange bricks" are a dark orange)."""
    la, lb = to_lab(a), to_lab(b)
    return math.sqrt((0.5 * (la[0] - lb[0])) ** 2 + (la[1] - lb[1]) ** 2 + (la[2] - lb[2]) ** 2)


def by_colour(c: Context, rgb: RGB, colours: list[Param], nouns: list[str]) -> list[Param]:
    """The colour parameters of the part a colour names ("the red panes"): the nearest to it
    (hue first) and every other as near (within ``part_de`` more), when the nearest is within
    ``part_max_de``; among those the nouns name, when they name any of them."""
    near = sorted((hue_distance(colour_value(p), rgb), i, p) for i, p in enumerate(colours))
    if not near or near[0][0] > c.ew.f("part_max_de"):
        return []
    part = [p for d, _, p in near if d <= near[0][0] + c.ew.f("part_de")]
    named = [p for p in part if p in matching(colours, nouns, c.program, c.ew)] if nouns else []
    if named:
        return named
    # "switch the teal for burgundy": the teal ground and the paler teal motif alike
    return part + [p for _, _, p in near if p not in part and same_family(c, colour_value(p), rgb)]


def same_family(c: Context, rgb: Sequence[float], named: Sequence[float]) -> bool:
    """Whether ``rgb`` is of the colour family ``named`` stands for (its hue and a share of
    its chroma, or for a grey one a grey of about its lightness; ``family_*`` of
    ``words.toml``)."""
    (l1, a1, b1), (l2, a2, b2) = to_lab(rgb), to_lab(named)
    c1, c2 = math.hypot(a1, b1), math.hypot(a2, b2)
    if c2 < c.ew.f("family_grey_chroma"):
        return c1 < c.ew.f("family_grey_chroma") and abs(l1 - l2) <= c.ew.f("family_grey_dl")
    if c1 < c.ew.f("family_chroma") * c2:
        return False
    return _hue_turn(a1, b1, a2, b2) <= c.ew.f("family_hue_deg")


def _hue_turn(a1: float, b1: float, a2: float, b2: float) -> float:
    """The angle between two CIELAB hues, 0 to 180 degrees."""
    turn = abs(math.degrees(math.atan2(b1, a1) - math.atan2(b2, a2))) % 360
    return min(turn, 360 - turn)


def hue_family(c: Context, rgb: Sequence[float], colours: Sequence[Param]) -> list[Param]:
    """The coloured (not grey) parameters whose hue is within ``family_hue_deg`` of ``rgb``'s,
    nearest hue first: "make the blue darker" where the blue is a pale periwinkle, too far from
    the named blue in CIELAB to be selected as close to it."""
    _, a2, b2 = to_lab(rgb)
    if math.hypot(a2, b2) < c.ew.f("family_grey_chroma"):
        return []
    found = []
    for i, p in enumerate(colours):
        _, a1, b1 = to_lab(colour_value(p))
        if math.hypot(a1, b1) < c.ew.f("family_grey_chroma"):
            continue
        turn = _hue_turn(a1, b1, a2, b2)
        if turn <= c.ew.f("family_hue_deg"):
            found.append((turn, i, p))
    return [p for _, _, p in sorted(found)]


def the_colour(c: Context) -> bool:
    """Whether the request names a colour as a part ("the blue", "those reds"), not as the
    colour to paint ("a darker blue")."""
    ws = c.words
    return any(
        a in ("the", "those", "these", "its") and c.vocabulary.ish_base(b) in c.vocabulary.named
        for a, b in zip(ws, ws[1:], strict=False)
    )


def explicit_colours(c: Context) -> list[tuple[int, int, RGB, bool]]:
    """Colours given as values: ``#d8e0cf`` (a hex word the request writes after ``#``) and
    ``RGB 150, 60, 40`` / ``rgb(150, 60, 40)`` (three numbers 0-255 after "rgb")."""
    ws = c.words
    raw = c.request.lower()
    out: list[tuple[int, int, RGB, bool]] = []
    for i, t in enumerate(ws):
        if len(t) == 6 and all(ch in "0123456789abcdef" for ch in t) and f"#{t}" in raw:
            out.append((i, 1, (int(t[0:2], 16), int(t[2:4], 16), int(t[4:6], 16)), False))
        elif t == "rgb" and i + 3 < len(ws) and all(x.isdigit() for x in ws[i + 1 : i + 4]):
            r, g, b = (int(x) for x in ws[i + 1 : i + 4])
            if max(r, g, b) <= 255:
                out.append((i, 4, (r, g, b), False))
    return out
