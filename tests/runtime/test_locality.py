"""The locality report: which maps an edit changed, and which changes leak."""

from __future__ import annotations

import pytest

from matloom.runtime.locality import LEAK_FRACTION, allowed_outputs, locality

BASE = """View(0, 0, 2, 2)
Define(shared, 0.5)
Define(spots, fBm(octaves=3, base_freq=4, to_01=True, seed=3))
Material(
  Layer(1).basecolor(200, 180, 160).roughness(shared).height(0),
  Layer(spots).basecolor(90, 80, 70).roughness(0.3).metallic(shared).height((spots * 0.01))
)
"""


def _edit(old: str, new: str) -> str:
    assert old in BASE
    return BASE.replace(old, new)


def test_unchanged_program_changes_nothing() -> None:
    report = locality(BASE, BASE, ["roughness"], size=64)
    assert report.changed == ()
    assert report.leaks == ()
    assert report.ok


def test_local_edit_is_not_a_leak() -> None:
    after = _edit("roughness(0.3)", "roughness(0.6)")
    report = locality(BASE, after, ["roughness"], size=64)
    assert report.changed == ("roughness",)
    assert report.maps["roughness"].fraction > 0.1
    assert report.ok


def test_leaking_edit_is_caught() -> None:
    # `shared` feeds roughness and metallic; the edit claims only roughness
    after = _edit("Define(shared, 0.5)", "Define(shared, 0.9)")
    report = locality(BASE, after, ["roughness"], size=64)
    assert set(report.changed) == {"roughness", "metallic"}
    assert report.leaks == ("metallic",)
    assert report.maps["metallic"].fraction > LEAK_FRACTION
    assert not report.ok
    assert "metallic changed on" in report.describe()
    assert report.to_json()["leaks"] == ["metallic"]
    # claiming both channels makes the same edit local
    assert locality(BASE, after, ["roughness", "metallic"], size=64).ok


def test_height_allows_its_derived_maps() -> None:
    after = _edit("(spots * 0.01)", "(spots * 0.03)")
    report = locality(BASE, after, ["height"], size=64)
    assert {"height", "normal"} <= set(report.changed)
    assert report.ok
    assert not locality(BASE, after, ["basecolor"], size=64).ok


def test_coverage_allows_every_map() -> None:
    assert allowed_outputs(["alpha"]) >= {"basecolor", "height", "normal", "roughness"}
    assert allowed_outputs(["height"]) == {"height", "normal", "ao"}
    with pytest.raises(ValueError, match="unknown channel"):
        allowed_outputs(["glaze"])


def test_tiny_changes_are_within_tolerance() -> None:
    after = _edit("basecolor(200, 180, 160)", "basecolor(200.01, 180, 160)")
    assert locality(BASE, after, ["roughness"], size=32).changed == ()
