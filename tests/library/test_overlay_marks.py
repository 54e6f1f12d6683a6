"""Fallen leaves, painted lines and soot (the leafy, lined and sooty overlays): their words
request them, a colour before the word sets the leaves' or the paint's colour, the composed
programs tile, each leaf takes one of several colours, the line is one band running the full
height of the texture, and soot is a soft film (no hard rim) rising in vertical runs."""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest

import matloom
from matloom.engine.evaluate import evaluate
from matloom.lang import ast as A
from matloom.lang.api import parse
from matloom.lang.tileable import tileable_warnings
from matloom.library import load_library
from matloom.library.author import author
from matloom.library.checks import period_problems
from matloom.library.data import words
from matloom.library.overlay import compose
from matloom.library.query import read

LIB = load_library()
MARKS = ("leafy", "lined", "sooty")
FLAT = """View(0, 0, 2, 2, tileable=True)
Material(Layer(1).basecolor(200, 200, 200).roughness(0.5))
"""


def _read(prompt: str):  # noqa: ANN202 - the request
    return read(prompt, words(), LIB.triggers, LIB.weak_triggers)


def _overlays(prompt: str) -> list[str]:
    return [o.name for o in _read(prompt).overlays]


@pytest.mark.parametrize(
    ("prompt", "name"),
    [
        ("cobblestone path with fallen autumn leaves", "leafy"),
        ("asphalt road covered in leaves", "leafy"),
        ("cobblestone path with autumn leaves", "leafy"),
        ("concrete pavers with dead leaves", "leafy"),
        ("brick paving with scattered leaves", "leafy"),
        ("stone patio with leaf litter", "leafy"),
        ("clay roof tiles with fallen leaves", "leafy"),
        ("asphalt road with yellow painted line", "lined"),
        ("concrete floor with white painted lines", "lined"),
        ("concrete with yellow parking lines", "lined"),
        ("polished concrete with a lane line", "lined"),
        ("concrete floor with line markings", "lined"),
        ("epoxy floor with a yellow safety line", "lined"),
        ("brick wall, soot stained", "sooty"),
        ("soot-stained concrete", "sooty"),
        ("stone fireplace wall with soot", "sooty"),
        ("plaster with smoke damage", "sooty"),
        ("smoke damaged plaster", "sooty"),
        ("blackened brick wall", "sooty"),
        ("heavily soot covered bricks", "sooty"),
    ],
)
def test_words_request_the_overlay(prompt: str, name: str) -> None:
    assert name in _overlays(prompt)


@pytest.mark.parametrize("name", MARKS)
def test_every_trigger_reaches_its_overlay(name: str) -> None:
    for trigger in LIB.overlays[name].triggers:
        assert name in _overlays(f"concrete floor, {trigger}"), trigger


@pytest.mark.parametrize(
    "prompt",
    ["silk with gold leaves", "white ceramic tile with blue leaves", "autumn leaves on wet ground"],
)
def test_leaves_as_a_motif_or_the_material_are_no_fallen_leaves(prompt: str) -> None:
    assert "leafy" not in _overlays(prompt)


def test_burnt_keeps_its_words() -> None:
    for word in ("burnt", "burned", "charred", "scorched"):
        assert _overlays(f"wood planks, {word}") == ["burnt"], word


def test_a_colour_before_the_word_sets_the_paint_and_the_leaves() -> None:
    yellow = words().colour("yellow")
    (line,) = _read("asphalt road with yellow painted line").overlays
    assert line.name == "lined" and line.colour == yellow
    (white,) = _read("concrete floor, white parking lines").overlays
    assert white.name == "lined" and white.colour == words().colour("white")
    (leaves,) = _read("cobblestones with yellow fallen leaves").overlays
    assert leaves.name == "leafy" and leaves.colour == yellow
    # the slot takes it: the composed paint is the colour asked for
    program = compose(parse(FLAT), LIB.overlays["lined"], main_colour=None, colour=line.colour)
    assert tuple(program.define(f"paint_{ch}").expr.value for ch in "rgb") == yellow  # type: ignore[union-attr]


def test_the_author_paints_a_yellow_line_on_a_plain_floor() -> None:
    r = author("concrete floor with yellow painted line")
    assert "lined" in r.overlays
    program = matloom.parse(r.program)
    paint = tuple(program.define(f"paint_{ch}").expr.value for ch in "rgb")  # type: ignore[union-attr]
    assert paint == words().colour("yellow")


def test_an_entry_that_shows_the_line_does_not_get_a_second_one() -> None:
    r = author("asphalt road lane line")
    assert r.entry == "asphalt-road-lane-line"
    assert "lined" not in r.overlays


@pytest.mark.parametrize("host_name", ["cobblestone", "brick-wall", "asphalt"])
@pytest.mark.parametrize("name", MARKS)
def test_composed_program_is_clean_and_tiles(name: str, host_name: str) -> None:
    program = compose(LIB.ast(host_name), LIB.overlays[name], main_colour=None, cover=0.6)
    assert program.tileable and tileable_warnings(program) == []
    assert matloom.check(matloom.format(program)) == []
    assert period_problems(program, 32) == []


def _alpha(program: A.Program, k: int, n: int) -> np.ndarray:
    """The coverage of the program's layer ``k`` as a map."""
    layer = program.layers[k]
    probe = replace(program, layers=(A.Layer(None, (A.ChannelSet("roughness", (layer.alpha,)),)),))
    return np.asarray(evaluate(probe, n, n).roughness, np.float64)


def test_leaves_take_several_distinct_colours() -> None:
    n = 160
    program = compose(parse(FLAT), LIB.overlays["leafy"], main_colour=None, cover=0.6)
    leaf = np.maximum(_alpha(program, -1, n), _alpha(program, -2, n)) > 0.99
    assert 0.08 < leaf.mean() < 0.4  # scattered leaves, the ground showing between them
    colour = evaluate(program, n, n).basecolor_linear[..., :3][leaf].astype(np.float64)
    # a leaf's shade scales its three channels alike: the green-to-red ratio is its colour
    ratio = colour[:, 1] / np.maximum(colour[:, 0], 1e-6)
    counts, _ = np.histogram(ratio, bins=np.linspace(0, 1, 11))
    assert (counts / counts.sum() > 0.05).sum() >= 3


def test_leaves_gather_in_the_low_parts_but_lie_everywhere() -> None:
    n = 96
    host = LIB.ast("brick-wall")
    program = compose(host, LIB.overlays["leafy"], main_colour=None, cover=0.5)
    bare = np.ones((n, n))
    for k in range(len(host.layers), len(program.layers)):
        bare *= 1 - _alpha(program, k, n)
    covered = 1 - bare
    height = np.asarray(evaluate(host, n, n).height, np.float64)
    low, high = np.quantile(height, (0.25, 0.75))
    in_low, in_high = covered[height <= low].mean(), covered[height >= high].mean()
    assert in_high > 0.05  # whole leaves lie on the bricks too
    assert in_low > 1.5 * in_high


def test_the_line_is_one_band_running_the_full_height() -> None:
    n = 160
    painted = []
    for cover in (0.25, 0.5, 0.8):
        program = compose(parse(FLAT), LIB.overlays["lined"], main_colour=None, cover=cover)
        paint = _alpha(program, -1, n)
        band = paint.mean(axis=0) > 0.3
        columns = np.flatnonzero(band)
        assert 0.05 < band.mean() < 0.1  # about 7.5 % of the width
        assert columns.max() - columns.min() + 1 == columns.size  # one band, not several
        assert paint[:, ~band].max() < 0.05
        painted.append(paint[:, band].mean())
        if cover >= 0.5:  # a few worn patches, no gap across the line
            assert paint[:, band].mean(axis=1).min() > 0.3
    assert painted[0] < painted[1] < painted[2]  # the amount is how much paint is intact
    assert painted[1] > 0.85


def test_paint_is_smoother_than_the_road() -> None:
    n = 96
    program = compose(LIB.ast("asphalt"), LIB.overlays["lined"], main_colour=None, cover=0.8)
    band = _alpha(program, -1, n) > 0.9
    rough = np.asarray(evaluate(program, n, n).roughness, np.float64)
    assert rough[band].mean() < rough[~band].mean() - 0.2


def test_soot_is_a_soft_film_rising_in_runs() -> None:
    n = 256
    program = compose(parse(FLAT), LIB.overlays["sooty"], main_colour=None, cover=0.5)
    soot = _alpha(program, -1, n)
    assert 0.3 < soot.mean() < 0.8
    # no hard rim: the coverage changes by less than half its range from one texel to the next
    # (the stains overlay's tide marks jump by more than 0.8)
    step = max(np.abs(np.diff(soot, axis=0)).max(), np.abs(np.diff(soot, axis=1)).max())
    assert step < 0.5
    # it darkens, and varies more across than up and down (smoke runs up the surface)
    lum = evaluate(program, 64, 64).basecolor_linear[..., :3].astype(np.float64).mean(axis=-1)
    assert lum.mean() < 0.5 * evaluate(FLAT, 8, 8).basecolor_linear[..., :3].mean()
    k = np.ones(5) / 5  # the fine grain smoothed away: the layout of the runs is left
    c = np.apply_along_axis(np.convolve, 0, lum, k, mode="valid")
    c = np.apply_along_axis(np.convolve, 1, c, k, mode="valid")
    assert np.abs(np.diff(c, axis=1)).mean() > 1.3 * np.abs(np.diff(c, axis=0)).mean()


def test_soot_settles_in_the_joints() -> None:
    n = 96
    host = LIB.ast("brick-wall")
    program = compose(host, LIB.overlays["sooty"], main_colour=None, cover=0.5)
    soot = _alpha(program, -1, n)
    height = np.asarray(evaluate(host, n, n).height, np.float64)
    low, high = np.quantile(height, (0.15, 0.75))
    assert soot[height <= low].mean() > soot[height >= high].mean() + 0.1
