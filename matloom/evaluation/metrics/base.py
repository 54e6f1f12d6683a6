"""The metric plugin interface and its registry.

A metric scores a batch of :class:`Sample` objects and returns, per sample, a mapping of named
values (one metric may report several: ``seam_ratio.base_color``, ``seam_ratio.max``). Text-image
metrics report on [0, 100]; material metrics report in their own units (docs/evaluation.md).

Metrics are found by name (:mod:`.registry`: ``get_metric``, ``metric_names``). Built-ins
register themselves when their module is imported (``registry.load_builtin_metrics``); other packages add metrics through the entry-point group
``matloom.metrics`` whose objects are factories ``factory(name: str, options: dict) -> Metric``.
A name may carry options after a colon (``clip:ViT-B-32:/path/weights.bin``): the factory of
the part before the first colon receives the whole name.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Protocol, runtime_checkable

ENTRY_POINT_GROUP = "matloom.metrics"
#: family -> factory; filled by :func:`register_metric` (the built-ins at import, as the scorers do).
FACTORIES: dict[str, MetricFactory] = {}


class MetricUnavailableError(RuntimeError):
    """The metric cannot run here (missing extra, missing weights): the message says how to fix it."""


@dataclass(frozen=True)
class Sample:
    """One authored material as the metrics see it.

    ``images`` maps a layout name (``quick`` = the flat quick preview PNG, ``flat`` and
    ``staged`` = the paper's Blender layouts when rendered) to an image file. ``program`` is the
    program text; ``size`` the evaluation size material metrics use. ``record`` carries
    authoring facts (``seconds``, ``prompt_tokens``, ``completion_tokens``) when known.
    """

    id: str
    prompt: str
    program: str
    images: Mapping[str, Path] = field(default_factory=dict)
    size: int = 256
    record: Mapping[str, Any] = field(default_factory=dict)
    #: The program's maps at ``size`` when the caller has them already (``matloom dataset``
    #: renders each sample once); material metrics use them instead of evaluating again.
    maps: Any = field(default=None, compare=False, repr=False)


@runtime_checkable
class Metric(Protocol):
    """Scores a batch of samples."""

    @property
    def name(self) -> str:
        """The registry name that re-creates this metric (also the ``metric`` column prefix)."""
        ...

    @property
    def layouts(self) -> tuple[str, ...]:
        """Image layouts it reads (empty for metrics of the program and maps only)."""
        ...

    def score(self, samples: Sequence[Sample]) -> list[dict[str, float]]:
        """One mapping ``value name -> float`` per sample, in order (NaN where undefined)."""
        ...


MetricFactory = Callable[[str, Mapping[str, Any]], Metric]


def register_metric(family: str, factory: MetricFactory) -> None:
    """Register ``factory`` for ``family`` and every ``family:...`` name."""
    if not family or ":" in family:
        raise ValueError(f"a metric family is a plain name, not {family!r}")
    FACTORIES[family] = factory
