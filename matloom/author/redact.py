"""Keep credentials out of everything a run stores or prints.

The secrets of a run are the API keys of its generator and critic (read from the environment,
never part of the config) and the credentials a base URL can carry: ``user:password@`` and the
query string (``?key=...``). :class:`Redactor` replaces them:

* every base URL, wherever it appears, by its :func:`redact_url` form
  (``https://REDACTED@host/v1?key=REDACTED``), so ``record.json`` stores no URL credentials;
* every secret of at least :data:`MIN_SECRET_CHARS` characters, wherever it appears (an error
  body that echoes the ``Authorization`` header, say), by :data:`REDACTED`. Shorter strings are
  left alone in free text: they would match ordinary words of the record.

The record, text artefacts, model error messages and the CLI's error output all go through it.
A resumed run whose recorded base URL was redacted needs ``--base-url`` again.

``extra_body`` (``--extra-body``, a profile's table) is merged into every request and can carry
tokens, so it is treated like the key: ``record.json`` keeps its shape with every string value
replaced (:func:`redact_extra_body`), and its strings of :data:`EXTRA_BODY_SECRET_CHARS` or more are redacted wherever they appear.
A resumed run that had string values there needs ``--extra-body`` (or ``--profile``) again.
"""

from __future__ import annotations

import base64
import json
from collections.abc import Iterable
from dataclasses import dataclass
from typing import Any
from urllib.parse import unquote, urlsplit, urlunsplit

from matloom.author.config import AuthorConfig, ModelSettings, api_key_for

#: What a secret is replaced by in free text.
REDACTED = "[REDACTED]"
#: What URL credentials are replaced by (URL-safe, so the redacted URL still reads as one).
URL_REDACTED = "REDACTED"
#: Secrets shorter than this are replaced only as part of their URL, not in free text.
MIN_SECRET_CHARS = 8
#: ``extra_body`` strings replaced in free text: from this length (a token is longer; shorter
#: ones are ordinary settings like "high", whose replacement could break a program's text).
EXTRA_BODY_SECRET_CHARS = 16


def redact_url(url: str) -> str:
    """``url`` with its userinfo, every query value and its fragment replaced by REDACTED."""
    try:
        parts = urlsplit(url)
    except ValueError:
        return URL_REDACTED
    netloc = parts.netloc
    if "@" in netloc:
        netloc = f"{URL_REDACTED}@{netloc.rsplit('@', 1)[1]}"
    query = "&".join(_redact_pair(pair) for pair in parts.query.split("&")) if parts.query else ""
    fragment = URL_REDACTED if parts.fragment else ""
    return urlunsplit((parts.scheme, netloc, parts.path, query, fragment))


def _redact_pair(pair: str) -> str:
    name, sep, value = pair.partition("=")
    if not sep:
        return URL_REDACTED if name else ""
    return f"{name}={URL_REDACTED}" if value else pair


def url_secrets(url: str) -> list[str]:
    """The credentials in ``url``: userinfo, its parts and its HTTP Basic form (the client sends
    it as ``Authorization: Basic ...``), query values, the fragment."""
    try:
        parts = urlsplit(url)
    except ValueError:
        return [url]
    found: list[str] = []
    if "@" in parts.netloc:
        userinfo = parts.netloc.rsplit("@", 1)[0]
        basic = base64.b64encode(unquote(userinfo).encode("utf-8")).decode("ascii")
        found += [userinfo, *userinfo.split(":", 1), basic]
    for pair in parts.query.split("&") if parts.query else ():
        found.append(pair.partition("=")[2] if "=" in pair else pair)
    found.append(parts.fragment)
    return [s for raw in found if raw for s in {raw, unquote(raw)}]


def _strings(value: Any) -> list[str]:
    """Every string value inside a JSON-like value (dict keys excluded)."""
    if isinstance(value, str):
        return [value]
    if isinstance(value, dict):
        return [s for v in value.values() for s in _strings(v)]
    if isinstance(value, list | tuple):
        return [s for v in value for s in _strings(v)]
    return []


def redact_extra_body(body: dict[str, Any] | None) -> dict[str, Any] | None:
    """``body`` with every string value (at any depth) replaced by :data:`REDACTED`."""

    def clean(value: Any) -> Any:
        if isinstance(value, str):
            return REDACTED
        if isinstance(value, dict):
            return {k: clean(v) for k, v in value.items()}
        if isinstance(value, list | tuple):
            return [clean(v) for v in value]
        return value

    return None if body is None else clean(body)


def has_redacted_values(body: dict[str, Any] | None) -> bool:
    """True when ``body`` holds a value :func:`redact_extra_body` replaced."""
    return REDACTED in _strings(body)


def redact_settings(config: AuthorConfig) -> AuthorConfig:
    """``config`` as ``record.json`` stores it: the models' ``extra_body`` redacted."""
    update = {
        role: settings.model_copy(update={"extra_body": redact_extra_body(settings.extra_body)})
        for role in ("generator", "critic")
        if (settings := getattr(config, role)) is not None and settings.extra_body
    }
    return config.model_copy(update=update) if update else config


def _settings_secrets(settings: ModelSettings) -> list[str]:
    key = api_key_for(settings)
    found = [key] if key else []
    found += url_secrets(settings.base_url) if settings.base_url else []
    extra = _strings(settings.extra_body)
    return found + [s for s in extra if len(s) >= EXTRA_BODY_SECRET_CHARS and s != REDACTED]


@dataclass(frozen=True)
class Redactor:
    """Replaces the base URLs and secrets it was built with; see the module docstring."""

    urls: tuple[tuple[str, str], ...] = ()
    secrets: tuple[str, ...] = ()

    @classmethod
    def for_settings(cls, settings: Iterable[ModelSettings | None]) -> Redactor:
        given = [s for s in settings if s is not None]
        urls = {s.base_url: redact_url(s.base_url) for s in given if s.base_url}
        secrets = {x for s in given for x in _settings_secrets(s) if len(x) >= MIN_SECRET_CHARS}
        return cls(
            urls=tuple((raw, safe) for raw, safe in urls.items() if raw != safe),
            secrets=tuple(sorted(secrets, key=len, reverse=True)),
        )

    @classmethod
    def for_config(cls, config: AuthorConfig | None) -> Redactor:
        """The redactor of a run's models (generator and critic)."""
        if config is None:
            return cls()
        return cls.for_settings([config.generator, config.critic])

    def _needles(self) -> list[str]:
        return [raw for raw, _ in self.urls] + list(self.secrets)

    def text(self, text: str) -> str:
        """``text`` with every base URL and secret replaced."""
        for raw, safe in self.urls:
            text = text.replace(raw, safe)
        for secret in self.secrets:
            text = text.replace(secret, REDACTED)
        return text

    def data(self, value: Any) -> Any:
        """A JSON-like value with :meth:`text` applied to every string in it (keys included)."""
        if isinstance(value, str):
            return self.text(value)
        if isinstance(value, list):
            return [self.data(v) for v in value]
        if isinstance(value, dict):
            return {self.text(k): self.data(v) for k, v in value.items()}
        return value

    def json_text(self, text: str) -> str:
        """Redact serialised JSON: strings are redacted after decoding, so an escape sequence
        inside a secret cannot hide it and a replacement cannot break an escape sequence."""
        needles = self._needles()
        escaped = [json.dumps(n, ensure_ascii=False)[1:-1] for n in needles]
        if not any(n in text for n in [*needles, *escaped]):
            return text
        data = self.data(json.loads(text))
        return json.dumps(data, ensure_ascii=False, indent=2) + "\n"
