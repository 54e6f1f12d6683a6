"""Stage II: the stateless critic and robust parsing of its JSON answer (reference §8.4).

The critic sees a fresh conversation per program (so its scores stay comparable across rounds)
with any subset of: the preview render (only if the model takes images), the 28 statistics,
the source. Its answer is parsed tolerantly: ``//`` comments outside strings are removed, the
first brace-balanced object is taken, ``json.loads`` then ``json_repair`` are tried, and the
result is validated; a failure is retried with a follow-up message up to ``retries`` times.
"""

from __future__ import annotations

import json
import time
from collections.abc import Collection

from pydantic import BaseModel, Field, ValidationError, field_validator

from matloom.author.llm.base import ChatMessage, ChatModel, ImageInput
from matloom.author.prompts.critic import (
    critic_retry_message,
    critic_system_prompt,
    critic_user_message,
)
from matloom.author.records import CritiqueRecord, MessageRecord


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
        if isinstance(value, float):
            value = round(value)
        if isinstance(value, int) and not isinstance(value, bool):
            return min(100, max(0, value))
        return value

    @field_validator("differences", "suggestions", mode="before")
    @classmethod
    def _listify(cls, value: object) -> object:
        if isinstance(value, str):
            return [value] if value.strip() else []
        if isinstance(value, list):
            return [str(v) for v in value]
        return value


class CritiqueParseError(ValueError):
    """The answer is not a usable critique."""


def strip_line_comments(text: str) -> str:
    """Remove ``// ...`` comments that are outside JSON strings."""
    out: list[str] = []
    in_string = escaped = False
    i = 0
    while i < len(text):
        ch = text[i]
        if in_string:
            out.append(ch)
            escaped = ch == "\\" and not escaped
            if ch == '"' and not escaped:
                in_string = False
        elif ch == '"':
            in_string, escaped = True, False
            out.append(ch)
        elif text.startswith("//", i):
            while i < len(text) and text[i] != "\n":
                i += 1
            continue
        else:
            out.append(ch)
        i += 1
    return "".join(out)


def first_json_object(text: str) -> str | None:
    """The first brace-balanced ``{...}`` (braces in strings ignored), or the tail from ``{``."""
    start = text.find("{")
    if start < 0:
        return None
    depth, in_string, escaped = 0, False, False
    for i in range(start, len(text)):
        ch = text[i]
        if in_string:
            escaped = ch == "\\" and not escaped
            if ch == '"' and not escaped:
                in_string = False
            continue
        if ch == '"':
            in_string, escaped = True, False
        elif ch == "{":
            depth += 1
        elif ch == "}":
            depth -= 1
            if depth == 0:
                return text[start : i + 1]
    return text[start:]


def parse_critique(text: str) -> Critique:
    """Parse a critic answer; raise :class:`CritiqueParseError` saying what was wrong."""
    candidate = first_json_object(strip_line_comments(text))
    if candidate is None:
        raise CritiqueParseError("no JSON object found")
    try:
        data = json.loads(candidate)
    except json.JSONDecodeError:
        import json_repair

        data = json_repair.loads(candidate)
    if not isinstance(data, dict):
        raise CritiqueParseError("the answer is not a JSON object")
    try:
        return Critique.model_validate(data)
    except ValidationError as err:
        problems = "; ".join(f"{'.'.join(map(str, e['loc']))}: {e['msg']}" for e in err.errors())
        raise CritiqueParseError(problems) from None


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
        replies.append(reply.text)
        try:
            critique = parse_critique(reply.text)
        except CritiqueParseError as err:
            error = str(err)
            messages = [
                *messages,
                ChatMessage(role="assistant", text=reply.text),
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
