"""Stage III (a): trajectory selection (reference-engine.md §8.5).

With a scorer, every trajectory program is rendered at ``size`` (512 by default) and scored for
the prompt; the best wins, ties going to the earliest. Without a scorer the critic's
``match_score`` decides (ties to the earliest); without usable critiques the last program is
kept. A single-program trajectory selects P0.
"""

from __future__ import annotations

import time
from collections.abc import Callable, Sequence

import numpy as np

from matloom.author.records import CritiqueRecord, SelectionRecord
from matloom.author.scorers.base import TextImageScorer

Render = Callable[[int], np.ndarray]


def earliest_argmax(values: Sequence[float | None]) -> int:
    """Index of the largest non-None value, the earliest on ties (0 if all are None)."""
    best, best_value = 0, None
    for i, v in enumerate(values):
        if v is not None and (best_value is None or v > best_value):
            best, best_value = i, v
    return best


def select_program(
    count: int,
    *,
    prompt: str,
    critiques: Sequence[CritiqueRecord],
    scorer: TextImageScorer | None,
    render: Render,
    size: int,
) -> SelectionRecord:
    """Choose one of P_0..P_{count-1}; ``render(k)`` returns P_k's preview at ``size``."""
    start = time.perf_counter()
    if count <= 1:
        return SelectionRecord(method="single", index=0, seconds=time.perf_counter() - start)
    if scorer is not None:
        images = [render(k) for k in range(count)]
        scores = [float(s) for s in scorer.score(images, prompt)]
        return SelectionRecord(
            method="scorer",
            index=earliest_argmax(scores),
            scorer=scorer.name,
            size=size,
            scores=scores,
            seconds=time.perf_counter() - start,
        )
    by_index = {c.program_index: c for c in critiques if c.ok}
    critic_scores: list[float | None] = [
        float(by_index[k].match_score)
        if k in by_index and by_index[k].match_score is not None
        else None
        for k in range(count)
    ]
    if any(s is not None for s in critic_scores):
        return SelectionRecord(
            method="critic",
            index=earliest_argmax(critic_scores),
            scores=critic_scores,
            seconds=time.perf_counter() - start,
        )
    return SelectionRecord(method="last", index=count - 1, seconds=time.perf_counter() - start)
