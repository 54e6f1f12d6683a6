"""Bounded repair of near-JSON answers (the critic's): linear time, capped size and depth.

Models answer "JSON" with trailing commas, single quotes, Python literals, unquoted keys,
missing commas or a missing end (a cut-off answer). :func:`repair_json` reads such text with a
forgiving recursive-descent parser over regex tokens and builds the Python value directly:

* every token is looked at once (time linear in the input), and input over
  :data:`REPAIR_MAX_CHARS` characters or nested deeper than :data:`REPAIR_MAX_DEPTH` levels is
  refused, so no answer can make the repair slow or exhaust the stack;
* characters that cannot start a token are skipped; a missing value becomes ``None``; open
  strings, arrays and objects are closed at the end; a ``}`` closes an open array too.

Every failure is a :class:`JsonRepairError` (a ``ValueError``).
"""

from __future__ import annotations

import json
import re
from typing import Any

#: Longest text :func:`repair_json` accepts (a critique is a few hundred to a few thousand).
REPAIR_MAX_CHARS = 65_536
#: Deepest nesting of objects and arrays :func:`repair_json` accepts (a critique needs 2).
REPAIR_MAX_DEPTH = 32

_TOKEN = re.compile(
    r'"[^"\\]*(?:\\.[^"\\]*)*(?:"|\\?\Z)'  # double-quoted string, possibly never closed
    r"|'[^'\\]*(?:\\.[^'\\]*)*(?:'|\\?\Z)"  # single-quoted string, possibly never closed
    r"|-?(?:\d+(?:\.\d*)?|\.\d+)(?:[eE][+-]?\d+)?"  # number
    r"|[A-Za-z_][\w.-]*"  # bare word: a literal, an unquoted key or string
    r"|[{}\[\]:,]"  # structure
    r"|\s+|.",  # skipped
    re.DOTALL,
)
_INT = re.compile(r"-?\d+")
_ESCAPE = re.compile(r"\\(u[0-9a-fA-F]{4}|.)", re.DOTALL)
_SIMPLE_ESCAPES = {"n": "\n", "t": "\t", "r": "\r", "b": "\b", "f": "\f"}
_LITERALS: dict[str, Any] = {
    "true": True,
    "false": False,
    "null": None,
    "True": True,
    "False": False,
    "None": None,
}
_VALUE_KINDS = frozenset({"str", "num", "lit", "{", "["})

Token = tuple[str, Any]


class JsonRepairError(ValueError):
    """The text cannot be read as JSON, even leniently, within the limits."""


def _unescape(body: str) -> str:
    """Decode the escapes of a string body; invalid escapes keep the escaped character."""
    try:
        return str(json.loads(f'"{body}"', strict=False))
    except ValueError:
        pass

    def one(m: re.Match[str]) -> str:
        code = m.group(1)
        if len(code) == 5:
            return chr(int(code[1:], 16))
        return _SIMPLE_ESCAPES.get(code, code)

    return _ESCAPE.sub(one, body)


def _string(token: str) -> str:
    quote = token[0]
    body = token[1:-1] if len(token) > 1 and token.endswith(quote) else token[1:]
    if body.endswith("\\") and (len(body) - len(body.rstrip("\\"))) % 2:
        body = body[:-1]  # a lone backslash left by a cut-off answer
    if quote == "'":
        body = body.replace("\\'", "'")
    return _unescape(body)


def _number(token: str) -> int | float:
    if _INT.fullmatch(token):
        try:
            return int(token)
        except ValueError:  # more digits than int() converts
            pass
    return float(token)


def _classify(token: str) -> Token | None:
    """(kind, value) of one regex token; None for whitespace and stray characters."""
    first = token[0]
    if first in "\"'":
        return "str", _string(token)
    if first in "{}[]:,":
        return first, None
    if first.isdigit() or (first in "-." and len(token) > 1):
        return "num", _number(token)
    if first.isalpha() or first == "_":
        if token in _LITERALS:
            return "lit", _LITERALS[token]
        return "str", token
    return None


def tokenize(text: str) -> list[Token]:
    """The meaningful tokens of ``text`` (strings decoded, numbers converted)."""
    tokens = []
    for m in _TOKEN.finditer(text):
        token = _classify(m.group())
        if token is not None:
            tokens.append(token)
    return tokens


class _Parser:
    """Recursive descent that never fails on a token: it skips what does not fit."""

    def __init__(self, tokens: list[Token], max_depth: int) -> None:
        self.tokens = tokens
        self.i = 0
        self.max_depth = max_depth

    def peek(self) -> str | None:
        return self.tokens[self.i][0] if self.i < len(self.tokens) else None

    def value(self, depth: int) -> Any:
        kind, value = self.tokens[self.i]
        self.i += 1
        if kind in ("{", "["):
            if depth >= self.max_depth:
                raise JsonRepairError(f"nested deeper than {self.max_depth} levels")
            return self.object(depth + 1) if kind == "{" else self.array(depth + 1)
        return value

    def object(self, depth: int) -> dict[str, Any]:
        out: dict[str, Any] = {}
        while (kind := self.peek()) is not None:
            if kind == "}":
                self.i += 1
                break
            if kind not in ("str", "num", "lit"):
                self.i += 1  # a stray comma, colon, bracket or nested value where a key belongs
                continue
            key = self.tokens[self.i][1]
            self.i += 1
            if self.peek() == ":":
                self.i += 1
            has_value = self.peek() in _VALUE_KINDS
            out[key if isinstance(key, str) else json.dumps(key)] = (
                self.value(depth) if has_value else None
            )
        return out

    def array(self, depth: int) -> list[Any]:
        out: list[Any] = []
        while (kind := self.peek()) is not None:
            if kind == "]":
                self.i += 1
                break
            if kind == "}":
                break  # the enclosing object ends: the array was never closed
            if kind in _VALUE_KINDS:
                out.append(self.value(depth))
            else:
                self.i += 1
        return out


def repair_json(
    text: str, *, max_chars: int = REPAIR_MAX_CHARS, max_depth: int = REPAIR_MAX_DEPTH
) -> Any:
    """The first JSON value in near-JSON ``text``; raise :class:`JsonRepairError` when there is
    none or the text is over ``max_chars`` characters or nested deeper than ``max_depth``."""
    if len(text) > max_chars:
        raise JsonRepairError(
            f"the JSON object is {len(text):,} characters long, over the {max_chars:,} "
            "that are repaired"
        )
    parser = _Parser(tokenize(text), max_depth)
    while (kind := parser.peek()) is not None and kind not in _VALUE_KINDS:
        parser.i += 1
    if kind is None:
        raise JsonRepairError("no JSON value found")
    return parser.value(0)
