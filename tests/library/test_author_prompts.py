"""The library as the offline author, over real prompts (what the retired built-in recipes'
tests checked, on the library): every development prompt yields a clean, finite, canonical
program with its physical size; the result is deterministic; colour words are honoured; the
program is tileable by default wherever the entry allows it; the explanation says what happened.
"""

from __future__ import annotations

import json
import re
from pathlib import Path

import numpy as np
import pytest

import matloom
from matloom.author.stages.finite import nonfinite_texels
from matloom.library import author, library
from matloom.library.adapt import slot_colour
from matloom.library.overlay import constant

DEV = Path(__file__).resolve().parents[1] / "data" / "prompts-dev.json"
DEV_PROMPTS = [p["text"] for p in json.loads(DEV.read_text(encoding="utf-8"))["prompts"]]
SEED_RE = re.compile(r"seed=\d+")


def body(program: str) -> str:
    """The program without the library's header comments."""
    return "\n".join(line for line in program.splitlines() if not line.startswith("#"))


def mean_basecolor(program: str, size: int = 32) -> np.ndarray:
    """Mean linear base colour (r, g, b) of the evaluated program."""
    maps = matloom.evaluate(program, size, size)
    return np.asarray(maps.basecolor_linear, dtype=np.float64).reshape(-1, 3).mean(axis=0)


def luminance(rgb: tuple[int, int, int]) -> float:
    r, g, b = (c / 255 for c in rgb)
    return 0.2126 * r + 0.7152 * g + 0.0722 * b


def test_dev_prompt_file_has_71_prompts() -> None:
    assert len(DEV_PROMPTS) == 71


@pytest.mark.parametrize("prompt", DEV_PROMPTS, ids=[f"dev{i:02d}" for i in range(71)])
def test_dev_prompt_yields_a_clean_finite_program_with_its_size(prompt: str) -> None:
    r = author(prompt)
    assert matloom.check(r.program) == [], r.explanation
    text = body(r.program)
    assert matloom.format(text) == text.rstrip("\n")
    program = matloom.parse(r.program)
    assert program.view.unit_m == pytest.approx(r.unit_m) and r.unit_m > 0
    assert program.tileable == r.tileable
    assert nonfinite_texels(matloom.evaluate(r.program, 24, 24)) == 0, r.entry
    assert f"entry: {r.entry} " in r.explanation
    head = "# composed: " if r.composed else "# library entry: "
    assert r.program.startswith(f"{head}{r.entry} ")


def test_same_prompt_and_seed_give_identical_results() -> None:
    for prompt in ("weathered red brick wall with pale mortar", DEV_PROMPTS[50]):
        a, b = author(prompt, seed=7), author(prompt, seed=7)
        assert a.program == b.program
        assert a.explanation == b.explanation
        assert a.unit_m == b.unit_m


def test_different_seed_changes_only_the_seeds() -> None:
    for prompt in ("mossy cobblestone street", "brown and white checkered cotton fabric"):
        a, b = author(prompt, seed=0).program, author(prompt, seed=1).program
        assert a != b
        assert SEED_RE.sub("seed=N", a) == SEED_RE.sub("seed=N", b)


def test_explanation_shows_candidates_entry_adaptations_and_ignored_words() -> None:
    r = author("dark walnut planks, slightly worn, with flurbonic knots")
    text = r.explanation
    assert text.splitlines()[0] == "prompt: dark walnut planks, slightly worn, with flurbonic knots"
    assert "candidates:" in text and f"*1. {r.entry} " in text
    assert re.search(r"^ [ *]2\. \S+ \d+\.\d\d  \(", text, re.MULTILINE), text
    assert f"entry: {r.entry} [{r.category}] (rank 1, score {r.score:.2f})" in text
    assert "adaptations:" in text and "walnut" in text
    assert "worn" in text  # an overlay, or the entry's own wear
    assert "ignored: " in text and "flurbonic" in r.ignored


@pytest.mark.parametrize(
    ("prompt", "channel"),
    [
        ("red plastic", 0),
        ("red brick wall", 0),
        ("dark red velvet", 0),
        ("green leather", 1),
        ("blue velvet", 2),
        ("pale blue linen", 2),
        ("navy denim", 2),
    ],
)
def test_colour_words_give_that_colour(prompt: str, channel: int) -> None:
    colour = mean_basecolor(author(prompt).program)
    others = [c for k, c in enumerate(colour) if k != channel]
    # pale colours are close to grey: the named hue must still lead clearly
    assert colour[channel] > 1.15 * max(others), (prompt, colour)


def test_colour_before_an_absorbed_overlay_is_kept() -> None:
    r = author("orange painted metal")
    assert "painted" in " ".join(r.absorbed), r.explanation  # the entry shows the paint itself
    colour = mean_basecolor(r.program)
    assert colour[0] > colour[1] > colour[2], colour
    assert any("'orange'" in a for a in r.adaptations), r.explanation


def test_colour_of_an_absorbed_condition_goes_to_its_slot() -> None:
    r = author("orange rusty metal")
    assert r.entry == "rusted-metal" and not r.overlays, r.explanation
    assert any(a.startswith("colour rust_col = 'orange'") for a in r.adaptations), r.explanation
    rust = slot_colour(matloom.parse(r.program), "rust_col")
    assert rust is not None and rust[0] > rust[1] > rust[2]


def test_a_colour_no_slot_takes_is_reported_as_ignored() -> None:
    r = author("red green blue yellow purple orange pink white black grey plastic")
    left = [a for a in r.adaptations if "unused: no free colour slot" in a]
    taken = [a for a in r.adaptations if a.startswith("colour ") and a not in left]
    assert left, r.explanation
    for note in left:
        word = note.split("'")[1]
        assert word in r.ignored, r.explanation
    assert len(taken) + len(left) == 10


def test_tone_words_shade_the_named_part() -> None:
    def mortar(prompt: str) -> tuple[int, int, int]:
        rgb = slot_colour(matloom.parse(author(prompt).program), "mortar")
        assert rgb is not None
        return rgb

    plain = mortar("red brick wall")
    assert luminance(mortar("red brick wall with dark mortar")) < luminance(plain)
    assert luminance(plain) < luminance(mortar("red brick wall with pale mortar"))


def test_conditions_become_overlay_layers() -> None:
    plain, mossy = author("grey concrete wall"), author("mossy grey concrete wall")
    assert mossy.entry == plain.entry and mossy.overlays == ["mossy"]
    assert mossy.program.count("Layer(") > plain.program.count("Layer(")
    assert "# overlay: mossy" in mossy.program


def test_an_entry_that_shows_the_condition_absorbs_it() -> None:
    r = author("heavily rusted metal")
    assert r.entry == "rusted-metal" and r.overlays == []
    assert constant(matloom.parse(r.program), "wear") == pytest.approx(0.8)


def test_dev_prompts_are_tileable_wherever_the_entry_allows_it() -> None:
    lib = library()
    results = [author(p) for p in DEV_PROMPTS]
    assert all(r.tileable for r in results if r.composed)  # composed programs always tile
    results = [r for r in results if not r.composed]
    plain = [r for r in results if lib.entry(r.entry).tileable and not r.overlays]
    assert len(plain) >= 30
    assert [r.entry for r in plain if not r.tileable] == []
    for r in results:
        if lib.entry(r.entry).tileable and not r.tileable:
            assert any("tile" in n for n in r.notes), r.explanation
    untiled = author(DEV_PROMPTS[0], tileable=False)
    assert not untiled.tileable and not matloom.parse(untiled.program).tileable


def test_unknown_request_gives_the_generic_entry_and_reports_the_words() -> None:
    r = author("zorblax quintessence of flibber")
    assert r.entry == "generic-surface" and r.rank == 0
    assert matloom.check(r.program) == []
    assert {"zorblax", "quintessence", "flibber"} <= set(r.ignored)
    assert any("no entry matched" in n for n in r.notes)


@pytest.mark.parametrize("prompt", ["", "   ", "12345", "ÜBER-glänzend ☃", "a " * 400])
def test_never_fails_on_odd_input(prompt: str) -> None:
    r = author(prompt)
    assert matloom.check(r.program) == []
