"""Where an added condition goes (matloom/author/edit/places.py): the relief's low parts ("in
the crevices", joints a program does not draw), its high parts ("on the tops", "the raised
studs"), the middle of the surface (a patch or a band, periodic so a tileable program still
tiles) and places that cannot repeat (a corner: made on a program that does not tile, refused
on one that does); the condition words that name an overlay by another form; a colour word
as a verb ("yellow it with age")."""

from __future__ import annotations

import numpy as np
import pytest

from matloom.author.edit.core import edit_offline
from matloom.author.edit.plan import EditRefused
from matloom.engine.evaluate import evaluate
from matloom.lang.api import parse
from matloom.lang.tileable import tileable_warnings

#: rounded grey stones (Worley cells, high) with narrow low gaps between them and no joint
#: parameter: its low parts are the gaps
STONES = """View(0, 0, 1, 1, tileable=True)
Define(stone_r, 150)
Define(stone_g, 146)
Define(stone_b, 140)
Define(cell, Worley(base_freq=5, to_01=True, seed=3))
Define(dome, Smoothstep(0.5, 0.25, cell))
Material(
  Layer(1)
    .basecolor(stone_r, stone_g, stone_b)
    .roughness(0.7)
    .height((dome * 0.02))
)
"""

#: a plain, flat, tileable plaster
FLAT = """View(0, 0, 1, 1, tileable=True)
Define(plaster_r, 210)
Define(plaster_g, 205)
Define(plaster_b, 195)
Material(
  Layer(1).basecolor(plaster_r, plaster_g, plaster_b).roughness(0.8)
)
"""

#: blue wires (a layer covering a third of the surface) over a pale ground
WIRES = """View(0, 0, 1, 1, tileable=True)
Define(ground_r, 220)
Define(ground_g, 215)
Define(ground_b, 205)
Define(wire_r, 60)
Define(wire_g, 90)
Define(wire_b, 160)
Define(wire, Smoothstep(0.34, 0.3, Abs((Fract((X() * 6)) - 0.5))))
Material(
  Layer(1).basecolor(ground_r, ground_g, ground_b).roughness(0.8),
  Layer(wire).basecolor(wire_r, wire_g, wire_b).roughness(0.4)
)
"""

N = 64


def _change(before: str, after: str) -> np.ndarray:
    a = evaluate(before, N, N).basecolor_linear[..., :3]
    b = evaluate(after, N, N).basecolor_linear[..., :3]
    return np.abs(a - b).sum(axis=-1)


def _height(text: str) -> np.ndarray:
    return np.asarray(evaluate(text, N, N).height)


def _edit(text: str, request: str):  # noqa: ANN202 - the EditResult
    return edit_offline(text, request, size=32)


def test_the_crevices_are_the_reliefs_low_part() -> None:
    result = _edit(STONES, "add dirt in the crevices")
    assert "low parts of the relief" in result.report.plan["note"]
    change, h = _change(STONES, result.program), _height(STONES)
    low, high = h < np.percentile(h, 20), h > np.percentile(h, 60)
    assert change[low].mean() > 4 * change[high].mean()


def test_joints_a_program_does_not_draw_are_its_low_parts() -> None:
    result = _edit(STONES, "add some moss in the gaps between the stones")
    assert "low parts of the relief" in result.report.plan["note"]


def test_the_tops_are_the_reliefs_high_part() -> None:
    for request in ("add dust on the tops", "scratch the raised parts"):
        result = _edit(STONES, request)
        assert "high parts of the relief" in result.report.plan["note"], request
        change, h = _change(STONES, result.program), _height(STONES)
        low, high = h < np.percentile(h, 20), h > np.percentile(h, 60)
        assert change[high].mean() > 2 * change[low].mean(), request


def test_joints_on_a_flat_program_are_refused_crevices_settle_as_they_would() -> None:
    with pytest.raises(EditRefused, match="no joints found"):
        _edit(FLAT, "add dirt in the gaps")
    # no relief to find crevices in: the dirt as "add dirt" alone would put it
    note = _edit(FLAT, "add dirt in the crevices").report.plan["note"]
    assert "'dirty' overlay" in note and "relief" not in note


def test_a_stain_near_the_middle_is_in_the_middle_and_still_tiles() -> None:
    result = _edit(FLAT, "put a coffee stain near the middle")
    assert "near the middle" in result.report.plan["note"]
    change = _change(FLAT, result.program)
    centre = change[N // 4 : 3 * N // 4, N // 4 : 3 * N // 4]
    border = np.concatenate([change[:6].ravel(), change[-6:].ravel()])
    assert centre.mean() > 5 * max(border.mean(), 1e-6)
    assert not tileable_warnings(parse(result.program))


def test_a_path_through_the_middle_is_a_band() -> None:
    result = _edit(FLAT, "make it dirty along a path through the middle")
    change = _change(FLAT, result.program)
    columns = change.mean(axis=0)
    assert columns[N // 2 - 4 : N // 2 + 4].mean() > 4 * columns[:6].mean()
    # a band down the surface: its top and bottom rows changed alike
    assert (
        change[:8, N // 2 - 4 : N // 2 + 4].mean()
        > 0.3 * change[-8:, N // 2 - 4 : N // 2 + 4].mean()
    )
    assert not tileable_warnings(parse(result.program))


def test_a_corner_of_a_tiling_program_is_where_four_repeats_meet() -> None:
    result = _edit(FLAT, "add black mould creeping in from one corner")
    assert "four repeats meet" in result.report.plan["note"]
    change = _change(FLAT, result.program)
    q = N // 4
    corners = np.concatenate([change[:q, :q].ravel(), change[-q:, -q:].ravel()])
    assert corners.mean() > 4 * change[q:-q, q:-q].mean()
    assert not tileable_warnings(parse(result.program))


def test_a_side_is_refused_on_a_tiling_program_and_made_on_one_that_does_not() -> None:
    with pytest.raises(EditRefused, match="place on the surface as a whole"):
        _edit(FLAT, "add black mould on one side")
    placed = FLAT.replace("tileable=True", "tileable=False")
    result = _edit(placed, "add black mould creeping in from one corner")
    change = _change(placed, result.program)
    h = N // 2
    # rows are top first in the maps: the top-left quarter
    assert change[:h, :h].mean() > 4 * change[h:, h:].mean()
    result = _edit(placed, "add black mould on the left side")
    change = _change(placed, result.program)
    assert change[:, :h].mean() > 4 * change[:, h:].mean()


def test_the_middle_of_each_feature_is_no_place_on_the_surface() -> None:
    note = _edit(FLAT, "make it dirty in the middle of each tile").report.plan["note"]
    assert "middle" not in note


@pytest.mark.parametrize(
    ("request_", "overlay"),
    [
        ("fade it", "faded"),
        ("bleach it", "faded"),
        ("make it look sun-bleached", "faded"),
        ("weather it", "weathered"),
        ("make the paint peeling", "chipped"),
        ("add foxing", "stained"),
        ("bird droppings", "stained"),
        ("fingerprints", "oily"),
        ("tarnish it", "rusty"),
        ("add a few dark water spots", "wet"),
        ("cover it with a layer of grey volcanic ash", "dusty"),
    ],
)
def test_condition_words_in_other_forms(request_: str, overlay: str) -> None:
    note = _edit(FLAT, request_).report.plan["note"]
    assert f"'{overlay}' overlay" in note, note


def test_a_colour_word_as_a_verb_moves_towards_it() -> None:
    """ "yellow it with age" is yellower, not the plaster painted bright yellow."""
    result = _edit(FLAT, "yellow it with age")
    assert "yellower" in result.report.plan["note"]
    r, g, b = (float(v) for v in result.report.changes[0].to_json()["after"])
    assert 100 < b < 190 and r > 200 and g > 190  # a warmer pale plaster, not bright yellow


def test_a_condition_on_a_part_is_on_that_part() -> None:
    result = _edit(WIRES, "add rust to the wires")
    assert "on the wires" in result.report.plan["note"]
    change = _change(WIRES, result.program)
    colour = np.asarray(evaluate(WIRES, N, N).basecolor_linear)
    cover = colour[..., 2] > 2 * colour[..., 0]  # the blue wires
    assert change[cover].mean() > 4 * change[~cover].mean()


def test_a_coffee_ring_is_a_ring_stain_not_a_coffee_colour() -> None:
    result = _edit(FLAT, "add a coffee ring")
    note = result.report.plan["note"]
    assert "'stained' overlay" in note and "as rings" in note
    assert not any(
        c.to_json()["address"].startswith("define:plaster") for c in result.report.changes
    )
    ring = _change(FLAT, result.program)
    blot = _change(FLAT, _edit(FLAT, "add a big coffee stain").program)
    # a ring's strong change is its rim, a thin share of what it marks; a stain's is its body
    assert 0 < (ring > 0.5 * ring.max()).mean() < 0.5 * (blot > 0.5 * blot.max()).mean()


#: a perforated sheet: round holes where no layer covers (alpha 0)
PERFORATED = """View(0, 0, 1, 1, tileable=True)
Define(sheet_r, 120)
Define(sheet_g, 120)
Define(sheet_b, 125)
Define(hole, Smoothstep(0.22, 0.2, Worley(base_freq=5, to_01=True, seed=8)))
Material(
  Layer((1 - hole)).basecolor(sheet_r, sheet_g, sheet_b).roughness(0.5)
)
"""


def test_a_condition_added_to_a_cut_out_keeps_its_holes_open() -> None:
    result = _edit(PERFORATED, "make it dusty")
    assert result.report.ok, result.report.locality.to_json()
    a = np.asarray(evaluate(PERFORATED, N, N).alpha)
    b = np.asarray(evaluate(result.program, N, N).alpha)
    assert (a < 0.5).mean() > 0.05  # it has holes
    assert np.abs(a - b).max() < 0.002


@pytest.mark.parametrize(
    "request_",
    [
        "add dirt but not in the middle",
        "add moss, but not in the cracks",
        "add dust, avoiding the tops",
    ],
)
def test_a_place_the_request_excludes_gets_no_mask(request_: str) -> None:
    note = _edit(STONES, request_).report.plan["note"]
    assert "middle" not in note and "relief" not in note, note


def test_the_corner_of_each_tile_is_no_corner_of_the_surface() -> None:
    note = _edit(FLAT, "add grime at the corner of each tile").report.plan["note"]
    assert "corner" not in note


def test_a_sheer_material_still_takes_a_condition() -> None:
    sheer = FLAT.replace("Layer(1)", "Layer(0.6)")
    assert "'dusty' overlay" in _edit(sheer, "add dust").report.plan["note"]
