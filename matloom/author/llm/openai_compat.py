"""OpenAI-compatible Chat Completions adapter (the ``openai`` SDK against any ``base_url``).

Retries are done here rather than by the SDK so every attempt is counted and the back-off is
configurable: 429, 5xx, timeouts and connection errors are retried ``max_retries`` times with
``backoff_s * 1.5**r + U(0, backoff_s)`` waits; bad replies (empty, or an HTTP-200 body that is
not a completion: :mod:`matloom.author.llm.completion`) are retried too, then raised as
:class:`~matloom.author.llm.base.BadReplyError`, which the stages record as a bad answer. Each
attempt is bounded (:mod:`matloom.author.llm.transport`): ``timeout_s`` of wall clock from
sending to the last byte, and a body of at most :func:`reply_byte_budget` bytes, past which the
reply is returned cut (``ChatReply.cut_at_bytes``) and refused by the stages as too large.
Other 4xx errors fail at once with a message saying what to fix. Error messages never carry the
API key or the base URL's credentials (:mod:`matloom.author.redact`), even when the server
echoes the request's ``Authorization`` header in its error body.
"""

from __future__ import annotations

import base64
import random
import time
from collections.abc import Sequence
from typing import Any

from matloom.author.config import ModelSettings, api_key_for
from matloom.author.llm.base import (
    BadReplyError,
    ChatMessage,
    ChatReply,
    ModelError,
    ModelTimeoutError,
    ModelUnavailableError,
    register_provider,
)
from matloom.author.llm.completion import MalformedReplyError, parse_completion, partial_content
from matloom.author.llm.transport import (
    DeadlineExceededError,
    RawReply,
    attach_trace,
    bounded_request,
    reply_byte_budget,
)
from matloom.author.redact import URL_REDACTED, Redactor, redact_url
from matloom.author.replies import CLIPPED_HEAD_CHARS

#: Placeholder key for local servers that need none (the SDK refuses an empty key).
NO_KEY = "no-key-configured"
#: Bad replies (empty or blank, or a malformed HTTP-200 body) are retried this many times.
BAD_REPLY_RETRIES = 3
#: The name this limit had when it covered only empty replies.
EMPTY_REPLY_RETRIES = BAD_REPLY_RETRIES
#: A bad-reply error quotes the reply (redacted first) up to this many characters.
BAD_REPLY_QUOTE_CHARS = 300


def to_openai_messages(messages: Sequence[ChatMessage]) -> list[dict[str, Any]]:
    """Chat Completions message dicts; images become ``image_url`` data-URL parts after the text."""
    out: list[dict[str, Any]] = []
    for m in messages:
        if not m.images:
            out.append({"role": m.role, "content": m.text})
            continue
        parts: list[dict[str, Any]] = [{"type": "text", "text": m.text}]
        for img in m.images:
            url = f"data:{img.mime};base64,{base64.b64encode(img.data).decode('ascii')}"
            parts.append({"type": "image_url", "image_url": {"url": url, "detail": "auto"}})
        out.append({"role": m.role, "content": parts})
    return out


class OpenAICompatModel:
    """A :class:`~matloom.author.llm.base.ChatModel` over the ``openai`` SDK."""

    def __init__(self, settings: ModelSettings) -> None:
        try:
            import openai
        except ImportError:
            raise ModelError(
                "the `openai` package is not installed; install the extra: pip install 'matloom[llm]'"
            ) from None
        if settings.base_url and URL_REDACTED in settings.base_url:
            raise ModelError(
                f"the base URL {settings.base_url} had credentials, which record.json does not "
                "store; pass --base-url (and --critic-base-url) again to resume this run"
            )
        self._openai = openai
        self.settings = settings
        self._redactor = Redactor.for_settings([settings])
        self._client = openai.OpenAI(
            base_url=settings.base_url,
            api_key=api_key_for(settings) or NO_KEY,
            timeout=settings.timeout_s,
            max_retries=0,
            # The hook lets each attempt find its socket, to shut it at the deadline.
            http_client=openai.DefaultHttpxClient(event_hooks={"request": [attach_trace]}),
        )

    @property
    def model_id(self) -> str:
        return self.settings.model

    @property
    def accepts_images(self) -> bool:
        return self.settings.accepts_images

    def _request_kwargs(self) -> dict[str, Any]:
        s = self.settings
        kwargs: dict[str, Any] = {"model": s.model}
        if s.max_completion_tokens is not None:
            kwargs["max_completion_tokens"] = s.max_completion_tokens
        if s.temperature is not None:
            kwargs["temperature"] = s.temperature
        if s.reasoning_effort is not None:
            kwargs["reasoning_effort"] = s.reasoning_effort
        if s.extra_body:
            kwargs["extra_body"] = dict(s.extra_body)
        return kwargs

    def _backoff(self, attempt: int) -> None:
        base = self.settings.backoff_s
        time.sleep(base * 1.5**attempt + random.uniform(0.0, base))

    def complete(
        self, messages: Sequence[ChatMessage], *, max_reply_chars: int | None = None
    ) -> ChatReply:
        """One answer, retrying transient failures and bad replies; a reply longer than
        ``max_reply_chars`` allows is returned cut (``cut_at_bytes``), not read whole."""
        payload = to_openai_messages(messages)
        budget = reply_byte_budget(max_reply_chars)
        start = time.perf_counter()
        attempt = 0
        bad = 0
        while True:
            attempt += 1
            try:
                raw = self._send(payload, budget)
            except Exception as err:  # noqa: BLE001 - classified below, re-raised if permanent
                self._handle_failure(err, attempt)
                self._backoff(attempt - 1)
                continue
            reply, problem = self._reply(raw, start, attempt)
            if reply is not None:
                return reply
            if bad >= BAD_REPLY_RETRIES:
                raise BadReplyError(self._bad_message(bad + 1, problem))
            bad += 1
            self._backoff(bad - 1)

    def _send(self, payload: list[dict[str, Any]], budget: int) -> RawReply:
        """One attempt, bounded in time and bytes."""
        kwargs = self._request_kwargs()

        def send() -> Any:
            return self._client.chat.completions.with_streaming_response.create(
                messages=payload, extra_headers={"Connection": "close"}, **kwargs
            )

        return bounded_request(send, timeout_s=self.settings.timeout_s, budget=budget)

    def _reply(self, raw: RawReply, start: float, attempt: int) -> tuple[ChatReply | None, str]:
        """The reply in ``raw``, or None and why it is unusable."""
        seconds = time.perf_counter() - start
        if raw.cut:
            head = partial_content(raw.body, CLIPPED_HEAD_CHARS)
            return ChatReply(head, self.model_id, seconds, attempt, cut_at_bytes=len(raw.body)), ""
        try:
            done = parse_completion(raw.body)
        except MalformedReplyError as err:
            return None, str(err)
        if not done.text.strip():
            return None, "an empty reply"
        return ChatReply(
            text=done.text,
            model=done.model or self.model_id,
            seconds=seconds,
            attempts=attempt,
            finish_reason=done.finish_reason,
            usage=done.usage,
        ), ""

    def _bad_message(self, count: int, last: str) -> str:
        """The error after ``count`` bad replies; a quoted reply is redacted, then clipped."""
        if last == "an empty reply":
            return f"{self.model_id} returned {count} empty replies in a row"
        last = self._redactor.text(last)
        if len(last) > BAD_REPLY_QUOTE_CHARS:
            last = last[:BAD_REPLY_QUOTE_CHARS] + " [...]"
        return f"{self.model_id} returned {count} unusable replies in a row; the last: {last}"

    def _handle_failure(self, err: Exception, attempt: int) -> None:
        """Raise a :class:`ModelError` (its message redacted) unless ``err`` is transient and
        retries remain."""
        try:
            self._classify_failure(err, attempt)
        except ModelError as failure:
            raise type(failure)(self._redactor.text(str(failure))) from None

    def _classify_failure(self, err: Exception, attempt: int) -> None:
        o = self._openai
        url = self.settings.base_url
        where = redact_url(url) if url else "the default OpenAI endpoint"
        retries_left = attempt <= self.settings.max_retries
        if isinstance(err, o.APITimeoutError | DeadlineExceededError):
            if retries_left:
                return
            raise ModelTimeoutError(
                f"{self.model_id} at {where} timed out {attempt} time(s) "
                f"(timeout {self.settings.timeout_s:g} s for all of a request, from sending it to the "
                "last byte of the reply); raise timeout_s or check the server"
            ) from None
        if isinstance(err, o.APIConnectionError):
            if retries_left:
                return
            raise ModelUnavailableError(
                f"cannot connect to {where} after {attempt} attempt(s): {err}; "
                "check --base-url and that the server is running"
            ) from None
        if isinstance(err, o.APIStatusError):
            status = err.status_code
            if (status == 429 or status >= 500) and retries_left:
                return
            raise ModelError(_status_message(self.model_id, where, status, err, attempt)) from None
        raise ModelError(f"{self.model_id} at {where}: unexpected error {err!r}") from None


def _status_message(model: str, where: str, status: int, err: Exception, attempts: int) -> str:
    if status in (401, 403):
        return (
            f"{where} refused the API key (HTTP {status}); set MATLOOM_API_KEY or OPENAI_API_KEY, "
            "or api_key_env in the matloom.toml profile"
        )
    if status == 404:
        return f"{where} does not know model {model!r} (HTTP 404); check --model"
    if status == 429 or status >= 500:
        return f"{model} at {where} still failing with HTTP {status} after {attempts} attempt(s)"
    return f"{model} at {where} rejected the request (HTTP {status}): {err}"


@register_provider("openai")
def _make_openai(settings: ModelSettings) -> OpenAICompatModel:
    return OpenAICompatModel(settings)
