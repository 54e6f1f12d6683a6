"""Words around an edit's target: "too bright" is a colour (not a finish), "rosettes" are a
print's spots, and a clause saying what the edit should go with ("so it sits better with the
red", "to match the grout") names no colour to paint."""

from __future__ import annotations

import pytest

from matloom.author.edit.core import edit_offline
from matloom.author.edit.plan import EditRefused

PRINT = """View(0, 0, 1, 1, tileable=True)
Define(ground_r, 236)
Define(ground_g, 226)
Define(ground_b, 200)
Define(spot_col_r, 40)
Define(spot_col_g, 30)
Define(spot_col_b, 20)
Define(spot, Smoothstep(0.3, 0.25, Worley(base_freq=6, to_01=True, seed=4)))
Material(
  Layer(1).basecolor(ground_r, ground_g, ground_b).roughness(0.7),
  Layer(spot).basecolor(spot_col_r, spot_col_g, spot_col_b).roughness(0.7)
)
"""


def _changed(request: str) -> dict[str, object]:
    result = edit_offline(PRINT, request, size=32)
    rows = (c.to_json() for c in result.report.changes)
    # the colour parameters (an RGB triple's own lines are listed too)
    return {r["address"]: r["after"] for r in rows if not r["address"].endswith(("_r", "_g", "_b"))}


def test_too_bright_is_a_muted_colour_not_a_rougher_finish() -> None:
    changed = _changed("the background is too bright")
    assert not any("roughness" in a for a in changed)
    r, g, b = changed["define:ground"]  # type: ignore[misc]
    assert r < 236 and (r - b) < (236 - 200)  # darker and less saturated


def test_rosettes_are_the_spots() -> None:
    assert set(_changed("darker rosettes")) == {"define:spot_col"}


def test_a_purpose_clause_names_no_colour() -> None:
    changed = _changed("make the background oatmeal so it sits better with the red")
    r, g, b = changed["define:ground"]  # type: ignore[misc]
    assert r > 180 and g > 170 and abs(r - g) < 30  # oatmeal, not red
    assert set(changed) == {"define:ground"}


#: a cream print with pale periwinkle flowers: far from the named blue in CIELAB, of its hue
FLOWERS = PRINT.replace(
    "Define(spot_col_r, 40)\nDefine(spot_col_g, 30)\nDefine(spot_col_b, 20)",
    "Define(spot_col_r, 120)\nDefine(spot_col_g, 150)\nDefine(spot_col_b, 210)",
)


def test_the_blue_is_the_part_of_that_hue_a_darker_blue_is_a_colour_to_paint() -> None:
    result = edit_offline(FLOWERS, "make the blue darker", size=32)
    rows = {c.to_json()["address"]: c.to_json()["after"] for c in result.report.changes}
    assert "define:spot_col" in rows and "define:ground" not in rows
    r, g, b = rows["define:spot_col"]  # type: ignore[misc]
    assert b < 210 and b > r  # the same blue, darker
    rows = {
        c.to_json()["address"]
        for c in edit_offline(FLOWERS, "make it a darker blue", size=32).report.changes
    }
    assert "define:ground" in rows


def test_a_purpose_clause_keeps_the_clauses_after_it() -> None:
    result = edit_offline(
        PRINT, "make the background oatmeal so it goes with the spots and add moss", size=32
    )
    assert "'mossy' overlay" in result.report.plan["note"]
    assert any(c.to_json()["address"] == "define:ground" for c in result.report.changes)


def test_white_as_a_verb() -> None:
    """ "white it a little": whiter (it was read as the unknown word "whiteer" and refused)."""
    r, g, b = _changed("white it a little")["define:ground"]  # type: ignore[misc]
    assert b > 200 and min(r, g, b) >= 200


GLAZE = """View(0, 0, 1, 1, tileable=True)
Define(tile_r, 230)
Define(tile_g, 230)
Define(tile_b, 226)
Material(
  Layer(1).basecolor(tile_r, tile_g, tile_b).roughness(0.12)
)
"""


def test_wet_darkens_what_is_porous_not_a_glaze() -> None:
    soil = GLAZE.replace(".roughness(0.12)", ".roughness(0.95)")
    glaze = edit_offline(GLAZE, "make it look wet", size=32)
    rough = edit_offline(soil, "make it look wet", size=32)

    def colour(result: object) -> list[float]:
        rows = {c.to_json()["address"]: c.to_json()["after"] for c in result.report.changes}  # type: ignore[attr-defined]
        return rows.get("define:tile", [230, 230, 226])  # type: ignore[return-value]

    assert sum(colour(glaze)) > 3 * 200  # a glaze darkens little when wet (its grout would)
    assert sum(colour(rough)) < 3 * 190  # soil soaks it up
    # "wet and darker" is darker whatever the surface
    darker = edit_offline(GLAZE, "make it look wet and darker", size=32)
    assert sum(colour(darker)) < 3 * 190


def test_add_some_yellowing_is_the_look_but_wet_patches_are_patches() -> None:
    from matloom.author.edit.rules import normalise

    assert normalise("add some yellowing") == "add some yellower overall"
    assert normalise("add some wet patches") == "add some wet patches"
    changed = _changed("add some yellowing")
    r, g, b = changed["define:ground"]  # type: ignore[misc]
    assert b < 200 - 20 and r >= 230  # the cream ground is yellower


def test_a_clear_coat_asked_for_where_none_is_written_is_added() -> None:
    import numpy as np

    from matloom.engine.evaluate import evaluate
    from matloom.lang.api import parse

    result = edit_offline(PRINT, "give it a clear varnish", size=32)
    assert result.report.plan["rule"] == "channel" and result.report.locality.ok
    coat = np.asarray(evaluate(parse(result.program), 32, 32).coat)
    assert coat.min() > 0.7  # every layer is coated
    before = evaluate(parse(PRINT), 32, 32)
    after = evaluate(parse(result.program), 32, 32)
    assert np.array_equal(before.basecolor_linear, after.basecolor_linear)
    with pytest.raises(EditRefused):  # nothing to take away
        edit_offline(PRINT, "no clear coat", size=32)


def test_a_coat_written_as_an_expression_is_not_overwritten() -> None:
    masked = PRINT.replace(
        "Layer(spot).basecolor(spot_col_r, spot_col_g, spot_col_b).roughness(0.7)",
        "Layer(spot).basecolor(spot_col_r, spot_col_g, spot_col_b).roughness(0.7).coat(spot)",
    )
    with pytest.raises(EditRefused):
        edit_offline(masked, "give it a clear varnish", size=32)
