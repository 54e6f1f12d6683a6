"""Offline edits beyond parameter assignments: the part a noun names (and what it leaves
alone), a library overlay added on top, layers rewritten for relief, channel bases inside sums
and clamps, and the escalation of a step too small to see."""

from __future__ import annotations

import math
import re

import pytest

from author.test_edit_rules import program
from matloom.author.edit import EditRefused, edit_offline
from matloom.author.edit.apply import all_params, parse_program
from matloom.author.edit.core import changed_seeds
from matloom.lang.api import check


def _seeds(text: str) -> dict[str, object]:
    return {p.address: p.value for p in all_params(parse_program(text)) if p.kind == "seed"}


@pytest.mark.parametrize(
    ("name", "request_", "changed", "kept"),
    [
        # "coating" is the paint layer's roughness, not the bare metal's or the rust's
        ("painted", "make the coating rougher", {"define:rough"}, {"layer:1.roughness"}),
        # "red paint": the paint colour, not the rust whose layer shows where the paint is not
        ("painted", "red paint", {"define:paint_col"}, {"define:rust_col", "define:metal"}),
        # "bigger tiles": the tile pattern, not the glaze noise on the tiles
        (
            "black",
            "bigger tiles",
            {"define:tileMask.Bricks.brick_width"},
            {"define:glazeRipple.fBm.base_freq", "define:glazeGrain.fBm.base_freq"},
        ),
        # "yellow bricks": the brick colour, not the mortar mixed into a brick-masked layer
        ("brickwall", "yellow bricks", {"colour:brick"}, {"define:mortar"}),
        # "the blue": the colour that is blue (the cobalt), not the white glaze
        ("delft", "make the blue darker", {"define:cobalt"}, {"define:glaze", "define:grout"}),
    ],
)
def test_the_noun_picks_its_part(name: str, request_: str, changed: set, kept: set) -> None:
    plan = edit_offline(program(name), request_, size=32).report.plan
    assert changed <= set(plan["assignments"]), plan["assignments"]
    assert not kept & set(plan["assignments"]), plan["assignments"]


@pytest.mark.parametrize(
    ("name", "request_", "overlay"),
    [
        ("brickwall", "add moss", "mossy"),
        ("brushed", "add dirt", "dirty"),
        ("painted", "more scratches", "scratched"),
        ("leather", "more worn", "worn"),
    ],
)
def test_absent_condition_adds_the_library_overlay(name: str, request_: str, overlay: str) -> None:
    text = program(name)
    result = edit_offline(text, request_, size=32)
    plan = result.report.plan
    assert plan["rule"] == "overlay" and overlay in plan["note"]
    before, after = parse_program(text), parse_program(result.program)
    added = len(after.layers) - len(before.layers)
    assert added >= 1 and after.layers[: len(before.layers)] == before.layers
    assert [d.name for d in after.defines[: len(before.defines)]] == [
        d.name for d in before.defines
    ]
    assert not [d for d in check(result.program) if d.is_error]
    old, new = _seeds(text), _seeds(result.program)
    assert all(new[a] == v for a, v in old.items())  # every existing seed kept
    assert len(new) > len(old)  # the overlay's noises bring new ones
    assert result.report.ok and result.report.locality.changed
    assert any(c.label == "added layer" for c in result.report.changes)


def test_overlay_words_and_feature_words() -> None:
    # an overlay's own trigger ("snowy") asked for alone, or with an amount word
    for request_ in ("make it snowy", "a little moss"):
        assert edit_offline(program("black"), request_, size=32).report.plan["rule"] == "overlay"
    # "bigger chips" is the size of chips, not the chipped overlay; "red paint" no painting
    assert edit_offline(program("concrete"), "bigger chips", size=32).report.plan["rule"] == "scale"
    assert edit_offline(program("painted"), "red paint", size=32).report.plan["rule"] == "colour"


def test_less_of_an_absent_condition_is_refused() -> None:
    with pytest.raises(EditRefused, match="no moss in this program to reduce"):
        edit_offline(program("brickwall"), "less moss", size=32)


def test_relief_without_a_relief_parameter_rewrites_the_heights() -> None:
    text = program("weathered")  # heights written out, no relief scalar
    result = edit_offline(text, "flatter", size=32)
    plan = result.report.plan
    assert plan["rule"] == "relief" and not plan["assignments"]
    assert set(plan["replace"]) == {"layer:1", "layer:2"}  # the layers whose height varies
    assert "* 0.5)" in plan["replace"]["layer:2"]
    assert set(result.report.locality.changed) <= {"height", "normal", "ao"}
    assert result.report.ok
    assert [c.address for c in result.report.changes] == ["layer:1", "layer:2"]


def test_rougher_on_a_rough_surface_deepens_the_relief_too() -> None:
    result = edit_offline(program("weathered"), "make it rougher", size=32)
    plan = result.report.plan
    assert plan["assignments"]["layer:2.roughness.base"] == pytest.approx(0.92)
    assert "relief x1.6" in plan["note"] and plan["replace"]  # the bricks start at 0.7
    glossy = edit_offline(program("black"), "rougher", size=32).report.plan
    assert "relief" not in glossy["note"] and "replace" not in glossy  # the glaze starts glossy


def test_channel_bases_inside_sums_and_clamps() -> None:
    params = {p.address: p for p in all_params(parse_program(program("velvet")))}
    # .sheen(Clamp((0.8 + (lie * 0.2)), 0, 1)) and .roughness(Clamp(((0.86 - ...) + ...), 0, 1))
    assert params["layer:1.sheen.base"].value == 0.8
    assert params["layer:1.roughness.base"].value == 0.86
    result = edit_offline(program("velvet"), "less sheen", size=32)
    assert "Clamp((0.4 + (lie * 0.2)), 0, 1)" in result.program  # written as it was, 0.8 -> 0.4
    assert result.report.locality.changed == ("sheen",)


def test_a_step_too_small_to_see_is_escalated() -> None:
    text = (
        "View(0, 0, 10, 10)\nDefine(b, Bricks(mortar=0.005))\n"
        "Material(Layer(1).basecolor(200, 200, 200), Layer(b).basecolor(150, 60, 40))"
    )
    result = edit_offline(text, "wider mortar", size=32)
    plan = result.report.plan
    # x2 of a sub-pixel joint would change nothing the preview shows: a wider joint is at
    # least 3.5 pixels of a 192-pixel preview of the View (10 units: 0.18)
    assert plan["assignments"]["define:b.Bricks.mortar"] > 0.15
    assert not result.report.warnings
    calm = edit_offline(text, "slightly wider mortar", size=32)
    assert "strength" not in calm.report.plan  # "slightly" is not escalated
    slight = calm.report.plan["assignments"]["define:b.Bricks.mortar"]
    assert 0.005 < slight < plan["assignments"]["define:b.Bricks.mortar"]


def test_physical_size_changes_no_map_without_a_scale() -> None:
    result = edit_offline(program("black"), "2 m wide", size=32)
    assert result.report.locality.changed == ()
    assert "unit_m=1" in result.program and not result.report.warnings


def test_zoom_keeps_a_tileable_program_tiling() -> None:
    from matloom.lang.tileable import tileable_warnings

    result = edit_offline(program("cobble"), "smaller stones", size=32)
    after = parse_program(result.program)
    assert after.view is not None and after.view.tileable
    assert (after.view.x2 - after.view.x1) == pytest.approx(4.0)
    assert len(tileable_warnings(after)) <= len(tileable_warnings(parse_program(program("cobble"))))


def test_changed_seeds_ignores_new_lines_but_not_a_changed_one() -> None:
    before = parse_program(program("black"))
    grown = parse_program(
        re.sub(
            r"Material\(",
            "Define(moss, fBm(base_freq=3, seed=99))\nMaterial(",
            program("black"),
            count=1,
        ).replace("Layer(tileMask)", "Layer((tileMask * moss))")
    )
    assert changed_seeds(before, grown) == []
    reseeded = parse_program(program("black").replace("seed=891377204", "seed=5"))
    assert changed_seeds(before, reseeded) == ["define:groutNoise.fBm.seed"]


def test_derived_colour_slot_of_a_named_part() -> None:
    # the square tiles' grout is derived from the tile colour: "darker grout" writes the
    # grout's three components as constants (darker), and leaves the tile colour alone
    before = program("square")
    result = edit_offline(before, "darker grout", size=32)
    lines = result.report.plan["replace"]
    assert set(lines) == {"define:grout_r", "define:grout_g", "define:grout_b"}
    assert "Define(tile_r, 226)" in result.program
    assert not [d for d in check(result.program) if d.is_error]
    new = [int(re.search(r", (\d+)\)", lines[f"define:grout_{k}"]).group(1)) for k in "rgb"]
    assert sum(new) < (226 + 224 + 218) * 0.65  # darker than the derived grout was


def test_less_dark_is_lighter() -> None:
    # "less dark" flips the tone: the derived grout gets lighter than it was
    result = edit_offline(program("square"), "make the grout less dark", size=32)
    lines = result.report.plan["replace"]
    assert int(re.search(r", (\d+)\)", lines["define:grout_r"]).group(1)) > 226 * 0.65


@pytest.mark.parametrize(
    ("request_", "reason"),
    [
        # a feature the program does not draw: refused, not the whole material rescaled
        ("smaller hexagons", "nothing in the program is named like 'hexagons'"),
        # a count no parameter draws: zooming would change the size, not the number
        ("fewer specks", "no parameter draws the specks"),
    ],
)
def test_unnamed_feature_refused(request_: str, reason: str) -> None:
    with pytest.raises(EditRefused, match=reason) as info:
        edit_offline(program("square"), request_, size=32)
    assert "define:" in str(info.value)  # the parameters it could change are listed


def test_keep_clause_and_mixed_colour() -> None:
    # what the request keeps is not what it changes
    kept = edit_offline(program("square"), "dark grey grout, keep the tiles as they are", size=32)
    assert set(kept.report.plan["replace"]) == {
        "define:grout_r",
        "define:grout_g",
        "define:grout_b",
    }
    # "purple brown": between the two in CIELAB, not the first one
    mixed = edit_offline(program("square"), "purple brown tiles", size=32).report.plan
    r, g, b = mixed["assignments"]["colour:tile"]
    assert r > b > g  # a brownish purple: red first, then blue, green least


def test_greyer_less_named_colour_reduces_chroma() -> None:
    from matloom.author.edit.lab import to_lab

    before = dict((p.address, p.value) for p in all_params(parse_program(program("painted"))))
    plan = edit_offline(program("painted"), "greyer paint, less red", size=32).report.plan
    new = plan["assignments"]["define:paint_col"]
    chroma = [math.hypot(*to_lab(c)[1:]) for c in (before["define:paint_col"], new)]
    assert chroma[1] < chroma[0] * 0.6


def test_copies_of_a_pattern_scale_in_step() -> None:
    text = (
        "Define(plank, Bricks(brick_width=1, brick_height=0.25, mortar=0.01))\n"
        'Define(plankval, Bricks(brick_width=1, brick_height=0.25, output="cell_value", seed=3))\n'
        "Material(Layer(1).basecolor(40, 30, 20).roughness(0.9),"
        " Layer(plank).basecolor((120 + (plankval * 60)), 90, 60).roughness(0.6))"
    )
    plan = edit_offline(text, "bigger planks", size=32).report.plan
    assert plan["assignments"]["define:plank.Bricks.brick_width"] == 1.5
    assert plan["assignments"]["define:plankval.Bricks.brick_width"] == 1.5


def test_relief_visibility_is_measured_in_the_normal_map() -> None:
    from matloom.author.edit.core import verify

    text = (
        "Define(n, fBm(octaves=3, base_freq=4, seed=1))\n"
        "Material(Layer(1).basecolor(100, 100, 100).roughness(0.5).height((0.01 + (n * 0.001))))"
    )
    after = text.replace("(0.01 + ", "(0.02 + ")
    checked = verify(parse_program(text), after, "deeper", ("height",), 32, None)
    assert checked.visible["height"] > 0.5  # the whole height map moved up ...
    assert checked.shows(0.05)  # ... which any allowed map counts
    assert not checked.shows(0.05, ("height",))  # but the lit preview (normals) would not show
