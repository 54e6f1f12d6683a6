"""Scorer registry, deterministic test scorers, and the real open_clip adapter on random weights."""

from __future__ import annotations

import importlib.util
import time

import numpy as np
import pytest

import matloom
from matloom.author.config import AuthorConfig
from matloom.author.pipeline import resolve_scorer
from matloom.author.scorers import ScorerUnavailableError, TextImageScorer, get_scorer, scorer_names
from matloom.author.scorers.base import text_colour
from matloom.author.stages.select import earliest_argmax

HAS_CLIP = all(importlib.util.find_spec(m) is not None for m in ("torch", "open_clip"))


def solid(rgb: tuple[int, int, int], size: int = 16) -> np.ndarray:
    return np.full((size, size, 3), rgb, dtype=np.uint8)


def test_registry_lists_builtins() -> None:
    names = scorer_names()
    assert {"mobileclip2", "test-brightness", "test-colour", "test-constant"} <= set(names)
    assert "open_clip:..." in names
    with pytest.raises(ScorerUnavailableError, match="unknown scorer"):
        get_scorer("no-such-scorer")


def test_test_scorers_are_deterministic_and_batched() -> None:
    images = [solid((0, 0, 0)), solid((128, 128, 128)), solid((255, 255, 255))]
    bright = get_scorer("test-brightness")
    assert isinstance(bright, TextImageScorer)
    np.testing.assert_allclose(bright.score(images, "x"), [0.0, 100 * 128 / 255, 100.0])
    target = tuple(int(v) for v in text_colour("red brick"))
    colour = get_scorer("test-colour").score([solid(target), solid((0, 0, 0))], "red brick")
    assert colour[0] == pytest.approx(100.0) and colour[1] < colour[0]
    assert list(get_scorer("test-constant").score(images, "x")) == [50.0] * 3
    assert get_scorer("test-colour") is get_scorer("test-colour")  # cached per process


def test_earliest_argmax_breaks_ties_toward_the_earliest() -> None:
    assert earliest_argmax([1.0, 3.0, 3.0, 2.0]) == 1
    assert earliest_argmax([None, None]) == 0
    assert earliest_argmax([None, 2.0, None, 2.0]) == 1


def test_scorer_none_and_auto_fall_back() -> None:
    assert resolve_scorer(AuthorConfig(scorer="none")) == (None, "no scorer configured")
    if not HAS_CLIP:
        scorer, reason = resolve_scorer(AuthorConfig(scorer="auto"))
        assert scorer is None and "MobileCLIP2 unavailable" in reason


@pytest.mark.skipif(HAS_CLIP, reason="open_clip is installed here")
def test_missing_open_clip_says_how_to_install() -> None:
    with pytest.raises(ScorerUnavailableError, match=r"pip install 'matloom\[clip\]'"):
        get_scorer("open_clip:MobileCLIP2-S2:random")


@pytest.mark.clip
@pytest.mark.skipif(not HAS_CLIP, reason="needs the clip extra (torch + open_clip)")
def test_open_clip_adapter_runs_real_preprocessing_and_encoders_on_random_weights() -> None:
    from matloom.author.scorers.openclip import OpenClipScorer

    scorer = get_scorer("open_clip:MobileCLIP2-S2:random")
    assert isinstance(scorer, OpenClipScorer) and scorer.name == "open_clip:MobileCLIP2-S2:random"
    images = [
        matloom.preview("Material(Layer(1).basecolor(200, 40, 40))", 256),
        matloom.preview(
            "View(0, 0, 4, 4)\nMaterial(Layer(1).basecolor(fBm(to_01=True, seed=3) * 255, 90, 60))",
            256,
        ),
        solid((20, 200, 20), 300),
    ]
    scores = scorer.score(images, "red brick wall")
    assert scores.shape == (3,) and np.all((scores >= 0) & (scores <= 100))
    # Batched scoring equals one-by-one scoring (same preprocessing, same encoder).
    single = np.array([scorer.score([img], "red brick wall")[0] for img in images])
    np.testing.assert_allclose(scores, single, rtol=1e-4, atol=1e-3)
    # The template is applied to the raw prompt, and text features are cached per prompt.
    assert scorer.template.format(prompt="red brick wall") == "A photo of red brick wall"
    assert "red brick wall" in scorer._text_cache


@pytest.mark.clip
@pytest.mark.skipif(not HAS_CLIP, reason="needs the clip extra (torch + open_clip)")
def test_absent_mobileclip2_weights_fail_fast_with_instructions(monkeypatch) -> None:
    monkeypatch.setenv("HF_HUB_OFFLINE", "1")
    monkeypatch.setenv("HF_HOME", "/nonexistent-hf-home")
    from matloom.author.scorers.openclip import OpenClipScorer

    start = time.perf_counter()
    with pytest.raises(ScorerUnavailableError, match="not in the local cache") as info:
        OpenClipScorer()
    assert "--scorer none" in str(info.value)
    assert time.perf_counter() - start < 40  # no long download retries (sanity bound)
