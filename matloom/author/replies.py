"""The reply-size cap: over-long model replies are refused, and stored and echoed clipped.

A reply longer than ``AuthorConfig.max_reply_chars`` (``--max-reply-chars``, default
1,000,000 characters) is not parsed at all: the generator's turn records the attempt as
``too_large`` and asks again, the critic's answer counts as unparseable and is retried. Only
the first :data:`CLIPPED_HEAD_CHARS` characters of such a reply go into ``record.json`` and back
into the conversation, so a degenerate answer can neither stall the run nor bloat its record.
The OpenAI-compatible adapter does not even receive all of a reply far over the cap: it stops
reading the body after 12 bytes per allowed character (plus 64 KiB), and such a cut reply
(``ChatReply.cut_at_bytes``) is refused the same way.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from matloom.author.llm.base import ChatReply

#: Characters kept from the start of a reply that is cut.
CLIPPED_HEAD_CHARS = 2_000


def oversize_error(length: int, limit: int) -> str:
    """The recorded error of a reply over the cap."""
    return (
        f"the reply is {length:,} characters long, over the limit of {limit:,} "
        "(max_reply_chars, --max-reply-chars)"
    )


def cut_error(read_bytes: int, limit: int) -> str:
    """The recorded error of a reply whose reading stopped at the byte budget."""
    return (
        f"the reply is longer than {read_bytes:,} bytes, more than a reply within the limit of "
        f"{limit:,} characters can take (max_reply_chars, --max-reply-chars); it was not read "
        "further"
    )


def refusal(reply: ChatReply, limit: int) -> str | None:
    """Why ``reply`` is refused unread (over the size cap), or None when it may be read."""
    if reply.cut_at_bytes is not None:
        return cut_error(reply.cut_at_bytes, limit)
    if len(reply.text) > limit:
        return oversize_error(len(reply.text), limit)
    return None


def shown_reply(reply: ChatReply, limit: int) -> str:
    """``reply`` as stored and echoed: whole, or clipped with a note of the cut."""
    if reply.cut_at_bytes is None:
        return clip_reply(reply.text, limit)
    head = reply.text[:CLIPPED_HEAD_CHARS]
    return f"{head}\n[... the reply was cut: reading stopped after {reply.cut_at_bytes:,} bytes]"


def clip_reply(text: str, limit: int) -> str:
    """``text`` when it has at most ``limit`` characters, else its start and a note of the cut."""
    if len(text) <= limit:
        return text
    head = text[: min(limit, CLIPPED_HEAD_CHARS)]
    return (
        f"{head}\n[... {len(text) - len(head):,} more characters cut; "
        f"the reply is {len(text):,} characters long]"
    )


def clean_text(text: str) -> str:
    """``text`` with lone UTF-16 surrogates (from ``\\udXXX`` escapes in a reply) replaced by
    U+FFFD: they cannot be written as UTF-8, so one would make every save of the record fail."""
    try:
        text.encode("utf-8")
    except UnicodeEncodeError:
        return text.encode("utf-16", "surrogatepass").decode("utf-16", "replace")
    return text
