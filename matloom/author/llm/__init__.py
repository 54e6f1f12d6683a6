"""Chat-model backends: the :class:`ChatModel` protocol, the provider registry and adapters."""

from matloom.author.llm.base import (
    BadReplyError,
    ChatMessage,
    ChatModel,
    ChatReply,
    ImageInput,
    ModelError,
    ModelTimeoutError,
    ModelUnavailableError,
    complete_within,
    register_provider,
)
from matloom.author.llm.providers import get_model, provider_names

__all__ = [
    "BadReplyError",
    "ChatMessage",
    "ChatModel",
    "ChatReply",
    "ImageInput",
    "ModelError",
    "ModelTimeoutError",
    "ModelUnavailableError",
    "complete_within",
    "get_model",
    "provider_names",
    "register_provider",
]
