"""Text-image scorers for trajectory selection and seed search (see :mod:`.base`)."""

from matloom.author.scorers.base import (
    ScorerUnavailableError,
    TextImageScorer,
    register_scorer,
)
from matloom.author.scorers.lookup import get_scorer, scorer_names

__all__ = [
    "ScorerUnavailableError",
    "TextImageScorer",
    "get_scorer",
    "register_scorer",
    "scorer_names",
]
