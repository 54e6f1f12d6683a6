"""Tolerant extraction of a program from a model reply: tags, code fences, prose around.

Every search here is linear in the reply size, whatever the reply holds: a degenerate model
answer (``<material>`` or a code fence repeated without its closing mark, megabytes of blank
lines) is scanned once, never re-scanned from every opening mark the way a lazy regex would.
"""

from __future__ import annotations

import re
from collections.abc import Iterator

_OPEN_TAG = re.compile(r"<material>", re.IGNORECASE)
_CLOSE_TAG = re.compile(r"</material>", re.IGNORECASE)
_FENCE_MARK = "```"
#: The info string after an opening fence and the newline that ends it.
_FENCE_INFO = re.compile(r"[^\n`]*\n")
#: A line starting a program. Only horizontal whitespace before the keyword: ``\s*`` spanning
#: newlines would re-scan a run of blank lines from each of its lines (quadratic); the match
#: then starts one line later, which the callers' ``strip()`` makes no difference to.
_START = re.compile(r"^[^\S\n]*(View|Define|Material)\s*\(", re.MULTILINE)


def _tag_block(reply: str) -> tuple[int, str] | None:
    """(start, body) of the first ``<material>...</material>`` pair, or None.

    Only the first opening tag is tried: when no closing tag follows it, none follows any later
    opening tag either.
    """
    opening = _OPEN_TAG.search(reply)
    if opening is None:
        return None
    closing = _CLOSE_TAG.search(reply, opening.end())
    if closing is None:
        return None
    return opening.start(), reply[opening.end() : closing.start()]


def fenced_blocks(text: str) -> Iterator[tuple[int, str]]:
    """(start, body) of each fenced block ```` ```info\\n body ``` ````, left to right.

    The same blocks as the lazy regex ```` ```[^\\n`]*\\n(.*?)``` ```` finds, in one pass: when
    an opening fence has no closing fence after it, no later fence can have one, so the scan
    stops instead of retrying from every later mark.
    """
    pos = 0
    while True:
        start = text.find(_FENCE_MARK, pos)
        if start < 0:
            return
        info = _FENCE_INFO.match(text, start + len(_FENCE_MARK))
        if info is None:
            pos = start + 1
            continue
        end = text.find(_FENCE_MARK, info.end())
        if end < 0:
            return
        yield start, text[info.end() : end]
        pos = end + len(_FENCE_MARK)


def strip_fences(text: str) -> str:
    """Remove a Markdown code fence wrapped around ``text`` (if any)."""
    if text.strip().startswith(_FENCE_MARK):
        block = next(fenced_blocks(text), None)
        if block is not None:
            return block[1].strip()
    return text.strip()


def extract_program(reply: str) -> tuple[str | None, str]:
    """Return ``(program_text, preamble)`` from a model reply.

    Order: the first ``<material>...</material>`` block (fences inside it are stripped); else the
    first fenced block that looks like a program; else the text from the first line starting with
    View(/Define(/Material( to the end. The preamble is the text before the program. The time
    taken is linear in ``len(reply)``.
    """
    tag = _tag_block(reply)
    if tag is not None:
        start, body = tag
        return strip_fences(body), reply[:start].strip()
    for start, body in fenced_blocks(reply):
        if _START.search(body):
            return body.strip(), reply[:start].strip()
    sm = _START.search(reply)
    if sm:
        return reply[sm.start() :].strip(), reply[: sm.start()].strip()
    return None, reply.strip()
