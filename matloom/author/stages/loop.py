"""Critic loop v3's rules over a run's trajectory (docs/authoring.md, "Critic loop v3").

* **Revise from the best.** A revision continues from the best program so far (the scorer's
  score when a scorer is used, as in selection, else the critic's ``match_score``), not from
  the latest; ties go to the latest (a tie is no regression).
* **Drafts.** With ``drafts`` > 1, P_0 .. P_{drafts-1} are first drafts, each asked to take a
  different approach; every draft is critiqued, and the first revision continues from the
  best of them (the rule above). A draft has no parent: it is never "unchanged", and the
  critic's history starts with the first revision.
* **No visible change.** A revision whose previews differ from the program it revised by less
  than ``no_change_threshold`` (:func:`preview_difference`: the mean absolute difference over
  the worst 16 x 16 px block of 512, in levels of 255) is not critiqued, is reported to the
  generator and counts toward stopping.

:class:`LoopState` is rebuilt from the record by every ``Run.refine``: the decisions depend only
on recorded critiques and on renders and scores that are deterministic, so a resumed run makes
the same ones.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from matloom.author.prompts.revision import continue_text, no_change_text
from matloom.author.records import RunRecord

#: The preview difference is the mean absolute difference over the worst block of this share
#: of the image side (16 px at 512): a change to one small feature counts as much as the same
#: change over the whole image.
BLOCK_SHARE = 1 / 32


def block_difference(a: np.ndarray, b: np.ndarray, share: float = BLOCK_SHARE) -> float:
    """The largest mean absolute difference, in levels of 255, over square blocks of ``share``
    of the side of two same-sized 8-bit images (all colour channels; at least 1 px blocks, an
    edge strip narrower than a block left out)."""
    if a.shape != b.shape:
        raise ValueError(f"images of different shapes {a.shape} and {b.shape}")
    diff = np.abs(a.astype(np.int16) - b.astype(np.int16)).astype(np.float64)
    if diff.ndim == 3:
        diff = diff.mean(axis=2)
    rows, cols = diff.shape
    block = max(1, min(rows, cols, round(min(rows, cols) * share)))
    r, c = rows // block * block, cols // block * block
    blocks = diff[:r, :c].reshape(r // block, block, c // block, block).mean(axis=(1, 3))
    return float(blocks.max())


def preview_difference(a: Sequence[np.ndarray], b: Sequence[np.ndarray]) -> float:
    """How much two programs' previews differ (``no_change_threshold`` is in these units): the
    :func:`block_difference` of each layout, the largest over the layouts (``a`` and ``b``:
    the same layouts, in the same order, at the same size)."""
    if len(a) != len(b) or not a:
        raise ValueError("preview_difference needs the same layouts of both programs")
    return max(block_difference(x, y) for x, y in zip(a, b, strict=True))


def latest_best(values: Sequence[float | None]) -> int | None:
    """Index of the largest non-None value, the latest on ties (None when all are None)."""
    best, best_value = None, None
    for i, v in enumerate(values):
        if v is not None and (best_value is None or v >= best_value):
            best, best_value = i, v
    return best


@dataclass
class LoopState:
    """What the refinement loop knows of the trajectory so far."""

    #: P_k -> the program it was revised from (k - 1 unless a revision continued from the best).
    parents: dict[int, int] = field(default_factory=dict)
    #: P_k -> its preview difference from its parent, for revisions with no visible change.
    unchanged: dict[int, float] = field(default_factory=dict)
    #: P_k -> the scorer's score (revise-from-best with a scorer), computed once.
    scores: dict[int, float] = field(default_factory=dict)
    #: P_0 .. P_{drafts-1} are first drafts (``drafts``), not revisions.
    drafts: int = 1

    def parent(self, k: int) -> int:
        """The program P_k was revised from."""
        return self.parents.get(k, k - 1)

    def is_draft(self, k: int) -> bool:
        """True when P_k is a first draft (P_0 always is): it was revised from nothing."""
        return k < self.drafts

    def name(self, k: int) -> str | None:
        """What the generator calls P_k when there are drafts (``draft 2``, ``revision 1``);
        None: ``round k``, as without drafts."""
        if self.drafts == 1:
            return None
        return f"draft {k + 1}" if k < self.drafts else f"revision {k - self.drafts + 1}"


def score_text(critic: int | None, scorer: tuple[str, float] | None = None) -> str:
    """A program's standing in words: ``score 78/100``, or with a scorer
    ``mobileclip2 score 0.312, critic 78/100``."""
    critic_text = f"{critic}/100" if critic is not None else "no critic score"
    if scorer is None:
        return f"score {critic_text}"
    name, value = scorer
    return f"{name} score {value:.3f}, critic {critic_text}"


def critic_score(record: RunRecord, k: int) -> int | None:
    """The critic's score of P_k (None: not critiqued, or the critique failed)."""
    critique = record.critique_of(k)
    return critique.match_score if critique is not None and critique.ok else None


def continue_from(
    record: RunRecord, k: int, loop: LoopState, scorer: Callable[[int], float] | None
) -> int:
    """The program the revision after P_k starts from: P_k, or with ``revise_from_best`` the
    best so far (``scorer(j)``'s score when there is a scorer, as in selection, else the
    critic's); a revision with no visible change is never it. The first revision after
    several drafts always starts from the best draft, with or without ``revise_from_best``."""
    after_drafts = loop.drafts > 1 and k == loop.drafts - 1
    if not record.settings.revise_from_best and not after_drafts:
        return k
    values: list[float | None] = []
    for j in range(k + 1):
        score = critic_score(record, j)
        if j in loop.unchanged:
            values.append(None)
        elif scorer is not None:
            values.append(scorer(j))
        else:
            values.append(None if score is None else float(score))
    best = latest_best(values)
    return k if best is None else best


def guide(record: RunRecord, base: int, loop: LoopState) -> int:
    """The program whose critique guides a revision of ``base``: ``base``, or (a revision with
    no visible change has none) the nearest critiqued program it was revised from."""
    while not loop.is_draft(base) and record.critique_of(base) is None:
        base = loop.parent(base)
    return base


def loop_sections(  # noqa: PLR0913 - the loop's view of the run, passed in
    record: RunRecord,
    k: int,
    base: int,
    loop: LoopState,
    shown: Callable[[int], str],
    scorer_name: str | None,
) -> dict[str, Any]:
    """The loop v3 keyword arguments of :func:`~matloom.author.prompts.revision.revision_message`
    for the revision after P_k that continues from ``base`` (``shown(j)``: P_j as its author
    wrote it); empty in the paper."""
    cfg, sections = record.settings, {}
    if cfg.revise_from_best or base != k:  # base != k without it: the best of the drafts
        standings: dict[int, str | None] = {}
        for j in range(k + 1):
            scored = (scorer_name, loop.scores[j]) if scorer_name and j in loop.scores else None
            unchanged = j in loop.unchanged
            standings[j] = None if unchanged else score_text(critic_score(record, j), scored)
        program = shown(base) if base != k else None
        names = {j: n for j in range(k + 1) if (n := loop.name(j)) is not None}
        sections["continue_from"] = continue_text(base, k, standings, program, names)
        dropped = record.critique_of(k)
        if base != k and dropped is not None and dropped.ok and not loop.is_draft(k):
            sections["dropped"] = (loop.name(k) or f"round {k}", dropped.differences)
    if k in loop.unchanged and cfg.no_change_threshold is not None:
        sections["no_change"] = no_change_text(
            k, loop.unchanged[k], cfg.no_change_threshold, loop.name(k)
        )
    guiding = record.critique_of(guide(record, base, loop))
    if cfg.critic_structural and guiding is not None:
        sections["structural"] = guiding.structural
    return sections
