"""Scorer lookup by name: the built-in scorers are loaded here, never from :mod:`.base`, so
their modules can import the registry in ``base`` without an import cycle. Instances are
cached per process (loading a model's weights is slow); a scorer registered again under the
same name replaces the cached instance."""

from __future__ import annotations

import threading

from matloom.author.scorers.base import (
    ScorerFactory,
    ScorerUnavailableError,
    TextImageScorer,
    factory_for,
    registered_names,
)

_INSTANCES: dict[str, tuple[ScorerFactory, TextImageScorer]] = {}
_LOCK = threading.Lock()


def _load_builtin_scorers() -> None:
    import matloom.author.scorers.openclip  # noqa: F401  (registers mobileclip2, open_clip:)


def scorer_names() -> list[str]:
    """Registered names (prefix families shown as ``prefix:...``)."""
    _load_builtin_scorers()
    return registered_names()


def get_scorer(name: str) -> TextImageScorer:
    """The scorer registered as ``name`` (one cached instance per process and factory)."""
    _load_builtin_scorers()
    with _LOCK:
        factory = factory_for(name)
        if factory is None:
            known = ", ".join(registered_names())
            raise ScorerUnavailableError(f"unknown scorer {name!r} (known: {known})")
        cached = _INSTANCES.get(name)
        if cached is not None and cached[0] is factory:
            return cached[1]
        instance = factory(name)
        _INSTANCES[name] = (factory, instance)
        return instance
