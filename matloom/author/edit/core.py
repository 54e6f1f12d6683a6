"""Edit a program by words: plan (rules or a model), apply, check, and verify locality.

:func:`edit` is what ``matloom edit`` and ``matloom.edit`` run. An edit is a set of parameter
assignments (addresses of :mod:`matloom.lang.params`, plus the channel bases of
:mod:`matloom.author.edit.bases`), View changes (``tileable``, ``unit_m``) and, from a model
only, replacements of whole named lines (a Define by name, a layer by number). The edited
program must check clean, keep every seed (unless the request asks about seeds), and change
no map outside its intended channels on more than 1 % of texels
(:mod:`matloom.runtime.locality`).
"""

from __future__ import annotations

import re
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field, replace
from typing import TYPE_CHECKING, Any

from matloom.author.edit.bases import (
    base_params,
    expand_slots,
    implicit_params,
    is_base,
    set_bases,
    set_implicit,
    slot_params,
)
from matloom.author.edit.rules import EditRefused, Plan, plan_edit
from matloom.lang import ast as A
from matloom.lang.api import analyse
from matloom.lang.diagnostics import ProgramError
from matloom.lang.params import Param, list_params, set_params
from matloom.lang.printer import format_program
from matloom.runtime.locality import LOCALITY_SIZE, LocalityReport, locality

if TYPE_CHECKING:
    from matloom.engine.session import Session

_SEED_WORDS = frozenset(
    {"seed", "seeds", "reseed", "variation", "variant", "randomise", "randomize"}
)


class EditError(ValueError):
    """An edit that could not be made (a bad answer after every repair turn, a program that
    does not parse): one line."""


@dataclass(frozen=True)
class Change:
    """One parameter the edit changed."""

    address: str
    label: str
    before: Any
    after: Any

    def to_json(self) -> dict[str, Any]:
        return {
            "address": self.address,
            "label": self.label,
            "before": self.before,
            "after": self.after,
        }


@dataclass(frozen=True)
class EditReport:
    """What an edit did: the request, the plan, the changed parameters and the locality."""

    request: str
    mode: str  # "rules" or "model"
    plan: dict[str, Any]
    changes: list[Change]
    warnings: list[str]
    locality: LocalityReport
    turns: int = 0
    attempts: list[str] = field(default_factory=list)

    @property
    def ok(self) -> bool:
        return self.locality.ok

    def to_json(self) -> dict[str, Any]:
        return {
            "request": self.request,
            "mode": self.mode,
            "edit": self.plan,
            "changed": [c.to_json() for c in self.changes],
            "warnings": list(self.warnings),
            "locality": self.locality.to_json(),
            "ok": self.ok,
            "repair_turns": self.turns,
            "rejected": list(self.attempts),
        }


@dataclass(frozen=True)
class EditResult:
    """The edited program's text and the report."""

    program: str
    report: EditReport


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


def _view(program: A.Program, view: Mapping[str, Any]) -> A.Program:
    if not view:
        return program
    allowed = {"tileable", "unit_m"}
    unknown = set(view) - allowed
    if unknown:
        raise ValueError(f"View changes may set only tileable and unit_m, not {sorted(unknown)}")
    decl = program.view or A.ViewDecl(0.0, 0.0, 1.0, 1.0)
    return replace(program, view=replace(decl, **dict(view)))


def replace_lines(program: A.Program, lines: Mapping[str, str]) -> A.Program:
    """``program`` with named lines replaced: ``define:NAME`` -> the new Define's text
    (``Define(NAME, ...)``), ``layer:N`` -> the new layer's text (``Layer(...)...``)."""
    if not lines:
        return program
    from matloom.lang.parser import parse_source

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
                raise ValueError(f"no Define named {name!r}")
            parsed, diags = parse_source(f"{text}\nMaterial(Layer(1).roughness(0.5))")
            new = parsed.defines if parsed is not None else ()
            if len(new) != 1 or new[0].name != name:
                raise ValueError(f"{address}: expected one Define({name}, ...), got {text!r}")
            defines[k] = new[0]
        else:
            n = int(m.group(4))
            if not 0 < n <= len(layers):
                raise ValueError(f"no layer {n} (the program has {len(layers)})")
            parsed, diags = parse_source(f"Material({text})")
            new_layers = parsed.layers if parsed is not None else ()
            if len(new_layers) != 1:
                raise ValueError(f"{address}: expected one Layer(...), got {text!r}")
            layers[n - 1] = new_layers[0]
    return replace(program, defines=tuple(defines), layers=tuple(layers))


def apply_edit(
    program: A.Program,
    assignments: Mapping[str, Any],
    view: Mapping[str, Any] | None = None,
    lines: Mapping[str, str] | None = None,
) -> tuple[str, list[str]]:
    """Apply an edit; return the new program's text (comments kept) and the warnings (values
    clamped into range). Raises ValueError for an unknown address or a bad value."""
    assignments = expand_slots({k: _value(k, v) for k, v in assignments.items()})
    prog = replace_lines(program, lines or {})
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
    prog = _view(prog, view or {})
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


def _seeds(program: A.Program) -> list[tuple[str, Any]]:
    return [(p.address, p.value) for p in list_params(program) if p.kind == "seed"]


def verify(
    before: A.Program,
    text: str,
    request: str,
    intended: Sequence[str],
    size: int,
    session: Session | None,
) -> tuple[A.Program, LocalityReport]:
    """Check the edited text (errors raise :class:`ProgramError`), that seeds are unchanged
    (ValueError) and compute the locality report."""
    after = parse_program(text)
    if not (_SEED_WORDS & set(re.findall(r"[a-z]+", request.lower()))):
        if _seeds(before) != _seeds(after):
            raise ValueError("the edit changed noise seeds, which the request did not ask for")
    return after, locality(before, after, intended, size=size, session=session)


def changes(before: A.Program, after: A.Program) -> list[Change]:
    """Parameters whose value differs between the two programs (by address)."""
    old = {p.address: p for p in all_params(before)}
    out = []
    for p in all_params(after):
        q = old.get(p.address)
        if q is not None and q.value != p.value:
            out.append(Change(p.address, p.label, _plain(q.value), _plain(p.value)))
    if before.view != after.view:
        out.append(Change("view", "View", _view_json(before.view), _view_json(after.view)))
    return out


def _plain(v: Any) -> Any:
    return list(v) if isinstance(v, tuple) else v


def _view_json(v: A.ViewDecl | None) -> Any:
    if v is None:
        return None
    return {"window": list(v.as_tuple()), "tileable": v.tileable, "unit_m": v.unit_m}


def edit_offline(
    text: str, request: str, *, size: int = LOCALITY_SIZE, session: Session | None = None
) -> EditResult:
    """The rule-based edit of ``request`` (raises :class:`EditRefused` when no rule maps it)."""
    before = parse_program(text)
    plan: Plan = plan_edit(before, all_params(before), request)
    new_text, warnings = apply_edit(before, plan.assignments, plan.view)
    after, report = verify(before, new_text, request, plan.intended, size, session)
    return EditResult(
        new_text,
        EditReport(request, "rules", plan.to_json(), changes(before, after), warnings, report),
    )


__all__ = [
    "Change",
    "EditError",
    "EditRefused",
    "EditReport",
    "EditResult",
    "apply_edit",
    "edit_offline",
]
