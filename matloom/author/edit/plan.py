"""What an offline rule returns (:class:`Plan`), what it reads (:class:`Context`), the refusal
(:class:`EditRefused`), and the value helpers the rules share."""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import Any

from matloom.author.edit.lexicon import EditWords, edit_words
from matloom.lang import ast as A
from matloom.lang.params import Param
from matloom.library.data import Words

Value = float | tuple[float, float, float]


class EditRefused(ValueError):
    """A request the offline rules cannot map (the message lists what could be changed)."""

    def __init__(self, request: str, reason: str, params: Sequence[Param] = ()) -> None:
        self.request = request
        self.reason = reason
        self.params = list(params)
        listed = ", ".join(f"{p.address} ({p.label or p.kind})" for p in self.params[:40])
        more = f" and {len(self.params) - 40} more" if len(self.params) > 40 else ""
        super().__init__(
            f"cannot edit {request!r} offline: {reason}"
            + (f"; parameters it could change: {listed}{more}" if listed else "")
        )


@dataclass(frozen=True)
class Plan:
    """What a rule decided: parameter assignments, View changes, replaced lines (``layer:N`` or
    ``define:NAME`` -> its new text), added lines (new Defines and layers on top), and the
    channels the edit means to change. ``graded``: the step grows with the context's strength
    (the edit may escalate it when the change is too small to see); ``exact``: the request
    gave the value itself ("12 mm joints", "white"), so a small change is no warning;
    ``reduces``: it takes something away (flatter): one that does not show at the greatest
    step is kept with a warning, not refused (there is nothing further to take)."""

    rule: str
    note: str
    assignments: dict[str, Value] = field(default_factory=dict)
    view: dict[str, Any] = field(default_factory=dict)
    intended: tuple[str, ...] = ()
    lines: dict[str, str] = field(default_factory=dict)
    add: tuple[str, ...] = ()
    graded: bool = False
    exact: bool = False
    reduces: bool = False
    #: the request's words an added condition came from ("dirt"): its own clause describes
    #: it, so no other rule re-reads that clause ("reddish-brown clay and dirt")
    said: tuple[str, ...] = ()

    def to_json(self) -> dict[str, Any]:
        out: dict[str, Any] = {
            "rule": self.rule,
            "note": self.note,
            "assignments": {k: _json_value(v) for k, v in self.assignments.items()},
            "view": dict(self.view),
            "intended": list(self.intended),
        }
        if self.lines:
            out["replace"] = dict(self.lines)
        if self.add:
            out["add"] = list(self.add)
        return out


def _json_value(v: Value) -> Any:
    return list(v) if isinstance(v, tuple) else v


def word_intensity(word: str, ew: EditWords, vocabulary: Words) -> float:
    """An intensity word's factor ("slightly" 0.5, "very" 1.4; 1 for any other word): the
    edits' own ``[intensity]`` over the library's."""
    return ew.intensity.get(word, vocabulary.intensity.get(word, 1.0))


@dataclass(frozen=True)
class Context:
    """A request as the rules read it: its words, the program and its parameters, the
    library's vocabulary, the edit words, and the step strength (1 at first, more when the
    edit escalates a change too small to see; "slightly" halves it), and the request's own
    words (``said``)."""

    request: str
    words: list[str]
    params: list[Param]
    program: A.Program
    vocabulary: Words
    strength: float = 1.0
    ew: EditWords = field(default_factory=edit_words)
    #: the request's own words, what it keeps cut off (a look's reading, "wet" as "darker
    #: overall, glossier", is not in them); empty: the words of ``request``
    said: tuple[str, ...] = ()

    @property
    def nouns(self) -> list[str]:
        return [t for t in self.words if t not in self.ew["filler"]]

    @property
    def intensity(self) -> float:
        """The product of the request's intensity words ("slightly" 0.5, "very" 1.4)."""
        k = 1.0
        for t in self.words:
            k *= word_intensity(t, self.ew, self.vocabulary)
        return k

    @property
    def k(self) -> float:
        """The step multiplier: the strength times the intensity words."""
        return self.strength * self.intensity

    def refuse(self, reason: str, params: Sequence[Param] | None = None) -> EditRefused:
        return EditRefused(self.request, reason, self.params if params is None else params)


def clamp(p: Param, v: float) -> float:
    """``v`` within the parameter's range (whole for counts and seeds), 6 significant digits."""
    lo = p.low if p.low is not None else -float("inf")
    hi = p.high if p.high is not None else float("inf")
    v = min(hi, max(lo, v))
    if p.kind in ("count", "seed"):
        return float(round(v))
    return float(f"{v:.6g}")


def scaled(p: Param, factor: float) -> float:
    return clamp(p, float(p.value) * factor)  # type: ignore[arg-type]


def changed(p: Param, new: Value) -> bool:
    if isinstance(new, tuple):
        return tuple(round(c) for c in new) != tuple(round(c) for c in p.value)  # type: ignore[union-attr]
    return abs(float(new) - float(p.value)) > 1e-9  # type: ignore[arg-type]


def affects(ps: Sequence[Param]) -> tuple[str, ...]:
    out: dict[str, None] = {}
    for p in ps:
        out.update(dict.fromkeys(p.affects))
    return tuple(out)


def assign(
    c: Context,
    rule: str,
    note: str,
    new: dict[Param, Value],
    intended: Sequence[str],
    graded: bool = True,
    exact: bool = False,
) -> Plan:
    """A plan of the assignments that change something (refused when none does)."""
    moved = {p.address: v for p, v in new.items() if changed(p, v)}
    if not moved:
        raise c.refuse(
            f"{rule}: {', '.join(p.address for p in new)} already at the limit of its range",
            list(new),
        )
    return Plan(rule, note, assignments=moved, intended=tuple(intended), graded=graded, exact=exact)
