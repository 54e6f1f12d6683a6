"""Shine conditions read as a finish: "more matte, less oily" on skin that has no oil overlay is
less glossy, not a refusal ("no oil to reduce")."""

from __future__ import annotations

import re

from matloom.author.edit.conditions import present
from matloom.author.edit.plan import Context


def shine_as_finish(c: Context, asked: str) -> str:
    """``asked`` with a shine condition after a ``flip`` word ("less oily", "too greasy": the
    ``shine_conditions`` of words.toml) read as "glossy" when the program has none of that
    condition to reduce (no amount, cover or layer of it: "fewer oil stains" on an oil-stained
    floor stays a condition)."""
    ew = c.ew
    flips = "|".join(sorted(map(re.escape, ew["flip"])))
    for word in sorted(ew["shine_conditions"]):
        if not present(c, (word, *ew.conditions.get(word, ()))):
            asked = re.sub(rf"\b((?:{flips})\s+)({re.escape(word)})\b", r"\1glossy", asked)
    return asked
