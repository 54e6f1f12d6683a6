"""Edits by a chat model: the program, its parameters and the request in; a JSON edit out.

The prompt holds the program, its layers (coverage and channels), its parameters (each with
its label and the maps it affects), the library's overlays and the request. The model answers
with one JSON object (see :data:`SYSTEM`): parameter assignments by address, replacements of
whole named lines, added lines (new Defines and layers on top, with new seeds), library
overlays by name, View changes, and the channels it means to change. The answer is applied,
checked and held to its channels by the locality report (:mod:`matloom.runtime.locality`); a
bad answer, a failed check, a changed existing seed, a leak, or a change too small to see goes
back to the model with the reason, at most ``repair_turns`` times. After the last turn, a leak
is reported (the edit is kept, ``report.ok`` is False); an answer that cannot be applied raises
:class:`~matloom.author.edit.core.EditError`.
"""

from __future__ import annotations

import json
from typing import TYPE_CHECKING, Any

from matloom.author.edit.apply import (
    add_lines,
    all_params,
    apply_edit,
    parse_program,
    replace_lines,
)
from matloom.author.edit.conditions import library_overlays, overlay_lines
from matloom.author.edit.core import EditError, EditReport, EditResult, changes, verify
from matloom.author.llm.base import ChatMessage, ModelError, complete_within
from matloom.author.stages.critique_parse import first_json_object
from matloom.lang import ast as A
from matloom.lang.deps import OUTPUTS
from matloom.lang.diagnostics import ProgramError
from matloom.lang.layout import keep_layout
from matloom.lang.printer import format_expr
from matloom.runtime.locality import LOCALITY_SIZE

if TYPE_CHECKING:
    from matloom.author.llm.base import ChatModel
    from matloom.engine.session import Session
    from matloom.lang.params import Param

#: Longest reply read (characters).
MAX_REPLY_CHARS = 100_000
#: An answer none of whose intended maps moves visibly on this share of texels goes back.
VISIBLE_FRACTION = 0.02

SYSTEM = f"""You edit MatLoom material programs. Make the SMALLEST edit that does what the
request asks and changes nothing else, and make it CLEARLY VISIBLE in a small lit preview:
move a roughness by at least 0.25 (matte is about 0.8, glossy about 0.15), a sheen, clearcoat or
metallic by at least 0.3, a colour to a clearly different colour, a size or frequency by x1.5 to
x2, an amount by at least a third of its range; a step of a few percent does not show.

Prefer parameter assignments by address (the list gives each one's label and the maps it
affects: pick the one of the part the request names, e.g. the roughness used by the paint
layer for "the coating"). Replace a whole Define or layer when the structure must change. To
add something new ("add moss", "more scratches" where there are none), add lines: new Defines
and new layers on top (new noises need new seeds), or a library overlay by name. Never change
an existing noise seed unless the request asks for it.

Answer with exactly one JSON object and nothing else:
{{
  "assign": {{"ADDRESS": number or [r, g, b], ...}},
  "replace": {{"define:NAME": "Define(NAME, ...)", "layer:N": "Layer(...).channel(...)..."}},
  "add": ["Define(NEW, ...)", "Layer(NEW).basecolor(...)..."],
  "overlay": [{{"name": "OVERLAY", "amount": 0.5}}],
  "view": {{"tileable": true, "unit_m": 0.25, "window": [x1, y1, x2, y2]}},
  "channels": ["the output maps the edit means to change"],
  "note": "one line saying what you changed"
}}
Leave out the keys you do not need. Addresses are those of the parameter list. Layers are
numbered from 1, bottom first; added layers go on top, in order. Channel names:
{", ".join(OUTPUTS)}. A change of a layer's coverage ("alpha") may change every map; height
also changes normal and ao.
"""

#: Keys of an answer.
KEYS = ("assign", "replace", "add", "overlay", "view", "channels", "note")


def _param_line(p: Param) -> str:
    value = list(p.value) if isinstance(p.value, tuple) else p.value
    lo = "-inf" if p.low is None else f"{p.low:g}"
    hi = "inf" if p.high is None else f"{p.high:g}"
    unit = f" {p.unit}" if p.unit else ""
    return (
        f"{p.address} = {value} ({p.kind}{unit}, range [{lo}, {hi}]; {p.label}; "
        f"affects {', '.join(p.affects) or 'nothing'})"
    )


def _layer_line(program: A.Program, i: int) -> str:
    layer = program.layers[i]
    alpha = layer.alpha
    full = alpha is None or (isinstance(alpha, A.Num) and float(alpha.value) == 1)
    mask = "everywhere" if full else format_expr(alpha)  # type: ignore[arg-type]
    chans = ", ".join(ch.name for ch in layer.channels)
    return f"layer:{i + 1}: coverage {mask}; writes {chans}"


def prompt(text: str, request: str) -> str:
    """The first user turn: the program, its layers, its parameters (address = value, kind,
    range, label, the maps it affects), the library's overlays and the request."""
    program = parse_program(text)
    params = all_params(program)
    listed = "\n".join(_param_line(p) for p in params) or "(none)"
    layers = "\n".join(_layer_line(program, i) for i in range(len(program.layers)))
    overlays = "\n".join(f"{ov.name}: {ov.description}" for ov in library_overlays().values())
    return (
        f"<program>\n{text.strip()}\n</program>\n\n<layers>\n{layers}\n</layers>\n\n"
        f"<parameters>\n{listed}\n</parameters>\n\n<overlays>\n{overlays}\n</overlays>\n\n"
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
    kinds = (
        ("assign", dict),
        ("replace", dict),
        ("add", list),
        ("overlay", list),
        ("view", dict),
        ("channels", list),
    )
    if isinstance(data.get("overlay"), dict):
        data["overlay"] = [data["overlay"]]
    for key, kind in kinds:
        if key in data and not isinstance(data[key], kind):
            raise ValueError(f"{key!r} must be a JSON {'object' if kind is dict else 'list'}")
    unknown = set(data) - set(KEYS)
    if unknown:
        raise ValueError(f"unknown keys {sorted(unknown)}")
    channels = data.get("channels", [])
    bad = [c for c in channels if c not in OUTPUTS]
    if bad:
        raise ValueError(f"unknown channels {bad}; channels: {', '.join(OUTPUTS)}")
    if not any(data.get(k) for k in ("assign", "replace", "add", "overlay", "view")):
        raise ValueError("the answer changes nothing: give assign, replace, add, overlay or view")
    return data


def overlay_additions(program: A.Program, uses: list[Any]) -> tuple[list[str], list[str]]:
    """The added lines and channels of an answer's ``overlay`` list (ValueError for an unknown
    overlay or a bad amount)."""
    overlays = library_overlays()
    add: list[str] = []
    channels: list[str] = []
    for use in uses:
        name = use.get("name") if isinstance(use, dict) else use
        if name not in overlays:
            raise ValueError(f"no library overlay {name!r}; overlays: {', '.join(overlays)}")
        amount = use.get("amount") if isinstance(use, dict) else None
        if amount is not None and not (
            isinstance(amount, int | float) and not isinstance(amount, bool) and 0 <= amount <= 1
        ):
            raise ValueError(f"overlay {name!r}: amount is a number in [0, 1], got {amount!r}")
        lines, chans = overlay_lines(program, overlays[name], amount)
        add += lines
        channels += chans
        program = add_lines(program, lines)
    return add, channels


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
    small: EditResult | None = None  # the last answer that was local but hardly visible
    for turn in range(repair_turns + 1):
        try:
            reply = complete_within(model, messages, MAX_REPLY_CHARS)
        except ModelError as err:
            raise EditError(f"the model failed: {err}") from None
        messages.append(ChatMessage("assistant", reply.text))
        try:
            data = read_answer(reply.text)
            base = add_lines(replace_lines(before, data.get("replace", {})), data.get("add", []))
            extra, extra_channels = overlay_additions(base, data.get("overlay", []))
            channels = list(dict.fromkeys([*data.get("channels", []), *extra_channels]))
            new_text, warnings = apply_edit(
                before,
                data.get("assign", {}),
                data.get("view"),
                data.get("replace"),
                [*data.get("add", []), *extra],
            )
            checked = verify(before, new_text, request, channels, size, session)
            report = checked.locality
        except ProgramError as err:
            problem = "the edited program does not check:\n" + "\n".join(
                str(d) for d in err.diagnostics if d.is_error
            )
        except ValueError as err:
            problem = str(err)
        else:
            plan = {k: data[k] for k in KEYS if k in data}
            if extra:
                plan["channels"] = channels
            last = EditResult(
                keep_layout(text, new_text),  # only the changed lines differ
                EditReport(
                    request,
                    "model",
                    plan,
                    changes(before, checked.program),
                    warnings,
                    report,
                    turn,
                    list(rejected),
                ),  # fmt: skip
            )
            shows = checked.shows(VISIBLE_FRACTION) or not report.changed
            if report.ok and (shows or turn == repair_turns):
                return last
            if report.ok:
                small = last
                problem = (
                    f"the edit is too small to see ({report.describe()}, but no map moved "
                    "visibly): make the change clearly visible, keeping it to the same part"
                )
            else:
                problem = (
                    f"the edit leaks: {report.describe()}. Change only what the request asks, "
                    "or list every channel the request means to change"
                )
        rejected.append(problem)
        if turn < repair_turns:
            messages.append(ChatMessage("user", f"{problem}\nAnswer again with one JSON object."))
    if small is not None:
        return small
    if last is not None:
        return last
    raise EditError(f"no usable edit after {repair_turns + 1} answers: {rejected[-1]}")
