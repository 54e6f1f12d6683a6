"""Tolerant extraction of a program from a model reply: tags, code fences, prose around."""

from __future__ import annotations

import re

_TAG = re.compile(r"<material>\s*(.*?)\s*</material>", re.DOTALL | re.IGNORECASE)
_FENCE = re.compile(r"```[^\n`]*\n(.*?)```", re.DOTALL)
_START = re.compile(r"^\s*(View|Define|Material)\s*\(", re.MULTILINE)


def strip_fences(text: str) -> str:
    """Remove a Markdown code fence wrapped around ``text`` (if any)."""
    m = _FENCE.search(text)
    if m and text.strip().startswith("```"):
        return m.group(1).strip()
    return text.strip()


def extract_program(reply: str) -> tuple[str | None, str]:
    """Return ``(program_text, preamble)`` from a model reply.

    Order: the first ``<material>...</material>`` block (fences inside it are stripped); else the
    first fenced block that looks like a program; else the text from the first line starting with
    View(/Define(/Material( to the end. The preamble is the text before the program.
    """
    m = _TAG.search(reply)
    if m:
        return strip_fences(m.group(1)), reply[: m.start()].strip()
    for fm in _FENCE.finditer(reply):
        body = fm.group(1)
        if _START.search(body):
            return body.strip(), reply[: fm.start()].strip()
    sm = _START.search(reply)
    if sm:
        return reply[sm.start() :].strip(), reply[: sm.start()].strip()
    return None, reply.strip()
