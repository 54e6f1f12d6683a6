"""The paper's statistics over a bench's scores (needs ``scipy``: the ``[bench]`` extra).

Per-prompt means over the runs; per system and metric the mean over prompts; paired
differences between two systems over the prompts both scored, with a percentile bootstrap 95 %
confidence interval of the mean difference (10,000 resamples, seeded: deterministic), a
two-sided Wilcoxon signed-rank test, and Holm's correction over the family of contrasts x
metrics asked for; and the same means per prompt source.
"""

from __future__ import annotations

import math
from collections import defaultdict
from collections.abc import Iterable, Mapping, Sequence
from dataclasses import asdict, dataclass
from typing import Any

import numpy as np

BOOTSTRAP_RESAMPLES = 10_000
BOOTSTRAP_SEED = 2026


@dataclass(frozen=True)
class Row:
    """One score: a prompt x system x run x metric value (a line of ``results.csv``)."""

    prompt_id: str
    source: str
    system: str
    run: int
    seed: int
    metric: str
    value: float


@dataclass(frozen=True)
class Paired:
    """``a - b`` over the prompts both systems scored on one metric."""

    a: str
    b: str
    metric: str
    n: int
    mean_a: float
    mean_b: float
    mean_diff: float
    ci_low: float
    ci_high: float
    wilcoxon_w: float
    p: float
    p_holm: float = math.nan

    def as_dict(self) -> dict[str, Any]:
        return {k: _json_float(v) for k, v in asdict(self).items()}


def _json_float(v: Any) -> Any:
    return None if isinstance(v, float) and not math.isfinite(v) else v


def prompt_means(rows: Iterable[Row]) -> dict[tuple[str, str, str], float]:
    """``(system, metric, prompt_id) -> mean over runs`` (NaN values ignored; a prompt whose
    runs are all NaN is left out)."""
    sums: dict[tuple[str, str, str], list[float]] = defaultdict(list)
    for r in rows:
        if math.isfinite(r.value):
            sums[(r.system, r.metric, r.prompt_id)].append(r.value)
    return {k: float(np.mean(v)) for k, v in sums.items()}


def bootstrap_ci(
    values: Sequence[float],
    *,
    resamples: int = BOOTSTRAP_RESAMPLES,
    seed: int = BOOTSTRAP_SEED,
    level: float = 0.95,
) -> tuple[float, float]:
    """Percentile bootstrap CI of the mean: ``resamples`` means of ``n`` values drawn with
    replacement by ``numpy.random.default_rng(seed).integers(0, n, (resamples, n))``."""
    data = np.asarray(values, dtype=np.float64)
    if data.size == 0:
        return math.nan, math.nan
    rng = np.random.default_rng(seed)
    idx = rng.integers(0, data.size, size=(resamples, data.size))
    means = data[idx].mean(axis=1)
    tail = (1.0 - level) / 2.0 * 100.0
    low, high = np.percentile(means, [tail, 100.0 - tail])
    return float(low), float(high)


def wilcoxon(diffs: Sequence[float]) -> tuple[float, float]:
    """Two-sided Wilcoxon signed-rank test of paired differences: ``(W, p)``, W the smaller
    rank sum (scipy's statistic); NaN when undefined (fewer than 2 non-zero differences)."""
    from scipy.stats import wilcoxon as scipy_wilcoxon

    data = np.asarray(diffs, dtype=np.float64)
    if np.count_nonzero(data) < 2:
        return math.nan, math.nan
    result = scipy_wilcoxon(data, alternative="two-sided", zero_method="wilcox")
    return float(result.statistic), float(result.pvalue)


def holm(pvalues: Sequence[float]) -> list[float]:
    """Holm's step-down adjusted p-values, in the order given (NaN stays NaN and is not
    counted in the family)."""
    valid = [(p, i) for i, p in enumerate(pvalues) if math.isfinite(p)]
    valid.sort()
    m = len(valid)
    out = [math.nan] * len(pvalues)
    running = 0.0
    for rank, (p, i) in enumerate(valid):
        running = max(running, min(1.0, (m - rank) * p))
        out[i] = running
    return out


def paired(
    means: Mapping[tuple[str, str, str], float],
    a: str,
    b: str,
    metric: str,
    *,
    prompts: Iterable[str] | None = None,
    resamples: int = BOOTSTRAP_RESAMPLES,
    seed: int = BOOTSTRAP_SEED,
) -> Paired:
    """The paired comparison of systems ``a`` and ``b`` on ``metric`` (over ``prompts``, or
    every prompt both have a mean for)."""
    ids_a = {p for (s, m, p) in means if s == a and m == metric}
    ids_b = {p for (s, m, p) in means if s == b and m == metric}
    common = sorted(ids_a & ids_b & (set(prompts) if prompts is not None else ids_a))
    va = np.array([means[(a, metric, p)] for p in common])
    vb = np.array([means[(b, metric, p)] for p in common])
    diffs = va - vb
    low, high = bootstrap_ci(diffs, resamples=resamples, seed=seed)
    w, p = wilcoxon(diffs)
    nan = math.nan
    return Paired(
        a=a,
        b=b,
        metric=metric,
        n=len(common),
        mean_a=float(va.mean()) if len(common) else nan,
        mean_b=float(vb.mean()) if len(common) else nan,
        mean_diff=float(diffs.mean()) if len(common) else nan,
        ci_low=low,
        ci_high=high,
        wilcoxon_w=w,
        p=p,
    )


def contrasts(
    means: Mapping[tuple[str, str, str], float],
    pairs: Sequence[tuple[str, str]],
    metrics: Sequence[str],
    *,
    resamples: int = BOOTSTRAP_RESAMPLES,
) -> list[Paired]:
    """Every pair x metric, Holm-adjusted over that whole family."""
    found = [paired(means, a, b, m, resamples=resamples) for a, b in pairs for m in metrics]
    adjusted = holm([r.p for r in found])
    return [Paired(**{**asdict(r), "p_holm": q}) for r, q in zip(found, adjusted, strict=True)]


def system_table(
    means: Mapping[tuple[str, str, str], float], systems: Sequence[str], metrics: Sequence[str]
) -> dict[str, dict[str, dict[str, Any]]]:
    """``metric -> system -> {n, mean, sd}`` over the per-prompt means."""
    out: dict[str, dict[str, dict[str, Any]]] = {}
    for metric in metrics:
        out[metric] = {}
        for system in systems:
            vals = [v for (s, m, _), v in means.items() if s == system and m == metric]
            out[metric][system] = {
                "n": len(vals),
                "mean": _json_float(float(np.mean(vals))) if vals else None,
                "sd": _json_float(float(np.std(vals, ddof=1))) if len(vals) > 1 else None,
            }
    return out


def source_table(
    means: Mapping[tuple[str, str, str], float],
    sources: Mapping[str, str],
    systems: Sequence[str],
    metrics: Sequence[str],
    pairs: Sequence[tuple[str, str]] = (),
    *,
    resamples: int = BOOTSTRAP_RESAMPLES,
) -> dict[str, dict[str, Any]]:
    """Per prompt source: ``source -> {"n": prompts, "means": metric -> system -> mean,
    "contrasts": [paired dicts]}`` (the contrasts unadjusted: Holm applies to the headline
    family only)."""
    by_source: dict[str, list[str]] = defaultdict(list)
    for pid, src in sources.items():
        by_source[src].append(pid)
    out: dict[str, dict[str, Any]] = {}
    for src in sorted(by_source):
        ids = set(by_source[src])
        sub = {k: v for k, v in means.items() if k[2] in ids}
        table = system_table(sub, systems, metrics)
        out[src] = {
            "n": len(ids),
            "means": {m: {s: table[m][s]["mean"] for s in systems} for m in metrics},
            "contrasts": [
                paired(sub, a, b, m, resamples=resamples).as_dict()
                for a, b in pairs
                for m in metrics
            ],
        }
    return out
