"""Reading a Chat Completions body without trusting it.

An HTTP-200 answer is parsed here rather than by the SDK's models, so a malformed one is a
:class:`MalformedReplyError` with a one-line reason (retried, then recorded as a bad reply)
instead of an exception from deep inside the run. What is accepted:

- ``choices[0].message.content`` as a string, ``null`` (an empty reply), or a list of content
  parts (the protocol allows them): the ``text`` of its text parts, joined without separator
  (servers that split one answer into parts split it anywhere); other parts (images, refusals)
  are left out. Anything else there is malformed, as is a body that is not a JSON object,
  ``choices`` that is not a list, or a first choice or message that is not an object.
- ``usage`` is informational: a field that is not a non-negative integer is left out of the
  record (``"prompt_tokens": "lots"`` does not cost the answer); ``model`` and
  ``finish_reason`` are kept only when they are strings.

A body cut at the byte budget is not JSON; :func:`partial_content` recovers the start of its
content for the record.
"""

from __future__ import annotations

import json
import re
from dataclasses import dataclass, field
from typing import Any

from matloom.author.replies import clean_text

USAGE_FIELDS = ("prompt_tokens", "completion_tokens", "total_tokens")
#: Characters of the body or of a server's own error message quoted in a bad-reply error.
#: Generous on purpose: the caller redacts credentials first and then clips the message, so a
#: key echoed by the server is never cut in half before the redaction could see it whole.
QUOTED_CHARS = 4096

_CONTENT_KEY = re.compile(rb'"content"\s*:\s*"')


class MalformedReplyError(ValueError):
    """An HTTP-200 body that holds no usable completion; the message says what is wrong."""


@dataclass(frozen=True)
class Completion:
    """What is used of a completion body."""

    text: str
    finish_reason: str | None = None
    model: str | None = None
    usage: dict[str, int] = field(default_factory=dict)


def parse_completion(body: bytes) -> Completion:
    """The first choice's text and the metadata of a Chat Completions body.

    Raises :class:`MalformedReplyError` for a body that is not a completion."""
    try:
        data = json.loads(body)
    except (ValueError, RecursionError):
        raise MalformedReplyError(f"the reply is not JSON ({_describe(body)})") from None
    if not isinstance(data, dict):
        raise MalformedReplyError(f"the reply is a JSON {type(data).__name__}, not an object")
    choices = data.get("choices")
    if choices is None and "error" in data:
        raise MalformedReplyError(f"the server answered HTTP 200 with an error: {_error(data)}")
    if not isinstance(choices, list):
        raise MalformedReplyError(f"`choices` is {_kind(choices)}, not a list")
    text, finish = ("", None) if not choices else _first_choice(choices[0])
    return Completion(
        text=clean_text(text),
        finish_reason=finish,
        model=data.get("model") if isinstance(data.get("model"), str) else None,
        usage=_usage(data.get("usage")),
    )


def _first_choice(choice: Any) -> tuple[str, str | None]:
    if not isinstance(choice, dict):
        raise MalformedReplyError(f"`choices[0]` is {_kind(choice)}, not an object")
    message = choice.get("message")
    if not isinstance(message, dict):
        raise MalformedReplyError(f"`choices[0].message` is {_kind(message)}, not an object")
    finish = choice.get("finish_reason")
    return _content_text(message.get("content")), finish if isinstance(finish, str) else None


def _content_text(content: Any) -> str:
    if content is None:
        return ""
    if isinstance(content, str):
        return content
    if not isinstance(content, list):
        raise MalformedReplyError(f"`content` is {_kind(content)}, not a string or a list")
    texts = []
    for part in content:
        if not isinstance(part, dict):
            raise MalformedReplyError(f"a part of `content` is {_kind(part)}, not an object")
        if part.get("type") in ("text", "output_text"):
            if not isinstance(part.get("text"), str):
                raise MalformedReplyError("a text part of `content` has no string `text`")
            texts.append(part["text"])
    return "".join(texts)


def _usage(usage: Any) -> dict[str, int]:
    if not isinstance(usage, dict):
        return {}
    return {
        f: usage[f]
        for f in USAGE_FIELDS
        if type(usage.get(f)) is int and usage[f] >= 0  # bool is an int subclass: excluded
    }


def _kind(value: Any) -> str:
    return "null or missing" if value is None else f"a {type(value).__name__}"


def _error(data: dict[str, Any]) -> str:
    error = data.get("error")
    message = error.get("message") if isinstance(error, dict) else error
    return str(message)[:QUOTED_CHARS]


def _describe(body: bytes) -> str:
    if not body.strip():
        return "an empty body"
    head = body[:QUOTED_CHARS].decode("utf-8", "replace")
    return f"{len(body):,} bytes starting {head!r}"


def partial_content(body: bytes, max_chars: int) -> str:
    """Up to ``max_chars`` characters of the first ``content`` string in a (cut) JSON body;
    '' when there is none. Best effort: only for showing what an oversized reply was."""
    found = _CONTENT_KEY.search(body)
    if found is None:
        return ""
    raw = body[found.end() : found.end() + 12 * max_chars].decode("utf-8", "replace")
    end = _string_end(raw)
    try:
        text = json.loads(f'"{raw[:end]}"')
    except ValueError:
        text = raw[:end]
    return clean_text(text[:max_chars])


def _string_end(raw: str) -> int:
    """Index of the closing quote of a JSON string body, or the end of its last whole escape."""
    i = 0
    last_whole = 0
    while i < len(raw):
        c = raw[i]
        if c == '"':
            return i
        if c == "\\":
            step = 6 if raw[i + 1 : i + 2] == "u" else 2
            if i + step > len(raw):
                break
            i += step
        else:
            i += 1
        last_whole = i
    return last_whole
