"""Offline edits beyond parameter assignments: the part a noun names (and what it leaves
alone), a library overlay added on top, layers rewritten for relief, channel bases inside sums
and clamps, and the escalation of a step too small to see."""

from __future__ import annotations

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
    # an overlay's own trigger ("wet") asked for alone, or with an amount word
    for request_ in ("make it wet", "a little moss"):
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
    assert "Clamp(x=(0.4 + (lie * 0.2))" in result.program
    assert result.report.locality.changed == ("sheen",)


def test_a_step_too_small_to_see_is_escalated() -> None:
    text = (
        "View(0, 0, 10, 10)\nDefine(b, Bricks(mortar=0.005))\n"
        "Material(Layer(1).basecolor(200, 200, 200), Layer(b).basecolor(150, 60, 40))"
    )
    result = edit_offline(text, "wider mortar", size=32)
    plan = result.report.plan
    assert plan["strength"] > 1  # x2 of a sub-pixel joint changed nothing the preview shows
    assert plan["assignments"]["define:b.Bricks.mortar"] > 0.01
    assert not result.report.warnings
    calm = edit_offline(text, "slightly wider mortar", size=32)
    assert "strength" not in calm.report.plan  # "slightly" is not escalated
    assert calm.report.warnings == ["the change is small: it may not show in a preview"]


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
