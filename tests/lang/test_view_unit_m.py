"""``View(..., unit_m=M)``: metres per coordinate unit, printed back, carried into the maps and
the manifest's physical size; bad values are one clear error."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

import matloom
from matloom.lang.api import check
from matloom.runtime.export import export_maps

TEXT = (
    "View(0, 0, 2, 1, tileable=True, unit_m=0.25)\n"
    "Define(g, fBm(octaves=3, base_freq=2, to_01=True, seed=3))\n"
    "Material(\n  Layer(1)\n    .basecolor((g * 255), 100, 100)\n    .height((g * 0.01))\n)"
)


def test_round_trip_and_keyword_order() -> None:
    assert matloom.format(matloom.parse(TEXT)) == TEXT
    swapped = TEXT.replace("tileable=True, unit_m=0.25", "unit_m=0.25, tileable=True")
    assert matloom.format(matloom.parse(swapped)) == TEXT


def test_manifest_physical_size_from_the_view(tmp_path: Path) -> None:
    maps = matloom.evaluate(TEXT, 64, 32)
    assert maps.view.unit_m == 0.25
    export_maps(maps, tmp_path / "out", program_text=TEXT)
    size = json.loads((tmp_path / "out" / "material.json").read_text())["physical_size"]
    assert size["width_m"] == pytest.approx(0.5) and size["height_m"] == pytest.approx(0.25)
    assert size["height_scale_m"] == pytest.approx(0.25)


def test_caller_unit_m_overrides_the_view(tmp_path: Path) -> None:
    maps = matloom.evaluate(TEXT, 32, 16)
    export_maps(maps, tmp_path / "o", program_text=TEXT, unit_m=1.0)
    size = json.loads((tmp_path / "o" / "material.json").read_text())["physical_size"]
    assert size["width_m"] == pytest.approx(2.0)


@pytest.mark.parametrize("value", ["-1", "0", "X()", "True", '"m"'])
def test_bad_unit_m_is_one_error(value: str) -> None:
    text = f"View(0, 0, 1, 1, unit_m={value})\nMaterial(Layer(1).basecolor(1, 1, 1))"
    diags = check(text)
    assert [d.code for d in diags if d.severity.value == "error"] == ["E061"]
    assert "unit_m" in diags[0].message


def test_twice_is_an_error() -> None:
    with pytest.raises(Exception, match="twice"):
        matloom.parse("View(0, 0, 1, 1, unit_m=1, unit_m=2)\nMaterial(Layer(1).basecolor(1, 1, 1))")


def test_without_unit_m_no_physical_size(tmp_path: Path) -> None:
    text = TEXT.replace(", unit_m=0.25", "")
    maps = matloom.evaluate(text, 16, 8)
    assert maps.view.unit_m is None
    export_maps(maps, tmp_path / "n", program_text=text)
    assert json.loads((tmp_path / "n" / "material.json").read_text())["physical_size"] is None
