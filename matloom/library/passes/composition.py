"""The composition pass: the request built from its parts when no entry covers it.

:func:`compose_request` makes the :class:`~matloom.library.compose.spec.CompositionSpec` of
the parts (:func:`matloom.library.parts.to_spec`), has the composer build it, then treats the
result like an entry: the overlays the request asks for are composed on top (reseeded for the
user seed, as on an entry) and the View carries its physical size. It reports what was shown and
everything requested that the program does not show.
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from pathlib import Path

from matloom.lang import ast as A
from matloom.library.compose.spec import CompositionSpec
from matloom.library.entry import Entry
from matloom.library.index import Library
from matloom.library.overlay import view_width
from matloom.library.parts import Parts, to_spec
from matloom.library.parts_words import parts_words
from matloom.library.passes.compose import OverlayUse, compose_overlays
from matloom.library.passes.fit import MAX_OVERLAYS

#: the colour slot of a composed program that overlays bind to (when it has one)
MAIN = "base"


@dataclass(frozen=True)
class Composition:
    """A composed program and what it shows."""

    name: str
    spec: CompositionSpec
    program: A.Program
    unit_m: float
    tileable: bool
    shown: tuple[str, ...]
    dropped: tuple[str, ...]
    overlays: tuple[OverlayUse, ...]
    notes: tuple[str, ...]

    @property
    def description(self) -> str:
        what = f"{self.spec.named} ({self.spec.base})" if self.spec.named else self.spec.base
        return f"composed from the request's parts: {what}"


def _not_carried(parts: Parts, spec: CompositionSpec) -> list[str]:
    """Parts the spec has no room for: a second layout or motif, a construction its base does
    not make, unknown motifs."""
    out = [f"layout {p.key} ({p.words}): one layout per program" for p in parts.layouts[1:]]
    out += [f"motif {p.key} ({p.words}): one motif per program" for p in parts.motifs[1:]]
    out += [f"motif {p.words}: no such motif" for p in parts.unknown_motifs]
    if parts.construction:
        made = parts_words().construction_bases.get(parts.construction)
        if made != spec.base:
            out.append(f"construction {parts.construction} ({parts.construction_words})")
    return out


def compose_request(
    parts: Parts, base: str, lib: Library, seed: int, tileable: bool
) -> Composition:
    """Compose ``parts`` on ``base`` (a key of the composer's ``BASES``)."""
    from matloom.library.compose.build import compose

    spec = to_spec(parts, base=base)
    built = compose(spec)
    name = "composed-" + "-".join((spec.named or spec.base).split())
    program = built.program
    view = program.view
    unit = built.unit_m  # metres per program unit (the View's unit_m)
    if view is not None:
        program = replace(
            program, view=replace(view, tileable=tileable and built.tileable, unit_m=unit)
        )
    main = (MAIN,) if program.define(f"{MAIN}_r") is not None else ()
    entry = Entry(
        name=name,
        path=Path(name),
        description=built.description or name,
        category=built.category or base,
        tags=(),
        synonyms=(),
        size_m=unit * view_width(program),
        tileable=built.tileable,
        colours=main,
        program=built.text,
    )
    wanted = [m for m in parts.request.overlays if m.name in parts.overlays]
    applied = tuple(m for m in wanted if m.name in lib.overlays)[:MAX_OVERLAYS]
    done = compose_overlays(program, applied, entry, lib, seed, tileable and built.tileable)
    dropped = [*built.dropped, *_not_carried(parts, spec)]
    dropped += [f"overlay {m.name}: at most {MAX_OVERLAYS}" for m in wanted[MAX_OVERLAYS:]]
    return Composition(
        name=name,
        spec=spec,
        program=done.program,
        unit_m=unit,
        tileable=done.tileable,
        shown=built.shown,
        dropped=tuple(dropped),
        overlays=done.overlays,
        notes=done.notes,
    )
