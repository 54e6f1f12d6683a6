"""Applying an edit to a program: parameter assignments (the addresses of
:mod:`matloom.lang.params` plus the channel bases, pattern defaults and colour slots of
:mod:`matloom.author.edit.bases`), View changes, replaced lines (a Define by name, a layer by
number) and added lines (new Defines after the others, new layers on top)."""

from __future__ import annotations

import re
from collections.abc import Mapping, Sequence
from dataclasses import replace
from typing import Any

from matloom.author.edit.bases import (
    base_params,
    expand_slots,
    implicit_params,
    is_base,
    set_bases,
    set_implicit,
    slot_params,
)
from matloom.lang import ast as A
from matloom.lang.api import analyse
from matloom.lang.diagnostics import ProgramError
from matloom.lang.params import Param, list_params, set_params
from matloom.lang.printer import format_program

#: The View fields an edit may set.
VIEW_KEYS = ("tileable", "unit_m", "window")


def parse_program(text: str) -> A.Program:
    program, diags = analyse(text)
    if program is None or any(d.is_error for d in diags):
        raise ProgramError(diags, text)
    return program


def all_params(program: A.Program) -> list[Param]:
    """The exposed parameters and the channel bases, as the edits see them."""
    params = list_params(program)
    extra = implicit_params(program, params) + slot_params(params) + base_params(program)
    return params + extra


def set_view(program: A.Program, view: Mapping[str, Any]) -> A.Program:
    """``program`` with View changes: ``tileable``, ``unit_m`` and ``window`` ([x1, y1, x2,
    y2], the sampling window)."""
    if not view:
        return program
    unknown = set(view) - set(VIEW_KEYS)
    if unknown:
        raise ValueError(f"View changes may set only {', '.join(VIEW_KEYS)}, not {sorted(unknown)}")
    decl = program.view or A.ViewDecl(0.0, 0.0, 1.0, 1.0)
    fields = {k: v for k, v in view.items() if k != "window"}
    if "unit_m" in fields and not (_is_number(fields["unit_m"]) and fields["unit_m"] > 0):
        raise ValueError(f"unit_m must be a positive number, got {fields['unit_m']!r}")
    if "window" in view:
        w = view["window"]
        if not (isinstance(w, list | tuple) and len(w) == 4 and all(_is_number(v) for v in w)):
            raise ValueError(f"window is four numbers [x1, y1, x2, y2], got {w!r}")
        x1, y1, x2, y2 = (float(v) for v in w)
        if x2 <= x1 or y2 <= y1:
            raise ValueError(f"window {list(w)}: x2 and y2 must exceed x1 and y1")
        fields.update(x1=x1, y1=y1, x2=x2, y2=y2)
    return replace(program, view=replace(decl, **fields))


def _parse_lines(text: str) -> A.Program:
    from matloom.lang.parser import parse_source

    parsed, _ = parse_source(text)
    if parsed is None:
        raise ValueError(f"cannot parse {text!r}")
    return parsed


def replace_lines(program: A.Program, lines: Mapping[str, str]) -> A.Program:
    """``program`` with named lines replaced: ``define:NAME`` -> the new Define's text
    (``Define(NAME, ...)``), ``layer:N`` -> the new layer's text (``Layer(...)...``)."""
    if not lines:
        return program
    defines = list(program.defines)
    layers = list(program.layers)
    for address, text in lines.items():
        m = re.fullmatch(r"(define):(\w+)|(layer):(\d+)", address)
        if m is None:
            raise ValueError(f"cannot replace {address!r}: give define:NAME or layer:N")
        if m.group(1):
            name = m.group(2)
            k = next((i for i, d in enumerate(defines) if d.name == name), None)
            if k is None:
                raise ValueError(f'no Define named {name!r} (new lines go under "add")')
            new = _parse_lines(f"{text}\nMaterial(Layer(1).roughness(0.5))").defines
            if len(new) != 1 or new[0].name != name:
                raise ValueError(f"{address}: expected one Define({name}, ...), got {text!r}")
            defines[k] = new[0]
        else:
            n = int(m.group(4))
            if not 0 < n <= len(layers):
                raise ValueError(
                    f'no layer {n} (the program has {len(layers)}; new layers go under "add")'
                )
            new_layers = _parse_lines(f"Material({text})").layers
            if len(new_layers) != 1:
                raise ValueError(f"{address}: expected one Layer(...), got {text!r}")
            layers[n - 1] = new_layers[0]
    return replace(program, defines=tuple(defines), layers=tuple(layers))


def add_lines(program: A.Program, lines: Sequence[str]) -> A.Program:
    """``program`` with new lines: each ``Define(NAME, ...)`` after the Defines (a name taken
    already is an error), each ``Layer(...)...`` on top of the layers, in order."""
    if not lines:
        return program
    if isinstance(lines, str) or not all(isinstance(t, str) for t in lines):
        raise ValueError('"add" is a list of lines: Define(NAME, ...) or Layer(...)...')
    defines = list(program.defines)
    layers = list(program.layers)
    taken = {d.name for d in defines}
    for text in lines:
        t = text.strip()
        if t.startswith("Define("):
            new = _parse_lines(f"{t}\nMaterial(Layer(1).roughness(0.5))").defines
            if len(new) != 1:
                raise ValueError(f"expected one Define(NAME, ...), got {text!r}")
            if new[0].name in taken:
                raise ValueError(f"Define {new[0].name!r} exists already (replace it instead)")
            taken.add(new[0].name)
            defines.append(new[0])
        elif t.startswith("Layer("):
            new_layers = _parse_lines(f"Material({t})").layers
            if len(new_layers) != 1:
                raise ValueError(f"expected one Layer(...), got {text!r}")
            layers.append(new_layers[0])
        else:
            raise ValueError(f"an added line is Define(NAME, ...) or Layer(...)..., not {text!r}")
    return replace(program, defines=tuple(defines), layers=tuple(layers))


def apply_edit(
    program: A.Program,
    assignments: Mapping[str, Any],
    view: Mapping[str, Any] | None = None,
    lines: Mapping[str, str] | None = None,
    add: Sequence[str] | None = None,
) -> tuple[str, list[str]]:
    """Apply an edit; return the new program's text (comments kept) and the warnings (values
    clamped into range). Raises ValueError for an unknown address or a bad value."""
    assignments = expand_slots({k: _value(k, v) for k, v in assignments.items()})
    prog = add_lines(replace_lines(program, lines or {}), add or ())
    listed = list_params(prog)
    implicit = {p.address for p in implicit_params(prog, listed)}
    bases = {k: v for k, v in assignments.items() if is_base(k)}
    unwritten = {k: v for k, v in assignments.items() if k in implicit}
    plain = {
        k: (tuple(v) if isinstance(v, list) else v)
        for k, v in assignments.items()
        if k not in bases and k not in unwritten
    }
    warnings: list[str] = []
    for k, v in bases.items():
        if isinstance(v, tuple):
            clamped = tuple(min(255.0, max(0.0, c)) for c in v)
            if clamped != v:
                warnings.append(f"{k}: {list(v)} is outside [0, 255]; clamped to {list(clamped)}")
                bases[k] = clamped
    if bases:
        prog = set_bases(prog, bases)
    if unwritten:
        prog = set_implicit(prog, unwritten)
    prog = set_view(prog, view or {})
    if plain:
        text, more = set_params(prog, plain)
        return text, warnings + more
    return format_program(prog, comments=True), warnings


def _value(address: str, v: Any) -> Any:
    """A value as an edit gives it: a number, or three numbers (a list becomes a tuple)."""
    if isinstance(v, list | tuple):
        if len(v) != 3 or not all(_is_number(c) for c in v):
            raise ValueError(f"{address}: a colour is three numbers [r, g, b], got {v!r}")
        return tuple(float(c) for c in v)
    if not _is_number(v):
        raise ValueError(f"{address}: expected a number, got {v!r}")
    return v


def _is_number(v: Any) -> bool:
    return isinstance(v, int | float) and not isinstance(v, bool)
