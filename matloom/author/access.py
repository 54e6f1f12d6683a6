"""The one line the CLI prints about each model's access: the model, the server its requests go
to (credentials redacted) and the variable its API key is read from."""

from __future__ import annotations

import os

from matloom.author.config import DEFAULT_BASE_URL, ModelSettings, api_key_source, key_variables
from matloom.author.redact import redact_url


def server_of(settings: ModelSettings) -> str:
    """The server requests go to, as the ``openai`` client picks it, credentials redacted."""
    if settings.provider != "openai":
        return f"the {settings.provider!r} provider (in-process)"
    url = settings.base_url or os.environ.get("OPENAI_BASE_URL") or DEFAULT_BASE_URL
    return redact_url(url)


def describe_access(role: str, settings: ModelSettings) -> str:
    """One line naming the model, the server and the key variable a role's requests use."""
    source = api_key_source(settings)
    if settings.provider != "openai":
        key = "no API key"
    elif source:
        key = f"API key from ${source}"
    else:
        key = "no API key ($" + ", $".join(key_variables(settings)) + " unset)"
    return f"{role} {settings.model} at {server_of(settings)}, {key}"
