"""Provider lookup: the built-in adapters are loaded here, never from :mod:`.base`, so the
adapters can import the registry in ``base`` without an import cycle."""

from __future__ import annotations

from matloom.author.config import ModelSettings
from matloom.author.llm.base import ChatModel, ModelError, registered_providers


def _load_builtin_providers() -> None:
    """Import the modules that register the built-in providers (idempotent, lazy)."""
    import matloom.author.llm.openai_compat  # noqa: F401
    import matloom.author.llm.scripted  # noqa: F401


def provider_names() -> list[str]:
    """Registered provider names (built-ins are loaded first)."""
    _load_builtin_providers()
    return sorted(registered_providers())


def get_model(settings: ModelSettings) -> ChatModel:
    """Instantiate the chat model described by ``settings``."""
    _load_builtin_providers()
    providers = registered_providers()
    factory = providers.get(settings.provider)
    if factory is None:
        known = ", ".join(sorted(providers))
        raise ModelError(f"unknown model provider {settings.provider!r} (known: {known})")
    return factory(settings)
