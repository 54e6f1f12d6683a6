"""Coverage per layer and the sources of the repeating patterns (issue 26): statistics that need
the program, on programs whose answer is known."""

from __future__ import annotations

import numpy as np
import pytest

import matloom
from matloom.author.views import Renderer
from matloom.render.layer_stats import (
    format_layer_stats,
    layer_stats,
    visible_shares,
    visible_stats_text,
)
from matloom.render.visible_stats import visible_stats

SIZE = 128

HALF = """View(0, 0, 1, 1)
Define(half, Threshold(X(), below_at=0.5, below_to=0, above_at=0.5, above_to=1))
Material(Layer(1).basecolor(200, 200, 200), Layer(half).basecolor(200, 30, 30))"""

#: A 4 x 4 checker (Sin of 2 cycles per unit along X and Y: 4 squares a side) in an upper
#: layer's mask, over a substrate with noise that has no period.
CHECKER = """View(0, 0, 1, 1)
Define(grain, fBm(octaves=4, base_freq=6, to_01=True, seed=3))
Define(check, Threshold(Sin(X() * 4 * pi) * Sin(Y() * 4 * pi), below_at=0, below_to=0, \
above_at=0, above_to=1))
Material(
  Layer(1).basecolor(180 + grain * 40, 170, 150).height(grain * 0.01),
  Layer(check).basecolor(40, 40, 50).height(0.005)
)"""

#: Grout lines of a 4 x 4 tile grid.
GRID = """View(0, 0, 1, 1)
Define(grain, fBm(octaves=4, base_freq=6, to_01=True, seed=3))
Define(line, Max(Threshold(Abs(Fract(X() * 4) - 0.5), below_at=0.44, below_to=0, above_at=0.44, \
above_to=1), Threshold(Abs(Fract(Y() * 4) - 0.5), below_at=0.44, below_to=0, above_at=0.44, \
above_to=1)))
Material(Layer(1).basecolor(180 + grain * 40, 170, 150), Layer(line).basecolor(60, 60, 60))"""


def stats_of(program: str) -> tuple[dict, dict]:
    maps = matloom.evaluate(program, SIZE, SIZE)
    visible = visible_stats(maps)
    return visible, layer_stats(program, maps, visible)


def test_half_plane_mask_covers_half() -> None:
    _, stats = stats_of(HALF)
    bottom, top = stats["layers"]
    assert top["visible_share"] == pytest.approx(0.5, abs=0.01)
    assert bottom["visible_share"] == pytest.approx(0.5, abs=0.01)
    assert bottom["mask_share"] == 1.0 and top["label"] == "layer 1 (alpha half)"
    text = format_layer_stats(stats)
    assert "- layer 1 (alpha half): visible on 50 % of the image\n" in text + "\n"
    assert "- layer 0 (alpha 1): visible on 50 % of the image (its mask covers 100 %)" in text


def test_over_rule_with_partial_alphas() -> None:
    """Top 0.5 over middle 0.5 over an opaque bottom: 0.5, 0.25, 0.25 (shares sum to the
    coverage)."""
    alphas = [np.ones((4, 4)), np.full((4, 4), 0.5), np.full((4, 4), 0.5)]
    assert visible_shares(alphas) == pytest.approx([0.25, 0.25, 0.5])
    program = (
        "Material(Layer(1).basecolor(10, 10, 10), Layer(0.5).basecolor(90, 90, 90), "
        "Layer(Clamp(X(), 0, 1) * 0).basecolor(200, 0, 0))"
    )
    _, stats = stats_of(program)
    assert [round(layer["visible_share"], 3) for layer in stats["layers"]] == [0.5, 0.5, 0.0]


def test_checker_layer_carries_the_4x4_pattern() -> None:
    visible, stats = stats_of(CHECKER)
    patterns = visible["albedo"]["patterns"]
    assert len(patterns) == 2  # the checker's two diagonal waves
    for pattern in patterns:
        # a 4 x 4 checker: squares of SIZE / 4 px, diagonal waves of period side * sqrt 2
        assert pattern["period_px"] == pytest.approx(SIZE / 4 * np.sqrt(2), rel=0.05)
    albedo = [item for item in stats["sources"] if item["map"] == "albedo"]
    assert [item["sources"] for item in albedo] == [["Define `check`", "layer 1's mask"]] * 2
    text = visible_stats_text(CHECKER, matloom.evaluate(CHECKER, SIZE, SIZE))
    assert "together: a checker of 32.0 px squares, 4.0 across the image" in text
    assert "Define `check`, layer 1's mask" in text and "`grain`" not in text


def test_a_4x4_grid_of_lines_is_found_and_attributed() -> None:
    """Grout of a 4 x 4 tile grid: its lattice's peaks are four bins apart, each in the
    others' background; the statistics used to report no pattern."""
    visible, stats = stats_of(GRID)
    patterns = visible["albedo"]["patterns"]
    assert sorted(round(p["orientation_deg"]) % 180 for p in patterns) == [0, 90]
    for pattern in patterns:
        assert pattern["period_px"] == pytest.approx(SIZE / 4, rel=0.03)
    for item in stats["sources"]:
        assert item["sources"] == ["Define `line`", "layer 1's mask"]


def test_deterministic_and_in_the_critic_statistics() -> None:
    maps = matloom.evaluate(CHECKER, SIZE, SIZE)
    first = visible_stats_text(CHECKER, maps)
    assert first == visible_stats_text(CHECKER, matloom.evaluate(CHECKER, SIZE, SIZE))
    critic = Renderer().stats(CHECKER, "visible", grid=SIZE, size=SIZE)
    assert critic == first and "Layers (0 = bottom" in critic
    assert "Layers (" not in Renderer().stats(CHECKER, "paper", grid=32, size=SIZE)
