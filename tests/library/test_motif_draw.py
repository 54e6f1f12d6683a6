"""A requested motif drawn onto a retrieved entry that shows the request's material but not the
motif (issue 27, item 3): the entry is kept, the motif goes on top as a print (or a relief), the
program stays checker-clean and tileable, and only the colour changes under the motif."""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest

import matloom
from matloom.lang.tileable import tileable_warnings
from matloom.library import author, library
from matloom.library.passes.cover import patterned


def _without_drawn(program: matloom.Program, layers: int) -> matloom.Program:
    return replace(program, layers=program.layers[:layers])


def _entry_layers(r) -> int:  # noqa: ANN001
    return len(library().ast(r.entry).layers) + len(r.overlays)


@pytest.mark.parametrize(
    ("prompt", "entry", "motif", "rgb"),
    [
        ("navy silk satin with small white stars", "satin-silk", "star", (236, 236, 232)),
        ("linen fabric printed with red hearts", "linen-natural-slub", "heart", (186, 32, 36)),
        ("black leather with small gold stars", "leather", "star", None),
    ],
)
def test_a_plain_entry_keeps_its_place_and_gets_the_motif(prompt, entry, motif, rgb) -> None:  # noqa: ANN001
    r = author(prompt)
    assert not r.composed and r.entry == entry, r.explanation
    assert any(n.startswith(f"motif {motif}:") for n in r.notes), r.explanation
    assert not any(motif in d for d in r.dropped) and "not shown" not in r.explanation
    assert matloom.check(r.program) == [], r.explanation
    program = matloom.parse(r.program)
    assert r.tileable and program.tileable and tileable_warnings(program) == []
    top = program.layers[-1]
    assert top.alpha is not None and "Tile(" in r.program
    if rgb is not None:
        values = [program.define(f"motif_{c}").expr.value for c in "rgb"]
        assert tuple(values) == rgb


def test_the_colour_of_the_motif_is_not_the_entrys() -> None:
    # "red hearts" on linen: the linen keeps its own colour, the hearts are red
    r = author("linen fabric printed with red hearts")
    assert not any("yarn" in a for a in r.adaptations), r.adaptations
    plain = author("linen fabric")
    assert matloom.parse(plain.program).define("yarn_r") == matloom.parse(r.program).define(
        "yarn_r"
    )


def test_only_the_colour_changes_under_a_printed_motif() -> None:
    r = author("navy silk satin with small white stars")
    program = matloom.parse(r.program)
    base = _without_drawn(program, _entry_layers(r))
    assert len(base.layers) == len(program.layers) - 1
    drawn, plain = matloom.evaluate(program, 96, 96), matloom.evaluate(base, 96, 96)
    assert np.array_equal(drawn.roughness, plain.roughness)
    assert np.array_equal(drawn.height, plain.height)
    changed = np.abs(drawn.basecolor_linear - plain.basecolor_linear).max(axis=-1) > 0.05
    assert 0.03 < changed.mean() < 0.5  # the stars, not the whole cloth


def test_an_embossed_motif_is_a_relief_in_the_entrys_colour() -> None:
    r = author("grey concrete with embossed triangles")
    assert not r.composed and r.entry == "concrete", r.explanation
    program = matloom.parse(r.program)
    assert program.define("motif_r") is None  # no print colour
    assert len(program.layers) == _entry_layers(r)  # no layer of its own
    plain = author("embossed grey concrete")  # the same adaptations, no motif
    assert plain.adaptations == r.adaptations
    base, drawn = matloom.evaluate(plain.program, 96, 96), matloom.evaluate(program, 96, 96)
    assert np.array_equal(drawn.basecolor_linear, base.basecolor_linear)
    assert np.array_equal(drawn.roughness, base.roughness)
    assert not (drawn.height < base.height).any()
    assert 0.03 < (drawn.height > base.height).mean() < 0.5  # the triangles


def test_a_motif_said_in_another_sentence_is_drawn_when_the_surface_shows_it() -> None:
    r = author("A navy silk satin. There are small white stars printed all over it.")
    assert r.entry == "satin-silk" and any(n.startswith("motif star:") for n in r.notes)


def test_one_motif_is_drawn_and_the_next_is_reported() -> None:
    r = author("blue linen with white stars and hearts")
    assert sum(n.startswith("motif ") for n in r.notes) == 1
    assert any("heart" in d for d in r.dropped) and "ignored: nothing" not in r.explanation


def test_a_patterned_entry_gives_way_to_a_composed_program() -> None:
    # argyle diamonds and drawn stars would be two patterns: composed instead
    assert patterned(library().entry("argyle-knit-sweater"))
    assert not patterned(library().entry("satin-silk"))
    r = author("blue knitted wool with white stars")
    assert r.composed, r.explanation


def test_drawing_is_deterministic_and_follows_the_seed() -> None:
    a = author("navy silk satin with small white stars", seed=4)
    b = author("navy silk satin with small white stars", seed=4)
    c = author("navy silk satin with small white stars", seed=5)
    assert a.program == b.program and a.program != c.program


def test_worn_spots_are_wear_not_a_motif() -> None:
    # "there are some faded spots where ..." described wear; drawing dots on canvas was wrong
    r = author("A heavy olive canvas. There are some faded spots where the colour wore off.")
    assert not any(n.startswith("motif ") for n in r.notes), r.explanation


def test_a_missing_layout_draws_no_motif_and_faux_is_the_look_of_the_material() -> None:
    # "faux leather with a quilted diamond pattern": the quilted leather entry covers faux
    # leather; no diamonds are drawn onto plain leather
    r = author("black faux leather with a quilted diamond pattern, puffy")
    assert r.entry == "quilted-diamond-leather", r.explanation
    assert not any(n.startswith("motif ") for n in r.notes)
