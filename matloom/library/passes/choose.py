"""The choose pass: the entry a ranking gives (the best, the N-th asked for, or a fallback)."""

from __future__ import annotations

from dataclasses import dataclass

from matloom.library.entry import Entry
from matloom.library.index import Library
from matloom.library.retrieval import Candidate

#: the entry used when no entry matched the request
FALLBACK = "generic-surface"


@dataclass(frozen=True)
class Choice:
    """The chosen entry, its score and its rank among the candidates (0: none matched)."""

    entry: Entry
    score: float
    rank: int

    @property
    def notes(self) -> tuple[str, ...]:
        if self.rank == 0:
            return (f"no entry matched the request; used {self.entry.name}",)
        return ()


def choose(cands: list[Candidate], lib: Library, pick: int | None) -> Choice:
    """The ``pick``-th candidate (1 = best; ValueError past the candidates), else the best,
    else the fallback entry."""
    if pick is not None:
        if not 1 <= pick <= len(cands):
            raise ValueError(f"--pick {pick}: only {len(cands)} candidates matched")
        c = cands[pick - 1]
        return Choice(lib.entry(c.name), c.score, pick)
    if cands:
        return Choice(lib.entry(cands[0].name), cands[0].score, 1)
    name = FALLBACK if FALLBACK in lib.entries else sorted(lib.entries)[0]
    return Choice(lib.entry(name), 0.0, 0)
