"""The library author: prompt -> request -> retrieved entry -> adapted, composed program.

:func:`author` never needs a model or the network. It reads the request, ranks the entries
(BM25), adapts the chosen one (colours, presets, finish, scale), composes the requested
overlays on top, keeps the View tileable where it can (with the wrap edge inside the pattern's
cells, :func:`matloom.library.adapt.place_origin`), drops the Defines nothing uses any more, and
says what it did: the top candidates with scores, the entry, every adaptation and the words it
did not use. The result is deterministic for a given (prompt, seed, pick, tileable).
"""

from __future__ import annotations

import hashlib
from collections.abc import Callable, Iterable
from dataclasses import dataclass, field, replace

import matloom
from matloom.lang import ast as A
from matloom.lang.rewrite import map_program
from matloom.lang.tileable import make_tileable, tileable_warnings
from matloom.library.adapt import VIEW_RANGE, adapt, place_origin, resize_view
from matloom.library.data import words
from matloom.library.entry import Entry
from matloom.library.index import Library, library
from matloom.library.overlay import Overlay, compose, prune_defines, view_width
from matloom.library.query import COLOUR_NOUNS, ColourMention, OverlayMention, Request, read
from matloom.library.retrieval import Candidate, Index

MAX_OVERLAYS = 3
FALLBACK = "generic-surface"
TOP = 5


@dataclass
class LibraryResult:
    """What the library author produced for one prompt, and why."""

    prompt: str
    program: str
    entry: str
    category: str
    description: str
    unit_m: float
    tileable: bool
    score: float
    seed: int
    candidates: list[Candidate] = field(default_factory=list)
    rank: int = 1
    adaptations: list[str] = field(default_factory=list)
    overlays: list[str] = field(default_factory=list)
    overlay_notes: list[str] = field(default_factory=list)
    absorbed: list[str] = field(default_factory=list)
    ignored: list[str] = field(default_factory=list)
    notes: list[str] = field(default_factory=list)

    @property
    def explanation(self) -> str:
        """The explanation as text (what ``--explain`` prints)."""
        lines = [f"prompt: {self.prompt.strip()}"]
        if self.candidates:
            lines.append("candidates:")
            for k, c in enumerate(self.candidates[:TOP], start=1):
                mark = "*" if c.name == self.entry else " "
                lines.append(f" {mark}{k}. {c.name} {c.score:.2f}  ({', '.join(c.matched)})")
        else:
            lines.append("candidates: none matched")
        lines.append(
            f"entry: {self.entry} [{self.category}] (rank {self.rank}, score {self.score:.2f}) - "
            f"{self.description}"
        )
        if self.adaptations:
            lines.append("adaptations:")
            lines += [f"  - {a}" for a in self.adaptations]
        if self.overlay_notes:
            lines.append("overlays: " + ", ".join(self.overlay_notes))
        if self.absorbed:
            lines.append("already part of the entry: " + ", ".join(self.absorbed))
        size = self.unit_m * _view_side(self.program)
        lines.append(
            f"tileable: {'yes' if self.tileable else 'no'}; covers {size:.3g} m "
            f"({self.unit_m:.4g} m per unit)"
        )
        lines += [f"note: {n}" for n in self.notes]
        lines.append("ignored: " + (", ".join(self.ignored) if self.ignored else "nothing"))
        return "\n".join(lines)


def _view_side(text: str) -> float:
    for line in text.splitlines():
        if line.startswith("View("):
            parts = [p.strip() for p in line[5:].split(",")]
            try:
                return abs(float(parts[2]) - float(parts[0]))
            except (ValueError, IndexError):
                return 1.0
    return 1.0


def index_of(lib: Library) -> Index:
    """The (cached) BM25 index of a library."""
    return lib.index


def search(text: str, lib: Library | None = None) -> list[Candidate]:
    """Entries ranked for ``text`` (best first), as :func:`author` ranks them."""
    lib = lib or library()
    req = read(text, words(), lib.triggers, lib.weak_triggers)
    return index_of(lib).rank(req)


def _derived_seed(entry: str, seed: int, old: int) -> int:
    key = f"{entry}\x1f{seed}\x1f{old}".encode()
    return int.from_bytes(hashlib.sha256(key).digest()[:4], "big") & 0x7FFFFFFF


def reseed(program: A.Program, entry: str, seed: int) -> A.Program:
    """Every explicit seed re-derived from (entry, user seed, old seed); unchanged for seed 0."""
    if seed == 0:
        return program

    def fn(node: A.Node) -> A.Node:
        if not isinstance(node, A.Call):
            return node
        args = tuple(
            replace(a, value=A.Num(_derived_seed(entry, seed, int(a.value.value))))
            if a.param == "seed" and isinstance(a.value, A.Num)
            else a
            for a in node.args
        )
        return replace(node, args=args)

    return map_program(program, fn)


def _nearest_tiling(
    options: Iterable[float], target: float, tolerance: float, tries: int, tiles: Callable
) -> float | None:
    """The option nearest ``target`` (within ``tolerance``, relative; at most ``tries`` tried,
    nearest first) for which ``tiles(option)`` holds, else None."""
    ranked = sorted(
        (o for o in options if abs(o / target - 1) <= tolerance),
        key=lambda o: (abs(o / target - 1), o),
    )
    return next((o for o in ranked[:tries] if tiles(o)), None)


def _tileable_side(program: A.Program, target: float, view0: float) -> float | None:
    """The View side nearest ``target`` at which ``program`` tiles (None if none close)."""
    candidates = {round(view0 * k / m, 6) for k in range(1, 17) for m in range(1, 9)}
    lo, hi = view0 * VIEW_RANGE[0], view0 * VIEW_RANGE[1]
    return _nearest_tiling(
        (c for c in candidates if lo <= c <= hi),
        target,
        0.35,
        10,
        lambda side: not tileable_warnings(make_tileable(resize_view(program, side))),
    )


def _tileable_scale(program: A.Program, put: Callable, scale: float) -> float:
    """The overlay size factor nearest ``scale`` (within 40 %) at which the composed program
    still tiles (noise frequencies stay whole numbers of periods), else ``scale`` itself."""
    options = {round(k / n, 4) for n in range(1, 5) for k in range(1, 13)} | {scale}
    found = _nearest_tiling(
        (s for s in options if s != 1.0),
        scale,
        0.4,
        6,
        lambda s: not tileable_warnings(put(program, s)),
    )
    return scale if found is None else found


def _metal_colours(req: Request, terms: frozenset[str], presets: dict, idx: Index) -> None:
    """A metal colour name ("silver", "gold", "copper") that the chosen entry neither shows nor
    takes as a preset is the colour of the entry ("silver fabric" is silver-coloured)."""
    w = words()
    for i, word in req.words_at():
        if i in req.used or word not in w.metal_colours or word in presets:
            continue
        rgb = w.colour(word)
        if rgb is None or idx.stem(word) in terms:
            continue
        req.colours.append(ColourMention(rgb, word, i))
        req.used[i] = "colour"
    req.colours.sort(key=lambda m: m.index)


#: words between a colour and the noun it describes ("yellow-and-black hazard stripe")
_COLOUR_JOIN = frozenset({"and", "or", "/", "-", ",", "&"})
#: nouns after a colour that are no thing of their own ("teal shades", "beige low-pile")
_NO_THING = COLOUR_NOUNS | {"shades", "tones", "hues", "tint", "tints", "low", "high"}


def _foreign_colours(req: Request, terms: frozenset[str], idx: Index, entry: Entry) -> list[str]:
    """Drop the colours that describe a noun the entry does not show ("a yellow-and-black hazard
    stripe" on diamond plate, "dark oil stains" on a sidewalk): they would recolour the main
    material. A colour keeps its place when its noun is a material, a category word, a role
    noun or one of the entry's own words. Returns the dropped colours' words."""
    w = words()
    known = w.materials | frozenset().union(*w.category_words.values()) | _NO_THING
    keep, dropped = [], []

    def colourish(k: int) -> bool:
        t = req.tokens[k]
        return w.colour(t) is not None or t in w.tones or req.used.get(k) == "colour"

    for m in req.colours:
        j = m.index + len(m.words.split())
        while j < len(req.tokens) and (
            (req.tokens[j] in _COLOUR_JOIN and j + 1 < len(req.tokens) and colourish(j + 1))
            or req.used.get(j) in {"colour", "finish", "tone"}
            or colourish(j)
        ):
            j += 1
        noun = req.tokens[j] if j < len(req.tokens) else ""
        roleless = m.role is None or (
            m.role not in {"grout", "overlay"}
            and not any(entry.role(s) == m.role for s in entry.colours)
        )
        foreign = (
            roleless
            and m.slot is None
            and noun.isalpha()
            and j not in req.used
            and noun not in w.stop_words
            and noun not in known
            and noun not in w.roles
            and not noun.endswith(("ed", "ing", "ly"))
            and idx.stem(noun) not in terms
        )
        if foreign:
            dropped.append(f"{m.words} (the colour of '{noun}')")
        else:
            keep.append(m)
    req.colours = keep
    return dropped


def _choose(cands: list[Candidate], lib: Library, pick: int | None) -> tuple[Entry, float, int]:
    if pick is not None:
        if not 1 <= pick <= len(cands):
            raise ValueError(f"--pick {pick}: only {len(cands)} candidates matched")
        c = cands[pick - 1]
        return lib.entry(c.name), c.score, pick
    if cands:
        return lib.entry(cands[0].name), cands[0].score, 1
    name = FALLBACK if FALLBACK in lib.entries else sorted(lib.entries)[0]
    return lib.entry(name), 0.0, 0


def _ignored(req: Request, used: set[int], stop: frozenset[str]) -> list[str]:
    out: list[str] = []
    for i, word in req.words_at():
        if i in used or i in req.used or word in stop or len(word) <= 2 or word in out:
            continue
        out.append(word)
    return out


def _takes_colour(overlay: Overlay) -> bool:
    return any(c != overlay.host for c in overlay.colours)


def _colour_the_entry(m: OverlayMention, entry: Entry) -> None:
    """The colour before an overlay word that no added overlay takes ("orange painted" metal,
    where the entry shows the paint itself) goes to the entry's slot named after the overlay
    (``paint_col`` for "painted", ``rust_col`` for "rusty"), else to the entry's colours like
    any other colour of the request (a colour no slot takes is reported as ignored)."""
    cm = m.colour_mention
    assert cm is not None
    words = (m.name, *m.word.split())
    cm.role = None
    for slot in entry.colours:
        parts = [p for p in slot.split("_") if len(p) >= 4]
        if any(w.startswith(p) or p.startswith(w) for p in parts for w in words):
            cm.slot = slot
            return


def author(
    prompt: str,
    *,
    seed: int = 0,
    pick: int | None = None,
    tileable: bool = True,
    lib: Library | None = None,
) -> LibraryResult:
    """Write a MatLoom program for ``prompt`` from the library (no model, no network).

    ``seed`` re-derives every noise seed (0 keeps the entry's own); ``pick`` takes the N-th
    candidate (1 = best) instead of the best; ``tileable`` asks for ``View(..., tileable=True)``
    wherever the material allows it. Raises ValueError only for a ``pick`` out of range.
    """
    lib = lib or library()
    w = words()
    idx = index_of(lib)
    req = read(prompt or "", w, lib.triggers, lib.weak_triggers)
    cands = idx.rank(req)
    entry, score, rank = _choose(cands, lib, pick)
    notes: list[str] = []
    if rank == 0:
        notes.append(f"no entry matched the request; used {entry.name}")
    base = lib.ast(entry.name)
    view0 = view_width(base)
    terms = idx.terms.get(entry.name, frozenset())
    absorbed, apply = [], []
    for m in req.overlays:
        if m.name in entry.absorbs or idx.stem(m.word.split()[0]) in terms:
            absorbed.append((m.name, m.amount))
            if m.scale != 1.0:  # "fine cracks" on cracked earth: the entry's own features
                req.scale *= m.scale
                req.scale_words.append(f"{m.word} x{m.scale:g}")
        elif m.name in lib.overlays:
            apply.append(m)
    if len(apply) > MAX_OVERLAYS:
        notes.append("dropped overlays (at most 3): " + ", ".join(m.name for m in apply[3:]))
        apply = apply[:MAX_OVERLAYS]
    for m in req.overlays:
        if m.colour_mention is None or (
            any(m is a for a in apply) and _takes_colour(lib.overlays[m.name])
        ):
            continue
        _colour_the_entry(m, entry)
    presets = lib.presets(entry, w.preset_sets)
    _metal_colours(req, terms, presets, idx)
    foreign = _foreign_colours(req, terms, idx, entry) if rank else []
    adapted = adapt(entry, base, req, w, presets, absorbed)
    adapted.unused.extend(foreign)
    program, side = adapted.program, adapted.view
    is_tileable = False
    if tileable:
        warnings = tileable_warnings(make_tileable(resize_view(program, side)))
        if not warnings:
            is_tileable = True
        elif entry.tileable and abs(side / view0 - 1) > 1e-6:
            snapped = _tileable_side(program, side, view0)
            if snapped is not None:
                notes.append(f"View {side:g} -> {snapped:g} so that it tiles")
                side, is_tileable = snapped, True
            elif not tileable_warnings(make_tileable(resize_view(program, view0))):
                # no tileable size near the asked one: tiling wins over a size word
                notes.append(
                    f"View kept at {view0:g}: the entry tiles only at sizes far from {side:g}"
                )
                side, is_tileable = view0, True
        if not is_tileable:
            notes.append("not tileable: " + warnings[0].message.removeprefix("tileable: "))
    program = resize_view(program, side)
    if is_tileable:
        program = place_origin(program, entry, base.view_tuple)
    unit_m = round(entry.size_m / side, 6)
    program = replace(program, view=replace(program.view, tileable=is_tileable, unit_m=unit_m))
    program = reseed(program, entry.name, seed)
    main = entry.colours[0] if entry.colours else None
    names = []
    for m in apply:
        ov = lib.overlays[m.name]

        def put(p: A.Program, s: float, m: OverlayMention = m, ov: Overlay = ov) -> A.Program:
            return compose(
                p,
                ov,
                main_colour=main,
                cover=m.amount,
                colour=m.colour,
                reseed=lambda q, n=m.name: reseed(q, f"{entry.name}+{n}", seed),
                scale=s,
            )

        scale = m.scale
        if scale != 1.0 and is_tileable:
            scale = _tileable_scale(program, put, scale)
        program = put(program, scale)
        size = f", size x{scale:g}" if scale != 1.0 else ""
        names.append(f"{m.name} (amount {m.amount:g}{size}) - {ov.description}")
    if apply and is_tileable and tileable_warnings(program):
        program = replace(program, view=replace(program.view, tileable=False))
        is_tileable = False
        notes.append("not tileable once the overlays were added")
    program = prune_defines(program)
    used = idx.understood(req, entry.name) | adapted.used
    for m in req.overlays:
        used.update(range(m.index, m.index + len(m.word.split())))
    ignored = _ignored(req, used, w.stop_words) + adapted.unused
    header = [f"# library entry: {entry.name} ({entry.category}) - {entry.description}"]
    header += [f"# adapted: {a}" for a in adapted.notes]
    header += [f"# overlay: {n}" for n in names]
    text = "\n".join(header) + "\n" + matloom.format(program)
    return LibraryResult(
        prompt=prompt,
        program=text,
        entry=entry.name,
        category=entry.category,
        description=entry.description,
        unit_m=unit_m,
        tileable=is_tileable,
        score=score,
        seed=seed,
        candidates=cands[:TOP],
        rank=rank,
        adaptations=adapted.notes,
        overlays=[m.name for m in apply],
        overlay_notes=names,
        absorbed=[f"{n} (amount {a:g})" for n, a in absorbed],
        ignored=ignored,
        notes=notes,
    )
