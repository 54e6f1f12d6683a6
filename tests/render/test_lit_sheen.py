"""Sheen in the ``lit`` preview: a grazing rim on cloth relief (issue 26), the same in both
implementations, and the measured layout facts the critic is given."""

from __future__ import annotations

import numpy as np
import pytest

import matloom
from matloom.author.prompts.previews import layout_facts, sheen_changes, uncovered_look
from matloom.render.lit import available_backends, shade_lit

SIZE = 64


def cloth(sheen: float, colour: tuple[int, int, int] = (120, 20, 40)) -> str:
    """A plain weave of raised threads (steep flanks at the thread edges) in a dark colour."""
    r, g, b = colour
    return (
        "View(0, 0, 1, 1)\n"
        "Define(w, Weave(base_freq=6, warp_width=0.8))\n"
        f"Material(Layer(1).basecolor({r}, {g}, {b}).roughness(0.8).sheen({sheen})"
        ".height(w * 0.03))"
    )


def _pair(colour: tuple[int, int, int], backend: str = "numpy") -> tuple[np.ndarray, ...]:
    """(sheen off, sheen on, surface tilt in degrees) at SIZE."""
    off = matloom.evaluate(cloth(0, colour), SIZE, SIZE)
    on = matloom.evaluate(cloth(1, colour), SIZE, SIZE)
    tilt = np.degrees(np.arccos(np.clip(off.normal[..., 2], -1.0, 1.0)))
    images = [shade_lit(m, backend=backend).astype(np.float64) for m in (off, on)]
    return images[0], images[1], tilt


@pytest.mark.parametrize("colour", [(120, 20, 40), (30, 30, 90)])
def test_sheen_is_a_rim_at_grazing_angles(colour: tuple[int, int, int]) -> None:
    off, on, tilt = _pair(colour)
    steep, flat = tilt > 40.0, tilt < 5.0
    assert steep.sum() > 100 and flat.sum() > 100  # the weave has both
    lift = (on - off).mean(axis=-1)
    # on the flanks (grazing view) sheen brightens by a lot, on the flat tops by much less
    assert lift[steep].mean() >= 30.0
    assert lift[steep].mean() >= 2.0 * lift[flat].mean()
    # the rim keeps the cloth's hue (a tint, not white, not as dark as the base)
    rim = on[steep].mean(axis=0)
    assert int(np.argmax(rim)) == int(np.argmax(colour))
    assert rim.max() - rim.min() >= 20.0


def test_the_sheen_of_a_white_cloth_is_white() -> None:
    off, on, _ = _pair((230, 230, 230))
    assert np.abs(on - off).mean() < 15.0  # a white cloth has little to gain
    change = on - off
    spread = change.max(axis=-1) - change.min(axis=-1)
    assert np.percentile(spread, 95) <= 3  # the sheen of a grey cloth adds no colour


@pytest.mark.numba
def test_cloth_with_sheen_is_bit_identical_in_numba_and_numpy() -> None:
    if "numba" not in available_backends():
        pytest.skip("numba is not installed")
    for sheen in (0, 1):
        maps = matloom.evaluate(cloth(sheen), SIZE, SIZE)
        assert np.array_equal(shade_lit(maps, backend="numba"), shade_lit(maps, backend="numpy"))


def test_layout_facts_are_measured() -> None:
    flat, slope = sheen_changes("lit")
    assert slope > 1.25 * flat and slope >= 16
    text = layout_facts(("flat", "lit"))
    assert f"by {slope} levels" in text and "bright rim" in text
    assert "sheen barely shows" in text  # the flat preview's sheen is a 10 % lift
    assert uncovered_look("flat") == "flat grey sRGB (128, 128, 128)"
    assert uncovered_look("lit").startswith("a checker of") and "8 cells" in uncovered_look("lit")
    assert "cannot show roughness" in text.split("- lit")[0]  # flat has no highlight to see it
