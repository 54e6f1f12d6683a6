"""What the README promises of every preset: constant maps are values, never files (glTF
factors, MaterialX and USD input values, ``constant_values`` for the engine sets), and
``--bits 16`` gives 16-bit colour and data maps in every preset whose format takes them
(all but glTF, whose viewers read 8-bit textures)."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

import matloom
from matloom.io import png
from matloom.io.presets import PRESETS
from matloom.runtime.export import export_maps

ROOT = Path(__file__).resolve().parents[2]
#: compositing leaves its ior (1.5 in every layer) 1.4999999 .. 1.5000001 (float rounding)
PEBBLES = ROOT / "docs" / "examples" / "02_pebbles.mat"
#: the same for a coat of 0.6 over the whole material
TERRAZZO = ROOT / "docs" / "examples" / "12_terrazzo.mat"
#: presets whose format reads 16-bit PNGs
SIXTEEN_BIT = ("mtlx", "usd", "unreal", "unity", "godot")


def _preset_pngs(out: Path) -> list[Path]:
    return sorted(p for preset in PRESETS for p in (out / preset).glob("*.png"))


def _bit_depth(path: Path) -> int:
    return path.read_bytes()[24]  # the IHDR bit depth byte


@pytest.mark.parametrize("example", [PEBBLES, TERRAZZO], ids=lambda p: p.stem)
def test_no_preset_writes_a_constant_texture(tmp_path: Path, example: Path) -> None:
    maps = matloom.evaluate(example.read_text(encoding="utf-8"), 64, 64, backend="numpy")
    result = export_maps(maps, tmp_path, presets=list(PRESETS), name="m", bits=16)
    for path in _preset_pngs(result.out_dir):
        pixels = png.read_png(path)
        flat = pixels.reshape(-1, pixels.shape[2] if pixels.ndim == 3 else 1)
        assert not np.all(flat == flat[0]), f"{path.parent.name}/{path.name} is one value"


def test_a_rounding_constant_ior_is_a_value_in_materialx_and_usd(tmp_path: Path) -> None:
    maps = matloom.evaluate(PEBBLES.read_text(encoding="utf-8"), 64, 64, backend="numpy")
    ior = np.asarray(maps.ior)
    assert ior.min() != ior.max() and ior.max() - ior.min() < 1e-6  # the case at hand
    result = export_maps(maps, tmp_path, presets=["mtlx", "usd"], name="m")
    mtlx = (result.out_dir / "mtlx" / "m.mtlx").read_text(encoding="utf-8")
    usda = (result.out_dir / "usd" / "m.usda").read_text(encoding="utf-8")
    assert not list(result.out_dir.glob("*/m_ior.png"))
    # 1.5 is the default of open_pbr_surface and UsdPreviewSurface: no input at all
    assert "ior_image" not in mtlx and "m_ior.png" not in usda
    assert "specular_ior" not in mtlx and "inputs:ior" not in usda


def test_bits16_reaches_every_preset_that_takes_it(tmp_path: Path, render_presets) -> None:
    _, result = render_presets("full", presets=list(PRESETS), bits=16)
    out = result.out_dir
    for path in _preset_pngs(out):
        expected = 8 if path.parent.name == "gltf" else 16
        assert _bit_depth(path) == expected, f"{path.parent.name}/{path.name}"
    manifest = json.loads((out / "material.json").read_text(encoding="utf-8"))
    for preset in SIXTEEN_BIT:
        for role, entry in manifest["presets"][preset]["files"].items():
            if str(entry.get("file", "")).endswith(".png"):
                assert entry["encoding"].startswith("png16"), (preset, role)


def test_bits8_keeps_colour_maps_8_bit(tmp_path: Path, render_presets) -> None:
    # 16 bits only where the data needs them whatever --bits says (height, ior, angle)
    _, result = render_presets("full", presets=list(PRESETS))
    always16 = ("_height", "_H.png", "_ior", "_anisotropy_angle")
    for path in _preset_pngs(result.out_dir):
        expected = 16 if any(k in path.name for k in always16) else 8
        assert _bit_depth(path) == expected, f"{path.parent.name}/{path.name}"
