"""Rules for long, descriptive and motif requests: colours in sentence form, the requested
palette, motif and material words, "term: definition" requests, overlay sizes."""

from __future__ import annotations

from pathlib import Path

import matloom
from matloom.library import author, library
from matloom.library import colour as C
from matloom.library.adapt import adapt, slot_colour
from matloom.library.data import words
from matloom.library.index import load_library
from matloom.library.overlay import OVERLAY_DIR
from matloom.library.query import read


def req(prompt: str):  # noqa: ANN201
    lib = library()
    return read(prompt, words(), lib.triggers, lib.weak_triggers)


def colours(prompt: str) -> list[str]:
    return [m.words for m in req(prompt).colours]


# ---------------------------------------------------------------- colours in sentence form
def test_metal_colour_after_a_colour_noun_and_a_copula_is_a_colour() -> None:
    assert colours("The color of it is silver") == ["silver"]
    assert colours("a shade of gold") == ["gold"]
    assert colours("colour: copper") == ["copper"]
    r = author("The colour of this fabric is silver")
    assert "silver" not in r.ignored
    assert any("'silver'" in a for a in r.adaptations), r.explanation


def test_an_ish_colour_before_a_plural_colour_is_one_colour() -> None:
    # "reddish browns" raised a KeyError in the reader (the plural looked up as a colour name)
    assert colours("wood in reddish browns") == ["reddish browns"]
    assert colours("greyish greens and bluish whites") == ["greyish greens", "bluish whites"]
    (r,) = req("reddish browns").colours
    assert r.rgb == req("reddish brown").colours[0].rgb


def test_colour_names_after_in_are_colours_but_not_material_nouns() -> None:
    assert colours("herringbone tweed in charcoal and cream") == ["charcoal", "cream"]
    assert colours("fish scales in copper") == ["copper"]
    assert colours("carved in slate") == []  # a material, not a colour


def test_a_metal_colour_before_another_material_colours_it() -> None:
    assert colours("gold velvet") == ["gold"]
    assert colours("copper leather") == ["copper"]
    assert colours("steel wool") == []
    r = author("gold velvet")
    assert r.category == "fabric" and "gold" not in r.ignored, r.explanation


def test_comparative_tones_make_a_second_shade() -> None:
    r = req("Its colors are a light brown with a mix of slightly darker brown")
    assert [m.words for m in r.colours] == ["light brown", "slightly darker brown"]
    light, darker = (C.luminance(m.rgb) for m in r.colours)
    brown = C.luminance(words().named["brown"])
    assert light > brown > darker
    # "slightly" halves the tone: darker than brown, lighter than plain "darker brown"
    assert darker > C.luminance(req("darker brown").colours[0].rgb)


def test_a_specific_colour_before_its_basic_family_is_one_colour() -> None:
    assert colours("cornflower blue cotton") == ["cornflower blue"]
    assert colours("burgundy red and ivory white") == ["burgundy red", "ivory white"]
    assert colours("gold black and white stripes") == ["gold", "black", "white"]


# ---------------------------------------------------------------- the requested palette
STRIPES = """# ---
# description = "Striped cloth: a red ground with navy bands and thin yellow lines"
# category = "fabric"
# tags = ["zorbstripe", "fabric"]
# size_m = 0.2
# tileable = true
# colours = ["base", "band", "line", "edge"]
# [roles]
# band = "accent"
# line = "accent"
# edge = "grout"
# ---
View(0, 0, 2, 2, tileable=True)
Define(base_r, 170)
Define(base_g, 30)
Define(base_b, 40)
Define(band_r, 20)
Define(band_g, 40)
Define(band_b, 70)
Define(line_r, 220)
Define(line_g, 200)
Define(line_b, 80)
Define(edge_r, 200)
Define(edge_g, 120)
Define(edge_b, 40)
Define(bands, fBm(octaves=2, base_freq=3, to_01=True, seed=11))
Define(lines, fBm(octaves=2, base_freq=9, to_01=True, seed=12))
Material(
  Layer(1).basecolor(base_r, base_g, base_b).roughness(0.8),
  Layer(bands).basecolor(band_r, band_g, band_b).roughness(0.8),
  Layer(lines).basecolor(line_r, line_g, line_b).roughness(0.8),
  Layer((lines * 0.5)).basecolor(edge_r, edge_g, edge_b).roughness(0.8)
)
"""


def stripes_library(tmp_path: Path):  # noqa: ANN201
    folder = tmp_path / "entries" / "fabric"
    folder.mkdir(parents=True)
    (folder / "zorb-stripes.mat").write_text(STRIPES)
    return load_library(tmp_path / "entries", OVERLAY_DIR)


def test_slots_the_request_did_not_colour_follow_its_palette(tmp_path: Path) -> None:
    lib = stripes_library(tmp_path)
    r = author("red and black zorbstripe", lib=lib)
    p = matloom.parse(r.program)
    red = words().named["red"]
    assert slot_colour(p, "base") == red and slot_colour(p, "band") == words().named["black"]
    line = slot_colour(p, "line")
    assert line is not None and C.hue_distance(line, red) <= 30, line  # no yellow line left
    assert C.luminance(line) > C.luminance(red)  # a lighter shade: the pattern keeps contrast
    assert slot_colour(p, "edge") == (200, 120, 40)  # a grout role keeps its colour
    bw = matloom.parse(author("black and white zorbstripe", lib=lib).program)
    assert C.saturation(slot_colour(bw, "line")) < 0.18  # a grey between black and white
    # one colour on a patterned entry: the other strong hues follow it too
    one = matloom.parse(author("navy zorbstripe", lib=lib).program)
    navy = words().named["navy"]
    for slot in ("band", "line"):
        assert C.hue_distance(slot_colour(one, slot), navy) <= 30


def test_an_extra_colour_goes_to_a_free_grout_slot() -> None:
    lib = library()
    entry = lib.entry("square-tiles")
    out = adapt(entry, lib.ast("square-tiles"), req("khaki and taupe tiles"), words(), {}, [])
    assert slot_colour(out.program, "grout") == words().named["taupe"]
    assert out.unused == ()


# ---------------------------------------------------------------- motif and material words
def test_a_named_motif_wins_over_incidental_words() -> None:
    idx = library().index
    r = author("black rubber floor mat with raised circles")
    assert "circle" in idx.motifs[r.entry], r.explanation
    assert "rubber" in idx.terms[r.entry]
    assert "circles" not in r.ignored
    r = author("This is a shiny fabric. The rose gold color has a honey comb pattern on top.")
    assert "hexagon" in idx.motifs[r.entry] and r.category == "fabric", r.explanation


def test_motif_words_taken_by_an_overlay_are_no_motif() -> None:
    idx = library().index
    assert idx.motif_words(req("concrete wall with cracks")) == set()
    assert idx.motif_words(req("hexagonal tiles")) == {"hexagon"}
    assert idx.motif_words(req("zig zag rug")) == {"chevron"}


def test_the_material_noun_outweighs_context_words() -> None:
    r = author("mossy cobblestone path after rain")
    assert "cobbleston" in library().index.terms[r.entry], r.explanation
    assert r.overlays == ["mossy", "wet"]
    assert author("studded black leather").category == "leather"


def test_category_cues_steer_long_descriptions() -> None:
    r = author("A summer dress in navy with small white polka dots, light and airy.")
    assert r.category == "fabric", r.explanation
    assert author("winter blanket in burgundy").category == "fabric"


def test_the_term_of_a_definition_weighs_most() -> None:
    r = req("Tweed: a rough woollen fabric, typically with a flecked look, in brown and green.")
    idx = library().index
    assert r.term_end == 1 and idx.rule(r, 0) == "term"
    assert idx.rule(r, 5) == "plain"
    long = req("This is a fabric. It is red.")
    assert idx.rule(long, 6) == "later"
    assert "tweed" in author(r.prompt).entry


# ---------------------------------------------------------------- sizes
def test_size_words_before_an_overlay_size_the_overlay_not_the_view() -> None:
    plain = author("concrete wall with cracks")
    small = author("concrete wall with small cracks")
    assert small.entry == plain.entry and small.overlays == ["cracked"]
    assert "size x" in small.overlay_notes[0] and "size x" not in plain.overlay_notes[0]
    assert not any(a.startswith("View") for a in small.adaptations)
    assert small.ignored == []
    assert req("hairline cracks").overlays[0].scale < req("small cracks").overlays[0].scale < 1
    # on an entry that shows the cracks itself, the entry's features get smaller
    earth = author("hairline cracks in dry earth")
    assert earth.entry == "cracked-earth" and any("View" in a for a in earth.adaptations)


def test_a_measured_row_sets_the_scale_and_is_not_ignored() -> None:
    r = author("wood floor with 1/2 inch rows")
    assert any("1/2 inch" in a for a in r.adaptations)
    assert "rows" not in r.ignored


def test_after_rain_adds_wet() -> None:
    assert "wet" in author("slate roof after rain").overlays


# ---------------------------------------------------------------- a colour names its part
def _given(prompt: str) -> dict[str, str]:
    """Slot -> the colour words the author gave it."""
    out = {}
    for a in author(prompt).adaptations:
        if a.startswith("colour ") and " = '" in a:
            slot, rest = a[len("colour ") :].split(" = '", 1)
            out[slot] = rest.split("'", 1)[0]
    return out


def test_a_colour_before_a_noun_naming_an_entry_slot_goes_to_that_slot() -> None:
    # the noun after the colour is one of the entry's colour slots: bole, line, crust, mortar
    assert _given("gold leaf gilding with red bole showing in the gaps") == {"bole": "red"}
    assert _given("tartan wool in green and navy with thin red lines")["line"] == "red"
    lava = _given("glowing orange lava with black crust")
    assert lava["crust_col"] == "black" and lava["glow"] == "orange"
    # a second colour before the same noun keeps its own role ("black and gray lines")
    spalted = _given("spalted wood with black and gray line patterns")
    assert spalted["line"] == "black" and spalted["decay_col"] == "gray"


def test_the_colour_of_a_patterned_entrys_motifs_is_its_pattern_colour() -> None:
    given = _given("azulejo tiles painted with blue floral motifs on a white ground")
    assert given["glaze"] == "white" and given["cobalt"] == "blue"


def test_olive_drab_and_whitewashed_are_colours() -> None:
    assert colours("tent canvas, olive drab") == ["olive drab"]
    assert _given("old whitewashed boards with peeling paint") == {"paint": "whitewashed"}


def test_a_metre_sized_tile_is_the_texture_repeat() -> None:
    # a game artist's "4x4m tile" is the repeat of the texture, no ceramic tile
    program = author("realistic forest floor, pine needles + cones + dirt, 4x4m tile").program
    assert "forest-floor" in program.splitlines()[0]
    r = req("forest floor, 4 m tile")
    assert r.sizes and r.sizes[0].metres == 4
    # tiles a few centimetres or a foot across are tiles
    assert "tile" in author("white 30 cm ceramic floor tiles").program.splitlines()[0]


# ---------------------------------------------------------------- compound colours
def test_two_basic_colours_side_by_side_are_one_colour_leaning_to_the_first() -> None:
    # "stone bricks, blue grey" gave blue bricks with grey mortar: judges saw saturated blue
    for prompt in ("blue grey stone bricks", "blue-grey stone bricks"):
        (m,) = req(prompt).colours
        assert m.words == "blue grey"
        grey, blue = words().named["grey"], words().named["blue"]
        assert C.saturation(m.rgb) < C.saturation(blue) * 0.6
        assert m.rgb[2] > m.rgb[0] and m.rgb != grey  # a grey leaning to blue
    assert colours("yellow green grass") == ["yellow green"]
    assert colours("red brown leather") == ["red brown"]
    assert colours("dark blue grey paint") == ["dark blue grey"]


def test_lists_and_contrasting_colours_stay_apart() -> None:
    assert colours("black white checker") == ["black", "white"]
    assert colours("red and blue stripes") == ["red", "blue"]
    assert colours("orange blue camo") == ["orange", "blue"]  # hues far apart
    assert colours("red green and blue") == ["red", "green", "blue"]
    assert colours("red green blue yellow plastic") == ["red", "green", "blue", "yellow"]


def test_a_tone_before_a_finish_coat_shades_the_material() -> None:
    r = author("oak floor, dark varnish")
    assert any("made dark ('dark varnish')" in a for a in r.adaptations), r.explanation
    assert "varnish" not in r.ignored


# ---------------------------------------------------------------- comma lists
def test_a_comma_lists_first_item_names_the_material() -> None:
    # a game artist's list: the first item is the material, the others describe it
    r = req("aged parchment, yellowed with stains and foxing, tileable")
    assert r.listed
    assert not req("aged parchment with stains").listed
    assert not req("red, white and blue flag").listed  # the first comma ends no material
    got = author("aged parchment, yellowed with stains and foxing, tileable")
    assert got.entry == "parchment", got.explanation  # not the handwritten letter


def test_a_colour_word_naming_a_slot_of_the_entry_goes_to_that_slot() -> None:
    # the colour before a condition the entry already shows goes to the entry's slot named
    # after the colour itself when none is named after the condition ("oil" stains)
    from matloom.library.passes.fit import _entry_colour
    from matloom.library.query import ColourMention, OverlayMention

    entry = library().entries["industrial-concrete-floor-oil-stains"]
    got = _entry_colour(
        ColourMention((34, 31, 28), "oil", 5), OverlayMention("stained", "stains", 6), entry
    )
    assert got.slot == "oil"


def test_a_conditions_own_phrase_is_no_colour() -> None:
    # "oil" before "spill" was read as a colour once "spill" became a stain word, and the
    # oil-spill phrase was lost: an oily overlay, not an oil-coloured stain
    r = author("concrete floor with an oil spill")
    assert [o for o in r.overlays] == ["oily"], r.explanation
    r = author("parking garage concrete floor with oil stains")
    assert r.entry == "industrial-concrete-floor-oil-stains", r.explanation
    assert not any(a.startswith("colour concrete") for a in r.adaptations), r.explanation


def test_a_colour_inside_a_two_word_condition_colours_it() -> None:
    # "painted white line": the painted-line overlay in white, not a white floor
    got = [(o.name, o.colour) for o in req("parking garage floor, painted yellow line").overlays]
    assert got == [("lined", words().named["yellow"])]
    assert colours("painted yellow line") == ["yellow"]
    assert [o.name for o in req("white painted metal").overlays] == ["painted"]


def test_hand_painted_is_a_style_not_a_coat_of_paint() -> None:
    lib = library()
    said = read("crystal cave floor, hand painted, 2x2m", words(), lib.triggers, lib.weak_triggers)
    assert "painted" not in [m.name for m in said.overlays]
    coat = read("painted brick wall", words(), lib.triggers, lib.weak_triggers)
    assert "painted" in [m.name for m in coat.overlays]


def test_a_colour_list_is_only_colours_side_by_side() -> None:
    """ "black marble, white veins": the white is the veins', the black the marble's (the
    black took the veins' role across the comma and the marble came out white)."""
    got = {m.words: m.role for m in req("nero marquina black marble, white veins").colours}
    assert got["black"] is None and got["white"] == "accent"
    listed = {m.words: m.role for m in req("black and gray line patterns").colours}
    assert listed["black"] == listed["gray"] == "accent"
