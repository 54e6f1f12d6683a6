"""Retrieval: BM25 over descriptions, tags and synonyms, with overlays for compositional
requests and a report of the words nothing used."""

from __future__ import annotations

import math
import warnings

import pytest

from matloom.library import author, search


def test_cracked_desert_mud_finds_cracked_earth_and_understands_desert() -> None:
    r = author("cracked desert mud")
    assert r.entry == "cracked-earth"
    assert "desert" not in r.ignored
    assert r.ignored == []
    assert not r.overlays  # the entry shows cracks itself
    assert any(a.startswith("cracked") for a in r.absorbed)


def test_cracked_dry_earth_finds_cracked_earth() -> None:
    assert author("cracked dry earth").entry == "cracked-earth"


def test_mossy_cobblestone_is_cobblestone_with_the_moss_overlay() -> None:
    r = author("mossy cobblestone")
    assert r.entry == "cobblestone"
    assert r.overlays == ["mossy"]
    assert "mossBlob" in r.program


def test_rusty_corrugated_metal_is_corrugated_metal_with_rust() -> None:
    r = author("rusty corrugated metal")
    assert r.entry == "corrugated-metal"
    assert r.overlays == ["rusty"]


def test_rusty_metal_alone_is_the_rusted_entry_without_an_overlay() -> None:
    r = author("rusty metal")
    assert r.entry == "rusted-metal"
    assert not r.overlays


@pytest.mark.parametrize(
    ("prompt", "entry"),
    [
        ("walnut floorboards", "wood-planks"),
        ("herringbone parquet", "wood-herringbone"),
        ("red brick wall", "brick-wall"),
        ("subway tiles", "subway-tiles"),
        ("tartan", "tartan"),
        ("brushed aluminium", "brushed-metal"),
        ("denim jeans fabric", "denim"),
        ("dirty concrete", "concrete"),
        ("fabric", "plain-weave"),
    ],
)
def test_everyday_requests(prompt: str, entry: str) -> None:
    assert author(prompt).entry == entry


def test_overlay_words_in_several_forms() -> None:
    for prompt, overlay in [
        ("wet cobblestone street", "wet"),
        ("snow covered rocks", "snowy"),
        ("worn leather", "worn"),
        ("dusty wooden planks", "dusty"),
        ("painted brick wall", None),  # brick-wall has a "painted brick" preset
    ]:
        r = author(prompt)
        names = r.overlays
        assert (overlay in names) if overlay else not names, (prompt, r.overlays)


def test_negated_words_are_not_retrieved() -> None:
    assert author("not wood, stone wall").entry != "wood-planks"


def test_ignored_words_are_reported() -> None:
    r = author("cobblestone with zorblax")
    assert r.entry == "cobblestone"
    assert r.ignored == ["zorblax"]
    assert "ignored: zorblax" in r.explanation


def test_search_is_ranked_and_scored() -> None:
    cands = search("cobblestone street")
    assert cands[0].name == "cobblestone"
    assert all(a.score >= b.score for a, b in zip(cands, cands[1:]))
    assert "cobbleston" in cands[0].matched


def test_nothing_matches_uses_the_fallback() -> None:
    r = author("zorblax quixotic")
    assert r.entry == "generic-surface"
    assert r.rank == 0
    assert set(r.ignored) == {"zorblax", "quixotic"}


def test_finish_and_colour_words_alone_pick_no_entry() -> None:
    r = author("glossy teal flurbonic gizmo")
    assert r.entry == "generic-surface" and r.rank == 0, r.explanation
    assert r.candidates == []
    assert {"flurbonic", "gizmo"} <= set(r.ignored)
    assert "glossy" not in r.ignored and "teal" not in r.ignored  # applied to the fallback
    assert any("glossy" in a for a in r.adaptations) and any("teal" in a for a in r.adaptations)
    assert search("glossy teal") == []


def test_a_material_word_still_counts_beside_finish_words() -> None:
    assert author("glossy teal tiles").entry != "generic-surface"
    assert author("shiny brushed aluminum").entry == "brushed-metal"


def test_rusted_steel_plate_is_plain_steel_with_rust_not_a_patterned_plate() -> None:
    r = author("heavily rusted steel plate")
    assert r.entry != "diamond-plate", r.explanation
    # rust as an overlay, or shown by the entry itself (rusted-metal, corten ...)
    shows_rust = "rusty" in r.overlays or any(a.startswith("rusty") for a in r.absorbed)
    assert shows_rust and r.category == "metal", r.explanation
    # the pattern is still found when it is asked for
    assert author("rusty diamond plate").entry == "diamond-plate"
    assert "plate" in author("steel tread plate").entry


def test_an_overlay_word_that_is_the_only_material_names_the_material() -> None:
    # "snow" and "moss" are overlay words ("snow covered rocks"), but alone they are the material
    assert author("fresh powder snow").entry == "snow"
    assert author("green moss").entry == "moss"
    r = author("snow covered rocks")
    assert "snowy" in r.overlays


def test_an_entry_named_for_a_motif_needs_the_motif_asked_for() -> None:
    # plain black tiles are not a black-and-white checkerboard
    assert author("black shiny ceramic floor tiles").entry != "checker-tiles"
    assert author("black and white checkered ceramic floor tiles").entry == "checker-tiles"


def test_a_named_material_beats_an_entry_that_only_matches_the_category() -> None:
    # "tiles" is a category word, "slate" a material: a travertine tile entry is not slate
    assert author("grey slate floor tiles in random sizes with dark grout").entry == "slate"


@pytest.mark.parametrize(
    ("prompt", "word"),
    [
        ("red brick wall", "brick"),
        ("huge bricks", "bricks"),
        ("rusty corrugated metal", "rusty"),
        ("rusty corrugated metal", "metal"),
        ("mossy cobblestone", "mossy"),
        ("tiny tiles", "tiny"),
        ("huge bricks", "huge"),
        ("small cracks on concrete", "small"),
    ],
)
def test_a_repeated_word_counts_as_one_mention(prompt: str, word: str) -> None:
    # a word said 1,500 times asks for no more than a word said once: the scores stay finite
    # (no numpy overflow warning) and the pick is the one-mention pick
    once = author(prompt)
    repeated = prompt.replace(word, " ".join([word] * 1500), 1)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        many = author(repeated)
    assert many.entry == once.entry
    assert [c.name for c in many.candidates[:3]] == [c.name for c in once.candidates[:3]]
    assert all(math.isfinite(c.score) for c in many.candidates)
    # scale words too: the size they ask for is the one-mention size, not 0.45**1500
    assert many.unit_m == once.unit_m and many.overlay_notes == once.overlay_notes


@pytest.mark.parametrize(
    ("prompt", "styled"),
    [
        ("stylized wood planks, chunky grain", True),
        ("hand painted wooden planks for a fantasy tavern", True),
        ("cartoon grass ground", True),
        ("blue painted wooden door, paint cracking", False),
        ("wood planks", False),
        ("green grass", False),
    ],
)
def test_an_art_style_entry_is_taken_only_when_a_style_is_asked_for(prompt, styled) -> None:  # noqa: ANN001
    # entries tagged with a [styles] word ("stylized") rank far lower unless the request names
    # a style; "painted" alone is no style
    r = author(prompt)
    assert r.entry.startswith("stylized-") == styled, (prompt, r.entry)
