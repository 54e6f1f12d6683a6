"""The compose pass: the entry's seeds re-derived for the user seed, the applied overlays
composed on top (each at a size factor that keeps the program tileable), and the Defines
nothing uses any more dropped."""

from __future__ import annotations

import hashlib
from dataclasses import dataclass, replace

from matloom.lang import ast as A
from matloom.lang.rewrite import map_seeds
from matloom.lang.tileable import tileable_warnings
from matloom.library.entry import Entry
from matloom.library.index import Library
from matloom.library.overlay import Overlay, compose, prune_defines
from matloom.library.passes.tile import tileable_scale
from matloom.library.query import OverlayMention


@dataclass(frozen=True)
class OverlayUse:
    """One overlay composed onto the entry: its amount and size factor."""

    name: str
    amount: float
    scale: float
    description: str

    @property
    def note(self) -> str:
        size = f", size x{self.scale:g}" if self.scale != 1.0 else ""
        return f"{self.name} (amount {self.amount:g}{size}) - {self.description}"


@dataclass(frozen=True)
class Composed:
    """The final program, the overlays on it and whether it still tiles."""

    program: A.Program
    overlays: tuple[OverlayUse, ...]
    tileable: bool
    notes: tuple[str, ...] = ()


def _derived_seed(entry: str, seed: int, old: int) -> int:
    key = f"{entry}\x1f{seed}\x1f{old}".encode()
    return int.from_bytes(hashlib.sha256(key).digest()[:4], "big") & 0x7FFFFFFF


def reseed(program: A.Program, entry: str, seed: int) -> A.Program:
    """Every explicit seed re-derived from (entry, user seed, old seed); unchanged for seed 0."""
    if seed == 0:
        return program
    return map_seeds(program, lambda old: _derived_seed(entry, seed, old))


@dataclass(frozen=True)
class _Put:
    """Composes one overlay onto a program at a size factor (what :func:`tileable_scale`
    tries)."""

    overlay: Overlay
    mention: OverlayMention
    entry: str
    main: str | None
    seed: int

    def __call__(self, program: A.Program, scale: float) -> A.Program:
        key = f"{self.entry}+{self.mention.name}"
        return compose(
            program,
            self.overlay,
            main_colour=self.main,
            cover=self.mention.amount,
            colour=self.mention.colour,
            reseed=lambda q: reseed(q, key, self.seed),
            scale=scale,
            streaks=self.mention.streaks,
        )


def compose_overlays(
    program: A.Program,
    applied: tuple[OverlayMention, ...],
    entry: Entry,
    lib: Library,
    seed: int,
    tileable: bool,
) -> Composed:
    """``program`` (placed) reseeded, with the ``applied`` overlays on top and pruned."""
    program = reseed(program, entry.name, seed)
    main = entry.colours[0] if entry.colours else None
    uses = []
    for m in applied:
        ov = lib.overlays[m.name]
        put = _Put(ov, m, entry.name, main, seed)
        scale = m.scale
        if scale != 1.0 and tileable:
            scale = tileable_scale(program, put, scale)
        program = put(program, scale)
        uses.append(OverlayUse(m.name, m.amount, scale, ov.description))
    notes: tuple[str, ...] = ()
    if applied and tileable and tileable_warnings(program):
        program = replace(program, view=replace(program.view, tileable=False))
        tileable = False
        notes = ("not tileable once the overlays were added",)
    return Composed(prune_defines(program), tuple(uses), tileable, notes)
