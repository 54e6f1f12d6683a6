"""The mouldy and dewy overlays: their words request them (and the edits' mould words reach
mouldy, no longer moss), mould is dark matte speckle that merges into blotches at its colonies'
hearts and thins out to specks, flat on the host and a little more in its joints; dew is many
small round near-mirror drops of varied size, each a dome raised on the host's own surface (the
overlay's ``surface`` Define bound to the host's height), sparse to dense with the cover."""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest

import matloom
from matloom.author.edit import edit_offline
from matloom.engine.evaluate import evaluate
from matloom.lang import ast as A
from matloom.lang.api import parse
from matloom.lang.tileable import tileable_warnings
from matloom.library import load_library
from matloom.library.author import author
from matloom.library.checks import period_problems
from matloom.library.data import words
from matloom.library.overlay import HOST_HEIGHT, compose
from matloom.library.query import read

LIB = load_library()
DAMP = ("mouldy", "dewy")
N = 192
#: the library programs the edits are tried on (light, busy green, tiled, dark and creased)
EDITED = ("drywall-painted", "clover-patch", "square-tiles", "trash-bag")
FLAT = """View(0, 0, 2, 2, tileable=True)
Material(Layer(1).basecolor(200, 200, 200).roughness(0.5))
"""
LUM = np.array([0.2126, 0.7152, 0.0722])


def _read(prompt: str):  # noqa: ANN202 - the request
    return read(prompt, words(), LIB.triggers, LIB.weak_triggers)


def _overlays(prompt: str) -> list[str]:
    return [o.name for o in _read(prompt).overlays]


def _on(
    host_name: str, name: str, cover: float = 0.5, colour: tuple[int, int, int] | None = None
) -> A.Program:
    main = LIB.entry(host_name).colours[0]
    return compose(
        LIB.ast(host_name), LIB.overlays[name], main_colour=main, cover=cover, colour=colour
    )


def _on_flat(name: str, cover: float = 0.5) -> A.Program:
    return compose(parse(FLAT), LIB.overlays[name], main_colour=None, cover=cover)


def _alpha(program: A.Program, n: int = N) -> np.ndarray:
    """The coverage of the program's last layer (the overlay's top layer) as a map."""
    top = program.layers[-1]
    probe = replace(program, layers=(A.Layer(None, (A.ChannelSet("roughness", (top.alpha,)),)),))
    return np.asarray(evaluate(probe, n, n).roughness, np.float64)


def _lum(maps: matloom.MaterialMaps) -> np.ndarray:
    return np.asarray(maps.basecolor_linear[..., :3], np.float64) @ LUM


def _components(mask: np.ndarray) -> np.ndarray:
    """The sizes (texels) of the 4-connected parts of ``mask``, wrapping at the edges."""
    label = np.zeros(mask.shape, int)
    sizes = []
    h, w = mask.shape
    for y, x in zip(*np.nonzero(mask), strict=True):
        if label[y, x]:
            continue
        label[y, x] = len(sizes) + 1
        stack, size = [(y, x)], 0
        while stack:
            a, b = stack.pop()
            size += 1
            for c, d in (((a + 1) % h, b), ((a - 1) % h, b), (a, (b + 1) % w), (a, (b - 1) % w)):
                if mask[c, d] and not label[c, d]:
                    label[c, d] = label[y, x]
                    stack.append((c, d))
        sizes.append(size)
    return np.array(sizes)


def _local_share(mask: np.ndarray, r: int) -> np.ndarray:
    """The share of ``mask`` in the (2r + 1)^2 window around each texel (wrapping)."""
    total = np.zeros(mask.shape)
    for dy in range(-r, r + 1):
        for dx in range(-r, r + 1):
            total += np.roll(np.roll(mask, dy, 0), dx, 1)
    return total / (2 * r + 1) ** 2


# ----------------------------------------------------------------------------- words
@pytest.mark.parametrize(
    ("prompt", "name"),
    [
        ("mouldy bathroom tiles", "mouldy"),
        ("black mould on a bathroom wall", "mouldy"),
        ("drywall with black mold", "mouldy"),
        ("moldy grout", "mouldy"),
        ("mildewed canvas", "mouldy"),
        ("mildewy shower curtain", "mouldy"),
        ("plaster with mould spots", "mouldy"),
        ("moulds on a ceiling", "mouldy"),  # words.toml's extra word
        ("leaves with morning dew", "dewy"),
        ("dewy grass", "dewy"),
        ("plastic with water droplets", "dewy"),
        ("black plastic with raindrops", "dewy"),
        ("window glass with rain drops", "dewy"),
        ("glass with condensation", "dewy"),
        ("misted mirror", "dewy"),
        ("beads of water on a leaf", "dewy"),
        ("waxed car hood beaded with water", "dewy"),
        ("a leaf with a dewdrop", "dewy"),  # words.toml's extra words
        ("glass with a droplet", "dewy"),
    ],
)
def test_words_request_the_overlay(prompt: str, name: str) -> None:
    assert name in _overlays(prompt)


@pytest.mark.parametrize("name", DAMP)
def test_every_trigger_reaches_its_overlay(name: str) -> None:
    for trigger in LIB.overlays[name].triggers:
        assert name in _overlays(f"concrete floor, {trigger}"), trigger


def test_damp_and_wet_stay_wet_and_moss_stays_moss() -> None:
    assert _overlays("damp plaster wall") == ["wet"]
    assert _overlays("wet leaves") == ["wet"]
    assert _overlays("mossy stone wall") == ["mossy"]
    assert _overlays("damp and mouldy basement wall") == ["wet", "mouldy"]
    assert "mossy" not in _overlays("mouldy stone wall")
    # beads as a motif are no water
    assert "dewy" not in _overlays("beaded curtain")
    assert "dewy" not in _overlays("beaded fabric")


def test_a_colour_before_the_word_tints_the_mould() -> None:
    (white,) = _read("white mildew on a plaster wall").overlays
    assert white.name == "mouldy" and white.colour == words().colour("white")
    (green,) = _read("green mould on plaster").overlays
    assert green.name == "mouldy" and green.colour == words().colour("green")
    # the slot takes it: white mildew is pale speckle on a dark host
    program = _on("trash-bag", "mouldy", colour=white.colour)
    mould = _alpha(program) > 0.6
    lum = _lum(evaluate(program, N, N))
    assert lum[mould].mean() > 3 * lum[~mould].mean()


# ----------------------------------------------------------------------------- both
@pytest.mark.parametrize("host_name", ["brick-wall", "cobblestone", "trash-bag", "clover-patch"])
@pytest.mark.parametrize("name", DAMP)
def test_composed_program_is_clean_and_tiles(name: str, host_name: str) -> None:
    program = _on(host_name, name, cover=0.6)
    assert program.tileable and tileable_warnings(program) == []
    assert matloom.check(matloom.format(program)) == []
    assert period_problems(program, 32) == []


@pytest.mark.parametrize("name", DAMP)
def test_the_cover_is_how_much(name: str) -> None:
    shares = [(_alpha(_on_flat(name, cover)) > 0.5).mean() for cover in (0.28, 0.5, 0.8)]
    assert shares[0] < shares[1] < shares[2]
    assert shares[2] > 1.6 * shares[0]


# ----------------------------------------------------------------------------- mould
def test_mould_is_dark_matte_and_flat() -> None:
    host = LIB.ast("drywall-painted")
    program = _on("drywall-painted", "mouldy")
    mould = _alpha(program) > 0.6
    assert 0.05 < mould.mean() < 0.4
    a, b = evaluate(host, N, N), evaluate(program, N, N)
    assert _lum(b)[mould].mean() < 0.25 * _lum(a)[mould].mean()  # dark grey-green to black
    r, g, bl = (float(np.asarray(b.basecolor_linear[..., k])[mould].mean()) for k in range(3))
    assert g >= r > bl  # a grey-green cast
    assert b.roughness[mould].mean() > 0.85  # matte
    assert np.array_equal(a.height, b.height)  # no thickness: the host's relief shows through
    # also where the host has deep folds the mould does not fill them
    folds, on_folds = LIB.ast("trash-bag"), _on("trash-bag", "mouldy")
    assert np.array_equal(evaluate(folds, 64, 64).height, evaluate(on_folds, 64, 64).height)


def test_mould_speckles_merge_into_blotches_and_thin_out_to_specks() -> None:
    n = 256
    mould = _alpha(_on_flat("mouldy"), n) > 0.5
    assert 0.08 < mould.mean() < 0.35
    sizes = _components(mould)
    assert (sizes <= 4).sum() > 300  # many scattered specks
    assert sizes.max() > 400  # and blotches where they merge
    share = _local_share(mould, 4)[mould]
    assert (share > 0.9).mean() > 0.1  # the dense hearts of the colonies
    assert (share < 0.3).mean() > 0.08  # the specks at their edges


def test_mould_follows_the_joints_a_little() -> None:
    for host_name in ("square-tiles", "brick-wall"):
        program = _on(host_name, "mouldy")
        mould = _alpha(program)
        height = np.asarray(evaluate(LIB.ast(host_name), N, N).height, np.float64)
        low, high = np.quantile(height, (0.1, 0.75))
        in_low, in_high = mould[height <= low].mean(), mould[height >= high].mean()
        assert in_low > 2 * in_high  # more in the grout
        assert in_high > 0.04  # but it grows on the tiles and bricks too


# ----------------------------------------------------------------------------- dew
def test_drops_are_small_round_near_mirror_domes() -> None:
    host = LIB.ast("drywall-painted")
    program = _on("drywall-painted", "dewy")
    drop = _alpha(program) > 0.5
    assert 0.05 < drop.mean() < 0.25
    a, b = evaluate(host, N, N), evaluate(program, N, N)
    assert b.roughness[drop].mean() < 0.1 < a.roughness[drop].mean() - 0.3
    assert b.coat[drop].mean() > 0.8
    ratio = _lum(b)[drop].mean() / _lum(a)[drop].mean()
    assert 0.5 < ratio < 0.95  # the surface a little darker under the water
    # many drops, most small, a few several times larger
    sizes = _components(drop)
    assert sizes.size > 300
    assert np.median(sizes) <= 4 and sizes.max() > 25 and (sizes > 12).sum() >= 5
    # domes: higher in the middle of a drop than at its rim, nothing raised between drops
    rise = np.asarray(b.height, np.float64) - np.asarray(a.height, np.float64)
    inner = drop.copy()
    for _ in range(2):
        inner &= np.roll(inner, 1, 0) & np.roll(inner, -1, 0) & np.roll(inner, 1, 1)
        inner &= np.roll(inner, -1, 1)
    assert rise[inner].mean() > 1.5 * rise[drop & ~inner].mean() > 0
    assert (rise >= -1e-6).all() and np.abs(rise[_alpha(program) == 0]).max() < 1e-6


@pytest.mark.parametrize("host_name", ["brick-wall", "square-tiles", "cobblestone"])
def test_drops_sit_on_the_hosts_surface(host_name: str) -> None:
    """The ``surface`` Define reads the host's height: a drop on a brick is a dome on the
    brick, not a disc at the mortar's level hidden under it."""
    program = _on(host_name, "dewy")
    surface = program.define("host_surface")
    assert surface is not None and HOST_HEIGHT in {
        n.name for n in A.walk(surface.expr) if isinstance(n, A.Ref)
    }
    drop = _alpha(program) > 0.5
    before = np.asarray(evaluate(LIB.ast(host_name), N, N).height, np.float64)
    after = np.asarray(evaluate(program, N, N).height, np.float64)
    high = before >= np.quantile(before, 0.5)
    assert (after - before).min() > -1e-6
    x1, _, x2, _ = LIB.ast(host_name).view_tuple
    # the overlay's heights are scaled from its View (2 wide) to the host's
    assert (after - before)[drop & high].mean() > 0.002 * abs(x2 - x1) / 2


def test_drops_on_a_host_without_relief_keep_their_stand_in_surface() -> None:
    program = _on_flat("dewy")
    assert program.define("host_surface").expr == A.Num(0)  # type: ignore[union-attr]
    assert HOST_HEIGHT not in {d.name for d in program.defines}
    drop = _alpha(program) > 0.5
    assert (np.asarray(evaluate(program, N, N).height)[drop] > 0).all()


# ----------------------------------------------------------------------------- edits, author
@pytest.mark.parametrize("host_name", EDITED)
def test_an_edit_adds_black_mould_not_moss(host_name: str) -> None:
    entry = LIB.entry(host_name).program
    for request in (
        "some black mould in the corners",
        "black mould spots spreading in from a corner",
    ):
        plan = edit_offline(entry, request, size=32).report.plan
        assert plan["rule"] == "overlay" and "'mouldy'" in plan["note"], request
        assert "'mossy'" not in plan["note"]


@pytest.mark.parametrize("host_name", EDITED)
def test_an_edit_adds_dew(host_name: str) -> None:
    entry = LIB.entry(host_name).program
    for request in ("add morning dew, little water droplets on the leaves", "add some raindrops"):
        plan = edit_offline(entry, request, size=32).report.plan
        assert plan["rule"] == "overlay" and "'dewy'" in plan["note"], request


def test_edits_move_the_added_mould_and_dew() -> None:
    mouldy = edit_offline(LIB.entry("square-tiles").program, "add some mildew", size=32)
    assert "'mouldy'" in mouldy.report.plan["note"]
    assert edit_offline(mouldy.program, "less mould", size=32).report.plan["rule"] == "amount"
    dewy = edit_offline(LIB.entry("trash-bag").program, "add some water droplets", size=32)
    assert edit_offline(dewy.program, "fewer droplets", size=32).report.plan["rule"] == "amount"


def test_the_author_applies_them() -> None:
    r = author("mouldy bathroom tiles")
    assert "mouldy" in r.overlays
    assert "dewy" in author("leaves with morning dew").overlays
    assert "dewy" in author("black plastic with raindrops").overlays
