"""The library author: prompt -> request -> retrieved entry -> adapted, composed program.

:func:`author` never needs a model or the network. It runs small passes
(:mod:`matloom.library.passes`), each returning a value and changing none of its inputs: read
the request, rank the entries (BM25), choose one, fit the request to it, adapt it (colours,
presets, finish, scale), find the View side at which it tiles (with the wrap edge inside the
pattern's cells, :func:`matloom.library.adapt.place_origin`), then reseed, compose the requested
overlays and drop the Defines nothing uses any more. The request is also read as parts
(:func:`matloom.library.parts.read_parts`: named material, class, colour roles, layout, motif);
when no good candidate covers the named material or class, or the one that does lacks a
requested motif or layout, the program is composed from the parts instead
(:mod:`matloom.library.passes.cover`, :mod:`matloom.library.passes.composition`). The result
holds the program (its AST and its text) and says what it did: the parts, the top candidates
with scores and what each misses, the entry or the composition, every adaptation, the words it
did not use and every requested part it does not show. The result is deterministic for a given
(prompt, seed, pick, tileable).
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace

from matloom.lang import ast as A
from matloom.lang.printer import format_program
from matloom.library.adapt import adapt
from matloom.library.data import words
from matloom.library.index import Library, library
from matloom.library.overlay import view_width
from matloom.library.parts import Parts, read_parts
from matloom.library.passes.choose import Choice, choose
from matloom.library.passes.compose import compose_overlays
from matloom.library.passes.composition import compose_request
from matloom.library.passes.fit import fit
from matloom.library.passes.motif import draw_motifs, without_motif_colours
from matloom.library.passes.tile import place, tile
from matloom.library.query import Request, read
from matloom.library.retrieval import Candidate

#: candidates kept in the result (and listed by the explanation)
TOP = 5


@dataclass(frozen=True)
class LibraryResult:
    """What the library author produced for one prompt, and why.

    ``program`` is the program's text (header comments naming the entry, its adaptations and
    overlays, then the canonical program); ``ast`` is the program itself."""

    prompt: str
    program: str
    ast: A.Program
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
    #: True when the program was composed from the request's parts (no entry covered them)
    composed: bool = False
    #: the request read as parts (None only for results made by hand)
    parts: Parts | None = None
    #: every requested part the program does not show, with the reason
    dropped: list[str] = field(default_factory=list)
    #: what a composed program shows ("layout: hexagons", "motif: star")
    shown: list[str] = field(default_factory=list)
    #: candidate name -> what it misses of the request's parts
    misses: dict[str, tuple[str, ...]] = field(default_factory=dict)

    @property
    def view_side(self) -> float:
        """The width of the program's View (1 when it has none)."""
        view = self.ast.view
        return 1.0 if view is None else abs(view.x2 - view.x1)

    @property
    def explanation(self) -> str:
        """The explanation as text (what ``--explain`` prints)."""
        lines = [f"prompt: {self.prompt.strip()}"]
        if self.parts is not None:
            lines.append(f"parts: {self.parts.summary()}")
        if self.candidates:
            lines.append("candidates:")
            for k, c in enumerate(self.candidates[:TOP], start=1):
                mark = "*" if c.name == self.entry else " "
                miss = self.misses.get(c.name)
                misses = f" - misses {', '.join(miss)}" if miss else ""
                lines.append(
                    f" {mark}{k}. {c.name} {c.score:.2f}  ({', '.join(c.matched)}){misses}"
                )
        else:
            lines.append("candidates: none matched")
        how = "composed" if self.composed else f"rank {self.rank}, score {self.score:.2f}"
        lines.append(f"entry: {self.entry} [{self.category}] ({how}) - {self.description}")
        if self.shown:
            lines.append("composed: " + ", ".join(self.shown))
        if self.adaptations:
            lines.append("adaptations:")
            lines += [f"  - {a}" for a in self.adaptations]
        if self.overlay_notes:
            lines.append("overlays: " + ", ".join(self.overlay_notes))
        if self.absorbed:
            lines.append("already part of the entry: " + ", ".join(self.absorbed))
        size = self.unit_m * self.view_side
        lines.append(
            f"tileable: {'yes' if self.tileable else 'no'}; covers {size:.3g} m "
            f"({self.unit_m:.4g} m per unit)"
        )
        lines += [f"note: {n}" for n in self.notes]
        if self.dropped:
            lines.append("not shown: " + "; ".join(self.dropped))
        ignored = ", ".join(self.ignored)
        if self.dropped:  # never "nothing" when a requested part was dropped
            ignored = "; ".join(x for x in (ignored, "not shown: " + "; ".join(self.dropped)) if x)
        lines.append("ignored: " + (ignored or "nothing"))
        return "\n".join(lines)


def search(text: str, lib: Library | None = None) -> list[Candidate]:
    """Entries ranked for ``text`` (best first), as :func:`author` ranks them."""
    lib = lib or library()
    req = read(text, words(), lib.triggers, lib.weak_triggers)
    return lib.index.rank(req)


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
    req = read(prompt or "", w, lib.triggers, lib.weak_triggers)
    parts = read_parts(prompt or "", req=req)
    cands = lib.index.rank(req)
    choice = choose(cands, lib, pick, parts)
    if choice.compose is not None:
        try:
            return _composed(prompt, parts, choice, cands, lib, seed, tileable)
        except ValueError as err:  # a composer bug must not cost the user a program
            choice = _retrieved(choice, cands, str(err).splitlines()[0])
    entry = choice.entry
    base = lib.ast(entry.name)
    presets = lib.presets(entry, w.preset_sets)
    # the colours of the motifs to draw are theirs: neither the entry's nor foreign to it
    req = without_motif_colours(req, choice.motifs, parts)
    fitted = fit(req, entry, lib, w, presets, matched=choice.rank > 0)
    reading = fitted.reading(req)
    adapted = adapt(entry, base, reading, w, presets, fitted.absorbed)
    tiling = tile(adapted.program, adapted.view, entry, view_width(base), tileable)
    placed = place(adapted.program, tiling, entry, base)
    composed = compose_overlays(placed, fitted.applied, entry, lib, seed, tiling.tileable)
    main = entry.colours[0] if entry.colours else None
    drawn = draw_motifs(composed.program, choice.motifs, parts, entry.name, main, seed)
    used = lib.index.understood(reading, entry.name) | adapted.used | drawn.used
    for m in req.overlays:
        used.update(range(m.index, m.index + len(m.word.split())))
    header = [f"# library entry: {entry.name} ({entry.category}) - {entry.description}"]
    header += [f"# adapted: {a}" for a in adapted.notes]
    header += [f"# overlay: {u.note}" for u in composed.overlays]
    header += [f"# drawn: {n}" for n in drawn.notes]
    return LibraryResult(
        prompt=prompt,
        program="\n".join(header) + "\n" + format_program(drawn.program),
        ast=drawn.program,
        entry=entry.name,
        category=entry.category,
        description=entry.description,
        unit_m=tiling.unit_m(entry),
        tileable=composed.tileable,
        score=choice.score,
        seed=seed,
        candidates=cands[:TOP],
        rank=choice.rank,
        adaptations=list(adapted.notes),
        overlays=[m.name for m in fitted.applied],
        overlay_notes=[u.note for u in composed.overlays],
        absorbed=[f"{n} (amount {a:g})" for n, a in fitted.absorbed],
        ignored=_not_twice(_ignored(reading, used, w.stop_words), choice.missing)
        + [*adapted.unused, *fitted.foreign],
        notes=[*_origin(lib, entry.name), *choice.notes, *fitted.notes, *tiling.notes]
        + list(composed.notes)
        + list(drawn.notes),
        parts=parts,
        dropped=list(choice.missing),
        misses={c.name: c.missing for c in choice.coverage if c.missing},
    )


def _not_twice(ignored: list[str], dropped: tuple[str, ...]) -> list[str]:
    """The ignored words not already reported inside a part that was not shown."""
    said = {w for d in dropped for w in d.replace("(", " ").replace(")", " ").split()}
    return [w for w in ignored if w not in said]


def _composed(
    prompt: str,
    parts: Parts,
    choice: Choice,
    cands: list[Candidate],
    lib: Library,
    seed: int,
    tileable: bool,
) -> LibraryResult:
    """The result of a program composed from the request's parts on ``choice.compose``."""
    assert choice.compose is not None
    made = compose_request(parts, choice.compose, lib, seed, tileable)
    req = parts.request
    used = set(parts.used)
    for m in req.overlays:
        used.update(range(m.index, m.index + len(m.word.split())))
    header = [f"# composed: {made.name} ({made.spec.base}) - {made.description}"]
    header.append(f"# parts: {parts.summary()}")
    header += [f"# overlay: {u.note}" for u in made.overlays]
    return LibraryResult(
        prompt=prompt,
        program="\n".join(header) + "\n" + format_program(made.program),
        ast=made.program,
        entry=made.name,
        category=made.spec.base,
        description=made.description,
        unit_m=made.unit_m,
        tileable=made.tileable,
        score=0.0,
        seed=seed,
        candidates=cands[:TOP],
        rank=0,
        overlays=[u.name for u in made.overlays],
        overlay_notes=[u.note for u in made.overlays],
        ignored=_ignored(req, used, words().stop_words),
        notes=[*choice.notes, *made.notes],
        composed=True,
        parts=parts,
        dropped=list(made.dropped),
        shown=list(made.shown),
        misses={c.name: c.missing for c in choice.coverage if c.missing},
    )


def _retrieved(choice: Choice, cands: list[Candidate], why: str) -> Choice:
    """``choice`` back on its entry (the best candidate) when composing failed."""
    return replace(
        choice,
        compose=None,
        rank=1 if cands else 0,
        score=cands[0].score if cands else 0.0,
        missing=choice.coverage[0].missing if choice.coverage else (),
        why=(*choice.why, f"composition failed ({why}); used the best entry"),
    )


def _origin(lib: Library, name: str) -> list[str]:
    """Where a user library's entry came from (nothing for a built-in one)."""
    if name not in lib.sources:
        return []
    return [f"entry from the user library {lib.sources[name]}"]


def _ignored(req: Request, used: set[int], stop: frozenset[str]) -> list[str]:
    """The request's words that no pass used (stop words and short words aside)."""
    out: list[str] = []
    for i, word in req.words_at():
        if i in used or i in req.used or word in stop or len(word) <= 2 or word in out:
            continue
        out.append(word)
    return out
