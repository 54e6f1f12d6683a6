"""Stage III (c): the exported material must have finite maps.

A program can parse and check and still compute NaN or infinity (``Sqrt(-1)``, ``Log(0)``,
``Pow`` of a negative base, ...). The 8-bit maps quantise NaN to 0, so such a material can look
plausible while its float maps are broken. Before the export the chosen program is evaluated at
the export size; when any texel of any map is non-finite, the best round whose maps are all
finite takes its place: rounds ranked by the selection's scores (the critic's match scores when
no scorer ran, the latest first without either), each round's seed-search winner before the
round as written. The run records a warning either way (and the CLI prints it on stderr).
"""

from __future__ import annotations

from collections.abc import Callable, Iterator

import numpy as np

from matloom.author.records import FinalRecord, RunRecord
from matloom.engine.maps import MaterialMaps


def nonfinite_texels(maps: MaterialMaps) -> int:
    """How many texels have a NaN or infinite value in at least one map."""
    mask: np.ndarray | None = None
    for values in maps.arrays().values():
        bad = ~np.isfinite(values)
        if bad.ndim == 3:
            bad = bad.any(axis=2)
        mask = bad if mask is None else mask | bad
    return 0 if mask is None else int(np.count_nonzero(mask))


def _round_scores(record: RunRecord) -> list[float | None]:
    """Per round: the selection score, else the critic's match score, else None."""
    count = len(record.programs)
    selection = record.selection
    scores = list(selection.scores) if selection is not None else []
    if any(s is not None for s in scores):
        return [scores[k] if k < len(scores) else None for k in range(count)]
    critic: dict[int, float] = {}
    for c in record.critiques:
        if c.ok and c.match_score is not None:
            critic[c.program_index] = float(c.match_score)
    return [critic.get(k) for k in range(count)]


def round_order(record: RunRecord) -> list[int]:
    """Round indices, best first (ties to the earliest); latest first when none is scored."""
    scores = _round_scores(record)
    if not any(s is not None for s in scores):
        return list(range(len(scores) - 1, -1, -1))
    return sorted(range(len(scores)), key=lambda k: (scores[k] is None, -(scores[k] or 0.0), k))


def fallback_candidates(record: RunRecord) -> Iterator[FinalRecord]:
    """Replacements for a final material with non-finite maps, best first."""
    scores = _round_scores(record)
    sweeps = {s.program_index: s for s in record.seed_search.sweeps} if record.seed_search else {}
    for k in round_order(record):
        sweep = sweeps.get(k)
        if sweep is not None and sweep.best_variant != 0:
            yield FinalRecord(
                program=sweep.best_program,
                program_index=k,
                variant=sweep.best_variant,
                score=sweep.best_score,
            )
        score = sweep.original_score if sweep is not None else scores[k]
        yield FinalRecord(program=record.programs[k].text, program_index=k, variant=0, score=score)


def describe(final: FinalRecord) -> str:
    """``P3`` or ``P3 (seed variant 12)``."""
    variant = f" (seed variant {final.variant})" if final.variant else ""
    return f"P{final.program_index}{variant}"


def finite_final(
    record: RunRecord, final: FinalRecord, nonfinite: Callable[[str], int], size: int
) -> tuple[FinalRecord, str | None]:
    """(the material to export, a warning or None): ``final`` when its maps are finite, else
    the best candidate of :func:`fallback_candidates` that is, else ``final`` with its count.

    ``nonfinite(program)`` counts the program's non-finite texels at the export ``size``.
    """
    bad = nonfinite(final.program)
    if bad == 0:
        return final, None
    problem = (
        f"the selected material {describe(final)} has {bad:,} texel(s) with NaN or infinite "
        f"values at {size}x{size} (e.g. Sqrt or Log of a negative number)"
    )
    for candidate in fallback_candidates(record):
        if candidate.program != final.program and nonfinite(candidate.program) == 0:
            return candidate, (
                f"{problem}; exported {describe(candidate)} instead, the best round whose maps "
                "are all finite"
            )
    final.nonfinite_texels = bad
    return final, f"{problem}; no round has all-finite maps, so it is exported as it is"
