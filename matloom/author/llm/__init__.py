"""Chat-model backends: the :class:`ChatModel` protocol, the provider registry and adapters."""

from matloom.author.llm.base import (
    ChatMessage,
    ChatModel,
    ChatReply,
    ImageInput,
    ModelError,
    ModelTimeoutError,
    ModelUnavailableError,
    get_model,
    provider_names,
    register_provider,
)

__all__ = [
    "ChatMessage",
    "ChatModel",
    "ChatReply",
    "ImageInput",
    "ModelError",
    "ModelTimeoutError",
    "ModelUnavailableError",
    "get_model",
    "provider_names",
    "register_provider",
]
