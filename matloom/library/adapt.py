"""Adaptation: change an entry's slot Defines and View to fit a request (AST level).

Order (later wins): word presets ("walnut" sets the ``wood`` colour), finish words (roughness,
relief, gloss slots), the amount of overlays the entry already shows ("rusty" on rusted metal
raises its wear slot), stated percentages (cover slot), scale words / sizes / counts (the
View), then explicit colours. Colours go to the slot whose role a nearby noun names ("white
grout", "gold veins"), else to the free slots in order, main colour first; plain colour words
("red") on natural materials are pulled toward the entry's own colour so "red brick" still looks
like brick. Slots the request left alone whose strong hue contradicts its palette take a shade
of a requested colour ("red and black tartan" has no yellow line). Every change is described
in a short note for the explanation. The category kinds (natural, patterned), the gloss of each
finish and the roles of tone nouns are data (``data/words.toml``).
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Sequence
from dataclasses import dataclass, replace

from matloom.lang import ast as A
from matloom.lang.api import parse_expression
from matloom.library import colour as C
from matloom.library.data import Words
from matloom.library.entry import Entry, PresetValue
from matloom.library.overlay import constant, define_value, view_width
from matloom.library.query import ColourMention, Request, plural_stem

#: a slot colour this grey (HSV saturation) is neutral: it never contradicts a palette
NEUTRAL_SAT = 0.18
#: a slot whose hue is this close (degrees) to a requested colour already fits the palette
PALETTE_HUE = 30
VIEW_RANGE = (0.25, 4.0)
#: colours given in prompt order go to the entry's free slots in that order, unless swapping
#: the first ``SWAP_MAX`` of them matches the slots' own lightness better by ``SWAP_GAIN``
#: (lightness 0..1, summed): black and white are never swapped between light and dark squares
SWAP_MAX = 3
SWAP_GAIN = 0.6


@dataclass(frozen=True)
class Adapted:
    """The adapted program and what changed."""

    program: A.Program
    view: float
    scale: float
    notes: tuple[str, ...] = ()
    used: frozenset[int] = frozenset()
    #: colour words the request gave that no slot took (reported as ignored)
    unused: tuple[str, ...] = ()


def colour_slots(program: A.Program, entry: Entry) -> tuple[list[str], list[str]]:
    """(primary slots, derived slots): primaries are plain numbers, derived ones expressions."""
    primary, derived = [], []
    for slot in entry.colours:
        (primary if constant(program, f"{slot}_r") is not None else derived).append(slot)
    return primary, derived


def slot_colour(program: A.Program, slot: str) -> C.RGB | None:
    values = [constant(program, f"{slot}_{ch}") for ch in "rgb"]
    if any(v is None for v in values):
        return None
    return C.clamp_rgb(tuple(values))  # type: ignore[arg-type]


def set_colour(program: A.Program, slot: str, rgb: C.RGB) -> A.Program:
    for ch, v in zip("rgb", rgb, strict=True):
        program = define_value(program, f"{slot}_{ch}", int(v))
    return program


def find_phrase(req: Request, phrase: str) -> list[int] | None:
    """Token indices of the first non-negated occurrence of ``phrase`` (plurals match)."""
    parts = [plural_stem(p) for p in phrase.lower().replace("-", " ").split()]
    toks = [plural_stem(t) for t in req.tokens]
    for start in range(len(toks) - len(parts) + 1):
        idx = list(range(start, start + len(parts)))
        if toks[start : start + len(parts)] == parts and not any(i in req.negated for i in idx):
            return idx
    return None


class Adapter:
    """Applies one request to one entry (its working state; :func:`adapt` returns the result)."""

    def __init__(self, entry: Entry, program: A.Program, req: Request, words: Words) -> None:
        self.entry = entry
        self.req = req
        self.w = words
        self.program = program
        self.side = view_width(program)
        self.scale = 1.0
        self.notes: list[str] = []
        self.used: set[int] = set()
        self.unused: list[str] = []

    def result(self) -> Adapted:
        return Adapted(
            self.program,
            self.side,
            self.scale,
            tuple(self.notes),
            frozenset(self.used),
            tuple(self.unused),
        )

    def note(self, text: str) -> None:
        self.notes.append(text)

    def scalar_slots(self, kind: str) -> list[str]:
        return [n for n, k in self.entry.scalars.items() if k == kind]

    # ------------------------------------------------------------------ presets
    def presets(self, presets: dict[str, dict[str, PresetValue]]) -> set[str]:
        explicit: set[str] = set()
        for word in sorted(presets, key=lambda w: (-len(w.split()), w)):
            idx = find_phrase(self.req, word)
            if idx is None or any(i in self.used for i in idx):
                continue
            self.used.update(idx)
            for slot, value in presets[word].items():
                if isinstance(value, tuple):
                    self.program = set_colour(self.program, slot, value)
                    explicit.add(slot)
                elif isinstance(value, str):
                    self.program = define_value(self.program, slot, parse_expression(value))
                else:
                    self.program = define_value(self.program, slot, value)
            self.note(
                f"preset '{word}': " + ", ".join(f"{k} {v}" for k, v in presets[word].items())
            )
        return explicit

    # ------------------------------------------------------------------ scalars
    def finishes(self) -> None:
        rough_done = False
        for key, word in self.req.finishes:
            if key in self.w.finish_roughness and not rough_done:
                for slot in self.scalar_slots("roughness"):
                    value = self.w.finish_roughness[key]
                    self.program = define_value(self.program, slot, value)
                    self.note(f"{slot} = {value:g} (finish '{word}')")
                    rough_done = True
            if key in self.w.finish_relief:
                for slot in self.scalar_slots("relief"):
                    old = constant(self.program, slot) or 1.0
                    value = round(old * self.w.finish_relief[key], 4)
                    self.program = define_value(self.program, slot, value)
                    self.note(f"{slot} x{self.w.finish_relief[key]:g} (finish '{word}')")
            if key == "metallic":
                for slot in self.scalar_slots("metallic"):
                    self.program = define_value(self.program, slot, 1)
                    self.note(f"{slot} = 1 (finish '{word}')")
            if key in self.w.finish_gloss:
                for slot in self.scalar_slots("gloss"):
                    self.program = define_value(self.program, slot, self.w.finish_gloss[key])
                    self.note(f"{slot} = {self.w.finish_gloss[key]:g} (finish '{word}')")

    def amounts(self, absorbed: Sequence[tuple[str, float]]) -> None:
        for name, amount in absorbed:
            for slot in self.scalar_slots("wear"):
                old = constant(self.program, slot) or 0.0
                # an amount word below the default lowers it ("slightly corroded copper")
                value = round(amount if amount < 0.5 else max(old, amount), 3)
                self.program = define_value(self.program, slot, value)
                self.note(f"{slot} = {value:g} ('{name}' is part of the entry)")
        if self.req.percents:
            for slot in self.scalar_slots("cover"):
                value = max(0.05, min(0.95, self.req.percents[0]))
                self.program = define_value(self.program, slot, value)
                self.note(f"{slot} = {value:g} (stated percentage)")

    # ------------------------------------------------------------------ View
    def view(self) -> None:
        e, req = self.entry, self.req
        view0 = self.side
        scale, why = 1.0, ""
        units = {plural_stem(u) for u in e.units}
        for count in req.counts:
            if count.noun in units and e.feature_m:
                scale = e.size_m / (count.value * e.feature_m)
                why = f"{count.value} {count.noun}s across"
                break
        else:
            for size in req.sizes:
                if size.extent:  # "2x2m": the View covers that much of the material
                    scale = e.size_m / size.metres
                    why = f"{size.words} across"
                    break
                if e.feature_m and (not size.noun or size.noun in units or len(req.sizes) == 1):
                    scale = size.metres / e.feature_m
                    why = f"{size.words} {size.noun}".strip()
                    self.used.update(
                        i
                        for i, t in enumerate(req.tokens)
                        if size.noun and plural_stem(t) == size.noun
                    )
                    break
            else:
                if req.scale != 1.0:
                    scale, why = req.scale, "scale words " + ", ".join(req.scale_words)
        if scale == 1.0:
            return
        scale = max(1 / VIEW_RANGE[1], min(1 / VIEW_RANGE[0], scale))
        self.scale = scale
        self.side = round(view0 / scale, 4)
        self.note(f"View {view0:g} -> {self.side:g} ({why})")

    # ------------------------------------------------------------------ colours
    def colours(self, explicit: set[str]) -> None:
        e = self.entry
        primary, derived = colour_slots(self.program, e)
        primary = [s for s in primary if e.role(s) != "material"]
        secondary = [s for s in derived if e.role(s) not in {"grout", "material"}]
        mentions = [m for m in self.req.colours if m.role != "overlay"]
        taken: set[str] = set()
        pending: list[ColourMention] = []
        for m in mentions:
            target = None
            if m.slot in e.colours and m.slot not in taken:
                self.give(m, m.slot, "the colour of what the entry shows", taken)
                continue
            same = m.words.replace(" ", "_")  # "yellow and black" on slots yellow and black
            if m.slot is None and same in e.colours and same not in taken:
                self.give(m, same, "the slot of that colour", taken)
                continue
            if m.role:
                target = next(
                    (s for s in primary + derived if e.role(s) == m.role and s not in taken), None
                )
            if target is None and m.role == "grout":
                target = next(
                    (s for s in e.colours if e.role(s) == "grout" and s not in taken), None
                )
            if target:
                self.give(m, target, f"'{m.role}' role", taken)
            else:
                pending.append(m)
        free = [s for s in primary + secondary if s not in taken]
        grout = [s for s in e.colours if e.role(s) == "grout" and s not in taken and s not in free]
        order = self.by_lightness(pending, free + grout)
        for m, slot in zip(pending, order, strict=False):
            why = "prompt order" if order == free + grout else "the slot nearest in lightness"
            self.give(m, slot, why, taken)
        for m in pending[len(free + grout) :]:
            self.note(f"colour '{m.words}' unused: no free colour slot")
            self.unused.append(m.words)
        named = [(m.rgb, m.words) for m in mentions]
        if named and (len(named) > 1 or e.category in self.w.patterned):
            free_primary = [s for s in primary if s not in taken | explicit]
            if e.category in self.w.natural and e.colours:  # the wood of "black and gray lines"
                free_primary = [s for s in free_primary if s != e.colours[0]]
            said = {plural_stem(t) for t in self.req.tokens}  # "flecks of dried petals"
            free_primary = [s for s in free_primary if s.split("_")[0] not in said]
            self.palette(named, free_primary)
        explicit |= taken
        self.tones(explicit)

    def by_lightness(self, pending: list[ColourMention], slots: list[str]) -> list[str]:
        """``slots`` in prompt order, unless the first ones swapped between the colours would
        fit their light and dark far better ("black and white checkerboard" on an entry whose
        light squares come first: black goes to the dark squares)."""
        n = min(len(pending), len(slots), SWAP_MAX)
        if n < 2 or not self.listed(pending[:n]):
            return slots
        own = [slot_colour(self.program, s) for s in slots[:n]]
        if any(c is None for c in own):
            return slots

        def cost(perm: tuple[int, ...]) -> float:
            return sum(
                abs(C.lightness(pending[i].rgb) - C.lightness(own[k]))  # type: ignore[arg-type]
                for i, k in enumerate(perm)
            )

        best = min(itertools.permutations(range(n)), key=cost)
        if cost(tuple(range(n))) - cost(best) < SWAP_GAIN:
            return slots
        return [slots[k] for k in best] + slots[n:]

    def listed(self, mentions: list[ColourMention]) -> bool:
        """Are the colours one list ("black and white", "blue/white"), only joining words
        between them (not "dark blue with a gold motif", where the order says which is
        which)?"""
        t = self.req.tokens
        for a, b in zip(mentions, mentions[1:], strict=False):
            between = t[a.index + len(a.words.split()) : b.index]
            if b.index <= a.index or not all(x in self.w.colour_join for x in between):
                return False
        return True

    def palette(self, named: list[tuple[C.RGB, str]], slots: list[str]) -> None:
        """Free primary slots whose colour contradicts the requested palette (a strong hue the
        request did not name: the yellow line of a "red and black tartan") take a shade of the
        requested colour nearest in lightness; neutral slots and grout/frame roles stay."""
        for slot in slots:
            if self.entry.role(slot) in {"grout", "frame", "material"}:
                continue
            old = slot_colour(self.program, slot)
            if old is None or C.saturation(old) < NEUTRAL_SAT:
                continue
            if any(
                C.saturation(n) >= NEUTRAL_SAT and C.hue_distance(n, old) <= PALETTE_HUE
                for n, _ in named
            ):
                continue
            near, words = min(named, key=lambda n: abs(C.luminance(n[0]) - C.luminance(old)))
            light = C.lightness(near) + (C.lightness(old) - C.lightness(near)) * 0.75
            rgb = C.with_lightness(near, light)
            self.program = set_colour(self.program, slot, rgb)
            self.note(f"colour {slot} = {rgb} (a shade of '{words}': only the requested palette)")

    def give(self, m: ColourMention, slot: str, why: str, taken: set[str]) -> None:
        rgb = m.rgb
        default = slot_colour(self.program, slot)
        natural = self.entry.category in self.w.natural
        if natural and m.words in self.w.basic and default is not None:
            if C.saturation(default) >= 0.12 and C.hue_distance(rgb, default) <= 35:
                rgb = C.mix(rgb, default, 0.45)
        self.program = set_colour(self.program, slot, rgb)
        taken.add(slot)
        self.used.update(range(m.index, m.index + len(m.words.split())))
        self.note(f"colour {slot} = '{m.words}' {rgb} ({why})")

    def tones(self, explicit: set[str]) -> None:
        e = self.entry
        for modifier, noun, index in self.req.tones:
            target = None
            role = self.w.tone_roles.get(noun)
            if role is not None:
                target = next((s for s in e.colours if e.role(s) == role), None)
            elif noun in e.tags or noun in e.name or noun in (t for t in e.synonyms):
                target = e.colours[0] if e.colours else None
            if target is None:
                continue
            current = slot_colour(self.program, target)
            if current is None:
                continue
            rgb = C.apply_tone(current, modifier, self.w.tones[modifier])
            self.program = set_colour(self.program, target, rgb)
            self.used.update((index, index + 1) if role is not None else (index,))
            self.note(f"colour {target} made {modifier} ('{modifier} {noun}') {rgb}")


def adapt(
    entry: Entry,
    program: A.Program,
    req: Request,
    words: Words,
    presets: dict[str, dict[str, PresetValue]],
    absorbed: Sequence[tuple[str, float]],
) -> Adapted:
    """Apply ``req`` to ``entry``'s parsed ``program``; the View is resized later (tiling)."""
    a = Adapter(entry, program, req, words)
    explicit = a.presets(presets)
    a.finishes()
    a.amounts(absorbed)
    a.view()
    a.colours(explicit)
    return a.result()


def resize_view(program: A.Program, side: float) -> A.Program:
    """``program`` with a square View of ``side`` (centred windows stay centred)."""
    view = program.view or A.ViewDecl(0.0, 0.0, 1.0, 1.0)
    if view.x1 < 0 and math.isclose(view.x1, -view.x2):
        return replace(
            program, view=replace(view, x1=-side / 2, y1=-side / 2, x2=side / 2, y2=side / 2)
        )
    return replace(program, view=replace(view, x2=view.x1 + side, y2=view.y1 + side))


def place_origin(
    program: A.Program, entry: Entry, own: tuple[float, float, float, float] | None = None
) -> A.Program:
    """``program`` (tileable output, its View size final) with the View's lower-left corner
    where the entry puts the wrap edge: its ``origin = [x, y]`` (front matter), else the corner
    of its own View ``own`` (default: the program's). The seam ratio of one render depends on
    where the wrap edge falls in the pattern (a plank joint or a grout line along the edge
    reports a seam although the maps repeat exactly, docs/tileable.md); the entry's corner is
    the one ``matloom library check`` measured, so a rescaled or centred View keeps it.
    Translation changes nothing else."""
    view = program.view or A.ViewDecl(0.0, 0.0, 1.0, 1.0)
    x, y = entry.origin if entry.origin is not None else (own or program.view_tuple)[:2]
    if (x, y) == (view.x1, view.y1):
        return program
    w, h = view.x2 - view.x1, view.y2 - view.y1
    return replace(program, view=replace(view, x1=x, y1=y, x2=x + w, y2=y + h))
