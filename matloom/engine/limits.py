"""Documented resource limits of the engine, checked before any evaluation work."""

from __future__ import annotations

import os
from dataclasses import dataclass

from matloom.lang.checker import MAX_NODES, MAX_OCTAVES


class LimitError(ValueError):
    """A request exceeds a documented resource limit."""


@dataclass(frozen=True)
class Limits:
    """Resource limits. Override the memory budget with $MATLOOM_MAX_MEMORY_MB."""

    max_resolution: int = 8192
    max_octaves: int = MAX_OCTAVES
    max_nodes: int = MAX_NODES
    max_memory_mb: int = int(os.environ.get("MATLOOM_MAX_MEMORY_MB", "8192"))


DEFAULT_LIMITS = Limits()

#: Bytes per texel of the finished maps (14 float32 maps: 3 + 1*11 + 3 + 3 components).
_MAP_BYTES = 4 * 22


def estimate_memory_mb(width: int, height: int, n_defines: int, n_layers: int) -> float:
    """Rough peak working set of one evaluation (maps + live float64 fields), in MiB."""
    live_fields = n_defines + 2 * max(n_layers, 1) + 8
    return width * height * (_MAP_BYTES + 8 * live_fields) / 2**20


def check_request(
    width: int, height: int, n_defines: int, n_layers: int, limits: Limits = DEFAULT_LIMITS
) -> None:
    """Raise :class:`LimitError` with a clear message if the request exceeds a limit."""
    for name, v in (("width", width), ("height", height)):
        if not isinstance(v, int) or v < 1:
            raise LimitError(f"{name} must be a positive integer, got {v!r}")
        if v > limits.max_resolution:
            raise LimitError(
                f"{name} {v} exceeds the maximum resolution {limits.max_resolution} "
                "(see docs/limits.md)"
            )
    mb = estimate_memory_mb(width, height, n_defines, n_layers)
    if mb > limits.max_memory_mb:
        raise LimitError(
            f"evaluating {width}x{height} needs about {mb:.0f} MiB, more than the "
            f"budget of {limits.max_memory_mb} MiB; lower the size or raise "
            "MATLOOM_MAX_MEMORY_MB"
        )
