"""The small chat-model interface every backend implements, and the provider registry.

A backend is anything with ``model_id``, ``accepts_images`` and ``complete(messages)``. The
built-in OpenAI-compatible adapter is itself just one registered provider (as in simonw/llm);
tests register a scripted model through the same :func:`register_provider`. A backend whose
``complete`` also takes a ``max_reply_chars`` keyword is told the reply-size cap, so it can stop
reading a reply that is over it (:func:`complete_within`).
"""

from __future__ import annotations

import inspect
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from typing import Any, Literal, Protocol, runtime_checkable

from matloom.author.config import ModelSettings

Role = Literal["system", "user", "assistant"]


@dataclass(frozen=True)
class ImageInput:
    """An image attached to a user turn: encoded bytes plus their MIME type."""

    data: bytes
    mime: str = "image/jpeg"
    #: Where the image is stored in the run folder (for the record), if it is.
    path: str | None = None


@dataclass(frozen=True)
class ChatMessage:
    """One turn of a conversation; images (user turns only) follow the text."""

    role: Role
    text: str
    images: tuple[ImageInput, ...] = ()

    def to_record(self) -> dict[str, Any]:
        """JSON form for ``record.json`` (images by path, never inline bytes)."""
        out: dict[str, Any] = {"role": self.role, "text": self.text}
        if self.images:
            out["images"] = [
                img.path or f"<{img.mime}, {len(img.data)} bytes>" for img in self.images
            ]
        return out

    @classmethod
    def from_record(cls, data: dict[str, Any]) -> ChatMessage:
        """Inverse of :meth:`to_record`; image bytes are not restored (history is text-only)."""
        return cls(role=data["role"], text=data["text"])


@dataclass(frozen=True)
class ChatReply:
    """A model's answer and what it cost."""

    text: str
    model: str
    seconds: float
    attempts: int = 1
    finish_reason: str | None = None
    usage: dict[str, int] = field(default_factory=dict)
    #: Set when reading stopped after this many bytes because the reply was longer than
    #: ``max_reply_chars`` allows: ``text`` is then only the start of the reply.
    cut_at_bytes: int | None = None


class ModelError(RuntimeError):
    """A chat call failed for good (after retries); the message is meant for the user."""


class BadReplyError(ModelError):
    """The server answered, but with no usable reply (malformed, or empty), after retries.

    A bad answer like any other: the stages record it and ask again, it never ends a run on its
    own (the critic's answer then counts as unusable, the generator's attempt as ``bad_reply``).
    """


class ModelUnavailableError(ModelError):
    """The endpoint could not be reached (connection refused, DNS, TLS)."""


class ModelTimeoutError(ModelError):
    """Every attempt timed out."""


@runtime_checkable
class ChatModel(Protocol):
    """What the pipeline needs from a chat backend."""

    @property
    def model_id(self) -> str: ...

    @property
    def accepts_images(self) -> bool: ...

    def complete(self, messages: Sequence[ChatMessage]) -> ChatReply:
        """Answer the conversation; raise :class:`ModelError` on a permanent failure."""
        ...


def complete_within(
    model: ChatModel, messages: Sequence[ChatMessage], max_reply_chars: int
) -> ChatReply:
    """``model.complete(messages)``, passing the reply-size cap to backends that take it (a
    backend written before the cap existed is called as before)."""
    if "max_reply_chars" in inspect.signature(model.complete).parameters:
        return model.complete(messages, max_reply_chars=max_reply_chars)  # type: ignore[call-arg]
    return model.complete(messages)


ProviderFactory = Callable[[ModelSettings], ChatModel]
_PROVIDERS: dict[str, ProviderFactory] = {}


def register_provider(name: str) -> Callable[[ProviderFactory], ProviderFactory]:
    """Decorator registering a factory ``ModelSettings -> ChatModel`` under ``name``."""

    def decorate(factory: ProviderFactory) -> ProviderFactory:
        _PROVIDERS[name] = factory
        return factory

    return decorate


def registered_providers() -> dict[str, ProviderFactory]:
    """The providers registered so far, by name (a copy; :mod:`matloom.author.llm.providers`
    loads the built-in ones first)."""
    return dict(_PROVIDERS)
