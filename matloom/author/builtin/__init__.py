"""Built-in offline author: convincing MatLoom programs from text, with no model and no network.

``author(prompt, seed=0)`` interprets the prompt (colours, materials, patterns, finishes,
conditions, scale, sizes, counts), picks the best recipe of the hand-written library by a
transparent score, fills its named slots, adds condition overlays and returns a canonical,
checker-clean program with an explanation of every choice.
"""

from __future__ import annotations

from matloom.author.builtin.compose import AuthorResult, author, derive_seed
from matloom.author.builtin.interpret import Interpretation, interpret
from matloom.author.builtin.recipes import FAMILIES, REGISTRY, Recipe

__all__ = [
    "FAMILIES",
    "REGISTRY",
    "AuthorResult",
    "Interpretation",
    "Recipe",
    "author",
    "derive_seed",
    "interpret",
]
