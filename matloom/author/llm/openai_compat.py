"""OpenAI-compatible Chat Completions adapter (the ``openai`` SDK against any ``base_url``).

Retries are done here rather than by the SDK so every attempt is counted and the back-off is
configurable: 429, 5xx, timeouts and connection errors are retried ``max_retries`` times with
``backoff_s * 1.5**r + U(0, backoff_s)`` waits; empty replies are retried too (as the reference
does). Other 4xx errors fail at once with a message saying what to fix. Error messages never
carry the API key or the base URL's credentials (:mod:`matloom.author.redact`), even when the
server echoes the request's ``Authorization`` header in its error body.
"""

from __future__ import annotations

import base64
import random
import time
from collections.abc import Sequence
from typing import Any

from matloom.author.config import ModelSettings, api_key_for
from matloom.author.llm.base import (
    ChatMessage,
    ChatReply,
    ModelError,
    ModelTimeoutError,
    ModelUnavailableError,
    register_provider,
)
from matloom.author.redact import URL_REDACTED, Redactor, redact_url
from matloom.author.replies import clean_text

#: Placeholder key for local servers that need none (the SDK refuses an empty key).
NO_KEY = "no-key-configured"
#: Replies that are empty or blank are retried this many times.
EMPTY_REPLY_RETRIES = 3


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

    def complete(self, messages: Sequence[ChatMessage]) -> ChatReply:
        """One answer, retrying transient failures and empty replies."""
        payload = to_openai_messages(messages)
        start = time.perf_counter()
        attempt = 0
        empty = 0
        while True:
            attempt += 1
            try:
                response = self._client.chat.completions.create(
                    messages=payload, **self._request_kwargs()
                )
            except Exception as err:  # noqa: BLE001 - classified below, re-raised if permanent
                self._handle_failure(err, attempt)
                self._backoff(attempt - 1)
                continue
            text, finish = _reply_text(response)
            if text.strip() or empty >= EMPTY_REPLY_RETRIES:
                if not text.strip():
                    raise ModelError(f"{self.model_id} returned {empty + 1} empty replies in a row")
                return ChatReply(
                    text=text,
                    model=getattr(response, "model", None) or self.model_id,
                    seconds=time.perf_counter() - start,
                    attempts=attempt,
                    finish_reason=finish,
                    usage=_usage(response),
                )
            empty += 1
            self._backoff(empty - 1)

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
        if isinstance(err, o.APITimeoutError):
            if retries_left:
                return
            raise ModelTimeoutError(
                f"{self.model_id} at {where} timed out {attempt} time(s) "
                f"(timeout {self.settings.timeout_s:g} s); raise timeout_s or check the server"
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


def _reply_text(response: Any) -> tuple[str, str | None]:
    """Text and finish reason of the first choice ('' when absent)."""
    choices = getattr(response, "choices", None) or []
    if not choices:
        return "", None
    message = choices[0].message
    text = clean_text(getattr(message, "content", None) or "")
    return text, getattr(choices[0], "finish_reason", None)


def _usage(response: Any) -> dict[str, int]:
    usage = getattr(response, "usage", None)
    if usage is None:
        return {}
    fields = ("prompt_tokens", "completion_tokens", "total_tokens")
    return {f: int(getattr(usage, f)) for f in fields if getattr(usage, f, None) is not None}


@register_provider("openai")
def _make_openai(settings: ModelSettings) -> OpenAICompatModel:
    return OpenAICompatModel(settings)
