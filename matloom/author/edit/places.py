"""Where an added condition goes: a mask its layers are confined to.

Three kinds of place, multiplied when a request names several:

* **the joints** ("dirt in the grout lines"): the mask that holds the program's joint width, or
  the joint-coloured base between the layers above it (:func:`joint_mask`);
* **the relief's low or high parts** ("rust in the crevices", "sand into the grooves",
  "iron staining between the crystals"; "worn on the raised parts", "snow on the tops"): the
  host's composite height below a third of its span, or above two thirds of it. Joints a
  program does not draw are its low parts when its relief has a distinct low part;
* **a place on the surface as a whole**: the middle (a patch, or a band "through" or "across"
  it) and the edges are periodic masks (cosines with one cycle per View), so a tileable
  program stays tileable; the top, bottom, a corner or one side cannot repeat and are only
  made on a program that does not tile (refused on one that does, with the reason).
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass

from matloom.author.edit.apply import add_lines
from matloom.author.edit.lexicon import split_words, stem
from matloom.author.edit.measured import mask_coverage
from matloom.author.edit.plan import Context
from matloom.author.edit.targets import layer_words, param_layers
from matloom.lang import ast as A
from matloom.lang.api import parse_expression
from matloom.lang.printer import format_expr
from matloom.library.overlay import fresh_name
from matloom.library.relief import height_span


@dataclass(frozen=True)
class Place:
    """A mask (None: everywhere), the Define lines it reads (added before the condition's own
    lines) and the words that say where, for the plan's note."""

    mask: A.Node | None = None
    lines: tuple[str, ...] = ()
    where: str = ""
    #: on the relief's high or low parts: the condition does not also settle by the relief
    on_relief: bool = False


#: A place on the surface as a whole that no repeat can have ("near the bottom", "lower down",
#: "rising damp"; "on top of each log" is each feature's own top).
_GRADIENT_RE = re.compile(
    r"\b(?:(?:near|at|towards?|along|round|around)\s+the\s+(?:bottom|top|base)\b"
    r"(?!\s+of\s+(?:each|every|all|the\s+\w+s\b))"
    r"|(?:lower|upper)\s+(?:down|up|part|half|courses|rows|section|edge|area)"
    r"|(?:bottom|top)\s+of\s+the\s+(?:wall|surface|panel|texture|image|roof|floor|frame|sheet)"
    r"|rising\s+damp|higher\s+up|lower\s+down)\b"
)
_CORNER_RE = re.compile(
    r"\b(?:from|in|at|into|near|towards?|round|around)\s+(?:one|a|the)\s+corner\b"
)
_SIDE_RE = re.compile(
    r"\b(?:on|along|from|down|at)\s+one\s+(?:side|edge)\b|\b(?:left|right)(?:\s+hand)?\s+side\b"
)
_MIDDLE = r"(?:middle|centre|center)"
_BAND_DOWN_RE = re.compile(rf"\b(?:through|down|along|up)\s+the\s+{_MIDDLE}\b")
_BAND_ACROSS_RE = re.compile(rf"\bacross\s+the\s+{_MIDDLE}\b")
_PATCH_RE = re.compile(
    rf"\b(?:in|near|at|around|round|towards?|to|on|over)\s+the\s+{_MIDDLE}\b"
    rf"|\b{_MIDDLE}\s+of\s+the\b|\bcent(?:red|ered)\b"
)
_EDGES_RE = re.compile(
    r"\b(?:at|toward|towards|around|round|along|near|on|by|to)\s+the\s+"
    r"(?:edges|borders|margins|perimeter|outside|rim)\b(?!\s+of\s+(?:each|every|all|the\s+\w+s\b))"
)
#: Nouns after "high"/"highest" that make a high part ("the high spots").
_PARTS = frozenset({"points", "spots", "parts", "areas", "bits", "places", "ground", "sections"})
#: Tokens between a condition word and the place words that may name its place.
_WINDOW = 10
#: A low (high) part is the height below (above) this share of its span, fully at the second.
_LOW = (0.34, 0.16)
_HIGH = (0.62, 0.82)
#: Shares of the surface a low / high part may cover and still be one (beyond: there is none,
#: "the gaps" of a surface that is mostly low).
_LOW_SHARE = (0.02, 0.5)
_HIGH_SHARE = (0.02, 0.9)
#: Shares of the surface a part's layer may cover to be a part a condition is put on (beyond:
#: the material itself, "moss on the bricks").
_PART_SHARE = (0.03, 0.8)


#: Words that exclude the place after them ("moss, but not in the cracks", "avoiding the
#: ridges"): no mask is made for it.
_NOT_RE = re.compile(r"\b(?:not|except|avoid|avoiding|without|apart\s+from|away\s+from|never)\b")


def _excluded(before: str) -> bool:
    """Whether the words just before a place exclude it (its last four words)."""
    return bool(_NOT_RE.search(" ".join(before.split()[-4:])))


def _inside(c: Context) -> frozenset[str]:
    """Words before a noun that put a condition in it ("moss in the gaps", "crust around the
    cracks"): the place words but "from" (where something comes from)."""
    return c.ew["place"] - {"from"}


def _said(c: Context) -> str:
    return " ".join(c.said or tuple(c.words))


def _cos(coord: str, start: float, span: float) -> str:
    """0 at the View's borders, 1 in its middle, one cosine cycle per View: periodic."""
    k = 2 * math.pi / span
    return f"(0.5 - (0.5 * Cos((({coord}() - {start:.6g}) * {k:.6g}))))"


def _smooth(e0: float, e1: float, x: str) -> A.Node:
    return parse_expression(f"Smoothstep({e0:g}, {e1:g}, {x})")


def _surface_mask(c: Context, word: str) -> tuple[A.Node, str] | None:
    """The mask of the place on the surface as a whole the request names (None: none);
    refused when it cannot repeat and the program tiles."""
    text = _said(c)
    x1, y1, x2, y2 = c.program.view_tuple
    w, h = x2 - x1, y2 - y1
    lo, hi = min(y1, y2), max(y1, y2)
    cx, cy = _cos("X", x1, w), _cos("Y", y1, h)
    corner = _found(_CORNER_RE, text)
    if corner is not None and c.program.tileable:
        # the corners of a repeat meet where four repeats do: one patch there, which the
        # single repeat shows in its four corners
        return _smooth(0.3, 0.7, f"((1 - {cx}) * (1 - {cy}))"), (
            f"{corner.group(0)} (the program tiles: where the corners of four repeats meet)"
        )
    fixed = [_found(_GRADIENT_RE, text), corner, _found(_SIDE_RE, text)]
    m = next((f for f in fixed if f), None)
    if m is not None:
        if c.program.tileable:
            raise c.refuse(
                f"the {word} is asked for {m.group(0)!r}, a place on the surface as a whole, "
                "which a tileable program cannot have (every part of it repeats); make the "
                "program non-tileable first"
            )
        if fixed[0]:
            return _gradient(m.group(0), lo, hi), m.group(0)
        if fixed[1]:  # the top-left corner
            d = f"Sqrt(Pow(((X() - {x1:.6g}) / {w:.6g}), 2) + Pow(((Y() - {hi:.6g}) / {h:.6g}), 2))"
            return _smooth(0.6, 0.15, d), m.group(0)
        side = "right" if "right" in m.group(0) else "left"
        start = x2 if side == "right" else x1
        return _smooth(0.45, 0.1, f"Abs(((X() - {start:.6g}) / {w:.6g}))"), m.group(0)
    for rx, mask in (
        (_BAND_DOWN_RE, _smooth(0.5, 0.88, cx)),
        (_BAND_ACROSS_RE, _smooth(0.5, 0.88, cy)),
        (_PATCH_RE, _smooth(0.25, 0.7, f"({cx} * {cy})")),
        (_EDGES_RE, _smooth(0.4, 0.08, f"({cx} * {cy})")),
    ):
        found = _found(rx, text)
        if found:
            return mask, found.group(0)
    return None


def _found(rx: re.Pattern[str], text: str) -> re.Match[str] | None:
    """The first match of ``rx`` in ``text`` that is a place on the surface: not on features
    ("the corner of each tile") and not excluded ("but not in the middle")."""
    return next(
        (
            m
            for m in rx.finditer(text)
            if not _of_features(text[m.end() :]) and not _excluded(text[: m.start()])
        ),
        None,
    )


def _of_features(rest: str) -> bool:
    """Whether the words after a place name features, not the surface ("the middle of each
    tile", "the edges of the cooled rock plates"; not "the middle of the rug")."""
    m = re.match(r"\s+of\s+([\w\s]+)", rest)
    if m is None:
        return False
    words: list[str] = []
    for t in m.group(1).split()[:5]:
        if t in _STOP:
            break
        words.append(t)
    if not words:
        return False
    plural = words[-1].endswith("s") and not words[-1].endswith("ss")
    return plural or bool({"each", "every", "all", "these", "those"} & set(words))


#: Words that end the noun phrase after "of".
_STOP = frozenset(
    {
        "like",
        "where",
        "and",
        "with",
        "so",
        "as",
        "to",
        "from",
        "that",
        "which",
        "because",
        "in",
        "on",
        "but",
        "or",
        "while",
        "when",
        "after",
        "for",
    }
)


def _gradient(place: str, lo: float, hi: float) -> A.Node:
    """A mask rising to 1 over the lower (or upper) half of the View: the place ``place``
    names."""
    h = hi - lo
    up = any(w in place for w in ("top", "upper", "higher"))
    edges = (lo + 0.45 * h, lo + 0.9 * h) if up else (lo + 0.55 * h, lo + 0.1 * h)
    return _smooth(round(edges[0], 6), round(edges[1], 6), "Y()")


def joint_mask(c: Context) -> tuple[A.Node | None, str]:
    """The joints ("dirt in the grout lines"): where the mask Define that holds the program's
    joint width (``define:tiles.Bricks.mortar``) is low, or high when the joints are its
    majority value's opposite; (None, "") when the program has no joint parameter."""
    for p in c.params:
        if p.kind != "size" or not any(k in p.address.lower() for k in c.ew.joint_params):
            continue
        m = re.fullmatch(r"define:(\w+)\.\w+\.\w+", p.address)
        if m is None or c.program.define(m.group(1)) is None:
            continue
        name = m.group(1)
        mask: A.Node = A.Ref(name)
        # the joints are the thin part: the mask's minority value
        if mask_coverage(c.program, mask) > 0.5:
            mask = A.BinOp("-", A.Num(1), mask)
        return mask, f" in the joints (of {name})"
    # no joint width: the joints are what a joint-coloured base shows between the layers above
    # ("Define(grout_r, ...)" paints the first layer; the tiles' layer covers the rest)
    for p in c.params:
        if p.kind != "colour" or not split_words(p.address.removeprefix("define:")) & c.ew["joint"]:
            continue
        if 0 in param_layers(p, c.program) and len(c.program.layers) > 1:
            cover = c.program.layers[1].alpha
            if cover is not None and mask_coverage(c.program, cover) > 0.5:
                return A.BinOp(
                    "-", A.Num(1), cover
                ), " in the joints (where the layer above leaves them)"
    return None, ""


def in_joints(c: Context) -> bool:
    """Whether the request puts something in joints ("moss in the gaps")."""
    ws, inside = c.words, _inside(c)
    return any(
        t in c.ew["joint"] and any(w in inside for w in ws[max(0, i - 3) : i])
        for i, t in enumerate(ws)
    )


def _relief_words(c: Context, word: str) -> tuple[str, str] | None:
    """("low"|"high", the place's words) for the relief place nearest the condition ``word``
    within :data:`_WINDOW` tokens, if any."""
    ws = c.words
    first = word.split()[0]
    at = ws.index(first) if first in ws else 0
    found: list[tuple[int, str, str]] = []
    low = c.ew["low_places"] | c.ew["joint"]
    inside, articles = _inside(c), c.ew["articles"]
    for i, t in enumerate(ws):
        before = ws[max(0, i - 3) : i]
        if _excluded(" ".join(ws[max(0, i - 5) : i])):  # "moss, but not in the cracks"
            continue
        prep = next((w for w in reversed(before) if w in inside), None)
        if t in low and prep is not None:
            found.append((i, "low", f"{prep} the {t}"))
        elif i > 1 and ws[i - 2] == "between" and ws[i - 1] in articles and t.endswith("s"):
            found.append((i, "low", f"between the {t}"))
        elif t in c.ew["high_places"]:
            found.append((i, "high", f"on the {t}"))
        elif t == "raised" and i + 1 < len(ws) and ws[i + 1] not in c.ew["filler"]:
            found.append((i, "high", f"raised {ws[i + 1]}"))
        elif t in ("high", "highest") and i + 1 < len(ws) and ws[i + 1] in _PARTS:
            found.append((i, "high", f"{t} {ws[i + 1]}"))
        elif t == "top" and ws[i + 1 : i + 3] in (["of", "each"], ["of", "every"]):
            found.append((i, "high", " ".join(ws[i : i + 4])))
    near = [(abs(i - at), kind, text) for i, kind, text in found if abs(i - at) <= _WINDOW]
    if not near:
        return None
    _, kind, text = min(near)
    return kind, text


def _relief_mask(c: Context, kind: str) -> tuple[A.Node, tuple[str, ...]] | None:
    """The mask of the host's low (high) part and the Define it reads, None when its relief
    has no such part (flat, too shallow, or mostly low: no gaps to fill)."""
    span = height_span(c.program)
    if span is None:
        return None
    height, lo, hi = span
    name = fresh_name("where_height", {d.name for d in c.program.defines})
    e0, e1 = _LOW if kind == "low" else _HIGH
    mask = _smooth(round(lo + e0 * (hi - lo), 6), round(lo + e1 * (hi - lo), 6), name)
    lines = (f"Define({name}, {format_expr(height)})",)
    share = mask_coverage(add_lines(c.program, lines), mask)
    least, most = _LOW_SHARE if kind == "low" else _HIGH_SHARE
    if not least <= share <= most:
        return None
    return mask, lines


def _part_mask(c: Context, word: str) -> tuple[A.Node, str] | None:
    """The part a condition is put on ("rust on the wires", "wear the yellow stripes down",
    "dust on the leaves"): the coverage of the layer (not the first) a noun near the
    condition names, when it covers part of the surface (:data:`_PART_SHARE`)."""
    ws = c.words
    first = word.split()[0]
    at = ws.index(first) if first in ws else 0
    skip = c.ew["filler"] | c.ew["joint"] | c.ew["low_places"] | c.ew["high_places"]
    nouns = [
        (abs(i - at), i, t)
        for i, t in enumerate(ws)
        if 0 < abs(i - at) <= _WINDOW
        and len(t) > 2
        and t not in skip
        and t not in c.ew.conditions
        and i > 0
        and ws[i - 1] in c.ew["articles"] | {"on", "to", "onto", "of"}
    ]
    for _, _, t in sorted(nouns):
        for index in range(1, len(c.program.layers)):
            alpha = c.program.layers[index].alpha
            if alpha is None or stem(t) not in {
                stem(w) for w in layer_words(c.program, index, c.ew)
            }:
                continue
            least, most = _PART_SHARE
            if least <= mask_coverage(c.program, alpha) <= most:
                return alpha, f" on the {t}"
    return None


def _times(a: A.Node | None, b: A.Node) -> A.Node:
    return b if a is None else A.BinOp("*", a, b)


def place_of(c: Context, word: str) -> Place:
    """Where the request puts the condition ``word`` (everywhere: ``Place()``), refused when
    it names joints the program does not have or a place a tileable program cannot have."""
    mask, where = joint_mask(c) if set(c.words) & c.ew["joint"] else (None, "")
    lines: tuple[str, ...] = ()
    relief = _relief_words(c, word) if mask is None else None
    found = _relief_mask(c, relief[0]) if relief is not None else None
    if relief is not None and found is not None:
        mask, lines = found
        where = f" on the {relief[0]} parts of the relief ({relief[1]})"
    elif mask is None and in_joints(c):  # "moss in the gaps": never spilled over the stones
        raise c.refuse(
            f"no joints found in this program to put the {word} in, and no low parts (joints, "
            "grooves, crevices) in its relief"
        )
    # ("moss in the cracks" of a relief with no distinct low part: the overlay settles by the
    # relief as it does on its own, as "moss" alone would)
    part = _part_mask(c, word) if mask is None else None
    if part is not None:
        mask = _times(mask, part[0])
        where += part[1]
    surface = _surface_mask(c, word)
    if surface is not None:
        mask = _times(mask, surface[0])
        where += f" {surface[1]}"
    return Place(mask, lines, where, on_relief=bool(lines))
