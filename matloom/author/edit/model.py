"""Edits by a chat model: the program, its parameters and the request in; a JSON edit out.

The model answers with one JSON object (see :data:`SYSTEM`): parameter assignments by
address, replacements of whole named lines when structure must change, View changes, and the
channels it means to change. The answer is applied, checked and held to its channels by the
locality report (:mod:`matloom.runtime.locality`); a bad answer, a failed check, changed seeds
or a leak goes back to the model with the diagnostics, at most ``repair_turns`` times. After
the last turn, a leak is reported (the edit is kept, ``report.ok`` is False); an answer that
cannot be applied raises :class:`~matloom.author.edit.core.EditError`.
"""

from __future__ import annotations

import json
from typing import TYPE_CHECKING, Any

from matloom.author.edit.core import (
    EditError,
    EditReport,
    EditResult,
    all_params,
    apply_edit,
    changes,
    parse_program,
    verify,
)
from matloom.author.llm.base import ChatMessage, ModelError, complete_within
from matloom.author.stages.critique_parse import first_json_object
from matloom.lang.deps import OUTPUTS
from matloom.lang.diagnostics import ProgramError
from matloom.runtime.locality import LOCALITY_SIZE

if TYPE_CHECKING:
    from matloom.author.llm.base import ChatModel
    from matloom.engine.session import Session
    from matloom.lang.params import Param

#: Longest reply read (characters).
MAX_REPLY_CHARS = 100_000

SYSTEM = f"""You edit MatLoom material programs. Make the SMALLEST edit that does what the
request asks and changes nothing else: prefer parameter assignments by address; replace a whole
Define or layer only when the structure must change. Never change a noise seed unless the
request asks for it.

Answer with exactly one JSON object and nothing else:
{{
  "assign": {{"ADDRESS": number or [r, g, b], ...}},
  "replace": {{"define:NAME": "Define(NAME, ...)", "layer:N": "Layer(...).channel(...)..."}},
  "view": {{"tileable": true, "unit_m": 0.25}},
  "channels": ["the output maps the edit means to change"],
  "note": "one line saying what you changed"
}}
Leave out the keys you do not need. Addresses are those of the parameter list. Layers are
numbered from 1, bottom first. Channel names: {", ".join(OUTPUTS)}. A change of a layer's
coverage ("alpha") may change every map; height also changes normal and ao.
"""


def _param_line(p: Param) -> str:
    value = list(p.value) if isinstance(p.value, tuple) else p.value
    lo = "-inf" if p.low is None else f"{p.low:g}"
    hi = "inf" if p.high is None else f"{p.high:g}"
    unit = f" {p.unit}" if p.unit else ""
    return (
        f"{p.address} = {value} ({p.kind}{unit}, range [{lo}, {hi}]; {p.label}; "
        f"affects {', '.join(p.affects) or 'nothing'})"
    )


def prompt(text: str, request: str) -> str:
    """The first user turn: the program, its parameters and the request."""
    params = all_params(parse_program(text))
    listed = "\n".join(_param_line(p) for p in params) or "(none)"
    return (
        f"<program>\n{text.strip()}\n</program>\n\n<parameters>\n{listed}\n</parameters>\n\n"
        f"<request>{request.strip()}</request>"
    )


def read_answer(reply: str) -> dict[str, Any]:
    """The first JSON object of a reply (bare, or in a ```json fence; found as the critic's
    answers are, :func:`~matloom.author.stages.critique_parse.first_json_object`); ValueError
    if none."""
    raw = first_json_object(reply) or ""
    try:
        data = json.loads(raw)
    except json.JSONDecodeError as err:
        raise ValueError(f"the answer is not one JSON object ({err.msg})") from None
    if not isinstance(data, dict):
        raise ValueError("the answer is not one JSON object")
    for key, kind in (("assign", dict), ("replace", dict), ("view", dict), ("channels", list)):
        if key in data and not isinstance(data[key], kind):
            raise ValueError(f"{key!r} must be a JSON {'object' if kind is dict else 'list'}")
    unknown = set(data) - {"assign", "replace", "view", "channels", "note"}
    if unknown:
        raise ValueError(f"unknown keys {sorted(unknown)}")
    channels = data.get("channels", [])
    bad = [c for c in channels if c not in OUTPUTS]
    if bad:
        raise ValueError(f"unknown channels {bad}; channels: {', '.join(OUTPUTS)}")
    if not (data.get("assign") or data.get("replace") or data.get("view")):
        raise ValueError("the answer changes nothing: give assign, replace or view")
    return data


def edit_with_model(
    text: str,
    request: str,
    model: ChatModel,
    *,
    repair_turns: int = 2,
    size: int = LOCALITY_SIZE,
    session: Session | None = None,
) -> EditResult:
    """Ask ``model`` for the edit and verify it (see the module docstring)."""
    before = parse_program(text)
    messages = [ChatMessage("system", SYSTEM), ChatMessage("user", prompt(text, request))]
    rejected: list[str] = []
    last: EditResult | None = None
    for turn in range(repair_turns + 1):
        try:
            reply = complete_within(model, messages, MAX_REPLY_CHARS)
        except ModelError as err:
            raise EditError(f"the model failed: {err}") from None
        messages.append(ChatMessage("assistant", reply.text))
        try:
            data = read_answer(reply.text)
            new_text, warnings = apply_edit(
                before, data.get("assign", {}), data.get("view"), data.get("replace")
            )
            after, report = verify(
                before, new_text, request, data.get("channels", []), size, session
            )
        except ProgramError as err:
            problem = "the edited program does not check:\n" + "\n".join(
                str(d) for d in err.diagnostics if d.is_error
            )
        except ValueError as err:
            problem = str(err)
        else:
            plan = {
                k: data[k] for k in ("assign", "replace", "view", "channels", "note") if k in data
            }
            last = EditResult(
                new_text,
                EditReport(
                    request,
                    "model",
                    plan,
                    changes(before, after),
                    warnings,
                    report,
                    turn,
                    list(rejected),
                ),  # fmt: skip
            )
            if report.ok:
                return last
            problem = (
                f"the edit leaks: {report.describe()}. Change only what the request asks, "
                "or list every channel the request means to change"
            )
        rejected.append(problem)
        if turn < repair_turns:
            messages.append(ChatMessage("user", f"{problem}\nAnswer again with one JSON object."))
    if last is not None:
        return last
    raise EditError(f"no usable edit after {repair_turns + 1} answers: {rejected[-1]}")
