"""Overlays follow the host's relief: the relief expression is the engine's composite height,
its rank spreads over the surface, grime settles in the low parts and wear finds the high
ones, and streak words run an overlay down the surface."""

from __future__ import annotations

import numpy as np
import pytest

from matloom.author.edit.api import edit
from matloom.engine.evaluate import evaluate
from matloom.lang import ast as A
from matloom.lang.api import parse
from matloom.lang.printer import format_expr
from matloom.library import load_library
from matloom.library.data import words
from matloom.library.entry import LibraryError
from matloom.library.overlay import check_overlay, compose, load_overlay
from matloom.library.query import read
from matloom.library.relief import height_expr, relief_of

LIB = load_library()
N = 64

#: a raised square on a flat ground (the square is the high part, the ground the low one)
SQUARE = """View(0, 0, 2, 2, tileable=True)
Define(sq, Fill(Rect(0.5, 0.5, 1, 1)))
Define(bump, fBm(octaves=2, base_freq=4, to_01=True, seed=3))
Material(
  Layer(1).basecolor(200, 200, 200).roughness(0.5).height((bump * 0.001)),
  Layer(sq).basecolor(200, 200, 200).roughness(0.5).height((0.02 + (bump * 0.001)))
)
"""
FLAT = """View(0, 0, 2, 2, tileable=True)
Material(Layer(1).basecolor(200, 200, 200).roughness(0.5))
"""


def _with_height_of(program: A.Program, expr: A.Node) -> str:
    """A one-layer program whose height is ``expr`` over ``program``'s Defines."""
    defines = "\n".join(f"Define({d.name}, {format_expr(d.expr)})" for d in program.defines)
    view = "View(0, 0, 2, 2, tileable=True)"
    if program.view is not None:
        v = program.view
        view = f"View({v.x1}, {v.y1}, {v.x2}, {v.y2}, tileable=True)"
    return f"{view}\n{defines}\nMaterial(Layer(1).height({format_expr(expr)}))\n"


@pytest.mark.parametrize("name", ["brick-wall", "plaster"])
def test_height_expression_is_the_composite_height(name: str) -> None:
    host = LIB.ast(name)
    expr = height_expr(host)
    assert expr is not None
    want = evaluate(host, N, N).height
    got = evaluate(_with_height_of(host, expr), N, N).height
    np.testing.assert_allclose(got, want, atol=1e-6)


def test_gated_layer_counts_only_where_it_covers() -> None:
    host = parse(SQUARE)
    got = evaluate(_with_height_of(host, height_expr(host)), N, N).height
    np.testing.assert_allclose(got, evaluate(host, N, N).height, atol=1e-6)


def test_relief_rank_spreads_over_the_surface() -> None:
    host = LIB.ast("brick-wall")
    found = relief_of(host, "host_height")
    assert found is not None
    h, rank = found
    text = _with_height_of(
        parse(
            _with_height_of(host, h).replace(
                "Material(", f"Define(host_height, {format_expr(h)})\nMaterial(", 1
            )
        ),
        rank,
    )
    r = evaluate(text, 127, 127).height.ravel()  # not a multiple of the courses: no aliasing
    assert 0.0 <= r.min() and r.max() <= 1.0
    # a rank: about a quarter of the surface below 0.25, half below 0.5
    assert abs(np.mean(r < 0.25) - 0.25) < 0.08
    assert abs(np.mean(r < 0.5) - 0.5) < 0.08


def test_flat_or_costly_hosts_have_no_relief() -> None:
    assert relief_of(parse(FLAT), "host_height") is None
    costly = parse(
        "Material(Layer(1).height(fBm(octaves=3, base_freq=4, seed=1)))"  # noise in the line
    )
    assert height_expr(costly) is None


def _changed(host: str, program: A.Program) -> np.ndarray:
    a = evaluate(host, N, N).basecolor_linear[..., :3].astype(np.float64)
    b = evaluate(program, N, N).basecolor_linear[..., :3].astype(np.float64)
    return np.abs(a - b).sum(axis=-1)


def _square_mask() -> np.ndarray:
    x = (np.arange(N) + 0.5) / N * 2
    xx, yy = np.meshgrid(x, x)
    return (xx > 0.55) & (xx < 1.45) & (yy > 0.55) & (yy < 1.45)


@pytest.mark.parametrize("name", ["dirty", "mossy", "efflorescence"])
def test_what_settles_finds_the_low_parts(name: str) -> None:
    host = parse(SQUARE)
    program = compose(host, LIB.overlays[name], main_colour=None, cover=0.5)
    assert "host_height" in {d.name for d in program.defines}
    change = _changed(SQUARE, program)
    inside = _square_mask()
    assert change[~inside].mean() > 1.5 * change[inside].mean()


def test_wear_finds_the_high_parts() -> None:
    colour = "Define(base_r, 90)\nDefine(base_g, 80)\nDefine(base_b, 70)\nMaterial("
    host = parse(SQUARE.replace("Material(", colour, 1))
    program = compose(host, LIB.overlays["worn"], main_colour="base", cover=0.6)
    change = _changed(SQUARE, program)
    inside = _square_mask()
    assert change[inside].mean() > change[~inside].mean()


def test_flat_host_keeps_the_stand_in() -> None:
    program = compose(parse(FLAT), LIB.overlays["dirty"], main_colour=None, cover=0.5)
    assert "host_height" not in {d.name for d in program.defines}
    assert program.define("host_relief").expr == A.Num(0.5)


@pytest.mark.parametrize("name", ["dirty", "rusty", "stained", "wet", "mossy"])
def test_streaks_run_down_the_surface(name: str) -> None:
    def gradients(streaks: bool) -> tuple[float, float]:
        program = compose(
            parse(FLAT), LIB.overlays[name], main_colour=None, cover=0.6, streaks=streaks
        )
        c = _changed(FLAT, program)
        k = np.ones(5) / 5  # the fine grain smoothed away: the layout of the patches is left
        c = np.apply_along_axis(np.convolve, 0, c, k, mode="valid")
        c = np.apply_along_axis(np.convolve, 1, c, k, mode="valid")
        return float(np.abs(np.diff(c, axis=1)).mean()), float(np.abs(np.diff(c, axis=0)).mean())

    across, down = gradients(True)
    assert across > 2 * down  # runs: the change varies across, little down
    across, down = gradients(False)
    assert across < 2 * down  # patches: no direction


def _read(prompt: str):  # noqa: ANN202 - the request's parts
    return read(prompt, words(), LIB.triggers, LIB.weak_triggers)


def test_streak_words_reach_generate_and_edit() -> None:
    assert _read("rust streaked steel plate").overlays[0].streaks
    assert not _read("rusty steel plate").overlays[0].streaks
    plaster = LIB.entry("plaster").program
    assert (
        "streaks running down"
        in edit(plaster, "add dirty streaks running down").report.plan["note"]
    )
    assert "streaks" not in edit(plaster, "add some dirt").report.plan["note"]


def test_overlay_relief_and_streaks_need_their_defines(tmp_path) -> None:  # noqa: ANN001
    text = LIB.overlays["dirty"].path.read_text(encoding="utf-8")
    bad = tmp_path / "dirty.mat"
    bad.write_text(text.replace('relief = "host_relief"', 'relief = "nowhere"'), encoding="utf-8")
    with pytest.raises(LibraryError, match="nowhere"):
        check_overlay(load_overlay(bad))
