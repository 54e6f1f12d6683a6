"""Transparent recipe scoring: which recipe fits a prompt, and why.

The score of a recipe is the sum of the weights of its tags found in the prompt (a tag is a word
or a phrase; plural forms match through a light stemmer) plus a bonus for each requested pattern
the recipe realises. Words in the head clause (before the first ':' '.' ',' or 'with') name the
material, so their matches count 1.4 times. A recipe's first pattern is its primary one (full
bonus), others count half. A pattern recipe that takes a micro-texture gains a further bonus
when the prompt names a material it can render as that texture ("checkered vinyl" is a
checker print on vinyl, not plain vinyl). Every contribution is kept as a readable reason.
Ties go to the recipe registered first (the library lists the everyday recipes first).
"""

from __future__ import annotations

from dataclasses import dataclass, field

from matloom.author.builtin.interpret import Interpretation
from matloom.author.builtin.micro import MICRO_WORDS
from matloom.author.builtin.recipes import REGISTRY, Recipe

HEAD_BONUS = 1.4
MICRO_BONUS = 4.0
PATTERN_BONUS = 3.0
MIN_SCORE = 2.0


@dataclass
class Scored:
    """A recipe with its score and the reasons that add up to it."""

    recipe: Recipe
    score: float
    reasons: list[str] = field(default_factory=list)
    matched: set[int] = field(default_factory=set)


#: words that say "this is cloth": every fabric-family recipe gains FAMILY_BONUS when present.
FABRIC_CONTEXT = frozenset(
    """fabric fabrics cloth textile textiles woven knit knitted cotton polyester polester wool
    nylon silk linen yarn yarns thread threads garment sewn stitching weave weaving""".split()
)
FAMILY_BONUS = 2.0


def _index(it: Interpretation) -> dict[str, list[int]]:
    """Word/stem -> positions (negated tokens left out), cached on the interpretation."""
    cached = getattr(it, "_phrase_index", None)
    if cached is not None:
        return cached
    index: dict[str, list[int]] = {}
    for i, tok in enumerate(it.tokens):
        if i in it.negated:
            continue
        index.setdefault(tok.text, []).append(i)
        if it.stems[i] != tok.text:
            index.setdefault(it.stems[i], []).append(i)
    it._phrase_index = index  # type: ignore[attr-defined]
    return index


def find_phrase(phrase: str, it: Interpretation, skip: set[int] | None = None) -> int | None:
    """Index of the first non-negated occurrence of ``phrase`` (words or stems), else None.

    Occurrences made only of tokens in ``skip`` (e.g. words used as colours) are ignored.
    """
    parts = phrase.split()
    index = _index(it)
    for start in index.get(parts[0], ()):
        ok = all(start + k in index.get(p, ()) for k, p in enumerate(parts[1:], 1))
        if ok and not (skip and all(start + k in skip for k in range(len(parts)))):
            return start
    return None


def find_all(phrase: str, it: Interpretation) -> list[int]:
    """Every non-negated start position of ``phrase``."""
    parts = phrase.split()
    index = _index(it)
    return [
        start
        for start in index.get(parts[0], ())
        if all(start + k in index.get(p, ()) for k, p in enumerate(parts[1:], 1))
    ]


def score_recipe(recipe: Recipe, it: Interpretation) -> Scored:
    """Score one recipe against an interpretation."""
    out = Scored(recipe, 0.0)
    for tag, weight in recipe.tags.items():
        pos = find_phrase(tag, it, it.colour_tokens)
        if pos is None:
            continue
        in_head = pos < it.head_end
        gain = weight * (HEAD_BONUS if in_head else 1.0)
        out.score += gain
        out.reasons.append(f"'{tag}' +{gain:.1f}{' (head)' if in_head else ''}")
        out.matched.update(range(pos, pos + len(tag.split())))
    if recipe.family == "fabric" and any(t.text in FABRIC_CONTEXT for t in it.tokens):
        out.score += FAMILY_BONUS
        out.reasons.append(f"fabric context +{FAMILY_BONUS:.1f}")
    realised = False
    for pattern in it.patterns:
        if pattern in recipe.patterns:
            primary = pattern == recipe.patterns[0]
            gain = PATTERN_BONUS * (1.0 if primary else 0.5)
            gain *= HEAD_BONUS if pattern in it.head_patterns else 1.0
            out.score += gain
            realised = True
            out.reasons.append(f"pattern {pattern} +{gain:.1f}{'' if primary else ' (secondary)'}")
    if realised and recipe.micro is not None:
        word = next((t.text for t in it.tokens if t.text in MICRO_WORDS), None)
        if word is not None:
            out.score += MICRO_BONUS
            out.reasons.append(f"pattern on '{word}' (micro-texture) +{MICRO_BONUS:.1f}")
    return out


def rank(it: Interpretation) -> list[Scored]:
    """All recipes with a positive score, best first (stable: registry order breaks ties)."""
    scored = [score_recipe(r, it) for r in REGISTRY.values()]
    scored = [s for s in scored if any(not r.startswith("fabric context") for r in s.reasons)]
    scored.sort(key=lambda s: -s.score)
    return scored
