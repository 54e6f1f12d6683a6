"""Offline edits, fourth round (classes of the v4 "no"s): the physical size of a feature
("pennies 3 cm across" is the pennies' size, not the whole tile's), a part named by its colour
("just the red panes"), and named colours at their usual values ("sage green", "olive drab")."""

from __future__ import annotations

import numpy as np
import pytest

from matloom.author.edit import edit_offline
from matloom.author.edit.apply import parse_program
from matloom.author.edit.lab import delta_e
from matloom.author.edit.measure import feature_size


def _entry(name: str) -> str:
    from matloom.library import load_library

    return load_library().entry(name).program


# ---- the physical size of a feature -------------------------------------------------------------
#: (entry, request, the feature's size in units from the program's geometry, metres asked,
#: whether the window must zoom)
FEATURES = [
    # Smoothstep(0.432, 0.412, dist): a penny is 0.844 units across
    ("penny-round-mosaic", "pennies should be about 3 cm across, these read too small", 0.844, 0.03),
    # Bricks(brick_height=0.25): a board is 0.25 units wide; "narrower" zooms out as well
    ("painted-chipped-wood-boards", "narrower boards please, more like 10 cm cladding strips", 0.25, 0.10),
    # bandX: Fract(X()) < 0.5, a check is half a unit
    ("gingham", "bigger squares - tablecloth scale, around 2.5 cm checks", 0.5, 0.025),
    # stitch rows at y = 0.125 and 0.375 of every half unit: 0.25 apart
    ("saddle-leather-stitching", "bring the stitch rows closer together, about 1 cm apart", 0.25, 0.01),
    # the divider grid: Fract(X()), Fract(Y()), 1 unit squares
    ("terrazzo-floor-brass-strips", "divider grid should be 50 cm squares, not these big 1 m panels", 1.0, 0.5),
]  # fmt: skip


@pytest.mark.parametrize(("name", "request_", "units", "metres"), FEATURES)
def test_a_size_given_for_a_feature_is_the_feature_s(
    name: str, request_: str, units: float, metres: float
) -> None:
    text = _entry(name)
    result = edit_offline(text, request_, size=32)
    plan = result.report.plan
    assert plan["rule"] == "physical size", plan
    unit_m = plan["view"]["unit_m"]
    # the feature measures what was asked (within 10 %), not the whole window
    assert abs(units * unit_m - metres) <= 0.1 * metres, (units * unit_m, plan["note"])
    after = parse_program(result.program)
    x1, _, x2, _ = after.view_tuple
    assert abs(x2 - x1) * unit_m > 2 * metres
    assert result.report.ok


def test_a_direction_or_a_current_size_zooms_so_the_change_shows() -> None:
    # "narrower", "closer together": the View zooms out (x2: it tiles)
    for name, request_ in (FEATURES[1][:2], FEATURES[3][:2]):
        before = parse_program(_entry(name)).view_tuple
        plan = edit_offline(_entry(name), request_, size=32).report.plan
        w = plan["view"]["window"]
        assert w[2] - w[0] == pytest.approx(2 * (before[2] - before[0]))
    # "50 cm squares, not these 1 m panels": the window keeps its 2 m, so 4 squares across
    name, request_ = FEATURES[4][:2]
    plan = edit_offline(_entry(name), request_, size=32).report.plan
    w = plan["view"]["window"]
    assert (w[2] - w[0]) * plan["view"]["unit_m"] == pytest.approx(2.0, rel=0.1)
    # "bigger squares" (checks): the View zooms in
    name, request_ = FEATURES[2][:2]
    plan = edit_offline(_entry(name), request_, size=32).report.plan
    w = plan["view"]["window"]
    assert w[2] - w[0] == pytest.approx(3.0)


def test_a_size_of_the_whole_material_still_spans_the_view() -> None:
    plan = edit_offline(
        _entry("penny-round-mosaic"), "the texture should cover 2 m", size=32
    ).report.plan
    assert plan["view"] == {"unit_m": 0.25}  # 8 units across


def _grid(n: int = 256) -> tuple[np.ndarray, np.ndarray]:
    y, x = np.mgrid[0:n, 0:n] / n * 4.0  # a 4-unit window
    return x, y


def test_feature_size_measures_pieces_stripes_networks_and_periods() -> None:
    x, y = _grid()
    fx, fy = x % 1 - 0.5, y % 1 - 0.5
    disks = (np.hypot(fx, fy) < 0.3) * 1.0  # 0.6 across, 1 apart
    assert feature_size(disks, 4, 4, "across") == pytest.approx(0.6, rel=0.05)
    assert feature_size(disks, 4, 4, "apart") == pytest.approx(1.0, rel=0.05)
    stripes = ((x % 1) < 0.25) * 1.0  # 0.25 wide
    assert feature_size(stripes, 4, 4, "width") == pytest.approx(0.25, rel=0.05)
    lines = (np.maximum(np.abs(fx), np.abs(fy)) > 0.46) * 1.0  # a grid of 1-unit cells
    assert feature_size(lines, 4, 4, "across") == pytest.approx(0.92, rel=0.05)
    assert feature_size(lines, 4, 4, "width") == pytest.approx(0.08, rel=0.1)
    rows = ((y % 0.5) < 0.05) * ((x % 0.1) < 0.05)  # stitches: rows 0.5 apart
    assert feature_size(rows * 1.0, 4, 4, "apart", rows=True) == pytest.approx(0.5, rel=0.05)
    assert feature_size(rows * 1.0, 4, 4, "apart") == pytest.approx(0.1, rel=0.05)
    assert feature_size(np.zeros((64, 64)), 4, 4) is None


# ---- a part named by its colour -------------------------------------------------------------
#: (entry, request, parameters that must change, parameters that must not)
PARTS = [
    # "the red panes" are the red glass, not the lead came the word "panes" reaches
    ("stained-glass", "change just the red panes to a deep purple", {"define:glass_a"},
     {"define:lead_col", "define:glass_b", "define:glass_c", "define:glass_d"}),
    ("stained-glass", "make the red panes purple", {"define:glass_a"},
     {"define:lead_col", "define:glass_b"}),
    # "the orange bricks": the brick colour (a dark orange), not the darker headers
    ("flemish-bond-brick", "paint the orange bricks blue", {"define:brick"},
     {"define:header", "define:mortar"}),
    # "the whole wall": every brick colour, the joints kept
    ("flemish-bond-brick", "turn the whole wall into a pale yellow London stock brick",
     {"define:brick", "define:header"}, {"define:mortar"}),
    # "chips unchanged": only the matrix
    ("terrazzo-floor-brass-strips", "charcoal matrix instead of cream, chips unchanged",
     {"define:matrix"}, {"define:chip_white", "define:chip_grey", "define:chip_black"}),
]  # fmt: skip


@pytest.mark.parametrize(("name", "request_", "changed", "kept"), PARTS)
def test_a_part_named_by_its_colour(name: str, request_: str, changed: set, kept: set) -> None:
    plan = edit_offline(_entry(name), request_, size=32).report.plan
    got = {a.replace("colour:", "define:") for a in plan["assignments"]}
    assert changed <= got, plan["assignments"]
    assert not kept & got, plan["assignments"]


def test_the_whole_wall_keeps_the_brick_and_header_contrast() -> None:
    plan = edit_offline(
        _entry("flemish-bond-brick"), "turn the whole wall into a pale yellow stock brick", size=32
    ).report.plan
    brick, header = plan["assignments"]["define:brick"], plan["assignments"]["define:header"]
    assert sum(header) < sum(brick)  # the headers stay the darker bricks


# ---- named colours at their usual values ----------------------------------------------------
#: A named colour -> its usual sRGB value (within ``_TOLERANCE`` CIELAB delta E).
NAMED = {
    "sage green": (156, 175, 136),
    "olive drab": (107, 142, 35),
    "military olive drab": (107, 142, 35),
    "olive green": (110, 120, 50),
    "navy blue": (20, 30, 90),
    "emerald green": (30, 150, 90),
    "terracotta": (204, 100, 70),
    "cream": (245, 235, 205),
    "mustard yellow": (215, 170, 40),
    "teal": (0, 128, 128),
    "sky blue": (135, 200, 235),
    "brick red": (170, 60, 45),
    "chocolate brown": (90, 55, 35),
    "gold": (212, 175, 55),
    "lavender": (200, 180, 230),
    "cobalt blue": (0, 71, 171),
    "beige": (225, 210, 180),
    "army green": (75, 83, 32),
    "hunter green": (53, 94, 59),
    "battleship grey": (132, 132, 130),
    "prussian blue": (0, 49, 83),
}
_TOLERANCE = 12.0


@pytest.mark.parametrize(("phrase", "rgb"), list(NAMED.items()))
def test_named_colour_lands_near_its_value(phrase: str, rgb: tuple[int, int, int]) -> None:
    plan = edit_offline(_entry("painted-metal"), f"paint it {phrase}", size=16).report.plan
    (value,) = plan["assignments"].values()
    assert delta_e(value, rgb) <= _TOLERANCE, (phrase, value)


def test_the_old_colour_s_tone_is_not_the_new_colour_s() -> None:
    # "instead of the pale blue": "pale" is the old colour's; sage green is not paled
    plan = edit_offline(
        _entry("painted-chipped-wood-boards"),
        "repaint it sage green instead of the pale blue",
        size=32,
    ).report.plan
    (value,) = plan["assignments"].values()
    assert delta_e(value, NAMED["sage green"]) <= _TOLERANCE, value


def test_a_colour_and_a_finish_in_two_clauses_are_both_applied() -> None:
    plan = edit_offline(
        _entry("riveted-panels"), "paint the panels military olive drab, satin finish", size=32
    ).report.plan
    assert plan["rule"] == "roughness+colour"
    assert "basecolor" in plan["intended"] and "roughness" in plan["intended"]
    colour = [v for v in plan["assignments"].values() if isinstance(v, list)]
    assert colour and delta_e(colour[0], NAMED["olive drab"]) <= _TOLERANCE


# ---- a stated factor ----------------------------------------------------------------------------
def test_a_stated_factor_is_read() -> None:
    from matloom.author.edit.lexicon import edit_words, stated_factor, tokens

    said = {
        "scale it up about 2x": 2.0,
        "x3 bigger": 3.0,
        "make the tiles 3 times bigger": 3.0,
        "three times as big": 3.0,
        "1.5x larger": 1.5,
        "a 2 x 3 m wall": None,  # a size, not a factor
        "20x bigger": None,  # out of range: not read as a factor
        "twice as big": None,  # the size rule's own word
    }
    assert {t: stated_factor(tokens(t), edit_words()) for t in said} == said


def test_a_stated_factor_scales_by_that_factor() -> None:
    text = _entry("tweed")
    request_ = "The weave pattern is too small for close-up shots; scale it up about 2x."
    plan = edit_offline(text, request_, size=32).report.plan
    assert plan["rule"] == "scale" and plan["note"] == "features x2", plan
    (freq,) = plan["assignments"].values()
    assert freq == 24.0  # Weave base_freq 48 -> 24: twice as big
