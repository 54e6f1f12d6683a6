"""Parameter labels of a library entry, from its front matter (``colours``, ``[roles]``,
``[scalars]``), so that ``matloom params`` on an entry reads like a parameter panel: "grout
colour", "roughness", "wear amount" rather than ``gap_r`` or ``rough``."""

from __future__ import annotations

from collections import Counter

from matloom.lang import ast as A
from matloom.lang.params import Param, list_params, words
from matloom.library.entry import Entry

#: ``[scalars]`` kind -> label (``other``: the Define's name in words).
SCALAR_LABELS: dict[str, str] = {
    "roughness": "roughness",
    "relief": "relief amount",
    "wear": "wear amount",
    "gloss": "gloss (clear coat)",
    "metallic": "metalness",
    "gap": "gap width",
    "cover": "coverage amount",
}
#: Colour roles named in a label when one slot has them ("grout colour").
_ROLE_NAMED = frozenset({"grout", "frame"})


def entry_labels(entry: Entry, program: A.Program | str | None = None) -> dict[str, str]:
    """Address -> label for the entry's colour slots (``define:SLOT``, or each component
    ``define:SLOT_r``... where the slot is no colour parameter) and ``[scalars]`` slots
    (``define:NAME``). ``program``: the entry's program (default: its text), parsed or not."""
    params = list_params(program if program is not None else entry.program)
    kinds = {p.address: p.kind for p in params}
    out: dict[str, str] = {}
    roles = Counter(entry.role(s) for s in entry.colours)
    for slot in entry.colours:
        role = entry.role(slot)
        name = words(slot)
        if role in _ROLE_NAMED and role not in name.split():
            name = role if roles[role] == 1 else f"{name} {role}"
        if kinds.get(f"define:{slot}") == "colour":
            out[f"define:{slot}"] = f"{name} colour"
            continue
        for c, comp in zip("rgb", ("red", "green", "blue"), strict=True):
            if f"define:{slot}_{c}" in kinds:
                out[f"define:{slot}_{c}"] = f"{name} colour {comp}"
    counts = Counter(entry.scalars.values())
    for name, kind in entry.scalars.items():
        label = SCALAR_LABELS.get(kind) or words(name)
        if kind in SCALAR_LABELS and counts[kind] > 1:
            label = f"{label} ({words(name)})"
        out[f"define:{name}"] = label
    return out


def entry_params(entry: Entry, program: A.Program | None = None) -> list[Param]:
    """:func:`~matloom.lang.params.list_params` of the entry's program with its labels."""
    prog = program if program is not None else entry.program
    return list_params(prog, entry_labels(entry, prog))
