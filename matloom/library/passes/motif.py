"""The motif pass: a requested motif drawn onto a retrieved entry that shows the request's
material but not the motif ("navy satin with small white stars", "linen printed with hearts").

The motif is one of the composer's silhouettes (:data:`~matloom.library.compose.motifs.MOTIFS`),
repeated by ``Tile`` in a half-drop grid (or scattered at random angles when the request says so)
with a whole number of cells across the entry's View, so a tileable entry stays tileable. It is
written as an overlay in the entry's own units (:func:`~matloom.library.overlay.compose` renames
any Define that clashes) and goes on top of the entry's layers: a print, coloured from the
request ("white stars") or, when the request gives it no colour, a light or dark contrast to the
entry's main colour. The motif layer takes the finish of the entry's first layer (roughness,
metalness, sheen, ...), so only the colour changes under it; its colour is the ``motif`` slot,
which ``matloom params`` lists and ``matloom set`` changes.
"""

from __future__ import annotations

import hashlib
from dataclasses import dataclass, replace
from pathlib import Path

from matloom.lang import ast as A
from matloom.library import colour as C
from matloom.library.adapt import slot_colour
from matloom.library.compose.motifs import MOTIFS
from matloom.library.compose.writer import num
from matloom.library.overlay import Overlay, compose, prune_defines, view_width
from matloom.library.parts import Parts
from matloom.library.parts_words import parts_words
from matloom.library.query import Request

#: motifs across the View at the request's scale 1 ("small" stars: more)
ACROSS = 6
#: fewest and most motifs across the View
ACROSS_RANGE = (3, 16)
#: a motif's diameter as a share of its cell
SIZE = 0.62
#: a relief motif's rise as a share of its cell ("embossed stars")
RISE = 0.02
#: how far (tokens) before the motif's words a colour may stand and still be its colour
#: ("small white anchors", "tiny bright red hearts")
_BEFORE = 4
#: channels the motif layer does not copy from the entry's first layer: it sets its own colour
#: and leaves the relief and glow below it as they are
_OWN = frozenset({"basecolor", "height", "emissive", "normal"})
#: the motif colour when the request gives none: light on a dark entry, dark on a light one
_LIGHT, _DARK = (236, 232, 222), (34, 32, 36)


@dataclass(frozen=True)
class Drawn:
    """The program with the motifs on top, the motifs drawn (keys) and notes."""

    program: A.Program
    motifs: tuple[str, ...]
    notes: tuple[str, ...]
    #: token indices of the request the motifs used (their words and colours)
    used: frozenset[int]


def _seed(entry: str, seed: int, key: str) -> int:
    digest = hashlib.sha256(f"{entry}\x1f{seed}\x1fmotif\x1f{key}".encode()).digest()
    return int.from_bytes(digest[:4], "big") & 0x7FFFFFFF


def motif_colour(parts: Parts, index: int) -> tuple[C.RGB, str, range] | None:
    """The colour the parts reader gave the motif role and said just before the motif's words
    at token ``index`` ("white stars", "small gold stars"), with its words and token range; None
    when there is none (the colour of the material before it, "grey concrete with triangles",
    has the base role)."""
    tokens = parts.request.tokens
    for c in parts.colours:
        if c.role != "motif":
            continue
        said = c.words.split()
        for start in range(max(0, index - _BEFORE - len(said) + 1), index):
            end = start + len(said)
            if end <= index and list(tokens[start:end]) == said:
                return c.rgb, c.words, range(start, end)
    return None


def without_motif_colours(req: Request, keys: tuple[str, ...], parts: Parts) -> Request:
    """``req`` without the colours of the motifs to be drawn ("red hearts" on linen: the red
    is the hearts', not the linen's), their words marked used (so no pass takes "gold stars"'
    gold for the entry or reports it foreign)."""
    taken: set[int] = set()
    for p in parts.motifs:
        found = motif_colour(parts, p.index) if p.key in keys else None
        if found is not None:
            taken.update(found[2])
    if not taken:
        return req
    used = {**req.used, **dict.fromkeys(taken, "motif")}
    return replace(req, colours=[m for m in req.colours if m.index not in taken], used=used)


def _contrast(program: A.Program, main: str | None) -> C.RGB:
    host = slot_colour(program, main) if main else None
    return _DARK if host is not None and C.lightness(host) > 0.55 else _LIGHT


def _overlay(program: A.Program, key: str, across: int, scatter: bool, seed: int) -> Overlay:
    """The motif as an overlay written in ``program``'s units."""
    motif = MOTIFS[key]
    view = program.view
    width = view_width(program)
    height = abs(view.y2 - view.y1) if view is not None else width
    cell_w = width / across
    cell_h = height / max(1, round(height / cell_w))
    size = f"(motif_size * {num(cell_w, 6)})"
    if scatter:
        place = f"jitter=0.35, rotate=180, scale_min=({size} * 0.75), scale_max={size}"
    else:
        place = f"offset=0.5, scale_min={size}, scale_max={size}"
    r, g, b = _LIGHT
    text = "\n".join(
        [
            f"View(0, 0, {num(width, 6)}, {num(height, 6)}, tileable=True)",
            f"Define(motif_r, {r})",
            f"Define(motif_g, {g})",
            f"Define(motif_b, {b})",
            f"Define(motif_size, {num(SIZE)})",
            f"Define({key}_shape, {motif.expr})",
            f"Define(motifs, Tile({key}_shape, {num(cell_w, 6)}, {num(cell_h, 6)}, {place}, "
            f"seed={seed}))",
            "Material(",
            "  Layer(1)",
            "    .basecolor(128, 128, 128),",
            "  Layer(motifs)",
            "    .basecolor(motif_r, motif_g, motif_b)",
            ")",
        ]
    )
    return Overlay(
        name=f"motif-{key}",
        path=Path(f"motif-{key}"),
        description=f"{motif.noun} drawn on top",
        triggers=(),
        program=text,
        colours=("motif",),
    )


def _finish(layer: A.Layer, host: A.Layer) -> A.Layer:
    """``layer`` with the host layer's channels it does not set itself."""
    own = {c.name for c in layer.channels}
    taken = tuple(c for c in host.channels if c.name not in _OWN and c.name not in own)
    return replace(layer, channels=layer.channels + taken)


def _raised(host: A.Layer, alpha: A.Node, rise: float) -> A.Layer:
    """The entry's first layer with its height raised by ``rise`` units where ``alpha`` (the
    motifs) covers it: a relief in the entry's own colours (the composite height is the maximum
    over the covered layers)."""
    lift = A.BinOp("*", alpha, A.Num(rise))
    height = host.channel("height")
    if height is None or not height.args:
        return replace(host, channels=(*host.channels, A.ChannelSet("height", (lift,))))
    raised = replace(height, args=(A.BinOp("+", height.args[0], lift),))
    return replace(host, channels=tuple(raised if c is height else c for c in host.channels))


def draw_motifs(
    program: A.Program,
    keys: tuple[str, ...],
    parts: Parts,
    entry: str,
    main: str | None,
    seed: int,
) -> Drawn:
    """``program`` (the adapted entry) with each motif of ``keys`` drawn on top."""
    scatter = any(p.key == "scatter" for p in parts.layouts)
    relief = bool(parts_words().motif_relief & set(parts.request.tokens))
    lo, hi = ACROSS_RANGE
    across = max(lo, min(hi, round(ACROSS / (parts.scale or 1.0))))
    notes: list[str] = []
    used: set[int] = set()
    drawn: list[str] = []
    for key in keys:
        if key not in MOTIFS or MOTIFS[key].kind != "shape" or not program.layers:
            continue
        said = next((p for p in parts.motifs if p.key == key), None)
        found = motif_colour(parts, said.index) if said is not None else None
        if relief:
            rgb, why = _LIGHT, "a relief in the entry's colour"
        elif found is not None:
            rgb, words, span = found
            used.update(span)
            why = f"'{words}'"
        else:
            rgb, why = _contrast(program, main), "a contrast to the entry's colour"
        if said is not None:
            used.update(range(said.index, said.index + len(said.words.split())))
        host = program.layers[0]
        before = len(program.layers)
        overlay = _overlay(program, key, across, scatter, _seed(entry, seed, key))
        program = compose(program, overlay, main_colour=None, colour=rgb)
        layers = list(program.layers)
        if relief:  # the motifs raise the entry's first layer; no layer of their own
            alpha = layers[before].alpha
            assert alpha is not None
            layers[0] = _raised(host, alpha, RISE * view_width(program) / across)
            del layers[before:]
        else:
            layers[before:] = [_finish(layer, host) for layer in layers[before:]]
        program = replace(program, layers=tuple(layers))
        drawn.append(key)
        how = "scattered" if scatter else "in a half-drop grid"
        look = "raised" if relief else f"colour {tuple(rgb)}"
        notes.append(f"motif {key}: {across} across, {how}, {look} ({why})")
    if relief and drawn:
        program = prune_defines(program)  # a relief leaves the motif colour unused
    return Drawn(program, tuple(drawn), tuple(notes), frozenset(used))
