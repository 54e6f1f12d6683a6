"""Robust parsing of the critic's JSON answer.

``//`` comments outside strings are removed, the first brace-balanced object is taken,
``json.loads`` then the bounded repair of :mod:`~matloom.author.stages.jsonfix` are tried, and
the result is validated leniently: ``match_score`` may be 72, 72.0, "72", "72/100" or "72%";
``differences``/``suggestions``/``structural`` may be one string; each entry of the optional ``edits`` may be
an object or a plain string, and an unusable entry is dropped rather than failing the answer;
``better_than_previous`` may be a boolean or yes/no. Every way an answer can be wrong (too long,
not JSON, nested too deep, wrong fields) is a :class:`CritiqueParseError`. All parsing is
linear in the answer's length.
"""

from __future__ import annotations

import json
import math
import re
from typing import Any

from pydantic import BaseModel, ConfigDict, Field, ValidationError, field_validator

from matloom.author.replies import clean_text
from matloom.author.stages.jsonfix import JsonRepairError, repair_json

#: A JSON string (possibly never closed: the rest of the text is then inside it).
_STRING = r'"[^"\\]*(?:\\.[^"\\]*)*(?:"|\\?\Z)'
_STRING_OR_COMMENT = re.compile(_STRING + r"|//[^\n]*", re.DOTALL)
_STRING_OR_BRACE = re.compile(_STRING + r"|[{}]", re.DOTALL)
_NUMBER = re.compile(r"[-+]?(?:\d+(?:\.\d*)?|\.\d+)")
_YES = frozenset({"true", "yes", "y", "better", "1"})
_NO = frozenset({"false", "no", "n", "worse", "same", "0"})
#: Keys read as an edit's change when ``change`` itself is missing.
_CHANGE_KEYS = ("change", "edit", "value", "to", "description")


class CritiqueParseError(ValueError):
    """The answer is not a usable critique."""


def _number(value: object) -> object:
    """72, 72.0, "72", " 72/100 ", "72%" -> a float or int; anything else unchanged."""
    if isinstance(value, str):
        found = _NUMBER.search(value)
        return float(found.group()) if found else value
    return value


def _int_or_none(value: object) -> int | None:
    value = _number(value)
    if isinstance(value, bool) or not isinstance(value, int | float):
        return None
    return int(value) if math.isfinite(value) else None


def _text(value: object) -> str | None:
    if value is None or isinstance(value, dict | list):
        return None
    text = clean_text(str(value)).strip()
    return text or None


class CriticEdit(BaseModel):
    """One concrete edit: a layer (0 = bottom) and a channel, or a Define, and the change."""

    model_config = ConfigDict(extra="forbid")

    layer: int | None = None
    channel: str | None = None
    define: str | None = None
    change: str

    @classmethod
    def lenient(cls, entry: object) -> CriticEdit | None:
        """The edit in one list entry, or None when it holds no change."""
        if isinstance(entry, str):
            change = _text(entry)
            return cls(change=change) if change else None
        if not isinstance(entry, dict):
            return None
        change = next((_text(entry[k]) for k in _CHANGE_KEYS if _text(entry.get(k))), None)
        if change is None:
            return None
        return cls(
            layer=_int_or_none(entry.get("layer")),
            channel=_text(entry.get("channel")),
            define=_text(entry.get("define")),
            change=change,
        )


class Critique(BaseModel):
    """The critic's answer."""

    match_score: int = Field(ge=0, le=100)
    differences: list[str] = Field(default_factory=list)
    suggestions: list[str] = Field(default_factory=list)
    edits: list[CriticEdit] = Field(default_factory=list)
    #: Structural changes (critic loop v3): a new layer, a different primitive, ...
    structural: list[str] = Field(default_factory=list)
    better_than_previous: bool | None = None

    @field_validator("match_score", mode="before")
    @classmethod
    def _round_score(cls, value: object) -> object:
        """Accept 72.5, "72", "72/100" (models do that) and clamp into 0..100."""
        value = _number(value)
        if isinstance(value, float) and math.isfinite(value):
            value = round(value)
        if isinstance(value, int) and not isinstance(value, bool):
            return min(100, max(0, value))
        return value

    @field_validator("differences", "suggestions", mode="before")
    @classmethod
    def _listify(cls, value: object) -> object:
        if value is None:
            return []
        if isinstance(value, str):
            return [clean_text(value)] if value.strip() else []
        if isinstance(value, list):
            return [clean_text(str(v)) for v in value]
        return value

    @field_validator("structural", mode="before")
    @classmethod
    def _changes(cls, value: object) -> object:
        """A list of changes, one string, or objects (their change text); empty ones dropped."""
        entries = value if isinstance(value, list) else [value]
        changes = []
        for entry in entries:
            if isinstance(entry, dict):
                entry = next((entry[k] for k in _CHANGE_KEYS if _text(entry.get(k))), None)
            text = _text(entry)
            if text:
                changes.append(text)
        return changes

    @field_validator("edits", mode="before")
    @classmethod
    def _edits(cls, value: object) -> object:
        if value is None:
            return []
        entries = value if isinstance(value, list) else [value]
        return [e for e in map(CriticEdit.lenient, entries) if e is not None]

    @field_validator("better_than_previous", mode="before")
    @classmethod
    def _yes_no(cls, value: object) -> object:
        if value is None or isinstance(value, bool):
            return value
        word = str(value).strip().lower()
        if word in _YES:
            return True
        if word in _NO:
            return False
        return None


def strip_line_comments(text: str) -> str:
    """Remove ``// ...`` comments that are outside JSON strings."""
    return _STRING_OR_COMMENT.sub(lambda m: m.group() if m.group().startswith('"') else "", text)


def first_json_object(text: str) -> str | None:
    """The first brace-balanced ``{...}`` (braces in strings ignored), or the tail from ``{``."""
    start = text.find("{")
    if start < 0:
        return None
    depth = 0
    for m in _STRING_OR_BRACE.finditer(text, start):
        token = m.group()
        if token == "{":
            depth += 1
        elif token == "}":
            depth -= 1
            if depth == 0:
                return text[start : m.end()]
    return text[start:]


def _load(candidate: str) -> object:
    """``json.loads``, else the bounded lenient repair; every failure a CritiqueParseError."""
    try:
        return json.loads(candidate, strict=False)
    except (ValueError, RecursionError):  # JSONDecodeError, too many digits, nested too deep
        pass
    try:
        return repair_json(candidate)
    except JsonRepairError as err:
        raise CritiqueParseError(str(err)) from None


def parse_critique(text: str) -> Critique:
    """Parse a critic answer; raise :class:`CritiqueParseError` saying what was wrong."""
    candidate = first_json_object(strip_line_comments(text))
    if candidate is None:
        raise CritiqueParseError("no JSON object found")
    data: Any = _load(candidate)
    if not isinstance(data, dict):
        raise CritiqueParseError("the answer is not a JSON object")
    try:
        return Critique.model_validate(data)
    except ValidationError as err:
        problems = "; ".join(f"{'.'.join(map(str, e['loc']))}: {e['msg']}" for e in err.errors())
        raise CritiqueParseError(problems) from None
    except RecursionError:  # a list entry nested deeply enough to exhaust str()
        raise CritiqueParseError("the answer is nested too deeply") from None
