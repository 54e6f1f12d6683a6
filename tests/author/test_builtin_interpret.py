"""Prompt interpretation of the built-in author: colours, palettes, conditions, scale words,
sizes, counts and finishes, with explicit expectations."""

from __future__ import annotations

import colorsys

import pytest

from matloom.author.builtin.colours import luminance
from matloom.author.builtin.interpret import interpret


def _hue_deg(rgb: tuple[int, int, int]) -> float:
    return colorsys.rgb_to_hsv(*(c / 255 for c in rgb))[0] * 360


def _colour(prompt: str, index: int = 0) -> tuple[int, int, int]:
    return interpret(prompt).colours[index].rgb


def test_dark_red_is_a_darker_red() -> None:
    dark, plain = _colour("dark red velvet"), _colour("red velvet")
    assert dark[0] > dark[1] and dark[0] > dark[2]
    assert luminance(dark) < luminance(plain)
    assert interpret("dark red velvet").colours[0].words == "dark red"


def test_pale_blue_is_a_lighter_blue() -> None:
    pale, plain = _colour("pale blue linen"), _colour("blue linen")
    assert pale[2] > pale[0] and pale[2] > pale[1]
    assert luminance(pale) > luminance(plain) + 0.2


def test_navy_is_dark_blue() -> None:
    navy = _colour("navy wool")
    assert navy[2] > navy[0] and navy[2] > navy[1]
    assert luminance(navy) < 0.2


@pytest.mark.parametrize(
    ("prompt", "words"),
    [
        ("light steel blue fabric", "light steel blue"),
        ("rose gold metallic fabric", "rose gold"),
        ("off white cotton", "off white"),
        ("a reddish brown leather", "reddish brown"),
        ("deep green glass", "deep green"),
    ],
)
def test_multi_word_colour_names(prompt: str, words: str) -> None:
    assert [c.words for c in interpret(prompt).colours] == [words]


def test_black_and_white_palette_keeps_order() -> None:
    found = interpret("black and white marble checker tile").colours
    assert [c.words for c in found] == ["black", "white"]
    assert luminance(found[0].rgb) < 0.15 < 0.85 < luminance(found[1].rgb)


def test_colour_list_with_material_like_names() -> None:
    found = interpret("It is cotton and the colors are tan, rust and brown.").colours
    assert [c.words for c in found] == ["tan", "rust", "brown"]


def test_material_nouns_are_not_colours_outside_colour_context() -> None:
    assert interpret("copper pipe").colours == []
    assert interpret("slate roof").colours == []
    assert [c.words for c in interpret("copper colored fabric").colours] == ["copper"]


def test_alternative_colours_merge_into_one() -> None:
    found = interpret("The overall color is a bright orange or candy red.").colours
    assert len(found) == 1
    hue = _hue_deg(found[0].rgb)
    assert hue < 30 or hue > 340


def test_colour_role_hints() -> None:
    found = interpret("The background color is white, with the diamonds in brown.").colours
    roles = {c.words: c.role for c in found}
    assert roles == {"white": "base", "brown": "accent"}


@pytest.mark.parametrize(
    ("prompt", "kind"),
    [
        ("rusty steel", "rusty"),
        ("mossy stone", "mossy"),
        ("cracked plaster", "cracked"),
        ("wet asphalt", "wet"),
        ("worn leather", "worn"),
        ("dirty concrete", "dirty"),
        ("stained carpet", "stained"),
        ("burnt wood", "burnt"),
        ("chipped paint", "chipped"),
        ("weathered planks", "weathered"),
        ("dusty shelf", "dusty"),
        ("scratched metal", "scratched"),
        ("snowy roof", "snowy"),
        ("muddy ground", "muddy"),
        ("faded denim", "faded"),
    ],
)
def test_condition_modifiers(prompt: str, kind: str) -> None:
    assert [c.kind for c in interpret(prompt).conditions] == [kind]


def test_condition_amounts_follow_adverbs() -> None:
    heavy = interpret("heavily rusted iron").conditions[0].amount
    light = interpret("slightly rusted iron").conditions[0].amount
    plain = interpret("rusted iron").conditions[0].amount
    assert light < plain < heavy


def test_negation_switches_a_condition_off() -> None:
    assert interpret("smooth plaster with no cracks").conditions == []


def test_coloured_stains_carry_their_colour() -> None:
    cond = interpret("white shirt with black stains").conditions
    assert [c.kind for c in cond] == ["stained"]
    assert cond[0].colour is not None and luminance(cond[0].colour) < 0.15


@pytest.mark.parametrize(
    ("prompt", "bigger"),
    [
        ("large tiles", True),
        ("huge bricks", True),
        ("big checks", True),
        ("fine weave", False),
        ("tiny dots", False),
        ("small hexagon tiles", False),
    ],
)
def test_scale_words(prompt: str, bigger: bool) -> None:
    scale = interpret(prompt).scale
    assert (scale > 1.0) if bigger else (scale < 1.0)


def test_scale_words_are_ordered() -> None:
    assert interpret("tiny dots").scale < interpret("small dots").scale < 1.0
    assert 1.0 < interpret("large dots").scale < interpret("huge dots").scale


def test_explicit_sizes() -> None:
    sizes = interpret("white ceramic 10 cm tiles").sizes
    assert len(sizes) == 1
    assert sizes[0].metres == pytest.approx(0.10)
    assert sizes[0].noun == "tile"
    half_inch = interpret('The knitting pattern creates 1/2" rows running horizontally').sizes
    assert half_inch[0].metres == pytest.approx(0.0127)


def test_counts_and_percentages() -> None:
    counts = interpret("The weaving used 3 yarns to the pattern").counts
    assert [(c.value, c.noun) for c in counts] == [(3, "yarn")]
    assert interpret("eight planks of oak").counts[0].value == 8
    assert interpret("stone wall, 30% covered in moss").percents == [pytest.approx(0.3)]


def test_patterns_and_finishes() -> None:
    it = interpret("glossy black and white checkered floor with a zig-zag border")
    assert "checker" in it.patterns and "zigzag" in it.patterns
    assert it.finishes == ["glossy"]
    assert "perforated" in interpret("foam with polka dot holes").patterns


def test_long_descriptions_are_read_token_by_token() -> None:
    it = interpret(
        "This looks like a midweight fabric, possibly polyester that has a blotchy muddled "
        "pattern of grays and variations of brown. There are many heavily worn and distressed "
        "areas that create gashes randomly across the fabric."
    )
    assert {c.kind for c in it.conditions} >= {"worn", "holes"}
    assert "brown" in [c.words for c in it.colours]


def test_tone_words_before_nouns_are_kept() -> None:
    assert ("pale", "mortar") in interpret("red brick wall with pale mortar").tones
    assert ("dark", "wood") in interpret("dark wood planks").tones


def test_scale_word_before_condition_adjective_scales_the_material() -> None:
    it = interpret("large weathered bricks")
    assert it.scale > 1.0
    assert it.conditions[0].scale == 1.0
    stains = interpret("huge rust stains on cotton")
    assert stains.scale == 1.0
    assert stains.conditions[0].scale > 1.0
