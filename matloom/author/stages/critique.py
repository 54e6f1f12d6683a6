"""Stage II: the critic (reference §8.4), with robust parsing and retries.

The critic sees a fresh conversation per program (so its scores stay comparable across rounds)
with any subset of: the preview render(s) in the configured layouts (only if the model takes
images), the statistics, the source. With ``critic_history`` it also sees the previous round's
render(s) and score and says whether this round is better. Critic loop v3 adds the measured
preview facts and structural changes (:class:`~matloom.author.prompts.critic.CriticOptions`) and
the score-only request (``score_only``: the answer holds the score, and the verdict on the
previous round, only). Its answer is parsed tolerantly
(:mod:`~matloom.author.stages.critique_parse`); a failure is retried with a follow-up message up
to ``retries`` times, so a bad critic answer ends as a failed critique in the record, never as
a failed run. A call that got no usable reply at all (:class:`BadReplyError`: a malformed or
empty body after the backend's own retries) is such a bad answer too: recorded as an empty
reply with its reason, and asked again.
"""

from __future__ import annotations

import time
from collections.abc import Collection, Sequence
from dataclasses import dataclass

from matloom.author.config import DEFAULT_MAX_REPLY_CHARS
from matloom.author.llm.base import (
    BadReplyError,
    ChatMessage,
    ChatModel,
    ChatReply,
    ImageInput,
    complete_within,
)
from matloom.author.prompts.critic import (
    PAPER,
    CriticOptions,
    PreviousView,
    critic_retry_message,
    critic_system_prompt,
    critic_user_message,
)
from matloom.author.records import CritiqueRecord, EditRecord, HistoryRecord, MessageRecord
from matloom.author.replies import clip_reply, refusal, shown_reply
from matloom.author.stages.critique_parse import (
    Critique,
    CritiqueParseError,
    first_json_object,
    parse_critique,
    strip_line_comments,
)

__all__ = [
    "Critique",
    "CritiqueParseError",
    "PreviousRound",
    "critique_program",
    "first_json_object",
    "parse_critique",
    "strip_line_comments",
]

#: An unusable answer is quoted back to the critic (in the retry) up to this many characters.
ECHO_MAX_CHARS = 8_000


@dataclass(frozen=True)
class PreviousRound:
    """The previous round as a critic with history sees it."""

    index: int
    score: int | None
    images: tuple[ImageInput, ...] = ()


def _read_answer(reply: ChatReply, max_reply_chars: int) -> Critique:
    """The critique in one answer; an answer over the size cap is refused unread."""
    refused = refusal(reply, max_reply_chars)
    if refused is not None:
        raise CritiqueParseError(refused)
    return parse_critique(reply.text)


def critique_program(
    model: ChatModel,
    description: str,
    program_index: int,
    program: str,
    *,
    signals: Collection[str],
    renders: Sequence[ImageInput] = (),
    views: Sequence[str] = ("flat",),
    stats: str | None,
    retries: int,
    history: bool = False,
    previous: PreviousRound | None = None,
    max_reply_chars: int = DEFAULT_MAX_REPLY_CHARS,
    options: CriticOptions = PAPER,
    score_only: bool = False,
) -> CritiqueRecord:
    """Run the critic on one program; never raises on a bad answer (``ok=False``).

    ``renders`` are this program's images in the layouts ``views``; ``history`` asks the
    better-or-worse question (from round 1 on, ``previous`` holds the previous round);
    ``options`` are the loop v3 parts of the prompts; ``score_only`` asks for the score only.
    """
    if "render" in signals and (not renders or not model.accepts_images):
        signals = [s for s in signals if s != "render"]
    sees = "render" in signals
    shown_previous = None
    if previous is not None:
        count = len(previous.images) if sees else 0
        shown_previous = PreviousView(previous.index, previous.score, count)
    images = (*renders, *(previous.images if previous and sees else ())) if sees else ()
    ask = {
        "edits": "code" in signals,
        "history": history and previous is not None,
        "structural": options.structural,
        "score_only": score_only,
    }
    user = critic_user_message(
        description,
        signals,
        program=program,
        stats=stats,
        views=views,
        previous=shown_previous,
        history=ask["history"],
        structural=options.structural,
        score_only=score_only,
    )
    system = critic_system_prompt(signals, views, history=history, options=options)
    messages = [
        ChatMessage(role="system", text=system),
        ChatMessage(role="user", text=user, images=tuple(images)),
    ]
    start = time.perf_counter()
    replies: list[str] = []
    error = "no answer"
    for _ in range(retries + 1):
        try:
            reply = complete_within(model, messages, max_reply_chars)
        except BadReplyError as err:  # nothing to quote back: ask the same again
            replies.append("")
            error = str(err)
            continue
        replies.append(shown_reply(reply, max_reply_chars))
        try:
            critique = _read_answer(reply, max_reply_chars)
        except CritiqueParseError as err:
            error = str(err)
            messages = [
                *messages,
                ChatMessage(role="assistant", text=clip_reply(reply.text, ECHO_MAX_CHARS)),
                ChatMessage(role="user", text=critic_retry_message(error, **ask)),
            ]
            continue
        return _record(
            program_index, signals, model, messages, replies, start, critique=critique,
            views=views if sees else (), renders=renders if sees else (), previous=previous,
            score_only=score_only,
        )  # fmt: skip
    return _record(
        program_index, signals, model, messages, replies, start, error=error,
        views=views if sees else (), renders=renders if sees else (), previous=previous,
        score_only=score_only,
    )  # fmt: skip


def _history(previous: PreviousRound | None, critique: Critique | None) -> HistoryRecord | None:
    if previous is None:
        return None
    return HistoryRecord(
        previous_index=previous.index,
        previous_score=previous.score,
        previous_renders=[img.path for img in previous.images if img.path],
        better=critique.better_than_previous if critique else None,
    )


def _record(  # noqa: PLR0913 - one record from everything a critique produced
    program_index: int,
    signals: Collection[str],
    model: ChatModel,
    messages: list[ChatMessage],
    replies: list[str],
    start: float,
    *,
    views: Sequence[str],
    renders: Sequence[ImageInput],
    previous: PreviousRound | None,
    critique: Critique | None = None,
    error: str | None = None,
    score_only: bool = False,
) -> CritiqueRecord:
    paths = [img.path for img in renders if img.path]
    return CritiqueRecord(
        program_index=program_index,
        ok=critique is not None,
        match_score=critique.match_score if critique else None,
        differences=critique.differences if critique else [],
        suggestions=critique.suggestions if critique else [],
        edits=[EditRecord(**e.model_dump()) for e in critique.edits] if critique else [],
        structural=critique.structural if critique else [],
        score_only=score_only,
        signals=list(signals),
        render=paths[0] if paths else None,
        views=list(views),
        renders=paths,
        history=_history(previous, critique),
        model=model.model_id,
        attempts=len(replies),
        seconds=time.perf_counter() - start,
        messages=[MessageRecord(**m.to_record()) for m in messages],
        replies=replies,
        error=None
        if critique
        else f"unparseable critique after {len(replies)} attempt(s): {error}",
    )
