"""`matloom params` on every library entry reads like a parameter panel: every main parameter
has a label in words, and the front matter's colour and scalar slots carry their role's label.

Main parameters: every constant Define (a colour slot's three Defines are one colour
parameter), every literal layer channel, and every ``colours``/``[scalars]`` slot of the front
matter whose Defines are literal constants (derived shades follow their source and are not
parameters)."""

from __future__ import annotations

import re

import pytest

from matloom.lang import ast as A
from matloom.lang.params import words
from matloom.library.index import library
from matloom.library.labels import SCALAR_LABELS, entry_labels, entry_params

ENTRIES = sorted(library().entries)
LABEL = re.compile(r"[a-z0-9][a-z0-9 ()#.,-]*")


def _constant(program: A.Program, name: str) -> bool:
    d = program.define(name)
    return d is not None and isinstance(d.expr, A.Num | A.Neg)


@pytest.mark.parametrize("name", ENTRIES)
def test_every_entry_has_labelled_main_parameters(name: str) -> None:
    lib = library()
    entry, program = lib.entry(name), lib.ast(name)
    params = {p.address: p for p in entry_params(entry, program)}
    main = [p for p in params.values() if p.address.count(".") <= 1]
    assert main, f"{name}: no main parameters"
    for p in main:
        assert LABEL.fullmatch(p.label), f"{name}: {p.address} has label {p.label!r}"
    slots = 0
    for slot in entry.colours:
        if all(_constant(program, f"{slot}_{c}") for c in "rgb"):
            if program.define(slot) is not None:  # a Define named like the slot: components
                for c, comp in zip("rgb", ("red", "green", "blue"), strict=True):
                    assert params[f"define:{slot}_{c}"].label.endswith(f"colour {comp}")
                slots += 1
                continue
            p = params.get(f"define:{slot}")
            assert p is not None and p.kind == "colour", f"{name}: colour slot {slot}"
            assert p.label.endswith("colour") and p.label != slot, (name, p.label)
            slots += 1
    for scalar, kind in entry.scalars.items():
        if _constant(program, scalar):
            p = params[f"define:{scalar}"]
            assert p.label.startswith(SCALAR_LABELS.get(kind) or words(scalar)), (name, p.label)
            slots += 1
    assert slots, f"{name}: no colour or scalar slot is a parameter"


def test_labels_name_roles() -> None:
    lib = library()
    with_grout = [e for e in lib.entries.values() if list(e.roles.values()).count("grout") == 1]
    checked = 0
    for e in with_grout:
        slot = next(s for s, r in e.roles.items() if r == "grout")
        if not _constant(lib.ast(e.name), f"{slot}_r"):
            continue  # a derived shade: no parameter
        checked += 1
        labels = entry_labels(e, lib.ast(e.name))
        assert labels.get(f"define:{slot}", "").endswith("grout colour") or labels.get(
            f"define:{slot}_r", ""
        ).endswith("grout colour red")
    assert checked >= 5
