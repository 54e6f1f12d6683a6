"""Stage I: one generator turn with parser-guided repair (reference-engine.md §8.3).

A turn sends the committed conversation plus a new user message, then up to ``repair_turns``
corrective turns carrying the parser's structured diagnostics (code, line:column, caret excerpt,
expectation, hint). An accepted program gets explicit seeds, and the last assistant turn is
rewritten to show the model its canonical text. The conversation in the record only grows when
a program is accepted, so a resumed run restarts an interrupted turn from a clean state. A reply
over the reply-size cap (:mod:`matloom.author.replies`) is not parsed: the attempt is recorded
as ``too_large`` with the reply clipped, and the model is asked again like after any bad reply.
"""

from __future__ import annotations

import time
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Literal

from matloom.author.config import DEFAULT_MAX_REPLY_CHARS
from matloom.author.llm.base import ChatMessage, ChatModel
from matloom.author.prompts.revision import (
    canonical_assistant_turn,
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
from matloom.author.replies import clip_reply, oversize_error
from matloom.lang.api import analyse
from matloom.lang.extract import extract_program
from matloom.lang.printer import format_program
from matloom.lang.seeds import canonicalize_seeds


class NoParseableProgramError(RuntimeError):
    """The model never produced a program that parses (after all repair turns)."""


Notify = Callable[[str], None]


def committed_messages(store: RecordStore) -> list[ChatMessage]:
    """System prompt plus the committed generator conversation, as chat messages."""
    system = store.record.system_prompt or ""
    history = [ChatMessage(role=m.role, text=m.text) for m in store.record.conversation]
    return [ChatMessage(role="system", text=system), *history]


def _check(program_text: str) -> tuple[str | None, list[dict[str, object]], str | None]:
    """(canonical text or None, error dicts, repair message or None) for extracted text."""
    program, diags = analyse(program_text)
    errors = [d for d in diags if d.is_error]
    if program is None or errors:
        return None, [d.to_dict() for d in errors], diagnostics_message(program_text, errors)
    return format_program(program), [], None


@dataclass
class _Outcome:
    """What one reply of a turn came to."""

    outcome: Literal["accepted", "no_program", "parse_error", "too_large"]
    canonical: str | None = None
    preamble: str = ""
    errors: list[dict[str, object]] = field(default_factory=list)
    repair: str = ""
    error: str | None = None


def _read_reply(text: str, max_reply_chars: int) -> _Outcome:
    """Extract and check the program of one reply (refused unread when over the cap)."""
    if len(text) > max_reply_chars:
        return _Outcome(
            "too_large",
            repair=reply_too_large_message(len(text), max_reply_chars),
            error=oversize_error(len(text), max_reply_chars),
        )
    program_text, preamble = extract_program(text)
    if program_text is None:
        return _Outcome("no_program", preamble=preamble, repair=missing_program_message())
    canonical, errors, repair = _check(program_text)
    if canonical is None:
        return _Outcome("parse_error", preamble=preamble, errors=errors, repair=repair or "")
    return _Outcome("accepted", canonical=canonical, preamble=preamble)


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
) -> ProgramRecord:
    """Run one generation/revision turn to an accepted program; record every attempt."""
    record = store.record
    index = len(record.programs)
    turn = TurnRecord(program_index=index, kind="initial" if index == 0 else "revision")
    record.turns.append(turn)
    store.save()  # the record shows the turn in flight
    user = ChatMessage(role="user", text=user_text)
    working = [*committed_messages(store), user]
    start = time.perf_counter()
    for attempt in range(1, repair_turns + 2):
        if notify:
            notify(f"{kind} P{index}, attempt {attempt}")
        t0 = time.perf_counter()
        reply = model.complete(working)
        read = _read_reply(reply.text, max_reply_chars)
        shown = clip_reply(reply.text, max_reply_chars)
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
            return _accept(
                store, turn, working, read.preamble, read.canonical, reply.text, program_seed, start
            )
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


def _accept(
    store: RecordStore,
    turn: TurnRecord,
    working: list[ChatMessage],
    preamble: str,
    canonical: str,
    authored: str,
    program_seed: int,
    start: float,
) -> ProgramRecord:
    """Pin seeds, commit the conversation with the canonical assistant turn, store P_k."""
    from matloom.lang.api import parse

    pinned = format_program(canonicalize_seeds(parse(canonical), program_seed))
    record = store.record
    shown = canonical_assistant_turn(preamble, pinned)
    record.conversation = [MessageRecord(role=m.role, text=m.text) for m in working[1:]] + [
        MessageRecord(role="assistant", text=shown)
    ]
    program = ProgramRecord(
        index=turn.program_index,
        text=pinned,
        authored=authored,
        source="generator",
        program_seed=program_seed,
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
