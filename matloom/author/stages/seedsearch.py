"""Stage III (b): seed search over the distinct {first, selected, last} programs (§8.6).

Each candidate's sweep renders the original and ``variants`` seed variants at ``size`` (256 by
default) with :func:`matloom.engine.schedules.sweep.run_sweep` and scores them with the scorer;
only noise seeds change, equal seeds stay equal, and the original is always in the pool, so the
sweep can never lose score relative to it. The best over all sweeps wins, ties going to the earliest
candidate. Each finished sweep is recorded at once, so a resumed run skips it.
"""

from __future__ import annotations

from collections.abc import Callable

from matloom.author.records import FinalRecord, RunRecord, SeedSearchRecord, SweepRecord
from matloom.author.scorers.base import TextImageScorer

SweepProgress = Callable[[int, int], None]


def candidate_indices(first: int, selected: int, last: int) -> list[int]:
    """Sorted distinct trajectory indices searched."""
    return sorted({first, selected, last})


def run_candidate_sweep(
    program_index: int,
    program: str,
    *,
    prompt: str,
    scorer: TextImageScorer,
    variants: int,
    size: int,
    seed: int,
    jobs: int,
    progress: SweepProgress | None = None,
) -> SweepRecord:
    """Sweep one candidate program and summarise the result for the record."""
    from matloom.engine.schedules.sweep import run_sweep
    from matloom.render.preview import ShadeParams

    result = run_sweep(
        program,
        variants=variants,
        shading=ShadeParams.of(),
        size=size,
        scorer=scorer,
        prompt=prompt,
        seed=seed,
        jobs=jobs,
        progress=progress,
    )
    scores = [c.score for c in sorted(result.candidates, key=lambda c: c.index)]
    return SweepRecord(
        program_index=program_index,
        variants=variants,
        size=size,
        seed=seed,
        best_variant=result.best_index,
        best_score=scores[result.best_index] if scores else None,
        original_score=scores[0] if scores else None,
        best_program=result.best_program,
        scores=scores,
        seconds=result.seconds,
        rate=result.rate,
        message=result.message,
    )


def best_of_sweeps(search: SeedSearchRecord) -> FinalRecord | None:
    """The highest-scoring sweep winner (earliest candidate on ties), or None if no sweep ran."""
    best: SweepRecord | None = None
    for sweep in sorted(search.sweeps, key=lambda s: s.program_index):
        score = sweep.best_score
        if best is None or (
            score is not None and (best.best_score is None or score > best.best_score)
        ):
            best = sweep
    if best is None:
        return None
    return FinalRecord(
        program=best.best_program,
        program_index=best.program_index,
        variant=best.best_variant,
        score=best.best_score,
    )


def chosen_final(record: RunRecord) -> FinalRecord:
    """The material stage III chose: the best seed-sweep winner, else the selected program
    (with the selection's score of it)."""
    final = best_of_sweeps(record.seed_search) if record.seed_search is not None else None
    if final is not None:
        return final
    assert record.selection is not None
    j = record.selection.index
    score = record.selection.scores[j] if record.selection.scores else None
    return FinalRecord(program=record.programs[j].text, program_index=j, variant=0, score=score)
