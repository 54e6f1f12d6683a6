"""Imports every built-in metric module so each registers its family (see :mod:`.base`).
Modules whose heavy imports (torch, transformers) are missing still register: their factory
raises :class:`~matloom.evaluation.metrics.base.MetricUnavailableError` when called."""

from __future__ import annotations
