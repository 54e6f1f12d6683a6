"""How strongly a named feature shows: "more visible grain", "less prominent lines", "less
variation in the tile colour", "less speckle" (matloom/author/edit/contrast.py). Measured on
the evaluated maps: the feature's spread in the base colour grows or shrinks, the rest stays."""

from __future__ import annotations

import numpy as np
import pytest

from matloom.author.edit.core import edit_offline
from matloom.author.edit.plan import EditRefused
from matloom.engine.evaluate import evaluate
from matloom.lang.api import parse

WOOD = """View(0, 0, 1, 1, tileable=True)
Define(wood_r, 200)
Define(wood_g, 160)
Define(wood_b, 110)
Define(line_r, 30)
Define(line_g, 25)
Define(line_b, 20)
Define(grain, fBm(octaves=3, base_freq_x=2, base_freq_y=24, to_01=True, seed=3))
Define(dark_line, Smoothstep(0.05, 0.0, Abs(fBm(octaves=2, base_freq=2, seed=5))))
Material(
  Layer(1)
    .basecolor((wood_r * (0.8 + (grain * 0.3))), (wood_g * (0.8 + (grain * 0.3))), (wood_b * (0.8 + (grain * 0.3))))
    .roughness(0.6),
  Layer(dark_line).basecolor(line_r, line_g, line_b).roughness(0.6)
)
"""

TILES = """View(0, 0, 4, 4, tileable=True)
Define(tile_r, 180)
Define(tile_g, 90)
Define(tile_b, 60)
Define(tile_tone, Hash(x=Floor(X()), y=Floor(Y()), seed=9))
Define(tile, Smoothstep(0.04, 0.06, Min(Fract(X()), Fract(Y()))))
Material(
  Layer(1).basecolor(200, 200, 195).roughness(0.9),
  Layer(tile)
    .basecolor((tile_r * (0.75 + (tile_tone * 0.5))), (tile_g * (0.75 + (tile_tone * 0.5))), (tile_b * (0.75 + (tile_tone * 0.5))))
    .roughness(0.5)
)
"""


def _lum(text: str) -> np.ndarray:
    maps = evaluate(parse(text), 96, 96)
    rgb = np.asarray(maps.basecolor_linear, np.float64)
    return rgb[..., 0] * 0.2126 + rgb[..., 1] * 0.7152 + rgb[..., 2] * 0.0722


def _line_share(text: str) -> float:
    return float((_lum(text) < 0.12 * _lum(text).max()).mean())


def test_more_visible_grain_spreads_the_grain_and_keeps_its_mean() -> None:
    result = edit_offline(WOOD, "more visible grain", size=32)
    assert result.report.plan["rule"] == "contrast"
    assert "define:grain" in result.report.plan["replace"]
    before, after = _lum(WOOD), _lum(result.program)
    wood = _lum(WOOD) > 0.3 * before.max()  # away from the dark lines
    assert after[wood].std() > 1.3 * before[wood].std()
    assert abs(after[wood].mean() - before[wood].mean()) < 0.1 * before[wood].mean()
    assert result.report.locality.ok and result.report.locality.leaks == ()


def test_subtler_grain_narrows_it() -> None:
    result = edit_offline(WOOD, "make the grain subtler", size=32)
    before, after = _lum(WOOD), _lum(result.program)
    wood = before > 0.3 * before.max()
    assert after[wood].std() < 0.75 * before[wood].std()


def test_less_prominent_lines_take_the_coverage_of_the_layer_painted_line() -> None:
    result = edit_offline(WOOD, "make the dark lines less prominent", size=32)
    assert list(result.report.plan["replace"]) == ["define:dark_line"]
    assert _line_share(result.program) < 0.5 * _line_share(WOOD)


def test_less_variation_in_tile_colour_is_the_tone_define() -> None:
    result = edit_offline(TILES, "less variation in the tile colour", size=32)
    assert list(result.report.plan["replace"]) == ["define:tile_tone"]
    before, after = _lum(TILES), _lum(result.program)
    tiles = before < 0.7 * before.max()  # the grout is the lightest
    assert after[tiles].std() < 0.7 * before[tiles].std()
    more = edit_offline(TILES, "more colour variation between the tiles", size=32)
    assert _lum(more.program)[tiles].std() > 1.2 * before[tiles].std()


def test_less_of_a_feature_no_other_rule_reads() -> None:
    result = edit_offline(WOOD, "less grain", size=32)
    assert result.report.plan["rule"] == "contrast"
    assert "define:grain" in result.report.plan["replace"]


def test_a_satin_finish_with_more_visible_grain_is_both() -> None:
    result = edit_offline(WOOD, "a satin finish with a bit more visible grain", size=32)
    parts = set(result.report.plan["rule"].split("+"))
    assert parts == {"roughness", "contrast"}


def test_contrast_with_nothing_named_is_refused() -> None:
    plain = WOOD.replace("grain", "fibre").replace("dark_line", "band")
    with pytest.raises(EditRefused):
        edit_offline(plain, "more contrast", size=32)


@pytest.mark.parametrize(
    "request_",
    [
        "contrast stitching in bright red thread",  # an adjective: a colour
        "dark lines should be almost black for more contrast",  # the reason for a colour
        "tint the wood a subtle deep red",  # "subtle" says how much red
    ],
)
def test_contrast_words_that_ask_for_no_contrast(request_: str) -> None:
    try:
        result = edit_offline(WOOD, request_, size=32)
    except EditRefused:
        return
    assert "contrast" not in result.report.plan["rule"]


def test_more_of_a_counted_feature_is_no_contrast() -> None:
    # "more grains" asks for a count: showing the grain more does not give it
    with pytest.raises(EditRefused):
        edit_offline(WOOD, "more grains", size=32)
    assert edit_offline(WOOD, "more grain", size=32).report.plan["rule"] == "contrast"


@pytest.mark.parametrize(
    ("request_", "narrower"),
    [
        ("make the grain not so prominent", True),
        ("the grain shouldn't be so visible", True),
        ("decrease the contrast of the grain", True),
        ("boost the contrast of the grain so it pops", False),
        ("give more contrast to the grain", False),
    ],
)
def test_negations_purposes_and_verbs(request_: str, narrower: bool) -> None:
    result = edit_offline(WOOD, request_, size=32)
    assert result.report.plan["rule"].startswith("contrast")
    before, after = _lum(WOOD), _lum(result.program)
    wood = before > 0.3 * before.max()
    assert (after[wood].std() < before[wood].std()) == narrower


def test_a_more_even_color_is_the_tone() -> None:
    result = edit_offline(TILES, "give the tiles a more even color", size=32)
    assert list(result.report.plan["replace"]) == ["define:tile_tone"]
