"""Scores cached per cell x metric: ``DIR/scores/<metric>/<cell key>.json``.

Each file is ``{"metric": NAME, "values": {value name: float or null}}``, written atomically; a
metric added to a finished bench scores only the cells it has no file for.
"""

from __future__ import annotations

import hashlib
import json
import math
import re
from collections.abc import Callable, Mapping, Sequence
from pathlib import Path
from typing import Any

from matloom.evaluation.metrics.base import Metric, Sample
from matloom.io.atomic import atomic_write_bytes

SCORES_DIR = "scores"
#: Samples handed to one ``Metric.score`` call (scores are saved after each batch).
BATCH = 256


def metric_dir(root: Path, name: str) -> Path:
    """The cache folder of metric ``name`` (a readable slug, plus a hash when not the name)."""
    slug = re.sub(r"[^A-Za-z0-9_.-]+", "_", name).strip("._") or "metric"
    if slug != name:
        slug = f"{slug[:60]}-{hashlib.sha256(name.encode()).hexdigest()[:8]}"
    return root / SCORES_DIR / slug


def write_scores(root: Path, name: str, key: str, values: Mapping[str, float | None]) -> None:
    clean = {
        k: (float(v) if v is not None and math.isfinite(float(v)) else None)
        for k, v in values.items()
    }
    data = json.dumps({"metric": name, "values": clean}, sort_keys=True, allow_nan=False)
    folder = metric_dir(root, name)
    folder.mkdir(parents=True, exist_ok=True)
    atomic_write_bytes(folder / f"{key}.json", data.encode("utf-8"))


def cached_keys(root: Path, name: str) -> set[str]:
    folder = metric_dir(root, name)
    return {p.stem for p in folder.glob("*.json")} if folder.is_dir() else set()


def read_all(root: Path) -> dict[str, dict[str, float]]:
    """``cell key -> {value name: value}`` over every cached metric (null read as NaN)."""
    out: dict[str, dict[str, float]] = {}
    base = root / SCORES_DIR
    if not base.is_dir():
        return out
    for folder in sorted(p for p in base.iterdir() if p.is_dir()):
        for path in sorted(folder.glob("*.json")):
            try:
                data = json.loads(path.read_text(encoding="utf-8"))
                values = data["values"]
            except (OSError, ValueError, KeyError, TypeError):
                continue  # a torn or foreign file: that score is recomputed next time
            target = out.setdefault(path.stem, {})
            for k, v in values.items():
                target[str(k)] = math.nan if v is None else float(v)
    return out


def score_missing(
    root: Path,
    metric: Metric,
    samples: Sequence[Sample],
    on_batch: Callable[[int, int], None] | None = None,
) -> int:
    """Score the samples ``metric`` has no cached file for; return how many were scored."""
    done = cached_keys(root, metric.name)
    todo = [s for s in samples if s.id not in done]
    for start in range(0, len(todo), BATCH):
        batch = list(todo[start : start + BATCH])
        results: list[dict[str, Any]] = metric.score(batch)
        if len(results) != len(batch):
            raise RuntimeError(
                f"metric {metric.name!r} returned {len(results)} results for {len(batch)} samples"
            )
        for sample, values in zip(batch, results, strict=True):
            write_scores(root, metric.name, sample.id, values)
        if on_batch:
            on_batch(start + len(batch), len(todo))
    return len(todo)
