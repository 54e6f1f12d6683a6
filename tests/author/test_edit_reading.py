"""Offline edits for wordings the v1-v10 edit sets showed misread: what a request replaces
("frosted instead of polished", "clear tape instead of brown"), "too big" (smaller ones),
"knock the gloss down", "coarser grain ... twice as big" (a size, not a finish), a colour word
that names a part ("thinner brass strips", "give the ice a slight blue tint"), a clause that
only describes the one before ("the wires copper, a warm orange-brown"), tints ("a slight
blue tint" keeps the lightness), looks of conditions ("lichen" is pale, "sooty" dark), a
condition word that says where ("weeds out of the cracks") and looks that change a surface
everywhere ("make it look wet": darker and glossier, not patches on top)."""

from __future__ import annotations

import math
import re

import pytest

from matloom.author.edit import EditRefused, edit_offline
from matloom.author.edit.apply import parse_program
from matloom.author.edit.lab import to_lab
from matloom.lang.params import list_params


def _entry(name: str) -> str:
    from matloom.library import load_library

    return load_library().entry(name).program


def _values(text: str) -> dict[str, object]:
    return {p.address: p.value for p in list_params(parse_program(text))}


def _plan(name: str, request: str) -> dict:
    return edit_offline(_entry(name), request, size=32).report.plan


def _window(text: str) -> float:
    v = parse_program(text).view
    return abs(v.x2 - v.x1)


def test_too_big_asks_for_smaller_ones_and_half_the_size_halves_them() -> None:
    before = _entry("hexagon-tiles")
    after = edit_offline(before, "hexes are too big, make them about half the size", size=32)
    assert _window(after.program) == pytest.approx(2 * _window(before))  # twice the window


def test_knocking_the_gloss_down_to_satin_reaches_satin() -> None:
    plan = _plan("toy-brick-stud-baseplate", "knock the gloss down to a satin finish")
    assert plan["rule"] == "roughness"
    assert "satin" in plan["note"] and "clearcoat down" in plan["note"]


def test_the_finish_named_as_replaced_is_not_the_one_applied() -> None:
    name = "wired-safety-glass"
    before = _values(_entry(name))
    plan = _plan(name, "frosted glass instead of polished")
    assert plan["rule"] == "roughness"
    for address, value in plan["assignments"].items():
        if "rough" in address:
            assert value > before[address]  # rougher, not glossier


def test_a_coarser_grain_with_a_size_is_a_size_not_a_finish() -> None:
    plan = _plan("granite", "coarser grain, the speckles about twice as big")
    assert plan["rule"] == "scale"
    assert not any("rough" in a for a in plan["assignments"])


def test_flattening_a_texture_to_nearly_smooth_is_the_relief() -> None:
    plan = _plan("sidewalk-slabs-expansion-joints", "flatten the broom texture, nearly smooth")
    assert plan["rule"] == "relief"


def test_a_colour_named_only_as_the_one_replaced_is_not_painted() -> None:
    with pytest.raises(EditRefused, match="no offline rule understands it"):
        edit_offline(_entry("cardboard-box-packing-tape"), "clear packing tape instead of brown")


def test_a_colour_word_naming_a_part_with_a_size_word_is_the_part() -> None:
    name = "terrazzo-floor-brass-strips"
    result = edit_offline(_entry(name), "thinner brass strips, almost hairline", size=32)
    assert result.report.plan["rule"] == "scale"
    assert _values(result.program)["define:brass"] == _values(_entry(name))["define:brass"]


def test_a_clause_that_describes_the_colour_joins_no_other_part() -> None:
    name = "wired-safety-glass"
    result = edit_offline(_entry(name), "make the wires copper, a warm orange-brown", size=32)
    before, after = _values(_entry(name)), _values(result.program)
    assert after["define:wire"] != before["define:wire"]
    assert after["define:glass"] == before["define:glass"]


def test_a_slight_tint_keeps_the_lightness_and_moves_the_hue() -> None:
    name = "ice-cubes-pile"
    result = edit_offline(_entry(name), "give the ice a slight blue tint", size=32)
    old = to_lab(_values(_entry(name))["define:ice"])  # type: ignore[arg-type]
    new = to_lab(_values(result.program)["define:ice"])  # type: ignore[arg-type]
    blue = to_lab((40, 80, 170))
    assert abs(new[0] - old[0]) < 1.5  # as light as it was

    def far(lab: tuple[float, float, float]) -> float:
        return math.hypot(lab[1] - blue[1], lab[2] - blue[2])

    assert far(new) < far(old) - 5  # its hue and chroma toward blue's
    assert math.hypot(new[1] - old[1], new[2] - old[2]) >= 8  # a tint that shows


@pytest.mark.parametrize(
    ("request_", "overlay", "dark"),
    [("more lichen on the rocks", "lichen", False), ("make it look sooty", "sooty", True)],
)
def test_a_condition_with_a_look_of_its_own_colours_its_overlay(
    request_: str, overlay: str, dark: bool
) -> None:
    plan = _plan("rock-scree-slope", request_)
    assert f"'{overlay}'" in plan["note"]
    found = re.search(r"coloured \((\d+), (\d+), (\d+)\)", plan["note"])
    assert found is not None
    r, g, b = (int(x) for x in found.groups())
    # the overlay's colour slot (renamed when the entry has one: ``lichen_r2``)
    assert any(
        re.fullmatch(rf"Define\((?:moss|grime|lichen|soot)2?_r2?, {r}\)", a) for a in plan["add"]
    )
    assert (max(r, g, b) < 60) if dark else (min(r, g, b) > 120)  # soot dark, lichen pale


def test_a_colour_named_before_a_condition_tints_its_overlay_half_way() -> None:
    from matloom.author.edit.conditions import library_overlays
    from matloom.library.data import words

    plan = _plan("polished-metal", "add some orange rust")
    found = re.search(r"coloured \((\d+), (\d+), (\d+)\)", plan["note"])
    assert "'rusty'" in plan["note"] and found is not None
    rusty = library_overlays()["rusty"]
    slot = next(x for x in rusty.colours if x != rusty.host)
    own = [float(rusty.ast.define(f"{slot}_{ch}").expr.value) for ch in "rgb"]  # type: ignore[union-attr]
    orange = words().named["orange"]
    half = [round((a + b) / 2) for a, b in zip(own, orange, strict=True)]
    assert [int(x) for x in found.groups()] == half


def test_a_condition_word_after_a_place_word_is_where_not_what() -> None:
    plan = _plan("cracked-concrete-weeds", "more weeds growing out of the cracks")
    assert plan["rule"] == "amount" and "weeds" in plan["note"]
    assert "cracked" not in plan["note"]


def test_patches_of_moss_are_moss() -> None:
    plan = _plan("river-rock-stones", "add some patches of moss between the stones")
    assert "'mossy'" in plan["note"]


def test_scuffs_and_dust_add_both() -> None:
    plan = _plan("toy-brick-stud-baseplate", "add scuffs and dust, like it's been played with")
    assert "'worn'" in plan["note"] and "'dusty'" in plan["note"]


def test_a_wet_look_is_darker_and_glossier_everywhere() -> None:
    name = "river-rock-stones"
    result = edit_offline(_entry(name), "make it look wet, like after rain", size=32)
    plan = result.report.plan
    assert "roughness" in plan["rule"] and "colour" in plan["rule"] and "add" not in plan
    before = _values(_entry(name))
    for address, value in plan["assignments"].items():
        if isinstance(value, list):  # every colour darker
            assert to_lab(value)[0] < to_lab(before[address])[0] - 5  # type: ignore[arg-type]
        elif "rough" in address:
            assert value < before[address]


def test_every_condition_of_the_request_adds_its_overlay() -> None:
    plan = _plan("hotel-carpet-swirl", "it needs to look worn, faded and a bit stained")
    assert plan["rule"] == "overlay"
    assert all(f"'{name}'" in plan["note"] for name in ("worn", "faded", "stained"))


def test_an_oil_finish_is_no_colour() -> None:
    plan = _plan("burl-walnut-veneer", "tone down the gloss to a satin oil finish")
    assert plan["rule"] == "roughness" and "satin" in plan["note"]


def test_fewer_and_larger_is_a_size() -> None:
    assert _plan("hexagon-tiles", "fewer, larger hexagons")["rule"] == "scale"


def test_algae_is_a_dark_green_film() -> None:
    plan = _plan("asphalt-shingles-three-tab", "add some dark algae")
    found = re.search(r"coloured \((\d+), (\d+), (\d+)\)", plan["note"])
    assert "'algae'" in plan["note"] and found is not None  # its own overlay, not moss
    r, g, b = (int(x) for x in found.groups())
    assert max(r, g, b) < 90 and g > r and g > b  # a dark green


def test_the_material_named_with_an_article_is_the_subject_not_a_condition() -> None:
    plan = _plan("snow", "make the snow look older")
    assert "'snowy'" not in plan["note"] and "'worn'" in plan["note"]


def test_muting_the_colours_lowers_every_colour_s_chroma() -> None:
    name = "tartan-plaid-carpet"
    plan = _plan(name, "mute the colours a little")
    before = _values(_entry(name))
    assert len(plan["assignments"]) >= 3
    for address, value in plan["assignments"].items():
        old, new = to_lab(before[address]), to_lab(value)  # type: ignore[arg-type]
        assert math.hypot(new[1], new[2]) < math.hypot(old[1], old[2])


def test_a_relief_and_a_colour_in_one_clause() -> None:
    plan = _plan("cliff-rock-face", "make the joints between the blocks shallower and not so dark")
    assert plan["rule"] == "relief+colour"


def test_coarser_lines_are_bigger_lines() -> None:
    assert _plan("anodized-metal", "make the brushing lines coarser")["rule"] == "scale"


def test_scaling_the_texture_up_zooms_whatever_the_other_nouns() -> None:
    name = "snow"
    after = edit_offline(
        _entry(name), "scale the texture up so the clumps read about twice as big", size=32
    )
    assert _window(after.program) == pytest.approx(_window(_entry(name)) / 2)


def test_leaves_are_the_leaf_layer() -> None:
    plan = _plan("swamp-duckweed-water", "scatter more dead leaves across the surface")
    assert plan["rule"] == "amount" and "leaf" in plan["note"]


def test_less_bleached_is_richer() -> None:
    name = "driftwood"
    plan = _plan(name, "less bleached")
    before = _values(_entry(name))
    assert plan["rule"] == "colour" and plan["assignments"]
    for address, value in plan["assignments"].items():
        old, new = to_lab(before[address]), to_lab(value)  # type: ignore[arg-type]
        assert math.hypot(new[1], new[2]) > math.hypot(old[1], old[2])


def test_a_material_colour_word_naming_a_part_is_the_part() -> None:
    name = "whitewashed-brick-wall"
    plan = _plan(name, "the brick underneath should be a darker, more brownish red")
    assert list(plan["assignments"]) == ["colour:brick"]


def test_a_deeper_pile_is_no_colour_and_muting_joins_it() -> None:
    plan = _plan("tartan-plaid-carpet", "give it a deeper, fluffier pile and mute the colours")
    assert plan["rule"] == "relief+colour" and len(plan["assignments"]) >= 3


def test_a_colour_given_as_a_value_takes_no_tone_of_its_words() -> None:
    text = "View(0, 0, 1, 1)\nDefine(base_r, 120)\nDefine(base_g, 90)\nDefine(base_b, 60)\n"
    text += "Material(\n  Layer(1)\n    .basecolor(base_r, base_g, base_b)\n)\n"
    result = edit_offline(text, "change the base colour to a pale sage green, #D8E0CF", size=32)
    assert _values(result.program)["define:base"] == (216, 224, 207)


def test_a_condition_beside_a_colour_of_the_request_is_a_colour() -> None:
    name = "wired-safety-glass"
    plan = _plan(name, "make the wires look rusty, orange-brown")
    assert plan["rule"] == "colour" and list(plan["assignments"]) == ["define:wire"]


def test_a_keep_clause_is_no_property_of_the_condition() -> None:
    plan = _plan("cracked-concrete-weeds", "more weeds, keep the concrete grey")
    assert plan["rule"] == "amount" and "weeds" in plan["note"]


def test_covered_in_moss_is_moss() -> None:
    plan = _plan("slate-roof-tiles", "make it covered in moss")
    assert "moss" in plan["note"]


def test_a_look_naming_a_finish_is_not_read_as_a_look() -> None:
    # "less wet sheen": not "less darker overall, glossier sheen" (which would be glossier)
    with pytest.raises(EditRefused):
        edit_offline(_entry("muddy-field-puddles"), "less wet sheen", size=32)


def test_a_tint_is_bounded_whatever_the_intensity_words() -> None:
    request = "give the ice a " + "slight " * 1100 + "blue tint"
    result = edit_offline(_entry("ice-cubes-pile"), request, size=32)
    assert result.report.plan["rule"] == "colour"


@pytest.mark.parametrize(
    ("name", "request_", "named"),
    [
        ("cracked-earth", "reddish desert clay colour", "red"),
        ("graph-paper-millimetre-grid", "age the paper: yellow the cream ground", "yellow"),
    ],
)
def test_an_ish_colour_or_a_colour_verb_moves_part_of_the_way(
    name: str, request_: str, named: str
) -> None:
    from matloom.library.data import words

    plan = _plan(name, request_)
    before = _values(_entry(name))
    target = to_lab(words().named[named])
    (address, value), *_ = plan["assignments"].items()
    old, new = to_lab(before[address]), to_lab(value)  # type: ignore[arg-type]
    assert 0 < math.dist(new, old) < math.dist(target, old)  # moved, not all the way
    assert math.dist(new, target) < math.dist(old, target)


@pytest.mark.parametrize(
    ("name", "request_"),
    [
        ("speckled-laminate-countertop", "add more of the dark flecks"),
        ("rubber-gym-floor-flecks", "more of the blue flecks"),
        ("pine-needle-forest-floor", "thin out the needle cover so more of the dark soil shows"),
    ],
)
def test_a_colour_naming_a_part_by_its_look_is_no_colour_to_paint(name: str, request_: str) -> None:
    try:
        plan = _plan(name, request_)
    except EditRefused:
        return  # refused is honest; painting the named colour on is not
    assert not any(isinstance(v, list) for v in plan["assignments"].values()), plan


def test_too_before_a_condition_asks_for_less_of_it() -> None:
    with pytest.raises(EditRefused, match="no rusty in this program to reduce"):
        edit_offline(_entry("pine-needle-forest-floor"), "it's too uniformly rusty", size=32)


def test_a_colour_said_of_a_named_part_is_the_colour_to_paint() -> None:
    plan = _plan("glowing-circuit-traces", "make the board green like a regular PCB")
    assert plan["rule"] == "colour" and "define:board" in plan["assignments"]


@pytest.mark.parametrize(
    ("name", "request_"),
    [
        ("cliff-rock-face", "the holes should be deeper"),
        ("cliff-rock-face", "the cracks are too subtle, make them deeper"),
    ],
)
def test_a_deeper_relief_is_no_darker_colour_and_too_subtle_no_calm_step(
    name: str, request_: str
) -> None:
    plan = _plan(name, request_)
    assert plan["rule"] == "relief" and "x2" in plan["note"]


def test_a_look_it_should_not_have_is_not_applied() -> None:
    plan = _plan("velvet", "tone down the shine a bit, more like satin than wet-look")
    assert "colour" not in plan["rule"]


@pytest.mark.parametrize(
    ("name", "request_", "way"),
    [
        # a finish word after a flipped one keeps its sense
        ("muddy-field-puddles", "drier mud, kill most of the wet shine", "rougher"),
        # "the polish" names the surface's finish: the comparative wins
        ("carved-jade-relief", "can the polish be a bit duller, more satin than glossy", "rougher"),
        # a contracted not flips the finish
        ("carved-jade-relief", "it shouldn't be glossy", "rougher"),
        # a flipped finish that leads wins over the one it is compared with
        ("velvet", "it reads too matte for satin, give it more sheen", "glossier"),
    ],
)
def test_which_way_the_finish_goes(name: str, request_: str, way: str) -> None:
    assert _plan(name, request_)["note"].startswith(way)


def _look(note: str) -> tuple[int, ...] | None:
    found = re.search(r"coloured \((\d+), (\d+), (\d+)\)", note)
    return tuple(int(x) for x in found.groups()) if found else None


def test_a_conditions_own_colour_is_its_own_not_the_materials() -> None:
    """ "reddish-brown clay and dirt": the colour before another noun of the condition's phrase
    colours the dirt; the crystals keep theirs (the clause is not read again as a colour)."""
    before = _values(_entry("amethyst-crystal-cluster"))
    r = edit_offline(
        _entry("amethyst-crystal-cluster"),
        "Add some reddish-brown clay and dirt caked down between the crystals at the bases, "
        "as if it was just dug out of the ground",
        size=32,
    )
    assert r.report.plan["rule"] == "overlay" and "'dirty'" in r.report.plan["note"]
    look = _look(r.report.plan["note"])
    assert look is not None and look[0] > look[2] + 30  # a warm brown
    after = _values(r.program)
    assert all(after[a] == v for a, v in before.items() if a in after)


def test_a_clause_describing_the_condition_gives_its_colour() -> None:
    """ "a water stain, that yellow-brown ring": the describing clause colours the stain, not
    the paint."""
    before = _values(_entry("drywall-painted"))
    r = edit_offline(
        _entry("drywall-painted"),
        "Add a water stain, that yellow-brown ring with a darker edge you get from a leak",
        size=32,
    )
    look = _look(r.report.plan["note"])
    assert "'stained'" in r.report.plan["note"] and look is not None
    assert look[0] > look[2] + 40 and look[1] > look[2]  # yellow-brown, not the stain's own
    after = _values(r.program)
    assert all(after[a] == v for a, v in before.items() if a in after)


def test_a_colour_of_another_wish_is_not_the_conditions() -> None:
    """ "darker grey and a bit wet": the grey is not the wet's; "faded blue, a little moss":
    the moss is not blue; a grey named for the condition keeps most of its own ("black
    mould")."""
    wet = _plan("square-tiles", "Make them darker grey and a bit wet-looking")
    assert "coloured" not in wet["note"].split("'wet'")[1].split(";")[0]
    moss = _plan("azulejo-portuguese-tiles", "water stains running down, faded blue, a little moss")
    mossy = [p for p in moss["note"].split(";") if "'mossy'" in p]
    assert len(mossy) == 1 and _look(mossy[0]) is None
    black = _look(_plan("drywall-painted", "some black mould spots")["note"])
    assert black is not None and max(black) < 50


@pytest.mark.parametrize(
    ("entry", "request_", "overlay"),
    [
        ("bokhara-gul-rug", "put a big dark wine stain on it", "stained"),
        ("stylized-roof-tiles", "it just snowed, a light dusting on the tops", "snowy"),
        ("molten-lava-flow", "yellow sulphur deposits around the edges", "efflorescence"),
        ("polished-metal", "add verdigris", "rusty"),
        ("camouflage-digital-pixel", "mud splatter", "muddy"),
    ],
)
def test_a_condition_is_added_not_the_material_recoloured(
    entry: str, request_: str, overlay: str
) -> None:
    """ "put a big dark wine stain on it": a stain (its size, its colour), not a darker rug; "it
    just snowed"; deposits, verdigris (the rust overlay in the patina's green) and splatter
    (small marks) are conditions too."""
    plan = _plan(entry, request_)
    assert plan["rule"] == "overlay" and f"'{overlay}'" in plan["note"], plan["note"]
    if "dusting" in request_:
        assert "(amount 0.3)" in plan["note"]
    if "splatter" in request_:
        assert "as spots" in plan["note"]
    if "big" in request_:
        assert "(size x2)" in plan["note"]  # one big stain: large marks, not a scatter
    look = _look(plan["note"])
    if "yellow" in request_:
        assert look is not None and look[0] > look[2] + 50 and look[1] > look[2] + 50
    if "verdigris" in request_:
        assert look is not None and look[1] > look[0]  # green, not rust orange


def test_a_size_or_depth_word_still_changes_the_programs_own_features() -> None:
    """Without a verb that adds, "bigger mud plates" scales and "deeper cracks" deepens what is
    there: no condition is added."""
    assert _plan("dry-lakebed-curled-mud", "Bigger mud plates")["rule"] == "scale"
    assert _plan("charred-shou-sugi-ban", "deeper alligator cracks")["rule"] == "relief"


def test_one_stain_is_one_or_two_large_marks_and_stains_a_scatter() -> None:
    one = _plan("cardboard", "put a coffee stain on it")["note"]
    many = _plan("cardboard", "add coffee stains")["note"]
    few = _plan("cardboard", "add a few rust spots")["note"]
    assert "(size x2)" in one and "(size x0.35)" in many and "(size x0.35)" in few


def test_another_clause_keeps_the_colour_and_the_size_it_asks_for() -> None:
    """A condition's colour is its own only in its own clause ("add red rust and make the tiles
    red" recolours the tiles too); a size before a part of the program sizes the part ("add
    bigger tiles and some rust"); "a small coffee stain" stays small; "a moss stain" is one."""
    both = _plan("square-tiles", "add red rust and make the tiles red")
    assert both["rule"] == "overlay+colour"
    assert _plan("square-tiles", "add bigger tiles and some rust")["rule"] == "scale"
    assert "(size x0.35)" in _plan("cardboard", "put a small coffee stain on it")["note"]
    assert "(size x2)" in _plan("cardboard", "put a moss stain on it")["note"]


@pytest.mark.parametrize(
    ("entry", "request_", "spots"),
    [
        ("stylized-grass", "Add a few dry brown patches scattered through the grass", False),
        ("stylized-grass", "add brown spots", True),
        ("polished-metal", "put some white smears on it", False),
    ],
)
def test_marks_of_a_colour_are_added_not_the_material_recoloured(
    entry: str, request_: str, spots: bool
) -> None:
    """ "add a few dry brown patches": marks in that colour on top (the stain overlay), not the
    whole grass turned brown; spots are small marks."""
    plan = _plan(entry, request_)
    assert plan["rule"] == "overlay" and "'stained'" in plan["note"], plan["note"]
    assert ("as spots" in plan["note"]) == spots
    look = _look(plan["note"])
    assert look is not None
    if "brown" in request_:
        assert look[0] > look[1] > look[2]  # brown: red over green over blue
    else:
        assert min(look) > 150  # white


def test_marks_without_an_adding_verb_or_a_colour_are_not_added() -> None:
    # "more green patches" changes the material's own colour; "add some patches" names none
    assert _plan("stylized-grass", "more green patches")["rule"] == "colour"
    with pytest.raises(EditRefused):
        _plan("stylized-grass", "add some patches")


def test_a_compound_colour_before_a_part_names_the_part() -> None:
    """ "make the blue-grey background a warm terracotta": blue-grey says which part, the
    terracotta is its new colour (the background turned blue)."""
    plan = _plan("arabesque-scroll-stucco", "make the blue-grey background a warm terracotta")
    assert plan["rule"] == "colour"
    ((address, rgb),) = plan["assignments"].items()
    assert address == "define:ground"
    assert rgb[0] > rgb[1] + 60 and rgb[0] > rgb[2] + 100, rgb  # terracotta: red-orange


def test_a_sentence_describing_the_material_as_it_is_is_not_the_request() -> None:
    """ "The rings look like dull grey plastic. Make them shinier": glossier, not rougher."""
    plan = _plan(
        "chainmail-rings",
        "The rings look like dull grey plastic. Make them shinier and more metallic.",
    )
    assert plan["rule"].startswith("roughness") and "glossier" in plan["note"], plan["note"]
    # "too" in it makes it a request: "The bars look too dull" asks for less dull
    from matloom.author.edit.clauses import without_state

    said = "The bars look too dull. Polish them up."
    assert without_state(said) == said
    # an imperative is never a description ("make it look like polished brass")
    said = "Make it shinier. Make it look like polished brass."
    assert without_state(said) == said


def test_a_condition_that_shows_too_strongly_is_never_added() -> None:
    """ "The rusty blush patches are too strong; make them much more subtle": less of it (here
    nothing to reduce: refused), not a rust overlay added."""
    with pytest.raises(EditRefused, match="no rusty in this program to reduce"):
        _plan(
            "speckled-stoneware-oatmeal",
            "The rusty blush patches are too strong; make them much more subtle.",
        )


def test_not_too_strong_is_an_amount_not_less() -> None:
    plan = _plan("speckled-stoneware-oatmeal", "some yellowish stains, not too strong")
    assert plan["rule"] == "overlay" and "'stained'" in plan["note"], plan["note"]


def test_glow_words_move_the_emissive_channel_of_a_glowing_program() -> None:
    """Where a layer glows, "the glow is too strong, dim the diodes" lowers its emissive
    strength (a glow overlay was added on top) and "more glow" raises it past 1 (it fell to 1);
    where nothing glows, "add a faint glow" adds the glow overlay."""
    strength = "layer:2.emissive.strength"
    less = _plan("led-panel", "The glow is too strong for a standby screen, dim the diodes a lot.")
    assert less["rule"] == "channel" and less["assignments"][strength] < 2.5, less
    more = _plan("led-panel", "more glow")
    assert more["rule"] == "channel" and more["assignments"][strength] > 2.5, more
    added = _plan("polished-metal", "add a faint glow")
    assert added["rule"] == "overlay" and "'glowing'" in added["note"]


def test_crackle_and_crazing_are_cracks() -> None:
    plan = _plan("porcelain-white-glaze", "Add a fine crackle network in the glaze")
    assert plan["rule"] == "overlay" and "'cracked'" in plan["note"], plan["note"]
    assert "'cracked'" in _plan("porcelain-white-glaze", "add some crazing")["note"]


def test_less_of_an_absent_shine_condition_is_a_rougher_finish() -> None:
    """ "more matte, less oily" on skin with no oil overlay: rougher (it was refused: "no oily
    to reduce"); "less rust" where there is none is still refused."""
    plan = _plan("human-skin-pores-closeup", "more matte, less oily")
    assert plan["rule"] == "roughness" and "rougher" in plan["note"], plan["note"]
    assert _plan("human-skin-pores-closeup", "less oily")["note"].startswith("rougher")
    with pytest.raises(EditRefused, match="no rust in this program"):
        _plan("polished-metal", "less rust, shinier")


@pytest.mark.parametrize(
    ("entry", "request_", "only"),
    [
        ("runestone", "thinner rune strokes", "runes"),
        ("sgraffito-slip-terracotta", "thicker scratched lines", None),
    ],
)
def test_a_width_word_on_drawn_lines_changes_the_stroke_widths(
    entry: str, request_: str, only: str | None
) -> None:
    """ "thinner rune strokes": the strokes' widths, not the whole pattern rescaled (the runes
    shrank and moved) nor the View zoomed."""
    plan = _plan(entry, request_)
    assert plan["rule"] == "scale" and plan["note"].startswith("line widths"), plan["note"]
    assert not plan.get("view") and plan["assignments"]
    assert all(a.endswith(".width") and ".Stroke" in a for a in plan["assignments"])
    if only:
        assert all(a.startswith(f"define:{only}.") for a in plan["assignments"])
    thinner = "thinner" in request_
    before = _values(_entry(entry))
    for address, value in plan["assignments"].items():
        assert (value < before[address]) == thinner


def test_a_width_word_on_a_part_not_drawn_by_strokes_scales_as_before() -> None:
    assert not _plan("metal-grid", "thicker bars")["note"].startswith("line widths")


def test_dim_words_say_less_only_as_a_verb_or_comparative() -> None:
    strength = "layer:2.emissive.strength"
    for request_ in ("the glow is too dim, brighten it", "the diodes are dim, make them glow more"):
        plan = _plan("led-panel", request_)
        assert plan["assignments"][strength] > 2.5, (request_, plan["note"])


def test_less_of_a_shine_condition_keeps_the_other_wishes() -> None:
    plan = _plan("human-skin-pores-closeup", "less oily and redder")
    assert plan["rule"] == "roughness+colour", plan["note"]
    # where the oil is a condition with an amount, "fewer oil stains" is less of it
    oil = _plan("industrial-concrete-floor-oil-stains", "fewer oil stains")
    assert oil["rule"] == "amount", oil["note"]


def test_a_texture_asked_to_show_more_is_deeper_relief() -> None:
    """ "make the hammered texture more pronounced": the relief deeper (it was refused); "the
    weave texture is too visible" stays the contrast rule's."""
    plan = _plan("hammered-glass-dimpled", "make the hammered texture more pronounced")
    assert plan["rule"] == "relief" and "deeper" in plan["note"], plan["note"]
    flatter = _plan("hammered-glass-dimpled", "make the texture less visible")
    assert flatter["rule"] == "relief" and "flatter" in flatter["note"]


def test_an_arrow_reads_as_to_and_too_saturated_as_muted() -> None:
    """ "red centres -> mustard yellow": the red parts become mustard (the background turned
    red); "the duckweed is too saturated": a muted duckweed (it was refused)."""
    plan = _plan("diamond-print", "red centres -> mustard yellow")
    assert plan["rule"] == "colour" and "define:base" not in plan["assignments"], plan["note"]
    for rgb in plan["assignments"].values():
        assert rgb[0] > rgb[2] + 100 and rgb[1] > rgb[2] + 80  # mustard: yellow-orange
    muted = _plan("swamp-duckweed-water", "the duckweed is too saturated")
    assert muted["rule"] == "colour" and "define:duckweed" in muted["assignments"]


def test_any_adding_verb_adds_a_condition() -> None:
    """ "put moss ... on the lower stones": added ("lower" read as less refused it)."""
    plan = _plan(
        "random-rubble-wall", "put moss and green algae in the mortar and on the lower stones"
    )
    assert plan["rule"].startswith("overlay") and "'mossy'" in plan["note"], plan["note"]


def test_fallen_leaves_are_added_where_the_program_has_no_leaves() -> None:
    """ "add some scattered fallen leaves" to a lawn: the leaf litter overlay (it was refused);
    "more floating dead leaves" on a pond that has some: more of its own."""
    plan = _plan("grass", "add some scattered fallen leaves")
    assert plan["rule"] == "overlay" and "'leafy'" in plan["note"], plan["note"]
    own = _plan("swamp-duckweed-water", "more floating dead leaves")
    assert own["rule"] == "amount" and "leaf" in own["note"], own["note"]
