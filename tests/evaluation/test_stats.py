"""The bench statistics against hand computations on a fixed small table."""

from __future__ import annotations

import math

import numpy as np
import pytest

pytest.importorskip("scipy", reason="needs the bench extra (pip install 'matloom[bench]')")

from matloom.evaluation.stats import (  # noqa: E402
    Row,
    bootstrap_ci,
    contrasts,
    holm,
    paired,
    prompt_means,
    source_table,
    wilcoxon,
)

#: Per-prompt differences A - B: |d| ranks 3, 1, 4, 6, 2, 5; the negative ones (-0.5, -1.0)
#: have ranks 1 and 2, so W- = 3, W+ = 18 and W = min = 3. Exact two-sided p: the subsets of
#: {1..6} with rank sum <= 3 are {}, {1}, {2}, {3}, {1,2}: p = 2 * 5 / 2**6 = 0.15625.
DIFFS = [1.5, -0.5, 2.0, 3.0, -1.0, 2.5]
B_MEANS = [40.0, 50.0, 60.0, 45.0, 55.0, 65.0]


def _table() -> list[Row]:
    """Two runs per prompt whose means are B_MEANS (system b) and B_MEANS + DIFFS (system a);
    a NaN run that must be ignored; two sources of three prompts."""
    rows = []
    for i, (b, d) in enumerate(zip(B_MEANS, DIFFS, strict=True)):
        pid, src = f"p{i}", "S1" if i < 3 else "S2"
        for system, mean in (("a", b + d), ("b", b)):
            rows.append(Row(pid, src, system, 0, 42, "m", mean - 1.0))
            rows.append(Row(pid, src, system, 1, 123, "m", mean + 1.0))
        rows.append(Row(pid, src, "a", 2, 2026, "m", math.nan))
    return rows


def test_prompt_means_are_run_means_ignoring_nan() -> None:
    means = prompt_means(_table())
    assert means[("b", "m", "p0")] == pytest.approx(40.0)
    assert means[("a", "m", "p4")] == pytest.approx(54.0)
    assert len(means) == 12


def test_wilcoxon_matches_the_hand_computation() -> None:
    w, p = wilcoxon(DIFFS)
    assert w == 3.0
    assert p == pytest.approx(0.15625)
    assert all(math.isnan(x) for x in wilcoxon([0.0, 0.0, 1.0]))


def test_holm_matches_the_hand_computation() -> None:
    # sorted 0.01, 0.03, 0.04, 0.20 -> 4*0.01, 3*0.03, max(2*0.04, 0.09), max(0.20, 0.09)
    assert holm([0.01, 0.04, 0.03, 0.20]) == pytest.approx([0.04, 0.09, 0.09, 0.20])
    out = holm([0.01, math.nan, 0.04])  # NaN is not in the family (m = 2)
    assert out[0] == pytest.approx(0.02) and math.isnan(out[1]) and out[2] == pytest.approx(0.04)
    assert holm([0.6, 0.7]) == pytest.approx([1.0, 1.0])


def _percentile(sorted_values: list[float], q: float) -> float:
    pos = q / 100.0 * (len(sorted_values) - 1)
    lo = math.floor(pos)
    hi = min(lo + 1, len(sorted_values) - 1)
    return sorted_values[lo] + (pos - lo) * (sorted_values[hi] - sorted_values[lo])


def test_bootstrap_ci_matches_a_direct_resampling() -> None:
    rng = np.random.default_rng(11)
    draws = rng.integers(0, len(DIFFS), size=(2000, len(DIFFS)))
    means = sorted(sum(DIFFS[j] for j in row) / len(DIFFS) for row in draws.tolist())
    low, high = bootstrap_ci(DIFFS, resamples=2000, seed=11)
    assert low == pytest.approx(_percentile(means, 2.5), abs=1e-12)
    assert high == pytest.approx(_percentile(means, 97.5), abs=1e-12)
    assert bootstrap_ci(DIFFS, seed=3) == bootstrap_ci(DIFFS, seed=3)  # deterministic
    assert bootstrap_ci([2.0] * 5) == (2.0, 2.0)


def test_paired_contrast_and_holm_over_the_family() -> None:
    means = prompt_means(_table())
    r = paired(means, "a", "b", "m", resamples=1000, seed=5)
    assert r.n == 6
    assert r.mean_diff == pytest.approx(sum(DIFFS) / 6)  # 7.5 / 6 = 1.25
    assert r.mean_b == pytest.approx(sum(B_MEANS) / 6)
    assert (r.wilcoxon_w, r.p) == (3.0, pytest.approx(0.15625))
    assert (r.ci_low, r.ci_high) == bootstrap_ci(DIFFS, resamples=1000, seed=5)
    found = contrasts(means, [("a", "b"), ("b", "a")], ["m"], resamples=200)
    # two tests with p = 0.15625 each: Holm gives min(1, 2p) for both
    assert [c.p_holm for c in found] == pytest.approx([0.3125, 0.3125])
    assert found[1].mean_diff == pytest.approx(-1.25)


def test_source_table_splits_the_prompts() -> None:
    means = prompt_means(_table())
    sources = {f"p{i}": "S1" if i < 3 else "S2" for i in range(6)}
    table = source_table(means, sources, ["a", "b"], ["m"], [("a", "b")], resamples=200)
    assert table["S1"]["n"] == 3
    assert table["S1"]["means"]["m"]["b"] == pytest.approx(50.0)
    assert table["S2"]["means"]["m"]["a"] == pytest.approx((48.0 + 54.0 + 67.5) / 3)
    assert table["S1"]["contrasts"][0]["mean_diff"] == pytest.approx((1.5 - 0.5 + 2.0) / 3)
