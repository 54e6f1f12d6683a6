"""MaterialX and USD store the displacement scale and bias as float32: a height range beyond
float32 (5.8e38) is clamped to a finite float32 and the preset's notes say so."""

from __future__ import annotations

import re
from pathlib import Path
from xml.etree import ElementTree as ET

import numpy as np

import matloom
from matloom.runtime.export import export_maps

HUGE = "Material(Layer(1).roughness(0.5).height((X() - 0.5) * 5.8e38))"
MODEST = "Material(Layer(1).roughness(0.5).height(X() * 0.25))"


def _export(tmp_path: Path, program: str) -> tuple[Path, dict]:
    maps = matloom.evaluate(program, 16, 16)
    low, high = float(np.nanmin(maps.height)), float(np.nanmax(maps.height))
    assert program == MODEST or high - low > 5e38  # the range itself exceeds float32
    result = export_maps(maps, tmp_path / "out", presets=["mtlx", "usd"], name="m", unit_m=1.0)
    return result.out_dir, result.manifest["presets"]


def _is_float32(text: str) -> bool:
    with np.errstate(over="ignore"):
        return bool(np.isfinite(np.float32(float(text))))


def test_materialx_displacement_scale_is_a_finite_float32(tmp_path: Path) -> None:
    out, presets = _export(tmp_path, HUGE)
    root = ET.parse(out / "mtlx" / "m.mtlx").getroot()
    (disp,) = root.iter("displacement")
    (scale,) = [i.get("value") for i in disp if i.get("name") == "scale"]
    assert _is_float32(scale) and float(scale) > 3e38
    assert any("beyond float32" in note for note in presets["mtlx"]["notes"])


def test_usd_displacement_scale_and_bias_are_finite_float32(tmp_path: Path) -> None:
    out, presets = _export(tmp_path, HUGE)
    text = (out / "usd" / "m.usda").read_text()
    block = text[text.index('def Shader "height"') :]
    for name in ("scale", "bias"):
        values = re.search(rf"float4 inputs:{name} = \(([^)]*)\)", block).group(1).split(",")
        assert all(_is_float32(v) for v in values), (name, values)
    assert any("beyond float32" in note for note in presets["usd"]["notes"])


def test_ordinary_heights_are_written_as_they_are(tmp_path: Path) -> None:
    out, presets = _export(tmp_path, MODEST)
    root = ET.parse(out / "mtlx" / "m.mtlx").getroot()
    (disp,) = root.iter("displacement")
    (scale,) = [float(i.get("value")) for i in disp if i.get("name") == "scale"]
    assert abs(scale - 0.25 * 15 / 16) < 1e-6  # the texel centres' height range, unit 1 m
    assert not any("float32" in n for p in presets.values() for n in p.get("notes", []))
