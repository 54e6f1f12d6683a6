"""Offline edits: a colour swapped by its family name moves every colour of that family; a
request about the repeat zooms the whole design; oil, salt, frost and lichen have overlays of
their own; a condition placed on part of the surface is put there, or refused on a program
that tiles; overlays do not follow a relief too shallow to see."""

from __future__ import annotations

import numpy as np
import pytest

from matloom.author.edit.core import edit_offline
from matloom.author.edit.plan import EditRefused
from matloom.engine.evaluate import evaluate
from matloom.library import load_library
from matloom.library.overlay import compose

LIB = load_library()

#: yellow stripes on a beige ground: "the yellow" is the stripes, not the beige
STRIPES = """View(0, 0, 2, 2, tileable=True)
Define(stripe_r, 236)
Define(stripe_g, 200)
Define(stripe_b, 30)
Define(ground_r, 214)
Define(ground_g, 200)
Define(ground_b, 170)
Define(band, Smoothstep(0.45, 0.55, Fract((X() * 2))))
Material(
  Layer(1).basecolor(ground_r, ground_g, ground_b).roughness(0.6),
  Layer(band).basecolor(stripe_r, stripe_g, stripe_b).roughness(0.6)
)
"""


def _edit(text: str, request: str):  # noqa: ANN202 - the EditResult
    return edit_offline(text, request, size=32)


def _changed(result) -> set[str]:  # noqa: ANN001
    return {c.to_json()["address"] for c in result.report.changes}


def test_a_swapped_colour_family_moves_every_colour_of_it() -> None:
    damask = LIB.entry("damask-wallpaper-teal").program
    changed = _changed(_edit(damask, "Switch the teal for a deep burgundy."))
    assert {"define:motif", "define:ground"} <= changed  # the light and the dark teal


def test_plural_families_are_colours_to_swap() -> None:
    mosaic = LIB.entry("glass-mosaic-tiles").program
    changed = _changed(_edit(mosaic, "swap the blues and greens for warm amber"))
    assert len([a for a in changed if a.startswith("define:glass")]) >= 2


def test_a_family_keeps_to_its_hue_and_chroma() -> None:
    changed = _changed(_edit(STRIPES, "swap the yellow for orange"))
    assert any(a.startswith("define:stripe") for a in changed)
    assert not any(a.startswith("define:ground") for a in changed)  # beige is no yellow


def test_the_repeat_zooms_the_whole_design() -> None:
    damask = LIB.entry("damask-wallpaper-teal").program
    result = _edit(damask, "Make the damask motif smaller so it repeats more often.")
    assert result.report.plan["view"]
    assert "whole design" in result.report.plan["note"]


@pytest.mark.parametrize(
    ("request_", "overlay"),
    [
        ("add oil stains", "oily"),
        ("a few grease spots please", "oily"),
        ("add white salt efflorescence", "efflorescence"),
        ("add a white salty bloom", "efflorescence"),
        ("add a light frost", "frosty"),
        ("give it some lichen", "lichen"),
    ],
)
def test_conditions_with_overlays_of_their_own(request_: str, overlay: str) -> None:
    wall = LIB.entry("brick-wall").program
    assert f"'{overlay}' overlay" in _edit(wall, request_).report.plan["note"]


def test_oil_stains_darken() -> None:
    host = LIB.entry("brick-wall").program
    after = _edit(host, "add oil stains").program
    a = evaluate(host, 48, 48).basecolor_linear[..., :3].mean()
    b = evaluate(after, 48, 48).basecolor_linear[..., :3].mean()
    assert b < a * 0.95


def test_a_place_on_a_tiling_program_is_refused() -> None:
    wall = LIB.entry("brick-wall").program
    with pytest.raises(EditRefused, match="place on the surface"):
        _edit(wall, "add some grime near the bottom")
    _edit(wall, "add some grime")  # the same condition with no place is accepted


def test_a_place_on_a_program_that_does_not_tile_is_a_gradient() -> None:
    wall = LIB.entry("brick-wall").program.replace("tileable=True", "tileable=False")
    result = _edit(wall, "add some grime near the bottom")
    assert "near the bottom" in result.report.plan["note"]
    a = evaluate(wall, 64, 64).basecolor_linear[..., :3]
    b = evaluate(result.program, 64, 64).basecolor_linear[..., :3]
    change = np.abs(a - b).sum(axis=-1)
    # rows are top first in the maps: the lower half changed, the upper barely
    assert change[32:].mean() > 4 * change[:32].mean()


@pytest.mark.parametrize("name", ["marble", "brushed-stainless-steel-sheet"])
def test_a_relief_too_shallow_to_see_is_not_followed(name: str) -> None:
    program = compose(LIB.ast(name), LIB.overlays["dirty"], main_colour=None, cover=0.5)
    assert "host_height" not in {d.name for d in program.defines}


def test_a_deep_relief_is_followed() -> None:
    program = compose(LIB.ast("brick-wall"), LIB.overlays["dirty"], main_colour=None, cover=0.5)
    assert "host_height" in {d.name for d in program.defines}


def test_a_condition_the_program_lacks_is_added_with_its_look() -> None:
    stones = LIB.entry("gabion-stone-wall").program
    result = _edit(stones, "lichen on the stones, those pale yellow-green crusty patches")
    assert "'lichen' overlay" in result.report.plan["note"]
    assert not any(a.startswith(("define:stone", "colour:stone")) for a in _changed(result))
    lawn = LIB.entry("lawn-grass-top-down").program
    note = _edit(lawn, "light dusting of snow with green blades poking through").report.plan
    assert "'snowy' overlay" in note["note"]


def test_a_condition_the_program_is_made_of_is_a_property() -> None:
    mud = LIB.entry("muddy-field-puddles").program
    assert "overlay" not in _edit(mud, "drier mud").report.plan["note"]


def test_a_simile_names_no_part_to_reduce() -> None:
    adobe = LIB.entry("adobe-mud-brick").program
    try:
        note = _edit(adobe, "less crumbly and eroded, like the bricks were only laid last week")
    except EditRefused:
        return
    assert "less brick" not in note.report.plan["note"]


def test_a_place_where_it_stays_damp_is_no_wet_look() -> None:
    wall = LIB.entry("brick-wall").program.replace("tileable=True", "tileable=False")
    request = "Put a little green moss in the joints and along the base where it stays damp"
    assert _edit(wall, request).report.plan["rule"].startswith("overlay")


def test_an_added_condition_that_does_not_show_is_added_more_strongly() -> None:
    plaster = LIB.entry("plaster").program  # a pale dust on a pale plaster hardly shows
    result = _edit(plaster, "a little dust")
    assert result.report.plan.get("strength", 1.0) > 1.0
    assert "'dusty' overlay" in result.report.plan["note"]


def test_two_wishes_make_two_changes() -> None:
    mosaic = LIB.entry("basketweave-marble-mosaic").program
    plan = _edit(mosaic, "Wider grout joints, and make the grout a darker grey.").report.plan
    assert plan["rule"] == "joints+colour" and "wider" in plan["note"]
    tiles = LIB.entry("tigers-eye-polished-tiles").program
    plan = _edit(tiles, "Bigger tiles with thinner joints.").report.plan
    assert "joints narrower" in plan["note"] and "scale" in plan["rule"]
    foam = LIB.entry("reticulated-foam").program
    plan = _edit(foam, "Smaller, denser cells and a bit more matte.").report.plan
    assert plan["rule"] == "roughness+scale" and plan["view"]


def test_a_part_named_by_its_colour_beside_a_size_is_resized() -> None:
    enamel = LIB.entry("cloisonne-enamel-floral").program
    plan = _edit(enamel, "thicker gold wires").report.plan
    assert plan["rule"] == "scale"


def test_a_change_and_an_added_condition_are_both_made() -> None:
    pipes = LIB.entry("industrial-pipe-rack").program
    request = "Paint the pipes safety yellow and add some rust streaks running down"
    plan = _edit(pipes, request).report.plan
    assert plan["rule"] == "colour+overlay" and "'rusty' overlay" in plan["note"]
    plate = LIB.entry("perforated-metal").program
    plan = _edit(plate, "Powder coat it matte black and add some chipped spots").report.plan
    assert "'chipped' overlay" in plan["note"]
    black = [v for k, v in plan["assignments"].items() if k.startswith("define:metal")]
    assert black and max(black[0]) < 60  # black, not powder blue


def test_less_of_an_overlay_over_another_moves_only_its_own_cover() -> None:
    # rust composed over moss follows the host's height, which reads the moss's cover: "less
    # rust" lowered both covers
    from matloom.author.edit.apply import all_params
    from matloom.author.edit.rules import plan_edit
    from matloom.lang.api import parse
    from matloom.library import author

    program = parse(author("mossy rusty brick wall").program)
    params = all_params(program)
    names = {p.address for p in params if p.address.startswith("define:cover")}
    assert names == {"define:cover", "define:cover2"}
    rust = plan_edit(program, params, "less rust")
    moss = plan_edit(program, params, "less moss")
    assert list(rust.assignments) == ["define:cover2"], rust
    assert list(moss.assignments) == ["define:cover"], moss
