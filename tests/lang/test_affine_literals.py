"""Literal arguments (``to_01=True``, ``output="cell_value"``) never make an expression vary
with X/Y, so they must not stop the tileable checker from proving a wrapper periodic."""

from __future__ import annotations

import matloom
from matloom.lang.tileable import tileable_warnings


def _codes(text: str) -> list[str]:
    return [d.code for d in tileable_warnings(matloom.parse(text))]


def test_fract_of_whole_cycles_plus_literal_flagged_noise_is_periodic() -> None:
    text = (
        "View(0, 0, 2, 2, tileable=True)\n"
        "Define(g, Fract(((Y() * 7) + fBm(octaves=3, base_freq=2, to_01=True, seed=3))))\n"
        "Material(Layer(1).basecolor((g * 255), 100, 100))\n"
    )
    assert "W010" not in _codes(text)


def test_fract_of_non_whole_cycles_still_warns() -> None:
    text = (
        "View(0, 0, 2, 2, tileable=True)\n"
        "Define(g, Fract(((Y() * 7.3) + fBm(octaves=3, base_freq=2, to_01=True, seed=3))))\n"
        "Material(Layer(1).basecolor((g * 255), 100, 100))\n"
    )
    assert "W010" in _codes(text)
