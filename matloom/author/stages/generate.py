"""Stage I: one generator turn with parser-guided repair (reference-engine.md §8.3).

A turn sends the committed conversation plus a new user message (with images, when it has
any), then up to ``repair_turns`` corrective turns carrying the parser's structured diagnostics
(code, line:column, caret excerpt, expectation, hint). The program of a reply is its last
``<material>...</material>`` block (thinking before it is welcome), else what
:func:`matloom.lang.extract.extract_program` finds. An accepted program gets explicit seeds in
its canonical text, which is what is rendered and recorded; the conversation keeps the model's
own reply, so the model goes on editing the text it wrote, and the seeds given to the noise it
left unseeded are recorded for the revision turn to tell it. The conversation in the record
only grows when a program is accepted, so a resumed run restarts an interrupted turn from a
clean state. A reply over the reply-size cap (:mod:`matloom.author.replies`) is not parsed: the
attempt is recorded as ``too_large`` with the reply clipped, and the model is asked again like
after any bad reply. A call that got no usable reply at all (:class:`BadReplyError`: malformed or
empty, after the backend's own retries) is recorded as ``bad_reply`` and the same request sent
again, counted against the same attempts.
"""

from __future__ import annotations

import re
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field, replace
from typing import Literal

from matloom.author.config import DEFAULT_MAX_REPLY_CHARS
from matloom.author.llm.base import (
    BadReplyError,
    ChatMessage,
    ChatModel,
    ChatReply,
    ImageInput,
    complete_within,
)
from matloom.author.prompts.revision import (
    diagnostics_message,
    missing_program_message,
    reply_too_large_message,
)
from matloom.author.records import (
    AttemptRecord,
    MessageRecord,
    ProgramRecord,
    RecordStore,
    TurnRecord,
)
from matloom.author.replies import refusal, shown_reply
from matloom.lang import ast as A
from matloom.lang.api import analyse
from matloom.lang.diagnostics import Severity
from matloom.lang.extract import extract_program
from matloom.lang.printer import format_program
from matloom.lang.rewrite import map_program
from matloom.lang.seeds import canonicalize_seeds, derive_seed, uses_seed

_OPEN_TAG = re.compile(r"<material>", re.IGNORECASE)
_CLOSE_TAG = re.compile(r"</material>", re.IGNORECASE)


class NoParseableProgramError(RuntimeError):
    """The model never produced a program that parses (after all repair turns)."""


Notify = Callable[[str], None]


def extract_answer(reply: str) -> tuple[str | None, str]:
    """``(program_text, preamble)`` of a reply: its last ``<material>...</material>`` block
    (the text before it is the preamble), else :func:`extract_program` of the whole reply.
    Linear in the reply's length."""
    last_close = None
    for last_close in _CLOSE_TAG.finditer(reply):  # noqa: B007 - the last one is wanted
        pass
    if last_close is not None:
        last_open = None
        for match in _OPEN_TAG.finditer(reply, 0, last_close.start()):
            last_open = match
        if last_open is not None:
            program, preamble = extract_program(reply[last_open.start() :])
            return program, reply[: last_open.start()] + preamble
    return extract_program(reply)


def _seedless_calls(program: A.Program) -> list[A.Call]:
    """The noise calls without a seed, in the order :func:`canonicalize_seeds` numbers them."""
    calls: list[A.Call] = []

    def visit(node: A.Node) -> A.Node:
        if isinstance(node, A.Call) and uses_seed(node) and node.arg("seed") is None:
            calls.append(node)
        return node

    map_program(program, visit)
    return calls


def added_seed_notes(source: str, canonical: str, program_seed: int) -> list[str]:
    """The seeds :func:`canonicalize_seeds` gives the seedless noise calls of the model's
    program ``source`` (whose canonical text is ``canonical``), each as
    ``fBm at line 3, column 15: seed=123`` (positions in ``source``)."""
    from matloom.lang.api import parse

    numbered = _seedless_calls(parse(canonical))
    written = _seedless_calls(parse(source))
    same = [c.func for c in written] == [c.func for c in numbered]
    notes = []
    for n, call in enumerate(numbered):
        where = f" at line {written[n].span.line}, column {written[n].span.col}" if same else ""
        notes.append(f"{call.func}{where}: seed={derive_seed(program_seed, n)}")
    return notes


def committed_messages(store: RecordStore) -> list[ChatMessage]:
    """System prompt plus the committed generator conversation, as chat messages (text only:
    images went with their own turn)."""
    system = store.record.system_prompt or ""
    history = [ChatMessage(role=m.role, text=m.text) for m in store.record.conversation]
    return [ChatMessage(role="system", text=system), *history]


def _check(
    program_text: str, refused: frozenset[str] = frozenset()
) -> tuple[str | None, list[dict[str, object]], str | None]:
    """(canonical text or None, error dicts, repair message or None) for extracted text;
    warnings whose code is in ``refused`` count as errors (a Define a built-in shadows)."""
    program, diags = analyse(program_text)
    errors = [
        d if d.is_error else replace(d, severity=Severity.ERROR)
        for d in diags
        if d.is_error or d.code in refused
    ]
    if program is None or errors:
        return None, [d.to_dict() for d in errors], diagnostics_message(program_text, errors)
    return format_program(program), [], None


@dataclass
class _Outcome:
    """What one reply of a turn came to."""

    outcome: Literal["accepted", "no_program", "parse_error", "too_large", "bad_reply"]
    canonical: str | None = None
    preamble: str = ""
    errors: list[dict[str, object]] = field(default_factory=list)
    repair: str = ""
    error: str | None = None
    #: The program text as the model wrote it (accepted replies).
    source: str = ""


def _read_reply(
    reply: ChatReply, max_reply_chars: int, strict: frozenset[str] = frozenset()
) -> _Outcome:
    """Extract and check the program of one reply (refused unread when over the cap)."""
    refused = refusal(reply, max_reply_chars)
    if refused is not None:
        length = None if reply.cut_at_bytes is not None else len(reply.text)
        return _Outcome(
            "too_large", repair=reply_too_large_message(length, max_reply_chars), error=refused
        )
    program_text, preamble = extract_answer(reply.text)
    if program_text is None:
        return _Outcome("no_program", preamble=preamble, repair=missing_program_message())
    canonical, errors, repair = _check(program_text, strict)
    if canonical is None:
        return _Outcome("parse_error", preamble=preamble, errors=errors, repair=repair or "")
    return _Outcome("accepted", canonical=canonical, preamble=preamble, source=program_text)


def run_turn(
    model: ChatModel,
    store: RecordStore,
    *,
    kind: str,
    user_text: str,
    program_seed: int,
    repair_turns: int,
    notify: Notify | None = None,
    max_reply_chars: int = DEFAULT_MAX_REPLY_CHARS,
    images: Sequence[ImageInput] = (),
    refused_warnings: frozenset[str] = frozenset(),
) -> ProgramRecord:
    """Run one generation/revision turn to an accepted program; record every attempt.

    ``kind``: ``generate``, ``draft`` (another first draft) or ``revise``; ``images`` go with
    the new user message (and its repairs), not with later turns;
    ``refused_warnings``: checker warnings answered with a repair turn like errors."""
    record = store.record
    index = len(record.programs)
    turn_kind: Literal["initial", "draft", "revision"] = (
        "initial" if index == 0 else "draft" if kind == "draft" else "revision"
    )
    turn = TurnRecord(program_index=index, kind=turn_kind)
    record.turns.append(turn)
    store.save()  # the record shows the turn in flight
    user = ChatMessage(role="user", text=user_text, images=tuple(images))
    working = [*committed_messages(store), user]
    start = time.perf_counter()
    for attempt in range(1, repair_turns + 2):
        if notify:
            notify(f"{kind} P{index}, attempt {attempt}")
        t0 = time.perf_counter()
        try:
            reply = complete_within(model, working, max_reply_chars)
        except BadReplyError as err:  # nothing to show or answer: ask the same again
            turn.attempts.append(_bad_attempt(attempt, str(err), t0, model.model_id))
            store.save()
            continue
        last = attempt == repair_turns + 1
        read = _read_reply(reply, max_reply_chars, refused_warnings)
        if last and read.outcome == "parse_error" and refused_warnings:
            # the last attempt: a program with only refused warnings is kept (it renders),
            # rather than failing the run; the warning reaches the revision turn
            lenient = _read_reply(reply, max_reply_chars)
            if lenient.canonical is not None:
                read = lenient
        shown = shown_reply(reply, max_reply_chars)
        turn.attempts.append(
            AttemptRecord(
                attempt=attempt,
                reply=shown,
                outcome=read.outcome,
                diagnostics=read.errors,
                error=read.error,
                seconds=time.perf_counter() - t0,
                model=reply.model,
            )
        )
        if read.canonical is not None:
            return _accept(store, turn, working, read, reply.text, program_seed, start)
        working += [
            ChatMessage(role="assistant", text=shown),
            ChatMessage(role="user", text=read.repair or missing_program_message()),
        ]
        store.save()
    turn.seconds = time.perf_counter() - start
    turn.error = f"no parseable program after {repair_turns + 1} attempt(s)"
    record.durations.generation.append(turn.seconds)
    store.save()
    raise NoParseableProgramError(turn.error)


def _bad_attempt(attempt: int, error: str, t0: float, model: str) -> AttemptRecord:
    return AttemptRecord(
        attempt=attempt,
        reply="",
        outcome="bad_reply",
        error=error,
        seconds=time.perf_counter() - t0,
        model=model,
    )


def _accept(
    store: RecordStore,
    turn: TurnRecord,
    working: list[ChatMessage],
    read: _Outcome,
    authored: str,
    program_seed: int,
    start: float,
) -> ProgramRecord:
    """Pin seeds, commit the conversation with the model's own reply, store P_k."""
    from matloom.lang.api import parse

    assert read.canonical is not None
    pinned = format_program(canonicalize_seeds(parse(read.canonical), program_seed))
    record = store.record
    turn_messages = working[1 + len(record.conversation) :]  # earlier turns keep their images
    record.conversation = [
        *record.conversation,
        *(MessageRecord(**m.to_record()) for m in turn_messages),
        MessageRecord(role="assistant", text=authored),
    ]
    program = ProgramRecord(
        index=turn.program_index,
        text=pinned,
        authored=authored,
        source="generator",
        program_seed=program_seed,
        added_seeds=added_seed_notes(read.source, read.canonical, program_seed),
    )
    record.programs.append(program)
    turn.accepted = True
    turn.seconds = time.perf_counter() - start
    record.durations.generation.append(turn.seconds)
    store.save()
    return program


def discard_unfinished_turns(store: RecordStore) -> int:
    """Drop turns that never produced a program (an interrupted run); return how many."""
    record = store.record
    keep = [t for t in record.turns if t.accepted or t.error]
    dropped = len(record.turns) - len(keep)
    record.turns = keep
    return dropped
