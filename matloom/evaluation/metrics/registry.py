"""Finding metrics by name: :func:`get_metric` and :func:`metric_names` load the built-in metric
modules (:mod:`.builtin`, which register their families in :mod:`.base`) and the entry points of
the group ``matloom.metrics`` once per process."""

from __future__ import annotations

from collections.abc import Mapping
from importlib import metadata
from typing import Any

from matloom.evaluation.metrics.base import (
    ENTRY_POINT_GROUP,
    FACTORIES,
    Metric,
    MetricUnavailableError,
)

_STATE = {"loaded": False}


def load_builtin_metrics() -> None:
    """Import the built-in metric modules (they register themselves) and the entry points."""
    if _STATE["loaded"]:
        return
    _STATE["loaded"] = True
    from matloom.evaluation.metrics import builtin  # noqa: F401  (registers the built-ins)

    for ep in metadata.entry_points(group=ENTRY_POINT_GROUP):
        if ep.name not in FACTORIES:
            FACTORIES[ep.name] = ep.load()


def metric_names() -> list[str]:
    """Registered metric families."""
    load_builtin_metrics()
    return sorted(FACTORIES)


def get_metric(name: str, options: Mapping[str, Any] | None = None) -> Metric:
    """A new metric for ``name`` (``family`` or ``family:options``)."""
    load_builtin_metrics()
    family = name.split(":", 1)[0]
    factory = FACTORIES.get(family)
    if factory is None:
        known = ", ".join(sorted(FACTORIES)) or "none"
        raise MetricUnavailableError(f"unknown metric {name!r} (metrics: {known})")
    return factory(name, dict(options or {}))
