"""Stage II: the stateless critic and robust parsing of its JSON answer (reference §8.4).

The critic sees a fresh conversation per program (so its scores stay comparable across rounds)
with any subset of: the preview render (only if the model takes images), the 28 statistics,
the source. Its answer is parsed tolerantly: ``//`` comments outside strings are removed, the
first brace-balanced object is taken, ``json.loads`` then the bounded repair of
:mod:`~matloom.author.stages.jsonfix` are tried, and the result is validated; a failure is
retried with a follow-up message up to ``retries`` times. Every way an answer can be wrong
(too long, not JSON, nested too deep, wrong fields) is a :class:`CritiqueParseError`, so a bad
critic answer ends as a failed critique in the record, never as a failed run. All parsing is
linear in the answer's length.
"""

from __future__ import annotations

import json
import math
import re
import time
from collections.abc import Collection

from pydantic import BaseModel, Field, ValidationError, field_validator

from matloom.author.config import DEFAULT_MAX_REPLY_CHARS
from matloom.author.llm.base import ChatMessage, ChatModel, ImageInput
from matloom.author.prompts.critic import (
    critic_retry_message,
    critic_system_prompt,
    critic_user_message,
)
from matloom.author.records import CritiqueRecord, MessageRecord
from matloom.author.replies import clean_text, clip_reply, oversize_error
from matloom.author.stages.jsonfix import JsonRepairError, repair_json

#: A JSON string (possibly never closed: the rest of the text is then inside it).
_STRING = r'"[^"\\]*(?:\\.[^"\\]*)*(?:"|\\?\Z)'
_STRING_OR_COMMENT = re.compile(_STRING + r"|//[^\n]*", re.DOTALL)
_STRING_OR_BRACE = re.compile(_STRING + r"|[{}]", re.DOTALL)
#: An unusable answer is quoted back to the critic (in the retry) up to this many characters.
ECHO_MAX_CHARS = 8_000


class Critique(BaseModel):
    """The critic's answer."""

    match_score: int = Field(ge=0, le=100)
    differences: list[str] = Field(default_factory=list)
    suggestions: list[str] = Field(default_factory=list)

    @field_validator("match_score", mode="before")
    @classmethod
    def _round_score(cls, value: object) -> object:
        """Accept 72.5 or "72" (models do that) and clamp into 0..100."""
        if isinstance(value, str):
            value = value.strip().split("/")[0].strip()
            try:
                value = float(value)
            except ValueError:
                return value
        if isinstance(value, float) and math.isfinite(value):
            value = round(value)
        if isinstance(value, int) and not isinstance(value, bool):
            return min(100, max(0, value))
        return value

    @field_validator("differences", "suggestions", mode="before")
    @classmethod
    def _listify(cls, value: object) -> object:
        if isinstance(value, str):
            return [clean_text(value)] if value.strip() else []
        if isinstance(value, list):
            return [clean_text(str(v)) for v in value]
        return value


class CritiqueParseError(ValueError):
    """The answer is not a usable critique."""


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
    data = _load(candidate)
    if not isinstance(data, dict):
        raise CritiqueParseError("the answer is not a JSON object")
    try:
        return Critique.model_validate(data)
    except ValidationError as err:
        problems = "; ".join(f"{'.'.join(map(str, e['loc']))}: {e['msg']}" for e in err.errors())
        raise CritiqueParseError(problems) from None
    except RecursionError:  # a list entry nested deeply enough to exhaust str()
        raise CritiqueParseError("the answer is nested too deeply") from None


def _read_answer(text: str, max_reply_chars: int) -> Critique:
    """The critique in one answer; an answer over the size cap is refused unread."""
    if len(text) > max_reply_chars:
        raise CritiqueParseError(oversize_error(len(text), max_reply_chars))
    return parse_critique(text)


def critique_program(
    model: ChatModel,
    description: str,
    program_index: int,
    program: str,
    *,
    signals: Collection[str],
    render: ImageInput | None,
    stats: str | None,
    retries: int,
    max_reply_chars: int = DEFAULT_MAX_REPLY_CHARS,
) -> CritiqueRecord:
    """Run the stateless critic on one program; never raises on a bad answer (``ok=False``)."""
    if "render" in signals and (render is None or not model.accepts_images):
        signals = [s for s in signals if s != "render"]
    messages = [
        ChatMessage(role="system", text=critic_system_prompt(signals)),
        ChatMessage(
            role="user",
            text=critic_user_message(description, signals, program=program, stats=stats),
            images=(render,) if "render" in signals and render is not None else (),
        ),
    ]
    start = time.perf_counter()
    replies: list[str] = []
    error = "no answer"
    for _ in range(retries + 1):
        reply = model.complete(messages)
        replies.append(clip_reply(reply.text, max_reply_chars))
        try:
            critique = _read_answer(reply.text, max_reply_chars)
        except CritiqueParseError as err:
            error = str(err)
            messages = [
                *messages,
                ChatMessage(role="assistant", text=clip_reply(reply.text, ECHO_MAX_CHARS)),
                ChatMessage(role="user", text=critic_retry_message(error)),
            ]
            continue
        return _record(program_index, signals, model, messages, replies, start, critique=critique)
    return _record(program_index, signals, model, messages, replies, start, error=error)


def _record(
    program_index: int,
    signals: Collection[str],
    model: ChatModel,
    messages: list[ChatMessage],
    replies: list[str],
    start: float,
    *,
    critique: Critique | None = None,
    error: str | None = None,
) -> CritiqueRecord:
    render_path = next((img.path for m in messages for img in m.images if img.path), None)
    return CritiqueRecord(
        program_index=program_index,
        ok=critique is not None,
        match_score=critique.match_score if critique else None,
        differences=critique.differences if critique else [],
        suggestions=critique.suggestions if critique else [],
        signals=list(signals),
        render=render_path,
        model=model.model_id,
        attempts=len(replies),
        seconds=time.perf_counter() - start,
        messages=[MessageRecord(**m.to_record()) for m in messages],
        replies=replies,
        error=None
        if critique
        else f"unparseable critique after {len(replies)} attempt(s): {error}",
    )
