"""Words whose reading depends on what the program has, rewritten before the rules read them:
a shine condition the program lacks is a finish ("more matte, less oily" on skin that has no
oil overlay is less glossy, not a refusal: "no oil to reduce"); fallen leaves on a program
without leaves are the leaf litter overlay ("add some fallen leaves" to a lawn), while "more
dead leaves" on a pond that has some is more of its own."""

from __future__ import annotations

import re

from matloom.author.edit.conditions import present
from matloom.author.edit.plan import Context
from matloom.author.edit.targets import named_in_program


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


def reread(c: Context, asked: str) -> str:
    """``asked`` with the rewrites of this module that apply to the program."""
    return litter_as_condition(c, shine_as_finish(c, asked))


def litter_as_condition(c: Context, asked: str) -> str:
    """``asked`` with a phrase of fallen leaves (``litter`` of words.toml: "fallen leaves",
    "dead leaves") read as the condition word "leafy" when no part of the program is leaves."""
    if named_in_program(c.program, ["leaf", "leaves"], c.ew):
        return asked
    for phrase in sorted(c.ew["litter"], key=len, reverse=True):
        asked = re.sub(rf"\b{re.escape(phrase)}\b", "leafy", asked)
    return asked
