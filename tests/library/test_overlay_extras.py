"""The puddles, algae and weedy overlays: their words request them, they settle in the host's
low parts (the joints of a brick wall, the gaps between cobbles), puddles are dark near-mirror
water with a flat surface that still shows on a host without relief, algae is a glossy film
that can run down in streaks, and weeds are green blades rising out of the joints."""

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
from matloom.library.data import words
from matloom.library.overlay import compose
from matloom.library.query import read

LIB = load_library()
N = 96
EXTRAS = ("puddles", "algae", "weedy")
FLAT = """View(0, 0, 2, 2, tileable=True)
Material(Layer(1).basecolor(200, 200, 200).roughness(0.5))
"""


def _overlays(prompt: str) -> list[str]:
    request = read(prompt, words(), LIB.triggers, LIB.weak_triggers)
    return [o.name for o in request.overlays]


@pytest.mark.parametrize(
    ("prompt", "name"),
    [
        ("cobblestone street with puddles", "puddles"),
        ("concrete floor with a puddle", "puddles"),
        ("asphalt road with standing water", "puddles"),
        ("paving with pools of water", "puddles"),
        ("puddled stone yard", "puddles"),
        ("stone wall with green algae", "algae"),
        ("algal rocks", "algae"),
        ("slimy stone steps", "algae"),
        ("concrete with slime", "algae"),
        ("brick wall with green slime", "algae"),
        ("pond scum on rocks", "algae"),
        ("brick paving with weeds", "weedy"),
        ("weedy cobblestones", "weedy"),
        ("pavers with weeds growing between them", "weedy"),
        ("bricks with grass growing between them", "weedy"),
        ("pavers with grass between them", "weedy"),
        ("patio overgrown with weeds", "weedy"),
        ("concrete with grass in cracks", "weedy"),
    ],
)
def test_words_request_the_overlay(prompt: str, name: str) -> None:
    assert name in _overlays(prompt)


def test_puddles_are_no_longer_plain_wet() -> None:
    assert _overlays("cobblestone street with puddles") == ["puddles"]
    assert _overlays("street with a puddle") == ["puddles"]  # words.toml's extra word
    assert _overlays("wet cobblestone street") == ["wet"]
    # the trigger phrases of each overlay all reach it
    for name in EXTRAS:
        for trigger in LIB.overlays[name].triggers:
            assert name in _overlays(f"stone floor {trigger}"), trigger


def _top_alpha(program: A.Program) -> np.ndarray:
    """The coverage of the program's last layer (the overlay's top layer) as a map."""
    top = program.layers[-1]
    probe = replace(program, layers=(A.Layer(None, (A.ChannelSet("roughness", (top.alpha,)),)),))
    return np.asarray(evaluate(probe, N, N).roughness, np.float64)


@pytest.mark.parametrize("host_name", ["brick-wall", "cobblestone"])
@pytest.mark.parametrize("name", EXTRAS)
def test_settles_in_the_joints(name: str, host_name: str) -> None:
    host = LIB.ast(host_name)
    program = compose(host, LIB.overlays[name], main_colour="base", cover=0.5)
    assert "host_height" in {d.name for d in program.defines}
    assert program.tileable and tileable_warnings(program) == []
    assert matloom.check(matloom.format(program)) == []
    mask = _top_alpha(program)
    height = np.asarray(evaluate(host, N, N).height, np.float64)
    low, high = np.quantile(height, (0.25, 0.75))
    in_low, in_high = mask[height <= low].mean(), mask[height >= high].mean()
    assert in_low > 0.15
    # a puddle fills the joints first but covers the whole of a dip; films and weeds keep low
    assert in_low > (1.8 if name == "puddles" else 4) * in_high


def _maps(program: A.Program | str) -> matloom.MaterialMaps:
    return evaluate(program, N, N)


def test_puddles_are_dark_glossy_and_flat() -> None:
    host = LIB.ast("brick-wall")
    program = compose(host, LIB.overlays["puddles"], main_colour="base", cover=0.5)
    water = _top_alpha(program) > 0.6
    assert 0.1 < water.mean() < 0.6
    a, b = _maps(host), _maps(program)
    assert b.roughness[water].mean() < 0.15 < a.roughness[water].mean() - 0.3
    assert b.coat[water].mean() > 0.6
    lum = np.array([0.2126, 0.7152, 0.0722])
    assert (b.basecolor_linear[..., :3] @ lum)[water].mean() < 0.6 * (
        (a.basecolor_linear[..., :3] @ lum)[water].mean()
    )
    # the water surface is flat: the joints under it are filled
    assert b.height[water].std() < 0.5 * a.height[water].std()


def test_puddles_show_on_a_host_without_relief() -> None:
    program = compose(parse(FLAT), LIB.overlays["puddles"], main_colour=None, cover=0.5)
    assert program.define("host_relief").expr == A.Num(0.5)
    water = _top_alpha(program) > 0.5
    assert 0.1 < water.mean() < 0.5
    # patches, not speckle: most water texels have water on all four sides
    inner = water & np.roll(water, 1, 0) & np.roll(water, -1, 0)
    inner &= np.roll(water, 1, 1) & np.roll(water, -1, 1)
    assert inner.sum() > 0.8 * water.sum()
    more = _top_alpha(compose(parse(FLAT), LIB.overlays["puddles"], main_colour=None, cover=0.85))
    assert (more > 0.5).mean() > water.mean() + 0.1  # "heavily puddled" holds more water


def test_algae_is_a_glossy_green_film() -> None:
    host = LIB.ast("brick-wall")
    program = compose(host, LIB.overlays["algae"], main_colour="base", cover=0.5)
    film = _top_alpha(program) > 0.6
    assert film.mean() > 0.1
    b = _maps(program)
    assert b.roughness[film].mean() < 0.35  # wet and slimy, unlike moss
    r, g, bl = (b.basecolor_linear[..., k][film].mean() for k in range(3))
    assert g > r > bl


def test_algae_streaks_run_down_the_surface() -> None:
    def gradients(streaks: bool) -> tuple[float, float]:
        program = compose(
            parse(FLAT), LIB.overlays["algae"], main_colour=None, cover=0.6, streaks=streaks
        )
        c = _top_alpha(program)
        k = np.ones(5) / 5
        c = np.apply_along_axis(np.convolve, 0, c, k, mode="valid")
        c = np.apply_along_axis(np.convolve, 1, c, k, mode="valid")
        return float(np.abs(np.diff(c, axis=1)).mean()), float(np.abs(np.diff(c, axis=0)).mean())

    across, down = gradients(True)
    assert across > 2 * down
    across, down = gradients(False)
    assert across < 2 * down


def test_weeds_are_green_blades_rising_from_the_joints() -> None:
    host = LIB.ast("cobblestone")
    program = compose(host, LIB.overlays["weedy"], main_colour="base", cover=0.5)
    weeds = _top_alpha(program) > 0.6
    assert 0.03 < weeds.mean() < 0.5
    b = _maps(program)
    r, g, bl = (b.basecolor_linear[..., k][weeds].mean() for k in range(3))
    assert g > r > bl
    # blades: thin features, so many weed texels border bare ones
    edge = weeds & ~(np.roll(weeds, 1, 0) & np.roll(weeds, -1, 0))
    assert edge.sum() > 0.15 * weeds.sum()
    # a host without relief still grows a few clumps
    flat = _top_alpha(compose(parse(FLAT), LIB.overlays["weedy"], main_colour=None, cover=0.5))
    assert 0.005 < (flat > 0.5).mean() < 0.3
