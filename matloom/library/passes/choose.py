"""The choose pass: the entry a ranking gives (the best, the N-th asked for, or a fallback), or
a composed program when no candidate covers the request's parts (:mod:`cover`)."""

from __future__ import annotations

from dataclasses import dataclass, field, replace

from matloom.library.entry import Entry
from matloom.library.index import Library
from matloom.library.parts import Parts
from matloom.library.passes.cover import Coverage, cover, decide, drawable_missing, patterned
from matloom.library.retrieval import Candidate

#: the entry used when no entry matched the request
FALLBACK = "generic-surface"


@dataclass(frozen=True)
class Choice:
    """The chosen entry, its score and its rank among the candidates (0: none matched)."""

    entry: Entry
    score: float
    rank: int
    #: the base to compose the request on instead of using ``entry`` (None: use the entry)
    compose: str | None = None
    #: what the chosen entry misses of the request's parts (reported as not shown)
    missing: tuple[str, ...] = ()
    #: what each of the best candidates misses (for the explanation)
    coverage: tuple[Coverage, ...] = ()
    why: tuple[str, ...] = field(default=())
    #: motifs (composer keys) to draw onto the entry (:mod:`.motif`)
    motifs: tuple[str, ...] = ()

    @property
    def notes(self) -> tuple[str, ...]:
        if self.compose is not None:
            return self.why
        if self.rank == 0:
            return (f"no entry matched the request; used {self.entry.name}", *self.why)
        return self.why


def choose(
    cands: list[Candidate], lib: Library, pick: int | None, parts: Parts | None = None
) -> Choice:
    """The ``pick``-th candidate (1 = best; ValueError past the candidates); else, with the
    request's ``parts``, the best candidate that covers them or a composition
    (:func:`~matloom.library.passes.cover.decide`); else the best, else the fallback entry."""
    if pick is not None:
        if not 1 <= pick <= len(cands):
            raise ValueError(f"--pick {pick}: only {len(cands)} candidates matched")
        c = cands[pick - 1]
        return Choice(lib.entry(c.name), c.score, pick)
    name = FALLBACK if FALLBACK in lib.entries else sorted(lib.entries)[0]
    if parts is not None:
        v = decide(cands, lib, parts)
        if v.compose is not None:
            best = cands[0] if cands else None
            entry = lib.entry(best.name if best else name)
            return Choice(entry, 0.0, 0, v.compose, (), v.coverage, v.notes)
        if v.index is not None:
            c = cands[v.index]
            if v.taken is not None and not v.motifs and not patterned(lib.entry(c.name)):
                drawn = drawable_missing(v.taken, parts)
                if drawn:
                    v = replace(v, motifs=drawn, notes=(*v.notes, f"drew {', '.join(drawn)}"))
            return Choice(
                lib.entry(c.name),
                c.score,
                v.index + 1,
                None,
                v.missing(),
                v.coverage,
                v.notes,
                v.motifs,
            )
    if cands:
        return Choice(lib.entry(cands[0].name), cands[0].score, 1)
    missing = cover(lib.entry(name), parts, lib).missing if parts is not None else ()
    return Choice(lib.entry(name), 0.0, 0, missing=missing)
