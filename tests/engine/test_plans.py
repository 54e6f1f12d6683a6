"""Compiled register programs reused across evaluations (matloom.engine.plans)."""

from __future__ import annotations

import numpy as np
import pytest

pytest.importorskip("numba")

from matloom.engine.evaluate import evaluate  # noqa: E402
from matloom.engine.schedules import banded as fused  # noqa: E402
from matloom.examples import example_text  # noqa: E402
from matloom.lang.seeds import seed_variants  # noqa: E402


def _same(a: dict[str, np.ndarray], b: dict[str, np.ndarray], label: str) -> None:
    for name, array in a.items():
        assert np.array_equal(array.view(np.uint32), b[name].view(np.uint32)), (label, name)


def test_reused_plans_give_the_maps_of_a_fresh_compile(monkeypatch: pytest.MonkeyPatch) -> None:
    tile = example_text("black_ceramic_tiles")
    texts = [tile, *seed_variants(tile, 3, seed=5)]
    fused._PLANS.plans.clear()
    for text in texts:  # the variants share the tile's structure: compiled once, then rebound
        cached = evaluate(text, 48, 40, backend="numba").arrays()
        _same(cached, evaluate(text, 48, 40, backend="numpy").arrays(), "cached vs numpy")
    assert len(fused._PLANS.plans) == 1
    monkeypatch.setattr(fused, "signature", lambda layers, shape: (object(), []))
    fresh = evaluate(texts[-1], 48, 40, backend="numba").arrays()  # never cached
    _same(cached, fresh, "cached vs fresh compile")


def test_programs_differing_in_a_constant_or_in_sharing_get_their_own_plans() -> None:
    base = "View(0, 0, 2, 2)\nDefine(n, fBm(octaves=2, base_freq=5, to_01=True, seed=3))\n"
    texts = [
        base + "Material(Layer(1).basecolor(n * 200, 10, 10).roughness(n * 0.5))",
        base + "Material(Layer(1).basecolor(n * 201, 10, 10).roughness(n * 0.5))",
        base + "Material(Layer(1).basecolor(n * 200, 10, 10).roughness(n * 0.5 + 0))",
        base.replace("seed=3", "seed=4")
        + "Material(Layer(1).basecolor(n * 200, 10, 10).roughness(fBm(octaves=2, base_freq=5,"
        " to_01=True, seed=3) * 0.5))",
    ]
    fused._PLANS.plans.clear()
    for _ in range(2):
        for text in texts:
            got = evaluate(text, 24, 16, backend="numba").arrays()
            _same(got, evaluate(text, 24, 16, backend="numpy").arrays(), text)
    assert len(fused._PLANS.plans) == len(texts)


def test_an_evaluation_leaves_nothing_alive_but_its_maps() -> None:
    """No reference cycle keeps band fields alive after evaluate() returns (the garbage
    collector is off, so only reference counting frees memory)."""
    import gc
    import tracemalloc

    text = example_text("black_ceramic_tiles")
    evaluate(text, 160, 160, backend="numba")  # warm caches (plans, gradient tables)
    gc.collect()
    gc.disable()
    try:
        tracemalloc.start()
        maps = evaluate(text, 160, 160, backend="numba")
        current = tracemalloc.get_traced_memory()[0]
        tracemalloc.stop()
    finally:
        gc.enable()
    kept = sum(a.nbytes for a in maps.arrays().values())
    band_field = 160 * 160 * 8  # one float64 field of the band
    assert current - kept < band_field, (current, kept)
