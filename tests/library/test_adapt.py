"""Adaptation: colour, preset, finish and scale words change the entry's slots and View."""

from __future__ import annotations

import matloom
from matloom.library import author, library
from matloom.library.adapt import slot_colour
from matloom.library.overlay import constant, define_value, prune_defines, view_width


def program(prompt: str, **kw: object) -> matloom.lang.ast.Program:
    return matloom.parse(author(prompt, **kw).program)


def default(entry: str) -> matloom.lang.ast.Program:
    return library().ast(entry)


def test_first_colour_is_the_main_colour() -> None:
    p = program("blue plastic")
    assert slot_colour(p, "base") == (40, 80, 170)


def test_tone_modifiers() -> None:
    pale = slot_colour(program("pale blue plastic"), "base")
    dark = slot_colour(program("dark blue plastic"), "base")
    assert pale is not None and dark is not None
    assert sum(pale) > sum((40, 80, 170)) > sum(dark)


def test_grout_phrase_targets_the_grout_slot() -> None:
    p = program("white square tiles with black grout")
    assert slot_colour(p, "grout") == (22, 22, 24)
    assert slot_colour(p, "tile") == (236, 236, 232)


def test_veins_phrase_targets_the_vein_slot() -> None:
    p = program("white marble with gold veins")
    assert slot_colour(p, "vein") == (212, 168, 60)
    assert slot_colour(p, "base") == (236, 236, 232)


def test_natural_colours_are_pulled_toward_the_material() -> None:
    brick = slot_colour(program("red brick wall"), "brick")
    assert brick is not None and brick != (186, 32, 36)


def test_preset_word_sets_the_species_colour() -> None:
    r = author("walnut planks")
    assert slot_colour(matloom.parse(r.program), "wood") == (112, 74, 48)
    assert any("walnut" in a for a in r.adaptations)


def test_preset_expression_changes_orientation() -> None:
    p = program("vertical stripes")
    d = p.define("axis")
    assert d is not None and matloom.format(p).count("Define(axis, X())") == 1


def test_finish_words_set_roughness_and_relief() -> None:
    assert constant(program("glossy red plastic"), "rough") == 0.14
    assert constant(program("matte red plastic"), "rough") == 0.82
    rough = program("rough concrete")
    assert constant(rough, "relief") == 1.6


def test_scale_words_resize_the_view_and_unit() -> None:
    base = author("square tiles")
    large = author("large square tiles")
    small = author("small square tiles")
    w = [view_width(matloom.parse(r.program)) for r in (large, base, small)]
    assert w[0] < w[1] < w[2]
    assert large.unit_m > base.unit_m > small.unit_m
    # the material always spans the entry's physical size
    for r, side in zip((large, base, small), w):
        assert abs(r.unit_m * side - library().entry("square-tiles").size_m) < 1e-3


def test_explicit_size_sets_the_feature_size() -> None:
    entry = library().entry("square-tiles")
    assert entry.feature_m == 0.3
    r = author("15 cm square tiles")
    side = view_width(matloom.parse(r.program))
    # tiles half the default size: twice as many across the View, each one unit_m * width
    assert side == 2 * view_width(default("square-tiles"))
    assert abs(r.unit_m * side - entry.size_m) < 1e-3
    assert any("15 cm" in a for a in r.adaptations)


def test_tileable_entries_stay_tileable_after_scaling() -> None:
    for prompt in ("large square tiles", "small square tiles", "tiny checkerboard tiles"):
        r = author(prompt)
        assert r.tileable, (prompt, r.notes)
        p = matloom.parse(r.program)
        assert p.tileable
        assert matloom.check(r.program) == []


def test_tileable_false_leaves_the_view_plain() -> None:
    r = author("square tiles", tileable=False)
    assert not r.tileable
    assert not matloom.parse(r.program).tileable


def test_overlay_amount_and_colour() -> None:
    r = author("heavily mossy cobblestone")
    assert r.overlays == ["mossy"]
    assert "amount 0.8" in r.overlay_notes[0]
    p = matloom.parse(r.program)
    assert constant(p, "cover") == 0.8
    r = author("blue moss on cobblestone")
    assert slot_colour(matloom.parse(r.program), "moss") == (40, 80, 170)


def test_prune_defines_drops_what_no_layer_uses_any_more() -> None:
    text = (
        "Define(base_r, 200)\nDefine(lum, (base_r * 0.3))\nDefine(dark_r, (lum * 0.5))\n"
        "Define(keep, 0.4)\nMaterial(Layer(1).basecolor(dark_r, 0, 0).roughness(keep))\n"
    )
    program = matloom.parse(text)
    assert prune_defines(program) is program
    # a preset sets the derived slot to a constant: lum and base_r are used no more
    adapted = define_value(program, "dark_r", 90)
    assert [d.name for d in prune_defines(adapted).defines] == ["dark_r", "keep"]
    assert matloom.check(matloom.format(prune_defines(adapted))) == []


def test_a_colour_of_something_the_entry_lacks_leaves_the_material_alone() -> None:
    r = author("aluminium diamond plate floor with a yellow hazard stripe along one edge")
    assert r.entry == "diamond-plate"
    rgb = slot_colour(matloom.parse(r.program), "metal")
    assert rgb is not None and max(rgb) - min(rgb) < 20  # aluminium grey, not yellow
    assert any(i.startswith("yellow") for i in r.ignored)
    # a colour of the material itself still applies
    assert slot_colour(program("yellow diamond plate"), "metal") != slot_colour(
        default("diamond-plate"), "metal"
    )


def test_plural_colour_words_are_colours() -> None:
    r = author("woven fabric in greys and browns")
    assert "greys" not in r.ignored and "browns" not in r.ignored
    assert any("grey" in a for a in r.adaptations)


def test_metallic_finish_sets_the_metallic_slot() -> None:
    r = author("shiny metallic fabric with a rose gold honeycomb pattern")
    assert r.entry == "honeycomb-print"
    assert constant(matloom.parse(r.program), "metal") == 1


def test_a_role_noun_after_a_colour_list_takes_every_colour_of_the_list() -> None:
    r = author("spalted wood with black and gray line patterns")
    assert r.entry == "spalted-wood"
    p = matloom.parse(r.program)
    assert slot_colour(p, "line") == (22, 22, 24)
    # the wood itself keeps its colour: the colours named the lines, not the wood
    assert slot_colour(p, "wood") == slot_colour(default("spalted-wood"), "wood")


def test_one_named_colour_leaves_the_accent_slots_of_a_patterned_entry() -> None:
    r = author("handmade paper, off-white, with flecks of dried petals")
    assert r.entry == "handmade-paper-inclusions"
    p = matloom.parse(r.program)
    assert slot_colour(p, "petal") == slot_colour(default("handmade-paper-inclusions"), "petal")


def test_an_amount_word_lowers_the_wear_of_an_entry_that_shows_the_condition() -> None:
    slight = constant(program("slightly rusted metal"), "wear")
    heavy = constant(program("heavily rusted metal"), "wear")
    assert slight is not None and heavy is not None and slight < 0.5 < heavy


def test_an_area_is_the_extent_the_texture_covers_not_a_feature() -> None:
    """ "2x2m" (a game artist's texture extent) widens the View to cover two metres of the
    material; it is never the size of one cobblestone, nor one repeat of a composed layout."""
    from matloom.library.parts import read_parts

    plain = author("cobblestone street")
    wide = author("cobblestone street, 4x4m")
    assert plain.entry == wide.entry == "cobblestone"
    assert view_width(wide.ast) > view_width(plain.ast)
    assert any("4 m across" in n for n in wide.adaptations)
    assert read_parts("white vinyl siding, 3x3m").size_m is None
    assert read_parts("white vinyl siding, 20cm boards, 3x3m").size_m == 0.2
    tiles = author("square ceramic tiles, 30 cm")
    assert not any("across" in n for n in tiles.adaptations)


def test_a_colour_before_a_modifier_of_the_material_is_the_materials() -> None:
    """ "forest green polar fleece", "lilac mohair knit": the unknown word between the colour
    and the material only modifies it; "red leaves on grey stone" stays the leaves' colour."""
    fleece = author("This is a forest green polar fleece. The surface is fuzzy.")
    assert any("forest green" in a for a in fleece.adaptations)
    knit = author("This is a lilac mohair knit.")
    assert any("'lilac'" in a for a in knit.adaptations)
    leaves = author("grey flagstones with red leaves on them")
    assert not any("'red'" in a for a in leaves.adaptations)


def test_a_colour_goes_to_the_slot_of_its_name_and_light_to_light() -> None:
    """ "yellow-and-black hazard stripe": yellow on the yellow stripes; "black and white
    checkerboard": black on the dark squares, whatever slot comes first."""
    hazard = author("diamond plate with a yellow-and-black hazard stripe")
    assert "colour yellow = 'yellow' (236, 204, 40) (the slot of that colour)" in hazard.adaptations
    for said in ("black and white checkerboard floor", "white and black checkerboard floor"):
        checks = author(said)
        got = {a.split(" = ")[0]: a.split("'")[1] for a in checks.adaptations if "colour" in a}
        assert got.get("colour dark") == "black" and got.get("colour light") == "white", said
