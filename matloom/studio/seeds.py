"""The noise seeds of a program, as the panel's seed chips show them, and their edits
(``/api/seeds``: reroll one, reroll all, pin).

Every call whose value depends on a seed (:func:`matloom.lang.seeds.uses_seed`) is one seed,
addressed like its parameter in :mod:`matloom.lang.params` --
``define:NAME.CALL.seed`` / ``layer:N.CHANNEL.CALL.seed``, the second call of a function in the
same owner ``CALL#2`` (counted across all the arguments of a channel). A seed the text leaves out
is ``auto``: evaluation draws it from the program seed 0 (the value shown); *pin* writes it, so
the material stays as it looks whatever the program seed, *reroll* writes a new random one.
"""

from __future__ import annotations

import secrets
from dataclasses import dataclass, replace
from typing import Any

from matloom.lang import ast as A
from matloom.lang.params import words
from matloom.lang.rewrite import map_program
from matloom.lang.seeds import SEED_LIMIT, canonicalize_seeds, uses_seed
from matloom.studio.program import checked, layer_label
from matloom.studio.protocol import ApiError
from matloom.studio.rewrite import program_text
from matloom.vocab import FUNCTIONS

SEED_OPS = ("reroll", "reroll_all", "pin")


@dataclass(frozen=True)
class SeedEntry:
    """One seed: its address, value (the drawn one when ``auto``), label, and the source
    offset of its call (how an edit finds it)."""

    address: str
    value: int
    auto: bool
    label: str
    call_start: int

    def to_json(self) -> dict[str, Any]:
        return {"address": self.address, "value": self.value, "auto": self.auto,
                "label": self.label}  # fmt: skip


def _owner(owner: tuple[Any, ...], program: A.Program) -> tuple[str, str]:
    """(address base, label) of a top-level expression's owner."""
    if owner[0] == "define":
        return f"define:{owner[1]}", words(owner[1])
    _, k, channel, _ = owner
    label = layer_label(k, program.layers[k])
    return f"layer:{k + 1}.{channel}", f"{label} {words(channel)}"


def seed_entries(program: A.Program) -> list[SeedEntry]:
    """Every literal or omitted seed of ``program``, in source order."""
    drawn = canonicalize_seeds(program, 0)
    auto_values = {
        n.span.start: n.arg("seed")
        for _, e in A.program_expressions(drawn)
        for n in A.walk(e)
        if isinstance(n, A.Call)
    }
    calls_by_owner: dict[str, tuple[str, list[A.Call]]] = {}
    for owner, expr in A.program_expressions(program):
        base, label = _owner(owner, program)
        calls = [n for n in A.walk(expr) if isinstance(n, A.Call)]
        calls_by_owner.setdefault(base, (label, []))[1].extend(calls)
    out: list[SeedEntry] = []
    for base, (label, calls) in calls_by_owner.items():
        seen: dict[str, int] = {}
        for call in sorted(calls, key=lambda c: c.span.start):
            spec = FUNCTIONS.get(call.func)
            if spec is None or spec.name == "Constant":
                continue
            seen[call.func] = seen.get(call.func, 0) + 1
            n = seen[call.func]
            if not uses_seed(call):
                continue
            name = call.func if n == 1 else f"{call.func}#{n}"
            node = call.arg("seed")
            auto = node is None
            if auto:
                node = auto_values.get(call.span.start)
            if not isinstance(node, A.Num) or isinstance(node.value, bool):
                continue  # a seed written as an expression: not a chip
            text = f"{label} {call.func}" if n == 1 else f"{label} {call.func} {n}"
            out.append(SeedEntry(f"{base}.{name}.seed", int(node.value), auto, text,
                                 call.span.start))  # fmt: skip
    return sorted(out, key=lambda s: s.call_start)


def _with_seeds(program: A.Program, new: dict[int, int]) -> A.Program:
    """``program`` with the seed of each call at source offset ``start`` set to ``new[start]``."""

    def fn(node: A.Node) -> A.Node:
        if isinstance(node, A.Call) and node.span.start in new and uses_seed(node):
            value = A.Num(new[node.span.start])
            args = {a.param: a for a in node.args}
            old = args.get("seed")
            args["seed"] = replace(old, value=value) if old else A.Arg("seed", value, True)
            order = FUNCTIONS[node.func].param_names
            return replace(
                node, args=tuple(sorted(args.values(), key=lambda a: order.index(a.param)))
            )
        return node

    return map_program(program, fn)


def seed_op(text: str, op: str, address: str | None) -> dict[str, Any]:
    """``/api/seeds``: ``reroll`` one seed (a new random value), ``reroll_all``, or ``pin``
    one auto seed (all of them without an address) to the value it draws now."""
    if op not in SEED_OPS:
        raise ApiError(400, f"unknown seed operation {op!r}; choose {', '.join(SEED_OPS)}")
    program = checked(text)
    entries = seed_entries(program)
    if op == "reroll_all":
        chosen = entries
    elif address is None:
        if op == "reroll":
            raise ApiError(400, "'address' names the seed to reroll")
        chosen = [e for e in entries if e.auto]
    else:
        chosen = [e for e in entries if e.address == address]
        if not chosen:
            known = ", ".join(e.address for e in entries[:8]) or "none"
            raise ApiError(400, f"no seed {address!r} in the program (seeds: {known})")
    if op == "pin":
        new = {e.call_start: e.value for e in chosen if e.auto}
    else:
        new = {e.call_start: secrets.randbelow(SEED_LIMIT) for e in chosen}
    if not new:
        return {"text": text, "changed": []}
    after = _with_seeds(program, new)
    changed = [e.address for e in chosen if e.call_start in new]
    return {"text": program_text(text, program, after), "changed": changed}
