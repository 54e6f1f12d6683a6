"""The library author: prompt -> request -> retrieved entry -> adapted, composed program.

:func:`author` never needs a model or the network. It runs small passes
(:mod:`matloom.library.passes`), each returning a value and changing none of its inputs: read
the request, rank the entries (BM25), choose one, fit the request to it, adapt it (colours,
presets, finish, scale), find the View side at which it tiles (with the wrap edge inside the
pattern's cells, :func:`matloom.library.adapt.place_origin`), then reseed, compose the requested
overlays and drop the Defines nothing uses any more. The result holds the program (its AST and
its text) and says what it did: the top candidates with scores, the entry, every adaptation and
the words it did not use. The result is deterministic for a given (prompt, seed, pick,
tileable).
"""

from __future__ import annotations

from dataclasses import dataclass, field

from matloom.lang import ast as A
from matloom.lang.printer import format_program
from matloom.library.adapt import adapt
from matloom.library.data import words
from matloom.library.index import Library, library
from matloom.library.overlay import view_width
from matloom.library.passes.choose import choose
from matloom.library.passes.compose import compose_overlays
from matloom.library.passes.fit import fit
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

    @property
    def view_side(self) -> float:
        """The width of the program's View (1 when it has none)."""
        view = self.ast.view
        return 1.0 if view is None else abs(view.x2 - view.x1)

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
        size = self.unit_m * self.view_side
        lines.append(
            f"tileable: {'yes' if self.tileable else 'no'}; covers {size:.3g} m "
            f"({self.unit_m:.4g} m per unit)"
        )
        lines += [f"note: {n}" for n in self.notes]
        lines.append("ignored: " + (", ".join(self.ignored) if self.ignored else "nothing"))
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
    cands = lib.index.rank(req)
    choice = choose(cands, lib, pick)
    entry = choice.entry
    base = lib.ast(entry.name)
    presets = lib.presets(entry, w.preset_sets)
    fitted = fit(req, entry, lib, w, presets, matched=choice.rank > 0)
    reading = fitted.reading(req)
    adapted = adapt(entry, base, reading, w, presets, fitted.absorbed)
    tiling = tile(adapted.program, adapted.view, entry, view_width(base), tileable)
    placed = place(adapted.program, tiling, entry, base)
    composed = compose_overlays(placed, fitted.applied, entry, lib, seed, tiling.tileable)
    used = lib.index.understood(reading, entry.name) | adapted.used
    for m in req.overlays:
        used.update(range(m.index, m.index + len(m.word.split())))
    header = [f"# library entry: {entry.name} ({entry.category}) - {entry.description}"]
    header += [f"# adapted: {a}" for a in adapted.notes]
    header += [f"# overlay: {u.note}" for u in composed.overlays]
    return LibraryResult(
        prompt=prompt,
        program="\n".join(header) + "\n" + format_program(composed.program),
        ast=composed.program,
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
        ignored=_ignored(reading, used, w.stop_words) + [*adapted.unused, *fitted.foreign],
        notes=[*_origin(lib, entry.name), *choice.notes, *fitted.notes, *tiling.notes]
        + list(composed.notes),
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
