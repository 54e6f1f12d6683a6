"""Edit a program by words: plan (rules or a model), apply, check, and verify locality.

:func:`edit` is what ``matloom edit`` and ``matloom.edit`` run. An edit is a set of parameter
assignments (addresses of :mod:`matloom.lang.params`, plus the channel bases of
:mod:`matloom.author.edit.bases`), View changes (``tileable``, ``unit_m``, ``window``),
replacements of whole named lines (a Define by name, a layer by number) and added lines (new
Defines, new layers on top: a library overlay, or a model's new structure); see
:mod:`matloom.author.edit.apply`. The edited program must check clean, keep every existing seed
(unless the request asks about seeds; added lines bring new ones), and change no map outside
its intended channels on more than 1 % of texels (:mod:`matloom.runtime.locality`).
"""

from __future__ import annotations

import re
from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

from matloom.author.edit.apply import (
    add_lines,
    all_params,
    apply_edit,
    parse_program,
    replace_lines,
    set_view,
)
from matloom.author.edit.lexicon import edit_words, tokens
from matloom.author.edit.plan import word_intensity
from matloom.author.edit.rules import EditRefused, Plan, plan_edit
from matloom.author.edit.visible import VISIBLE_SIZE, lit_changes, visible_changes
from matloom.engine.evaluate import evaluate
from matloom.lang import ast as A
from matloom.lang.layout import keep_layout
from matloom.lang.params import list_params
from matloom.lang.printer import format_expr, format_layer
from matloom.library.data import words
from matloom.runtime.locality import (
    LOCALITY_SIZE,
    LocalityReport,
    allowed_outputs,
    compare_maps,
)

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


def _seeds(program: A.Program) -> dict[str, Any]:
    return {p.address: p.value for p in list_params(program) if p.kind == "seed"}


def changed_seeds(before: A.Program, after: A.Program) -> list[str]:
    """Seed addresses of ``before`` whose value differs in ``after``. Seeds of added lines are
    new (an added noise needs one); a seed whose line was removed or rewritten without it is
    gone, not changed."""
    old, new = _seeds(before), _seeds(after)
    return [a for a, v in old.items() if a in new and new[a] != v]


@dataclass(frozen=True)
class Verified:
    """The checked edited program, its locality report and how much of it shows."""

    program: A.Program
    locality: LocalityReport
    visible: dict[str, float]
    #: the fraction of the lit preview's pixels that moved at all (``visible["lit"]``: visibly)
    lit_moved: float = 0.0

    def shows(self, fraction: float, channels: Sequence[str] = ()) -> bool:
        """Whether a map the edit meant to change moved visibly on ``fraction`` of texels.

        With ``channels`` (the request's own: the plan's intended channels), the change is
        measured where a lit preview shows it: a relief in the lit preview itself (a height map
        may double its range, and its normals move on half the texels, and still not show),
        another channel in its own map; else in any map the locality allows."""
        seen = [SEEN_AS.get(ch, ch) for ch in channels if ch != "alpha"]
        names = [n for n in dict.fromkeys(seen) if n in self.visible]
        if not names:
            names = [n for n in self.visible if n in self.locality.allowed]
        for n in names:
            v = self.visible[n]
            if n == "lit":
                moved = self.lit_moved
            else:
                moved = self.locality.maps[n].fraction if n in self.locality.maps else v
            # visible on enough of the map, or on most of the texels that moved at all (a
            # part that covers little of the surface: the knots, the veins, the worn patches)
            if v >= fraction or (v >= PART_FRACTION and moved > 0 and v / moved >= PART_SHARE):
                return True
        return False


#: A change confined to a part shows when it is visible on this share of the texels it moved
#: (and on at least ``PART_FRACTION`` of the map).
PART_SHARE = 0.3
PART_FRACTION = 0.004


#: The map a change of a channel shows in, in a lit preview ("lit": the lit preview itself).
#: Channels whose change is judged in the lit preview: a relief, and a gloss (a roughness
#: from 0.92 to 0.41 moves the roughness map everywhere but 0.02 % of the lit preview's pixels
#: visibly; 0.25 moves 14 %).
SEEN_AS = {"height": "lit", "roughness": "lit"}


def _seen_name(channel: str) -> str:
    seen = SEEN_AS.get(channel, channel)
    return "lit preview" if seen == "lit" else seen


def verify(
    before: A.Program,
    text: str,
    request: str,
    intended: Sequence[str],
    size: int,
    session: Session | None,
) -> Verified:
    """Check the edited text (errors raise :class:`ProgramError`), that existing seeds are
    unchanged (ValueError), and compute the locality report and the visible change."""
    after = parse_program(text)
    if not (_SEED_WORDS & set(re.findall(r"[a-z]+", request.lower()))):
        moved = changed_seeds(before, after)
        if moved:
            raise ValueError(
                f"the edit changed noise seeds ({', '.join(moved[:3])}), which the request did "
                "not ask for; new lines may bring new seeds, existing ones stay"
            )
    intended_t = tuple(dict.fromkeys(intended))
    allowed_outputs(intended_t)  # validates the names
    a = evaluate(before, size, size, session=session)
    b = evaluate(after, size, size, session=session)
    if size != VISIBLE_SIZE:  # what shows does not depend on the locality grid
        va = evaluate(before, VISIBLE_SIZE, VISIBLE_SIZE, session=session)
        vb = evaluate(after, VISIBLE_SIZE, VISIBLE_SIZE, session=session)
    else:
        va, vb = a, b
    visible = visible_changes(va, vb)
    lit_moved = 0.0
    if set(SEEN_AS) & set(intended_t):
        visible["lit"], lit_moved = lit_changes(va, vb)
    return Verified(after, compare_maps(a, b, intended_t), visible, lit_moved)


def _line_texts(program: A.Program) -> dict[str, str]:
    out = {f"define:{d.name}": f"Define({d.name}, {format_expr(d.expr)})" for d in program.defines}
    for i, layer in enumerate(program.layers):
        out[f"layer:{i + 1}"] = " ".join(x.strip() for x in format_layer(layer))
    return out


def changes(before: A.Program, after: A.Program) -> list[Change]:
    """Parameters whose value differs between the two programs (by address), then the lines
    added, and the lines rewritten with no parameter of theirs changed."""
    old = {p.address: p for p in all_params(before)}
    out = []
    for p in all_params(after):
        q = old.get(p.address)
        if q is not None and q.value != p.value:
            out.append(Change(p.address, p.label, _plain(q.value), _plain(p.value)))
    if before.view != after.view:
        out.append(Change("view", "View", _view_json(before.view), _view_json(after.view)))
    was, now = _line_texts(before), _line_texts(after)
    for address, text in now.items():
        if address not in was:
            label = "added Define" if address.startswith("define:") else "added layer"
            out.append(Change(address, label, None, text))
        elif text != was[address] and not any(
            c.address.startswith(f"{address}.") or c.address == address for c in out
        ):
            out.append(Change(address, "rewritten line", was[address], text))
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
    """The rule-based edit of ``request`` (raises :class:`EditRefused` when no rule maps it).

    A graded step whose change does not show (no intended map moved visibly on
    ``visible_fraction`` of its texels) is planned again at a greater strength (times
    ``escalate``, up to ``max_strength``; "slightly" or "a bit" start from a smaller step and
    so stop at the smallest one that shows). The change is measured in the request's own
    channels (a relief in the lit preview). A change that still does not show at
    ``max_strength`` is refused with the reason; one whose parameters reached their limits (all
    the wear removed) is kept with a warning, as is a "slightly" step."""
    ew = edit_words()
    before = parse_program(text)
    params = all_params(before)
    strength = 1.0
    plan: Plan = plan_edit(before, params, request, strength, ew)
    calm = any(word_intensity(t, ew, words()) < 1.0 for t in tokens(request))
    capped = False  # the strength ran out before the parameters reached their limits
    while True:
        new_text, warnings = apply_edit(before, plan.assignments, plan.view, plan.lines, plan.add)
        checked = verify(before, new_text, request, plan.intended, size, session)
        structural = bool(plan.assignments or plan.lines or plan.add)
        # a condition's amount spreads over the surface: a change on a few texels reads as
        # noise, so "more worn" must move more of them
        frac = ew.f("amount_visible_fraction" if plan.rule == "amount" else "visible_fraction")
        shows = checked.shows(frac, plan.intended) or not (structural or checked.locality.changed)
        # "slightly" starts from a smaller step and grows only until the change just shows
        if shows or not plan.graded:
            break
        if strength * ew.f("escalate") > ew.f("max_strength"):
            capped = True
            break
        strength *= ew.f("escalate")
        try:
            stronger = plan_edit(before, params, request, strength, ew)
        except EditRefused:
            break
        if (
            stronger.assignments == plan.assignments
            and stronger.lines == plan.lines
            and tuple(stronger.add) == tuple(plan.add)
        ):
            break
        plan = stronger
    if not shows and structural and not plan.exact:
        if capped and not calm and not plan.reduces:  # refused, not returned
            seen = ", ".join(dict.fromkeys(_seen_name(ch) for ch in plan.intended)) or "maps"
            raise EditRefused(
                request,
                f"{plan.rule}: even at {strength:.3g} times the step ({plan.note}) the {seen} "
                "would change too little to show",
                params,
            )
        warnings = [*warnings, "the change is small: it may not show in a preview"]
    record = plan.to_json()
    if strength != 1.0:
        record["strength"] = round(strength, 3)
    return EditResult(
        keep_layout(text, new_text),  # only the changed lines differ from the user's text
        EditReport(
            request, "rules", record, changes(before, checked.program), warnings, checked.locality
        ),
    )


__all__ = [
    "Change",
    "EditError",
    "EditRefused",
    "EditReport",
    "EditResult",
    "Verified",
    "add_lines",
    "all_params",
    "apply_edit",
    "changed_seeds",
    "edit_offline",
    "parse_program",
    "replace_lines",
    "set_view",
]
